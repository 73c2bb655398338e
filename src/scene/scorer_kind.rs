//! What one kind of scorer is, end to end: [`SceneScorerKind`], which each file of
//! `scorer/` implements for its kind, and the `scorer_kinds!` table of `scorer.rs`
//! names in one row. From its table in scene files ([`File`](SceneScorerKind::File)) to
//! its resolved goal, its memory estimate, its CPU scorer and its optional GPU path
//! ([`GpuCount`], or [`Infallible`] for a kind counted on the CPU on every backend).

use std::convert::Infallible;
use std::fmt::Debug;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use shapegen_runtime::Grammar;
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::gpu::{GpuContext, GpuError};
use shapegen_runtime::optimize::Bred;
use shapegen_runtime::score::silhouette::GpuRetention;
use shapegen_runtime::score::{Form, InstanceBatch, retained::RetainedScorer};

use super::error::{SceneError, ValueError};
use super::resolver::Resolver;

/// One kind of scorer: its table, goal, scorer and counts, and how each is made from the
/// one before. The `scorer_kinds!` row that names the kind derives the rest: its field of
/// the scene file, its variant of every enum over kinds, its dispatch.
///
/// A kind with no GPU path leaves out [`gpu`](Self::gpu) and takes [`Infallible`] as its
/// [`Gpu`](Self::Gpu): its part is then counted on the CPU, with the same counts, when
/// the others count on the GPU.
pub trait SceneScorerKind {
    /// Its table in scene files as written, read strictly (unknown keys are errors).
    type File: DeserializeOwned + Debug;
    /// Its table resolved: files loaded and values checked.
    type Goal: Clone + Debug;
    /// Its scorer, counting on the CPU, from nothing or incrementally.
    type Scorer: RetainedScorer<Counts = Self::Counts> + Clone + Debug;
    /// What it counts of one model, as `shapegen score` writes it.
    type Counts: Copy + Debug + Default + PartialEq + Serialize;
    /// Its GPU path, or [`Infallible`] for a kind that has none.
    type Gpu<'a>: GpuCount<Self::Counts>;

    /// Resolves the table `file`, whose part of the fitness takes the form `form`
    /// (`fitness.form`); errors name the table's keys as written (`volume.grid`).
    ///
    /// # Errors
    /// A [`SceneError`] naming the key at fault.
    fn resolve(
        resolver: &Resolver<'_>,
        file: &Self::File,
        form: FormName,
    ) -> Result<Self::Goal, SceneError>;

    /// What its scorer takes of memory, with `threads` worker threads.
    fn memory(goal: &Self::Goal, threads: usize) -> ScorerMemory;

    /// Its scorer of models made of `meshes`.
    ///
    /// # Errors
    /// Why the goal cannot score these meshes.
    fn make(goal: &Self::Goal, meshes: &BoundMeshes) -> Result<Self::Scorer, ValueError>;

    /// Its GPU path on `context`; `None` for a kind counted on the CPU on every backend.
    fn gpu<'a>(
        scorer: &'a Self::Scorer,
        context: &'a GpuContext,
    ) -> Option<Result<Self::Gpu<'a>, GpuError>> {
        let _ = (scorer, context);
        None
    }

    /// What its GPU path `gpu` keeps on the device of the models it counted, to count
    /// their bred children incrementally ([`count_bred`](Self::count_bred)); `None` (the
    /// default) counts every child from nothing.
    fn gpu_retention(gpu: &Self::Gpu<'_>) -> Option<GpuRetention> {
        let _ = gpu;
        None
    }

    /// Counts the bred `children` (the models of `batch`) on `gpu` into `out`, from what
    /// `retention` kept of their `parents` (child `i` bred from `parents[from[i]]`). By
    /// default, from nothing.
    ///
    /// # Errors
    /// When the GPU fails while counting.
    fn count_bred<G: Grammar>(
        gpu: &Self::Gpu<'_>,
        retention: &mut GpuRetention,
        bred: Bred<'_, G>,
        batch: &InstanceBatch,
        out: &mut [Self::Counts],
    ) -> Result<(), GpuError> {
        let _ = (retention, bred);
        gpu.count_batch(batch, out)
    }
}

/// A GPU path's counting of whole batches of `C` counts, as
/// [`count_batch`](shapegen_runtime::score::count_batch) counts on the CPU. A kind
/// without a GPU path takes [`Infallible`] as its [`Gpu`](SceneScorerKind::Gpu), of
/// which no value exists.
pub trait GpuCount<C> {
    /// Counts every model of `batch` into `out`, one slot per model.
    ///
    /// # Errors
    /// When the GPU fails while counting.
    fn count_batch(&self, batch: &InstanceBatch, out: &mut [C]) -> Result<(), GpuError>;

    /// The most models one batch may hold.
    fn max_batch(&self) -> usize;
}

impl<C> GpuCount<C> for Infallible {
    fn count_batch(&self, _: &InstanceBatch, _: &mut [C]) -> Result<(), GpuError> {
        match *self {}
    }

    fn max_batch(&self) -> usize {
        match *self {}
    }
}

/// What one scorer takes of memory ([`SceneScorerKind::memory`]).
#[derive(Clone, Debug, Default)]
pub struct ScorerMemory {
    /// The cells it counts over, when it has any: what they are (`voxels`), the setting
    /// that sizes them, and how many. Each takes a byte and bit planes in the scorer,
    /// scratch per thread, and 16-bit counts per model kept for incremental counting.
    pub cells: Option<(&'static str, String, u64)>,
    /// Its other buffers: what they are for, the setting that sizes them, and bytes.
    pub other: Vec<(String, String, u64)>,
}

/// `fitness.form`: how each scorer's counts become its part of the fitness.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FormName {
    /// The original implementation's smoothstep form.
    #[default]
    Smooth,
    /// The paper's weighted sum.
    Weighted,
    /// The intersection over union that runs report, times `good`.
    Iou,
    /// Volumes only: the surface F-score at `volume.fscore_threshold`, times `good`.
    FScore,
}

/// The form `form` of table `table` (`volume` or `silhouette`), its weights read from
/// `(good, bad, overlap)`; `threshold` is the F-score's, which only a volume has.
///
/// # Errors
/// [`SceneError::Invalid`] naming `table.good`, `table.bad` or `table.overlap` when not
/// finite, or `fitness.form` for `fscore` without a threshold.
pub fn resolve_form(
    resolver: &Resolver<'_>,
    table: &str,
    form: FormName,
    (good, bad, overlap): (f64, f64, f64),
    threshold: Option<f64>,
) -> Result<Form, SceneError> {
    let finite = |key: &str, value: f64| resolver.finite(&format!("{table}.{key}"), value);
    Ok(match form {
        FormName::Smooth => Form::Smooth {
            good: finite("good", good)?,
            bad: finite("bad", bad)?,
        },
        FormName::Weighted => Form::Weighted {
            overlap: finite("overlap", overlap)?,
        },
        FormName::Iou => Form::Iou {
            good: finite("good", good)?,
        },
        FormName::FScore => match threshold {
            Some(threshold) => Form::FScore {
                good: finite("good", good)?,
                threshold,
            },
            None => {
                return Err(resolver.invalid(
                    "fitness.form",
                    format!(
                        "`fscore` is for volume goals; a [{table}] takes \"smooth\", \
                         \"weighted\" or \"iou\""
                    ),
                ));
            }
        },
    })
}
