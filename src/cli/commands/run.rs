//! `shapegen run`: evolves models toward a scene's goal and writes what it found, kept
//! consistent on disk at every moment so that an interrupted run loses nothing.
//!
//! Every method takes one path. [`Scene::search`] calls `Run` back with the optimizer
//! that searches the scene: a method's of the `methods!` table, the GA's island model
//! (spread over the processes under `mpirun`), or the multi-objective GA for a scene with
//! objectives. `Run::drive` runs it to the budget, writing at every save the files of
//! what the method records with `run.json` and the checkpoint, in one batch, and at the
//! end `summary.json`; the record's own files are `cli/single.rs`'s (one fitness) or
//! `cli/front.rs`'s (a front).

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use shapegen::Grammar;
use shapegen::optimize::islands::{IslandGa, IslandGaSettings};
use shapegen::optimize::multi::{Front, MultiGaSettings};
use shapegen::optimize::{Best, Optimizer, Save, Session};
use shapegen::scene::{
    Method, MethodJob, ObjectiveEvaluator, Overrides, Scene, SceneEvaluator, SceneScorer, SearchJob,
};

use crate::registry::Entry;

use crate::cli::backend::{BackendArgs, check_batches};
use crate::cli::checkpoint::{Checkpoint, Head};
use crate::cli::files::Files;
use crate::cli::folder::{Existing, Folder, Kind};
use crate::cli::front;
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::interrupt;
use crate::cli::memory::{MemoryArgs, MemoryCheck, check_resumed};
use crate::cli::processes::Processes;
use crate::cli::record::{Counts, Scoring, Written};
use crate::cli::single;
use crate::cli::view::Live;

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
        let scene = self.scene;
        scene.search::<G, _>(&scene.optimizer, self)
    }
}

impl<G: Grammar> MethodJob<G> for Run<'_> {
    type Output = anyhow::Result<()>;

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> anyhow::Result<()> {
        let optimizer = self.start::<G, O>(settings)?;
        self.single(optimizer)
    }

    /// The island model, its islands spread over the processes where they exchange
    /// through MPI.
    fn run_islands(self, settings: IslandGaSettings) -> anyhow::Result<()> {
        let Some(exchange) = self.processes.exchange() else {
            return <Self as MethodJob<G>>::run::<IslandGa<G>>(self, settings);
        };
        let islands = match self.resumed::<G, IslandGa<G>>()? {
            Some(state) => IslandGa::resume_on(state, exchange)?,
            None => {
                let seed = self.scene.optimizer.seed;
                IslandGa::new_on(settings, self.scene.limits, seed, exchange)?
            }
        };
        self.single(islands)
    }
}

impl<G: Grammar> SearchJob<G> for Run<'_> {
    fn run_front<O>(self, settings: MultiGaSettings) -> anyhow::Result<()>
    where
        O: Optimizer<G, Record = Front<G>, Settings = MultiGaSettings>,
    {
        let optimizer = self.start::<G, O>(settings)?;
        self.front(optimizer)
    }
}

