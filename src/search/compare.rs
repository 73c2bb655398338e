//! Several methods on one scene, each run several times on shared seeds: `shapegen
//! compare` without its files ([`Compare`]).

use std::sync::atomic::AtomicBool;
use std::time::Duration;

use serde::Serialize;
use shapegen_runtime::Grammar;
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::optimize::{Budget, Control, RunResult, Snapshot, StopReason};

use crate::scene::{
    BackendChoice, Method, Metrics, OptimizerGoal, Scene, SceneEvaluator, SceneScorer,
};

use super::error::{CompareError, SearchError};
use super::single::Job;
use super::stats::{Reached, mean_std, quartiles, reached};

/// Several methods on one scene, each run several times on shared seeds: `shapegen
/// compare` without its files. The tool writes its tables (`compare.csv`, `runs.csv`,
/// `summary.json`) from the [`Comparison`] this makes; the Python package hands it over
/// as objects.
///
/// Each method takes its settings as a search of the scene with that method does
/// ([`Scene::optimizer_for`]: the scene's `[optimizer]` table over the paper's settings
/// for the method and the generator), with three changes that make the runs comparable:
/// - the wall-time budget is the comparison's, and the methods' own generation counts
///   (`generations`, `steps`, `iterations`) are not limits: a method that would have
///   finished its published generations goes on until the time is spent. SMC and SOSMC
///   then go on resampling their particles, which stop changing once every particle is
///   complete, so their best stays where it was;
/// - an evaluation budget (`optimizer.evaluations`) still stops a run, so that a
///   comparison can be made at equal evaluations, and exactly repeated;
/// - run `r` (from 0) of every method uses the seed `base + r`, where `base` is the
///   comparison's seed or the scene's `optimizer.seed`: in each run the methods start
///   from the same seed, and a search of the scene with method M and seed `base + r`
///   repeats a run.
///
/// Runs go run-major (run 0 of every method, then run 1, ...) so that slow drifts of the
/// machine's load hit every method alike; they share one backend and one evaluator.
///
/// ```
/// use std::path::Path;
/// use shapegen::scene::{Method, Overrides, Scene};
/// use shapegen::search::{Compare, Comparison, Search};
/// use generators::spaceship::Spaceship;
///
/// let overrides = Overrides { evaluations: Some(400), ..Overrides::default() };
/// let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper/spaceship_volume.toml");
/// let scene = Scene::open(&path, &shapegen::registry::Registry::published(), &overrides)?;
/// let compare = Compare::new(&scene, &[Method::Ga, Method::Random], 2, Some(7), None)?;
/// let done: Comparison<Spaceship> = compare.run(&mut ())?;
/// assert!(done.complete());
/// assert_eq!(done.runs.len(), 4);
/// assert_eq!((done.runs[1].method, done.runs[1].run, done.runs[1].seed), (Method::Random, 0, 7));
/// let ga = done.summary(Method::Ga);
/// assert_eq!(ga.finals.len(), 2);
/// assert!(ga.best >= ga.final_quartiles[2]);
/// // Run 1 of the GA is the search of the scene with the GA and seed 8.
/// let mut alone = scene.clone();
/// alone.optimizer = scene.optimizer_for(Method::Ga)?;
/// alone.optimizer.seed = 8;
/// let alone = Search::new(&alone).run::<Spaceship>(&mut shapegen::optimize::Silent)?;
/// assert_eq!(alone.result.best_fitness, done.runs[2].result.best_fitness);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Compare<'s> {
    scene: &'s Scene,
    methods: Vec<Method>,
    goals: Vec<OptimizerGoal>,
    seeds: Vec<u64>,
    seconds: Option<f64>,
    choice: BackendChoice,
    gpu: Option<&'s GpuContext>,
    incremental: bool,
    stop: Option<&'s AtomicBool>,
}

/// What sees a [`Compare`] as it goes; every method does nothing by default, and `()`
/// is an observer that sees nothing.
pub trait CompareObserver<G: Grammar> {
    /// Before the first run, with the backend that counts (`CPU`, or the GPU's name).
    fn started(&mut self, backend: &str) {
        let _ = backend;
    }

    /// After every generation of run `run` of `method` (the initial population's
    /// included); [`Control::Stop`] interrupts the run, which ends the comparison.
    fn generation(&mut self, method: Method, run: u64, snapshot: &Snapshot<'_, G>) -> Control {
        let _ = (method, run, snapshot);
        Control::Continue
    }

    /// After every finished run, with the comparison so far (the run last in
    /// [`Comparison::runs`]); [`Control::Stop`] ends the comparison there.
    fn finished(&mut self, so_far: &Comparison<G>) -> Control {
        let _ = so_far;
        Control::Continue
    }
}

impl<G: Grammar> CompareObserver<G> for () {}

/// One finished run of a [`Comparison`].
#[derive(Debug)]
pub struct ComparedRun<G: Grammar> {
    /// Its method.
    pub method: Method,
    /// Its number among the method's runs, from 0.
    pub run: u64,
    /// Its seed.
    pub seed: u64,
    /// The best model, its fitness, the counters, the history and why the run ended.
    pub result: RunResult<G>,
    /// The best model's measures against the scene's targets.
    pub metrics: Metrics,
}

