//! Request targets as `shapegen view` reads them from a request line: whatever the bytes,
//! parsing returns a route or a refusal, never panics, and a file route is a plain
//! relative path (no empty, `.` or `..` segment, no separator or NUL inside a segment)
//! that resolves, if at all, to a file inside the folder.

#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use shapegen::cli::view::{MAX_TARGET, RequestPath};

fuzz_target!(|data: &[u8]| {
    let Ok(target) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(path) = RequestPath::parse(target) else {
        return;
    };
    assert!(target.len() <= MAX_TARGET);
    if let RequestPath::File(segments) = &path {
        assert!(!segments.is_empty());
        for s in segments {
            assert!(!s.is_empty() && s != "." && s != "..", "{target:?}");
            assert!(!s.contains(['/', '\\', ':', '\0']), "{target:?}");
        }
        // The folder the fuzzer runs in stands for a run's folder.
        let root = Path::new(".");
        if let Ok(file) = path.file_in(root) {
            assert!(file.starts_with(root.canonicalize().unwrap()), "{target:?}");
        }
    }
});
