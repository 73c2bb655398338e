//! `shapegen run`: evolves models toward a scene's goal and writes what it found, kept
//! consistent on disk at every moment so that an interrupted run loses nothing.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use image::{GrayImage, ImageFormat, Luma, Rgb};
use serde::Serialize;
use shapegen::export::{Palette, Preview, glb_bytes, write_mtl, write_obj};
use shapegen::optimize::islands::{IslandGa, IslandGaSettings, IslandSettings};
use shapegen::optimize::{Best, Control, Optimizer, RunResult, Session, Snapshot};
use shapegen::scene::{
    Method, MethodJob, MethodSettings, Metrics, Overrides, Scene, SceneEvaluator, SceneScorer,
};
use shapegen::{Genome, Grammar, Limits, Site};

use crate::registry::Entry;

use crate::cli::backend::{BackendArgs, Incremental, check_batches};
use crate::cli::checkpoint::{Checkpoint, Head};
use crate::cli::files::{Files, csv_bytes};
use crate::cli::folder::{Existing, Folder, Kind};
use crate::cli::front::FrontRun;
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::interrupt;
use crate::cli::memory::{MemoryArgs, MemoryCheck, check_resumed, peak_rss};
use crate::cli::overlay::overlay;
use crate::cli::plot::{self, Line, Titles};
use crate::cli::processes::Processes;
use crate::cli::progress::ProgressLine;
use crate::cli::view::Live;
use crate::cli::voxels::voxel_surface_obj;

use super::view::ServeArgs;

/// Arguments of `shapegen run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (TOML); a resumed run takes its checkpoint's.
    #[arg(required_unless_present = "resume", conflicts_with = "resume")]
    scene: Option<PathBuf>,
    /// The search method (overrides `optimizer.method`).
    #[arg(long, help = crate::cli::method::method_help("The search method (overrides `optimizer.method`)"))]
    method: Option<Method>,
    /// Seed of the run (overrides `optimizer.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Wall-time budget in seconds (overrides `optimizer.seconds`).
    #[arg(long)]
    seconds: Option<f64>,
    /// Evaluation budget (overrides `optimizer.evaluations`); unlike a time budget, it
    /// makes the result independent of the machine's speed.
    #[arg(long)]
    evaluations: Option<u64>,
    /// Generations after the initial population: the GA's generations, SMC's steps,
    /// RJMCMC's iterations (overrides `optimizer.generations`).
    #[arg(long)]
    generations: Option<u64>,
    /// Runs the GA as an island model of this many populations, each of the scene's
    /// settings (overrides `islands.count`; `--set islands.migrants=M` and
    /// `islands.interval=G` say how many of each island's best go to the next on the
    /// ring, and how often). Under `mpirun` (a build with the `mpi` feature) the islands
    /// are spread over the processes, with the same result for any number of processes
    /// that divides them.
    #[arg(long, value_name = "K")]
    islands: Option<u32>,
    /// Overrides any scene value, e.g. `--set optimizer.population=200`; repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    #[command(flatten)]
    backend: BackendArgs,
    /// Folder to write into; created if missing. One that holds another run's outputs
    /// is refused: give `--resume DIR` to go on with that run, or `--force` to replace it.
    #[arg(long, required_unless_present = "resume")]
    out: Option<PathBuf>,
    /// Continue the run saved in this folder (its `checkpoint.json`) to its budget, and
    /// write there; ends with the same result as a run that was never interrupted.
    #[arg(long, value_name = "DIR", conflicts_with = "out")]
    resume: Option<PathBuf>,
    /// Replace the outputs of another run (or comparison, or study) in the --out folder:
    /// they are removed, and listed, before this run starts.
    #[arg(long, conflicts_with = "resume")]
    force: bool,
    #[command(flatten)]
    memory: MemoryArgs,
    /// Serve the run viewer's page for the output folder while the run goes on (as
    /// `shapegen view DIR` does), and after it until Ctrl-C.
    #[arg(long)]
    view: bool,
    #[command(flatten)]
    serve: ServeArgs,
}

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

