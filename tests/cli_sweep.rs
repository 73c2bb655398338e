//! `shapegen sweep` end to end on a small scene: the study's files, results that do not
//! depend on --jobs or --threads, going on after a rerun or an interruption, the plan a
//! folder holds, mistakes, and the Slurm path without Slurm (`--plan-only`, the cells
//! run by hand with `--cell`, `--collect`) against the local sweep.

mod support;

use std::fs;
use std::path::Path;

use support::{chart, cube_ship_scene, fails, interrupt_when, ok, s, sweep_rows_without_seconds};

/// A 2 x 2 study of 2 runs each (8 cells) at 300 evaluations per run, in `out`, with
/// `extra` arguments.
fn study<'a>(scene: &'a Path, out: &'a Path, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "sweep",
        s(scene),
        "--grid",
        "optimizer.population=40,60",
        "--grid",
        "optimizer.selection=tournament,random",
        "--runs",
        "2",
        "--evaluations",
        "300",
        "--seed",
        "4",
        "--cpu",
        "--out",
        s(out),
    ];
    args.extend_from_slice(extra);
    args
}

/// Every cell's best genome, by folder name.
fn genomes(dir: &Path) -> Vec<(String, String)> {
    let mut cells: Vec<(String, String)> = fs::read_dir(dir.join("cells"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (
                name,
                fs::read_to_string(p.join("best.genome.json")).unwrap(),
            )
        })
        .collect();
    cells.sort();
    cells
}

#[test]
fn a_sweep_writes_every_cell_its_tables_and_its_plots() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let out = dir.path().join("out");
    ok(&study(&scene, &out, &[]));

    let rows = sweep_rows_without_seconds(&out);
    assert_eq!(
        rows[0].join(","),
        "cell,optimizer.population,optimizer.selection,run,seed,best,evaluations,\
         generations,evaluations_to_50,evaluations_to_90,evaluations_to_99,genes,\
         instances,triangles,voxel_iou,silhouette_iou,chamfer,f_score"
    );
    assert_eq!(rows.len(), 9, "one row per cell");
    let points = [
        ("40", "tournament"),
        ("40", "random"),
        ("60", "tournament"),
        ("60", "random"),
    ];
    let mut bests = Vec::new();
    for (i, row) in rows[1..].iter().enumerate() {
        // Cells in index order: grid points in the order given, runs inner, seeds 4 + r.
        let (population, selection) = points[i / 2];
        let run = i % 2;
        assert_eq!(
            row[..5],
            [
                i.to_string(),
                population.to_owned(),
                selection.to_owned(),
                run.to_string(),
                (4 + run).to_string()
            ],
            "{row:?}"
        );
        let evaluations: u64 = row[6].parse().unwrap();
        assert!(evaluations <= 300 && evaluations > 250, "{row:?}");
        bests.push(row[5].parse::<f64>().unwrap());
        // The levels a run reached, within its evaluations, each no sooner than the
        // one below: a run that missed a level missed those above it.
        let reached: Vec<Option<u64>> = row[8..11].iter().map(|c| c.parse().ok()).collect();
        // The best model's measures: a volume scene's size, voxel IoU and surfaces.
        let genes: u64 = row[11].parse().unwrap();
        assert!(genes >= 1, "{row:?}");
        let iou: f64 = row[14].parse().unwrap();
        assert!((0.0..=1.0).contains(&iou), "{row:?}");
        assert_eq!(row[15], "", "no silhouette: {row:?}");
        assert!(row[16].parse::<f64>().unwrap() >= 0.0, "{row:?}");
        for pair in reached.windows(2) {
            match (pair[0], pair[1]) {
                (Some(a), Some(b)) => assert!(a <= b && b <= evaluations, "{row:?}"),
                (None, b) => assert_eq!(b, None, "{row:?}"),
                (Some(a), None) => assert!(a <= evaluations, "{row:?}"),
            }
        }
    }
    let top = bests.iter().copied().fold(f64::MIN, f64::max);
    let top_row = &rows[1 + bests.iter().position(|&b| b == top).unwrap()];
    assert!(top_row[8..11].iter().all(|c| !c.is_empty()), "{top_row:?}");

    for i in 0..8 {
        let cell = out.join(format!("cells/{i:04}"));
        let result: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(cell.join("result.json")).unwrap()).unwrap();
        assert_eq!(result["index"], i);
        assert_eq!(result["seed"], 4 + i % 2);
        assert_eq!(
            result["point"]["optimizer.population"],
            points[i as usize / 2].0
        );
        assert_eq!(result["stopped"], "evaluations");
        let history = fs::read_to_string(cell.join("fitness.csv")).unwrap();
        assert!(history.starts_with("generation,elapsed_s,evaluations,best,mean,std\n0,"));
        assert!(
            fs::read_to_string(cell.join("best.genome.json"))
                .unwrap()
                .contains(r#""generator": "spaceship""#)
        );
    }
    let summary = fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(summary.contains("8 of 8 cells done"), "{summary}");
    assert_eq!(summary.matches("| 2 of 2 |").count(), 4, "{summary}");
    assert_eq!(summary.matches("| **best** |").count(), 1, "{summary}");
    let y = "final best fitness (mean +- std over runs)";
    let bars = "dot: mean, bar: mean +- std";
    let population = [
        "Final best fitness against optimizer.population",
        "optimizer.population",
        y,
        "optimizer.selection=tournament",
        "optimizer.selection=random",
        bars,
    ];
    chart(
        &out,
        "final-optimizer.population.png",
        (800, 500),
        &population,
    );
    let selection = [
        "Final best fitness against optimizer.selection",
        "optimizer.selection",
        y,
        "optimizer.population=40",
        "optimizer.population=60",
        bars,
        // The names on the x axis.
        "tournament",
        "random",
    ];
    chart(
        &out,
        "final-optimizer.selection.png",
        (800, 500),
        &selection,
    );
    let curves = [
        "Best fitness against evaluations: the best and the worst grid point",
        "evaluations",
        "best fitness so far (mean +- std over runs)",
        "line: mean, shaded: mean +- std",
    ];
    let svg = chart(&out, "curves.png", (800, 500), &curves);
    // The best grid point (and the worst, where they differ) named.
    assert!(svg.contains(">\nbest: optimizer.population="), "{svg}");
    let plan: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    assert_eq!(plan["runs"], 2);
    assert_eq!(plan["seed"], 4);
    assert_eq!(plan["budget"]["evaluations"], 300);
    assert_eq!(plan["grid"][1]["values"][1], "random");
}

