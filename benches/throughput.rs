//! Generation throughput, per published generator on its scene: models derived per
//! second, children bred per second and whole-search evaluations per second, on one
//! thread and on every core, and the peak resident memory of each whole search. Prints
//! the Markdown table at the top of `benches/README.md`:
//!
//! ```text
//! cargo bench --bench throughput            # every scene
//! cargo bench --bench throughput -- tree    # the scenes whose file names hold `tree`
//! ```
//!
//! - **Derived**: 64 random genomes of the GA's initial length for the scene (seed 1),
//!   each derived on the scene's site, over and over for at least a second; on every
//!   core, the 64 are shared among the threads.
//! - **Bred**: the GA with the scene's settings and limits and a fitness that costs
//!   nothing (closeness to the initial length), for at least a second after two
//!   generations of warm-up: children per second of its run, selection, operators and
//!   the run's bookkeeping included, scoring left out.
//! - **Evaluated**: the whole search as a user runs it, `shapegen run SCENE --method ga
//!   --cpu --seed 1 --threads T` to the scene's own budget, in its own process: the
//!   evaluations over the elapsed time its `summary.json` gives, and its
//!   `peak_rss_bytes` (the process's peak resident memory).
//!
//! Each rate is one measurement on a shared machine: compare the rows of one run.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use generators::{GeneratorVisitor, Published};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use shapegen::genome::Limits;
use shapegen::ops::Operators;
use shapegen::optimize::{Budget, FnEvaluator, Ga, GaSettings, Optimizer, Silent};
use shapegen::registry::Registry;
use shapegen::scene::{Method, MethodSettings, Overrides, Scene};
use shapegen::{Genome, Grammar, Instance, Site};

/// The published generators measured, each with the scene it is measured on.
const SCENES: &[(Published, &str)] = &[
    (Published::Spaceship, "scenes/paper/spaceship_volume.toml"),
    (Published::Tree, "scenes/paper/tree_sketch1.toml"),
    (Published::City, "scenes/paper/city_whale.toml"),
    (Published::Building, "scenes/building.toml"),
    (Published::RoofedBuilding, "scenes/roofed_building.toml"),
    (Published::LotBuilding, "scenes/lot_building.toml"),
];

/// How long each in-process rate is measured for, at least.
const AT_LEAST: Duration = Duration::from_secs(1);

/// The random genomes the derivation rate cycles through.
const GENOMES: usize = 64;

fn main() {
    // `cargo bench` passes `--bench`; a filter, if given, picks scenes by file name.
    let filter = std::env::args().skip(1).find(|a| !a.starts_with("--"));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let thread_counts = if cores > 1 { vec![1, cores] } else { vec![1] };
    println!(
        "| generator (scene) | threads | models derived/s | children bred/s | \
         evaluations/s (whole search) | search: generations, wall time | peak RSS |"
    );
    println!("|---|---|---|---|---|---|---|");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for &(generator, file) in SCENES {
        if filter.as_deref().is_some_and(|f| !file.contains(f)) {
            continue;
        }
        let path = root.join(file);
        // The GA's settings, whatever method the scene names.
        let ga = Overrides {
            method: Some(Method::Ga),
            ..Overrides::default()
        };
        let scene = Scene::open(&path, &Registry::published(), &ga)
            .unwrap_or_else(|e| panic!("{file} opens: {e}"));
        let MethodSettings::Ga(settings) = scene.optimizer.settings else {
            panic!("{file} is opened with the GA");
        };
        for &threads in &thread_counts {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool of worker threads");
            let rates = pool.install(|| {
                generator.visit(Rates {
                    settings,
                    limits: scene.limits,
                    site: &scene.site,
                })
            });
            let search = search(&path, threads);
            println!(
                "| {} (`{file}`) | {threads} | {} | {} | {} | {}, {:.1} s | {} |",
                scene.generator,
                rate(rates.derived),
                rate(rates.bred),
                rate(search.evaluations as f64 / search.elapsed_s),
                search.generations,
                search.elapsed_s,
                search.peak_rss_bytes.map_or("n/a".to_owned(), |b| format!(
                    "{:.0} MiB",
                    b as f64 / 1048576.0
                )),
            );
        }
    }
}

/// A rate in three significant digits: `1.14 M`, `77.6 k`, `812`.
fn rate(per_second: f64) -> String {
    match per_second {
        r if r >= 1e6 => format!("{:.2} M", r / 1e6),
        r if r >= 1e3 => format!("{:.1} k", r / 1e3),
        r => format!("{r:.0}"),
    }
}

