//! `shapegen compare`: runs several search methods on one scene, each several times on
//! the same seeds and with the same wall-time budget, and writes their results side by
//! side: every run's history (`compare.csv`), every run's final best and its best
//! model's measures (`runs.csv`: size, IoU, Chamfer distance and F-score, see
//! [`Metrics::columns`]), a summary per method and a picture of the median curves.
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
use std::time::Duration;

use anyhow::Context;
use clap::Args;
use image::Rgb;
use serde::Serialize;
use shapegen::Grammar;
use shapegen::export::{Palette, glb_bytes};
use shapegen::optimize::{Budget, HistoryEntry, StopReason};
use shapegen::scene::{
    METRIC_COLUMNS, Method, Metrics, OptimizerGoal, Overrides, Scene, SceneEvaluator, SceneScorer,
};

use crate::cli::backend::{BackendArgs, check_batches};
use crate::cli::files::{atomic_write, csv_bytes, save_figure};
use crate::cli::folder::{Existing, Folder, Kind};
use crate::cli::gap::{self, Group, Reached};
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::interrupt;
use crate::cli::memory::{MemoryArgs, MemoryCheck};
use crate::cli::method::SessionRun;
use crate::cli::plot::{self, Spread, Titles, YScale};
use crate::cli::stats::{mean_std, quartile_curve, quartiles};
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
    let goals = methods
        .iter()
        .map(|&method| scene.optimizer_for(method))
        .collect::<Result<Vec<_>, _>>()?;
    let base = args.seed.unwrap_or(scene.optimizer.seed);
    let seeds = (0..args.runs)
        .map(|r| base.checked_add(r))
        .collect::<Option<Vec<u64>>>()
        .with_context(|| {
            format!(
                "--seed {base}: with {} runs the seeds would pass {}",
                args.runs,
                u64::MAX
            )
        })?;
    tool.visit(
        &scene.generator,
        MemoryCheck {
            scene: &scene,
            goals: &goals,
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
            methods: &methods,
            scene: &scene,
            goals: &goals,
            seeds: &seeds,
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
    methods: &'a [Method],
    scene: &'a Scene,
    /// Each method's goal.
    goals: &'a [OptimizerGoal],
    /// Seed of each run.
    seeds: &'a [u64],
}

/// One finished run.
struct Finished {
    method: Method,
    run: u64,
    seed: u64,
    best: f64,
    evaluations: u64,
    history: Vec<HistoryEntry>,
    /// Its best model's measures.
    metrics: Metrics,
}

impl Visit for Compare<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let gpu = self.args.backend.open();
        let backend = scorer.on(self.args.backend.choice(), gpu.as_ref())?;
        for goal in self.goals {
            check_batches(&backend, &self.scene.genomes_held::<G>(goal))?;
        }
        let total = self.seeds.len() * self.methods.len();
        eprintln!(
            "comparing {} on {}: {} runs of {} s",
            self.methods
                .iter()
                .map(|m| m.name())
                .collect::<Vec<_>>()
                .join(", "),
            backend.describe(),
            total,
            self.args.seconds
        );
        let mut evaluator =
            SceneEvaluator::new(&backend).with_incremental(self.args.backend.incremental());
        let stop = interrupt::flag();
        let mut done: Vec<Finished> = Vec::with_capacity(total);
        let (meshes, palette) = (self.scene.meshes.bind(G::GRAPH)?, Palette::new());
        let mut instances = Vec::new();
        let outputs = Outputs {
            args: self.args,
            methods: self.methods,
            seeds: self.seeds,
            backend: backend.describe(),
            optimum: self.scene.optimum,
        };
        for (run, &seed) in self.seeds.iter().enumerate() {
            for (&method, goal) in self.methods.iter().zip(self.goals) {
                let goal = OptimizerGoal {
                    seed,
                    ..goal.clone()
                };
                let budget = Budget {
                    generations: None,
                    evaluations: goal.evaluations,
                    wall_time: Some(Duration::from_secs_f64(self.args.seconds)),
                };
                let result = goal.run::<G, _>(SessionRun {
                    seed: goal.seed,
                    limits: self.scene.limits,
                    budget,
                    stop: &stop,
                    evaluator: &mut evaluator,
                })?;
                if result.stopped == StopReason::Observer {
                    outputs.write(&done)?;
                    anyhow::bail!(
                        "interrupted during run {run} of {}: wrote the {} complete runs of {total} to {}",
                        method.name(),
                        done.len(),
                        self.args.out.display()
                    );
                }
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
                result.best.derive_on(&self.scene.site, &mut instances);
                atomic_write(
                    &dir.join("best.glb"),
                    &glb_bytes(&instances, &meshes, &palette)?,
                )?;
                let elapsed = result.history.last().map_or(0.0, |h| h.elapsed_s);
                eprintln!(
                    "{:<6} run {run} (seed {seed}): best {:.5}  {} evaluations  {elapsed:.1} s  [{}/{total}]",
                    method.name(),
                    result.best_fitness,
                    result.evaluations,
                    done.len() + 1
                );
                let metrics = Metrics::of_genome(self.scene, Some(&scorer), &meshes, &result.best);
                done.push(Finished {
                    method,
                    run: run as u64,
                    seed,
                    best: result.best_fitness,
                    evaluations: result.evaluations,
                    history: result.history,
                    metrics,
                });
                outputs.write(&done)?;
            }
        }
        let gaps = if self.scene.optimum.is_some() {
            ", targets.csv, gap-time.png, gap-evaluations.png (each PNG with its SVG)"
        } else {
            ""
        };
        println!(
            "compared {} runs; wrote compare.csv, runs.csv, compare.png, summary.json{gaps} and runs/ to {}",
            done.len(),
            self.args.out.display()
        );
        Ok(())
    }
}

