//! `shapegen run` on a scene with `[[objective]]` tables, searched by the multi-objective
//! GA: the non-dominated front it finds written as models, a contact sheet, a CSV and
//! scatter plots, kept consistent on disk at every moment ([`Written`] for [`Front`]).

use std::path::Path;

use anyhow::Context;
use image::Rgb;
use serde::Serialize;
use shapegen::export::{ContactSheet, Model, Palette, glb_bytes};
use shapegen::genome::GenomeSet;
use shapegen::optimize::multi::{
    Front, Member, MultiObserver, MultiResult, MultiSnapshot, Ranking,
};
use shapegen::optimize::{Control, Sense};
use shapegen::scene::{Metrics, ObjectiveEvaluator, Scene};
use shapegen::score::objective::{ObjectiveSet, Surface};
use shapegen::search::{ranking_name, sorted_front as sorted};
use shapegen::{BoundMeshes, Grammar, Instance, Site};

use super::backend::Incremental;
use super::files::{Files, csv_bytes, save_figure, save_png};
use super::memory::peak_rss;
use super::overlay::{projection_overlay, projections};
use super::plot::{self, Titles};
use super::progress::ProgressLine;
use super::record::{Counts, Ended, Written};

/// Most models drawn on the contact sheet; a larger front is shown evenly thinned.
const SHEET_MODELS: usize = 100;
/// Columns of the contact sheet.
const SHEET_COLUMNS: usize = 10;
/// Side of one contact-sheet picture, in pixels.
const SHEET_CELL: u32 = 200;
/// The colour of the front's points in the scatter charts.
const FRONT: Rgb<u8> = Rgb([30, 60, 140]);

/// One objective in `summary.json`.
#[derive(Serialize)]
struct ObjectiveSummary<'a> {
    name: &'a str,
    kind: &'a str,
    sense: Sense,
    /// The best value in the front.
    best: f64,
    /// The measures of the front's model with that value, against the scene's targets.
    #[serde(skip_serializing_if = "Option::is_none")]
    metrics: Option<Metrics>,
}

/// `summary.json` of a multi-objective run.
#[derive(Serialize)]
struct Summary<'a> {
    front: usize,
    evaluations: u64,
    generations: u64,
    elapsed_s: f64,
    seed: u64,
    method: &'a str,
    ranking: &'a str,
    objectives: Vec<ObjectiveSummary<'a>>,
    stopped: &'a str,
    /// How bred children's projection objectives were counted; absent when every
    /// objective of every model was measured in full.
    #[serde(skip_serializing_if = "Option::is_none")]
    incremental: Option<Incremental>,
    /// The most memory the process held resident up to the summary (Linux); absent
    /// where the system does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    peak_rss_bytes: Option<u64>,
}

impl<'a> Outputs<'a> {
    /// The writer of a run of `scene` scored by `evaluator`, its models ranked by
    /// `ranking`.
    pub fn new(scene: &'a Scene, evaluator: &ObjectiveEvaluator<'a>, ranking: &Ranking) -> Self {
        Outputs {
            scene,
            set: evaluator.set(),
            site: &scene.site,
            meshes: evaluator.meshes().clone(),
            palette: Palette::new(),
            ranking: ranking_name(ranking),
        }
    }

    /// Says what the run searches.
    pub fn announce(&self) {
        let names: Vec<&str> = self.set.names().collect();
        eprintln!(
            "evolving {} against {} objective{} ({}) with the multi-objective GA, {} ranking, \
             on the CPU",
            self.scene.generator,
            self.set.len(),
            if self.set.len() == 1 { "" } else { "s" },
            names.join(", "),
            self.ranking,
        );
    }

    /// The progress line of the run.
    pub fn progress(&self) -> Progress<'a> {
        Progress {
            line: ProgressLine::new(),
            names: self.set.names().collect(),
            total: self.scene.optimizer.generations(),
        }
    }

    /// `summary.json`'s objectives: each one's best value in `front`, with the measures
    /// of the model that has it.
    fn objectives<G: Grammar>(&self, front: &[&Member<G>]) -> Vec<ObjectiveSummary<'a>> {
        let set = self.set;
        set.entries()
            .iter()
            .zip(set.senses())
            .enumerate()
            .map(|(i, ((name, objective), &sense))| {
                let best = best_by(front, i, sense);
                ObjectiveSummary {
                    name,
                    kind: objective.name(),
                    sense,
                    best: best.map_or(f64::NAN, |m| m.values[i]),
                    metrics: best
                        .map(|m| Metrics::of_genome(self.scene, None, &self.meshes, &m.genome)),
                }
            })
            .collect()
    }
}

/// The progress line after a generation: the front's size and each objective's best.
pub struct Progress<'a> {
    line: ProgressLine,
    names: Vec<&'a str>,
    total: u64,
}

impl<G: Grammar> MultiObserver<G> for Progress<'_> {
    fn observe(&mut self, s: &MultiSnapshot<'_, G>) -> Control {
        self.line
            .show(s.generation, &progress(s, &self.names, self.total));
        Control::Continue
    }
}

