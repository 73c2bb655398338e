//! Output folders: one command at a time in each, and never two runs' outputs mixed.
//!
//! `run`, `compare` and `sweep` [claim](Folder::claim) their output folder before they
//! write anything in it, and hold it until they end:
//! - **the lock**: `shapegen.lock` in the folder, locked with `flock` and holding the
//!   holder's pid, host and command line. A second command for the same folder is
//!   refused with the holder named. The kernel lets go of the lock when its process
//!   ends however it ends, so a lock file left by a killed process is found unlocked,
//!   said so and taken over. The file is removed when the command ends (returning, failing
//!   or interrupted by SIGINT, SIGTERM or SIGHUP).
//! - **the outputs**: a folder that holds another command's outputs, that is a run's
//!   `checkpoint.json` or `summary.json`, a comparison's `summary.json` or
//!   `compare.csv`, or a study's `plan.json`, is refused unless the command goes on
//!   with them (`run --resume DIR`; a sweep whose plan is the one there) or is told to
//!   replace them (`--force`: every file and folder the commands write there is removed
//!   first, and listed). Other files in the folder are left alone.
//! - **leftovers**: temporary files (`*.tmp`) left by a killed process are removed once
//!   the folder is held.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::{Deserialize, Serialize};

/// The lock file's name in a held folder.
pub const LOCK_FILE: &str = "shapegen.lock";

/// What the commands write into their folders: file names, `prefix*suffix` patterns, and
/// folders (ending in `/`). `--force` removes what matches; the markers say whose
/// outputs a folder holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `shapegen run`, single- or multi-objective.
    Run,
    /// `shapegen compare`.
    Compare,
    /// `shapegen sweep`.
    Sweep,
}

impl Kind {
    const ALL: [Kind; 3] = [Kind::Run, Kind::Compare, Kind::Sweep];

    /// The file whose presence means the folder holds this command's outputs: the
    /// first it writes.
    fn marker(self) -> &'static str {
        match self {
            Kind::Run => "checkpoint.json",
            Kind::Compare => "compare.csv",
            Kind::Sweep => "plan.json",
        }
    }

    /// Everything the command writes.
    fn written(self) -> &'static [&'static str] {
        match self {
            Kind::Run => &[
                "checkpoint.json",
                "summary.json",
                "best.obj",
                "best.mtl",
                "best.glb",
                "best.png",
                "best.genome.json",
                "overlay.png",
                "fitness.csv",
                "fitness.png",
                "fitness.svg",
                "front/",
                "front.csv",
                "front.genomes.json",
                "contact_sheet.png",
                "scatter_*.png",
                "scatter_*.svg",
                "overlay_*.png",
                "history.csv",
                "run.json",
                "target.obj",
                "target.png",
                "camera.json",
                "report.html",
            ],
            Kind::Compare => &[
                "summary.json",
                "compare.csv",
                "compare.png",
                "compare.svg",
                "targets.csv",
                "gap-*.png",
                "gap-*.svg",
                "runs/",
                "report.html",
            ],
            Kind::Sweep => &[
                "plan.json",
                "sweep.sbatch",
                "cells/",
                "logs/",
                "sweep.csv",
                "summary.md",
                "final-*.png",
                "final-*.svg",
                "curves.png",
                "report.html",
                "curves.svg",
                "targets.csv",
                "gap-*.png",
                "gap-*.svg",
            ],
        }
    }

    /// The command in words.
    fn what(self) -> &'static str {
        match self {
            Kind::Run => "a run",
            Kind::Compare => "a comparison",
            Kind::Sweep => "a study",
        }
    }
}

/// The outputs a folder holds: whose, by the files that mark them.
struct Found {
    /// The commands whose marker is there, or, when only a `summary.json` is, those
    /// that write one.
    kinds: Vec<Kind>,
    /// The marker files there.
    markers: Vec<&'static str>,
}

impl Found {
    /// What `dir` holds.
    fn in_folder(dir: &Path) -> Found {
        let mut kinds: Vec<Kind> = Kind::ALL
            .into_iter()
            .filter(|k| dir.join(k.marker()).exists())
            .collect();
        let mut markers: Vec<&str> = kinds.iter().map(|k| k.marker()).collect();
        if dir.join(SUMMARY).exists() {
            markers.push(SUMMARY);
            if kinds.is_empty() {
                kinds = vec![Kind::Run, Kind::Compare];
            }
        }
        Found { kinds, markers }
    }

    /// Whose outputs, in words: "a run", "a run and a study", "a run or a comparison".
    fn what(&self) -> String {
        let whats: Vec<&str> = self.kinds.iter().map(|k| k.what()).collect();
        match self.kinds.as_slice() {
            [Kind::Run, Kind::Compare] if self.markers == [SUMMARY] => whats.join(" or "),
            _ => whats.join(" and "),
        }
    }
}

/// The summary a run and a comparison both write last.
const SUMMARY: &str = "summary.json";

