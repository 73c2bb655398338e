//! A scene's scorers for one grammar, and the backend that counts them: whole populations
//! counted at once, on the CPU or the GPU, and their counts turned into fitness.
//!
//! The kinds of scorer are listed once, in the `scorer_kinds!` invocation below: each
//! kind's table, resolved goal, CPU scorer (a runtime [`Scorer`], which counts and turns
//! counts into fitness), GPU path and counts, and the one arm that makes its scorer from
//! its goal. A scene holds a list of [`ScorerGoal`]s, its [`SceneScorer`] a list of
//! [`AnyScorer`]s and each model's [`SceneCounts`] a list of [`AnyCounts`], all in the
//! order of [`ScorerKind::ALL`] with at most one of each kind.

use serde::{Serialize, Serializer};
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::gpu::{GpuContext, GpuError, wgpu};
use shapegen_runtime::optimize::{EvaluateError, Evaluator, Held};
use shapegen_runtime::score::retained::{
    CellCounts, Overflow, RetainedScorer, Retention, RetentionStats,
};
use shapegen_runtime::score::silhouette::{
    GpuRetention, GpuSilhouetteScorer, SilhouetteCounts, SilhouetteScorer,
};
use shapegen_runtime::score::volume::{GpuVolumeScorer, VolumeCounts, VolumeScorer};
use shapegen_runtime::score::{InstanceBatch, LengthPenalty, Scorer, count_batch};
use shapegen_runtime::{Genome, Grammar, Instance, Site};

use super::{BackendError, Scene, SceneError, SilhouetteGoal, ValueError, VolumeGoal};