impl<'a, G: Grammar> Written<G, Front<G>> for Outputs<'a> {
    type Progress = Progress<'a>;
    const INCREMENTAL_NOTE: &'static str =
        " (the projection objectives; the others measured in full)";

    fn observer<'s>(progress: &'s mut Progress<'a>) -> &'s mut (dyn MultiObserver<G> + 's)
    where
        Progress<'a>: 's,
    {
        progress
    }

    fn finish(progress: &Progress<'a>) {
        progress.line.finish();
    }

    fn counts(result: &MultiResult<G>) -> Counts {
        Counts {
            generations: result.generations,
            evaluations: result.evaluations,
            elapsed_s: result.history.last().map_or(0.0, |h| h.elapsed_s),
            best_fitness: None,
            front: Some(result.front.len()),
        }
    }

    /// The front's tables and its models.
    fn save(&self, files: &mut Files, dir: &Path, result: &MultiResult<G>) -> anyhow::Result<()> {
        self.table(files, dir, result)?;
        let front = sorted(&result.front, self.set.senses());
        self.models(files, dir, &front)
    }

    fn saved(&mut self, dir: &Path, result: &MultiResult<G>) -> anyhow::Result<()> {
        remove_stale_models(dir, result.front.len())
    }

    /// The contact sheet, the scatter charts and the overlays (the session's last save
    /// wrote the front's table and models).
    fn end(
        &self,
        dir: &Path,
        result: &MultiResult<G>,
        incremental: Option<Incremental>,
    ) -> anyhow::Result<Ended> {
        let front = sorted(&result.front, self.set.senses());
        self.sheet(dir, &front)?;
        self.scatters(dir, &front)?;
        self.overlays(dir, &front)?;
        let goal = &self.scene.optimizer;
        let stopped = result.stopped.name();
        let summary = Summary {
            front: front.len(),
            evaluations: result.evaluations,
            generations: result.generations,
            elapsed_s: result.history.last().map_or(0.0, |h| h.elapsed_s),
            seed: goal.seed,
            method: goal.method().name(),
            ranking: self.ranking,
            objectives: self.objectives(&front),
            stopped,
            incremental,
            peak_rss_bytes: peak_rss(),
        };
        let message = format!(
            "{} non-dominated models after {} generations and {} evaluations ({stopped}); wrote \
             front/ (one .glb each), front.csv, front.genomes.json, contact_sheet.png, \
             scatter_*.png with their SVGs, history.csv and summary.json to {}",
            front.len(),
            result.generations,
            result.evaluations,
            dir.display()
        );
        Ok(Ended {
            summary: serde_json::to_string_pretty(&summary)?.into_bytes(),
            message,
        })
    }
}

/// Removes the models of an earlier, larger front: those numbered `len` and above.
fn remove_stale_models(dir: &Path, len: usize) -> anyhow::Result<()> {
    let folder = dir.join("front");
    for entry in std::fs::read_dir(&folder)? {
        let path = entry?.path();
        let stale = path
            .file_stem()
            .and_then(|s| s.to_str())
            .and_then(|s| s.strip_prefix("model_"))
            .and_then(|n| n.parse::<usize>().ok())
            .is_some_and(|n| n >= len);
        if stale {
            std::fs::remove_file(&path)
                .with_context(|| format!("cannot remove `{}`", path.display()))?;
        }
    }
    Ok(())
}

/// The member of `front` best by objective `i` (the first of equals), if any.
fn best_by<'a, G>(front: &[&'a Member<G>], i: usize, sense: Sense) -> Option<&'a Member<G>> {
    front.iter().copied().reduce(|a, b| {
        if sense.better(b.values[i], a.values[i]) {
            b
        } else {
            a
        }
    })
}

/// The progress line after a generation: the front's size and each objective's best.
fn progress<G>(s: &MultiSnapshot<'_, G>, names: &[&str], total: u64) -> String {
    let elapsed = s.elapsed.as_secs_f64();
    let best: Vec<String> = names
        .iter()
        .zip(s.best)
        .map(|(name, v)| format!("{name} {v:.4}"))
        .collect();
    format!(
        "generation {:>4}/{}  front {:>4}  best {}  {:>6.0} evaluations/s",
        s.generation,
        total,
        s.front.len(),
        best.join("  "),
        s.evaluations as f64 / elapsed.max(1e-9)
    )
}

/// Writes the files of a multi-objective run.
pub struct Outputs<'a> {
    scene: &'a Scene,
    set: &'a ObjectiveSet,
    /// The scene's site, which the models grow on.
    site: &'a Site,
    meshes: BoundMeshes,
    palette: Palette,
    /// The ranking's name in scene files.
    ranking: &'static str,
}