/// What a command does with outputs already in its folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Existing {
    /// Refuse any (a new run).
    Refuse,
    /// Go on with its own kind's (`--resume`, a sweep's same plan); refuse others'.
    GoOn,
    /// Remove every command's outputs first (`--force`).
    Replace,
}

impl Existing {
    /// From the flags: `--force` replaces, otherwise `go_on` says whether the command
    /// continues what is there.
    pub fn from_flags(force: bool, go_on: bool) -> Existing {
        match (force, go_on) {
            (true, _) => Existing::Replace,
            (false, true) => Existing::GoOn,
            (false, false) => Existing::Refuse,
        }
    }
}

/// Who holds a folder: what `shapegen.lock` says.
#[derive(Debug, Serialize, Deserialize)]
struct Holder {
    pid: u32,
    host: String,
    command: String,
}

impl Holder {
    /// This process.
    fn me() -> Holder {
        let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
            .map(|h| h.trim().to_owned())
            .unwrap_or_else(|_| "unknown".to_owned());
        let command = std::env::args()
            .map(|a| {
                if a.is_empty() || a.contains(|c: char| c.is_whitespace() || c == '\'') {
                    format!("'{}'", a.replace('\'', r"'\''"))
                } else {
                    a
                }
            })
            .collect::<Vec<_>>()
            .join(" ");
        Holder {
            pid: std::process::id(),
            host,
            command,
        }
    }

    /// In words: `pid 12 on host h: shapegen run ..`.
    fn describe(&self) -> String {
        format!("pid {} on host {}: `{}`", self.pid, self.host, self.command)
    }
}

/// An output folder held by this process; the lock goes when it is dropped.
#[derive(Debug)]
pub struct Folder {
    lock: PathBuf,
    /// The locked file; closing it lets go of the lock.
    _file: File,
}

impl Folder {
    /// Creates `dir` if missing, locks it for this process, removes leftover temporary
    /// files, and handles the outputs there as `existing` says for a command writing
    /// `outputs`.
    ///
    /// # Errors
    /// When the folder cannot be created or locked, another process holds it, or it holds
    /// outputs `existing` refuses (the error says what they are and which flag would
    /// take them).
    pub fn claim(dir: &Path, outputs: Kind, existing: Existing) -> anyhow::Result<Folder> {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create `{}`", dir.display()))?;
        let folder = Folder::lock(dir)?;
        remove_leftovers(dir)?;
        let found = Found::in_folder(dir);
        match existing {
            _ if found.markers.is_empty() => {}
            Existing::GoOn if found.kinds == [outputs] => {}
            Existing::Replace => {
                let removed = remove_outputs(dir)?;
                eprintln!(
                    "--force: replacing {} in `{}`: removed {}",
                    found.what(),
                    dir.display(),
                    removed.join(", ")
                );
            }
            Existing::GoOn | Existing::Refuse => {
                let go_on = if outputs == Kind::Run && found.kinds == [Kind::Run] {
                    format!("--resume {} to go on with it, ", dir.display())
                } else {
                    String::new()
                };
                anyhow::bail!(
                    "`{}` holds the outputs of {} ({}): give {go_on}--force to replace them, \
                     or another folder",
                    dir.display(),
                    found.what(),
                    found.markers.join(", ")
                );
            }
        }
        Ok(folder)
    }

    /// Takes `dir`'s lock, or says who holds it.
    fn lock(dir: &Path) -> anyhow::Result<Folder> {
        let path = dir.join(LOCK_FILE);
        let cannot = || format!("cannot lock `{}`", path.display());
        // Another process may remove the file between our open and our lock (it ended);
        // the lock then holds a file no longer there, and is taken again.
        loop {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(|err| unwritable(dir, err))
                .with_context(cannot)?;
            match file.try_lock() {
                Ok(()) => {}
                Err(TryLockError::WouldBlock) => {
                    let holder = read_holder(&mut file)
                        .map_or_else(|| "another process".to_owned(), |h| h.describe());
                    anyhow::bail!(
                        "`{}` is in use by {holder}; wait for it to end, or write elsewhere",
                        dir.display()
                    );
                }
                Err(TryLockError::Error(err)) => return Err(err).with_context(cannot),
            }
            let same = std::fs::metadata(&path)
                .is_ok_and(|m| file.metadata().is_ok_and(|f| f.ino() == m.ino()));
            if !same {
                continue;
            }
            if let Some(holder) = read_holder(&mut file) {
                eprintln!(
                    "taking over `{}` from {}, which ended without letting go of it",
                    dir.display(),
                    holder.describe()
                );
            }
            let me = serde_json::to_string(&Holder::me())?;
            file.set_len(0).with_context(cannot)?;
            file.rewind().with_context(cannot)?;
            file.write_all(me.as_bytes()).with_context(cannot)?;
            return Ok(Folder {
                lock: path,
                _file: file,
            });
        }
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        // Removed before the file closes, so that no process finds it unlocked meanwhile.
        let _ = std::fs::remove_file(&self.lock);
    }
}

