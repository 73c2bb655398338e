//! Serving a folder with `shapegen view` (or `shapegen run --view`) from the tests.

use std::io::{BufRead, BufReader};
use std::net::SocketAddr;
use std::process::{Child, Command, Stdio};

/// A `shapegen view` process and the address it listens on.
pub struct Served {
    child: Child,
    /// The address it listens on.
    pub addr: SocketAddr,
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `shapegen view` with `args` and reads its address from the line it prints.
pub fn serve(args: &[&str]) -> Served {
    let mut child = Command::new(env!("CARGO_BIN_EXE_shapegen"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the shapegen binary runs");
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let line = lines
        .next()
        .expect("a line from shapegen view")
        .expect("text");
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .unwrap_or_else(|| panic!("no URL in `{line}`"));
    let addr = url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .parse()
        .unwrap();
    // The rest of its output is read and dropped: a closed pipe would fail its prints.
    std::thread::spawn(move || lines.for_each(drop));
    Served { child, addr }
}
