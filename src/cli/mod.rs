//! The `shapegen` command-line tool, for the published generators and for your own.
//!
//! [`Cli`] gathers the generators the tool knows and runs the command its arguments
//! give. The `shapegen` binary is `Cli::new().published().run()`; a crate with its own
//! generators gets every subcommand (`sample`, `score`, `target`, `run`, `compare`,
//! `sweep`, `render`, `export`, `genome`) for them with a `main` like this, and its scenes name
//! them as `generator = "tower"`:
//!
//! ```no_run
//! use shapegen::prelude::*;
//!
//! generator! {
//!     /// A tower of boxes.
//!     pub Tower {
//!         axiom Floor;
//!         node Floor {
//!             children { up: Floor = 0.8 }
//!             derive(s) {
//!                 s.emit(CUBE);
//!                 if let Some(up) = up { s.translate(vec3(0.0, 1.0, 0.0)).derive(up); }
//!             }
//!         }
//!     }
//! }
//!
//! fn main() -> std::process::ExitCode {
//!     shapegen::cli::Cli::new().generator::<Tower>("tower").run()
//! }
//! ```

mod backend;
mod checkpoint;
mod compare;
mod dispatch;
mod export;
mod files;
mod folder;
mod front;
mod gap;
mod genome;
mod genomes;
mod interrupt;
mod memory;
#[cfg(feature = "mpi")]
mod mpi;
mod overlay;
mod plot;
mod processes;
mod progress;
mod render;
mod run;
mod sample;
mod score;
mod search;
mod stats;
mod sweep;
mod target;
mod voxels;

use std::ffi::OsString;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};
use shapegen_runtime::Grammar;

use generators::{GeneratorVisitor, Published};
use shapegen_runtime::genome::Limits;

use crate::registry::{Defaults, RegistryError, published_defaults};
use dispatch::Generators;

/// The command-line tool, with the generators it knows; see the
/// [module documentation](self).
#[derive(Default)]
pub struct Cli {
    generators: Generators,
    /// The first generator that could not be registered, reported when the tool runs.
    error: Option<RegistryError>,
}

impl Cli {
    /// A tool that knows no generator yet.
    pub fn new() -> Cli {
        Cli::default()
    }

    /// Adds the published generators: `spaceship`, `tree`, `city` and `building`, with
    /// their meshes and the original's settings
    /// ([`Registry::published`](crate::registry::Registry::published)).
    pub fn published(mut self) -> Cli {
        let meshes = generators::default_meshes();
        for generator in Published::ALL {
            self = generator.visit(Register {
                cli: self,
                name: generator.name(),
                defaults: published_defaults(generator, &meshes),
            });
        }
        self
    }

    /// Adds grammar `G` as `name`, with the built-in meshes and every method's own
    /// settings ([`Defaults::default`]). A name that is taken or not a plain identifier
    /// is reported when the tool runs.
    pub fn generator<G: Grammar>(self, name: &str) -> Cli {
        self.generator_with::<G>(name, Defaults::default())
    }

    /// Adds grammar `G` as `name` with its own `defaults`: the meshes it uses, the limits
    /// `sample` draws within, each method's settings.
    pub fn generator_with<G: Grammar>(mut self, name: &str, defaults: Defaults) -> Cli {
        if let Err(err) = self.generators.add::<G>(name, defaults) {
            self.error.get_or_insert(err);
        }
        self
    }

    /// Runs the command the process's arguments give; prints what went wrong and returns
    /// a failure exit code when it fails.
    pub fn run(self) -> ExitCode {
        let args = match Args::try_parse() {
            Ok(args) => args,
            Err(err) => err.exit(),
        };
        match self.execute(args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(err) => {
                eprintln!("error: {err:#}");
                ExitCode::FAILURE
            }
        }
    }

