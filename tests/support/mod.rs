//! Running the `shapegen` binary from the command-line tests.

// Each test file uses the helpers it needs.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// Runs `shapegen` with `args`.
pub fn shapegen(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shapegen"))
        .args(args)
        .output()
        .expect("the shapegen binary runs")
}

/// Runs `shapegen` with `args`, which must succeed, and returns what it printed.
pub fn ok(args: &[&str]) -> String {
    let run = shapegen(args);
    assert!(
        run.status.success(),
        "shapegen {args:?} failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).unwrap()
}

/// Runs `shapegen` with `args`, which must fail, and returns its error output.
pub fn fails(args: &[&str]) -> String {
    let run = shapegen(args);
    assert!(!run.status.success(), "shapegen {args:?} should fail");
    String::from_utf8(run.stderr).unwrap()
}

/// A path as a command-line argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
