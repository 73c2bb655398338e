//! `shapegen compare` end to end on a small scene: the files it writes, the seeds of the
//! runs, equal results at equal evaluations, Ctrl-C and mistakes.

mod support;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

use support::{chart, fails, interrupt_when, ok, s};

/// What the lines and the shading of every comparison chart show, in its legend.
const QUARTILES: &str = "line: median, shaded: first to third quartile";

/// A city scene at 160 x 90 whose target is the silhouette of a sampled city, with the
/// paper's settings for every method.
fn scene(dir: &Path) -> PathBuf {
    let text = r#"
generator = "city"
[limits]
min_len = 4
optimal_len = 100
max_len = 201
max_depth = 8
[fitness]
length = 0.02
[silhouette]
[[silhouette.target]]
image = "skyline.png"
camera = { phi = -1.5708, theta = 0.06, radius = 25, lookat = [0, 4.2, 0], fov = 45, near = 0.1, far = 200, width = 160, height = 90 }
[optimizer]
seed = 4
"#;
    let path = dir.join("skyline.toml");
    fs::write(&path, text).unwrap();
    image::GrayImage::from_pixel(160, 90, image::Luma([255]))
        .save(dir.join("skyline.png"))
        .unwrap();
    let c = dir.join("c");
    ok(&["sample", "-g", "city", "-n", "1", "-s", "3", "-o", s(&c)]);
    let genomes = c.join("genomes.json");
    let target = dir.join("skyline.png");
    ok(&[
        "target",
        s(&path),
        "--genome",
        s(&genomes),
        "--out",
        s(&target),
    ]);
    path
}

/// One row of `compare.csv`.
#[derive(Debug)]
struct Row {
    method: String,
    run: u64,
    seed: u64,
    elapsed_s: f64,
    evaluations: u64,
    best: f64,
}

fn rows(dir: &Path) -> Vec<Row> {
    let csv = fs::read_to_string(dir.join("compare.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("method,run,seed,elapsed_s,evaluations,best")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 6, "{l}");
            Row {
                method: f[0].to_owned(),
                run: f[1].parse().unwrap(),
                seed: f[2].parse().unwrap(),
                elapsed_s: f[3].parse().unwrap(),
                evaluations: f[4].parse().unwrap(),
                best: f[5].parse().unwrap(),
            }
        })
        .collect()
}

