//! Ctrl-C: a flag the long-running commands check between generations.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A flag set when the process receives Ctrl-C (SIGINT or SIGTERM), so that a command
/// can stop at its next generation and write what it has.
pub fn flag() -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    // A second handler cannot be set in one process (tests run commands as processes).
    let _ = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst));
    stop
}
