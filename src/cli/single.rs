//! `shapegen run` on a scene with one fitness: the best model (OBJ, GLB, a picture, the
//! overlay on the silhouette target, the genome) and the fitness curves, rewritten at
//! every save, and the summary at the end ([`Written`] for [`Best`]).

use std::path::Path;

use image::{GrayImage, ImageFormat, Luma, Rgb};
use serde::Serialize;
use shapegen::export::{Model, Palette, Preview, glb_bytes, write_mtl, write_obj};
use shapegen::optimize::islands::IslandSettings;
use shapegen::optimize::{Best, Control, Observer, RunResult, Snapshot};
use shapegen::scene::{Metrics, OptimizerGoal, Scene, SceneScorer};
use shapegen::{Genome, Grammar, Limits, Site};

use super::backend::Incremental;
use super::files::Files;
use super::history::{self, Elapsed};
use super::memory::peak_rss;
use super::overlay::overlay;
use super::plot::{self, Line, Titles};
use super::progress::ProgressLine;
use super::record::{Counts, Ended, Written};
use super::voxels::voxel_surface_obj;

/// `camera.json`: the first silhouette target's camera, for the viewer to look through.
#[derive(Serialize)]
struct TargetCamera {
    width: u32,
    height: u32,
    /// World to clip space, column by column.
    view_projection: [f32; 16],
}

/// `summary.json`.
#[derive(Serialize)]
struct Summary<'a> {
    best_fitness: f64,
    evaluations: u64,
    generations: u64,
    elapsed_s: f64,
    seed: u64,
    method: &'a str,
    /// The island model's settings, when the GA ran as one.
    #[serde(skip_serializing_if = "Option::is_none")]
    islands: Option<IslandSettings>,
    /// The processes the run was spread over (MPI ranks).
    processes: usize,
    backend: &'a str,
    genes: usize,
    instances: usize,
    /// The limits that every model the run scored kept, the best's included: the
    /// scene's, or fewer where the method follows a rule of the original's
    /// (`Settings::kept_limits`).
    kept_limits: Limits,
    stopped: &'a str,
    /// How bred children were counted; absent when every model was counted from nothing.
    #[serde(skip_serializing_if = "Option::is_none")]
    incremental: Option<Incremental>,
    /// The best model against the scene's targets in the literature's measures.
    metrics: Metrics,
    /// The most memory the process held resident up to the summary (Linux); absent
    /// where the system does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    peak_rss_bytes: Option<u64>,
}

/// Writes the files of a run on one fitness.
pub struct Outputs<'a> {
    scene: &'a Scene,
    scorer: &'a SceneScorer,
    /// The scene's site, which the models grow on.
    site: &'a Site,
    /// The fitness chart's title: the generator and the method.
    title: String,
    meshes: shapegen::BoundMeshes,
    palette: Palette,
    /// Where the models are counted, in words.
    backend: &'a str,
    /// The processes the run is spread over.
    processes: usize,
    /// The fitness of the best model written, to write it again only when it changes.
    best_written: f64,
}

