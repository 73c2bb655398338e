//! One search of a scene's goal to its budget, without the tool's files; see the
//! [module documentation](super).

use std::sync::atomic::AtomicBool;

use shapegen_runtime::Grammar;
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::optimize::{Best, Budget, Observer, Optimizer, RunResult, Session};

use crate::scene::{
    Backend, BackendChoice, MethodJob, OptimizerGoal, Scene, SceneEvaluator, SceneScorer,
};

use super::error::SearchError;

/// What a [`Search`] found.
#[derive(Debug)]
pub struct Found<G: Grammar> {
    /// The best model, its fitness, the counters, the history and why the run ended.
    pub result: RunResult<G>,
    /// The backend that counted, as the tool prints it (`CPU`, or the GPU's name).
    pub backend: String,
}

/// A search of a scene's goal; see the [module documentation](crate::search).
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
        let goal = &self.scene.optimizer;
        let job = Job {
            scene: self.scene,
            goal,
            budget: goal.budget(),
            stop: self.stop,
            resume: self.resume,
            backend: &backend,
            evaluator: &mut evaluator,
            observer,
            save,
        };
        let result = goal.run::<G, _>(job)?;
        Ok(Found {
            result,
            backend: backend.describe().to_owned(),
        })
    }
}

/// One run of `goal`'s method on `scene` to `budget`, from the start or from the saved
/// state `resume`: a [`Search`]'s run, or one of a [`Compare`](super::Compare)'s.
pub(super) struct Job<'s, 'b, 'e, 'o, 'h, 'k, G> {
    /// The scene searched.
    pub scene: &'s Scene,
    /// The method, its settings and seed.
    pub goal: &'s OptimizerGoal,
    /// Where the run stops.
    pub budget: Budget,
    /// Stops the run after the generation during which it is set.
    pub stop: Option<&'s AtomicBool>,
    /// The state to go on from, as JSON.
    pub resume: Option<&'s str>,
    /// What counts the models.
    pub backend: &'b Backend<'b>,
    /// What scores the populations.
    pub evaluator: &'e mut SceneEvaluator<'b>,
    /// Sees every generation.
    pub observer: &'o mut dyn Observer<G>,
    /// Saves the state.
    pub save: Option<&'h mut SaveHook<'k>>,
}

impl<G: Grammar> MethodJob<G> for Job<'_, '_, '_, '_, '_, '_, G> {
    type Output = Result<RunResult<G>, SearchError>;

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output {
        self.backend.check_held(&O::genomes_held(&settings))?;
        let optimizer = match self.resume {
            Some(json) => {
                let state =
                    serde_json::from_str(json).map_err(|source| SearchError::Checkpoint {
                        method: self.goal.method().name(),
                        source,
                    })?;
                O::resume(state)?
            }
            None => O::new(settings, self.scene.limits, self.goal.seed)?,
        };
        let mut session = Session::new(optimizer, self.budget).on_progress(self.observer);
        if let Some(stop) = self.stop {
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
