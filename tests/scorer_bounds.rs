//! The `[bounds]` scorer: exact counts of a hand-built model, the same counts when kept
//! and updated, a scene with it that runs beside a volume, and the mistakes of its table
//! named by their keys.

mod support;

use std::fs;
use std::path::Path;

use glam::{Affine3A, Vec3};
use shapegen::scene::{AnyCounts, Scene, SceneScorer, ScorerKind};
use shapegen_runtime::score::Scorer;
use shapegen_runtime::score::retained::RetainedScorer;
use shapegen_runtime::{Instance, MeshId};
use support::{cube_ship_scene, ok, s, sample, score};

/// A spaceship scene scored only by a `[bounds]` table of `bounds`.
fn bounds_scene(bounds: &str) -> String {
    format!(
        "generator = \"spaceship\"\n[limits]\nmin_len = 4\nmax_len = 100\nmax_depth = 15\n\
         [bounds]\n{bounds}\n"
    )
}

/// The unit cube (mesh 0), scaled by `scale` and moved to `at`.
fn cube(scale: f32, at: [f32; 3]) -> Instance {
    Instance {
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::splat(scale),
            glam::Quat::IDENTITY,
            Vec3::from(at),
        ),
        mesh: MeshId(0),
    }
}

#[test]
fn the_volume_outside_the_box_is_counted_exactly_and_weighed() {
    let text = bounds_scene("min = [-1, -1, -1]\nmax = [1, 1, 1]\nweight = 0.5");
    let scene = Scene::parse(&text, Path::new("scene.toml")).unwrap();
    let scorer = SceneScorer::new::<generators::Spaceship>(&scene).unwrap();
    let bounds = scorer.bounds().expect("the scene has bounds");
    // Inside; half outside along x (a 2 x 2 x 2 cube from x = 0 to 2: 4 cubic units
    // outside); wholly outside (a unit cube: 1).
    let model = [
        cube(1.0, [0.0, 0.0, 0.0]),
        cube(2.0, [1.0, 0.0, 0.0]),
        cube(1.0, [5.0, 5.0, 5.0]),
    ];
    let counts = bounds.count(&model, &mut bounds.scratch());
    assert_eq!((counts.outside, counts.instances), (5_000_000, 2));
    assert_eq!(bounds.fitness(&counts), -2.5);
    let whole = scorer.fitness(
        &counts_of(&scorer, &model),
        1, // genes: no length penalty in this scene
    );
    assert_eq!(whole, -2.5);

    // Kept and updated, the counts are those counted from nothing.
    let mut state = bounds.count_retained(&model[..1], &mut ()).unwrap();
    bounds
        .update(&mut state, &model[..1], &model[1..], &mut ())
        .unwrap();
    assert_eq!(
        bounds.state_counts(&state),
        bounds.count(&model[1..], &mut ())
    );
}

/// The scene's counts of `model`, counted on the CPU.
fn counts_of(scorer: &SceneScorer, model: &[Instance]) -> shapegen::scene::SceneCounts {
    let backend = scorer
        .on(shapegen::scene::BackendChoice::Cpu, None)
        .unwrap();
    let mut batch = shapegen_runtime::score::InstanceBatch::new();
    batch.push_with(|instances| instances.extend_from_slice(model));
    let mut counts = Vec::new();
    backend.count(&batch, &mut counts).unwrap();
    let [counts] = <[_; 1]>::try_from(counts).unwrap();
    assert!(matches!(counts.parts(), [AnyCounts::Bounds(_)]));
    counts
}

#[test]
fn a_scene_with_bounds_beside_a_volume_runs_and_scores_them() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let text =
        fs::read_to_string(&scene).unwrap() + "[bounds]\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\n";
    fs::write(&scene, text).unwrap();
    let loaded = Scene::load(&scene).unwrap();
    let kinds: Vec<ScorerKind> = loaded.scorers().iter().map(|g| g.kind()).collect();
    assert_eq!(kinds, [ScorerKind::Volume, ScorerKind::Bounds]);

    let out = dir.path().join("run");
    let sets = ["--set", "optimizer.evaluations=300", "--seed", "2", "--cpu"];
    ok(&[&["run", s(&scene), "--out", s(&out)][..], &sets[..]].concat());
    assert!(out.join("best.genome.json").is_file());

    let genomes = sample("spaceship", "5", &dir.path().join("ships"));
    let scored = score(&scene, &genomes, "--cpu");
    assert!(!scored.is_empty());
    for line in &scored {
        let outside = line["bounds"]["outside"].as_u64().unwrap();
        let instances = line["bounds"]["instances"].as_u64().unwrap();
        assert_eq!(outside > 0, instances > 0, "{line}");
        assert!(line["volume"].is_object(), "{line}");
    }
}

#[test]
fn a_bad_bounds_key_is_named_with_what_is_valid() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    let cases = [
        (
            "min = [0, 0, 0]\nmax = [1, 1, 1]\nwieght = 2",
            "wieght",
            "`min`, `max`, `weight`",
        ),
        (
            "min = [0, 0, 0]\nmax = [1, 0, 1]",
            "bounds.max",
            "above bounds.min",
        ),
        (
            "min = [0, 0, 0]\nmax = [1, 1, 1]\nweight = -1",
            "bounds.weight",
            ">= 0",
        ),
        (
            "min = [0, 0]\nmax = [1, 1, 1]",
            "min = [0, 0]",
            "array of length 3",
        ),
    ];
    for (table, key, valid) in cases {
        fs::write(&path, bounds_scene(table)).unwrap();
        let loaded = Scene::load(&path).unwrap_err().to_string();
        assert!(loaded.contains(key) && loaded.contains(valid), "{loaded}");
    }
}
