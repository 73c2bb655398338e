//! `shapegen run` on a scene with objectives, end to end on a tiny building scene: the
//! front's files, determinism at any thread count, resume and interruption, and the
//! other commands (target, render, score, compare) on such a scene.

mod support;

use std::fs;
use std::path::{Path, PathBuf};

use support::{chart, fails, interrupt_when, ok, s, shapegen, timeless_summary, timeless_table};

/// A tiny multi-objective building scene: a 16 x 16 footprint target (the lot's left
/// half), distinct normals and a height of 20; population 16 for 5 generations.
fn scene(dir: &Path) -> PathBuf {
    image::GrayImage::from_fn(16, 16, |x, y| {
        let inside = (3..8).contains(&x) && (3..13).contains(&y);
        image::Luma([if inside { 0 } else { 255 }])
    })
    .save(dir.join("top.png"))
    .unwrap();
    let path = dir.join("scene.toml");
    fs::write(
        &path,
        r#"
generator = "building"
[limits]
min_len = 2
optimal_len = 30
max_len = 60
max_depth = 12
[[objective]]
name = "top"
kind = "top_match"
image = "top.png"
min = [-8, -8]
max = [8, 8]
[[objective]]
name = "facets"
kind = "unique_normals"
[[objective]]
kind = "height"
target = 20
[selection]
ranking = "pareto"
[optimizer]
seed = 3
population = 16
elitism = 2
initial_length = 10
generations = 5
archive = 40
"#,
    )
    .unwrap();
    path
}

fn read(dir: &Path, file: &str) -> String {
    fs::read_to_string(dir.join(file)).unwrap()
}

#[test]
fn a_front_run_writes_the_whole_front_at_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let one = dir.path().join("one");
    let two = dir.path().join("two");
    let out = ok(&["--threads", "1", "run", s(&scene), "--out", s(&one)]);
    assert!(out.contains("non-dominated models"), "{out}");
    ok(&["--threads", "2", "run", s(&scene), "--out", s(&two)]);

    let summary = timeless_summary(&one);
    assert_eq!(summary["generations"], 5);
    assert_eq!(summary["evaluations"], 16 + 5 * 14);
    assert_eq!(summary["ranking"], "pareto");
    assert_eq!(summary["objectives"][2]["name"], "height");
    assert_eq!(summary["objectives"][2]["sense"], "minimize");
    let front = summary["front"].as_u64().unwrap() as usize;
    assert!((1..=40).contains(&front), "{summary}");

    let csv = read(&one, "front.csv");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("model,genes,top,facets,height"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), front);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row[0], i as f64);
        assert!(
            (0.0..=1.0).contains(&row[2]),
            "a match is a fraction: {row:?}"
        );
        assert!(row[3] >= 1.0 && row[4] >= 0.0, "{row:?}");
    }
    // No member dominates another.
    let dominates = |a: &[f64], b: &[f64]| {
        let (ge, gt) = (
            a[2] >= b[2] && a[3] >= b[3] && a[4] <= b[4],
            a[2] > b[2] || a[3] > b[3] || a[4] < b[4],
        );
        ge && gt
    };
    for a in &rows {
        assert!(rows.iter().all(|b| !dominates(a, b)), "{a:?} dominates");
    }
    // Sorted by the first objective, best first.
    assert!(rows.windows(2).all(|w| w[0][2] >= w[1][2]));

    let models = fs::read_dir(one.join("front")).unwrap().count();
    assert_eq!(models, front);
    let glb = fs::read(one.join("front/model_000.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let history = read(&one, "history.csv");
    assert_eq!(
        history.lines().next(),
        Some("generation,elapsed_s,evaluations,front,best_top,best_facets,best_height")
    );
    assert_eq!(history.lines().count(), 1 + 6);
    for file in ["contact_sheet.png", "overlay_top.png"] {
        image::open(one.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
    let members = format!("front members ({front})");
    for (a, b) in [("top", "facets"), ("top", "height"), ("facets", "height")] {
        let title = format!("Multi-objective front: {b} against {a}");
        let file = format!("scatter_{a}_{b}.png");
        chart(&one, &file, (640, 480), &[&title, a, b, &members]);
    }
    assert_eq!(
        image::open(one.join("overlay_top.png")).unwrap().width(),
        16
    );

    // Threads change nothing.
    assert_eq!(summary, timeless_summary(&two));
    for file in [
        "contact_sheet.png",
        "scatter_top_facets.png",
        "scatter_top_facets.svg",
    ] {
        assert_eq!(
            fs::read(one.join(file)).unwrap(),
            fs::read(two.join(file)).unwrap(),
            "{file}"
        );
    }
    assert_eq!(read(&one, "front.csv"), read(&two, "front.csv"));
    assert_eq!(
        read(&one, "front.genomes.json"),
        read(&two, "front.genomes.json")
    );
}

#[test]
fn a_resumed_front_run_ends_as_an_uninterrupted_one() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let whole = dir.path().join("whole");
    let parts = dir.path().join("parts");
    ok(&["run", s(&scene), "--out", s(&whole)]);
    ok(&["run", s(&scene), "--generations", "2", "--out", s(&parts)]);
    assert_eq!(timeless_summary(&parts)["generations"], 2);
    ok(&["run", "--resume", s(&parts), "--generations", "5"]);
    assert_eq!(timeless_summary(&parts), timeless_summary(&whole));
    assert_eq!(read(&parts, "front.csv"), read(&whole, "front.csv"));
    assert_eq!(
        read(&parts, "front.genomes.json"),
        read(&whole, "front.genomes.json")
    );
}

/// Counting bred children's projections from their parents' kept state changes nothing
/// but the time: the same front, genomes and history (its elapsed_s column aside) as
/// measuring every child in full.
#[test]
fn a_front_run_ends_the_same_with_and_without_incremental_scoring() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let (on, off) = (dir.path().join("on"), dir.path().join("off"));
    let base = ["run", s(&scene), "--generations", "12", "--out"];
    let run = shapegen(&[&base[..], &[s(&on)]].concat());
    assert!(run.status.success());
    let printed = String::from_utf8(run.stderr).unwrap();
    assert!(
        printed.contains("incremental scoring: ") && printed.contains("projection objectives"),
        "{printed}"
    );
    ok(&[&base[..], &[s(&off), "--no-incremental"]].concat());
    assert_eq!(timeless_summary(&on), timeless_summary(&off));
    for file in ["front.csv", "front.genomes.json"] {
        assert_eq!(read(&on, file), read(&off, file), "{file}");
    }
    let history = timeless_table(&on, "history.csv");
    assert_eq!(history, timeless_table(&off, "history.csv"));
    assert_eq!(history.len(), 1 + 13);

    let summary = |dir: &Path| -> serde_json::Value {
        serde_json::from_str(&read(dir, "summary.json")).unwrap()
    };
    let counted = &summary(&on)["incremental"];
    // 12 generations of 14 bred children, each counted one way or the other.
    let children = counted["children_incremental"].as_u64().unwrap()
        + counted["children_full"].as_u64().unwrap();
    assert_eq!(children, 12 * 14, "{counted}");
    assert!(
        counted["children_incremental"].as_u64().unwrap() > 84,
        "{counted}"
    );
    assert!(counted["kept_bytes"].as_u64().unwrap() > 0, "{counted}");
    assert!(summary(&off).get("incremental").is_none());
}

#[test]
fn target_and_render_work_on_objective_scenes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let run = dir.path().join("run");
    ok(&["run", s(&scene), "--generations", "1", "--out", s(&run)]);
    let genomes = run.join("front.genomes.json");
    let out = ok(&[
        "target",
        s(&scene),
        "--genome",
        s(&genomes),
        "--out",
        s(&dir.path().join("made")),
    ]);
    assert!(out.contains("for `top`"), "{out}");
    assert_eq!(
        image::open(dir.path().join("made.png")).unwrap().width(),
        16
    );
    let pictures = dir.path().join("pictures");
    ok(&[
        "render",
        s(&scene),
        "--genomes",
        s(&genomes),
        "--out",
        s(&pictures),
        "--width",
        "64",
        "--height",
        "48",
    ]);
    let preview = image::open(pictures.join("model_0.png")).unwrap();
    assert_eq!((preview.width(), preview.height()), (64, 48));
    assert!(pictures.join("overlay_0.png").is_file());

    let scores = ok(&["score", s(&scene), "--genomes", s(&genomes)]);
    let rows: Vec<serde_json::Value> = scores
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let front: Vec<Vec<f64>> = read(&run, "front.csv")
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), front.len());
    // Equal up to serde_json's reading precision.
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
    for (row, values) in rows.iter().zip(&front) {
        assert!(same(row["objectives"]["top"].as_f64().unwrap(), values[2]));
        assert!(same(
            row["objectives"]["height"].as_f64().unwrap(),
            values[4]
        ));
    }

    let err = fails(&[
        "compare",
        s(&scene),
        "--runs",
        "1",
        "--seconds",
        "1",
        "--out",
        s(&dir.path().join("c")),
    ]);
    assert!(err.contains("multi-objective"), "{err}");
}