impl<'a> Outputs<'a> {
    /// The writer of a run of `scene`, scored by `scorer` on `backend` (in words) over
    /// `processes` processes.
    pub fn new<G: Grammar>(
        scene: &'a Scene,
        scorer: &'a SceneScorer,
        backend: &'a str,
        processes: usize,
    ) -> anyhow::Result<Outputs<'a>> {
        Ok(Outputs {
            scene,
            scorer,
            site: &scene.site,
            title: format!(
                "{} with {}: fitness per generation",
                scene.generator,
                scene.optimizer.method().name()
            ),
            meshes: scene.meshes.bind(G::GRAPH)?,
            palette: Palette::new(),
            backend,
            processes,
            best_written: f64::NAN,
        })
    }

    fn has_overlay(&self) -> bool {
        self.scorer.silhouette().is_some()
    }

    /// What the viewer shows beside the model: `target.obj`, the surface of the volume
    /// target's voxels (weight above 0), and `target.png` with `camera.json`, the first
    /// silhouette target and the camera it is seen through.
    pub fn targets(&self, dir: &Path) -> anyhow::Result<()> {
        let mut files = Files::new();
        if let Some(volume) = self.scorer.volume() {
            let classes = volume.classes();
            let voxels = classes.voxels();
            let mut covered = vec![0u64; voxels.len().div_ceil(64)];
            for (v, &class) in voxels.iter().enumerate() {
                if classes.is_target(usize::from(class)) {
                    covered[v / 64] |= 1 << (v % 64);
                }
            }
            let (obj, _) = voxel_surface_obj(volume.grid(), &covered);
            files.write(&dir.join("target.obj"), obj.as_bytes())?;
        }
        if let Some(silhouette) = self.scorer.silhouette() {
            let t = &silhouette.targets()[0];
            let image = GrayImage::from_fn(t.width(), t.height(), |x, y| Luma([t.level(x, y)]));
            let mut png = std::io::Cursor::new(Vec::new());
            image.write_to(&mut png, ImageFormat::Png)?;
            files.write(&dir.join("target.png"), png.get_ref())?;
            let camera = TargetCamera {
                width: t.width(),
                height: t.height(),
                view_projection: t.view_projection().to_cols_array(),
            };
            files.write(
                &dir.join("camera.json"),
                serde_json::to_string_pretty(&camera)?.as_bytes(),
            )?;
        }
        files.commit()
    }

    /// The best model: OBJ with its MTL, GLB, a shaded picture, the overlay and the genome.
    fn best<G: Grammar>(
        &self,
        files: &mut Files,
        dir: &Path,
        best: &Genome<G>,
    ) -> anyhow::Result<()> {
        let mut instances = Vec::new();
        best.derive_on(self.site, &mut instances);
        let model = Model::new(&instances, &self.meshes, &self.palette);
        let (mut obj, mut mtl) = (Vec::new(), Vec::new());
        write_obj(&mut obj, "best.mtl", model)?;
        write_mtl(&mut mtl, model)?;
        files.write(&dir.join("best.mtl"), &mtl)?;
        files.write(&dir.join("best.obj"), &obj)?;
        files.write(&dir.join("best.glb"), &glb_bytes(model)?)?;
        files.write(&dir.join("best.genome.json"), best.to_json().as_bytes())?;
        let target = self.scorer.silhouette().map(|s| (s, &s.targets()[0]));
        let preview = match target {
            Some((_, t)) => Preview {
                view_projection: t.view_projection(),
                width: t.width(),
                height: t.height(),
            },
            None => Preview::framing(&instances, &self.meshes, 800, 600),
        };
        files.png(&dir.join("best.png"), &preview.render(model)?)?;
        if let Some((silhouette, t)) = target {
            let (w, h) = (t.width(), t.height());
            let mut mask = vec![false; w as usize * h as usize];
            silhouette.coverage_mask(0, &instances, &mut mask)?;
            let overlay = overlay(t, &mask);
            files.png(&dir.join("overlay.png"), &overlay)?;
        }
        Ok(())
    }

    /// `fitness.csv`, and `fitness.png` with `fitness.svg`: best (dark blue) and mean
    /// (orange) fitness against generations.
    fn curves<G>(
        &self,
        files: &mut Files,
        dir: &Path,
        result: &RunResult<G>,
    ) -> anyhow::Result<()> {
        let table = history::csv(&result.history, Elapsed::Milliseconds)?;
        files.write(&dir.join("fitness.csv"), &table)?;
        let generations: Vec<f64> = result.history.iter().map(|h| h.generation as f64).collect();
        let best: Vec<f64> = result.history.iter().map(|h| h.best).collect();
        let mean: Vec<f64> = result.history.iter().map(|h| h.mean).collect();
        let lines = [
            Line {
                name: "best",
                colour: Rgb([30, 60, 140]),
                values: &best,
            },
            Line {
                name: "mean",
                colour: Rgb([230, 140, 40]),
                values: &mean,
            },
        ];
        let titles = Titles {
            title: &self.title,
            x: "generations",
            y: "fitness",
        };
        let figure = plot::curves((640, 400), &titles, &generations, &lines)?;
        files.figure(&dir.join("fitness.png"), &figure)
    }
}

/// The progress line after a generation: best and mean fitness, rate, time left; shown
/// only by the process that writes.
pub struct Progress {
    line: ProgressLine,
    total: u64,
    seconds: Option<f64>,
    shown: bool,
}

