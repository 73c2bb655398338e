//! Command-line interface: argument parsing and dispatch to the commands.

mod backend;
mod compare;
mod export;
mod files;
mod front;
mod genome;
mod genomes;
mod interrupt;
mod plot;
mod render;
mod run;
mod sample;
mod score;
mod search;
mod target;
mod voxels;

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
    /// Print the counts and fitness of saved genomes in a scene, one JSON object each.
    Score(score::ScoreArgs),
    /// Write a reachable target made from a fixed derivation: a volume OBJ or a
    /// silhouette PNG through the scene's camera.
    Target(target::TargetArgs),
    /// Evolve models toward a scene's goal and write the best found.
    Run(run::RunArgs),
    /// Run several methods on one scene, each several times on the same seeds with the
    /// same wall-time budget, and write their curves and a summary side by side.
    Compare(compare::CompareArgs),
    /// Write shaded previews of saved genomes and, for image targets, overlays.
    Render(render::RenderArgs),
    /// Write the model a saved genome derives as OBJ (with its MTL) or binary glTF.
    Export(export::ExportArgs),
    /// Work on genome files: `convert` rewrites one in the other JSON form (packed or
    /// nested).
    Genome(genome::GenomeArgs),
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
        Command::Score(score) => score::run(&score),
        Command::Target(target) => target::run(&target),
        Command::Render(render) => render::run(&render),
        Command::Run(args) => run::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Export(args) => export::run(&args),
        Command::Genome(args) => genome::run(&args),
    })
}