/// Writes `compare.csv`, `runs.csv`, `summary.json` and `compare.png` for the runs done
/// so far.
struct Outputs<'a> {
    args: &'a CompareArgs,
    methods: &'a [Method],
    seeds: &'a [u64],
    backend: &'a str,
    /// The scene's optimum, when it gives one.
    optimum: Option<f64>,
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

/// One method's part of `summary.json`.
#[derive(Serialize)]
struct MethodSummary {
    method: &'static str,
    runs: usize,
    /// Mean over runs of each run's final best fitness.
    final_mean: f64,
    /// Their sample standard deviation (0 for one run).
    final_std: f64,
    /// Their first quartile, median and third quartile.
    final_quartiles: [f64; 3],
    /// The best fitness of all runs.
    best: f64,
    /// The run that found it.
    best_run: Option<u64>,
    /// Mean evaluations per run.
    evaluations: f64,
    /// Each run's final best fitness, by run.
    finals: Vec<f64>,
    /// Each run's best model's measures, by run.
    metrics: Vec<Metrics>,
    /// With an optimum: when the runs reached each fraction of it.
    #[serde(skip_serializing_if = "Option::is_none")]
    targets: Option<Vec<Reached>>,
}

impl Outputs<'_> {
    fn write(&self, done: &[Finished]) -> anyhow::Result<()> {
        let dir = &self.args.out;
        let header =
            ["method", "run", "seed", "elapsed_s", "evaluations", "best"].map(str::to_owned);
        let rows = done.iter().flat_map(|f| {
            f.history.iter().map(|h| {
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
                f.evaluations.to_string(),
                f.best.to_string(),
            ]
            .into_iter()
            .chain(f.metrics.columns())
            .collect::<Vec<_>>()
        });
        atomic_write(&dir.join("runs.csv"), &csv_bytes(&header, rows)?)?;

        let groups: Vec<Group<'_>> = self
            .methods
            .iter()
            .map(|&m| Group {
                name: m.name().to_owned(),
                colour: Rgb(m.colour()),
                runs: done
                    .iter()
                    .filter(|f| f.method == m)
                    .map(|f| f.history.as_slice())
                    .collect(),
            })
            .collect();
        let mut methods: Vec<MethodSummary> =
            self.methods.iter().map(|&m| summarize(m, done)).collect();
        if let Some(optimum) = self.optimum {
            let reached = gap::write(dir, "method", optimum, &groups)?;
            for (summary, reached) in methods.iter_mut().zip(reached) {
                summary.targets = Some(reached);
            }
        }
        let summary = Summary {
            scene: &self.args.scene,
            seconds: self.args.seconds,
            base_seed: self.seeds[0],
            seed_rule: "run r uses base_seed + r",
            seeds: self.seeds,
            backend: self.backend,
            complete: done.len() == self.seeds.len() * self.methods.len(),
            optimum: self.optimum,
            methods,
        };
        atomic_write(
            &dir.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )?;

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
        save_figure(&dir.join("compare.png"), &figure)?;
        match self.optimum {
            Some(optimum) => gap::check_optimum(optimum, &groups),
            None => Ok(()),
        }
    }
}

/// `method`'s summary over its runs in `done`.
fn summarize(method: Method, done: &[Finished]) -> MethodSummary {
    let runs: Vec<&Finished> = done.iter().filter(|f| f.method == method).collect();
    let finals: Vec<f64> = runs.iter().map(|f| f.best).collect();
    let (final_mean, final_std) = mean_std(&finals);
    let best = runs
        .iter()
        .filter(|f| !f.best.is_nan())
        .max_by(|a, b| a.best.total_cmp(&b.best));
    MethodSummary {
        method: method.name(),
        runs: runs.len(),
        final_mean,
        final_std,
        final_quartiles: quartiles(&finals),
        best: best.map_or(f64::NAN, |f| f.best),
        best_run: best.map(|f| f.run),
        evaluations: runs.iter().map(|f| f.evaluations as f64).sum::<f64>()
            / runs.len().max(1) as f64,
        finals,
        metrics: runs.iter().map(|f| f.metrics.clone()).collect(),
        targets: None,
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
