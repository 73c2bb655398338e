//! One cell of a study (run `r` of one grid point), run exactly as its plan says,
//! wherever it runs: in a local sweep, or alone as `shapegen sweep --cell DIR I` in a
//! cluster's job. Its folder, `DIR/cells/NNNN/` (the cell's index), holds
//! - `result.json`: its row (grid values, run, seed, final best, evaluations,
//!   generations, seconds, why it stopped, its best model's measures);
//! - `fitness.csv`: its history, one row per generation (`generation`, `elapsed_s`,
//!   `evaluations`, `best`, `mean`, `std`; every number as it round-trips exactly);
//! - `best.genome.json`: the best genome found;
//! - `best.glb`: its model, for the run viewer (`shapegen view`).
//!
//! The folder is written as `cells/.NNNN.partial-PID` and renamed into place once
//! complete, so a cell's folder exists only whole: a study killed at any moment loses the
//! cells that were running, and nothing else.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use anyhow::Context;
use serde::{Deserialize, Deserializer, Serialize};
use shapegen::Grammar;
use shapegen::export::{Model, Palette, glb_bytes};
use shapegen::gpu::GpuContext;
use shapegen::optimize::{HistoryEntry, StopReason};
use shapegen::scene::{Metrics, Scene, SceneEvaluator, SceneScorer};

use super::plan::Plan;
use crate::cli::backend::check_batches;
use crate::cli::files::read;
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::history::{self, Elapsed};
use crate::cli::method::SessionRun;
use crate::registry::Entry;

/// The files of a cell's folder.
const RESULT: &str = "result.json";
const HISTORY: &str = "fitness.csv";
const GENOME: &str = "best.genome.json";
const MODEL: &str = "best.glb";

/// A cell's `result.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Record {
    /// The cell's index in its plan.
    pub index: u64,
    /// Its grid point: each swept key's value.
    pub point: BTreeMap<String, String>,
    /// Its run, from 0.
    pub run: u64,
    /// Its seed.
    pub seed: u64,
    /// The best fitness found (NaN, written `null`, when no model had a fitness).
    #[serde(deserialize_with = "nan_for_null")]
    pub best: f64,
    /// Fitness evaluations done.
    pub evaluations: u64,
    /// Generations (steps, iterations) done after the initial population.
    pub generations: u64,
    /// Wall time of the run, in seconds.
    pub seconds: f64,
    /// Why it stopped: "evaluations", "generations" or "time".
    pub stopped: String,
    /// Its best model's measures against the scene's targets.
    #[serde(default)]
    pub metrics: Option<Metrics>,
}

/// Reads a number, or `null` (how JSON writes NaN) as NaN.
fn nan_for_null<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// A finished cell: its row and its history.
#[derive(Clone, Debug, PartialEq)]
pub struct Finished {
    /// Its row.
    pub record: Record,
    /// Its history, one entry per generation.
    pub history: Vec<HistoryEntry>,
}

/// Cell `index`'s folder in study folder `dir`.
pub fn folder(plan: &Plan, dir: &Path, index: u64) -> PathBuf {
    dir.join("cells").join(name(plan, index))
}

/// Cell `index`'s folder name: its index with at least four digits, all cells of a plan
/// with as many.
fn name(plan: &Plan, index: u64) -> String {
    let width = (plan.cells().saturating_sub(1)).to_string().len().max(4);
    format!("{index:0width$}")
}

/// Runs cell `index` of `plan` (counting on `gpu` where the plan's backend may) and
/// writes its folder into `dir`. `None` when `stop` interrupted it: nothing is written.
pub fn run<J: Jobs>(
    plan: &Plan,
    dir: &Path,
    index: u64,
    tool: &Generators<J>,
    gpu: Option<&GpuContext>,
    stop: &AtomicBool,
) -> anyhow::Result<Option<Finished>>
where
    for<'a> J::Job<'a>: From<CellRun<'a>>,
{
    let cell = plan.cell(index);
    let scene = Scene::open(&plan.scene, tool.registry(), &plan.overrides(cell))?;
    let mut outcome = None;
    tool.visit(
        &scene.generator,
        CellRun {
            plan,
            scene: &scene,
            gpu,
            stop,
            outcome: &mut outcome,
        },
    )?;
    let outcome = outcome.expect("a cell's run leaves its outcome");
    if outcome.stopped == StopReason::Observer {
        return Ok(None);
    }
    let finished = Finished {
        record: Record {
            index,
            point: plan
                .grid
                .iter()
                .zip(plan.values(cell.point))
                .map(|(axis, v)| (axis.key.clone(), v.to_owned()))
                .collect(),
            run: cell.run,
            seed: cell.seed,
            best: outcome.best,
            evaluations: outcome.evaluations,
            generations: outcome.generations,
            seconds: outcome.history.last().map_or(0.0, |h| h.elapsed_s),
            stopped: outcome.stopped.name().to_owned(),
            metrics: Some(outcome.metrics),
        },
        history: outcome.history,
    };
    write(plan, dir, &finished, &outcome.genome, &outcome.model)?;
    Ok(Some(finished))
}

