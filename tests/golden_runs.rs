//! Golden runs: whole searches through the tool whose results are checked byte for byte,
//! so that a change that claims to leave results unchanged is proved to, and one that
//! changes them shows as updated files in `tests/golden_runs/`.
//!
//! Each run is a scene, a method (with any `--set` overrides), a seed and an evaluation
//! budget, run on the CPU with one worker thread and with two: both must write exactly
//! the committed `fitness.csv` (all but its `elapsed_s` column) and `best.genome.json`
//! (for a multi-objective run, `history.csv` but `elapsed_s`, `front.csv` and
//! `front.genomes.json`). A missing golden file fails the test.
//!
//! Each single-objective run is also held to what a run promises whatever its results:
//! `best` is never below the generation's `mean` in `fitness.csv`, and `shapegen score`
//! on `best.genome.json` gives the summary's `best_fitness`.
//!
//! To record the files anew after a deliberate change of results:
//! `SHAPEGEN_BLESS_GOLDEN=1 cargo test --test golden_runs`, then review the diff.

mod support;

use std::fs;
use std::path::{Path, PathBuf};

use libtest_mimic::{Arguments, Failed, Trial};
use support::{ok, s, score, timeless_summary, timeless_table};

/// One golden run.
struct Golden {
    /// Its name: the golden files are `tests/golden_runs/<name>.<file>`.
    name: &'static str,
    /// The scene, relative to the repository.
    scene: &'static str,
    /// The method.
    method: &'static str,
    /// More arguments of `shapegen run` (`--set KEY=VALUE`, `--islands K`).
    args: &'static [&'static str],
    /// The seed.
    seed: u64,
    /// The evaluation budget.
    evaluations: u64,
}

/// Every method on the paper's three scenes with their published settings, the variants
/// of the methods that the presets leave out, the island model and a multi-objective run.
const GOLDEN: &[Golden] = &{
    const fn run(
        name: &'static str,
        scene: &'static str,
        method: &'static str,
        args: &'static [&'static str],
        evaluations: u64,
    ) -> Golden {
        Golden {
            name,
            scene,
            method,
            args,
            seed: 7,
            evaluations,
        }
    }
    const TREE: &str = "scenes/paper/tree_sketch1.toml";
    const SHIP: &str = "scenes/paper/spaceship_volume.toml";
    const CITY: &str = "scenes/paper/city_whale.toml";
    [
        run("tree_ga", TREE, "ga", &[], 1200),
        run("tree_hybrid", TREE, "hybrid", &[], 1200),
        run("tree_smc", TREE, "smc", &[], 2000),
        run("tree_sosmc", TREE, "sosmc", &[], 2000),
        run("tree_rjmcmc", TREE, "rjmcmc", &[], 1200),
        run("tree_random", TREE, "random", &[], 1200),
        run("spaceship_ga", SHIP, "ga", &[], 3000),
        run("spaceship_hybrid", SHIP, "hybrid", &[], 3000),
        run("spaceship_smc", SHIP, "smc", &[], 3000),
        run("spaceship_sosmc", SHIP, "sosmc", &[], 3000),
        run("spaceship_rjmcmc", SHIP, "rjmcmc", &[], 3000),
        run("spaceship_random", SHIP, "random", &[], 3000),
        run("city_ga", CITY, "ga", &[], 2000),
        run("city_hybrid", CITY, "hybrid", &[], 2000),
        run("city_smc", CITY, "smc", &[], 2000),
        run("city_sosmc", CITY, "sosmc", &[], 2000),
        run("city_rjmcmc", CITY, "rjmcmc", &[], 2000),
        run("city_random", CITY, "random", &[], 2000),
        // The variants and settings the presets leave out.
        run(
            "spaceship_ga_weighted",
            SHIP,
            "ga",
            &["--set", "optimizer.operators=\"weighted\""],
            3000,
        ),
        run(
            "spaceship_smc_generative",
            SHIP,
            "smc",
            &["--set", "optimizer.variant=\"generative\""],
            3000,
        ),
        run(
            "spaceship_rjmcmc_tempered",
            SHIP,
            "rjmcmc",
            &["--set", "optimizer.variant=\"tempered\""],
            3000,
        ),
        run(
            "spaceship_hybrid_seeded_unpolished",
            SHIP,
            "hybrid",
            &[
                "--set",
                "optimizer.seed_share=1",
                "--set",
                "optimizer.polish=0",
            ],
            3000,
        ),
        run("spaceship_islands", SHIP, "ga", &["--islands", "3"], 3000),
        run("building_front", "scenes/building.toml", "ga", &[], 1500),
    ]
};

