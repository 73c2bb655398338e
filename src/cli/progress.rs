//! The progress line of a long-running command: one per generation, rewritten in place
//! on a terminal, every tenth generation on its own line otherwise (a log, a cluster
//! job's output).

use std::io::IsTerminal;

/// Where progress lines go: standard error.
pub struct ProgressLine {
    terminal: bool,
}

impl ProgressLine {
    /// Progress on standard error, in place if it is a terminal.
    pub fn new() -> ProgressLine {
        ProgressLine {
            terminal: std::io::stderr().is_terminal(),
        }
    }

    /// Shows `line`, the progress after `generation`.
    pub fn show(&self, generation: u64, line: &str) {
        if self.terminal {
            eprint!("\r{line}");
        } else if generation.is_multiple_of(10) {
            eprintln!("{line}");
        }
    }

    /// Ends the line rewritten in place, so that what follows starts on its own line.
    pub fn finish(&self) {
        if self.terminal {
            eprintln!();
        }
    }
}
