//! Ctrl-C and its kin: a flag the long-running commands check between generations.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// The process's flag, set by the first of SIGINT (Ctrl-C), SIGTERM (`kill`, a batch
/// system's time limit) and SIGHUP (a closed terminal or SSH session) that arrives, so
/// that a command can stop at its next generation and write what it has. Every call
/// returns the same flag: one process has one handler (the `ctrlc` crate's, with its
/// `termination` feature for SIGTERM and SIGHUP). A run under `nohup` stops on SIGHUP
/// too; detach it with `setsid` or a terminal multiplexer instead.
pub fn flag() -> Arc<AtomicBool> {
    static STOP: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    Arc::clone(STOP.get_or_init(|| {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        if let Err(err) = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst)) {
            eprintln!(
                "cannot catch Ctrl-C ({err}): an interrupted command loses its last generation"
            );
        }
        stop
    }))
}
