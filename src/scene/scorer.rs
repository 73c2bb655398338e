//! The kinds of scorer a scene may have, listed once in the `scorer_kinds!` invocation
//! below: each kind's table, resolved goal, CPU scorer (a runtime [`Scorer`], which
//! counts and turns counts into fitness), GPU path and counts, and the one arm that makes
//! its scorer from its goal. A scene holds a list of [`ScorerGoal`]s, its [`SceneScorer`]
//! a list of [`AnyScorer`]s and each model's [`SceneCounts`] a list of [`AnyCounts`], all
//! in the order of [`ScorerKind::ALL`] with at most one of each kind. Making a scene's
//! scorers and counting them on a backend is `evaluate.rs`'s.

use serde::{Serialize, Serializer};
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::gpu::{GpuContext, GpuError};
use shapegen_runtime::score::retained::{CellCounts, Overflow, RetainedScorer};
use shapegen_runtime::score::silhouette::{
    GpuSilhouetteScorer, SilhouetteCounts, SilhouetteScorer,
};
use shapegen_runtime::score::volume::{GpuVolumeScorer, VolumeCounts, VolumeScorer};
use shapegen_runtime::score::{InstanceBatch, LengthPenalty, Scorer, count_batch};
use shapegen_runtime::{Instance, Site};

use super::error::ValueError;
use super::goal::{SilhouetteGoal, VolumeGoal};

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
        pub(super) enum AnyGpuScorer<'a> {
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
            pub(super) fn scorer(&self, meshes: &BoundMeshes) -> Result<AnyScorer, ValueError> {
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
            pub(super) fn nothing(&self) -> AnyCounts {
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
            pub(super) fn gpu<'a>(&'a self, context: &'a GpuContext) -> Result<AnyGpuScorer<'a>, GpuError> {
                Ok(match self {
                    $(AnyScorer::$kind(s) => AnyGpuScorer::$kind($gpu::new(context, s)?),)*
                })
            }

            /// The most models one batch may hold on `gpu`.
            pub(super) fn max_batch(gpu: &AnyGpuScorer<'_>) -> usize {
                match gpu {
                    $(AnyGpuScorer::$kind(g) => GpuCount::max_batch(g),)*
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
