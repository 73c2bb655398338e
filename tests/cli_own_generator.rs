//! A generator defined here, outside the workspace's crates, gets the whole command-line
//! tool from `shapegen::cli::Cli`: sample, target, score, run (and resume), render and
//! export on it, end to end, through the same code as the `shapegen` binary.

use std::fs;
use std::path::Path;

mod support;

use shapegen::cli::Cli;
use shapegen::prelude::*;
use support::{UNIT_CUBE_OBJ, s};

generator! {
    /// A pile of blocks, each on the one below, shifted a little.
    pub Pile {
        axiom Block;
        node Block {
            params {
                shift: f32 ~ uniform(-0.5, 0.5),
                height: f32 ~ uniform(0.5, 1.5),
            }
            children { up: Block = 0.8 }
            derive(s) {
                let s = s.with_size(vec3(1.0, height, 1.0));
                s.translate(vec3(shift, height / 2.0, 0.0)).emit(CUBE);
                if let Some(up) = up {
                    s.translate(vec3(shift, height, 0.0)).derive(up);
                }
            }
        }
    }
}

/// The tool with `Pile` registered as `pile`, run with `args`.
fn pile(args: &[&str]) -> anyhow::Result<()> {
    let mut all = vec!["pile-tool"];
    all.extend_from_slice(args);
    Cli::new().generator::<Pile>("pile").run_from(all)
}

/// A volume scene for the pile, aiming at `target`.
fn scene(dir: &Path, target: &str) -> String {
    let path = dir.join("pile.toml");
    fs::write(
        &path,
        format!(
            "generator = \"pile\"\n\
             [limits]\nmin_len = 1\nmax_len = 12\nmax_depth = 12\n\
             [volume]\ngrid = {{ min = [-4, 0, -2], max = [4, 10, 2], resolution = [32, 40, 16] }}\n\
             [[volume.target]]\nmesh = \"{target}\"\n\
             [optimizer]\npopulation = 24\nelitism = 4\ninitial_length = 3\nseed = 5\n"
        ),
    )
    .unwrap();
    s(&path).to_owned()
}

#[test]
fn a_generator_of_ones_own_gets_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let samples = d.join("samples");
    pile(&[
        "sample",
        "--generator",
        "pile",
        "-n",
        "4",
        "--genes",
        "5",
        "--out",
        s(&samples),
    ])
    .unwrap();
    let genomes = samples.join("genomes.json");
    let text = fs::read_to_string(&genomes).unwrap();
    assert!(text.contains(r#""generator": "pile""#), "{text}");
    assert!(samples.join("model_0.obj").is_file() && samples.join("model_3.glb").is_file());

    // A reachable target: the voxels of sample 2, through a scene that names the pile.
    fs::write(d.join("unit.obj"), UNIT_CUBE_OBJ).unwrap();
    let first = scene(d, "unit.obj");
    let target = d.join("target.obj");
    pile(&[
        "target",
        &first,
        "--genome",
        s(&genomes),
        "--index",
        "2",
        "--out",
        s(&target),
    ])
    .unwrap();
    assert!(target.is_file());
    let scene = scene(d, "target.obj");
    pile(&["score", &scene, "--genomes", s(&genomes), "--cpu"]).unwrap();

    // Search toward it, stop after 5 generations, then go on to 10.
    let run = d.join("run");
    pile(&[
        "run",
        &scene,
        "--cpu",
        "--generations",
        "5",
        "--out",
        s(&run),
    ])
    .unwrap();
    let summary = |dir: &Path| -> serde_json::Value {
        serde_json::from_str(&fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
    };
    assert_eq!(summary(&run)["generations"], 5);
    pile(&["run", "--resume", s(&run), "--generations", "10"]).unwrap();
    let resumed = summary(&run);
    assert_eq!(resumed["generations"], 10);

    // The same 10 generations in one go end at the same best fitness.
    let straight = d.join("straight");
    pile(&[
        "run",
        &scene,
        "--cpu",
        "--generations",
        "10",
        "--out",
        s(&straight),
    ])
    .unwrap();
    assert_eq!(summary(&straight)["best_fitness"], resumed["best_fitness"]);
    assert_eq!(summary(&straight)["evaluations"], resumed["evaluations"]);

    let best = run.join("best.genome.json");
    let render = d.join("render");
    pile(&["render", &scene, "--genomes", s(&best), "--out", s(&render)]).unwrap();
    assert!(render.join("model_0.png").is_file());
    let glb = d.join("best.glb");
    pile(&["export", "--genome", s(&best), "--out", s(&glb)]).unwrap();
    assert!(fs::metadata(&glb).unwrap().len() > 0);
}

#[test]
fn unknown_and_clashing_names_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x");
    let err = pile(&["sample", "--generator", "tower", "--out", s(&out)]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "unknown generator `tower`; the generators are pile"
    );
    let err = Cli::new()
        .published()
        .generator::<Pile>("city")
        .run_from(["t", "sample", "--generator", "pile", "--out", s(&out)])
        .unwrap_err();
    assert!(
        err.to_string().contains("`city` is already registered"),
        "{err}"
    );
    let err = Cli::new()
        .generator::<Pile>("my pile")
        .run_from(["t", "sample", "--generator", "pile", "--out", s(&out)])
        .unwrap_err();
    assert!(err.to_string().contains("cannot name a generator"), "{err}");

    // A scene naming a generator the tool lacks says which it has.
    fs::write(dir.path().join("unit.obj"), UNIT_CUBE_OBJ).unwrap();
    let path = scene(dir.path(), "unit.obj");
    let published = fs::read_to_string(&path)
        .unwrap()
        .replace("\"pile\"", "\"spaceship\"");
    fs::write(&path, published).unwrap();
    let err = pile(&["run", &path, "--generations", "1", "--out", s(&out)]).unwrap_err();
    let message = format!("{err:#}");
    assert!(
        message.contains("`spaceship` is not a registered generator; the generators are pile"),
        "{message}"
    );
}