/// What a [`Compare`] did: every finished run, in the order they ran, and each method's
/// [`summary`](Self::summary).
#[derive(Debug)]
pub struct Comparison<G: Grammar> {
    /// The methods, in the order they run.
    pub methods: Vec<Method>,
    /// The seed of each run, by run number: the base seed and those after it.
    pub seeds: Vec<u64>,
    /// The wall-time budget of every run, in seconds.
    pub seconds: Option<f64>,
    /// The backend that counted, as the tool prints it (`CPU`, or the GPU's name).
    pub backend: String,
    /// The scene's optimum (`fitness.optimum`), when it gives one.
    pub optimum: Option<f64>,
    /// The finished runs, run-major: run 0 of every method, then run 1, ...
    pub runs: Vec<ComparedRun<G>>,
    /// The run that was interrupted (the stop flag, or an observer), which ended the
    /// comparison and is not among [`runs`](Self::runs).
    pub interrupted: Option<(Method, u64)>,
}

/// One method's summary over its runs, as the tool's `summary.json` gives it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodSummary {
    /// The method's name.
    pub method: &'static str,
    /// Its finished runs.
    pub runs: usize,
    /// Mean over runs of each run's final best fitness.
    pub final_mean: f64,
    /// Their sample standard deviation (0 for one run).
    pub final_std: f64,
    /// Their first quartile, median and third quartile.
    pub final_quartiles: [f64; 3],
    /// The best fitness of all runs.
    pub best: f64,
    /// The run that found it.
    pub best_run: Option<u64>,
    /// Mean evaluations per run.
    pub evaluations: f64,
    /// Each run's final best fitness, by run.
    pub finals: Vec<f64>,
    /// Each run's best model's measures, by run.
    pub metrics: Vec<Metrics>,
    /// With an optimum: when the runs reached each fraction of it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub targets: Option<Vec<Reached>>,
}

impl<'s> Compare<'s> {
    /// A comparison of `methods` (in the order they run) on `scene`, `runs` runs each,
    /// run `r` on seed `seed + r` (the scene's seed by default), each run to `seconds`
    /// of wall time and the scene's evaluation budget, counted on the CPU, bred children
    /// counted from their parents' kept state.
    ///
    /// # Errors
    /// When no method or one twice is given, no run, a wall time that is not above 0,
    /// neither a wall time nor an evaluation budget for some method, seeds past
    /// `u64::MAX`, a multi-objective scene, or a method's goal the scene's
    /// `[optimizer]` table cannot give ([`CompareError::Scene`]).
    pub fn new(
        scene: &'s Scene,
        methods: &[Method],
        runs: u64,
        seed: Option<u64>,
        seconds: Option<f64>,
    ) -> Result<Self, CompareError> {
        if methods.is_empty() {
            return Err(CompareError::NoMethods);
        }
        let listed = |(i, m): &(usize, &Method)| methods[..*i].contains(m);
        if let Some((_, &twice)) = methods.iter().enumerate().find(listed) {
            return Err(CompareError::Twice(twice));
        }
        if runs == 0 {
            return Err(CompareError::NoRuns);
        }
        if let Some(s) = seconds.filter(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(CompareError::Seconds(s));
        }
        if scene.objectives.is_some() {
            return Err(CompareError::MultiObjective(scene.path.clone()));
        }
        let goals = methods
            .iter()
            .map(|&method| scene.optimizer_for(method))
            .collect::<Result<Vec<_>, _>>()?;
        if seconds.is_none()
            && let Some(goal) = goals.iter().find(|g| g.evaluations.is_none())
        {
            return Err(CompareError::Unbounded(goal.method()));
        }
        let base = seed.unwrap_or(scene.optimizer.seed);
        let seeds = (0..runs)
            .map(|r| base.checked_add(r))
            .collect::<Option<Vec<u64>>>()
            .ok_or(CompareError::Seeds { base, runs })?;
        Ok(Compare {
            scene,
            methods: methods.to_vec(),
            goals,
            seeds,
            seconds,
            choice: BackendChoice::Cpu,
            gpu: None,
            incremental: true,
            stop: None,
        })
    }

    /// Counts on the backend `choice` picks, with `gpu` where it may use one.
    pub fn backend(self, choice: BackendChoice, gpu: Option<&'s GpuContext>) -> Self {
        Compare {
            choice,
            gpu,
            ..self
        }
    }

    /// Whether bred children are counted from their parents' kept state (the same
    /// results either way, more slowly without).
    pub fn incremental(self, incremental: bool) -> Self {
        Compare {
            incremental,
            ..self
        }
    }

    /// Interrupts the run going on when `flag` is set, which ends the comparison.
    pub fn stop_flag(self, flag: &'s AtomicBool) -> Self {
        Compare {
            stop: Some(flag),
            ..self
        }
    }

    /// The methods, in the order they run.
    pub fn methods(&self) -> &[Method] {
        &self.methods
    }

