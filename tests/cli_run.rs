//! `shapegen run` end to end on a small scene: the files it writes, the same result at
//! any thread count, resuming, and mistakes.

mod support;

use std::fs;
use std::path::Path;

use shapegen::scene::Method;

use support::{
    chart, interrupt_when, ok, s, score, shapegen, skyline_scene as scene, timeless_curve,
    timeless_summary,
};

#[test]
fn a_run_writes_everything_and_does_not_depend_on_threads() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let one = dir.path().join("one");
    let two = dir.path().join("two");
    let out = ok(&[
        "--threads",
        "1",
        "run",
        s(&scene),
        "--cpu",
        "--seed",
        "5",
        "--out",
        s(&one),
    ]);
    assert!(out.contains("best fitness"), "{out}");
    ok(&[
        "--threads",
        "2",
        "run",
        s(&scene),
        "--cpu",
        "--seed",
        "5",
        "--out",
        s(&two),
    ]);
    for file in [
        "best.obj",
        "best.mtl",
        "best.glb",
        "best.png",
        "overlay.png",
        "best.genome.json",
        "fitness.csv",
        "fitness.png",
        "fitness.svg",
        "summary.json",
        "checkpoint.json",
    ] {
        assert!(one.join(file).is_file(), "{file} written");
    }
    let a = timeless_summary(&one);
    assert_eq!(
        a,
        timeless_summary(&two),
        "same seed, same summary at 1 and 2 threads"
    );
    assert_eq!(a["generations"], 8);
    assert_eq!(a["evaluations"], 24 + 8 * 20);
    assert_eq!(
        (a["seed"].as_u64(), a["method"].as_str()),
        (Some(5), Some("ga"))
    );
    assert_eq!(a["backend"], "CPU");
    let csv = fs::read_to_string(one.join("fitness.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 9);
    assert!(csv.starts_with("generation,elapsed_s,evaluations,best,mean,std\n"));
    // The best fitness never drops, and the run improved on its initial population.
    let best: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).unwrap().parse().unwrap())
        .collect();
    assert!(best.windows(2).all(|w| w[1] >= w[0]));
    assert!(best[8] > best[0], "{best:?}");
    let overlay = image::open(one.join("overlay.png")).unwrap();
    assert_eq!((overlay.width(), overlay.height()), (160, 90));
    let texts = [
        "city with ga: fitness per generation",
        "generations",
        "fitness",
        "best",
        "mean",
    ];
    chart(&one, "fitness.png", (640, 400), &texts);
    // The chart is drawn from the generations alone: the same at any thread count.
    for file in ["fitness.png", "fitness.svg"] {
        assert_eq!(
            fs::read(one.join(file)).unwrap(),
            fs::read(two.join(file)).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn a_resumed_run_ends_as_an_uninterrupted_one() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let whole = dir.path().join("whole");
    let parts = dir.path().join("parts");
    ok(&["run", s(&scene), "--cpu", "--out", s(&whole)]);
    ok(&[
        "run",
        s(&scene),
        "--cpu",
        "--generations",
        "3",
        "--out",
        s(&parts),
    ]);
    assert_eq!(timeless_summary(&parts)["generations"], 3);
    ok(&["run", "--resume", s(&parts), "--cpu", "--generations", "8"]);
    assert_eq!(timeless_summary(&parts), timeless_summary(&whole));
    for file in ["best.genome.json", "fitness.png", "fitness.svg"] {
        assert_eq!(
            fs::read(parts.join(file)).unwrap(),
            fs::read(whole.join(file)).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn mistakes_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let methods = format!("the methods are {}", Method::names());
    let cases: [(&[&str], &str); 5] = [
        (
            &["--set", "optimizer.populaton=5"],
            "unknown field `populaton`",
        ),
        (&["--set", "optimizer.elitism=30"], "optimizer.elitism"),
        (&["--set", "optimizer"], "write it as key=value"),
        (&["--method", "annealing"], &methods),
        (
            &["--seconds=-1"],
            "`--seconds`: -1 must be a number of seconds > 0",
        ),
    ];
    for (extra, expected) in cases {
        let mut args = vec!["run", s(&scene), "--cpu", "--out", s(&out)];
        args.extend_from_slice(extra);
        let run = shapegen(&args);
        assert!(!run.status.success(), "{extra:?} succeeded");
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(err.contains(expected), "{extra:?}: {err}");
    }
    let run = shapegen(&["run", "--resume", s(dir.path())]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        !run.status.success() && err.contains("checkpoint.json"),
        "{err}"
    );
}

#[test]
fn an_interrupted_run_keeps_what_it_found() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let args = [
        "run",
        s(&scene),
        "--cpu",
        "--generations",
        "1000000",
        "--out",
        s(&out),
    ];
    let ended = interrupt_when(&args, &out.join("checkpoint.json"), || {});
    assert!(ended.status.success(), "an interrupted run ends cleanly");
    let summary = timeless_summary(&out);
    assert_eq!(summary["stopped"], "interrupted");
    let genome = fs::read_to_string(out.join("best.genome.json")).unwrap();
    assert!(genome.contains("\"generator\": \"city\""));
    // The run can go on from where it stopped.
    ok(&[
        "run",
        "--resume",
        s(&out),
        "--cpu",
        "--generations",
        &(summary["generations"].as_u64().unwrap() + 2).to_string(),
    ]);
}

/// Counting children from their parents' kept state is exact: a run without it finds
/// the same models with the same fitness, generation by generation, and only the summary
/// of how children were counted differs.
#[test]
fn incremental_scoring_changes_nothing_but_the_time() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let (on, off) = (dir.path().join("on"), dir.path().join("off"));
    let base = ["run", s(&scene), "--cpu", "--seed", "9", "--out"];
    ok(&[&base[..], &[s(&on)]].concat());
    ok(&[&base[..], &[s(&off), "--no-incremental"]].concat());
    assert_eq!(timeless_summary(&on), timeless_summary(&off));
    for file in ["best.genome.json", "best.obj"] {
        assert_eq!(
            fs::read_to_string(on.join(file)).unwrap(),
            fs::read_to_string(off.join(file)).unwrap(),
            "{file}"
        );
    }
    assert_eq!(timeless_curve(&on), timeless_curve(&off));
    let summary = |dir: &Path| -> serde_json::Value {
        serde_json::from_str(&fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
    };
    let counted = &summary(&on)["incremental"];
    // 8 generations of 20 bred children, each counted one way or the other.
    let children = counted["children_incremental"].as_u64().unwrap()
        + counted["children_full"].as_u64().unwrap();
    assert_eq!(children, 8 * 20, "{counted}");
    assert!(
        counted["children_incremental"].as_u64().unwrap() > 80,
        "{counted}"
    );
    assert!(summary(&off).get("incremental").is_none());
    // The process's peak memory, where the system says (Linux).
    if cfg!(target_os = "linux") {
        let peak = summary(&on)["peak_rss_bytes"].as_u64().unwrap();
        assert!((1 << 20..1 << 40).contains(&peak), "{peak}");
    }

    // RJMCMC's proposals are counted from their chains' states.
    let text = fs::read_to_string(&scene).unwrap();
    let any = dir.path().join("any.toml");
    fs::write(&any, text.split("[optimizer]").next().unwrap()).unwrap();
    let (on, off) = (dir.path().join("mcmc_on"), dir.path().join("mcmc_off"));
    let base = [
        "run",
        s(&any),
        "--cpu",
        "--method",
        "rjmcmc",
        "--set",
        "optimizer.chains=6",
        "--generations",
        "6",
        "--out",
    ];
    ok(&[&base[..], &[s(&on)]].concat());
    ok(&[&base[..], &[s(&off), "--no-incremental"]].concat());
    assert_eq!(timeless_summary(&on), timeless_summary(&off));
    assert_eq!(
        fs::read_to_string(on.join("best.genome.json")).unwrap(),
        fs::read_to_string(off.join("best.genome.json")).unwrap()
    );
    let counted = &summary(&on)["incremental"];
    assert!(
        counted["children_incremental"].as_u64().unwrap() > 0,
        "{counted}"
    );
}

#[test]
fn every_method_runs_and_resumes_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let ga_scene = scene(dir.path());
    // The same scene without the GA's settings.
    let text = fs::read_to_string(&ga_scene).unwrap();
    let scene = dir.path().join("any.toml");
    fs::write(&scene, text.split("[optimizer]").next().unwrap()).unwrap();
    // The hybrid with both additions on: the resume lands just after its seeding.
    let hybrid = "population=16,elitism=4,refine=3,seed_steps=2";
    for (method, sets) in [
        ("smc", "particles=16"),
        ("sosmc", "particles=16"),
        ("rjmcmc", "chains=6"),
        ("hybrid", hybrid),
    ] {
        let whole = dir.path().join(format!("{method}_whole"));
        let parts = dir.path().join(format!("{method}_parts"));
        let sets: Vec<String> = sets.split(',').map(|v| format!("optimizer.{v}")).collect();
        let mut base = vec!["run", s(&scene), "--cpu", "--method", method];
        for set in &sets {
            base.extend(["--set", set.as_str()]);
        }
        ok(&[&base[..], &["--generations", "6", "--out", s(&whole)]].concat());
        ok(&[&base[..], &["--generations", "2", "--out", s(&parts)]].concat());
        ok(&["run", "--resume", s(&parts), "--cpu", "--generations", "6"]);
        let summary = timeless_summary(&whole);
        assert_eq!(summary["method"], method);
        assert_eq!(summary["generations"], 6);
        assert_eq!(
            summary,
            timeless_summary(&parts),
            "{method}: resumed equals uninterrupted"
        );
    }
}

#[test]
fn the_papers_scenes_run_from_the_repository() {
    // The paper's three scenes read only files in the repository (`scenes/paper/`).
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for name in ["spaceship_volume", "tree_sketch1", "city_whale"] {
        let scene = root.join(format!("scenes/paper/{name}.toml"));
        let out = dir.path().join(name);
        let printed = ok(&[
            "run",
            s(&scene),
            "--cpu",
            "--generations",
            "2",
            "--out",
            s(&out),
        ]);
        assert!(printed.contains("after 2 generations"), "{name}: {printed}");
        assert!(out.join("best.genome.json").is_file(), "{name}");
    }
}

/// Runs `scene` on the CPU into `out` with `args` added; returns its `summary.json`.
fn run_summary(scene: &Path, out: &Path, args: &[&str]) -> serde_json::Value {
    ok(&[&["run", s(scene), "--cpu", "--out", s(out)], args].concat());
    timeless_summary(out)
}

#[test]
fn every_method_returns_the_best_it_scored_within_the_limits_it_keeps_on_an_unreachable_sketch() {
    // Every model that draws anything scores below the bare axiom here. Each method
    // returns the best model it scored, within the limits it keeps, which the summary
    // states: the scene's min_len = 4 for the methods that keep it, none for the
    // original SMC, whose particles grow one gene a step from the axiom.
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/tree_sketch_offset.toml");
    for method in Method::ALL {
        let name = method.name();
        let out = dir.path().join(name);
        let summary = run_summary(&scene, &out, &["--method", name, "--evaluations", "4000"]);
        let genes = summary["genes"].as_u64().unwrap();
        let kept = &summary["kept_limits"];
        let (min, max) = (
            kept["min_len"].as_u64().unwrap(),
            kept["max_len"].as_u64().unwrap(),
        );
        assert!(
            (min..=max).contains(&genes),
            "{name}: {genes} genes, {kept}"
        );
        if name == "ga" {
            assert_eq!(min, 4, "{name}: {kept}");
        }
        let best = summary["best_fitness"].as_f64().unwrap();
        let scored = score(&scene, &out.join("best.genome.json"), "--cpu")[0]["fitness"]
            .as_f64()
            .unwrap();
        assert_eq!(scored, best, "{name}");
    }
}

#[test]
fn a_shaped_scene_runs_and_its_best_scores_above_its_published_fitness() {
    // Shaping only lowers what off-target pixels cost, so a model that covers any
    // pixel beside the sketch scores higher in the shaped scene than in the plain one.
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let shaped = root.join("scenes/tree_sketch_offset_shaped.toml");
    let plain = root.join("scenes/tree_sketch_offset.toml");
    let out = dir.path().join("shaped");
    let args = ["--method", "ga", "--evaluations", "1000", "--seed", "2"];
    let summary = run_summary(&shaped, &out, &args);
    let genome = out.join("best.genome.json");
    let fitness = |scene: &Path| {
        score(scene, &genome, "--cpu")[0]["fitness"]
            .as_f64()
            .unwrap()
    };
    let metrics = &summary["metrics"];
    assert_eq!(metrics["genes"], summary["genes"]);
    assert_eq!(metrics["instances"], summary["instances"]);
    assert!(metrics["triangles"].as_u64().unwrap() > 0);
    let iou = metrics["silhouette_iou"][0]["iou"].as_f64().unwrap();
    assert!((0.0..1.0).contains(&iou), "{metrics}");
    let (in_shaped, in_plain) = (fitness(&shaped), fitness(&plain));
    assert_eq!(in_shaped, summary["best_fitness"].as_f64().unwrap());
    assert!(in_plain < in_shaped, "{in_plain} < {in_shaped}");
}

#[test]
fn a_scene_of_three_views_searches_all_three_and_measures_each() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spaceship_views.toml");
    let summary = run_summary(&scene, &dir.path().join("out"), &["--evaluations", "1500"]);
    let views = summary["metrics"]["silhouette_iou"].as_array().unwrap();
    let names: Vec<&str> = views
        .iter()
        .map(|v| v["target"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "targets/spaceship_views_front.png",
            "targets/spaceship_views_side.png",
            "targets/spaceship_views_top.png"
        ]
    );
    // Each view is matched in part by 1,500 evaluations of the hybrid; the fitness sums
    // the three terms, so it is above what any one view alone can give (1).
    for view in views {
        let iou = view["iou"].as_f64().unwrap();
        assert!(iou > 0.5, "{view}");
    }
    assert!(summary["best_fitness"].as_f64().unwrap() > 2.0, "{summary}");
}
