//! A scene's search run from a program: the scene's scorers on the backend chosen, its
//! method with its settings, seed and budget, and a progress hook that sees every
//! generation and may stop the run. This is `shapegen run` without the files: a program
//! that wants the best model as values (the Python package, an editor's add-on) runs
//! this, and gets the same result as the tool for the same scene and seed.
//!
//! ```
//! use std::path::Path;
//! use shapegen::optimize::{Control, Snapshot};
//! use shapegen::scene::{Overrides, Scene};
//! use shapegen::search::Search;
//! use generators::spaceship::Spaceship;
//!
//! let overrides = Overrides { method: "ga".parse().ok(), evaluations: Some(600), ..Overrides::default() };
//! let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper/spaceship_volume.toml");
//! let scene = Scene::open(&path, &shapegen::registry::Registry::published(), &overrides)?;
//! let mut generations = 0;
//! let mut watch = |s: &Snapshot<'_, Spaceship>| {
//!     generations += 1;
//!     if s.generation == 2 { Control::Stop } else { Control::Continue }
//! };
//! let found = Search::new(&scene).run::<Spaceship>(&mut watch)?;
//! assert_eq!((generations, found.result.generations), (3, 2));
//! assert_eq!(found.result.stopped.name(), "interrupted");
//! assert!(found.result.best_fitness.is_finite());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::sync::atomic::AtomicBool;

use shapegen_runtime::Grammar;
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::optimize::{
    Best, Observer, OptimizeError, Optimizer, RunResult, Session, SessionError,
};

use crate::scene::{
    Backend, BackendChoice, MethodJob, Scene, SceneError, SceneEvaluator, SceneScorer,
};

/// Why a [`Search`] failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SearchError {
    /// The scene's scorers or backend could not be made.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The method could not start or go on.
    #[error(transparent)]
    Session(#[from] SessionError),
    /// The state to resume from is not a checkpoint of the scene's method.
    #[error("the checkpoint is not one of a {method} run: {source}")]
    Checkpoint {
        /// The scene's method.
        method: &'static str,
        /// What the reader said.
        source: serde_json::Error,
    },
}

impl From<OptimizeError> for SearchError {
    fn from(error: OptimizeError) -> Self {
        SearchError::Session(error.into())
    }
}

/// What a [`Search`] found.
#[derive(Debug)]
pub struct Found<G: Grammar> {
    /// The best model, its fitness, the counters, the history and why the run ended.
    pub result: RunResult<G>,
    /// The backend that counted, as the tool prints it (`CPU`, or the GPU's name).
    pub backend: String,
}

/// A search of a scene's goal; see the [module documentation](self).
#[derive(Clone, Copy, Debug)]
pub struct Search<'s> {
    scene: &'s Scene,
    choice: BackendChoice,
    gpu: Option<&'s GpuContext>,
    incremental: bool,
    stop: Option<&'s AtomicBool>,
    resume: Option<&'s str>,
}

/// Called with the search's state, as JSON, every second or so and at the end: what
/// [`Search::resume`] goes on from (the `search` of the tool's `checkpoint.json`).
pub type SaveHook<'h> =
    dyn FnMut(&str) -> Result<(), Box<dyn std::error::Error + Send + Sync>> + 'h;

impl<'s> Search<'s> {
    /// A search of `scene` with its method, settings, seed and budget, counting on the
    /// CPU, bred children counted from their parents' kept state (as the tool does by
    /// default).
    pub fn new(scene: &'s Scene) -> Self {
        Search {
            scene,
            choice: BackendChoice::Cpu,
            gpu: None,
            incremental: true,
            stop: None,
            resume: None,
        }
    }

    /// Goes on from `state`, the JSON a [`SaveHook`] was given (or the `search` of a
    /// `checkpoint.json` the tool wrote for this scene), to the scene's budget: the run
    /// ends as one that was never interrupted.
    pub fn resume(self, state: &'s str) -> Self {
        Search {
            resume: Some(state),
            ..self
        }
    }

