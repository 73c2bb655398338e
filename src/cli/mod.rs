//! Command-line interface: argument parsing and dispatch to the commands.

mod sample;

use anyhow::Context;
use clap::{Parser, Subcommand};

/// Controlled procedural modeling: search a procedural generator's derivation trees for
/// models that meet a goal.
#[derive(Debug, Parser)]
#[command(name = "shapegen", version, about)]
pub struct Cli {
    /// Worker threads (default: one per core). Results do not depend on it.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,

    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Write random models of a published generator, drawn from its own distribution.
    Sample(sample::SampleArgs),
}

/// Runs the command `args` asks for.
pub fn run(args: Cli) -> anyhow::Result<()> {
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(threads) = args.threads {
        anyhow::ensure!(threads > 0, "--threads must be at least 1");
        pool = pool.num_threads(threads);
    }
    let pool = pool.build().context("could not start the worker threads")?;
    pool.install(|| match args.command {
        Command::Sample(sample) => sample::run(&sample),
    })
}
