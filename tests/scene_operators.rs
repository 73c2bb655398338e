//! The GA's operator keys of a scene's `[optimizer]` table: `operators` and
//! `cross_array_index`, from the file and from `--set`, and the errors naming them.

use std::fs;

use shapegen::ops::OperatorVariant;
use shapegen::optimize::{GaSettings, HybridSettings};
use shapegen::registry::Registry;
use shapegen::scene::{MethodSettings, Overrides, Scene, SceneError};

/// A spaceship volume scene with a unit-cube target; `optimizer` is appended.
fn scene(dir: &tempfile::TempDir, optimizer: &str) -> std::path::PathBuf {
    let mut cube = String::new();
    for i in 0..8 {
        let c = |bit: i32| if i & bit == 0 { -0.5 } else { 0.5 };
        cube += &format!("v {} {} {}\n", c(1), c(2), c(4));
    }
    for f in [
        [1, 3, 7, 5],
        [2, 6, 8, 4],
        [1, 5, 6, 2],
        [3, 4, 8, 7],
        [1, 2, 4, 3],
        [5, 7, 8, 6],
    ] {
        cube += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    fs::write(dir.path().join("cube.obj"), cube).unwrap();
    let path = dir.path().join("scene.toml");
    let text = format!(
        "generator = \"spaceship\"\n\
         [limits]\nmin_len = 4\noptimal_len = 10\nmax_len = 100\nmax_depth = 15\n\
         [volume]\ngrid = {{ min = [-1, -1, -1], max = [1, 1, 1], resolution = [8, 8, 8] }}\n\
         [[volume.target]]\nmesh = \"cube.obj\"\n{optimizer}"
    );
    fs::write(&path, text).unwrap();
    path
}

/// The GA's settings: those of the hybrid's GA, the default method.
fn ga(scene: &Scene) -> GaSettings {
    match scene.optimizer.settings {
        MethodSettings::Ga(s) => s,
        MethodSettings::Hybrid(h) => h.ga,
        other => panic!("not the GA: {other:?}"),
    }
}

#[test]
fn the_paper_settings_use_the_original_operators() {
    let dir = tempfile::tempdir().unwrap();
    let s = ga(&Scene::load(scene(&dir, "")).unwrap());
    // The paper's GA, which the hybrid (the default method) polishes.
    let polished = GaSettings {
        polish: HybridSettings::POLISH,
        ..generators::spaceship::paper_ga()
    };
    assert_eq!(s, polished);
    assert_eq!(s.operators, OperatorVariant::Original);
    assert!(!s.cross_array_index);
}

#[test]
fn operators_and_cross_array_index_are_read_from_the_file_and_from_set() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(
        &dir,
        "[optimizer]\noperators = \"weighted\"\ncross_array_index = true\n",
    );
    let s = ga(&Scene::load(&path).unwrap());
    assert_eq!(
        (s.operators, s.cross_array_index),
        (OperatorVariant::Weighted, true)
    );
    assert_eq!(s.population, generators::spaceship::paper_ga().population);
    let sets = [
        "optimizer.operators=original".to_owned(),
        "optimizer.cross_array_index=false".to_owned(),
    ];
    let s = ga(&load_with(&path, &sets).unwrap());
    assert_eq!(
        (s.operators, s.cross_array_index),
        (OperatorVariant::Original, false)
    );
    let s = ga(&load_with(scene(&dir, ""), &["optimizer.operators=weighted".into()]).unwrap());
    assert_eq!(s.operators, OperatorVariant::Weighted);
}

#[test]
fn bad_operator_keys_are_refused_with_the_valid_values() {
    let dir = tempfile::tempdir().unwrap();
    for (optimizer, key, reason) in [
        (
            "operators = \"paper\"",
            "optimizer.operators",
            "\"paper\" is not an operator variant; the variants are \"weighted\" and \"original\"",
        ),
        (
            "operators = 1",
            "optimizer.operators",
            "the variants are \"weighted\" and \"original\"",
        ),
        (
            "cross_array_index = \"yes\"",
            "optimizer.cross_array_index",
            "must be true or false",
        ),
    ] {
        let path = scene(&dir, &format!("[optimizer]\n{optimizer}\n"));
        let message = Scene::load(&path).unwrap_err().to_string();
        assert!(message.contains(key), "names `{key}`: {message}");
        assert!(message.contains(reason), "says `{reason}`: {message}");
    }
    let path = scene(&dir, "");
    let message = load_with(&path, &["optimizer.operators=paper".into()])
        .unwrap_err()
        .to_string();
    assert!(message.contains("optimizer.operators"), "{message}");
    assert!(
        message.contains("\"weighted\" and \"original\""),
        "{message}"
    );
}

/// The scene at `path` with `--set` overrides.
fn load_with(path: impl AsRef<std::path::Path>, sets: &[String]) -> Result<Scene, SceneError> {
    let overrides = Overrides {
        sets: sets.to_vec(),
        ..Overrides::default()
    };
    Scene::open(path, &Registry::published(), &overrides)
}