impl Progress {
    /// The progress of a run of `goal`, shown if `shown`.
    pub fn new(goal: &OptimizerGoal, shown: bool) -> Progress {
        Progress {
            line: ProgressLine::new(),
            total: goal.generations(),
            seconds: goal.seconds,
            shown,
        }
    }

    fn show<G>(&mut self, s: &Snapshot<'_, G>) {
        // Both count from the start of the run, resumed parts included.
        let elapsed = s.elapsed.as_secs_f64();
        let rate = s.evaluations as f64 / elapsed.max(1e-9);
        let by_generations = (s.generation > 0).then(|| {
            elapsed / s.generation as f64 * self.total.saturating_sub(s.generation) as f64
        });
        let left = match (by_generations, self.seconds) {
            (Some(a), Some(b)) => a.min(b - elapsed),
            (a, b) => a.or(b.map(|b| b - elapsed)).unwrap_or(0.0),
        }
        .max(0.0);
        let line = format!(
            "generation {:>4}/{}  best {:>9.5}  mean {:>9.5}  {:>7.0} evaluations/s  {:>4.0} s left",
            s.generation, self.total, s.best_fitness, s.mean, rate, left
        );
        self.line.show(s.generation, &line);
    }
}

impl<G: Grammar> Observer<G> for Progress {
    fn observe(&mut self, s: &Snapshot<'_, G>) -> Control {
        if self.shown {
            self.show(s);
        }
        Control::Continue
    }
}

impl<G: Grammar> Written<G, Best<G>> for Outputs<'_> {
    type Progress = Progress;
    const INCREMENTAL_NOTE: &'static str = "";

    fn observer<'s>(progress: &'s mut Progress) -> &'s mut (dyn Observer<G> + 's)
    where
        Progress: 's,
    {
        progress
    }

    fn finish(progress: &Progress) {
        progress.line.finish();
    }

    fn counts(result: &RunResult<G>) -> Counts {
        Counts {
            generations: result.generations,
            evaluations: result.evaluations,
            elapsed_s: result.history.last().map_or(0.0, |h| h.elapsed_s),
            best_fitness: Some(result.best_fitness),
            front: None,
        }
    }

    /// The best model when it changed, and the curves.
    fn save(&self, files: &mut Files, dir: &Path, result: &RunResult<G>) -> anyhow::Result<()> {
        if self.best_written.to_bits() != result.best_fitness.to_bits() {
            self.best(files, dir, &result.best)?;
        }
        self.curves(files, dir, result)
    }

    fn saved(&mut self, _: &Path, result: &RunResult<G>) -> anyhow::Result<()> {
        self.best_written = result.best_fitness;
        Ok(())
    }

    fn end(
        &self,
        dir: &Path,
        result: &RunResult<G>,
        incremental: Option<Incremental>,
    ) -> anyhow::Result<Ended> {
        let goal = &self.scene.optimizer;
        let mut instances = Vec::new();
        result.best.derive_on(&self.scene.site, &mut instances);
        let summary = Summary {
            best_fitness: result.best_fitness,
            evaluations: result.evaluations,
            generations: result.generations,
            elapsed_s: result.history.last().map_or(0.0, |h| h.elapsed_s),
            seed: goal.seed,
            method: goal.method().name(),
            islands: goal.islands,
            processes: self.processes,
            backend: self.backend,
            genes: result.best.len(),
            instances: instances.len(),
            kept_limits: goal.settings.kept_limits(self.scene.limits),
            stopped: result.stopped.name(),
            incremental,
            peak_rss_bytes: peak_rss(),
            metrics: Metrics::of(
                self.scene,
                Some(self.scorer),
                &self.meshes,
                result.best.len(),
                &instances,
            ),
        };
        let message = format!(
            "best fitness {:.4} after {} generations and {} evaluations ({}); wrote best.obj, \
             best.glb, best.png{}, best.genome.json, fitness.csv, fitness.png, fitness.svg and summary.json to {}",
            result.best_fitness,
            result.generations,
            result.evaluations,
            summary.stopped,
            if self.has_overlay() {
                ", overlay.png"
            } else {
                ""
            },
            dir.display()
        );
        Ok(Ended {
            summary: serde_json::to_string_pretty(&summary)?.into_bytes(),
            message,
        })
    }
}
