//! The quality guard: a short study of every method on the paper's three scenes and on
//! three reachable targets (made with `shapegen target` from the published generators:
//! a tree silhouette, a spaceship volume, a city skyline), at evaluation budgets and on
//! fixed seeds, so that it gives the same figures on any machine however busy.
//!
//! Each scene is one trial. It runs every method through the tool (`shapegen run SCENE
//! --method M --seed S --evaluations N --threads 2 --cpu`) on each seed and fails when
//! - a method's mean best fitness falls below its floor, or
//! - the default method's mean falls behind another method's by more than the scene's
//!   margin.
//!
//! Floors, margins, budgets and seeds are in `tests/quality/floors.toml`, with the
//! command that measured them; each floor is the mean measured then, less a slack the
//! file states. To measure them anew after a deliberate change of results:
//! `SHAPEGEN_RECORD_QUALITY=1 cargo test --test quality`, then review the diff.

mod support;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use libtest_mimic::{Arguments, Failed, Trial};
use serde::{Deserialize, Serialize};
use shapegen::scene::Method;
use support::{ok, s, timeless_summary};

/// `tests/quality/floors.toml`.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Floors {
    /// How the floors were measured.
    command: String,
    /// Each floor is the measured mean less `slack` times its magnitude (at least
    /// `slack` itself).
    slack: f64,
    /// The seeds every run of the study uses.
    seeds: Vec<u64>,
    /// The default method, which must keep up with every other.
    default_method: String,
    /// Each scene of the study.
    scene: BTreeMap<String, SceneFloors>,
}

/// One scene of the study.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFloors {
    /// The scene file, relative to the repository.
    path: String,
    /// The evaluation budget of every run.
    evaluations: u64,
    /// How far (in fitness) the default method's mean may fall behind another method's.
    margin: f64,
    /// Each method's floor on its mean best fitness over the seeds.
    floors: BTreeMap<String, f64>,
    /// Each method's mean when the floors were measured (for reading, not checked).
    measured: BTreeMap<String, f64>,
}

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The floors file.
fn floors_path() -> PathBuf {
    root().join("tests/quality/floors.toml")
}

/// Mean best fitness of `method` on `scene` over `seeds`, each run into `dir`.
fn mean_best(scene: &SceneFloors, method: &str, seeds: &[u64], dir: &Path) -> f64 {
    let path = root().join(&scene.path);
    let evaluations = scene.evaluations.to_string();
    let mut sum = 0.0;
    for seed in seeds {
        let out = dir.join(format!("{method}-{seed}"));
        let seed = seed.to_string();
        ok(&[
            "run",
            s(&path),
            "--cpu",
            "--method",
            method,
            "--seed",
            &seed,
            "--evaluations",
            &evaluations,
            "--threads",
            "2",
            "--out",
            s(&out),
        ]);
        sum += timeless_summary(&out)["best_fitness"].as_f64().unwrap();
    }
    sum / seeds.len() as f64
}

/// The comment at the top of the floors file.
const HEADER: &str = "\
# The quality guard's floors (tests/quality.rs), measured by `command`, which rewrites
# the floors and measured means: the seeds, the default method, each scene's budget and
# margin, and the slack are set by hand. A floor is the mean measured less `slack` times
# the mean's magnitude (at least 1).
";

/// The floor below a measured mean.
fn floor_of(mean: f64, slack: f64) -> f64 {
    let floor = mean - slack * mean.abs().max(1.0);
    (floor * 1e4).floor() / 1e4
}

/// Runs the study on one scene; returns its means by method.
fn study(scene: &SceneFloors, seeds: &[u64]) -> BTreeMap<String, f64> {
    let dir = tempfile::tempdir().unwrap();
    Method::ALL
        .iter()
        .map(|m| {
            let name = m.name().to_owned();
            let mean = mean_best(scene, &name, seeds, dir.path());
            (name, mean)
        })
        .collect()
}

/// Checks one scene's means against its floors and margin.
fn check(name: &str, floors: &Floors, means: &BTreeMap<String, f64>) -> Result<(), Failed> {
    let scene = &floors.scene[name];
    let mut table = String::new();
    let mut failures = Vec::new();
    for (method, mean) in means {
        let Some(floor) = scene.floors.get(method) else {
            failures.push(format!("{method}: no floor in {}", floors_path().display()));
            continue;
        };
        writeln!(table, "  {method:8} {mean:.4} (floor {floor:.4})").unwrap();
        if mean < floor {
            failures.push(format!(
                "{method}: mean best {mean:.4} below its floor {floor:.4}"
            ));
        }
    }
    let default = &floors.default_method;
    let ours = means[default];
    for (method, mean) in means {
        if ours < mean - scene.margin {
            failures.push(format!(
                "the default method {default} ({ours:.4}) behind {method} ({mean:.4}) by more \
                 than the margin {}",
                scene.margin
            ));
        }
    }
    if failures.is_empty() {
        println!("{name}:\n{table}");
        Ok(())
    } else {
        Err(format!("{name}:\n{table}{}", failures.join("\n")).into())
    }
}

/// Measures every scene anew and writes the floors file.
fn record(mut floors: Floors) {
    for scene in floors.scene.values_mut() {
        let means = study(scene, &floors.seeds);
        scene.floors = means
            .iter()
            .map(|(m, v)| (m.clone(), floor_of(*v, floors.slack)))
            .collect();
        scene.measured = means;
    }
    let text = format!("{HEADER}{}", toml::to_string(&floors).unwrap());
    fs::write(floors_path(), text).unwrap();
}

fn main() {
    let args = Arguments::from_args();
    let text = fs::read_to_string(floors_path())
        .unwrap_or_else(|e| panic!("{}: {e}", floors_path().display()));
    let floors: Floors =
        toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", floors_path().display()));
    if std::env::var_os("SHAPEGEN_RECORD_QUALITY").is_some() {
        record(floors);
        return;
    }
    let floors: &'static Floors = Box::leak(Box::new(floors));
    let trials = floors
        .scene
        .iter()
        .map(|(name, scene)| {
            Trial::test(name.clone(), move || {
                let means = study(scene, &floors.seeds);
                check(name, floors, &means)
            })
        })
        .collect();
    libtest_mimic::run(&args, trials).exit();
}
