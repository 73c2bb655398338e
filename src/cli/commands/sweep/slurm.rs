//! A study as a Slurm job array: `DIR/sweep.sbatch`, written by `--plan-only`.
//!
//! Task `I` of the array runs `shapegen sweep --cell DIR I` (cell `I` of the plan, skipped
//! when done) with the running binary's absolute path, and as many worker threads as the
//! task has CPUs; logs go to `DIR/logs/`. The array's lowest task first submits the job
//! that collects the study, `shapegen sweep --collect DIR`, to start once every task of
//! the array has ended, whatever their outcome; its job id is written to
//! `DIR/logs/collect.jobid`. A user types one command, `sbatch DIR/sweep.sbatch`.

use std::fmt::Write as _;
use std::path::Path;

use clap::Args;

/// The job name of the array's tasks.
pub const ARRAY_NAME: &str = "shapegen-sweep";
/// The job name of the collecting job.
pub const COLLECT_NAME: &str = "shapegen-collect";

/// The resources of the job array, as `sbatch` options.
#[derive(Debug, Args)]
pub struct SlurmArgs {
    /// With --plan-only: the partition the jobs run in (sbatch --partition).
    #[arg(long, requires = "plan_only")]
    partition: Option<String>,
    /// With --plan-only: each task's time limit, as sbatch takes it (e.g. 30, 1:00:00,
    /// 1-0); the collecting job gets the same.
    #[arg(long, requires = "plan_only")]
    time: Option<String>,
    /// With --plan-only: CPUs of each task; its run uses as many worker threads
    /// (default: Slurm's, 1).
    #[arg(long, requires = "plan_only", value_name = "N")]
    cpus_per_task: Option<u32>,
    /// With --plan-only: memory of each task, as sbatch takes it (e.g. 2G).
    #[arg(long, requires = "plan_only")]
    mem: Option<String>,
    /// With --plan-only: at most this many tasks run at once (the array's `%N`).
    #[arg(long, requires = "plan_only", value_name = "N")]
    max_running: Option<u32>,
    /// With --plan-only: any other sbatch option for the tasks and the collecting job,
    /// e.g. `--sbatch-option=--account=proj42`; repeatable.
    #[arg(
        long = "sbatch-option",
        requires = "plan_only",
        value_name = "OPTION",
        allow_hyphen_values = true
    )]
    options: Vec<String>,
}

impl SlurmArgs {
    /// Checks the options: numbers at least 1, no line breaks.
    pub fn check(&self) -> anyhow::Result<()> {
        for (flag, n) in [
            ("--cpus-per-task", self.cpus_per_task),
            ("--max-running", self.max_running),
        ] {
            anyhow::ensure!(n != Some(0), "{flag} 0: give at least 1");
        }
        let texts = [
            ("--partition", self.partition.as_deref()),
            ("--time", self.time.as_deref()),
            ("--mem", self.mem.as_deref()),
        ];
        let options = self
            .options
            .iter()
            .map(|o| ("--sbatch-option", Some(o.as_str())));
        for (flag, text) in texts.into_iter().chain(options) {
            if let Some(text) = text {
                anyhow::ensure!(
                    !text.trim().is_empty() && !text.contains(['\n', '\r']),
                    "{flag} {text:?}: give one line of text"
                );
            }
        }
        for option in &self.options {
            anyhow::ensure!(
                option.starts_with('-'),
                "--sbatch-option {option}: give an sbatch option with its dashes, e.g. \
                 --sbatch-option=--account=proj42"
            );
        }
        Ok(())
    }

    /// The text of `sweep.sbatch` for a study of `cells` cells in folder `dir` (absolute),
    /// run by the binary `exe` (absolute).
    pub fn script(&self, cells: u64, dir: &Path, exe: &Path) -> String {
        let (dir_text, exe_text) = (dir.display().to_string(), exe.display().to_string());
        let logs = format!("{dir_text}/logs");
        let mut s = String::from("#!/bin/bash\n");
        let _ = writeln!(
            s,
            "# A shapegen sweep as a Slurm job array, written by `shapegen sweep --plan-only`."
        );
        let _ = writeln!(
            s,
            "# Submit it with:  sbatch {}",
            shell_quote(&format!("{dir_text}/sweep.sbatch"))
        );
        let _ = writeln!(
            s,
            "# Task I runs cell I of plan.json ({cells} cells; a finished one is skipped). The"
        );
        let _ = writeln!(
            s,
            "# lowest task submits the job that collects the tables and plots once every task"
        );
        let _ = writeln!(s, "# has ended. Logs: {logs}/.");
        for option in self.task_options(cells, &logs) {
            let _ = writeln!(s, "#SBATCH {option}");
        }
        s.push_str("set -euo pipefail\n");
        s.push_str("if [ \"$SLURM_ARRAY_TASK_ID\" = \"$SLURM_ARRAY_TASK_MIN\" ]; then\n");
        let _ = writeln!(
            s,
            "    sbatch {} > {}",
            self.collect_options(&dir_text, &exe_text, &logs).join(" "),
            shell_quote(&format!("{logs}/collect.jobid"))
        );
        s.push_str("fi\n");
        let _ = writeln!(
            s,
            "exec {} --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" sweep --cell {} \"$SLURM_ARRAY_TASK_ID\"",
            shell_quote(&exe_text),
            shell_quote(&dir_text)
        );
        s
    }

