//! `shapegen view`: serves the run viewer's page for an output folder, on the loopback
//! interface unless told otherwise.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;

use clap::Args;

use crate::cli::view::Viewer;

/// Where the viewer listens: `shapegen view` and `shapegen run --view` share these.
#[derive(Debug, Clone, Copy, Args)]
pub struct ServeArgs {
    /// Port to listen on (default: any free port, printed).
    #[arg(long)]
    pub port: Option<u16>,
    /// Address to listen on instead of 127.0.0.1, e.g. 0.0.0.0 for every interface:
    /// anyone who can reach it can then read the folder's files.
    #[arg(long, value_name = "ADDR")]
    pub listen: Option<IpAddr>,
}

impl ServeArgs {
    /// Binds the viewer for `dir` and says where it is, loudly when it is reachable
    /// from other machines.
    pub fn bind(&self, dir: &std::path::Path) -> anyhow::Result<Viewer> {
        let ip = self.listen.unwrap_or(IpAddr::V4(Ipv4Addr::LOCALHOST));
        let viewer = Viewer::bind(dir, SocketAddr::new(ip, self.port.unwrap_or(0)))?;
        if !ip.is_loopback() {
            eprintln!(
                "WARNING: the viewer listens on {}, not on the loopback interface only: anyone \
                 who can reach this machine on port {} can read every file of `{}`",
                viewer.addr(),
                viewer.addr().port(),
                dir.display()
            );
        }
        eprintln!(
            "viewing `{}` at {} (Ctrl-C to stop)",
            dir.display(),
            viewer.url()
        );
        Ok(viewer)
    }
}

/// Arguments of `shapegen view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// The folder of a run, a multi-objective run, a comparison or a study (its --out),
    /// finished or still running.
    dir: PathBuf,
    #[command(flatten)]
    serve: ServeArgs,
}

/// Runs `shapegen view`: serves until the process is stopped.
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    args.serve.bind(&args.dir)?.serve();
    Ok(())
}
