//! `shapegen compare`: runs several search methods on one scene, each several times on
//! the same seeds and with the same wall-time budget, and writes their results side by
//! side: every run's history (`compare.csv`), every run's final best and its best
//! model's measures (`runs.csv`: size, IoU, Chamfer distance and F-score, see
//! [`Metrics::columns`]), a summary per method and a picture of the median curves.
//!
//! The runs and the summaries are those of the library's
//! [`Compare`](shapegen::search::Compare) (which the Python package offers as
//! `Scene.compare`); this command writes them.
//!
//! Each method takes its settings as `shapegen run --method M` does (the scene's
//! `[optimizer]` table over the paper's settings for the method and the generator), with
//! three changes that make the runs comparable:
//! - the wall budget `--seconds` is the only time limit, and the methods' own generation
//!   counts (`generations`, `steps`, `iterations`, from the paper or the scene) are not
//!   limits: a method that would have finished its published generations goes on until
//!   the time is spent. SMC and SOSMC then go on resampling their particles, which stop
//!   changing once every particle is complete, so their best stays where it was;
//! - an evaluation budget (`optimizer.evaluations`) still stops a run, so that a
//!   comparison can be made at equal evaluations, and exactly repeated;
//! - run `r` (from 0) of every method uses the seed `base + r`, where `base` is `--seed`
//!   or the scene's `optimizer.seed`: in each run the methods start from the same seed,
//!   and `shapegen run --method M --seed S` repeats a run.
//!
//! Runs go run-major (run 0 of every method, then run 1, ...) so that slow drifts of the
//! machine's load hit every method alike.
//!
//! Results are given as the median with its quartiles over the runs (and the mean +-
//! std in `summary.json`). For a scene with a known optimum (`fitness.optimum`), compare
//! also writes each method's time and evaluations to 90 %, 99 % and 99.9 % of it
//! (`targets.csv`, and in `summary.json`) and its gap to the optimum against time and
//! against evaluations on a log scale (`gap-time.png`, `gap-evaluations.png`); see
//! [`gap`](crate::cli::gap).

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use image::Rgb;
use serde::Serialize;
use shapegen::Grammar;
use shapegen::export::{Model, Palette, glb_bytes};
use shapegen::optimize::Control;
use shapegen::scene::{METRIC_COLUMNS, Method, Overrides, Scene};
use shapegen::search::stats::quartile_curve;
use shapegen::search::{Compare as Plan, CompareError, CompareObserver, Comparison, MethodSummary};

use crate::cli::backend::BackendArgs;
use crate::cli::files::{atomic_write, csv_bytes, save_figure};
use crate::cli::folder::{Existing, Folder, Kind};
use crate::cli::gap::{self, Group};
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::interrupt;
use crate::cli::memory::{MemoryArgs, MemoryCheck};
use crate::cli::plot::{self, Spread, Titles, YScale};
use crate::registry::Entry;

/// Points of the common time grid the curves are sampled on.
const GRID_POINTS: usize = 400;
/// Size of `compare.png` (and `compare.svg`).
const PLOT_SIZE: (u32, u32) = (800, 500);

/// Arguments of `shapegen compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// The methods to compare, comma-separated, in the order they run and are listed
    /// (default: every method).
    #[arg(long, value_delimiter = ',', help = crate::cli::method::method_help(
        "The methods to compare, comma-separated, in the order they run and are listed \
         (default: all of them)"
    ))]
    methods: Option<Vec<String>>,
    /// Runs of each method (at least 1).
    #[arg(long, default_value_t = 3)]
    runs: u64,
    /// Wall-time budget of every run, in seconds (> 0).
    #[arg(long)]
    seconds: f64,
    /// Base seed: run r of every method uses seed + r (default: `optimizer.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Overrides any scene value, e.g. `--set optimizer.evaluations=5000`; repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    #[command(flatten)]
    backend: BackendArgs,
    /// Folder to write into; created if missing. One that holds the outputs of another
    /// comparison, run or study is refused unless --force is given.
    #[arg(long)]
    out: PathBuf,
    /// Replace the outputs already in the --out folder: they are removed, and listed,
    /// before the comparison starts.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    memory: MemoryArgs,
}