    /// Counts on the backend `choice` picks, with `gpu` where it may use one
    /// ([`SceneScorer::on`]).
    pub fn backend(self, choice: BackendChoice, gpu: Option<&'s GpuContext>) -> Self {
        Search {
            choice,
            gpu,
            ..self
        }
    }

    /// Whether bred children are counted from their parents' kept state (the same
    /// results either way, more slowly without).
    pub fn incremental(self, incremental: bool) -> Self {
        Search {
            incremental,
            ..self
        }
    }

    /// Stops the run after the generation during which `flag` is set.
    pub fn stop_flag(self, flag: &'s AtomicBool) -> Self {
        Search {
            stop: Some(flag),
            ..self
        }
    }

    /// Runs the search to its budget with grammar `G`, the scene's generator;
    /// `observer` sees every generation (the initial population's included) and may
    /// stop the run ([`Control::Stop`](shapegen_runtime::optimize::Control::Stop)).
    ///
    /// # Errors
    /// [`SearchError::Scene`] when the scene is multi-objective (its front is searched
    /// by `shapegen run`), its meshes lack one `G` uses or the backend cannot count the
    /// method's batches; [`SearchError::Session`] when the method's settings cannot
    /// start or the counting fails.
    pub fn run<G: Grammar>(self, observer: &mut dyn Observer<G>) -> Result<Found<G>, SearchError> {
        self.run_saving(observer, None)
    }

    /// [`run`](Self::run), saving the search's state through `save` every second or so
    /// and at the end.
    ///
    /// # Errors
    /// Those of [`run`](Self::run); [`SearchError::Checkpoint`] when the state to resume
    /// from is not one of the scene's method; [`SearchError::Session`] when `save` fails.
    pub fn run_saving<G: Grammar>(
        self,
        observer: &mut dyn Observer<G>,
        save: Option<&mut SaveHook<'_>>,
    ) -> Result<Found<G>, SearchError> {
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let backend = scorer.on(self.choice, self.gpu)?;
        let mut evaluator = SceneEvaluator::new(&backend).with_incremental(self.incremental);
        let job = Job {
            search: self,
            backend: &backend,
            evaluator: &mut evaluator,
            observer,
            save,
        };
        let result = self.scene.optimizer.run::<G, _>(job)?;
        Ok(Found {
            result,
            backend: backend.describe().to_owned(),
        })
    }
}

/// The run, with the method's optimizer.
struct Job<'s, 'b, 'e, 'o, 'h, 'k, G> {
    search: Search<'s>,
    backend: &'b Backend<'b>,
    evaluator: &'e mut SceneEvaluator<'b>,
    observer: &'o mut dyn Observer<G>,
    save: Option<&'h mut SaveHook<'k>>,
}

impl<G: Grammar> MethodJob<G> for Job<'_, '_, '_, '_, '_, '_, G> {
    type Output = Result<RunResult<G>, SearchError>;

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output {
        self.backend.check_held(&O::genomes_held(&settings))?;
        let scene = self.search.scene;
        let optimizer = match self.search.resume {
            Some(json) => {
                let state =
                    serde_json::from_str(json).map_err(|source| SearchError::Checkpoint {
                        method: scene.optimizer.method().name(),
                        source,
                    })?;
                O::resume(state)?
            }
            None => O::new(settings, scene.limits, scene.optimizer.seed)?,
        };
        let mut session =
            Session::new(optimizer, scene.optimizer.budget()).on_progress(self.observer);
        if let Some(stop) = self.search.stop {
            session = session.stop_flag(stop);
        }
        if let Some(save) = self.save {
            session = session.on_save(move |s| {
                let json = serde_json::to_string(&s.state)?;
                save(&json)
            });
        }
        Ok(session.run(self.evaluator)?)
    }
}