/// `err`, from creating a file in `dir`, with what to do added when the folder cannot
/// be written (permissions, a read-only file system).
fn unwritable(dir: &Path, err: std::io::Error) -> anyhow::Error {
    use std::io::ErrorKind::{PermissionDenied, ReadOnlyFilesystem};
    match err.kind() {
        PermissionDenied | ReadOnlyFilesystem => anyhow::Error::new(err).context(format!(
            "`{}` is not writable: give a folder this user can write in (nothing in it was \
             changed)",
            dir.display()
        )),
        _ => err.into(),
    }
}

/// The holder named in an open lock file, if it names one.
fn read_holder(file: &mut File) -> Option<Holder> {
    let mut text = String::new();
    file.rewind().ok()?;
    file.read_to_string(&mut text).ok()?;
    serde_json::from_str(&text).ok()
}

/// Whether `name` matches `pattern`: a name, or `prefix*suffix`.
fn matches(pattern: &str, name: &str) -> bool {
    match pattern.split_once('*') {
        Some((prefix, suffix)) => {
            name.len() >= prefix.len() + suffix.len()
                && name.starts_with(prefix)
                && name.ends_with(suffix)
        }
        None => name == pattern,
    }
}

/// Removes the temporary files a killed process left in `dir` (and in its `front/`).
fn remove_leftovers(dir: &Path) -> anyhow::Result<()> {
    for folder in [dir.to_owned(), dir.join("front")] {
        let Ok(entries) = std::fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_file() && matches("*.tmp", &entry.file_name().to_string_lossy()) {
                std::fs::remove_file(&path)
                    .with_context(|| format!("cannot remove `{}`", path.display()))?;
            }
        }
    }
    Ok(())
}

/// Removes every command's outputs from `dir`; returns their names, sorted.
fn remove_outputs(dir: &Path) -> anyhow::Result<Vec<String>> {
    let mut removed = Vec::new();
    for entry in
        std::fs::read_dir(dir).with_context(|| format!("cannot read `{}`", dir.display()))?
    {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_dir = entry.file_type()?.is_dir();
        let written =
            Kind::ALL
                .iter()
                .flat_map(|o| o.written())
                .any(|p| match p.strip_suffix('/') {
                    Some(folder) => is_dir && folder == name,
                    None => !is_dir && matches(p, &name),
                });
        if !written {
            continue;
        }
        let path = entry.path();
        if is_dir {
            std::fs::remove_dir_all(&path)
        } else {
            std::fs::remove_file(&path)
        }
        .with_context(|| format!("cannot remove `{}`", path.display()))?;
        removed.push(if is_dir { format!("{name}/") } else { name });
    }
    removed.sort();
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_match_names_and_wildcards() {
        assert!(matches("summary.json", "summary.json"));
        assert!(!matches("summary.json", "summary.md"));
        assert!(matches("scatter_*.png", "scatter_top_front.png"));
        assert!(!matches("scatter_*.png", "scatter_.pn"));
        assert!(matches("*.tmp", "best.obj.tmp"));
    }

    #[test]
    fn a_held_folder_is_refused_and_free_again_when_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let held = Folder::claim(dir.path(), Kind::Run, Existing::Refuse).unwrap();
        let err = Folder::claim(dir.path(), Kind::Run, Existing::Refuse).unwrap_err();
        let err = format!("{err:#}");
        assert!(
            err.contains(&format!("pid {}", std::process::id())) && err.contains("in use"),
            "{err}"
        );
        drop(held);
        assert!(!dir.path().join(LOCK_FILE).exists());
        Folder::claim(dir.path(), Kind::Run, Existing::Refuse).unwrap();
    }

    #[test]
    fn outputs_are_refused_kept_or_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::write(d.join("checkpoint.json"), "{}").unwrap();
        std::fs::write(d.join("best.obj"), "").unwrap();
        std::fs::write(d.join("best.obj.tmp"), "").unwrap();
        std::fs::write(d.join("notes.txt"), "mine").unwrap();
        std::fs::create_dir(d.join("front")).unwrap();
        let err = Folder::claim(d, Kind::Run, Existing::Refuse).unwrap_err();
        let err = format!("{err:#}");
        assert!(
            err.contains("a run (checkpoint.json)") && err.contains("--resume"),
            "{err}"
        );
        assert!(!d.join("best.obj.tmp").exists(), "leftovers go");
        let err = Folder::claim(d, Kind::Sweep, Existing::GoOn).unwrap_err();
        assert!(format!("{err:#}").contains("a run"), "{err:#}");
        drop(Folder::claim(d, Kind::Run, Existing::GoOn).unwrap());
        drop(Folder::claim(d, Kind::Sweep, Existing::Replace).unwrap());
        let mut left: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, ["notes.txt"]);
    }
}
