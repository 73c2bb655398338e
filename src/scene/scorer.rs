//! The kinds of scorer a scene may have, listed once in the `scorer_kinds!` invocation
//! below, one row each naming the kind and its file of `scorer/`, which implements
//! [`SceneScorerKind`]:
//! its table, resolved goal, memory estimate, CPU scorer (a runtime [`Scorer`], which
//! counts and turns counts into fitness), optional GPU path and counts. A scene holds a
//! list of [`ScorerGoal`]s, its [`SceneScorer`] a list of [`AnyScorer`]s and each model's
//! [`SceneCounts`] a list of [`AnyCounts`], all in the order of [`ScorerKind::ALL`] with
//! at most one of each kind. Making a scene's scorers and counting them on a backend is
//! `evaluate.rs`'s.
//!
//! ```
//! use shapegen::scene::{Scene, ScorerKind};
//!
//! let names: Vec<&str> = ScorerKind::ALL.iter().map(|k| k.name()).collect();
//! assert_eq!(&names[..2], ["volume", "silhouette"]);
//! let scene = Scene::load("scenes/spaceship_fill.toml")?;
//! assert_eq!(scene.scorers()[0].kind(), ScorerKind::Volume);
//! assert!(scene.scorers()[0].volume().is_some());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use serde::{Serialize, Serializer};
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::gpu::{GpuContext, GpuError};
use shapegen_runtime::optimize::Bred;
use shapegen_runtime::score::retained::{CellCounts, Overflow, RetainedScorer};
use shapegen_runtime::score::silhouette::GpuRetention;
use shapegen_runtime::score::{InstanceBatch, LengthPenalty, Scorer, count_batch};
use shapegen_runtime::{Grammar, Instance, Site};

use super::error::ValueError;
use super::scorer_kind::{GpuCount, SceneScorerKind, ScorerMemory};

