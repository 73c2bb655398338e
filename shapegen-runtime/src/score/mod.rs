//! Scoring derived models against a goal: a volume to fill or avoid, or silhouettes
//! seen through cameras.
//!
//! A scorer first *counts* (voxels or pixels of each kind a model covers) and then turns
//! the counts into a fitness with a [`Form`]: the paper's weighted sum, or the original
//! implementation's smoothstep form. Counts are exact integers, so every backend that
//! counts the same way gives the same fitness.
//!
//! Whole populations are scored at once: their instances go into one
//! [`InstanceBatch`], and [`count_batch`] counts every model on the rayon pool, in a few
//! chunks per worker thread with one scratch buffer each.
//!
//! [`volume`] scores how well models fill weighted target volumes on a voxel grid, on
//! the CPU or, for grammars made of boxes, on the GPU with identical counts;
//! [`silhouette`] scores how well their projections through cameras match target
//! images, on the CPU or the GPU (equal to within a few edge pixels). [`objective`]
//! measures geometric objectives (height, distinct normals, footprint, orthographic
//! projection matches) on models, one value each, for multi-objective searches.
//!
//! ```
//! use shapegen_runtime::score::{LengthPenalty, smoothstep};
//!
//! assert_eq!(smoothstep(0.0, 10.0, 5.0), 0.5);
//! let penalty = LengthPenalty { weight: 0.1, from: 10.0, to: 100.0 };
//! assert_eq!(penalty.apply(10), 0.0);
//! assert_eq!(penalty.apply(100), 0.1);
//! ```

mod batch;
mod distance;
mod form;
pub mod metrics;
pub mod objective;
pub mod retained;
mod scorer;
pub mod silhouette;
pub mod volume;

pub use batch::{InstanceBatch, count_batch};
pub use distance::squared_distances;
pub use form::{Form, LengthPenalty, smoothstep};
pub use scorer::Scorer;