/// Writes `finished`'s folder: into a partial folder first, renamed into place when
/// whole. A folder already there (the same cell, finished by another process) is kept.
fn write(
    plan: &Plan,
    dir: &Path,
    finished: &Finished,
    genome: &str,
    model: &[u8],
) -> anyhow::Result<()> {
    let index = finished.record.index;
    let cells = dir.join("cells");
    let name = name(plan, index);
    // Partial folders of this cell left by killed processes.
    let prefix = format!(".{name}.partial-");
    if let Ok(entries) = std::fs::read_dir(&cells) {
        for entry in entries.flatten() {
            if entry.file_name().to_string_lossy().starts_with(&prefix) {
                let _ = std::fs::remove_dir_all(entry.path());
            }
        }
    }
    let partial = cells.join(format!("{prefix}{}", std::process::id()));
    std::fs::create_dir_all(&partial)
        .with_context(|| format!("cannot create `{}`", partial.display()))?;
    let write = |file: &str, bytes: &[u8]| {
        let path = partial.join(file);
        std::fs::write(&path, bytes).with_context(|| format!("cannot write `{}`", path.display()))
    };
    let written = (|| {
        write(
            RESULT,
            serde_json::to_string_pretty(&finished.record)?.as_bytes(),
        )?;
        write(HISTORY, &history::csv(&finished.history, Elapsed::Exact)?)?;
        write(GENOME, genome.as_bytes())?;
        write(MODEL, model)
    })();
    if let Err(err) = written {
        // A full disk or a file-size limit: no partial folder is left behind.
        let _ = std::fs::remove_dir_all(&partial);
        return Err(err);
    }
    let done = cells.join(&name);
    if let Err(err) = std::fs::rename(&partial, &done) {
        let _ = std::fs::remove_dir_all(&partial);
        anyhow::ensure!(
            done.join(RESULT).exists(),
            "cannot move cell {index} into `{}`: {err}",
            done.display()
        );
    }
    Ok(())
}

/// Cell `index` of `plan` as its folder in `dir` holds it; `None` when it is not done.
pub fn load(plan: &Plan, dir: &Path, index: u64) -> anyhow::Result<Option<Finished>> {
    let folder = folder(plan, dir, index);
    let path = folder.join(RESULT);
    if !path.exists() {
        return Ok(None);
    }
    let record: Record = serde_json::from_str(&read(&path)?)
        .with_context(|| format!("`{}` is not a cell's result", path.display()))?;
    let cell = plan.cell(index);
    anyhow::ensure!(
        (record.index, record.run, record.seed) == (index, cell.run, cell.seed),
        "`{}` holds cell {} (run {}, seed {}), not cell {index} of this plan (run {}, seed {})",
        path.display(),
        record.index,
        record.run,
        record.seed,
        cell.run,
        cell.seed
    );
    let history = history::read(&folder.join(HISTORY))?;
    Ok(Some(Finished { record, history }))
}

/// Every finished cell of `plan` in `dir`, by index.
pub fn load_all(plan: &Plan, dir: &Path) -> anyhow::Result<BTreeMap<u64, Finished>> {
    let mut done = BTreeMap::new();
    for index in 0..plan.cells() {
        if let Some(finished) = load(plan, dir, index)? {
            done.insert(index, finished);
        }
    }
    Ok(done)
}

/// What a cell's run ended with, whatever its grammar.
struct Outcome {
    best: f64,
    evaluations: u64,
    generations: u64,
    history: Vec<HistoryEntry>,
    stopped: StopReason,
    /// The best genome, as JSON.
    genome: String,
    /// Its measures.
    metrics: Metrics,
    /// Its model, as binary glTF.
    model: Vec<u8>,
}

/// The run of one cell, generic over the grammar of its scene's generator.
pub struct CellRun<'a> {
    plan: &'a Plan,
    scene: &'a Scene,
    gpu: Option<&'a GpuContext>,
    stop: &'a AtomicBool,
    outcome: &'a mut Option<Outcome>,
}

impl Visit for CellRun<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let backend = scorer.on(self.plan.backend.choice(), self.gpu)?;
        check_batches(
            &backend,
            &self.scene.genomes_held::<G>(&self.scene.optimizer),
        )?;
        let mut evaluator =
            SceneEvaluator::new(&backend).with_incremental(self.plan.backend.incremental());
        let goal = &self.scene.optimizer;
        let result = goal.run::<G, _>(SessionRun {
            seed: goal.seed,
            limits: self.scene.limits,
            budget: self.plan.budget.budget(),
            stop: self.stop,
            evaluator: &mut evaluator,
        })?;
        let meshes = self.scene.meshes.bind(G::GRAPH)?;
        let metrics = Metrics::of_genome(self.scene, Some(&scorer), &meshes, &result.best);
        let mut instances = Vec::new();
        result.best.derive_on(&self.scene.site, &mut instances);
        let model = glb_bytes(Model::new(&instances, &meshes, &Palette::new()))?;
        *self.outcome = Some(Outcome {
            best: result.best_fitness,
            evaluations: result.evaluations,
            generations: result.generations,
            history: result.history,
            stopped: result.stopped,
            genome: result.best.to_json(),
            metrics,
            model,
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histories_round_trip_to_the_bit() {
        let history = [
            HistoryEntry {
                generation: 0,
                elapsed_s: 0.012_345_678_9,
                evaluations: 150,
                best: 0.1 + 0.2,
                mean: -1.0 / 3.0,
                std: f64::NAN,
            },
            HistoryEntry {
                generation: 1,
                elapsed_s: 1e-9,
                evaluations: 270,
                best: f64::INFINITY,
                mean: 5e-324,
                std: 0.0,
            },
        ];
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(HISTORY);
        std::fs::write(&path, history::csv(&history, Elapsed::Exact).unwrap()).unwrap();
        let back = history::read(&path).unwrap();
        let bits = |h: &[HistoryEntry]| -> Vec<[u64; 6]> {
            h.iter()
                .map(|h| {
                    [
                        h.generation,
                        h.elapsed_s.to_bits(),
                        h.evaluations,
                        h.best.to_bits(),
                        h.mean.to_bits(),
                        h.std.to_bits(),
                    ]
                })
                .collect()
        };
        assert_eq!(bits(&back), bits(&history));
    }
}
