//! The viewer's request paths: what a request line's target names, and the file of the
//! run folder it may read.
//!
//! A target is `/` (the page), `/assets/NAME` (an embedded asset), `/files/REL` (a file
//! of the folder) or `/list` (the folder's listing). `REL` is percent-decoded and must be
//! a plain relative path: no empty, `.` or `..` segment, no backslash, colon or NUL, so
//! that it can name nothing but a path under the folder; [`RequestPath::file_in`] then
//! refuses a file whose real path (symbolic links followed) leaves the folder.

use std::fmt;
use std::path::{Path, PathBuf};

use percent_encoding::percent_decode_str;

/// Longest request target accepted, in bytes.
pub const MAX_TARGET: usize = 2048;

/// What a request's target names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RequestPath {
    /// `/`: the viewer's page.
    Page,
    /// `/assets/NAME`: an embedded asset, by its name under `assets/viewer/`.
    Asset(String),
    /// `/files/REL`: a file of the run folder, by its path relative to the folder, in
    /// checked segments.
    File(Vec<String>),
    /// `/list`: the folder's files, as JSON.
    List,
}

/// Why a request's target was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Refusal {
    /// The target is longer than [`MAX_TARGET`].
    TooLong,
    /// The target does not start with `/` (an absolute URL or `*`).
    NotAbsolutePath,
    /// Its percent-encoding does not decode to UTF-8.
    BadEncoding,
    /// A segment is empty, `.` or `..`, or holds a backslash, colon or NUL.
    BadSegment(String),
    /// The target names nothing the viewer serves.
    Unknown,
    /// The file's real path is outside the folder (a symbolic link out of it).
    OutsideFolder,
    /// No such file (or not a regular file).
    NotFound,
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Refusal::TooLong => write!(f, "request path longer than {MAX_TARGET} bytes"),
            Refusal::NotAbsolutePath => write!(f, "request path must start with `/`"),
            Refusal::BadEncoding => write!(f, "request path is not percent-encoded UTF-8"),
            Refusal::BadSegment(s) => write!(
                f,
                "path segment `{}` refused: segments may not be empty, `.` or `..`, nor hold `\\`, `:` or NUL",
                s.escape_debug()
            ),
            Refusal::Unknown => {
                write!(
                    f,
                    "not found: the viewer serves /, /list, /assets/… and /files/…"
                )
            }
            Refusal::OutsideFolder => write!(f, "refused: the file is outside the run folder"),
            Refusal::NotFound => write!(f, "not found"),
        }
    }
}

impl std::error::Error for Refusal {}

impl Refusal {
    /// The HTTP status the refusal answers with: 404 for what is not there, 403 for a
    /// path leaving the folder, 400 for the rest.
    pub fn status(&self) -> u16 {
        match self {
            Refusal::Unknown | Refusal::NotFound => 404,
            Refusal::OutsideFolder => 403,
            Refusal::TooLong => 414,
            _ => 400,
        }
    }
}

impl RequestPath {
    /// Parses a request line's target (`/files/best.glb?t=3`); a query or fragment is
    /// ignored.
    ///
    /// ```
    /// use shapegen::cli::view::{Refusal, RequestPath};
    ///
    /// assert_eq!(
    ///     RequestPath::parse("/files/front/model_001.glb?t=1"),
    ///     Ok(RequestPath::File(vec!["front".into(), "model_001.glb".into()]))
    /// );
    /// let up = ".."; // a parent step
    /// let escape = format!("/files/{up}/etc/passwd");
    /// assert!(matches!(RequestPath::parse(&escape), Err(Refusal::BadSegment(_))));
    /// assert!(matches!(RequestPath::parse("/files/%2e%2e/x"), Err(Refusal::BadSegment(_))));
    /// ```
    pub fn parse(target: &str) -> Result<RequestPath, Refusal> {
        if target.len() > MAX_TARGET {
            return Err(Refusal::TooLong);
        }
        let path = target.split(['?', '#']).next().unwrap_or_default();
        let Some(rest) = path.strip_prefix('/') else {
            return Err(Refusal::NotAbsolutePath);
        };
        let (head, tail) = rest.split_once('/').unwrap_or((rest, ""));
        match head {
            "" | "index.html" if tail.is_empty() => Ok(RequestPath::Page),
            "list" if tail.is_empty() => Ok(RequestPath::List),
            "assets" => Ok(RequestPath::Asset(segments(tail)?.join("/"))),
            "files" => Ok(RequestPath::File(segments(tail)?)),
            _ => Err(Refusal::Unknown),
        }
    }

    /// The real path of the file this target names under `root`: an existing regular
    /// file whose path, symbolic links followed, is inside `root`'s.
    ///
    /// # Errors
    /// [`Refusal::Unknown`] when the target names no file of the folder,
    /// [`Refusal::NotFound`] when there is no such regular file (or `root` is gone),
    /// [`Refusal::OutsideFolder`] when its real path leaves the folder.
    pub fn file_in(&self, root: &Path) -> Result<PathBuf, Refusal> {
        let RequestPath::File(segments) = self else {
            return Err(Refusal::Unknown);
        };
        let root = root.canonicalize().map_err(|_| Refusal::NotFound)?;
        let joined = segments.iter().fold(root.clone(), |p, s| p.join(s));
        let real = joined.canonicalize().map_err(|_| Refusal::NotFound)?;
        if !real.starts_with(&root) {
            return Err(Refusal::OutsideFolder);
        }
        if !real.is_file() {
            return Err(Refusal::NotFound);
        }
        Ok(real)
    }
}

