//! A Slurm cluster from the tests: whether one is up, running its commands, waiting for
//! jobs, and their logs for failure messages.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// How long a test's jobs may take, queueing included.
pub const PATIENCE: Duration = Duration::from_secs(600);

/// The standard output of `program args`, or why it did not run or failed.
pub fn output(program: &str, args: &[&str]) -> Result<String, String> {
    output_in(Path::new("."), program, args)
}

/// The standard output of `program args` run in folder `dir`, or why it did not run or
/// failed.
pub fn output_in(dir: &Path, program: &str, args: &[&str]) -> Result<String, String> {
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
pub fn probe() -> Result<String, String> {
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
pub fn wait_for(id: &str, deadline: Instant, logs: &Path) -> Result<(), String> {
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
pub fn read_logs(logs: &Path) -> String {
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