/// Declares the kinds of scorer, each once, after a `$` (which the macro passes on to the
/// macro it defines). Its enums are `#[non_exhaustive]`: a kind is added by its row,
/// and matches outside the crate have an arm for the kinds they do not name.
///
/// ```text
/// /// docs
/// Kind(table);
/// ```
///
/// `table` names the kind's table in scene files, its key in `shapegen score`'s output
/// and its module, the file `scorer/table.rs`, which defines `Kind` and implements
/// [`SceneScorerKind`] for it. It expands into the module, [`ScorerKind`],
/// [`ScorerGoal`], [`AnyScorer`], [`AnyCounts`], the GPU paths, their dispatch, a typed
/// accessor per kind on [`ScorerGoal`] and [`SceneScorer`] (`scorer.volume()`, ...), and
/// `scene_file!`, which gives the scene file's struct a field per kind and its resolution.
macro_rules! scorer_kinds {
    ($d:tt $(
        $(#[doc = $doc:literal])*
        $kind:ident($name:ident);
    )*) => {
        $($(#[doc = $doc])* pub(super) mod $name;)*

        /// The kinds of scorer a scene may have, at most one of each.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        #[non_exhaustive]
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
        #[non_exhaustive]
        pub enum ScorerGoal {
            $($(#[doc = $doc])* $kind(<crate::scene::scorer::$name::$kind as SceneScorerKind>::Goal),)*
        }

        /// One scorer of a scene, counting on the CPU.
        #[derive(Clone, Debug)]
        #[non_exhaustive]
        #[allow(clippy::large_enum_variant, reason = "a scene holds one of each kind")]
        pub enum AnyScorer {
            $($(#[doc = $doc])* $kind(<crate::scene::scorer::$name::$kind as SceneScorerKind>::Scorer),)*
        }

        /// What one model covers for one scorer. It serializes as the kind's counts.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize)]
        #[non_exhaustive]
        #[serde(untagged)]
        pub enum AnyCounts {
            $($(#[doc = $doc])* $kind(<crate::scene::scorer::$name::$kind as SceneScorerKind>::Counts),)*
        }

        /// One scorer's GPU path.
        pub(super) enum AnyGpuScorer<'a> {
            $($kind(<crate::scene::scorer::$name::$kind as SceneScorerKind>::Gpu<'a>),)*
        }

        /// One scorer's working memory.
        pub enum AnyScratch {
            $($(#[doc = $doc])* $kind(<<crate::scene::scorer::$name::$kind as SceneScorerKind>::Scorer as Scorer>::Scratch),)*
        }

        /// What one scorer keeps of one model, for incremental scoring.
        #[derive(Clone)]
        pub enum AnyState {
            $($(#[doc = $doc])* $kind(<<crate::scene::scorer::$name::$kind as SceneScorerKind>::Scorer as RetainedScorer>::State),)*
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
            pub(super) fn scorer(&self, meshes: &BoundMeshes) -> Result<AnyScorer, ValueError> {
                match self {
                    $(ScorerGoal::$kind(goal) => <crate::scene::scorer::$name::$kind>::make(goal, meshes).map(AnyScorer::$kind),)*
                }
            }

            /// What its scorer takes of memory, with `threads` worker threads.
            pub(super) fn memory(&self, threads: usize) -> ScorerMemory {
                match self {
                    $(ScorerGoal::$kind(goal) => <crate::scene::scorer::$name::$kind>::memory(goal, threads),)*
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
            pub(super) fn nothing(&self) -> AnyCounts {
                match self {
                    $(AnyScorer::$kind(_) => AnyCounts::$kind(Default::default()),)*
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

            /// Its GPU path on `context`; `None` for a kind counted on the CPU on every
            /// backend.
            pub(super) fn gpu<'a>(
                &'a self,
                context: &'a GpuContext,
            ) -> Result<Option<AnyGpuScorer<'a>>, GpuError> {
                match self {
                    $(AnyScorer::$kind(s) => {
                        <crate::scene::scorer::$name::$kind>::gpu(s, context).transpose().map(|g| g.map(AnyGpuScorer::$kind))
                    })*
                }
            }

            /// Counts every model of `batch`, on `gpu` when given, and appends each
            /// model's counts to its slot of `out`.
            pub(super) fn count(
                &self,
                gpu: Option<&AnyGpuScorer<'_>>,
                batch: &InstanceBatch,
                out: &mut [SceneCounts],
            ) -> Result<(), GpuError> {
                match self {
                    $(AnyScorer::$kind(s) => {
                        #[allow(unreachable_patterns)]
                        let gpu = match gpu {
                            Some(AnyGpuScorer::$kind(g)) => Some(g),
                            _ => None,
                        };
                        count_parts(s, gpu, batch, out, AnyCounts::$kind)
                    })*
                }
            }
        }

        impl AnyGpuScorer<'_> {
            /// The most models one batch may hold on it.
            pub(super) fn max_batch(&self) -> usize {
                match self {
                    $(AnyGpuScorer::$kind(g) => {
                        GpuCount::<<crate::scene::scorer::$name::$kind as SceneScorerKind>::Counts>::max_batch(g)
                    })*
                }
            }

            /// What it keeps on the device of the models it counts, for their bred
            /// children; `None` when it counts every child from nothing.
            pub(super) fn retention(&self) -> Option<GpuRetention> {
                match self {
                    $(AnyGpuScorer::$kind(g) => <crate::scene::scorer::$name::$kind>::gpu_retention(g),)*
                }
            }

            /// Counts the bred `children` (the models of `batch`) from what `retention`
            /// kept of their `parents` (child `i` bred from `parents[from[i]]`), and
            /// appends each model's counts to its slot of `out`.
            pub(super) fn count_bred<G: Grammar>(
                &self,
                retention: &mut GpuRetention,
                bred: Bred<'_, G>,
                batch: &InstanceBatch,
                out: &mut [SceneCounts],
            ) -> Result<(), GpuError> {
                match self {
                    $(AnyGpuScorer::$kind(g) => {
                        let mut counts = vec![Default::default(); batch.len()];
                        <crate::scene::scorer::$name::$kind>::count_bred(g, retention, bred, batch, &mut counts)?;
                        for (slot, c) in out.iter_mut().zip(counts) {
                            slot.parts.push(AnyCounts::$kind(c));
                        }
                    })*
                }
                Ok(())
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
            impl ScorerGoal {
                #[doc = concat!("The `", stringify!($name), "` goal, when it is one.")]
                pub fn $name(&self) -> Option<&<crate::scene::scorer::$name::$kind as SceneScorerKind>::Goal> {
                    #[allow(unreachable_patterns)]
                    match self {
                        ScorerGoal::$kind(goal) => Some(goal),
                        _ => None,
                    }
                }
            }

            impl SceneScorer {
                #[doc = concat!("The `", stringify!($name), "` scorer, when the scene has one.")]
                pub fn $name(&self) -> Option<&<crate::scene::scorer::$name::$kind as SceneScorerKind>::Scorer> {
                    #[allow(unreachable_patterns)]
                    self.scorers.iter().find_map(|scorer| match scorer {
                        AnyScorer::$kind(scorer) => Some(scorer),
                        _ => None,
                    })
                }
            }
        )*

        /// Declares the scene file's struct, `{ fields } scorers { fields }`, with a field
        /// per kind of scorer between the two lists (each an optional table), and its
        /// `scorer_goals`, which resolves them.
        macro_rules! scene_file {
            (
                $d(#[$d meta:meta])*
                $d vis:vis struct $d file:ident {
                    { $d($d before:tt)* }
                    scorers
                    { $d($d after:tt)* }
                }
            ) => {
                $d(#[$d meta])*
                $d vis struct $d file {
                    $d($d before)*
                    $($(#[doc = $doc])* pub $name: Option<<crate::scene::scorer::$name::$kind as crate::scene::scorer_kind::SceneScorerKind>::File>,)*
                    $d($d after)*
                }

                impl $d file {
                    /// The scene's scorers, resolved from their tables: one per table
                    /// given, in the order of
                    /// [`ScorerKind::ALL`](crate::scene::ScorerKind::ALL).
                    pub(super) fn scorer_goals(
                        &self,
                        resolver: &crate::scene::resolver::Resolver<'_>,
                    ) -> Result<Vec<crate::scene::scorer::ScorerGoal>, crate::scene::error::SceneError> {
                        use crate::scene::scorer_kind::SceneScorerKind;
                        let form = self.fitness.form;
                        [$(
                            self.$name.as_ref().map(|file| {
                                <crate::scene::scorer::$name::$kind>::resolve(resolver, file, form)
                                    .map(crate::scene::scorer::ScorerGoal::$kind)
                            }),
                        )*]
                        .into_iter()
                        .flatten()
                        .collect()
                    }
                }
            };
        }
        pub(super) use scene_file;
    };
}

scorer_kinds! { $
    /// `[volume]`: weighted target volumes to fill or avoid on a voxel grid.
    Volume(volume);
    /// `[silhouette]`: target images seen through cameras.
    Silhouette(silhouette);
    /// `[bounds]`: a penalty for the volume of the model outside a box.
    Bounds(bounds);
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
    G: GpuCount<S::Counts>,
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

/// What one model of a scene covers: one [`AnyCounts`] per scorer, in the scorers'
/// order. It serializes as a map from each kind's [name](ScorerKind::name) to its
/// counts (`{"volume": {...}, "silhouette": [...]}`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneCounts {
    pub(super) parts: Vec<AnyCounts>,
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
    pub(super) scorers: Vec<AnyScorer>,
    /// The genome-length term.
    pub length: LengthPenalty,
    /// The site the scene's models grow on.
    pub(super) site: Site,
}

impl SceneScorer {
    /// The site the scene's models grow on ([`Scene::site`](crate::scene::Scene::site)).
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// The scorers, one per goal of the scene, in its order.
    pub fn scorers(&self) -> &[AnyScorer] {
        &self.scorers
    }

    /// The fitness of a model of `genes` genes with these counts: the scorers' parts, less
    /// the genome-length term.
    pub fn fitness(&self, counts: &SceneCounts, genes: usize) -> f64 {
        self.fitness_of_parts(&counts.parts, genes)
    }

    /// [`fitness`](Self::fitness) of the counts `parts`, one per scorer in order.
    pub(super) fn fitness_of_parts(&self, parts: &[AnyCounts], genes: usize) -> f64 {
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