    /// The sbatch options both kinds of job take: partition, time and the user's own.
    fn shared_options(&self) -> Vec<String> {
        let mut shared = Vec::new();
        if let Some(p) = &self.partition {
            shared.push(format!("--partition={p}"));
        }
        if let Some(t) = &self.time {
            shared.push(format!("--time={t}"));
        }
        shared.extend(self.options.iter().cloned());
        shared
    }

    /// The `#SBATCH` options of the array of `cells` tasks, logging into `logs`.
    fn task_options(&self, cells: u64, logs: &str) -> Vec<String> {
        let mut array = format!("0-{}", cells.saturating_sub(1));
        if let Some(n) = self.max_running {
            let _ = write!(array, "%{n}");
        }
        let mut task = vec![
            format!("--job-name={ARRAY_NAME}"),
            format!("--array={array}"),
            format!("--output={}", directive_path(&format!("{logs}/%A_%a.out"))),
        ];
        if let Some(c) = self.cpus_per_task {
            task.push(format!("--cpus-per-task={c}"));
        }
        if let Some(m) = &self.mem {
            task.push(format!("--mem={m}"));
        }
        task.extend(self.shared_options());
        task
    }

    /// The arguments of the `sbatch` that submits the collecting job, which runs `exe`
    /// on `dir` once the array has ended, logging into `logs`: each a shell word.
    fn collect_options(&self, dir: &str, exe: &str, logs: &str) -> Vec<String> {
        let collect_command = format!("{} sweep --collect {}", shell_quote(exe), shell_quote(dir));
        let mut collect = vec![
            "--parsable".to_owned(),
            format!("--job-name={COLLECT_NAME}"),
            "--dependency=afterany:\"$SLURM_ARRAY_JOB_ID\"".to_owned(),
            format!(
                "--output={}",
                shell_quote(&format!("{logs}/collect-%j.out"))
            ),
        ];
        collect.extend(self.shared_options().iter().map(|o| shell_quote(o)));
        collect.push(format!("--wrap={}", shell_quote(&collect_command)));
        collect
    }
}

/// `text` as one word of a POSIX shell: bare when it holds only safe characters,
/// single-quoted otherwise.
fn shell_quote(text: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "@%+=:,./_-".contains(c);
    if !text.is_empty() && text.chars().all(safe) {
        text.to_owned()
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}

/// A path in an `#SBATCH` line, which sbatch splits at spaces unless quoted.
fn directive_path(path: &str) -> String {
    if path.contains(char::is_whitespace) {
        format!("\"{path}\"")
    } else {
        path.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(max_running: Option<u32>, options: &[&str]) -> SlurmArgs {
        SlurmArgs {
            partition: Some("short".into()),
            time: Some("0:10:00".into()),
            cpus_per_task: Some(2),
            mem: Some("1G".into()),
            max_running,
            options: options.iter().map(|o| (*o).to_owned()).collect(),
        }
    }

    #[test]
    fn the_script_is_an_array_over_the_cells_with_its_resources() {
        let s = args(Some(3), &["--account=p1"]).script(
            12,
            Path::new("/data/study one"),
            Path::new("/opt/shapegen"),
        );
        for line in [
            "#SBATCH --array=0-11%3",
            "#SBATCH --output=\"/data/study one/logs/%A_%a.out\"",
            "#SBATCH --partition=short",
            "#SBATCH --time=0:10:00",
            "#SBATCH --cpus-per-task=2",
            "#SBATCH --mem=1G",
            "#SBATCH --account=p1",
            "exec /opt/shapegen --threads \"${SLURM_CPUS_PER_TASK:-1}\" sweep --cell \
             '/data/study one' \"$SLURM_ARRAY_TASK_ID\"",
        ] {
            assert!(s.lines().any(|l| l == line), "no line {line:?} in\n{s}");
        }
        // Every directive comes before the first command, or sbatch ignores it.
        let lines: Vec<&str> = s.lines().collect();
        let first_command = lines
            .iter()
            .position(|l| *l == "set -euo pipefail")
            .unwrap();
        let last_directive = lines
            .iter()
            .rposition(|l| l.starts_with("#SBATCH"))
            .unwrap();
        assert!(last_directive < first_command);
        // The collecting job waits for the whole array, with the shared options only.
        let submit = s.lines().find(|l| l.contains("--wrap=")).unwrap();
        assert!(submit.contains("--dependency=afterany:\"$SLURM_ARRAY_JOB_ID\""));
        assert!(submit.contains("--partition=short --time=0:10:00 --account=p1"));
        assert!(!submit.contains("--mem") && !submit.contains("--cpus-per-task"));
        assert!(
            submit.contains(r"--wrap='/opt/shapegen sweep --collect '\''/data/study one'\'''"),
            "{submit}"
        );
    }

    #[test]
    fn quoting_keeps_words_whole() {
        assert_eq!(shell_quote("/a/b-c_d.e"), "/a/b-c_d.e");
        assert_eq!(shell_quote("a b"), "'a b'");
        assert_eq!(shell_quote("it's"), r"'it'\''s'");
        assert_eq!(shell_quote(""), "''");
    }

    #[test]
    fn bad_options_are_named() {
        assert!(
            args(Some(0), &[])
                .check()
                .unwrap_err()
                .to_string()
                .contains("--max-running")
        );
        let err = args(None, &["account=p1"]).check().unwrap_err().to_string();
        assert!(err.contains("with its dashes"), "{err}");
        assert!(args(None, &["--a\n--b"]).check().is_err());
        assert!(args(None, &["--account=p1"]).check().is_ok());
    }
}
