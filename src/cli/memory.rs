//! `--max-memory SIZE`: a run's memory, estimated before it allocates anything
//! ([`Scene::memory_estimate`]), checked against the limit given or, without one, against
//! the memory available now: `MemAvailable` of `/proc/meminfo`, or less where the
//! process's cgroup has a memory limit. A run over it is refused with the estimate, its
//! parts and the setting that drives it, rather than growing until the kernel kills it.

use std::path::{Path, PathBuf};

use clap::Args;
use shapegen::Grammar;
use shapegen::optimize::{Checkpoint, Optimizer};
use shapegen::scene::{OptimizerGoal, RunShape, Scene};

use super::backend::BackendArgs;
use super::generators::Visit;
use crate::registry::Entry;

/// The `--max-memory` flag of the commands that search.
#[derive(Clone, Copy, Debug, Default, Args)]
pub struct MemoryArgs {
    /// The most memory a run may take, e.g. 512M, 4G or 1.5T (K, M, G, T are powers of
    /// 1024; a plain number is bytes). A run whose estimate is larger is refused before
    /// it starts. Default: the memory available now (MemAvailable, or what the process's
    /// cgroup limit leaves, whichever is less).
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    max_memory: Option<u64>,
}

impl MemoryArgs {
    /// The limit in bytes, with what sets it in words (`None` when neither the flag nor
    /// the system says).
    pub fn limit(&self) -> Option<(u64, String)> {
        match self.max_memory {
            Some(n) => Some((n, "that --max-memory allows".to_owned())),
            None => available(),
        }
    }
}

/// Refuses a search of `scene` that would not fit in memory: each of `goals` (a
/// comparison's methods) run `jobs` at a time (a sweep's cells side by side), the worker
/// threads shared among them, on the backend `backend` allows.
pub struct MemoryCheck<'a> {
    /// The scene searched.
    pub scene: &'a Scene,
    /// The goals run, one at a time.
    pub goals: &'a [OptimizerGoal],
    /// Runs at once.
    pub jobs: usize,
    /// Where models are counted, and whether incrementally.
    pub backend: &'a BackendArgs,
    /// The limit given.
    pub limit: MemoryArgs,
}

impl<'a> MemoryCheck<'a> {
    /// The check of `jobs` runs at once of `scene`'s own goal.
    pub fn scene(
        scene: &'a Scene,
        jobs: usize,
        backend: &'a BackendArgs,
        limit: MemoryArgs,
    ) -> Self {
        MemoryCheck {
            scene,
            goals: std::slice::from_ref(&scene.optimizer),
            jobs,
            backend,
            limit,
        }
    }
}

/// The worker threads each of `jobs` runs at once gets: an equal share of the pool's,
/// at least one.
pub fn threads_per_job(jobs: usize) -> usize {
    (rayon::current_num_threads() / jobs.max(1)).max(1)
}

impl Visit for MemoryCheck<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let threads = threads_per_job(self.jobs);
        let (incremental, gpu) = (self.backend.incremental(), self.backend.may_use_gpu());
        for goal in self.goals {
            let shape = self.scene.run_shape::<G>(goal, threads, incremental, gpu);
            check(self.scene, &shape, self.jobs, self.limit)?;
        }
        Ok(())
    }
}

/// Refuses to resume a run of `scene` from `state`, a checkpoint of `O`, that would not
/// fit in memory: what the checkpoint's own settings and genome limits hold, which may
/// not be the scene's.
pub fn check_resumed<G: Grammar, O: Optimizer<G>>(
    scene: &Scene,
    state: &O::State,
    incremental: bool,
    gpu: bool,
    limit: MemoryArgs,
) -> anyhow::Result<()> {
    let shape = RunShape {
        graph: G::GRAPH,
        held: O::genomes_held(state.settings()),
        max_len: state.limits().max_len,
        threads: rayon::current_num_threads(),
        incremental,
        gpu,
    };
    check(scene, &shape, 1, limit)
}

/// Refuses `jobs` runs of `scene` shaped as `shape` at once over `limit`.
fn check(scene: &Scene, shape: &RunShape, jobs: usize, limit: MemoryArgs) -> anyhow::Result<()> {
    let Some((limit, source)) = limit.limit() else {
        return Ok(());
    };
    let estimate = scene.memory_estimate(shape).times(jobs);
    Ok(estimate.check(limit, &source)?)
}

/// Why a text is not a size as `--max-memory` takes it.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SizeError {
    /// Not a number, with or without a unit.
    #[error(
        "`{0}` is not a size: give a number of bytes or a number with K, M, G or T (powers \
         of 1024), e.g. 512M or 4G"
    )]
    NotASize(String),
    /// A number of bytes below one, or too large to count.
    #[error("`{0}`: give a size of at least one byte, e.g. 512M or 4G")]
    OutOfRange(String),
}