/// Runs `shapegen run`.
pub fn run<J: Jobs>(args: &RunArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<Run<'a>> + From<MemoryCheck<'a>>,
{
    let given = Overrides {
        method: args.method,
        seed: args.seed,
        seconds: args.seconds,
        evaluations: args.evaluations,
        generations: args.generations,
        islands: args.islands,
        sets: args.sets.clone(),
    };
    anyhow::ensure!(
        args.view || (args.serve.port.is_none() && args.serve.listen.is_none()),
        "--port and --listen say where --view serves: give --view too"
    );
    let processes = Processes::start()?;
    let outcome = (|| {
        let (dir, scene_path, overrides) = match &args.resume {
            Some(dir) => {
                let head = Head::load(dir)?;
                (dir.clone(), head.scene, head.overrides.then(&given))
            }
            None => (
                args.out.clone().context("--out is required")?,
                args.scene.clone().context("the scene is required")?,
                given,
            ),
        };
        let scene = Scene::open(&scene_path, tool.registry(), &overrides)?;
        processes.check(&scene)?;
        tool.visit(
            &scene.generator,
            MemoryCheck::scene(&scene, 1, &args.backend, args.memory),
        )?;
        let existing = Existing::from_flags(args.force, args.resume.is_some());
        let _folder = processes
            .writes()
            .then(|| Folder::claim(&dir, Kind::Run, existing))
            .transpose()?;
        let viewer = (args.view && processes.writes())
            .then(|| args.serve.bind(&dir))
            .transpose()?;
        if let Some(viewer) = viewer {
            viewer.spawn();
        }
        tool.visit(
            &scene.generator,
            Run {
                args,
                scene: &scene,
                scene_path: &scene_path,
                overrides: &overrides,
                dir: &dir,
                processes: &processes,
            },
        )
    })();
    let outcome = processes.end(outcome);
    if args.view && outcome.is_ok() {
        eprintln!("the run is over; the viewer goes on serving until Ctrl-C");
        let stop = interrupt::flag();
        while !stop.load(std::sync::atomic::Ordering::SeqCst) {
            std::thread::sleep(std::time::Duration::from_millis(200));
        }
    }
    outcome
}

/// The body of `shapegen run`.
pub struct Run<'a> {
    args: &'a RunArgs,
    scene: &'a Scene,
    scene_path: &'a Path,
    overrides: &'a Overrides,
    dir: &'a Path,
    processes: &'a Processes,
}

impl Visit for Run<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        if self.scene.objectives.is_some() {
            return FrontRun {
                scene: self.scene,
                scene_path: self.scene_path,
                overrides: self.overrides,
                dir: self.dir,
                resume: self.args.resume.as_deref(),
                incremental: self.args.backend.incremental(),
                memory: self.args.memory,
            }
            .run::<G>();
        }
        if let (Some(islands), MethodSettings::Ga(ga)) =
            (self.scene.optimizer.islands, self.scene.optimizer.settings)
            && let Some(exchange) = self.processes.exchange()
        {
            let settings = IslandGaSettings { ga, islands };
            let islands = match self.resumed::<G, IslandGa<G>>()? {
                Some(state) => IslandGa::resume_on(state, exchange)?,
                None => {
                    let seed = self.scene.optimizer.seed;
                    IslandGa::new_on(settings, self.scene.limits, seed, exchange)?
                }
            };
            return self.drive(islands);
        }
        let scene = self.scene;
        scene.optimizer.run::<G, _>(self)
    }
}

impl<G: Grammar> MethodJob<G> for Run<'_> {
    type Output = anyhow::Result<()>;

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> anyhow::Result<()> {
        let optimizer = match self.resumed::<G, O>()? {
            Some(state) => O::resume(state)?,
            None => O::new(settings, self.scene.limits, self.scene.optimizer.seed)?,
        };
        self.drive(optimizer)
    }
}

