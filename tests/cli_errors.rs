//! Every error the command line prints names its problem, and names each cause once:
//! the CLI prints an error with its whole `source()` chain, so a message that also
//! repeated its cause would print it twice.

mod support;

use std::fs;
use std::path::{Path, PathBuf};

use support::{fails, s};

/// A published scene, whose target mesh lies beside it.
fn published() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spaceship_fill.toml")
}

/// A valid genome file of the published scene's generator.
fn genome_file(dir: &Path) -> PathBuf {
    let path = dir.join("genome.json");
    fs::write(
        &path,
        r#"{"generator": "Spaceship", "genes": [{"node": "Start", "parent": 0, "links": [0], "params": {}}]}"#,
    )
    .unwrap();
    path
}

/// The published scene with its target mesh replaced by `mesh` (relative to `dir`), written
/// into `dir`.
fn scene_with_mesh(dir: &Path, mesh: &str) -> PathBuf {
    let text = fs::read_to_string(published()).unwrap();
    assert!(text.contains("targets/spaceship_fill.obj"));
    let path = dir.join("scene.toml");
    fs::write(&path, text.replace("targets/spaceship_fill.obj", mesh)).unwrap();
    path
}

/// The segments of `stderr` that `: ` separates, of more than 10 characters, which
/// appear more than once.
fn repeated_segments(stderr: &str) -> Vec<&str> {
    let segments: Vec<&str> = stderr
        .trim()
        .split(": ")
        .map(str::trim)
        .filter(|segment| segment.chars().count() > 10)
        .collect();
    let mut repeated = Vec::new();
    for (i, segment) in segments.iter().enumerate() {
        if segments[..i].contains(segment) && !repeated.contains(segment) {
            repeated.push(*segment);
        }
    }
    repeated
}

/// Runs `shapegen` with `args`, which must fail with one `error:` message that contains
/// every one of `names` and repeats no segment.
fn fails_naming(args: &[&str], names: &[&str]) -> String {
    let stderr = fails(args);
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    for name in names {
        assert!(
            stderr.contains(name),
            "{args:?}: `{name}` not named in: {stderr}"
        );
    }
    let repeated = repeated_segments(&stderr);
    assert!(
        repeated.is_empty(),
        "{args:?}: {repeated:?} printed twice in: {stderr}"
    );
    stderr
}

#[test]
fn the_repeat_check_finds_a_cause_printed_twice() {
    let doubled = "error: not a genome in JSON: invalid type: integer `3`, expected a \
                   sequence at line 1 column 37: invalid type: integer `3`, expected a sequence \
                   at line 1 column 37";
    assert_eq!(
        repeated_segments(doubled),
        [
            "invalid type",
            "integer `3`, expected a sequence at line 1 column 37"
        ]
    );
    // Short segments (a key, a word) may well recur.
    assert!(repeated_segments("error: scene: `a`: x: `a`: y").is_empty());
}

#[test]
fn a_genome_file_of_bad_json() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.json");
    fs::write(&bad, r#"{"generator": "Spaceship", "genes": 3}"#).unwrap();
    let scene = published();
    fails_naming(
        &["score", s(&scene), "--genomes", s(&bad), "--cpu"],
        &["bad.json", "not a genome in JSON", "invalid type", "line 1"],
    );
    // Not JSON at all.
    fs::write(&bad, "{").unwrap();
    fails_naming(
        &["score", s(&scene), "--genomes", s(&bad), "--cpu"],
        &["bad.json", "not a genome in JSON", "EOF while parsing"],
    );
}

#[test]
fn genomes_that_are_not_valid() {
    let dir = tempfile::tempdir().unwrap();
    let scene = published();
    let empty = dir.path().join("empty.json");
    fs::write(&empty, r#"{"generator": "Spaceship", "genes": []}"#).unwrap();
    fails_naming(
        &["score", s(&scene), "--genomes", s(&empty), "--cpu"],
        &["empty.json", "invalid genome", "holds no gene"],
    );
    let set = dir.path().join("set.json");
    fs::write(
        &set,
        r#"{"generator": "Spaceship", "genomes": [{"genes": []}]}"#,
    )
    .unwrap();
    fails_naming(
        &["score", s(&scene), "--genomes", s(&set), "--cpu"],
        &["genome 0 of the set", "invalid genome", "holds no gene"],
    );
    let missing = dir.path().join("missing.json");
    fails_naming(
        &["score", s(&scene), "--genomes", s(&missing), "--cpu"],
        &["missing.json", "cannot read"],
    );
}

#[test]
fn a_scene_with_a_toml_syntax_error() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("broken.toml");
    fs::write(&scene, "generator = \"spaceship\"\n[limits\nmin_len = 4\n").unwrap();
    let genomes = genome_file(dir.path());
    fails_naming(
        &["score", s(&scene), "--genomes", s(&genomes), "--cpu"],
        &["broken.toml", "line 2"],
    );
}

#[test]
fn a_scene_that_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("nothere.toml");
    let genomes = genome_file(dir.path());
    fails_naming(
        &["score", s(&scene), "--genomes", s(&genomes), "--cpu"],
        &["cannot read scene", "nothere.toml"],
    );
}

#[test]
fn a_scene_whose_target_mesh_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_with_mesh(dir.path(), "missing.obj");
    let genomes = genome_file(dir.path());
    fails_naming(
        &["score", s(&scene), "--genomes", s(&genomes), "--cpu"],
        &["volume.target[0].mesh", "missing.obj", "not a file"],
    );
}

#[test]
fn a_mesh_with_a_bad_line() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("bad.obj"),
        "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let scene = scene_with_mesh(dir.path(), "bad.obj");
    let genomes = genome_file(dir.path());
    fails_naming(
        &["score", s(&scene), "--genomes", s(&genomes), "--cpu"],
        &["volume.target[0].mesh", "bad.obj", "line 2"],
    );
}

#[test]
fn a_bad_set() {
    let dir = tempfile::tempdir().unwrap();
    let scene = published();
    let out = dir.path().join("out");
    fails_naming(
        &[
            "run",
            s(&scene),
            "--set",
            "optimizer.population=abc",
            "--out",
            s(&out),
        ],
        &["optimizer", "\"abc\"", "u32"],
    );
    fails_naming(
        &[
            "run",
            s(&scene),
            "--set",
            "optimizer.population",
            "--out",
            s(&out),
        ],
        &["optimizer.population", "key=value"],
    );
    assert!(!out.exists(), "a refused run writes nothing");
}