/// A size as `--max-memory` takes it: a number (a fraction allowed) and a unit K, M, G
/// or T (powers of 1024, optionally followed by `B` or `iB`, any case), or bytes.
///
/// # Errors
/// [`SizeError`], saying what is valid, for anything else or a size of 0.
pub fn parse_size(text: &str) -> Result<u64, SizeError> {
    let invalid = || SizeError::NotASize(text.to_owned());
    let t = text.trim();
    let lower = t.to_ascii_lowercase();
    let digits = lower.trim_end_matches(|c: char| c.is_ascii_alphabetic());
    let unit = &lower[digits.len()..];
    let shift = match unit.trim_end_matches("ib").trim_end_matches('b') {
        "" if unit.is_empty() || unit == "b" => 0,
        "k" => 10,
        "m" => 20,
        "g" => 30,
        "t" => 40,
        _ => return Err(invalid()),
    };
    let number: f64 = digits.trim().parse().map_err(|_| invalid())?;
    let size = number * (1u64 << shift) as f64;
    if !size.is_finite() || size < 1.0 || size >= u64::MAX as f64 {
        return Err(SizeError::OutOfRange(text.to_owned()));
    }
    Ok(size as u64)
}

/// The memory available now, with where the figure comes from: `MemAvailable`, or what
/// the process's cgroup limit leaves when that is less.
fn available() -> Option<(u64, String)> {
    let mem_available = kib_field("/proc/meminfo", "MemAvailable:").map(|bytes| {
        (
            bytes,
            "available (MemAvailable in /proc/meminfo)".to_owned(),
        )
    });
    let cgroup = cgroup_left().map(|(left, dir)| {
        (
            left,
            format!("left under the memory limit of cgroup {}", dir.display()),
        )
    });
    match (mem_available, cgroup) {
        (Some(a), Some(c)) => Some(if c.0 < a.0 { c } else { a }),
        (a, c) => a.or(c),
    }
}

/// The most memory this process has held resident so far (`VmHWM` of
/// `/proc/self/status`), in bytes; `None` where the system does not say.
pub fn peak_rss() -> Option<u64> {
    kib_field("/proc/self/status", "VmHWM:")
}

/// The value in bytes of the line of `file` that starts with `key` and gives a number of
/// kibibytes (`MemAvailable:   123 kB`).
fn kib_field(file: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The least memory left under a limit of the process's cgroup or one above it, and
/// that cgroup's folder: the limit less what is charged, page cache aside (the kernel
/// reclaims it before it refuses memory).
fn cgroup_left() -> Option<(u64, PathBuf)> {
    let read =
        |path: &Path| -> Option<u64> { std::fs::read_to_string(path).ok()?.trim().parse().ok() };
    let file_cache = |stat: &Path, key: &str| -> u64 {
        std::fs::read_to_string(stat)
            .ok()
            .and_then(|text| {
                let line = text
                    .lines()
                    .find(|l| l.split_whitespace().next() == Some(key))?;
                line.split_whitespace().nth(1)?.parse().ok()
            })
            .unwrap_or(0)
    };
    // What the cgroup of folder `dir` leaves: its limit (file `limit`) less what it is
    // charged (file `usage`) beyond its page cache (`cache` of `memory.stat`); `None`
    // without a limit.
    let left = |dir: &Path, limit: &str, usage: &str, cache: &str| -> Option<u64> {
        let (max, used) = (read(&dir.join(limit))?, read(&dir.join(usage))?);
        let cache = file_cache(&dir.join("memory.stat"), cache);
        Some(max.saturating_sub(used.saturating_sub(cache)))
    };
    let mut least: Option<(u64, PathBuf)> = None;
    let mut consider = |left: u64, dir: PathBuf| {
        if least.as_ref().is_none_or(|(l, _)| left < *l) {
            least = Some((left, dir));
        }
    };
    let own = std::fs::read_to_string("/proc/self/cgroup").unwrap_or_default();
    // cgroup v2: one line `0::/path`; the limits of every cgroup above apply too.
    if let Some(path) = own.lines().find_map(|l| l.strip_prefix("0::")) {
        let root = Path::new("/sys/fs/cgroup");
        let mut dir = root.join(path.trim_start_matches('/'));
        while dir.starts_with(root) {
            if let Some(free) = left(&dir, "memory.max", "memory.current", "file") {
                consider(free, dir.clone());
            }
            if !dir.pop() {
                break;
            }
        }
    }
    // cgroup v1: the memory controller's own hierarchy.
    let v1 = Path::new("/sys/fs/cgroup/memory");
    if let Some(free) = left(
        v1,
        "memory.limit_in_bytes",
        "memory.usage_in_bytes",
        "cache",
    ) {
        consider(free, v1.to_owned());
    }
    least
}

#[cfg(test)]
mod tests {
    use super::{available, parse_size};

    #[test]
    fn sizes_take_binary_units_in_any_case() {
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("4gib"), Ok(4 << 30));
        assert_eq!(parse_size("4GB"), Ok(4 << 30));
        assert_eq!(parse_size("1.5K"), Ok(1536));
        assert_eq!(parse_size("2T"), Ok(2 << 40));
        assert_eq!(parse_size("1000"), Ok(1000));
        assert_eq!(parse_size("1000B"), Ok(1000));
    }

    #[test]
    fn sizes_that_are_not_refused_with_what_is_valid() {
        for bad in ["", "G", "4X", "four G", "-1G", "1e400", "0", "0.1"] {
            let err = parse_size(bad).unwrap_err().to_string();
            assert!(err.contains("512M"), "{bad}: {err}");
        }
    }

    #[test]
    fn the_memory_available_is_read_on_linux() {
        if cfg!(target_os = "linux") {
            let (n, source) = available().expect("/proc/meminfo is readable");
            assert!(n > 0, "{source}");
        }
    }
}
