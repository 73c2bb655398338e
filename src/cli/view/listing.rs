//! The folder's files as the page sees them: which kind of output folder it is, and the
//! files under it that the page shows.

use std::path::Path;

use serde::Serialize;

/// Deepest folder level listed: `runs/ga-0/best.glb` (compare) and
/// `cells/0001/fitness.csv` (sweep) are at level 3.
const MAX_DEPTH: usize = 3;
/// Most files listed.
const MAX_FILES: usize = 5000;

/// `/list`: the folder's files, relative, `/`-separated, sorted.
#[derive(Debug, Serialize, PartialEq, Eq)]
pub struct Listing {
    /// Relative paths of the regular files (symbolic links and hidden or temporary
    /// files left out), at most 5,000.
    pub files: Vec<String>,
    /// Whether files were left out because there were more than 5,000.
    pub truncated: bool,
}

/// The files of `root`, down to 3 levels (`runs/ga-0/best.glb`); an unreadable folder lists as
/// empty.
pub fn listing(root: &Path) -> Listing {
    let mut files = Vec::new();
    let mut truncated = false;
    walk(root, "", 1, &mut files, &mut truncated);
    files.sort();
    Listing { files, truncated }
}

fn walk(dir: &Path, prefix: &str, depth: usize, files: &mut Vec<String>, truncated: &mut bool) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if name.starts_with('.') || name.ends_with(".tmp") {
            continue;
        }
        // `file_type` does not follow symbolic links: they are left out.
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        let rel = format!("{prefix}{name}");
        if kind.is_file() {
            if files.len() == MAX_FILES {
                *truncated = true;
                return;
            }
            files.push(rel);
        } else if kind.is_dir() && depth < MAX_DEPTH {
            walk(
                &entry.path(),
                &format!("{rel}/"),
                depth + 1,
                files,
                truncated,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_files_not_links_hidden_or_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir_all(root.join("runs/ga-0/deeper")).unwrap();
        for f in [
            "summary.json",
            "runs/ga-0/best.glb",
            "runs/ga-0/deeper/x",
            ".lock",
            "best.glb.tmp",
        ] {
            std::fs::write(root.join(f), b"x").unwrap();
        }
        #[cfg(unix)]
        std::os::unix::fs::symlink(root.join("summary.json"), root.join("link.json")).unwrap();
        let listed = listing(root);
        assert_eq!(listed.files, ["runs/ga-0/best.glb", "summary.json"]);
        assert!(!listed.truncated);
        assert_eq!(listing(&root.join("missing")).files.len(), 0);
    }
}
