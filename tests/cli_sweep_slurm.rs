//! `shapegen sweep` through a real Slurm, under its own harness so that a missing Slurm
//! shows: the study's job array and its collecting job are submitted with `sbatch`, and
//! their results must equal a local sweep's. Without a Slurm controller and an idle node
//! the test is reported as ignored, after a line saying why, unless
//! `SHAPEGEN_REQUIRE_SLURM=1` (as in CI, which brings Slurm up with
//! `scripts/slurm-up.sh`), where it fails instead.

mod support;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{Duration, Instant};

use libtest_mimic::{Arguments, Failed, Trial};
use support::{cube_ship_scene, ok, s, sweep_rows_without_seconds};

/// How long the array and the collecting job may take, queueing included.
const PATIENCE: Duration = Duration::from_secs(600);

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

/// The standard output of `program args`, or why it did not run or failed.
fn output(program: &str, args: &[&str]) -> Result<String, String> {
    output_in(Path::new("."), program, args)
}

/// The standard output of `program args` run in folder `dir`, or why it did not run or
/// failed.
fn output_in(dir: &Path, program: &str, args: &[&str]) -> Result<String, String> {
    let out = Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .map_err(|err| format!("`{program}` does not run ({err})"))?;
    if !out.status.success() {
        let said: Vec<String> = [&out.stdout, &out.stderr]
            .iter()
            .flat_map(|text| {
                String::from_utf8_lossy(text)
                    .lines()
                    .map(str::to_owned)
                    .collect::<Vec<_>>()
            })
            .filter(|line| !line.trim().trim_matches('*').is_empty())
            .collect();
        let said = said.join(" ");
        return Err(format!(
            "`{program} {}` failed: {}",
            args.join(" "),
            said.trim()
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The node jobs would run on, or why there is none: the controller must answer and a
/// node be up.
fn probe() -> Result<String, String> {
    let no_slurm =
        |err: String| format!("no Slurm cluster is up (scripts/slurm-up.sh starts one): {err}");
    let ping = output("scontrol", &["ping"]).map_err(no_slurm)?;
    if !ping.contains("is UP") {
        return Err(no_slurm(format!("scontrol ping says {}", ping.trim())));
    }
    let nodes = output("sinfo", &["-h", "-o", "%n %t"]).map_err(no_slurm)?;
    nodes
        .lines()
        .find(|l| ["idle", "mix", "alloc"].iter().any(|s| l.ends_with(s)))
        .map(str::to_owned)
        .ok_or_else(|| no_slurm(format!("no node is up (sinfo: {})", nodes.trim())))
}

/// Waits until job `id` has left the queue, at most until `deadline`.
fn wait_for(id: &str, deadline: Instant, logs: &Path) -> Result<(), String> {
    loop {
        // A job that ended long ago is unknown to squeue: that is gone too.
        let queued = output("squeue", &["-h", "-j", id]).unwrap_or_default();
        if queued.trim().is_empty() {
            return Ok(());
        }
        if Instant::now() > deadline {
            return Err(format!(
                "job {id} was still queued or running after {} s:\n{}\n{}",
                PATIENCE.as_secs(),
                queued.trim(),
                read_logs(logs)
            ));
        }
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// Every file of the logs folder with its text, for a failure message.
fn read_logs(logs: &Path) -> String {
    let mut files: Vec<PathBuf> = fs::read_dir(logs)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    files.sort();
    let mut text = format!("logs in {}:", logs.display());
    for file in files {
        text.push_str(&format!(
            "\n--- {}\n{}",
            file.display(),
            fs::read_to_string(&file).unwrap_or_else(|err| format!("(unreadable: {err})"))
        ));
    }
    text
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