/// Runs `shapegen compare`.
pub fn run<J: Jobs>(args: &CompareArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<Compare<'a>> + From<MemoryCheck<'a>>,
{
    let methods = match &args.methods {
        Some(names) => parse_methods(names)?,
        None => Method::ALL.to_vec(),
    };
    anyhow::ensure!(
        args.runs >= 1,
        "--runs {}: give at least 1 run per method",
        args.runs
    );
    anyhow::ensure!(
        args.seconds.is_finite() && args.seconds > 0.0,
        "--seconds {}: give a wall-time budget of more than 0 seconds",
        args.seconds
    );
    let multi_objective = |scene: &Scene| {
        anyhow::ensure!(
            scene.objectives.is_none(),
            "`{}` has [[objective]] tables: compare measures single-objective methods by \
             one fitness, and a multi-objective scene is searched by the multi-objective GA \
             (`shapegen run`)",
            args.scene.display()
        );
        Ok(())
    };
    // The scene as written, when it loads so (it may not: `--set` keys may belong to the
    // compared methods rather than to the scene's own), says whether it has objectives.
    let overrides = Overrides {
        sets: args.sets.clone(),
        ..Overrides::default()
    };
    if let Ok(scene) = Scene::open(&args.scene, tool.registry(), &overrides) {
        multi_objective(&scene)?;
    }
    // Each method's goal, as `shapegen run --method M` resolves it: `--set` keys are read
    // as the method's own (a `variant`, say, is each method's variant).
    let overrides = Overrides {
        method: Some(methods[0]),
        ..overrides
    };
    let scene = Scene::open(&args.scene, tool.registry(), &overrides)?;
    multi_objective(&scene)?;
    let plan = Plan::new(&scene, &methods, args.runs, args.seed, Some(args.seconds))
        .map_err(|err| match err {
            CompareError::Seeds { base, runs } => {
                anyhow::anyhow!(
                    "--seed {base}: with {runs} runs the seeds would pass {}",
                    u64::MAX
                )
            }
            other => other.into(),
        })?
        .incremental(args.backend.incremental());
    tool.visit(
        &scene.generator,
        MemoryCheck {
            scene: &scene,
            goals: plan.goals(),
            jobs: 1,
            backend: &args.backend,
            limit: args.memory,
        },
    )?;
    let _folder = Folder::claim(
        &args.out,
        Kind::Compare,
        Existing::from_flags(args.force, false),
    )?;
    tool.visit(
        &scene.generator,
        Compare {
            args,
            plan: &plan,
            scene: &scene,
        },
    )
}

/// The methods `names` lists, in order.
fn parse_methods(names: &[String]) -> anyhow::Result<Vec<Method>> {
    let valid = || {
        Method::ALL
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let names: Vec<&str> = names
        .iter()
        .map(|n| n.trim())
        .filter(|n| !n.is_empty())
        .collect();
    anyhow::ensure!(
        !names.is_empty(),
        "--methods is empty: give one or more of {}",
        valid()
    );
    let mut methods = Vec::with_capacity(names.len());
    for name in names {
        let method: Method = name.parse().with_context(|| {
            format!(
                "--methods: `{name}` is not a method; the methods are {}",
                valid()
            )
        })?;
        anyhow::ensure!(
            !methods.contains(&method),
            "--methods: `{name}` is listed twice"
        );
        methods.push(method);
    }
    Ok(methods)
}

/// The body of `shapegen compare`.
pub struct Compare<'a> {
    args: &'a CompareArgs,
    /// The methods, their goals and the runs' seeds.
    plan: &'a Plan<'a>,
    scene: &'a Scene,
}

impl Visit for Compare<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let gpu = self.args.backend.open();
        let plan = self
            .plan
            .clone()
            .backend(self.args.backend.choice(), gpu.as_ref());
        let stop = interrupt::flag();
        let plan = plan.stop_flag(&stop);
        let mut shown = Shown {
            args: self.args,
            scene: self.scene,
            methods: self.plan.methods(),
            runs: self.plan.seeds().len(),
            meshes: None,
            palette: Palette::new(),
            instances: Vec::new(),
            failed: None,
        };
        let done = plan.run::<G>(&mut shown);
        if let Some(err) = shown.failed {
            return Err(err);
        }
        let done = done?;
        let total = done.planned();
        let outputs = Outputs {
            args: self.args,
            backend: &done.backend,
        };
        if let Some((method, run)) = done.interrupted {
            outputs.write(&done)?;
            anyhow::bail!(
                "interrupted during run {run} of {}: wrote the {} complete runs of {total} to {}",
                method.name(),
                done.runs.len(),
                self.args.out.display()
            );
        }
        let gaps = if self.scene.optimum.is_some() {
            ", targets.csv, gap-time.png, gap-evaluations.png (each PNG with its SVG)"
        } else {
            ""
        };
        println!(
            "compared {} runs; wrote compare.csv, runs.csv, compare.png, summary.json{gaps} and runs/ to {}",
            done.runs.len(),
            self.args.out.display()
        );
        Ok(())
    }
}

