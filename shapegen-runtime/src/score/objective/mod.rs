//! Geometric objectives measured on derived models, for multi-objective searches.
//!
//! A model's instances become a [`Surface`]: its world-space triangles, each with its
//! unit face normal. Each [`Objective`] measures one raw value on it, with a
//! [`Sense`](crate::evaluate::Sense) saying whether higher or lower is better. Its kinds
//! are the rows of the table of kinds (`kinds.rs`; [`Objective::NAMES`]), each an
//! [`ObjectiveKind`] in a file of its own, read from a scene's `[[objective]]` table as
//! an [`ObjectiveFile`] and resolved through an [`ObjectiveSource`]. Kinds may match an
//! orthographic projection against a black-and-white target image ([`ProjectionMatch`],
//! rasterized as the silhouette scorer does) or approach a scanned point cloud
//! ([`ChamferMatch`]), or read which part each triangle belongs to (its instance's mesh,
//! a set of [`Parts`]).
//!
//! An [`ObjectiveSet`] names the objectives of a search and measures whole populations
//! ([`InstanceBatch`](crate::score::InstanceBatch)es) on the rayon pool, one row of
//! values per model; [`ObjectiveSet::weighted`] and [`WeightedObjectives`] turn the
//! values into one fitness, so that one objective or a weighted combination drives the
//! single-objective searches.
//!
//! ```
//! use glam::{Affine3A, Quat, Vec3};
//! use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Surface, UniqueNormals};
//! use shapegen_runtime::{CUBE, Instance, MeshLibrary};
//!
//! let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
//! let turned = Affine3A::from_quat(Quat::from_rotation_y(std::f32::consts::FRAC_PI_4));
//! let model = [
//!     Instance { transform: Affine3A::IDENTITY, mesh: CUBE },
//!     Instance { transform: turned, mesh: CUBE },
//! ];
//! let surface = Surface::from_instances(&model, &meshes);
//! let unique = Objective::from(UniqueNormals { tolerance_deg: 1.0 });
//! // Both cubes share their top and bottom; their sides point 8 ways.
//! assert_eq!(unique.measure(&surface, &mut ObjectiveScratch::default()), 10.0);
//! # Ok::<(), shapegen_runtime::MeshError>(())
//! ```

mod bred;
mod error;
mod kind;
mod kinds;
mod normals;
mod normals_kind;
mod parts;
mod projected;
mod projection;
mod retained;
mod scratch;
mod set;
mod surface;
mod weighted;

pub use bred::BredObjectives;
pub use error::ObjectiveError;
pub use kind::{AsWritten, FromTable, ObjectiveKind, ObjectiveSource};
/// The table of kinds: [`Objective`], [`ObjectiveFile`], and each kind's type and file
/// form.
pub use kinds::*;
pub use parts::{MIN_UPWARD_Y, Parts};
pub use projected::ProjectionFile;
pub use projection::{ProjectionMatch, View};
pub use retained::{ProjectionCounts, ProjectionScorer, ProjectionScratch, ProjectionState};
pub use scratch::ObjectiveScratch;
pub use set::ObjectiveSet;
pub use surface::Surface;
pub use weighted::WeightedObjectives;
