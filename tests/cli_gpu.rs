//! `shapegen score --gpu` and `shapegen run --gpu` end to end, under its own harness so
//! that a missing adapter shows: without one the test is reported as ignored, after a
//! line saying that no adapter was found, unless `SHAPEGEN_REQUIRE_GPU=1` (as in CI,
//! which installs a software Vulkan driver), where it fails instead.

mod support;

use std::fs;
use std::process::ExitCode;

use libtest_mimic::{Arguments, Failed, Trial};
use shapegen::gpu::GpuContext;
use support::{
    SHIP_SCENE, UNIT_CUBE_OBJ, fails, ok, s, sample, score, shapegen, skyline_scene, timeless_curve,
};

/// A test that runs the binary on the GPU: its name and its body, which panics when the
/// test fails.
type GpuTest = (&'static str, fn());

/// The tests of this file.
const TESTS: &[GpuTest] = &[
    (
        "the_gpu_counts_as_the_cpu_does",
        the_gpu_counts_as_the_cpu_does,
    ),
    (
        "the_gpu_counts_several_views_as_the_cpu_does",
        the_gpu_counts_several_views_as_the_cpu_does,
    ),
    (
        "a_population_beyond_the_gpus_bindings_is_refused_before_it_runs",
        a_population_beyond_the_gpus_bindings_is_refused_before_it_runs,
    ),
    (
        "a_gpu_search_counts_children_from_their_parents_with_the_same_result",
        a_gpu_search_counts_children_from_their_parents_with_the_same_result,
    ),
    (
        "lot_buildings_fill_a_volume_on_the_gpu_as_on_the_cpu",
        lot_buildings_fill_a_volume_on_the_gpu_as_on_the_cpu,
    ),
    (
        "a_kind_without_a_gpu_path_counts_on_the_cpu_beside_the_gpu",
        a_kind_without_a_gpu_path_counts_on_the_cpu_beside_the_gpu,
    ),
];

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let required = std::env::var("SHAPEGEN_REQUIRE_GPU").as_deref() == Ok("1");
    // The binary opens its own device the same way; this one is only a probe, closed
    // before the tests start.
    let gpu: Result<(), String> = GpuContext::new()
        .map(|gpu| eprintln!("GPU tests run on {}", gpu.describe()))
        .map_err(|err| format!("no GPU adapter was found: {err}"));
    match &gpu {
        Ok(()) => {}
        Err(err) if required => eprintln!("{err}; SHAPEGEN_REQUIRE_GPU=1, so the GPU tests fail"),
        Err(err) => eprintln!("{err}; the GPU tests are ignored"),
    }
    let trials = TESTS
        .iter()
        .map(|&(name, test)| match &gpu {
            Ok(()) => Trial::test(name, move || {
                test();
                Ok(())
            }),
            Err(err) => {
                let err = err.clone();
                Trial::test(name, move || Err(Failed::from(err))).with_ignored_flag(!required)
            }
        })
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}