/// What the tool shows and writes as the comparison goes: the line of its start, and
/// after each run its files, its line and the tables so far.
struct Shown<'a> {
    args: &'a CompareArgs,
    scene: &'a Scene,
    /// The methods compared.
    methods: &'a [Method],
    /// Runs of each.
    runs: usize,
    /// The scene's meshes, bound to the generator once the first run has finished.
    meshes: Option<shapegen::BoundMeshes>,
    palette: Palette,
    instances: Vec<shapegen::Instance>,
    /// What failed to be written, which stopped the comparison.
    failed: Option<anyhow::Error>,
}

impl<G: Grammar> CompareObserver<G> for Shown<'_> {
    fn started(&mut self, backend: &str) {
        eprintln!(
            "comparing {} on {backend}: {} runs of {} s",
            self.methods
                .iter()
                .map(|m| m.name())
                .collect::<Vec<_>>()
                .join(", "),
            self.methods.len() * self.runs,
            self.args.seconds
        );
    }

    fn finished(&mut self, so_far: &Comparison<G>) -> Control {
        match self.write(so_far) {
            Ok(()) => Control::Continue,
            Err(err) => {
                self.failed = Some(err);
                Control::Stop
            }
        }
    }
}

impl Shown<'_> {
    /// The last run's files and line, and the tables of the runs so far.
    fn write<G: Grammar>(&mut self, so_far: &Comparison<G>) -> anyhow::Result<()> {
        let Some(last) = so_far.runs.last() else {
            return Ok(());
        };
        let (method, run, seed, result) = (last.method, last.run, last.seed, &last.result);
        let dir = self
            .args
            .out
            .join("runs")
            .join(format!("{}-{run}", method.name()));
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("cannot create `{}`", dir.display()))?;
        atomic_write(
            &dir.join("best.genome.json"),
            result.best.to_json().as_bytes(),
        )?;
        // The model, for the run viewer (`shapegen view`).
        let meshes = match &mut self.meshes {
            Some(meshes) => meshes,
            none => none.insert(self.scene.meshes.bind(G::GRAPH)?),
        };
        result.best.derive_on(&self.scene.site, &mut self.instances);
        atomic_write(
            &dir.join("best.glb"),
            &glb_bytes(Model::new(&self.instances, meshes, &self.palette))?,
        )?;
        let elapsed = result.history.last().map_or(0.0, |h| h.elapsed_s);
        eprintln!(
            "{:<6} run {run} (seed {seed}): best {:.5}  {} evaluations  {elapsed:.1} s  [{}/{}]",
            method.name(),
            result.best_fitness,
            result.evaluations,
            so_far.runs.len(),
            so_far.planned()
        );
        Outputs {
            args: self.args,
            backend: &so_far.backend,
        }
        .write(so_far)
    }
}

/// Writes `compare.csv`, `runs.csv`, `summary.json` and `compare.png` for the runs done
/// so far.
struct Outputs<'a> {
    args: &'a CompareArgs,
    backend: &'a str,
}

/// `summary.json`.
#[derive(Serialize)]
struct Summary<'a> {
    scene: &'a Path,
    seconds: f64,
    base_seed: u64,
    /// How each run's seed follows from the base seed.
    seed_rule: &'static str,
    seeds: &'a [u64],
    backend: &'a str,
    /// Whether every planned run finished.
    complete: bool,
    /// The scene's optimum (`fitness.optimum`), when it gives one.
    optimum: Option<f64>,
    methods: Vec<MethodSummary>,
}