#[test]
fn results_do_not_depend_on_jobs_or_threads() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let one = dir.path().join("one");
    let three = dir.path().join("three");
    ok(&[
        &["--threads", "1"][..],
        &study(&scene, &one, &["--jobs", "1"]),
    ]
    .concat());
    ok(&[
        &["--threads", "2"][..],
        &study(&scene, &three, &["--jobs", "3"]),
    ]
    .concat());
    assert_eq!(
        sweep_rows_without_seconds(&one),
        sweep_rows_without_seconds(&three)
    );
    assert_eq!(genomes(&one), genomes(&three));
    assert_eq!(
        fs::read_to_string(one.join("summary.md")).unwrap(),
        fs::read_to_string(three.join("summary.md")).unwrap()
    );
}

#[test]
fn a_rerun_keeps_finished_cells_and_runs_the_missing_ones() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let out = dir.path().join("out");
    let args = study(&scene, &out, &[]);
    ok(&args);
    let rows = sweep_rows_without_seconds(&out);
    let genomes_before = genomes(&out);
    let kept = out.join("cells/0000/result.json");
    let written = fs::metadata(&kept).unwrap().modified().unwrap();
    fs::remove_dir_all(out.join("cells/0005")).unwrap();

    let run = support::shapegen(&args);
    assert!(run.status.success());
    let stderr = String::from_utf8(run.stderr).unwrap();
    assert!(
        stderr.contains("7 of 8 cells are done") && stderr.contains("running the other 1"),
        "{stderr}"
    );
    assert!(stderr.contains("cell 5 ("), "{stderr}");
    assert!(!stderr.contains("cell 0 ("), "{stderr}");
    assert_eq!(fs::metadata(&kept).unwrap().modified().unwrap(), written);
    assert_eq!(sweep_rows_without_seconds(&out), rows);
    assert_eq!(genomes(&out), genomes_before);
}

#[test]
fn another_study_in_the_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let out = dir.path().join("out");
    ok(&study(&scene, &out, &["--plan-only"]));
    let mut args = study(&scene, &out, &[]);
    let runs = args.iter().position(|a| *a == "--runs").unwrap();
    args[runs + 1] = "3";
    let err = fails(&args);
    assert!(
        err.contains("holds another study")
            && err.contains("runs is 2 there and 3 now")
            && err.contains("new --out"),
        "{err}"
    );
    let err = fails(&study(&scene, &out, &["--set", "optimizer.tournament=3"]));
    assert!(err.contains("sets is [] there"), "{err}");
}

