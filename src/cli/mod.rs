//! The `shapegen` command-line tool, for the published generators and for your own.
//!
//! [`Cli`] gathers the generators the tool knows and runs the command its arguments
//! give. The `shapegen` binary is `Cli::new().published().run()`; a crate with its own
//! generators gets every subcommand (`sample`, `score`, `target`, `run`, `compare`,
//! `sweep`, `render`, `export`, `genome`, `view`, `report`) for them with a `main` like
//! this, and its scenes name them as `generator = "tower"`:
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
mod commands;
mod files;
mod folder;
mod front;
mod gap;
mod generators;
mod genomes;
mod history;
mod interrupt;
mod memory;
mod method;
#[cfg(feature = "mpi")]
mod mpi;
mod overlay;
mod plot;
mod processes;
mod progress;
mod record;
mod single;
pub mod view;
mod voxels;

use std::ffi::OsString;
use std::process::ExitCode;

use anyhow::Context;
use clap::Parser;
use shapegen_runtime::Grammar;

use crate::registry::{AddGrammar, Defaults, RegistryError, add_published};
use commands::{Command, Commands};
use generators::Generators;

/// The command-line tool, with the generators it knows; see the
/// [module documentation](self).
#[derive(Default)]
pub struct Cli {
    generators: Generators<Commands>,
    /// The first generator that could not be registered, reported when the tool runs.
    error: Option<RegistryError>,
}

impl Cli {
    /// A tool that knows no generator yet.
    pub fn new() -> Cli {
        Cli::default()
    }

    /// Adds the published generators ([`Published`](::generators::Published): the paper's `spaceship`,
    /// `tree` and `city`, the buildings and the others), with their meshes, limits and
    /// presets ([`Registry::published`](crate::registry::Registry::published)).
    pub fn published(mut self) -> Cli {
        if let Err(err) = add_published(&mut self.generators) {
            self.error.get_or_insert(err);
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
        pool.install(|| args.command.run(tool))
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