/// The in-process rates of one generator on one scene, in the current pool.
struct Rates<'a> {
    settings: GaSettings,
    limits: Limits,
    site: &'a Site,
}

/// What [`Rates`] measures.
struct Measured {
    derived: f64,
    bred: f64,
}

impl GeneratorVisitor for Rates<'_> {
    type Output = Measured;

    fn visit<G: Grammar>(self, _: Limits) -> Measured {
        Measured {
            derived: derived::<G>(&self.settings, self.limits, self.site),
            bred: bred::<G>(self.settings, self.limits),
        }
    }
}

/// Models derived per second: [`GENOMES`] random genomes of the initial length, derived
/// on `site` round after round, shared among the pool's threads.
fn derived<G: Grammar>(settings: &GaSettings, limits: Limits, site: &Site) -> f64 {
    let ops = Operators::<G>::new(limits).expect("the scene's limits are valid");
    let genomes: Vec<Genome<G>> = (0..GENOMES)
        .map(|i| ops.clone().random(settings.initial_length, &mut seeded(i)))
        .collect();
    let round = || {
        genomes
            .par_iter()
            .for_each_init(Vec::<Instance>::new, |out, g| {
                g.derive_on(site, out);
                black_box(out.len());
            })
    };
    round();
    let (rounds, elapsed) = repeat(round);
    (rounds * GENOMES) as f64 / elapsed.as_secs_f64()
}

/// Children bred per second by the GA with `settings` within `limits`, scoring costing
/// nothing.
fn bred<G: Grammar>(settings: GaSettings, limits: Limits) -> f64 {
    let initial = f64::from(settings.initial_length);
    let mut fitness = FnEvaluator(|g: &Genome<G>| -(g.len() as f64 - initial).abs());
    let mut ga = Ga::<G>::new(settings, limits, 1).expect("the scene's GA settings are valid");
    // The children bred so far: one evaluation each, after the first population's.
    let mut run = |ga: &mut Ga<G>, generations: u64| {
        ga.run(&mut fitness, &Budget::generations(generations), &mut Silent)
            .expect("the free fitness never fails")
            .evaluations
    };
    let mut generations = 2;
    let before = run(&mut ga, generations);
    let t0 = Instant::now();
    let mut after = before;
    while t0.elapsed() < AT_LEAST {
        generations += 10;
        after = run(&mut ga, generations);
    }
    (after - before) as f64 / t0.elapsed().as_secs_f64()
}

/// Calls `f` until [`AT_LEAST`] has passed: the calls made and the time they took.
fn repeat(f: impl Fn()) -> (usize, Duration) {
    let t0 = Instant::now();
    let mut calls = 0;
    while t0.elapsed() < AT_LEAST {
        f();
        calls += 1;
    }
    (calls, t0.elapsed())
}

fn seeded(i: usize) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(1 + i as u64)
}

/// What a whole search's `summary.json` says.
struct Search {
    evaluations: u64,
    generations: u64,
    elapsed_s: f64,
    peak_rss_bytes: Option<u64>,
}

/// Runs the whole search of `scene` as a user does, on `threads` threads, in its own
/// process.
fn search(scene: &Path, threads: usize) -> Search {
    let out = tempfile::tempdir().expect("a temporary folder");
    let dir: PathBuf = out.path().join("run");
    let status = Command::new(env!("CARGO_BIN_EXE_shapegen"))
        .arg("run")
        .arg(scene)
        .args(["--method", "ga", "--cpu", "--seed", "1"])
        .arg("--threads")
        .arg(threads.to_string())
        .arg("--out")
        .arg(&dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .expect("shapegen starts");
    assert!(status.success(), "shapegen run {} failed", scene.display());
    let text = std::fs::read_to_string(dir.join("summary.json")).expect("the run's summary");
    let summary: serde_json::Value = serde_json::from_str(&text).expect("the summary parses");
    let number = |key: &str| {
        summary[key]
            .as_f64()
            .unwrap_or_else(|| panic!("summary.json has {key}"))
    };
    Search {
        evaluations: number("evaluations") as u64,
        generations: number("generations") as u64,
        elapsed_s: number("elapsed_s"),
        peak_rss_bytes: summary["peak_rss_bytes"].as_u64(),
    }
}