impl Run<'_> {
    /// The checkpoint of the run to resume, if it is one.
    /// The checkpoint's settings are checked against the memory before it is resumed.
    fn resumed<G: Grammar, O: Optimizer<G>>(&self) -> anyhow::Result<Option<O::State>> {
        let Some(dir) = &self.args.resume else {
            return Ok(None);
        };
        let method = self.scene.optimizer.method().name();
        let checkpoint: Checkpoint<O::State> =
            Checkpoint::load(dir, &format!("a {method} run of this scene"))?;
        let backend = &self.args.backend;
        check_resumed::<G, O>(
            self.scene,
            &checkpoint.search,
            backend.incremental(),
            backend.may_use_gpu(),
            self.args.memory,
        )?;
        Ok(Some(checkpoint.search))
    }

    /// Runs `optimizer` to the scene's budget, writing the outputs as it goes (on rank 0
    /// only, when the run is spread over several processes).
    fn drive<G: Grammar, O: Optimizer<G, Record = Best<G>>>(
        self,
        optimizer: O,
    ) -> anyhow::Result<()> {
        let goal = &self.scene.optimizer;
        let writes = self.processes.writes();
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let gpu = self.args.backend.open();
        let backend = scorer.on(self.args.backend.choice(), gpu.as_ref())?;
        check_batches(&backend, &O::genomes_held(optimizer.settings()))?;
        if writes {
            eprintln!(
                "evolving {} with {}{} on {}",
                self.scene.generator,
                goal.method().name(),
                self.processes.describe(goal.islands),
                backend.describe()
            );
        }
        let mut evaluator =
            SceneEvaluator::new(&backend).with_incremental(self.args.backend.incremental());
        let stop = interrupt::flag();
        let outputs = Outputs::new::<G>(self.scene, &scorer)?;
        if writes {
            outputs.targets(self.dir)?;
        }
        let live = |result: &RunResult<G>, running: bool| Live {
            generator: &self.scene.generator,
            method: goal.method().name(),
            seed: goal.seed,
            generation: result.generations,
            evaluations: result.evaluations,
            elapsed_s: result.history.last().map_or(0.0, |h| h.elapsed_s),
            best_fitness: Some(result.best_fitness),
            front: None,
            running,
        };
        let mut progress = Progress::new(goal);
        let mut show = |s: &Snapshot<'_, G>| {
            if writes {
                progress.show(s);
            }
            Control::Continue
        };
        let mut best_written = f64::NAN;
        let result = Session::new(optimizer, goal.budget())
            .stop_flag(&stop)
            .on_progress(&mut show)
            .on_save(|save| {
                if !writes {
                    return Ok(());
                }
                // One save lands whole or not at all: the best model, the curves and
                // the checkpoint always describe the same moment of the run.
                let mut files = Files::new();
                let result = save.result();
                let new_best = best_written.to_bits() != result.best_fitness.to_bits();
                if new_best {
                    outputs.best(&mut files, self.dir, &result.best)?;
                }
                outputs.curves(&mut files, self.dir, &result)?;
                files.write(&self.dir.join("run.json"), &live(&result, true).to_bytes()?)?;
                Checkpoint {
                    scene: self.scene_path.to_owned(),
                    overrides: self.overrides.clone(),
                    search: save.state,
                }
                .write(&mut files, self.dir)?;
                files.commit()?;
                if new_best {
                    best_written = result.best_fitness;
                }
                Ok::<(), anyhow::Error>(())
            })
            .run(&mut evaluator)?;
        if !writes {
            return Ok(());
        }
        progress.finish();

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
            processes: self.processes.count(),
            backend: backend.describe(),
            genes: result.best.len(),
            instances: instances.len(),
            kept_limits: goal.settings.kept_limits(self.scene.limits),
            stopped: result.stopped.name(),
            incremental: evaluator.retention().map(Incremental::from),
            peak_rss_bytes: peak_rss(),
            metrics: Metrics::of(
                self.scene,
                Some(&scorer),
                &outputs.meshes,
                result.best.len(),
                &instances,
            ),
        };
        if let Some(incremental) = &summary.incremental {
            eprintln!("{incremental}");
        }
        let mut files = Files::new();
        files.write(
            &self.dir.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )?;
        files.write(
            &self.dir.join("run.json"),
            &live(&result, false).to_bytes()?,
        )?;
        files.commit()?;
        println!(
            "best fitness {:.4} after {} generations and {} evaluations ({}); wrote best.obj, \
             best.glb, best.png{}, best.genome.json, fitness.csv, fitness.png, fitness.svg and summary.json to {}",
            result.best_fitness,
            result.generations,
            result.evaluations,
            summary.stopped,
            if outputs.has_overlay() {
                ", overlay.png"
            } else {
                ""
            },
            self.dir.display()
        );
        Ok(())
    }
}

