//! `shapegen report`: the run viewer's page for an output folder as one self-contained
//! HTML file.

use std::path::PathBuf;

use clap::Args;

use crate::cli::files::atomic_write;
use crate::cli::view::report_html;

/// Arguments of `shapegen report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// The folder of a run, a multi-objective run, a comparison or a study (its --out).
    dir: PathBuf,
    /// The file to write (default: DIR/report.html).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs `shapegen report`.
pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let html = report_html(&args.dir)?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| args.dir.join("report.html"));
    atomic_write(&out, html.as_bytes())?;
    println!(
        "wrote {} ({:.1} MiB, self-contained: open it in a browser, no network needed)",
        out.display(),
        html.len() as f64 / (1 << 20) as f64
    );
    Ok(())
}