impl Run<'_> {
    /// Optimizer `O` with `settings`, or resumed from the checkpoint of the run to resume.
    fn start<G: Grammar, O: Optimizer<G>>(&self, settings: O::Settings) -> anyhow::Result<O> {
        Ok(match self.resumed::<G, O>()? {
            Some(state) => O::resume(state)?,
            None => O::new(settings, self.scene.limits, self.scene.optimizer.seed)?,
        })
    }

    /// The checkpoint of the run to resume, if it is one.
    /// The checkpoint's settings are checked against the memory before it is resumed.
    fn resumed<G: Grammar, O: Optimizer<G>>(&self) -> anyhow::Result<Option<O::State>> {
        let Some(dir) = &self.args.resume else {
            return Ok(None);
        };
        let backend = &self.args.backend;
        // A multi-objective run counts on the CPU.
        let (what, gpu) = match self.scene.objectives {
            Some(_) => ("a multi-objective run of this scene".to_owned(), false),
            None => {
                let method = self.scene.optimizer.method().name();
                (
                    format!("a {method} run of this scene"),
                    backend.may_use_gpu(),
                )
            }
        };
        let checkpoint: Checkpoint<O::State> = Checkpoint::load(dir, &what)?;
        check_resumed::<G, O>(
            self.scene,
            &checkpoint.search,
            backend.incremental(),
            gpu,
            self.args.memory,
        )?;
        Ok(Some(checkpoint.search))
    }

    /// Runs `optimizer`, of one fitness, scoring on the backend the flags choose.
    fn single<G: Grammar, O: Optimizer<G, Record = Best<G>>>(
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
        let count = self.processes.count();
        let outputs = single::Outputs::new::<G>(self.scene, &scorer, backend.describe(), count)?;
        if writes {
            outputs.targets(self.dir)?;
        }
        let progress = single::Progress::new(goal, writes);
        self.drive(optimizer, &mut evaluator, progress, outputs)
    }

    /// Runs `optimizer`, the multi-objective GA, measuring the scene's objectives.
    fn front<G, O>(self, optimizer: O) -> anyhow::Result<()>
    where
        G: Grammar,
        O: Optimizer<G, Record = Front<G>, Settings = MultiGaSettings>,
    {
        let mut evaluator = ObjectiveEvaluator::new::<G>(self.scene)?
            .with_incremental(self.args.backend.incremental());
        let ranking = &optimizer.settings().selection.ranking;
        let outputs = front::Outputs::new(self.scene, &evaluator, ranking);
        outputs.announce();
        let progress = outputs.progress();
        self.drive(optimizer, &mut evaluator, progress, outputs)
    }

    /// Runs `optimizer` to the scene's budget, scoring with `scoring`: at every save, the
    /// files of what it records (`written`), `run.json` and the checkpoint, in one batch;
    /// at the end, `summary.json` with `run.json`. Only one process writes (rank 0, when
    /// the run is spread over several).
    fn drive<G, O, S, W>(
        &self,
        optimizer: O,
        scoring: &mut S,
        mut progress: W::Progress,
        mut written: W,
    ) -> anyhow::Result<()>
    where
        G: Grammar,
        O: Optimizer<G>,
        S: Scoring<G, O::Record>,
        W: Written<G, O::Record>,
    {
        let writes = self.processes.writes();
        let stop = interrupt::flag();
        let result = Session::new(optimizer, self.scene.optimizer.budget())
            .stop_flag(&stop)
            .on_progress(W::observer(&mut progress))
            .on_save(|save| {
                if writes {
                    self.save(&mut written, save)
                } else {
                    Ok(())
                }
            })
            .run(scoring.evaluator())?;
        if !writes {
            return Ok(());
        }
        W::finish(&progress);
        let incremental = scoring.incremental();
        let note = incremental
            .as_ref()
            .map(|i| format!("{i}{}", W::INCREMENTAL_NOTE));
        let ended = written.end(self.dir, &result, incremental)?;
        let mut files = Files::new();
        files.write(&self.dir.join("summary.json"), &ended.summary)?;
        let live = self.live(W::counts(&result), false);
        files.write(&self.dir.join("run.json"), &live.to_bytes()?)?;
        files.commit()?;
        if let Some(note) = note {
            eprintln!("{note}");
        }
        println!("{}", ended.message);
        Ok(())
    }

    /// Writes a save: one batch that lands whole or not at all, so that the record's
    /// files, `run.json` and the checkpoint always describe the same moment of the run.
    fn save<G, O, W>(&self, written: &mut W, save: Save<'_, G, O>) -> anyhow::Result<()>
    where
        G: Grammar,
        O: Optimizer<G>,
        W: Written<G, O::Record>,
    {
        let mut files = Files::new();
        let result = save.result();
        written.save(&mut files, self.dir, &result)?;
        let live = self.live(W::counts(&result), true);
        files.write(&self.dir.join("run.json"), &live.to_bytes()?)?;
        Checkpoint {
            scene: self.scene_path.to_owned(),
            overrides: self.overrides.clone(),
            search: save.state,
        }
        .write(&mut files, self.dir)?;
        files.commit()?;
        written.saved(self.dir, &result)
    }

    /// `run.json` at a moment of the run with these `counts`.
    fn live(&self, counts: Counts, running: bool) -> Live<'_> {
        let goal = &self.scene.optimizer;
        Live {
            generator: &self.scene.generator,
            method: goal.method().name(),
            seed: goal.seed,
            generation: counts.generations,
            evaluations: counts.evaluations,
            elapsed_s: counts.elapsed_s,
            best_fitness: counts.best_fitness,
            front: counts.front,
            running,
        }
    }
}