impl Outputs<'_> {
    /// `front.csv`, `front.genomes.json` and `history.csv`: cheap enough to keep current
    /// while the run goes on, so that an interrupted run keeps its front.
    fn table<G: Grammar>(
        &self,
        files: &mut Files,
        dir: &Path,
        result: &MultiResult<G>,
    ) -> anyhow::Result<()> {
        let front = sorted(&result.front, self.set.senses());
        let names: Vec<&str> = self.set.names().collect();
        let header: Vec<String> = ["model", "genes"]
            .into_iter()
            .chain(names.iter().copied())
            .map(str::to_owned)
            .collect();
        let rows = front.iter().enumerate().map(|(i, member)| {
            [i.to_string(), member.genome.len().to_string()]
                .into_iter()
                .chain(member.values.iter().map(f64::to_string))
                .collect::<Vec<_>>()
        });
        files.write(&dir.join("front.csv"), &csv_bytes(&header, rows)?)?;
        let genomes = GenomeSet::new(front.iter().map(|m| m.genome.clone()).collect());
        files.write(
            &dir.join("front.genomes.json"),
            genomes.to_json().as_bytes(),
        )?;
        let header: Vec<String> = ["generation", "elapsed_s", "evaluations", "front"]
            .into_iter()
            .map(str::to_owned)
            .chain(names.iter().map(|n| format!("best_{n}")))
            .collect();
        let rows = result.history.iter().map(|h| {
            [
                h.generation.to_string(),
                format!("{:.3}", h.elapsed_s),
                h.evaluations.to_string(),
                h.front.to_string(),
            ]
            .into_iter()
            .chain(h.best.iter().map(f64::to_string))
            .collect::<Vec<_>>()
        });
        files.write(&dir.join("history.csv"), &csv_bytes(&header, rows)?)
    }

    /// `front/model_NNN.glb`, numbered as in `front.csv`, kept current while the run
    /// goes on so that the viewer shows any point of the front.
    fn models<G: Grammar>(
        &self,
        files: &mut Files,
        dir: &Path,
        front: &[&Member<G>],
    ) -> anyhow::Result<()> {
        let folder = dir.join("front");
        std::fs::create_dir_all(&folder)
            .with_context(|| format!("cannot create `{}`", folder.display()))?;
        let mut instances = Vec::new();
        for (i, member) in front.iter().enumerate() {
            member.genome.derive_on(self.site, &mut instances);
            files.write(
                &folder.join(format!("model_{i:03}.glb")),
                &glb_bytes(Model::new(&instances, &self.meshes, &self.palette))?,
            )?;
        }
        Ok(())
    }

    /// `contact_sheet.png`: shaded previews of the front (at most [`SHEET_MODELS`],
    /// evenly thinned), all through one camera framing every model shown, each with its
    /// number in `front.csv`.
    fn sheet<G: Grammar>(&self, dir: &Path, front: &[&Member<G>]) -> anyhow::Result<()> {
        let step = front.len().div_ceil(SHEET_MODELS).max(1);
        let shown: Vec<(usize, Vec<Instance>)> = front
            .iter()
            .enumerate()
            .step_by(step)
            .map(|(i, m)| {
                let mut instances = Vec::new();
                m.genome.derive_on(self.site, &mut instances);
                (i, instances)
            })
            .collect();
        let models: Vec<&[Instance]> = shown.iter().map(|(_, v)| v.as_slice()).collect();
        let sheet = ContactSheet {
            cell: SHEET_CELL,
            columns: SHEET_COLUMNS,
        }
        .render(&models, &self.meshes, &self.palette, |k, cell| {
            plot::label(cell, &shown[k].0.to_string())
        })?;
        save_png(&dir.join("contact_sheet.png"), &sheet)
    }

    /// `scatter_A_B.png` with `scatter_A_B.svg` for every pair of objectives: the front's
    /// values, A across and B up.
    fn scatters<G>(&self, dir: &Path, front: &[&Member<G>]) -> anyhow::Result<()> {
        let names: Vec<&str> = self.set.names().collect();
        for a in 0..names.len() {
            for b in a + 1..names.len() {
                let points: Vec<(f64, f64)> =
                    front.iter().map(|m| (m.values[a], m.values[b])).collect();
                let title = format!("Multi-objective front: {} against {}", names[b], names[a]);
                let titles = Titles {
                    title: &title,
                    x: names[a],
                    y: names[b],
                };
                let name = format!("front members ({})", points.len());
                let figure = plot::scatter((640, 480), &titles, &points, FRONT, &name)?;
                save_figure(
                    &dir.join(format!("scatter_{}_{}.png", names[a], names[b])),
                    &figure,
                )?;
            }
        }
        Ok(())
    }

    /// `overlay_NAME.png` for every projection objective: the target and the front's
    /// best model for that objective (target alone blue, model alone red, both green).
    fn overlays<G: Grammar>(&self, dir: &Path, front: &[&Member<G>]) -> anyhow::Result<()> {
        let mut instances = Vec::new();
        for (name, projection) in projections(self.set) {
            let i = self
                .set
                .names()
                .position(|n| n == name)
                .context("a projection of the set")?;
            let Some(best) = best_by(front, i, self.set.senses()[i]) else {
                continue;
            };
            best.genome.derive_on(self.site, &mut instances);
            let surface = Surface::from_instances(&instances, &self.meshes);
            save_png(
                &dir.join(format!("overlay_{name}.png")),
                &projection_overlay(projection, &surface),
            )?;
        }
        Ok(())
    }
}