/// The rows of each (method, run), in order.
fn by_run(rows: &[Row]) -> BTreeMap<(String, u64), Vec<&Row>> {
    let mut runs: BTreeMap<(String, u64), Vec<&Row>> = BTreeMap::new();
    for r in rows {
        runs.entry((r.method.clone(), r.run)).or_default().push(r);
    }
    runs
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn a_comparison_writes_every_run_on_shared_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    ok(&[
        "compare",
        s(&scene),
        "--methods",
        "rjmcmc,ga,sosmc",
        "--runs",
        "2",
        "--seconds",
        "0.6",
        "--seed",
        "7",
        // Published generation counts do not end a compare run: only time does.
        "--set",
        "optimizer.generations=1",
        "--cpu",
        "--out",
        s(&out),
    ]);
    let rows = rows(&out);
    let runs = by_run(&rows);
    let methods = ["rjmcmc", "ga", "sosmc"];
    assert_eq!(runs.len(), 6, "every method and run present");
    // runs.csv: each run's final best and its model's measures (a silhouette scene:
    // size and silhouette IoU, no volume or surface measures).
    let table = fs::read_to_string(out.join("runs.csv")).unwrap();
    let lines: Vec<Vec<&str>> = table.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        lines[0].join(","),
        "method,run,seed,evaluations,best,genes,instances,triangles,voxel_iou,\
         silhouette_iou,chamfer,f_score"
    );
    assert_eq!(lines.len(), 7);
    for line in &lines[1..] {
        let best: f64 = line[4].parse().unwrap();
        let last = runs[&(line[0].to_owned(), line[1].parse().unwrap())]
            .last()
            .unwrap();
        assert_eq!(best, last.best, "{line:?}");
        let iou: f64 = line[9].parse().unwrap();
        assert!((0.0..=1.0).contains(&iou), "{line:?}");
        assert_eq!([line[8], line[10], line[11]], ["", "", ""], "{line:?}");
    }
    let summary_json = summary(&out);
    assert_eq!(
        summary_json["methods"][0]["metrics"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    for m in methods {
        for r in 0..2 {
            let run = &runs[&(m.to_owned(), r)];
            // Run r of every method uses the base seed + r.
            assert!(run.iter().all(|row| row.seed == 7 + r), "{m} {r}");
            assert!(run.len() > 2, "{m} run {r} went past 1 generation");
            assert!(run.windows(2).all(|w| w[1].best >= w[0].best
                && w[1].evaluations > w[0].evaluations
                && w[1].elapsed_s >= w[0].elapsed_s));
            let last = run.last().unwrap();
            assert!(last.elapsed_s >= 0.6 && last.elapsed_s < 5.0, "{m} {r}");
            let genome = out.join(format!("runs/{m}-{r}/best.genome.json"));
            assert!(
                fs::read_to_string(genome)
                    .unwrap()
                    .contains(r#""generator": "city""#)
            );
        }
    }

    let summary = summary(&out);
    assert_eq!(summary["seconds"], 0.6);
    assert_eq!(summary["base_seed"], 7);
    assert_eq!(summary["seeds"], serde_json::json!([7, 8]));
    assert_eq!(summary["backend"], "CPU");
    assert_eq!(summary["complete"], true);
    assert!(summary["scene"].as_str().unwrap().ends_with("skyline.toml"));
    let listed: Vec<&str> = summary["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    assert_eq!(listed, methods, "methods in the order given");
    for m in summary["methods"].as_array().unwrap() {
        let name = m["method"].as_str().unwrap();
        let finals: Vec<f64> = (0..2)
            .map(|r| runs[&(name.to_owned(), r)].last().unwrap().best)
            .collect();
        let evaluations: Vec<u64> = (0..2)
            .map(|r| runs[&(name.to_owned(), r)].last().unwrap().evaluations)
            .collect();
        assert_eq!(m["runs"], 2);
        let mean = (finals[0] + finals[1]) / 2.0;
        assert!(
            (m["final_mean"].as_f64().unwrap() - mean).abs() < 1e-12,
            "{m}"
        );
        let std = (finals[0] - finals[1]).abs() / 2f64.sqrt();
        assert!(
            (m["final_std"].as_f64().unwrap() - std).abs() < 1e-12,
            "{m}"
        );
        // serde_json reads floats to within an ulp or so, not always exactly.
        let best = m["best"].as_f64().unwrap();
        assert!((best - finals[0].max(finals[1])).abs() < 1e-12, "{m}");
        assert_eq!(
            m["evaluations"].as_f64().unwrap(),
            (evaluations[0] + evaluations[1]) as f64 / 2.0
        );
    }

    let texts = [
        "skyline: best fitness against time",
        "wall time (seconds)",
        "best fitness (median and quartiles over runs)",
        "rjmcmc",
        "ga",
        "sosmc",
        QUARTILES,
    ];
    chart(&out, "compare.png", (800, 500), &texts);
    // The scene gives no optimum: no gaps to it.
    assert_eq!(summary["optimum"], serde_json::Value::Null);
    for file in ["targets.csv", "gap-time.png", "gap-time.svg"] {
        assert!(!out.join(file).exists(), "{file}");
    }
}

#[test]
fn equal_evaluation_budgets_give_equal_results_at_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let finals = |threads: &str, name: &str| {
        let out = dir.path().join(name);
        ok(&[
            "--threads",
            threads,
            "compare",
            s(&scene),
            "--runs",
            "2",
            "--seconds",
            "1000",
            "--set",
            "optimizer.evaluations=400",
            "--cpu",
            "--out",
            s(&out),
        ]);
        let rows = rows(&out);
        let runs = by_run(&rows);
        assert_eq!(
            runs.len(),
            2 * shapegen::scene::Method::ALL.len(),
            "every method twice"
        );
        runs.into_iter()
            .map(|(k, v)| {
                let last = v.last().unwrap();
                assert!(last.evaluations <= 400, "{k:?}");
                (k, last.best.to_bits(), last.evaluations)
            })
            .collect::<Vec<_>>()
    };
    let one = finals("1", "one");
    assert_eq!(one, finals("2", "two"));
    // Every method sees the scene's seed 4 in run 0 and 5 in run 1, and the two runs differ.
    let ga: Vec<_> = one.iter().filter(|(k, ..)| k.0 == "ga").collect();
    assert_ne!(ga[0].1, ga[1].1, "different seeds, different runs");
    assert_eq!(
        summary(&dir.path().join("one"))["seeds"],
        serde_json::json!([4, 5])
    );
}

#[test]
fn a_known_optimum_gives_the_gaps_and_the_times_to_its_fractions() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let compare = |optimum: &str, out: &Path| {
        vec![
            "compare".to_owned(),
            s(&scene).to_owned(),
            "--methods".to_owned(),
            "ga,hybrid".to_owned(),
            "--runs".to_owned(),
            "3".to_owned(),
            "--seconds".to_owned(),
            "1000".to_owned(),
            "--set".to_owned(),
            "optimizer.evaluations=600".to_owned(),
            "--set".to_owned(),
            format!("fitness.optimum={optimum}"),
            "--cpu".to_owned(),
            "--out".to_owned(),
            s(out).to_owned(),
        ]
    };
    let out = dir.path().join("out");
    let args = compare("1.0", &out);
    ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let rows = rows(&out);
    let runs = by_run(&rows);
    let summary = summary(&out);
    assert_eq!(summary["optimum"], 1.0);
    let targets = fs::read_to_string(out.join("targets.csv")).unwrap();
    let lines: Vec<&str> = targets.lines().collect();
    assert_eq!(lines.len(), 1 + 2 * 3, "{targets}");
    assert_eq!(
        lines[0],
        "method,fraction,level,runs,reached,seconds_q1,seconds_median,seconds_q3,\
         evaluations_q1,evaluations_median,evaluations_q3"
    );
    for (m, method) in summary["methods"].as_array().unwrap().iter().enumerate() {
        let name = method["method"].as_str().unwrap();
        let finals: Vec<f64> = (0..3)
            .map(|r| runs[&(name.to_owned(), r)].last().unwrap().best)
            .collect();
        let mut sorted = finals.clone();
        sorted.sort_by(f64::total_cmp);
        let quartiles = method["final_quartiles"].as_array().unwrap();
        assert!((quartiles[1].as_f64().unwrap() - sorted[1]).abs() < 1e-12);
        let reached = method["targets"].as_array().unwrap();
        for (k, fraction) in [0.9, 0.99, 0.999].into_iter().enumerate() {
            let want = finals.iter().filter(|&&b| b >= fraction).count();
            assert_eq!(reached[k]["fraction"], fraction);
            assert_eq!(reached[k]["runs"], 3);
            assert_eq!(reached[k]["reached"], want, "{name} {fraction}");
            let row: Vec<&str> = lines[1 + 3 * m + k].split(',').collect();
            assert_eq!((row[0], row[4]), (name, want.to_string().as_str()));
            // The median time is given exactly when two of the three runs got there.
            assert_eq!(row[6].is_empty(), want < 2, "{row:?}");
        }
    }
    let y = "optimum - best (median and quartiles over runs)";
    for (plot, against, x) in [
        ("gap-time.png", "time", "wall time (seconds)"),
        ("gap-evaluations.png", "evaluations", "evaluations"),
    ] {
        let title = format!("Gap to the optimum (1) against {against}");
        let svg = chart(
            &out,
            plot,
            (800, 500),
            &[&title, x, y, "ga", "hybrid", QUARTILES],
        );
        // The gaps on a log scale, with powers of ten as ticks.
        assert!(svg.contains(">\n1e-"), "{plot}");
    }
    chart(
        &out,
        "compare.png",
        (800, 500),
        &["ga", "hybrid", QUARTILES],
    );
    // An optimum below what the runs reach is wrong, and said so once they show it.
    let low = dir.path().join("low");
    let args = compare("0.000001", &low);
    let err = fails(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(err.contains("fitness.optimum = 0.000001"), "{err}");
    assert!(low.join("compare.csv").exists());
}

#[test]
fn ctrl_c_keeps_the_complete_runs_and_fails() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let args = [
        "compare",
        s(&scene),
        "--methods",
        "ga,smc",
        "--runs",
        "20",
        "--seconds",
        "0.3",
        "--cpu",
        "--out",
        s(&out),
    ];
    let output = interrupt_when(&args, &out.join("summary.json"), || {});
    assert!(!output.status.success(), "an interrupted comparison fails");
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.contains("interrupted"), "{stderr}");
    let summary = summary(&out);
    assert_eq!(summary["complete"], false);
    let rows = rows(&out);
    let runs = by_run(&rows);
    let complete: u64 = summary["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["runs"].as_u64().unwrap())
        .sum();
    assert!((1..40).contains(&complete), "{complete}");
    assert_eq!(
        runs.len() as u64,
        complete,
        "only complete runs are written"
    );
}

#[test]
fn mistakes_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let base = ["compare", s(&scene), "--cpu", "--out", s(&out)];
    let err = |extra: &[&str]| fails(&[&base[..], extra].concat());
    assert!(err(&["--seconds", "1", "--runs", "0"]).contains("--runs 0"));
    for bad in ["0", "-1", "NaN", "inf"] {
        let e = err(&["--runs", "1", &format!("--seconds={bad}")]);
        assert!(e.contains("--seconds"), "{bad}: {e}");
        assert!(!e.contains("panicked"), "{e}");
    }
    let e = err(&["--seconds", "1", "--methods", "ga,pso"]);
    assert!(
        e.contains("`pso`") && e.contains("ga, smc, sosmc, rjmcmc"),
        "{e}"
    );
    assert!(err(&["--seconds", "1", "--methods", ""]).contains("--methods is empty"));
    let e = err(&["--seconds", "1", "--set", "optimizer.population=0"]);
    assert!(e.contains("optimizer.population"), "{e}");
    let e = fails(&[
        "compare",
        s(&dir.path().join("missing.toml")),
        "--seconds",
        "1",
        "--out",
        s(&out),
    ]);
    assert!(e.contains("missing.toml"), "{e}");
    assert!(
        !out.exists(),
        "nothing written for a command that cannot start"
    );
}

#[test]
fn set_keys_are_read_as_each_methods_own() {
    // `variant` is a key of RJMCMC's settings and of SMC's, with values of their own;
    // the scene names no method, so the key must be read as each compared method's.
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    for (methods, variant) in [("rjmcmc", "tempered"), ("smc,sosmc", "generative")] {
        let out = dir.path().join(variant);
        ok(&[
            "compare",
            s(&scene),
            "--methods",
            methods,
            "--runs",
            "1",
            "--seconds",
            "0.3",
            "--set",
            &format!("optimizer.variant={variant}"),
            "--cpu",
            "--out",
            s(&out),
        ]);
        let methods = summary(&out)["methods"].as_array().unwrap().len();
        assert_eq!(methods, if variant == "tempered" { 1 } else { 2 });
    }
}