/// The checked, decoded segments of a relative path (at least one).
fn segments(rel: &str) -> Result<Vec<String>, Refusal> {
    rel.split('/')
        .map(|raw| {
            let s = percent_decode_str(raw)
                .decode_utf8()
                .map_err(|_| Refusal::BadEncoding)?;
            let bad = s.is_empty() || s == "." || s == ".." || s.contains(['\\', ':', '\0', '/']);
            if bad {
                Err(Refusal::BadSegment(s.into_owned()))
            } else {
                Ok(s.into_owned())
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(parts: &[&str]) -> RequestPath {
        RequestPath::File(parts.iter().map(|s| s.to_string()).collect())
    }

    #[test]
    fn routes() {
        assert_eq!(RequestPath::parse("/"), Ok(RequestPath::Page));
        assert_eq!(RequestPath::parse("/index.html"), Ok(RequestPath::Page));
        assert_eq!(RequestPath::parse("/list?x=1"), Ok(RequestPath::List));
        assert_eq!(
            RequestPath::parse("/assets/vendor/three.module.js"),
            Ok(RequestPath::Asset("vendor/three.module.js".into()))
        );
        assert_eq!(
            RequestPath::parse("/files/best.glb?t=12#x"),
            Ok(file(&["best.glb"]))
        );
        assert_eq!(
            RequestPath::parse("/files/runs/ga-0/best%20model.glb"),
            Ok(file(&["runs", "ga-0", "best model.glb"]))
        );
        assert_eq!(RequestPath::parse("/other"), Err(Refusal::Unknown));
        assert_eq!(RequestPath::parse("/list/x"), Err(Refusal::Unknown));
    }

    /// A parent step, spelt apart from the `/` after it in these tests.
    const UP: &str = "..";

    #[test]
    fn refuses_escapes() {
        let (one, two) = (
            format!("/files/{UP}/secret"),
            format!("/files/a/{UP}/{UP}/secret"),
        );
        let assets = format!("/assets/{UP}/Cargo.toml");
        for bad in [
            one.as_str(),
            two.as_str(),
            assets.as_str(),
            "/files/%2e%2e/secret",
            "/files/%2E%2E%2Fsecret",
            "/files/./best.glb",
            "/files//etc/passwd",
            "/files/",
            "/files",
            "/files/a%5c..%5csecret",
            "/files/C:%5cwindows",
            "/files/a%00b",
        ] {
            let refused = RequestPath::parse(bad);
            assert!(
                matches!(refused, Err(Refusal::BadSegment(_))),
                "{bad}: {refused:?}"
            );
        }
        assert_eq!(
            RequestPath::parse("http://example.com/files/x"),
            Err(Refusal::NotAbsolutePath)
        );
        assert_eq!(RequestPath::parse("*"), Err(Refusal::NotAbsolutePath));
        assert_eq!(RequestPath::parse("/files/%ff"), Err(Refusal::BadEncoding));
        let long = format!("/files/{}", "a".repeat(MAX_TARGET));
        assert_eq!(RequestPath::parse(&long), Err(Refusal::TooLong));
    }

    #[test]
    fn files_stay_in_the_folder() {
        let outer = tempfile::tempdir().unwrap();
        let root = outer.path().join("run");
        std::fs::create_dir_all(root.join("front")).unwrap();
        std::fs::write(root.join("best.glb"), b"glb").unwrap();
        std::fs::write(root.join("front/model_000.glb"), b"glb").unwrap();
        std::fs::write(outer.path().join("secret.txt"), b"secret").unwrap();

        let found = file(&["front", "model_000.glb"]).file_in(&root).unwrap();
        assert_eq!(std::fs::read(found).unwrap(), b"glb");
        assert_eq!(
            file(&["missing.glb"]).file_in(&root),
            Err(Refusal::NotFound)
        );
        assert_eq!(file(&["front"]).file_in(&root), Err(Refusal::NotFound));
        assert_eq!(RequestPath::Page.file_in(&root), Err(Refusal::Unknown));

        #[cfg(unix)]
        {
            use std::os::unix::fs::symlink;
            symlink(outer.path().join("secret.txt"), root.join("out.txt")).unwrap();
            symlink(outer.path(), root.join("up")).unwrap();
            symlink(root.join("best.glb"), root.join("inside.glb")).unwrap();
            assert_eq!(
                file(&["out.txt"]).file_in(&root),
                Err(Refusal::OutsideFolder)
            );
            assert_eq!(
                file(&["up", "secret.txt"]).file_in(&root),
                Err(Refusal::OutsideFolder)
            );
            assert!(file(&["inside.glb"]).file_in(&root).is_ok());
        }
    }
}
