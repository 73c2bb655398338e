//! `mpirun -n P shapegen run SCENE --islands K` end to end, under its own harness: the
//! same run on 1, 2 and 4 processes, a stop on one rank stopping every rank, resuming on
//! another number of processes, and islands the processes cannot share. The tests need
//! a build with the `mpi` feature and OpenMPI's `mpirun`; without them they are reported
//! as ignored, after a line saying why, unless `SHAPEGEN_REQUIRE_MPI=1` (as in CI's run
//! with the feature), where they fail instead.

mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Output, Stdio};
use std::time::{Duration, Instant};

use libtest_mimic::{Arguments, Failed, Trial};
use support::slurm::{PATIENCE, output_in, probe, read_logs, wait_for};
use support::{ok, s, skyline_scene, timeless_curve, timeless_summary};

/// What a test needs that a machine may lack.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Needs {
    /// The `mpi` feature and `mpirun`.
    Mpi,
    /// Those and a Slurm cluster.
    MpiAndSlurm,
}

/// The tests of this file: name, needs and body, which panics when the test fails.
const TESTS: &[(&str, Needs, fn())] = &[
    (
        "island_runs_are_the_same_on_one_two_and_four_processes",
        Needs::Mpi,
        island_runs_are_the_same_on_one_two_and_four_processes,
    ),
    (
        "a_stop_on_one_rank_stops_every_rank_and_the_run_resumes_on_others",
        Needs::Mpi,
        a_stop_on_one_rank_stops_every_rank_and_the_run_resumes_on_others,
    ),
    (
        "islands_the_processes_cannot_share_are_refused",
        Needs::Mpi,
        islands_the_processes_cannot_share_are_refused,
    ),
    (
        "island_runs_under_slurm_equal_one_process",
        Needs::MpiAndSlurm,
        island_runs_under_slurm_equal_one_process,
    ),
];

/// Why MPI runs cannot be tested here, if they cannot.
fn mpi_missing() -> Option<String> {
    if !cfg!(feature = "mpi") {
        return Some(
            "the binary is built without the `mpi` feature (cargo test --features mpi)".into(),
        );
    }
    Command::new("mpirun")
        .arg("--version")
        .output()
        .err()
        .map(|err| format!("`mpirun` does not run ({err}); install openmpi-bin"))
}

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let require = |var: &str| std::env::var(var).as_deref() == Ok("1");
    // Each missing piece, whether a variable makes it a failure, and that variable.
    let mpi =
        mpi_missing().map(|why| (why, require("SHAPEGEN_REQUIRE_MPI"), "SHAPEGEN_REQUIRE_MPI"));
    let slurm = probe().err().map(|why| {
        (
            why,
            require("SHAPEGEN_REQUIRE_SLURM"),
            "SHAPEGEN_REQUIRE_SLURM",
        )
    });
    for (why, required, var) in mpi.iter().chain(&slurm) {
        match required {
            true => eprintln!("{why}; {var}=1, so the tests that need it fail"),
            false => eprintln!("{why}; the tests that need it are ignored"),
        }
    }
    let trials = TESTS
        .iter()
        .map(|&(name, needs, test)| {
            let missing = match needs {
                Needs::Mpi => mpi.as_ref(),
                Needs::MpiAndSlurm => mpi.as_ref().or(slurm.as_ref()),
            };
            match missing {
                None => Trial::test(name, move || {
                    test();
                    Ok(())
                }),
                Some((why, required, _)) => {
                    let why = why.clone();
                    Trial::test(name, move || Err(Failed::from(why))).with_ignored_flag(!required)
                }
            }
        })
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}

/// `mpirun -n processes shapegen args`, as root too, more processes than cores allowed,
/// each process on one worker thread.
fn mpirun(processes: usize, args: &[&str]) -> Command {
    let mut command = Command::new("mpirun");
    command
        .args(["--allow-run-as-root", "--oversubscribe", "-n"])
        .arg(processes.to_string())
        .arg(env!("CARGO_BIN_EXE_shapegen"))
        .args(["--threads", "1"])
        .args(args);
    command
}

