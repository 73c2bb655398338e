//! A multi-objective scene's search: `shapegen run` on a scene with `[[objective]]`
//! tables, without its files ([`FrontSearch`]).

use std::sync::atomic::AtomicBool;

use shapegen_runtime::Grammar;
use shapegen_runtime::optimize::multi::{Member, MultiGa, MultiObserver, MultiResult, Ranking};
use shapegen_runtime::optimize::{Optimizer, Sense, Session};

use crate::scene::{ObjectiveEvaluator, Scene};

use super::error::SearchError;

/// A multi-objective scene's search: `shapegen run` on a scene with `[[objective]]`
/// tables, without its files. The multi-objective GA breeds for the scene's
/// [`multi_settings`](Scene::multi_settings), each model measured by every objective
/// on the CPU, and finds the front of non-dominated models.
///
/// ```
/// use std::path::Path;
/// use shapegen::scene::{Overrides, Scene};
/// use shapegen::search::FrontSearch;
/// use generators::building::Building;
///
/// let overrides = Overrides {
///     generations: Some(2),
///     sets: vec!["optimizer.population=40".into()],
///     ..Overrides::default()
/// };
/// let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/building.toml");
/// let scene = Scene::open(&path, &shapegen::registry::Registry::published(), &overrides)?;
/// let found = FrontSearch::new(&scene).run::<Building>(&mut shapegen::optimize::Silent)?;
/// assert_eq!(found.objectives, ["top", "front", "facets"]);
/// assert_eq!((found.result.generations, found.result.history.len()), (2, 3));
/// let front = found.sorted();
/// assert!(!front.is_empty() && front.iter().all(|m| m.values.len() == 3));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FrontSearch<'s> {
    scene: &'s Scene,
    incremental: bool,
    stop: Option<&'s AtomicBool>,
}

/// What a [`FrontSearch`] found.
#[derive(Debug)]
pub struct FoundFront<G: Grammar> {
    /// The front (the archive of non-dominated models), the counters, the history and
    /// why the run ended.
    pub result: MultiResult<G>,
    /// The objectives' names, in the scene's order: that of every member's values.
    pub objectives: Vec<String>,
    /// Each objective's kind, as scene files name it (`top_match`, ...).
    pub kinds: Vec<&'static str>,
    /// Whether each objective is maximized or minimized.
    pub senses: Vec<Sense>,
    /// The ranking the selection used, as scene files name it.
    pub ranking: &'static str,
}

impl<G: Grammar> FoundFront<G> {
    /// The front in the order of the tool's files ([`sorted_front`]).
    pub fn sorted(&self) -> Vec<&Member<G>> {
        sorted_front(&self.result.front, &self.senses)
    }
}

impl<'s> FrontSearch<'s> {
    /// A search of `scene`'s front with its settings, seed and budget, bred children's
    /// projection objectives counted from their parents' kept state (as the tool does
    /// by default).
    pub fn new(scene: &'s Scene) -> Self {
        FrontSearch {
            scene,
            incremental: true,
            stop: None,
        }
    }

    /// Whether bred children's projection objectives are counted from their parents'
    /// kept state (the same results either way, more slowly without).
    pub fn incremental(self, incremental: bool) -> Self {
        FrontSearch {
            incremental,
            ..self
        }
    }

    /// Stops the run after the generation during which `flag` is set.
    pub fn stop_flag(self, flag: &'s AtomicBool) -> Self {
        FrontSearch {
            stop: Some(flag),
            ..self
        }
    }

    /// Runs the multi-objective GA to the scene's budget with grammar `G`, the scene's
    /// generator; `observer` sees every generation (the initial population's included)
    /// and may stop the run.
    ///
    /// # Errors
    /// [`SearchError::Scene`] when the scene has no objectives or they cannot be
    /// measured for `G`; [`SearchError::Session`] when the settings cannot start.
    pub fn run<G: Grammar>(
        self,
        observer: &mut dyn MultiObserver<G>,
    ) -> Result<FoundFront<G>, SearchError> {
        let scene = self.scene;
        let settings = scene.multi_settings().ok_or_else(|| {
            scene.invalid(
                "objective",
                "the scene has no [[objective]] tables: its single fitness is searched by \
                 a Search"
                    .into(),
            )
        })?;
        let ga = MultiGa::<G>::new(settings, scene.limits, scene.optimizer.seed)?;
        let ranking = ranking_name(&ga.settings().selection.ranking);
        let mut evaluator = ObjectiveEvaluator::new::<G>(scene)?.with_incremental(self.incremental);
        let mut session = Session::new(ga, scene.optimizer.budget()).on_progress(observer);
        if let Some(stop) = self.stop {
            session = session.stop_flag(stop);
        }
        let result = session.run(&mut evaluator)?;
        let set = evaluator.set();
        Ok(FoundFront {
            result,
            objectives: set.names().map(str::to_owned).collect(),
            kinds: set.entries().iter().map(|(_, o)| o.name()).collect(),
            senses: set.senses().to_vec(),
            ranking,
        })
    }
}

/// The ranking's name in scene files.
pub fn ranking_name(ranking: &Ranking) -> &'static str {
    match ranking {
        Ranking::WeightedSum { .. } => "weighted_sum",
        Ranking::Pareto => "pareto",
        Ranking::SummedRank => "summed_rank",
        Ranking::NormalizedSummedRank => "normalized_summed_rank",
    }
}

/// The front ordered by its first objective, best first (then by the others), so that
/// files and pictures read along the trade-off: the order of the tool's `front.csv`,
/// `front.genomes.json` and `front/model_NNN.glb`.
pub fn sorted_front<'a, G>(front: &'a [Member<G>], senses: &[Sense]) -> Vec<&'a Member<G>> {
    let mut order: Vec<&Member<G>> = front.iter().collect();
    order.sort_by(|a, b| {
        senses
            .iter()
            .zip(a.values.iter().zip(&b.values))
            .map(|(s, (&x, &y))| s.oriented(y).total_cmp(&s.oriented(x)))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    order
}