    /// Runs the command `args` give (the program's name first, as in `std::env::args`).
    ///
    /// # Errors
    /// When the arguments do not parse (the error holds clap's usage message) or the
    /// command fails.
    pub fn run_from<I, T>(self, args: I) -> anyhow::Result<()>
    where
        I: IntoIterator<Item = T>,
        T: Into<OsString> + Clone,
    {
        let args = Args::try_parse_from(args)?;
        self.execute(args)
    }

    fn execute(self, args: Args) -> anyhow::Result<()> {
        if let Some(err) = self.error {
            return Err(err.into());
        }
        let mut pool = rayon::ThreadPoolBuilder::new();
        if let Some(threads) = args.threads {
            anyhow::ensure!(threads > 0, "--threads must be at least 1");
            pool = pool.num_threads(threads);
        }
        let pool = pool.build().context("could not start the worker threads")?;
        let tool = &self.generators;
        pool.install(|| match args.command {
            Command::Sample(args) => sample::run(&args, tool),
            Command::Score(args) => score::run(&args, tool),
            Command::Target(args) => target::run(&args, tool),
            Command::Render(args) => render::run(&args, tool),
            Command::Run(args) => run::run(&args, tool),
            Command::Compare(args) => compare::run(&args, tool),
            Command::Sweep(args) => sweep::run(&args, tool),
            Command::Export(args) => export::run(&args, tool),
            Command::Genome(args) => genome::run(&args, tool),
        })
    }
}

/// Adds the grammar a [`Published`] generator visits with.
struct Register {
    cli: Cli,
    name: &'static str,
    defaults: Defaults,
}

impl GeneratorVisitor for Register {
    type Output = Cli;

    fn visit<G: Grammar>(self, _: Limits) -> Cli {
        self.cli.generator_with::<G>(self.name, self.defaults)
    }
}

/// Controlled procedural modeling: search a procedural generator's derivation trees for
/// models that meet a goal.
#[derive(Debug, Parser)]
#[command(name = "shapegen", version, about)]
struct Args {
    /// Worker threads (default: one per core). Results do not depend on it.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,

    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Write random models of a generator, drawn from its own distribution.
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
    /// Run a parameter study: every combination of the --grid values, each --runs
    /// times, in parallel here or as a Slurm job array; write each run's result and the
    /// study's tables and plots.
    ///
    /// Each grid point runs on seeds seed + r (r = 0 .. runs - 1) with the one budget
    /// given. Budgets by --evaluations or --generations make the results independent of
    /// the machine's speed and of --jobs (and of --threads, as always); a --seconds budget
    /// does not.
    ///
    /// DIR gets plan.json, cells/NNNN/ per finished run (result.json, fitness.csv,
    /// best.genome.json), and, rewritten after each: sweep.csv (one row per run: the swept
    /// values, seed, final best, evaluations, generations, seconds, and
    /// evaluations_to_50/90/99: the evaluations a run took to reach 50, 90 and 99 % of
    /// the way from the sweep's lowest initial best, the lowest best of any run's first
    /// population, to its highest final best, empty if it never did), summary.md (mean
    /// +- std and median of the final best per grid point, the best marked),
    /// final-KEY.png per swept key (final best against the key's values with error bars,
    /// one line per value of a second key) and curves.png (the mean curves of the best
    /// and the worst grid points against evaluations), each chart also as SVG.
    ///
    /// Run the same command again to go on after an interruption; --plan-only writes a
    /// Slurm job array instead (`sbatch DIR/sweep.sbatch` runs it and collects it).
    Sweep(sweep::SweepArgs),
    /// Write shaded previews of saved genomes and, for image targets, overlays.
    Render(render::RenderArgs),
    /// Write the model a saved genome derives as OBJ (with its MTL) or binary glTF.
    Export(export::ExportArgs),
    /// Work on genome files: `convert` rewrites one in the other JSON form (packed or
    /// nested).
    Genome(genome::GenomeArgs),
}

/// The help of an option naming methods: what it does, and every method it may name.
fn method_help(what: &str) -> String {
    format!(
        "{what}; the methods are {}",
        shapegen::scene::Method::names()
    )
}