/// Declares the kinds of scorer, each once:
///
/// ```text
/// /// docs
/// Kind(table): Goal => CpuScorer, GpuScorer, Counts, |goal, meshes| make the CpuScorer;
/// ```
///
/// `table` names the kind's table in scene files and its key in `shapegen score`'s
/// output; `CpuScorer` implements [`Scorer`] with `Counts`, and `GpuScorer` has
/// `new(&GpuContext, &CpuScorer)` and `count_batch(&InstanceBatch, &mut [Counts])`;
/// making the `CpuScorer` fails with an error that a [`ValueError`] holds. It
/// expands into [`ScorerKind`], [`ScorerGoal`], [`AnyScorer`], [`AnyCounts`], the GPU
/// paths, their dispatch, and a typed accessor per kind on [`SceneScorer`]
/// (`scorer.volume()`, `scorer.silhouette()`, ...).
macro_rules! scorer_kinds {
    ($(
        $(#[doc = $doc:literal])*
        $kind:ident($name:ident): $goal:ty => $scorer:ident, $gpu:ident, $counts:ident,
            |$g:ident, $meshes:ident| $new:expr;
    )*) => {
        /// The kinds of scorer a scene may have, at most one of each.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum ScorerKind {
            $($(#[doc = $doc])* $kind,)*
        }

        impl ScorerKind {
            /// Every kind, in the order a scene holds them and sums their parts of the
            /// fitness.
            pub const ALL: &[ScorerKind] = &[$(ScorerKind::$kind),*];

            /// Its table in scene files, and its key in `shapegen score`'s output.
            pub fn name(self) -> &'static str {
                match self {
                    $(ScorerKind::$kind => stringify!($name),)*
                }
            }
        }

        /// One scorer's settings, resolved from its table.
        #[derive(Clone, Debug)]
        pub enum ScorerGoal {
            $($(#[doc = $doc])* $kind($goal),)*
        }

        /// One scorer of a scene, counting on the CPU.
        #[derive(Clone, Debug)]
        #[allow(clippy::large_enum_variant, reason = "a scene holds one of each kind")]
        pub enum AnyScorer {
            $($(#[doc = $doc])* $kind($scorer),)*
        }

        /// What one model covers for one scorer. It serializes as the kind's counts.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize)]
        #[serde(untagged)]
        pub enum AnyCounts {
            $($(#[doc = $doc])* $kind($counts),)*
        }

        /// One scorer's GPU path.
        enum AnyGpuScorer<'a> {
            $($kind($gpu<'a>),)*
        }

        /// One scorer's working memory.
        pub enum AnyScratch {
            $($(#[doc = $doc])* $kind(<$scorer as Scorer>::Scratch),)*
        }

        /// What one scorer keeps of one model, for incremental scoring.
        #[derive(Clone)]
        pub enum AnyState {
            $($(#[doc = $doc])* $kind(<$scorer as RetainedScorer>::State),)*
        }

        impl Scorer for AnyScorer {
            type Counts = AnyCounts;
            type Scratch = AnyScratch;

            fn scratch(&self) -> AnyScratch {
                match self {
                    $(AnyScorer::$kind(s) => AnyScratch::$kind(s.scratch()),)*
                }
            }

            fn count(&self, instances: &[Instance], scratch: &mut AnyScratch) -> AnyCounts {
                #[allow(unreachable_patterns)]
                match (self, scratch) {
                    $((AnyScorer::$kind(s), AnyScratch::$kind(scratch)) => {
                        AnyCounts::$kind(s.count(instances, scratch))
                    })*
                    _ => unreachable!("a scorer's scratch is of its own kind"),
                }
            }

            fn fitness(&self, counts: &AnyCounts) -> f64 {
                AnyScorer::fitness(self, counts)
            }
        }

        impl RetainedScorer for AnyScorer {
            type State = AnyState;

            fn count_retained(
                &self,
                instances: &[Instance],
                scratch: &mut AnyScratch,
            ) -> Result<AnyState, Overflow> {
                #[allow(unreachable_patterns)]
                match (self, scratch) {
                    $((AnyScorer::$kind(s), AnyScratch::$kind(scratch)) => {
                        s.count_retained(instances, scratch).map(AnyState::$kind)
                    })*
                    _ => unreachable!("a scorer's scratch is of its own kind"),
                }
            }

            fn update(
                &self,
                state: &mut AnyState,
                removed: &[Instance],
                added: &[Instance],
                scratch: &mut AnyScratch,
            ) -> Result<(), Overflow> {
                #[allow(unreachable_patterns)]
                match (self, state, scratch) {
                    $((AnyScorer::$kind(s), AnyState::$kind(state), AnyScratch::$kind(scratch)) => {
                        s.update(state, removed, added, scratch)
                    })*
                    _ => unreachable!("a scorer's state and scratch are of its own kind"),
                }
            }

            fn state_counts(&self, state: &AnyState) -> AnyCounts {
                #[allow(unreachable_patterns)]
                match (self, state) {
                    $((AnyScorer::$kind(s), AnyState::$kind(state)) => {
                        AnyCounts::$kind(s.state_counts(state))
                    })*
                    _ => unreachable!("a scorer's state is of its own kind"),
                }
            }

            fn visit_cells(&self, state: &AnyState, visit: &mut dyn FnMut(&CellCounts)) {
                #[allow(unreachable_patterns)]
                match (self, state) {
                    $((AnyScorer::$kind(s), AnyState::$kind(state)) => s.visit_cells(state, visit),)*
                    _ => unreachable!("a scorer's state is of its own kind"),
                }
            }

            fn visit_blocks(&self, state: &AnyState, visit: &mut dyn FnMut(usize, usize)) {
                #[allow(unreachable_patterns)]
                match (self, state) {
                    $((AnyScorer::$kind(s), AnyState::$kind(state)) => s.visit_blocks(state, visit),)*
                    _ => unreachable!("a scorer's state is of its own kind"),
                }
            }
        }

        impl ScorerGoal {
            /// Its kind.
            pub fn kind(&self) -> ScorerKind {
                match self {
                    $(ScorerGoal::$kind(_) => ScorerKind::$kind,)*
                }
            }

            /// Its scorer of models made of `meshes`, or why there is none.
            fn scorer(&self, meshes: &BoundMeshes) -> Result<AnyScorer, ValueError> {
                match self {
                    $(ScorerGoal::$kind($g) => {
                        let $meshes = meshes;
                        $new.map(AnyScorer::$kind).map_err(ValueError::from)
                    })*
                }
            }
        }

        impl AnyScorer {
            /// Its kind.
            pub fn kind(&self) -> ScorerKind {
                match self {
                    $(AnyScorer::$kind(_) => ScorerKind::$kind,)*
                }
            }

            /// The counts of a model that covers nothing.
            fn nothing(&self) -> AnyCounts {
                match self {
                    $(AnyScorer::$kind(_) => AnyCounts::$kind($counts::default()),)*
                }
            }

            /// Its part of the fitness of a model with `counts` ([`Scorer::fitness`]); 0
            /// for counts of another kind.
            pub fn fitness(&self, counts: &AnyCounts) -> f64 {
                #[allow(unreachable_patterns)]
                match (self, counts) {
                    $((AnyScorer::$kind(s), AnyCounts::$kind(c)) => s.fitness(c),)*
                    _ => 0.0,
                }
            }

            /// Its GPU path on `context`.
            fn gpu<'a>(&'a self, context: &'a GpuContext) -> Result<AnyGpuScorer<'a>, GpuError> {
                Ok(match self {
                    $(AnyScorer::$kind(s) => AnyGpuScorer::$kind($gpu::new(context, s)?),)*
                })
            }

            /// The most models one batch may hold on `gpu`.
            fn max_batch(gpu: &AnyGpuScorer<'_>) -> usize {
                match gpu {
                    $(AnyGpuScorer::$kind(g) => GpuCount::max_batch(g),)*
                }
            }

            /// Counts every model of `batch`, on `gpu` when given, and appends each
            /// model's counts to its slot of `out`.
            fn count(
                &self,
                gpu: Option<&AnyGpuScorer<'_>>,
                batch: &InstanceBatch,
                out: &mut [SceneCounts],
            ) -> Result<(), GpuError> {
                #[allow(unreachable_patterns)]
                match (self, gpu) {
                    $((AnyScorer::$kind(s), gpu) => {
                        let gpu = match gpu {
                            Some(AnyGpuScorer::$kind(g)) => Some(g),
                            _ => None,
                        };
                        count_parts(s, gpu, batch, out, AnyCounts::$kind)
                    })*
                }
            }
        }

        impl AnyCounts {
            /// Its kind.
            pub fn kind(&self) -> ScorerKind {
                match self {
                    $(AnyCounts::$kind(_) => ScorerKind::$kind,)*
                }
            }
        }

        $(
            impl GpuCount for $gpu<'_> {
                type Counts = $counts;

                fn count_batch(
                    &self,
                    batch: &InstanceBatch,
                    out: &mut [$counts],
                ) -> Result<(), GpuError> {
                    $gpu::count_batch(self, batch, out)
                }

                fn max_batch(&self) -> usize {
                    $gpu::max_batch(self)
                }
            }

            impl SceneScorer {
                #[doc = concat!("The `", stringify!($name), "` scorer, when the scene has one.")]
                pub fn $name(&self) -> Option<&$scorer> {
                    #[allow(unreachable_patterns)]
                    self.scorers.iter().find_map(|scorer| match scorer {
                        AnyScorer::$kind(scorer) => Some(scorer),
                        _ => None,
                    })
                }
            }
        )*
    };
}

scorer_kinds! {
    /// `[volume]`: weighted target volumes to fill or avoid on a voxel grid.
    Volume(volume): VolumeGoal => VolumeScorer, GpuVolumeScorer, VolumeCounts,
        |goal, meshes| {
            let scorer = VolumeScorer::new(goal.grid, &goal.targets, meshes, goal.form)?;
            match goal.shaping_radius {
                None => Ok(scorer),
                Some(radius) => scorer.shaped(radius),
            }
        };
    /// `[silhouette]`: target images seen through cameras.
    Silhouette(silhouette): SilhouetteGoal => SilhouetteScorer, GpuSilhouetteScorer, SilhouetteCounts,
        |goal, meshes| SilhouetteScorer::new(goal.targets.clone(), meshes, goal.form);
}

/// A GPU path's counting of whole batches, as [`count_batch`] counts on the CPU.
trait GpuCount {
    /// What it counts per model.
    type Counts;

    /// Counts every model of `batch` into `out`, one slot per model.
    fn count_batch(&self, batch: &InstanceBatch, out: &mut [Self::Counts]) -> Result<(), GpuError>;

    /// The most models one batch may hold.
    fn max_batch(&self) -> usize;
}

/// Counts every model of `batch` with `scorer`, on `gpu` when given, and appends each
/// model's counts, made [`AnyCounts`] by `any`, to its slot of `out`.
fn count_parts<S, G>(
    scorer: &S,
    gpu: Option<&G>,
    batch: &InstanceBatch,
    out: &mut [SceneCounts],
    any: fn(S::Counts) -> AnyCounts,
) -> Result<(), GpuError>
where
    S: Scorer<Counts: Default>,
    G: GpuCount<Counts = S::Counts>,
{
    let mut counts = vec![S::Counts::default(); batch.len()];
    match gpu {
        Some(gpu) => gpu.count_batch(batch, &mut counts)?,
        None => count_batch(scorer, batch, &mut counts),
    }
    for (slot, c) in out.iter_mut().zip(counts) {
        slot.parts.push(any(c));
    }
    Ok(())
}

/// Which backend counts: the CPU path always exists; the GPU path needs an adapter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BackendChoice {
    /// The GPU when a hardware adapter is found and supports the scene, else the CPU.
    #[default]
    Auto,
    /// The CPU, on all worker threads.
    Cpu,
    /// The GPU, any adapter (a software one too); an error when there is none or the
    /// scene cannot run on it.
    Gpu,
}

/// What one model of a scene covers: one [`AnyCounts`] per scorer, in the scorers'
/// order. It serializes as a map from each kind's [name](ScorerKind::name) to its
/// counts (`{"volume": {...}, "silhouette": [...]}`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneCounts {
    parts: Vec<AnyCounts>,
}

impl SceneCounts {
    /// Each scorer's counts, in the scorers' order.
    pub fn parts(&self) -> &[AnyCounts] {
        &self.parts
    }
}

impl Serialize for SceneCounts {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_map(self.parts.iter().map(|c| (c.kind().name(), c)))
    }
}

/// A scene's scorers for one grammar, counting on the CPU; [`on`](Self::on) gives the
/// backend that counts whole populations.
#[derive(Clone, Debug)]
pub struct SceneScorer {
    /// One per goal of the scene, in its order.
    scorers: Vec<AnyScorer>,
    /// The genome-length term.
    pub length: LengthPenalty,
    /// The site the scene's models grow on.
    site: Site,
}

impl Scene {
    /// The scene's scorers' settings, at most one of each kind, in the order of
    /// [`ScorerKind::ALL`]; empty for a scene with [`objectives`](Scene::objectives).
    pub fn scorers(&self) -> &[ScorerGoal] {
        &self.scorers
    }
}

impl SceneScorer {
    /// The scene's scorers for grammar `G`, which must be the scene's generator.
    ///
    /// # Errors
    /// [`SceneError::Value`] when the scene's meshes lack one the grammar uses or a
    /// target cannot be used, [`SceneError::Invalid`] when the scene's goal is
    /// [`objectives`](Scene::objectives).
    pub fn new<G: Grammar>(scene: &Scene) -> Result<SceneScorer, SceneError> {
        if scene.objectives.is_some() {
            return Err(scene.invalid(
                "objective",
                "the scene's goal is several objectives, which have no single fitness: \
                 search it with the multi-objective GA (`shapegen run` does) and measure \
                 it with an ObjectiveEvaluator"
                    .into(),
            ));
        }
        let meshes = scene
            .meshes
            .bind(G::GRAPH)
            .map_err(|err| scene.refused("meshes", err))?;
        let scorers = scene
            .scorers
            .iter()
            .map(|goal| {
                goal.scorer(&meshes)
                    .map_err(|cause| scene.refused(goal.kind().name(), cause))
            })
            .collect::<Result<_, _>>()?;
        Ok(SceneScorer {
            scorers,
            length: scene.length,
            site: scene.site.clone(),
        })
    }

    /// The site the scene's models grow on ([`Scene::site`]).
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// The scorers, one per goal of the scene, in its order.
    pub fn scorers(&self) -> &[AnyScorer] {
        &self.scorers
    }

    /// The backend `choice` asks for. `gpu` is the device, opened by the caller (`None`
    /// when there is none: [`BackendChoice::Auto`] then counts on the CPU). `Auto` passes
    /// over software adapters, which are slower than the CPU path.
    ///
    /// # Errors
    /// [`SceneError::Backend`] for [`BackendChoice::Gpu`]: [`BackendError::NoAdapter`]
    /// without a device, [`BackendError::Gpu`] when the scene cannot run on it.
    pub fn on<'a>(
        &'a self,
        choice: BackendChoice,
        gpu: Option<&'a GpuContext>,
    ) -> Result<Backend<'a>, SceneError> {
        let cpu = |why: &str| Backend {
            scorer: self,
            gpu: Vec::new(),
            description: format!("CPU{why}"),
        };
        let context = match (choice, gpu) {
            (BackendChoice::Cpu, _) => return Ok(cpu("")),
            (BackendChoice::Gpu, None) => return Err(BackendError::NoAdapter.into()),
            (BackendChoice::Auto, None) => return Ok(cpu(" (no GPU adapter)")),
            (BackendChoice::Auto, Some(context))
                if context.info.device_type == wgpu::DeviceType::Cpu =>
            {
                return Ok(cpu(&format!(" (passed over {})", context.describe())));
            }
            (_, Some(context)) => context,
        };
        let paths: Result<Vec<_>, _> = self.scorers.iter().map(|s| s.gpu(context)).collect();
        match paths {
            Ok(gpu) => Ok(Backend {
                scorer: self,
                gpu,
                description: format!("GPU: {}", context.describe()),
            }),
            Err(err) if choice == BackendChoice::Gpu => Err(BackendError::Gpu(err).into()),
            Err(err) => Ok(cpu(&format!(" ({err})"))),
        }
    }

    /// The fitness of a model of `genes` genes with these counts: the scorers' parts, less
    /// the genome-length term.
    pub fn fitness(&self, counts: &SceneCounts, genes: usize) -> f64 {
        self.fitness_of_parts(&counts.parts, genes)
    }

    /// [`fitness`](Self::fitness) of the counts `parts`, one per scorer in order.
    fn fitness_of_parts(&self, parts: &[AnyCounts], genes: usize) -> f64 {
        // Every kind adds its part, 0 when the scene lacks it, in the order of the kinds:
        // the same sum, to the bit (signed zeros too), whichever kinds a scene has.
        let part = |kind: &ScorerKind| {
            self.scorers
                .iter()
                .zip(parts)
                .find(|(scorer, _)| scorer.kind() == *kind)
                .map_or(0.0, |(scorer, counts)| scorer.fitness(counts))
        };
        let parts = ScorerKind::ALL.iter().map(part).reduce(|a, b| a + b);
        parts.unwrap_or(0.0) - self.length.apply(genes)
    }
}

/// A scene's scorers on the backend that counts them.
pub struct Backend<'a> {
    scorer: &'a SceneScorer,
    /// Each scorer's GPU path, in the scorers' order; empty on the CPU.
    gpu: Vec<AnyGpuScorer<'a>>,
    description: String,
}

impl Backend<'_> {
    /// The backend in words: `CPU (no GPU adapter)`, `GPU: NVIDIA H200
    /// (vulkan, discrete GPU)`, ...
    pub fn describe(&self) -> &str {
        &self.description
    }

    /// The scorers.
    pub fn scorer(&self) -> &SceneScorer {
        self.scorer
    }

    /// Checks, before a run allocates its populations, that the GPU can count `models`
    /// models at once, the most a batch of the run holds; `setting` names what sets their
    /// number, as `key = value`. Always passes on the CPU.
    ///
    /// # Errors
    /// [`SceneError::Backend`] with [`BackendError::Batch`]: the setting, the number and
    /// the device's bound.
    pub fn check_batch(&self, models: u64, setting: &str) -> Result<(), SceneError> {
        let max = self.gpu.iter().map(AnyScorer::max_batch).min();
        match max {
            Some(max) if models > max as u64 => Err(BackendError::Batch {
                setting: setting.to_owned(),
                models,
                max,
                backend: self.description.clone(),
            }
            .into()),
            _ => Ok(()),
        }
    }

    /// Checks [`check_batch`](Self::check_batch) for each batch a method holds at once
    /// ([`Optimizer::genomes_held`](shapegen_runtime::optimize::Optimizer::genomes_held)):
    /// the models a checkpoint saves of it, named by the setting that sets them.
    pub fn check_held(&self, held: &[Held]) -> Result<(), SceneError> {
        for h in held {
            self.check_batch(h.saved, &format!("{} = {}", h.setting, h.value))?;
        }
        Ok(())
    }

    /// Counts every model of `batch` into `out`, resized to the batch.
    ///
    /// # Errors
    /// When the GPU fails while counting.
    pub fn count(&self, batch: &InstanceBatch, out: &mut Vec<SceneCounts>) -> Result<(), GpuError> {
        out.resize_with(batch.len(), SceneCounts::default);
        for slot in out.iter_mut() {
            slot.parts.clear();
        }
        for (i, scorer) in self.scorer.scorers.iter().enumerate() {
            scorer.count(self.gpu.get(i), batch, out)?;
        }
        Ok(())
    }

    /// The GPU path of the silhouette scorer, when the scene has one and counts on the
    /// GPU.
    fn gpu_silhouette(&self) -> Option<&GpuSilhouetteScorer<'_>> {
        self.gpu.iter().find_map(|gpu| match gpu {
            AnyGpuScorer::Silhouette(g) => Some(g),
            _ => None,
        })
    }

    /// Counts the bred `children` (the models of `batch`) into `out` as
    /// [`count`](Self::count) does, but the silhouette scorer's counts from what
    /// `retention` kept of their `parents` (child `i` bred from `parents[from[i]]`).
    fn count_bred<G: Grammar>(
        &self,
        retention: &mut GpuRetention,
        children: &[Genome<G>],
        batch: &InstanceBatch,
        parents: &[Genome<G>],
        from: &[u32],
        out: &mut Vec<SceneCounts>,
    ) -> Result<(), GpuError> {
        out.resize_with(batch.len(), SceneCounts::default);
        for slot in out.iter_mut() {
            slot.parts.clear();
        }
        for (i, scorer) in self.scorer.scorers.iter().enumerate() {
            match self.gpu.get(i) {
                Some(AnyGpuScorer::Silhouette(gpu)) => {
                    let mut counts = vec![SilhouetteCounts::default(); batch.len()];
                    retention.count_bred(gpu, children, batch, parents, from, &mut counts)?;
                    for (slot, counts) in out.iter_mut().zip(counts) {
                        slot.parts.push(AnyCounts::Silhouette(counts));
                    }
                }
                gpu => scorer.count(gpu, batch, out)?,
            }
        }
        Ok(())
    }
}

/// Scores populations for an optimizer with a scene's scorers on a backend: derives
/// every genome into one reused batch, counts it, and subtracts the length term.
///
/// Children bred from a scored population ([`evaluate_bred`](Evaluator::evaluate_bred))
/// are counted incrementally, from what was kept of their parents, with exactly the
/// counts of counting them from nothing: on the CPU every scorer's ([`Retention`]), on
/// the GPU the silhouette scorer's, whose slots of per-pixel counts stay on the device
/// ([`GpuRetention`]; the GPU's volume scorer counts every model from nothing).
/// [`with_incremental(false)`](Self::with_incremental) counts every child from nothing.
pub struct SceneEvaluator<'a> {
    backend: &'a Backend<'a>,
    batch: InstanceBatch,
    counts: Vec<SceneCounts>,
    retention: Option<Retention<AnyScorer>>,
    gpu_retention: Option<GpuRetention>,
    parts: Vec<AnyCounts>,
}

impl<'a> SceneEvaluator<'a> {
    /// An evaluator counting on `backend`, incrementally where it can.
    pub fn new(backend: &'a Backend<'a>) -> Self {
        SceneEvaluator {
            backend,
            batch: InstanceBatch::new().on_site(backend.scorer().site().clone()),
            counts: Vec::new(),
            retention: None,
            gpu_retention: None,
            parts: Vec::new(),
        }
        .with_incremental(true)
    }

    /// Whether bred children are counted from their parents' kept state (the default).
    /// On the GPU, a scene without a silhouette scorer, or whose one model's per-pixel
    /// counts exceed the device's largest binding, counts every child from nothing.
    pub fn with_incremental(mut self, incremental: bool) -> Self {
        let gpu = !self.backend.gpu.is_empty();
        self.retention = (incremental && !gpu).then(Retention::new);
        self.gpu_retention = self
            .backend
            .gpu_silhouette()
            .filter(|_| incremental)
            .and_then(|scorer| GpuRetention::new(scorer).ok());
        self
    }

    /// Whether bred children are counted incrementally.
    pub fn incremental(&self) -> bool {
        self.retention.is_some() || self.gpu_retention.is_some()
    }

    /// How the bred children were counted so far, and the bytes of state kept now (on
    /// the GPU, the device memory of the slots); `None` when not counting
    /// incrementally.
    pub fn retention(&self) -> Option<(RetentionStats, usize)> {
        if let Some(gpu) = &self.gpu_retention {
            let bytes = usize::try_from(gpu.memory()).unwrap_or(usize::MAX);
            return Some((gpu.stats(), bytes));
        }
        let retention = self.retention.as_ref()?;
        Some((
            retention.stats(),
            retention.memory(self.backend.scorer.scorers()),
        ))
    }

    /// Writes the fitness of each of `genomes` from its counts.
    fn write_fitness<G: Grammar>(&self, genomes: &[Genome<G>], out: &mut [f64]) {
        let scorer = self.backend.scorer();
        for ((slot, counts), genome) in out.iter_mut().zip(&self.counts).zip(genomes) {
            *slot = scorer.fitness(counts, genome.len());
        }
    }
}

impl<G: Grammar> Evaluator<G> for SceneEvaluator<'_> {
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.batch.set_genomes(genomes);
        self.backend
            .count(&self.batch, &mut self.counts)
            .map_err(|err| EvaluateError(err.to_string()))?;
        self.write_fitness(genomes, out);
        Ok(())
    }

    fn evaluate_bred(
        &mut self,
        genomes: &[Genome<G>],
        parents: &[Genome<G>],
        from: &[u32],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        if let Some(retention) = &mut self.gpu_retention {
            self.batch.set_genomes(genomes);
            let (batch, counts) = (&self.batch, &mut self.counts);
            self.backend
                .count_bred(retention, genomes, batch, parents, from, counts)
                .map_err(|err| EvaluateError(err.to_string()))?;
            self.write_fitness(genomes, out);
            return Ok(());
        }
        if self.retention.is_none() {
            return self.evaluate(genomes, out);
        }
        self.batch.set_genomes(genomes);
        let scorer = self.backend.scorer();
        let scorers = scorer.scorers();
        let k = scorers.len();
        self.parts.clear();
        for _ in genomes {
            self.parts.extend(scorers.iter().map(AnyScorer::nothing));
        }
        let retention = self.retention.as_mut().expect("checked above");
        retention.count_bred(
            scorers,
            genomes,
            &self.batch,
            parents,
            from,
            &mut self.parts,
        );
        for (i, (slot, genome)) in out.iter_mut().zip(genomes).enumerate() {
            *slot = scorer.fitness_of_parts(&self.parts[i * k..(i + 1) * k], genome.len());
        }
        Ok(())
    }
}