/// Runs `command`, which must succeed.
fn succeeds(mut command: Command) -> Output {
    let out = command.output().expect("mpirun runs");
    assert!(
        out.status.success(),
        "{command:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// What two runs must share to be the same run: the summary without its wall time and
/// process count, the fitness curve without its times, and the best genome.
fn outcome(dir: &Path) -> (serde_json::Value, Vec<String>, String) {
    let mut summary = timeless_summary(dir);
    summary.as_object_mut().unwrap().remove("processes");
    let genome = std::fs::read_to_string(dir.join("best.genome.json")).unwrap();
    (summary, timeless_curve(dir), genome)
}

/// The summary's process count.
fn processes(dir: &Path) -> u64 {
    timeless_summary(dir)["processes"].as_u64().unwrap()
}

fn island_runs_are_the_same_on_one_two_and_four_processes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let run = [
        "run",
        s(&scene),
        "--cpu",
        "--islands",
        "4",
        "--set",
        "islands.interval=3",
    ];
    let alone = dir.path().join("alone");
    ok(&[&run[..], &["--out", s(&alone)]].concat());
    assert_eq!(processes(&alone), 1);
    for n in [2, 4] {
        let out = dir.path().join(format!("on{n}"));
        let printed = succeeds(mpirun(n, &[&run[..], &["--out", s(&out)]].concat()));
        assert_eq!(processes(&out), n as u64);
        assert_eq!(outcome(&out), outcome(&alone), "{n} processes");
        // Rank 0 alone prints the result.
        let stdout = String::from_utf8_lossy(&printed.stdout);
        assert_eq!(stdout.matches("best fitness").count(), 1, "{stdout}");
    }
}

/// The process ids of the ranks `mpirun` started for a run writing to `out`, by rank.
fn ranks_writing_to(out: &Path) -> Vec<(u32, u32)> {
    let mut ranks = Vec::new();
    for entry in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let read = |file: &str| std::fs::read(entry.path().join(file)).unwrap_or_default();
        let cmdline = String::from_utf8_lossy(&read("cmdline")).replace('\0', " ");
        if !cmdline.starts_with(env!("CARGO_BIN_EXE_shapegen")) || !cmdline.contains(s(out)) {
            continue;
        }
        let environ = String::from_utf8_lossy(&read("environ")).into_owned();
        if let Some(rank) = environ
            .split('\0')
            .find_map(|v| v.strip_prefix("OMPI_COMM_WORLD_RANK="))
        {
            ranks.push((rank.parse().unwrap(), pid));
        }
    }
    ranks.sort();
    ranks
}

fn a_stop_on_one_rank_stops_every_rank_and_the_run_resumes_on_others() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let out = dir.path().join("stopped");
    let run = [
        "run",
        s(&scene),
        "--cpu",
        "--islands",
        "4",
        "--set",
        "islands.interval=2",
    ];
    let mut command = mpirun(
        2,
        &[&run[..], &["--generations", "100000", "--out", s(&out)]].concat(),
    );
    let child = command
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mpirun runs");
    // Once the run has saved, Ctrl-C on rank 1 alone.
    let start = Instant::now();
    let rank_one = loop {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "the run did not start"
        );
        let ranks = ranks_writing_to(&out);
        if out.join("checkpoint.json").exists() && ranks.len() == 2 {
            break ranks[1].1;
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(
        Command::new("kill")
            .args(["-INT", &rank_one.to_string()])
            .status()
            .unwrap()
            .success()
    );
    let ended = child.wait_with_output().unwrap();
    assert!(
        ended.status.success(),
        "every rank ends cleanly: {}",
        String::from_utf8_lossy(&ended.stderr)
    );
    let stopped = timeless_summary(&out);
    assert_eq!(stopped["stopped"], "interrupted");
    let generations = stopped["generations"].as_u64().unwrap() + 3;

    // Resumed on four processes, it ends as a run that was never stopped.
    let whole = dir.path().join("whole");
    let g = generations.to_string();
    ok(&[&run[..], &["--generations", &g, "--out", s(&whole)]].concat());
    succeeds(mpirun(
        4,
        &["run", "--resume", s(&out), "--cpu", "--generations", &g],
    ));
    assert_eq!(outcome(&out), outcome(&whole));
}

fn islands_the_processes_cannot_share_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scene: PathBuf = skyline_scene(dir.path());
    let out = dir.path().join("out");
    for (args, expected) in [
        (&["--islands", "3"][..], "multiple of 2"),
        (&[][..], "give --islands K"),
    ] {
        let base = ["run", s(&scene), "--cpu", "--out", s(&out)];
        let run = mpirun(2, &[&base[..], args].concat()).output().unwrap();
        assert!(!run.status.success(), "{args:?} succeeded");
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
}

fn island_runs_under_slurm_equal_one_process() {
    let dir = tempfile::tempdir().unwrap();
    let dir = std::fs::canonicalize(dir.path()).unwrap();
    let scene = skyline_scene(&dir);
    let run = [
        "run",
        s(&scene),
        "--cpu",
        "--islands",
        "4",
        "--set",
        "islands.interval=3",
    ];
    let alone = dir.join("alone");
    ok(&[&run[..], &["--out", s(&alone)]].concat());
    let bin = env!("CARGO_BIN_EXE_shapegen");
    let logs = dir.join("logs");
    std::fs::create_dir_all(&logs).unwrap();
    let deadline = Instant::now() + PATIENCE;
    let launchers = [
        ("mpirun", "mpirun --allow-run-as-root -n 2"),
        ("srun", "srun --mpi=pmix"),
    ];
    let mut jobs = Vec::new();
    for (name, launcher) in launchers {
        let out = dir.join(name);
        let command = format!(
            "{launcher} {bin} --threads 1 {} --out {}",
            run.join(" "),
            s(&out)
        );
        let log = format!("--output={}", s(&logs.join(format!("{name}.log"))));
        let id = output_in(
            &dir,
            "sbatch",
            &["--parsable", "-n", "2", &log, "--wrap", &command],
        )
        .unwrap_or_else(|err| panic!("{err}"));
        jobs.push((name, id.trim().to_owned(), out));
    }
    for (name, id, out) in jobs {
        wait_for(&id, deadline, &logs).unwrap_or_else(|err| panic!("{err}"));
        assert!(
            out.join("summary.json").exists(),
            "the {name} job wrote no summary:\n{}",
            read_logs(&logs)
        );
        assert_eq!(processes(&out), 2, "{name}");
        assert_eq!(outcome(&out), outcome(&alone), "{name}");
    }
}
