//! Resource limits up front: a run whose estimated memory exceeds what is available, or
//! `--max-memory`, is refused before it allocates anything, with the estimate and the
//! setting that drives it; runs that fit go on as before. For `run` (single- and
//! multi-objective), `compare` and `sweep`.

mod support;

use std::path::Path;

use support::{fails, ok, s, shapegen, skyline_scene as scene};

/// A scene of the project's `scenes/` folder.
fn project_scene(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn a_population_of_a_hundred_million_is_refused_naming_the_setting() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // Without --max-memory: against the memory available, which no machine this runs
    // on has terabytes of.
    let err = fails(&[
        "run",
        &project_scene("paper/spaceship_volume.toml"),
        "--cpu",
        "--set",
        "optimizer.population=100000000",
        "--out",
        s(&out),
    ]);
    assert!(err.contains("this run would take about"), "{err}");
    assert!(err.contains("TiB of memory"), "{err}");
    assert!(
        err.contains("comes from optimizer.population = 100000000"),
        "{err}"
    );
    assert!(err.contains("--max-memory SIZE"), "{err}");
    assert!(!out.exists(), "nothing is written for a refused run");
}

#[test]
fn max_memory_refuses_a_run_over_it_and_lets_one_under_it_run() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let err = fails(&[
        "run",
        s(&scene),
        "--cpu",
        "--max-memory",
        "1M",
        "--out",
        s(&out),
    ]);
    assert!(
        err.contains("more than the 1.0 MiB that --max-memory allows"),
        "{err}"
    );
    assert!(err.contains("optimizer.population = 24"), "{err}");
    assert!(!out.exists());
    ok(&[
        "run",
        s(&scene),
        "--cpu",
        "--max-memory",
        "2G",
        "--out",
        s(&out),
    ]);
    assert!(out.join("summary.json").exists());
}

#[test]
fn a_normal_scene_fits_the_memory_available() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    ok(&[
        "run",
        &project_scene("building.toml"),
        "--generations",
        "1",
        "--set",
        "optimizer.population=10",
        "--out",
        s(&out),
    ]);
    assert!(out.join("summary.json").exists());
}

#[test]
fn a_multi_objective_run_is_refused_naming_its_largest_part() {
    let dir = tempfile::tempdir().unwrap();
    let err = fails(&[
        "run",
        &project_scene("building.toml"),
        "--set",
        "optimizer.archive=1000000",
        "--max-memory",
        "4G",
        "--out",
        s(&dir.path().join("out")),
    ]);
    assert!(err.contains("that --max-memory allows"), "{err}");
    assert!(err.contains("optimizer.archive = 1000000"), "{err}");
}

#[test]
fn compare_is_refused_naming_the_methods_setting() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let err = fails(&[
        "compare",
        &project_scene("paper/spaceship_volume.toml"),
        "--methods",
        "rjmcmc",
        "--seconds",
        "1",
        "--runs",
        "1",
        "--cpu",
        "--set",
        "optimizer.chains=50000000",
        "--out",
        s(&out),
    ]);
    assert!(
        err.contains("comes from optimizer.chains = 50000000"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn a_sweep_is_refused_for_its_largest_grid_point_with_its_cells_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let sweep = |population: &str, jobs: &str, max: &str| {
        shapegen(&[
            "sweep",
            s(&scene),
            "--grid",
            &format!("optimizer.population={population}"),
            "--runs",
            "2",
            "--generations",
            "1",
            "--cpu",
            "--jobs",
            jobs,
            "--max-memory",
            max,
            "--out",
            s(&out),
        ])
    };
    let refused = sweep("8,2000", "1", "20M");
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(
        err.contains("grid point optimizer.population=2000"),
        "{err}"
    );
    assert!(!out.exists());
    // One cell of 8 fits where two side by side do not.
    let one = sweep("8", "1", "6M");
    assert!(
        one.status.success(),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    std::fs::remove_dir_all(&out).unwrap();
    let two = sweep("8", "2", "6M");
    let err = String::from_utf8_lossy(&two.stderr);
    assert!(!two.status.success());
    assert!(err.contains("2 x "), "{err}");
}

#[test]
fn a_size_that_is_not_one_is_refused_with_what_is_valid() {
    let err = fails(&["run", "any.toml", "--max-memory", "4X", "--out", "x"]);
    assert!(err.contains("`4X` is not a size"), "{err}");
    assert!(err.contains("512M or 4G"), "{err}");
}

#[test]
fn a_resumed_checkpoint_is_checked_by_its_own_settings_and_limits() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    ok(&[
        "run",
        s(&scene),
        "--cpu",
        "--generations",
        "1",
        "--out",
        s(&out),
    ]);
    // A checkpoint edited by hand (or damaged) to hold a hundred million genomes.
    let path = out.join("checkpoint.json");
    let mut checkpoint: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    checkpoint["search"]["settings"]["population"] = 100_000_000.into();
    std::fs::write(&path, checkpoint.to_string()).unwrap();
    let err = fails(&["run", "--resume", s(&out), "--cpu", "--generations", "2"]);
    assert!(
        err.contains("comes from optimizer.population = 100000000"),
        "{err}"
    );
    // Its own population, but genomes allowed to grow to a billion genes.
    checkpoint["search"]["settings"]["population"] = 100.into();
    checkpoint["search"]["limits"]["max_len"] = 1_000_000_000.into();
    std::fs::write(&path, checkpoint.to_string()).unwrap();
    let err = fails(&["run", "--resume", s(&out), "--cpu", "--generations", "2"]);
    assert!(err.contains("of up to 1000000000 genes"), "{err}");
}