    /// Each method's goal: its settings, and the scene's seed and budgets.
    pub fn goals(&self) -> &[OptimizerGoal] {
        &self.goals
    }

    /// The seed of each run, by run number.
    pub fn seeds(&self) -> &[u64] {
        &self.seeds
    }

    /// Runs every run of every method, run-major, with grammar `G` (the scene's
    /// generator), showing each generation and each finished run to `observer`.
    ///
    /// # Errors
    /// [`SearchError::Scene`] when the scene's scorers or backend cannot be made or the
    /// backend cannot count a method's batches; [`SearchError::Session`] when a method
    /// cannot start or the counting fails.
    pub fn run<G: Grammar>(
        &self,
        observer: &mut dyn CompareObserver<G>,
    ) -> Result<Comparison<G>, SearchError> {
        let scene = self.scene;
        let scorer = SceneScorer::new::<G>(scene)?;
        let backend = scorer.on(self.choice, self.gpu)?;
        for goal in &self.goals {
            backend.check_held(&scene.genomes_held::<G>(goal))?;
        }
        observer.started(backend.describe());
        let mut evaluator = SceneEvaluator::new(&backend).with_incremental(self.incremental);
        let meshes = scene
            .meshes
            .bind(G::GRAPH)
            .map_err(|err| scene.refused("meshes", err))?;
        let never = AtomicBool::new(false);
        let stop = self.stop.unwrap_or(&never);
        let mut done = Comparison {
            methods: self.methods.clone(),
            seeds: self.seeds.clone(),
            seconds: self.seconds,
            backend: backend.describe().to_owned(),
            optimum: scene.optimum,
            runs: Vec::with_capacity(self.seeds.len() * self.methods.len()),
            interrupted: None,
        };
        for (run, &seed) in (0u64..).zip(&self.seeds) {
            for (&method, goal) in self.methods.iter().zip(&self.goals) {
                let goal = OptimizerGoal {
                    seed,
                    ..goal.clone()
                };
                let budget = Budget {
                    generations: None,
                    evaluations: goal.evaluations,
                    wall_time: self.seconds.map(Duration::from_secs_f64),
                };
                let mut watch = |s: &Snapshot<'_, G>| observer.generation(method, run, s);
                let result = goal.run::<G, _>(Job {
                    scene,
                    goal: &goal,
                    budget,
                    stop: Some(stop),
                    resume: None,
                    backend: &backend,
                    evaluator: &mut evaluator,
                    observer: &mut watch,
                    save: None,
                })?;
                if result.stopped == StopReason::Observer {
                    done.interrupted = Some((method, run));
                    return Ok(done);
                }
                let metrics = Metrics::of_genome(scene, Some(&scorer), &meshes, &result.best);
                done.runs.push(ComparedRun {
                    method,
                    run,
                    seed,
                    result,
                    metrics,
                });
                if observer.finished(&done) == Control::Stop {
                    return Ok(done);
                }
            }
        }
        Ok(done)
    }
}

impl<G: Grammar> Comparison<G> {
    /// The runs planned: every method's runs.
    pub fn planned(&self) -> usize {
        self.seeds.len() * self.methods.len()
    }

    /// Whether every planned run finished.
    pub fn complete(&self) -> bool {
        self.runs.len() == self.planned()
    }

    /// The finished runs of `method`, by run number.
    pub fn runs_of(&self, method: Method) -> impl Iterator<Item = &ComparedRun<G>> {
        self.runs.iter().filter(move |r| r.method == method)
    }

    /// Each method's summary, in the order they ran.
    pub fn summaries(&self) -> Vec<MethodSummary> {
        self.methods.iter().map(|&m| self.summary(m)).collect()
    }

    /// `method`'s summary over its finished runs: the statistics of its final best
    /// fitnesses, its best run, its mean evaluations, its runs' measures and, for a
    /// scene with an optimum, when its runs reached fractions of it.
    pub fn summary(&self, method: Method) -> MethodSummary {
        let runs: Vec<&ComparedRun<G>> = self.runs_of(method).collect();
        let finals: Vec<f64> = runs.iter().map(|r| r.result.best_fitness).collect();
        let (final_mean, final_std) = mean_std(&finals);
        let best = runs
            .iter()
            .filter(|r| !r.result.best_fitness.is_nan())
            .max_by(|a, b| a.result.best_fitness.total_cmp(&b.result.best_fitness));
        let targets = self.optimum.map(|optimum| {
            let histories: Vec<_> = runs.iter().map(|r| r.result.history.as_slice()).collect();
            reached(optimum, &histories)
        });
        MethodSummary {
            method: method.name(),
            runs: runs.len(),
            final_mean,
            final_std,
            final_quartiles: quartiles(&finals),
            best: best.map_or(f64::NAN, |r| r.result.best_fitness),
            best_run: best.map(|r| r.run),
            evaluations: runs
                .iter()
                .map(|r| r.result.evaluations as f64)
                .sum::<f64>()
                / runs.len().max(1) as f64,
            finals,
            metrics: runs.iter().map(|r| r.metrics.clone()).collect(),
            targets,
        }
    }
}