impl Outputs<'_> {
    /// Writes `compare.csv`, `runs.csv`, `summary.json`, the gap tables when the scene
    /// gives an optimum, and `compare.png`; then fails if a run went past the optimum.
    fn write<G: Grammar>(&self, comparison: &Comparison<G>) -> anyhow::Result<()> {
        let dir = &self.args.out;
        self.write_tables(comparison)?;
        let groups: Vec<Group<'_>> = comparison
            .methods
            .iter()
            .map(|&m| Group {
                name: m.name().to_owned(),
                colour: Rgb(m.colour()),
                runs: comparison
                    .runs_of(m)
                    .map(|f| f.result.history.as_slice())
                    .collect(),
            })
            .collect();
        // The summaries' targets are those of `targets.csv`.
        let optimum = comparison.optimum;
        if let Some(optimum) = optimum {
            gap::write(dir, "method", optimum, &groups)?;
        }
        self.write_summary(comparison)?;
        self.write_chart(&groups)?;
        match optimum {
            Some(optimum) => gap::check_optimum(optimum, &groups),
            None => Ok(()),
        }
    }

    /// `compare.csv` (every run's curve) and `runs.csv` (every run's end and measures).
    fn write_tables<G: Grammar>(&self, comparison: &Comparison<G>) -> anyhow::Result<()> {
        let dir = &self.args.out;
        let done = &comparison.runs;
        let header =
            ["method", "run", "seed", "elapsed_s", "evaluations", "best"].map(str::to_owned);
        let rows = done.iter().flat_map(|f| {
            f.result.history.iter().map(|h| {
                vec![
                    f.method.name().to_owned(),
                    f.run.to_string(),
                    f.seed.to_string(),
                    format!("{:.4}", h.elapsed_s),
                    h.evaluations.to_string(),
                    h.best.to_string(),
                ]
            })
        });
        atomic_write(&dir.join("compare.csv"), &csv_bytes(&header, rows)?)?;
        let header: Vec<String> = ["method", "run", "seed", "evaluations", "best"]
            .into_iter()
            .chain(METRIC_COLUMNS)
            .map(str::to_owned)
            .collect();
        let rows = done.iter().map(|f| {
            [
                f.method.name().to_owned(),
                f.run.to_string(),
                f.seed.to_string(),
                f.result.evaluations.to_string(),
                f.result.best_fitness.to_string(),
            ]
            .into_iter()
            .chain(f.metrics.columns())
            .collect::<Vec<_>>()
        });
        atomic_write(&dir.join("runs.csv"), &csv_bytes(&header, rows)?)?;
        Ok(())
    }

    /// `summary.json`: the settings and each method's statistics.
    fn write_summary<G: Grammar>(&self, comparison: &Comparison<G>) -> anyhow::Result<()> {
        let summary = Summary {
            scene: &self.args.scene,
            seconds: self.args.seconds,
            base_seed: comparison.seeds[0],
            seed_rule: "run r uses base_seed + r",
            seeds: &comparison.seeds,
            backend: self.backend,
            complete: comparison.complete(),
            optimum: comparison.optimum,
            methods: comparison.summaries(),
        };
        atomic_write(
            &self.args.out.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )?;
        Ok(())
    }

    /// `compare.png`: each method's median best fitness against wall time, with its
    /// quartiles.
    fn write_chart(&self, groups: &[Group<'_>]) -> anyhow::Result<()> {
        let curves: Vec<_> = groups
            .iter()
            .map(|g| quartile_curve(&g.runs, |h| h.elapsed_s, self.args.seconds, GRID_POINTS))
            .collect();
        let spreads: Vec<Spread<'_>> = groups
            .iter()
            .zip(&curves)
            .map(|(g, q)| Spread {
                name: &g.name,
                colour: g.colour,
                centre: &q.median,
                low: &q.q1,
                high: &q.q3,
            })
            .collect();
        let scene = self.args.scene.file_stem().unwrap_or_default();
        let title = format!("{}: best fitness against time", scene.to_string_lossy());
        let titles = Titles {
            title: &title,
            x: "wall time (seconds)",
            y: "best fitness (median and quartiles over runs)",
        };
        let figure = plot::spreads(
            PLOT_SIZE,
            &titles,
            self.args.seconds,
            &spreads,
            YScale::Linear,
            gap::QUARTILES,
        )?;
        save_figure(&self.args.out.join("compare.png"), &figure)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn methods_keep_their_order_and_mistakes_are_named() {
        let names = |s: &[&str]| s.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(
            parse_methods(&names(&["rjmcmc", "ga"])).unwrap(),
            [Method::Rjmcmc, Method::Ga]
        );
        let err = parse_methods(&names(&["ga", "pso"]))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("`pso`") && err.contains("ga, smc, sosmc, rjmcmc, hybrid"),
            "{err}"
        );
        assert!(
            parse_methods(&names(&[""]))
                .unwrap_err()
                .to_string()
                .contains("empty")
        );
        assert!(
            parse_methods(&names(&["ga", "ga"]))
                .unwrap_err()
                .to_string()
                .contains("twice")
        );
    }
}
