//! The tool's commands, one module each: its arguments, and its body, generic over the
//! grammar of the generator it works on (a [`Visit`]). [`Command`] lists them for the
//! command line, and [`Commands`] is every body as one [`Jobs`], which
//! [`Generators`] runs with the grammar a generator's name gives.

mod compare;
mod export;
mod genome;
mod on_scene;
mod render;
mod report;
mod run;
mod sample;
mod score;
mod sweep;
mod target;
mod view;

use clap::Subcommand;
use shapegen_runtime::Grammar;

use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::memory::MemoryCheck;
use crate::registry::Entry;
use on_scene::visit_scene;

/// The commands of the tool, each with its arguments.
#[derive(Debug, Subcommand)]
pub enum Command {
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
    /// Serve a page that shows an output folder live in the browser: the best model in
    /// 3D beside the target, the fitness curve, the run's numbers; a multi-objective
    /// run's front, a comparison's or a study's runs. Listens on 127.0.0.1 unless
    /// --listen says otherwise; serves only the folder, read-only.
    View(view::ViewArgs),
    /// Write the viewer's page for an output folder as one self-contained
    /// `report.html`: models, curves, targets and numbers inline, nothing fetched.
    Report(report::ReportArgs),
}

impl Command {
    /// Runs the command with the generators of `tool`.
    pub fn run(self, tool: &Generators<Commands>) -> anyhow::Result<()> {
        match self {
            Command::Sample(args) => sample::run(&args, tool),
            Command::Score(args) => visit_scene(&args.scene, &args, tool),
            Command::Target(args) => visit_scene(&args.scene, &args, tool),
            Command::Render(args) => visit_scene(&args.scene, &args, tool),
            Command::Run(args) => run::run(&args, tool),
            Command::Compare(args) => compare::run(&args, tool),
            Command::Sweep(args) => sweep::run(&args, tool),
            Command::Export(args) => export::run(&args, tool),
            Command::Genome(args) => genome::run(&args, tool),
            Command::View(args) => view::run(&args),
            Command::Report(args) => report::run(&args),
        }
    }
}

/// Declares [`Job`], one variant per command body, and [`Commands`], which runs a `Job`
/// with a grammar.
macro_rules! jobs {
    ($($variant:ident($ty:ty)),* $(,)?) => {
        /// A command body waiting for its grammar.
        pub enum Job<'a> {
            $(
                #[doc = concat!("`", stringify!($ty), "`.")]
                $variant($ty),
            )*
        }

        $(
            impl<'a> From<$ty> for Job<'a> {
                fn from(visit: $ty) -> Self {
                    Job::$variant(visit)
                }
            }
        )*

        /// Every command body of the tool, as the [`Jobs`] its generators run.
        pub struct Commands;

        impl Jobs for Commands {
            type Job<'a> = Job<'a>;

            fn run<G: Grammar>(job: Job<'_>, entry: &Entry) -> anyhow::Result<()> {
                match job {
                    $(Job::$variant(visit) => visit.visit::<G>(entry),)*
                }
            }
        }
    };
}

jobs! {
    Sample(sample::Sample<'a>),
    Score(score::Score<'a>),
    Target(target::Target<'a>),
    Render(render::Render<'a>),
    Run(run::Run<'a>),
    Compare(compare::Compare<'a>),
    Cell(sweep::cell::CellRun<'a>),
    Memory(MemoryCheck<'a>),
    Export(export::Export<'a>),
    Convert(genome::Convert<'a>),
}