/// The files a run in `out` is checked by, each with whether it is a table whose
/// `elapsed_s` column is left out.
fn files_of(out: &Path) -> &'static [(&'static str, bool)] {
    if out.join("front.csv").exists() {
        &[
            ("history.csv", true),
            ("front.csv", false),
            ("front.genomes.json", false),
        ]
    } else {
        &[("fitness.csv", true), ("best.genome.json", false)]
    }
}

/// The text of `file` in `out` as the golden file holds it: a timed table without its
/// `elapsed_s` column.
fn golden_text(out: &Path, file: &str, timed: bool) -> Result<String, Failed> {
    if timed {
        return Ok(timeless_table(out, file)
            .iter()
            .map(|line| format!("{line}\n"))
            .collect());
    }
    fs::read_to_string(out.join(file)).map_err(|e| format!("{file}: {e}").into())
}

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The golden file of run `name`'s `file`.
fn golden_path(name: &str, file: &str) -> PathBuf {
    root()
        .join("tests/golden_runs")
        .join(format!("{name}.{file}"))
}

/// Runs `golden` with `threads` worker threads into a new folder under `dir`.
fn run(golden: &Golden, threads: u32, dir: &Path) -> PathBuf {
    let out = dir.join(format!("threads{threads}"));
    let (seed, evaluations, threads) = (
        golden.seed.to_string(),
        golden.evaluations.to_string(),
        threads.to_string(),
    );
    let scene = root().join(golden.scene);
    let mut args = vec![
        "run",
        s(&scene),
        "--cpu",
        "--method",
        golden.method,
        "--seed",
        &seed,
        "--evaluations",
        &evaluations,
        "--threads",
        &threads,
        "--out",
        s(&out),
    ];
    args.extend(golden.args);
    ok(&args);
    out
}

/// Checks that the run in `out` returned the best it scored: `best` at or above `mean`
/// in every row of `fitness.csv`, and the best genome scoring the summary's
/// `best_fitness`.
fn returns_its_best(golden: &Golden, out: &Path) -> Result<(), Failed> {
    let csv = fs::read_to_string(out.join("fitness.csv")).map_err(|e| e.to_string())?;
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let (best, mean) = (column("best"), column("mean"));
    for line in lines {
        let cells: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        if cells[best] < cells[mean] {
            return Err(format!("{}: best below mean in fitness.csv: {line}", golden.name).into());
        }
    }
    let summary = timeless_summary(out);
    let scene = root().join(golden.scene);
    let scored = score(&scene, &out.join("best.genome.json"), "--cpu")[0]["fitness"].as_f64();
    if scored != summary["best_fitness"].as_f64() {
        return Err(format!(
            "{}: best.genome.json scores {scored:?}, the summary says {}",
            golden.name, summary["best_fitness"]
        )
        .into());
    }
    Ok(())
}

/// Runs `golden` at one and two threads and compares (or, blessing, writes) its files.
fn check(golden: &Golden, bless: bool) -> Result<(), Failed> {
    let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
    for threads in [1, 2] {
        let out = run(golden, threads, dir.path());
        if threads == 1 && out.join("fitness.csv").exists() {
            returns_its_best(golden, &out)?;
        }
        for &(file, timed) in files_of(&out) {
            let got = golden_text(&out, file, timed)?;
            let path = golden_path(golden.name, file);
            if bless && threads == 1 {
                fs::write(&path, &got).map_err(|e| format!("{}: {e}", path.display()))?;
                continue;
            }
            let want = fs::read_to_string(&path).map_err(|e| {
                format!(
                    "{}: {e} (record it with SHAPEGEN_BLESS_GOLDEN=1 cargo test --test golden_runs)",
                    path.display()
                )
            })?;
            if got != want {
                let line = got
                    .lines()
                    .zip(want.lines())
                    .position(|(a, b)| a != b)
                    .map_or_else(|| "their lengths".to_owned(), |i| format!("line {}", i + 1));
                return Err(format!(
                    "{} at {threads} thread(s): {file} differs from {} at {line}",
                    golden.name,
                    path.display()
                )
                .into());
            }
        }
    }
    Ok(())
}

fn main() {
    let args = Arguments::from_args();
    let bless = std::env::var_os("SHAPEGEN_BLESS_GOLDEN").is_some();
    let trials = GOLDEN
        .iter()
        .map(|g| Trial::test(g.name, move || check(g, bless)))
        .collect();
    libtest_mimic::run(&args, trials).exit();
}