#[test]
fn bad_values_fail_before_any_run_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let out = dir.path().join("out");
    let sweep = |grid: &str, extra: &[&str]| {
        let mut args = vec![
            "sweep",
            s(&scene),
            "--grid",
            grid,
            "--runs",
            "2",
            "--evaluations",
            "100",
            "--out",
            s(&out),
        ];
        args.extend_from_slice(extra);
        fails(&args)
    };
    let err = sweep("optimizer.population=40,abc", &[]);
    assert!(
        err.contains("optimizer.population=abc") && err.contains("`optimizer.population`"),
        "{err}"
    );
    let err = sweep("optimizer.selection=tournament,best", &[]);
    assert!(
        err.contains("`optimizer.selection`") && err.contains("unknown variant `best`"),
        "{err}"
    );
    let err = sweep(
        "optimizer.elitism=10,30",
        &["--set", "optimizer.population=25"],
    );
    assert!(
        err.contains("optimizer.elitism=30") && err.contains("less than the population"),
        "{err}"
    );
    let err = sweep("optimizer.populaton=40,60", &[]);
    assert!(err.contains("unknown field `populaton`"), "{err}");
    let err = sweep("optimizer.seed=1,2", &[]);
    assert!(
        err.contains("--grid optimizer.seed") && err.contains("--runs"),
        "{err}"
    );
    let err = sweep("optimizer.method=ga,rjmcmc", &["--method", "ga"]);
    assert!(err.contains("--method"), "{err}");
    let err = sweep("optimizer.population=40,40", &[]);
    assert!(err.contains("`40` is listed twice"), "{err}");
    let err = sweep("optimizer.population", &[]);
    assert!(err.contains("KEY=V1,V2"), "{err}");
    assert!(!out.exists(), "nothing is written before the plan holds");

    let err = fails(&[
        "sweep",
        s(&scene),
        "--grid",
        "optimizer.population=40,60",
        "--runs",
        "2",
        "--out",
        s(&out),
    ]);
    assert!(
        err.contains("--evaluations, --generations or --seconds"),
        "{err}"
    );
    let err = fails(&["sweep", "--cell", s(&out), "0", "--runs", "2"]);
    assert!(err.contains("--cell") && err.contains("--runs"), "{err}");
}

#[test]
fn slurm_cells_run_by_hand_and_collected_equal_the_local_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let local = dir.path().join("local");
    let planned = dir.path().join("planned");
    ok(&study(&scene, &local, &[]));
    let printed = ok(&study(
        &scene,
        &planned,
        &[
            "--plan-only",
            "--partition",
            "short",
            "--time",
            "0:05:00",
            "--max-running",
            "2",
            "--sbatch-option=--account=p1",
        ],
    ));
    let planned = fs::canonicalize(&planned).unwrap();
    let script_path = planned.join("sweep.sbatch");
    assert!(
        printed.contains(&format!("sbatch {}", script_path.display())),
        "{printed}"
    );
    assert!(!planned.join("cells").exists(), "--plan-only runs nothing");
    assert!(planned.join("logs").is_dir());
    let script = fs::read_to_string(&script_path).unwrap();
    let exe = fs::canonicalize(env!("CARGO_BIN_EXE_shapegen")).unwrap();
    for line in [
        "#SBATCH --array=0-7%2".to_owned(),
        format!("#SBATCH --output={}/logs/%A_%a.out", planned.display()),
        "#SBATCH --partition=short".to_owned(),
        "#SBATCH --time=0:05:00".to_owned(),
        "#SBATCH --account=p1".to_owned(),
        format!(
            "exec {} --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" sweep --cell {} \
             \"$SLURM_ARRAY_TASK_ID\"",
            exe.display(),
            planned.display()
        ),
    ] {
        assert!(
            script.lines().any(|l| l == line),
            "no {line:?} in\n{script}"
        );
    }

    // Collecting before any cell ran names them all missing.
    let err = fails(&["sweep", "--collect", s(&planned)]);
    assert!(err.contains("8 cells are missing: 0-7"), "{err}");
    assert!(err.contains("sbatch --array=0-7"), "{err}");
    // The cells by hand, as the array's tasks run them, in any order; a done one is kept.
    for i in (0..8).rev() {
        ok(&["sweep", "--cell", s(&planned), &i.to_string()]);
    }
    let again = ok(&["sweep", "--cell", s(&planned), "3"]);
    assert!(again.contains("cell 3 is done already"), "{again}");
    let err = fails(&["sweep", "--cell", s(&planned), "8"]);
    assert!(err.contains("cells 0 to 7"), "{err}");
    ok(&["sweep", "--collect", s(&planned)]);

    assert_eq!(
        sweep_rows_without_seconds(&planned),
        sweep_rows_without_seconds(&local)
    );
    assert_eq!(genomes(&planned), genomes(&local));
    assert_eq!(
        fs::read_to_string(planned.join("summary.md")).unwrap(),
        fs::read_to_string(local.join("summary.md")).unwrap()
    );
    for plot in [
        "final-optimizer.population.png",
        "final-optimizer.population.svg",
        "final-optimizer.selection.png",
        "final-optimizer.selection.svg",
        "curves.png",
        "curves.svg",
    ] {
        assert_eq!(
            fs::read(planned.join(plot)).unwrap(),
            fs::read(local.join(plot)).unwrap(),
            "{plot}"
        );
    }
}