#[test]
fn an_interrupted_front_run_keeps_its_front() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let args = [
        "run",
        s(&scene),
        "--generations",
        "1000000",
        "--out",
        s(&out),
    ];
    let ended = interrupt_when(&args, &out.join("checkpoint.json"), || {
        // What is kept while the run goes on: the front as a table, as genomes and as
        // models, and the viewer's `run.json`, all of the same save.
        assert!(out.join("front.csv").is_file() && out.join("front.genomes.json").is_file());
        // Read between two saves: `run.json` the same before and after.
        let (live, rows, models) = (0..50)
            .find_map(|_| {
                let before = read(&out, "run.json");
                let rows = read(&out, "front.csv").lines().count() - 1;
                let live: serde_json::Value = serde_json::from_str(&before).unwrap();
                let members = live["front"].as_u64().unwrap() as usize;
                let models = (0..members)
                    .filter(|i| out.join(format!("front/model_{i:03}.glb")).is_file())
                    .count();
                (read(&out, "run.json") == before).then_some((live, rows, models))
            })
            .expect("a moment between two saves");
        assert_eq!(live["running"], true, "{live}");
        assert_eq!(live["method"], "ga", "{live}");
        assert_eq!(live["front"], rows, "{live}");
        assert_eq!(models, rows, "a model per member");
    });
    assert!(ended.status.success(), "an interrupted run ends cleanly");
    let summary = timeless_summary(&out);
    assert_eq!(summary["stopped"], "interrupted");
    let front = summary["front"].as_u64().unwrap() as usize;
    assert_eq!(read(&out, "front.csv").lines().count(), 1 + front);
    assert_eq!(fs::read_dir(out.join("front")).unwrap().count(), front);
    let live: serde_json::Value = serde_json::from_str(&read(&out, "run.json")).unwrap();
    assert_eq!(
        (live["running"].as_bool(), live["front"].as_u64()),
        (Some(false), Some(front as u64))
    );
    assert_eq!(live["evaluations"], summary["evaluations"]);
    // The run can go on from where it stopped.
    let generations = summary["generations"].as_u64().unwrap() + 2;
    ok(&[
        "run",
        "--resume",
        s(&out),
        "--generations",
        &generations.to_string(),
    ]);
    assert_eq!(timeless_summary(&out)["generations"], generations);
}
