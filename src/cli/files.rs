//! Reading and writing the commands' files: every output is written atomically.

use std::path::{Path, PathBuf};

use anyhow::Context;
use image::RgbImage;

use super::plot::Figure;

/// The text of `path`, or an error naming it.
pub fn read(path: &Path) -> anyhow::Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read `{}`", path.display()))
}

/// Writes `image` as a PNG file, atomically.
pub fn save_png(path: &Path, image: &RgbImage) -> anyhow::Result<()> {
    let mut files = Files::new();
    files.png(path, image)?;
    files.commit()
}

/// Writes `figure` as a PNG file at `path` and as an SVG file beside it (the same name
/// with `.svg`), atomically and together.
pub fn save_figure(path: &Path, figure: &Figure) -> anyhow::Result<()> {
    let mut files = Files::new();
    files.figure(path, figure)?;
    files.commit()
}

/// Writes `bytes` to a temporary file beside `path`, then renames it over `path`: a
/// reader (or a run killed midway) sees the old file or the new one, never half of one.
/// When the write fails (a full disk, a file-size limit, a read-only folder) the
/// temporary file is removed, `path` is left as it was, and the error names it.
pub fn atomic_write(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let mut files = Files::new();
    files.write(path, bytes)?;
    files.commit()
}

/// Files written together, all or none: each is written to a temporary file beside it
/// (`NAME.EXT.tmp`), and only when every one is written are they renamed into place. A
/// write that fails (a full disk, a file-size limit, a read-only folder) removes the
/// temporaries and names the file, and every file there is left as it was: a run's save
/// never leaves a new best model beside an old checkpoint. Temporaries not committed are
/// removed when the set is dropped.
///
/// ```text
/// let mut files = Files::new();
/// files.write(&dir.join("best.obj"), &obj)?;
/// files.write(&dir.join("checkpoint.json"), &checkpoint)?;
/// files.commit()?; // both, or (on an error above) neither
/// ```
#[derive(Debug, Default)]
pub struct Files {
    /// (temporary, final) paths written and not yet renamed, in order.
    pending: Vec<(PathBuf, PathBuf)>,
}

impl Files {
    /// An empty set.
    pub fn new() -> Files {
        Files::default()
    }

    /// Writes `bytes` to `path`'s temporary file.
    pub fn write(&mut self, path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
        let tmp = path.with_extension(format!(
            "{}.tmp",
            path.extension().and_then(|e| e.to_str()).unwrap_or("")
        ));
        if let Err(err) = std::fs::write(&tmp, bytes) {
            let _ = std::fs::remove_file(&tmp);
            return Err(self.failed(path, &err));
        }
        self.pending.push((tmp, path.to_owned()));
        Ok(())
    }

    /// Writes `image` as a PNG file to `path`'s temporary file.
    pub fn png(&mut self, path: &Path, image: &RgbImage) -> anyhow::Result<()> {
        let mut bytes = Vec::new();
        image.write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )?;
        self.write(path, &bytes)
    }

    /// Writes `figure` as a PNG file to `path`'s temporary file and as an SVG file to
    /// the temporary file of `path` with `.svg`.
    pub fn figure(&mut self, path: &Path, figure: &Figure) -> anyhow::Result<()> {
        self.png(path, &figure.png)?;
        self.write(&path.with_extension("svg"), figure.svg.as_bytes())
    }

    /// Renames every file written into place, in the order written.
    pub fn commit(mut self) -> anyhow::Result<()> {
        for (tmp, path) in std::mem::take(&mut self.pending) {
            if let Err(err) = std::fs::rename(&tmp, &path) {
                let _ = std::fs::remove_file(&tmp);
                return Err(self.failed(&path, &err));
            }
        }
        Ok(())
    }

    /// The error of a failed write of `path`; the set's other temporaries go when it is
    /// dropped.
    fn failed(&self, path: &Path, err: &std::io::Error) -> anyhow::Error {
        let others = if self.pending.is_empty() {
            ""
        } else {
            " (and the files written with it)"
        };
        anyhow::anyhow!(
            "cannot write `{}`: {err}; the file there{others}, if any, is left as it was",
            path.display()
        )
    }
}

impl Drop for Files {
    fn drop(&mut self) {
        for (tmp, _) in &self.pending {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

/// A CSV file's bytes: `header`, then one record per row, each field quoted where it
/// holds a comma, a quote or a line break (names given by users may).
pub fn csv_bytes<R, F>(header: &[String], rows: R) -> anyhow::Result<Vec<u8>>
where
    R: IntoIterator<Item = Vec<F>>,
    F: AsRef<[u8]>,
{
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for row in rows {
        writer.write_record(row)?;
    }
    writer
        .into_inner()
        .map_err(|err| anyhow::anyhow!("cannot write CSV: {}", err.error()))
}

#[cfg(test)]
mod tests {
    use super::{Files, atomic_write, csv_bytes};

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.json");
        atomic_write(&path, b"old").unwrap();
        // Writing the temporary file fails: a folder is in its way.
        std::fs::create_dir(dir.path().join("a.json.tmp")).unwrap();
        std::fs::write(dir.path().join("a.json.tmp/x"), "").unwrap();
        let err = atomic_write(&path, b"new").unwrap_err().to_string();
        assert!(
            err.contains("a.json`") && err.contains("left as it was"),
            "{err}"
        );
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
    }

    #[test]
    fn files_written_together_land_all_or_none() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        let mut files = Files::new();
        files.write(&a, b"a1").unwrap();
        files.write(&b, b"b1").unwrap();
        files.commit().unwrap();
        let mut files = Files::new();
        files.write(&a, b"a2").unwrap();
        std::fs::create_dir(dir.path().join("b.txt.tmp")).unwrap();
        std::fs::write(dir.path().join("b.txt.tmp/x"), "").unwrap();
        let err = files.write(&b, b"b2").unwrap_err().to_string();
        assert!(
            err.contains("b.txt`") && err.contains("files written with it"),
            "{err}"
        );
        drop(files);
        assert_eq!(std::fs::read(&a).unwrap(), b"a1");
        assert_eq!(std::fs::read(&b).unwrap(), b"b1");
        assert!(!dir.path().join("a.txt.tmp").exists());
    }

    #[test]
    fn names_with_commas_and_quotes_stay_one_field() {
        let header = [
            "model".to_owned(),
            "width, m".to_owned(),
            "say \"hi\"".to_owned(),
        ];
        let bytes = csv_bytes(&header, [vec!["0", "1.5", "2"]]).unwrap();
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "model,\"width, m\",\"say \"\"hi\"\"\"\n0,1.5,2\n"
        );
    }
}