#[test]
fn an_interrupted_sweep_keeps_its_finished_cells_and_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let out = dir.path().join("out");
    let whole = dir.path().join("whole");
    // 24 cells, one at a time, so that many are left when the first is written.
    let grid = "optimizer.population=40,42,44,46,48,50";
    let args = |out: &Path| -> Vec<String> {
        [
            "sweep",
            s(&scene),
            "--grid",
            grid,
            "--runs",
            "4",
            "--evaluations",
            "300",
            "--cpu",
            "--jobs",
            "1",
            "--out",
            s(out),
        ]
        .map(str::to_owned)
        .to_vec()
    };
    let interrupted: Vec<String> = args(&out);
    let interrupted: Vec<&str> = interrupted.iter().map(String::as_str).collect();
    let output = interrupt_when(&interrupted, &out.join("cells/0000"), || {});
    assert!(!output.status.success(), "an interrupted sweep fails");
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(
        stderr.contains("interrupted") && stderr.contains("again"),
        "{stderr}"
    );
    let cells = fs::read_dir(out.join("cells")).unwrap().count();
    assert!((1..24).contains(&cells), "{cells} cells");
    // The tables hold exactly the finished cells.
    assert_eq!(sweep_rows_without_seconds(&out).len(), cells + 1);

    ok(&interrupted);
    let uninterrupted: Vec<String> = args(&whole);
    ok(&uninterrupted.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(
        sweep_rows_without_seconds(&out),
        sweep_rows_without_seconds(&whole)
    );
    assert_eq!(genomes(&out), genomes(&whole));
    // The plots are drawn from the finished cells alone, whichever process ran them.
    for plot in [
        "final-optimizer.population.png",
        "final-optimizer.population.svg",
        "curves.png",
        "curves.svg",
    ] {
        assert_eq!(
            fs::read(out.join(plot)).unwrap(),
            fs::read(whole.join(plot)).unwrap(),
            "{plot}"
        );
    }
}

#[test]
fn a_known_optimum_gives_each_point_its_gaps_and_times() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube_ship_scene(dir.path());
    let out = dir.path().join("out");
    ok(&[
        "sweep",
        s(&scene),
        "--grid",
        "optimizer.population=40,60",
        "--runs",
        "2",
        "--evaluations",
        "300",
        "--set",
        "fitness.optimum=100",
        "--cpu",
        "--out",
        s(&out),
    ]);
    let plan: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    assert_eq!(plan["optimum"], 100.0);
    let targets = fs::read_to_string(out.join("targets.csv")).unwrap();
    let lines: Vec<&str> = targets.lines().collect();
    assert_eq!(lines.len(), 1 + 2 * 3, "{targets}");
    assert!(lines[0].starts_with("point,fraction,level,runs,reached,"));
    assert!(
        lines[1].starts_with("optimizer.population=40,0.9,90,2,"),
        "{targets}"
    );
    for plot in ["gap-time.png", "gap-evaluations.png"] {
        let names = ["optimizer.population=40", "optimizer.population=60"];
        chart(&out, plot, (800, 500), &names);
    }
    // Every grid point is measured against one optimum.
    let err = fails(&[
        "sweep",
        s(&scene),
        "--grid",
        "fitness.optimum=50,100",
        "--runs",
        "1",
        "--evaluations",
        "100",
        "--cpu",
        "--out",
        s(&dir.path().join("two")),
    ]);
    assert!(err.contains("fitness.optimum"), "{err}");
}