/// Writes the run's files.
struct Outputs<'a> {
    scorer: &'a SceneScorer,
    /// The scene's site, which the models grow on.
    site: &'a Site,
    /// The fitness chart's title: the generator and the method.
    title: String,
    meshes: shapegen::BoundMeshes,
    palette: Palette,
}

impl<'a> Outputs<'a> {
    fn new<G: Grammar>(scene: &'a Scene, scorer: &'a SceneScorer) -> anyhow::Result<Outputs<'a>> {
        Ok(Outputs {
            scorer,
            site: &scene.site,
            title: format!(
                "{} with {}: fitness per generation",
                scene.generator,
                scene.optimizer.method().name()
            ),
            meshes: scene.meshes.bind(G::GRAPH)?,
            palette: Palette::new(),
        })
    }

    fn has_overlay(&self) -> bool {
        self.scorer.silhouette().is_some()
    }

    /// What the viewer shows beside the model: `target.obj`, the surface of the volume
    /// target's voxels (weight above 0), and `target.png` with `camera.json`, the first
    /// silhouette target and the camera it is seen through.
    fn targets(&self, dir: &Path) -> anyhow::Result<()> {
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
        let (mut obj, mut mtl) = (Vec::new(), Vec::new());
        write_obj(
            &mut obj,
            "best.mtl",
            &instances,
            &self.meshes,
            &self.palette,
        )?;
        write_mtl(&mut mtl, &instances, &self.meshes, &self.palette)?;
        files.write(&dir.join("best.mtl"), &mtl)?;
        files.write(&dir.join("best.obj"), &obj)?;
        files.write(
            &dir.join("best.glb"),
            &glb_bytes(&instances, &self.meshes, &self.palette)?,
        )?;
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
        files.png(
            &dir.join("best.png"),
            &preview.render(&instances, &self.meshes, &self.palette)?,
        )?;
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
        let header = [
            "generation",
            "elapsed_s",
            "evaluations",
            "best",
            "mean",
            "std",
        ]
        .map(str::to_owned);
        let rows = result.history.iter().map(|h| {
            vec![
                h.generation.to_string(),
                format!("{:.3}", h.elapsed_s),
                h.evaluations.to_string(),
                h.best.to_string(),
                h.mean.to_string(),
                h.std.to_string(),
            ]
        });
        files.write(&dir.join("fitness.csv"), &csv_bytes(&header, rows)?)?;
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

/// The progress line after a generation: best and mean fitness, rate, time left.
struct Progress {
    line: ProgressLine,
    total: u64,
    seconds: Option<f64>,
}

impl Progress {
    fn new(goal: &shapegen::scene::OptimizerGoal) -> Progress {
        Progress {
            line: ProgressLine::new(),
            total: goal.generations(),
            seconds: goal.seconds,
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

    fn finish(&self) {
        self.line.finish();
    }
}
