//! `shapegen sweep` through a real Slurm, under its own harness so that a missing Slurm
//! shows: the study's job array and its collecting job are submitted with `sbatch`, and
//! their results must equal a local sweep's. Without a Slurm controller and an idle node
//! the test is reported as ignored, after a line saying why, unless
//! `SHAPEGEN_REQUIRE_SLURM=1` (as in CI, which brings Slurm up with
//! `scripts/slurm-up.sh`), where it fails instead.

mod support;

use std::fs;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use libtest_mimic::{Arguments, Failed, Trial};
use support::slurm::{PATIENCE, output_in, probe, read_logs, wait_for};
use support::{cube_ship_scene, ok, s, sweep_rows_without_seconds};

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let required = std::env::var("SHAPEGEN_REQUIRE_SLURM").as_deref() == Ok("1");
    let slurm = probe();
    match &slurm {
        Ok(node) => eprintln!("Slurm tests run on {node}"),
        Err(err) if required => {
            eprintln!("{err}; SHAPEGEN_REQUIRE_SLURM=1, so the Slurm tests fail")
        }
        Err(err) => eprintln!("{err}; the Slurm tests are ignored"),
    }
    let trial = match &slurm {
        Ok(_) => Trial::test("a_sweep_on_slurm_equals_the_local_sweep", || {
            a_sweep_on_slurm_equals_the_local_sweep().map_err(Failed::from)
        }),
        Err(err) => {
            let err = err.clone();
            Trial::test("a_sweep_on_slurm_equals_the_local_sweep", move || {
                Err(Failed::from(err))
            })
            .with_ignored_flag(!required)
        }
    };
    libtest_mimic::run(&args, vec![trial]).exit_code()
}

fn a_sweep_on_slurm_equals_the_local_sweep() -> Result<(), String> {
    let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
    let dir = fs::canonicalize(dir.path()).map_err(|e| e.to_string())?;
    let scene = cube_ship_scene(&dir);
    let (local, cluster) = (dir.join("local"), dir.join("cluster"));
    let study = |out: &Path, extra: &[&str]| {
        let mut args = vec![
            "sweep",
            s(&scene),
            "--grid",
            "optimizer.population=40,60",
            "--runs",
            "2",
            "--evaluations",
            "300",
            "--cpu",
        ];
        args.extend_from_slice(extra);
        args.extend(["--out", s(out)]);
        ok(&args);
    };
    study(&local, &[]);
    study(&cluster, &["--plan-only", "--time", "10"]);

    let deadline = Instant::now() + PATIENCE;
    let logs = cluster.join("logs");
    let script = cluster.join("sweep.sbatch");
    let array = output_in(&dir, "sbatch", &["--parsable", s(&script)])?;
    let array = array
        .trim()
        .split(';')
        .next()
        .unwrap_or_default()
        .to_owned();
    wait_for(&array, deadline, &logs)?;
    let collect = fs::read_to_string(logs.join("collect.jobid")).map_err(|err| {
        format!(
            "the array's first task did not submit the collecting job ({err}):\n{}",
            read_logs(&logs)
        )
    })?;
    let collect = collect
        .trim()
        .split(';')
        .next()
        .unwrap_or_default()
        .to_owned();
    wait_for(&collect, deadline, &logs)?;

    let failed = |what: String| format!("{what}\n{}", read_logs(&logs));
    if !cluster.join("sweep.csv").exists() {
        return Err(failed("the collecting job wrote no sweep.csv".into()));
    }
    let (want, got) = (
        sweep_rows_without_seconds(&local),
        sweep_rows_without_seconds(&cluster),
    );
    if got != want {
        return Err(failed(format!(
            "sweep.csv differs from the local sweep's (but for seconds):\nlocal: {want:?}\n\
             Slurm: {got:?}"
        )));
    }
    for i in 0..4 {
        let genome = |study: &Path| fs::read(study.join(format!("cells/{i:04}/best.genome.json")));
        if genome(&local).ok() != genome(&cluster).ok() {
            return Err(failed(format!("the best genomes of cell {i} differ")));
        }
    }
    for plot in ["final-optimizer.population.png", "curves.png"] {
        if !cluster.join(plot).exists() {
            return Err(failed(format!("the collecting job wrote no {plot}")));
        }
    }
    Ok(())
}