fn the_gpu_counts_as_the_cpu_does() {
    let dir = tempfile::tempdir().unwrap();
    let genomes = sample("spaceship", "11", &dir.path().join("ships"));
    let cube = dir.path().join("cube.obj");
    fs::write(&cube, UNIT_CUBE_OBJ).unwrap();
    let scene = dir.path().join("ship.toml");
    fs::write(&scene, SHIP_SCENE.replace("TARGET", "cube.obj")).unwrap();
    let gpu = shapegen(&["score", s(&scene), "--genomes", s(&genomes), "--gpu"]);
    assert!(
        gpu.status.success(),
        "a GPU adapter was found, yet `score --gpu` failed: {}",
        String::from_utf8_lossy(&gpu.stderr)
    );
    assert!(String::from_utf8_lossy(&gpu.stderr).contains("on GPU: "));
    let cpu = score(&scene, &genomes, "--cpu");
    let gpu: Vec<serde_json::Value> = String::from_utf8(gpu.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(cpu, gpu, "exact voxel counts and equal fitness");
}

/// `[bounds]` has no GPU path: with `--gpu` the volume counts on the GPU and the bounds
/// on the CPU, and every count and fitness is the CPU's, in the same run and after
/// incremental counting.
fn a_kind_without_a_gpu_path_counts_on_the_cpu_beside_the_gpu() {
    let dir = tempfile::tempdir().unwrap();
    let genomes = sample("spaceship", "12", &dir.path().join("ships"));
    let cube = dir.path().join("cube.obj");
    fs::write(&cube, UNIT_CUBE_OBJ).unwrap();
    let scene = dir.path().join("ship.toml");
    let text = SHIP_SCENE.replace("TARGET", "cube.obj")
        + "[bounds]\nmin = [-1, -1, -1]\nmax = [1, 2, 1]\n";
    fs::write(&scene, text).unwrap();
    let gpu = score(&scene, &genomes, "--gpu");
    let cpu = score(&scene, &genomes, "--cpu");
    assert!(gpu.iter().all(|line| line["bounds"].is_object()));
    assert_eq!(cpu, gpu, "exact counts and equal fitness");
    let run = |backend: &str| {
        let out = dir.path().join(backend.trim_start_matches('-'));
        let args = ["run", s(&scene), "--out", s(&out), "--seed", "4", backend];
        ok(&[&args[..], &["--set", "optimizer.evaluations=400"]].concat());
        timeless_curve(&out)
    };
    assert_eq!(run("--gpu"), run("--cpu"));
}

/// The three views of `scenes/spaceship_views.toml` on random spaceships and on the
/// target's own genome: each view's pixel counts agree up to pixels whose centres lie
/// within rounding of an edge (0.5 % of the CPU's count plus 2 pixels per instance, as
/// the runtime's GPU tests allow), and the target's genome covers every view exactly.
fn the_gpu_counts_several_views_as_the_cpu_does() {
    let dir = tempfile::tempdir().unwrap();
    let project = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = project.join("scenes/spaceship_views.toml");
    let own = project.join("scenes/targets/spaceship_fill2.genome.json");
    let random = sample("spaceship", "12", &dir.path().join("ships"));
    for genomes in [&random, &own] {
        let cpu = score(&scene, genomes, "--cpu");
        let gpu = score(&scene, genomes, "--gpu");
        assert_eq!(cpu.len(), gpu.len());
        for (c, g) in cpu.iter().zip(&gpu) {
            let instances = c["instances"].as_f64().unwrap();
            let (cv, gv) = (
                c["silhouette"].as_array().unwrap(),
                g["silhouette"].as_array().unwrap(),
            );
            assert_eq!((cv.len(), gv.len()), (3, 3), "{c}");
            for (cc, gc) in cv.iter().zip(gv) {
                for field in ["covered", "on_target", "off_target"] {
                    let (a, b) = (cc[field].as_f64().unwrap(), gc[field].as_f64().unwrap());
                    let tolerance = a * 0.005 + 2.0 * instances;
                    assert!((a - b).abs() <= tolerance, "{field}: cpu {c}, gpu {g}");
                }
            }
        }
        if genomes == &own {
            assert_eq!(
                cpu, gpu,
                "the target's own genome: exact counts in every view"
            );
            assert_eq!(cpu[0]["fitness"], 3.0);
        }
    }
}

/// A million models' volume counters take more than the 128 MiB a storage binding is
/// kept to (`shapegen::gpu::MAX_BINDING`): the run is refused when the backend is opened,
/// before the first generation, naming the setting.
fn a_population_beyond_the_gpus_bindings_is_refused_before_it_runs() {
    let dir = tempfile::tempdir().unwrap();
    let cube = dir.path().join("cube.obj");
    fs::write(&cube, UNIT_CUBE_OBJ).unwrap();
    let scene = dir.path().join("ship.toml");
    fs::write(&scene, SHIP_SCENE.replace("TARGET", "cube.obj")).unwrap();
    let out = dir.path().join("out");
    let err = fails(&[
        "run",
        s(&scene),
        "--gpu",
        "--max-memory",
        "1T",
        "--set",
        "optimizer.population=1000000",
        "--out",
        s(&out),
    ]);
    assert!(
        err.contains("optimizer.population = 1000000 has the GPU count 1000000 models at once"),
        "{err}"
    );
    assert!(err.contains("count on the CPU (--cpu)"), "{err}");
    assert!(!out.join("checkpoint.json").exists());
}

fn a_gpu_search_counts_children_from_their_parents_with_the_same_result() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let base = ["run", s(&scene), "--gpu", "--seed", "5", "--out", s(&out)];
        let printed = ok(&[&base[..], extra].concat());
        (out, printed)
    };
    let (kept, _) = run("kept", &[]);
    let (full, _) = run("full", &["--no-incremental"]);
    assert_eq!(timeless_curve(&kept), timeless_curve(&full));
    let summary = |dir: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
    };
    let (kept, full) = (summary(&kept), summary(&full));
    assert_eq!(kept["best_fitness"], full["best_fitness"]);
    let incremental = &kept["incremental"];
    assert!(
        incremental["children_incremental"].as_u64().unwrap() > 0,
        "{incremental}"
    );
    assert!(full["incremental"].is_null(), "{}", full["incremental"]);
}

/// Lot buildings (walls, roofs and windows are generated facets) evolved toward a block
/// on the volume scorer: the GPU run counts what the CPU run counts, so both end with
/// the same curve and the same best model.
fn lot_buildings_fill_a_volume_on_the_gpu_as_on_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let block = "v -5 0 -4\nv 3 0 -4\nv 3 9 -4\nv -5 9 -4\nv -5 0 4\nv 3 0 4\nv 3 9 4\n\
                 v -5 9 4\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
    fs::write(dir.path().join("block.obj"), block).unwrap();
    let scene = dir.path().join("lot.toml");
    fs::write(
        &scene,
        r#"generator = "lot_building"

[lot]
points = [[-8, -6], [8, -6], [8, 0], [0, 0], [0, 6], [-8, 6]]

[limits]
min_len = 2
optimal_len = 40
max_len = 200
max_depth = 16

[optimizer]
population = 40
generations = 6

[volume]
grid = { min = [-9, 0, -7], max = [9, 12, 7], resolution = [54, 36, 42] }
good = 2.0
bad = 15.0

[[volume.target]]
mesh = "block.obj"
inside = 1.0
outside = -1.0
"#,
    )
    .unwrap();
    let run = |backend: &str| {
        let out = dir.path().join(backend.trim_start_matches('-'));
        let run = shapegen(&["run", s(&scene), backend, "--seed", "3", "--out", s(&out)]);
        let printed = String::from_utf8_lossy(&run.stderr).into_owned();
        assert!(run.status.success(), "{printed}");
        (out, printed)
    };
    let (cpu, _) = run("--cpu");
    let (gpu, printed) = run("--gpu");
    assert!(printed.contains("on GPU: "), "{printed}");
    assert_eq!(timeless_curve(&cpu), timeless_curve(&gpu));
    let best = |dir: &std::path::Path| fs::read_to_string(dir.join("best.genome.json")).unwrap();
    assert_eq!(best(&cpu), best(&gpu));
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(gpu.join("summary.json")).unwrap()).unwrap();
    assert!(summary["best_fitness"].as_f64().unwrap() > 0.0, "{summary}");
}
