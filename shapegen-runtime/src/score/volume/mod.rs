//! The volume scorer: how well a model fills target volumes, counted on a voxel grid.
//!
//! Targets are voxelized once by ray parity ([`VoxelClasses`]); each voxel gets the
//! combined weight `sum_i (inside target i ? inside_i : outside_i)`, and the distinct
//! weights are the voxel *classes*. A model is the union of its instances: instances of
//! the unit cube (or any mesh whose geometry is exactly the unit cube) are rasterised
//! with exact integer arithmetic from a quantised form of the instance, which the GPU
//! evaluates identically; other meshes are voxelized by parity on their transformed
//! triangles. A model's [facets](crate::geometry::Mesh::facet), the triangles of the
//! surfaces its rules generate, are voxelized together by winding number: a lattice
//! point is covered by them once for each closed, outward-wound facet surface holding
//! it (corners snapped to 1/4096 of a voxel, so that a corner two facets share is one
//! point), and each facet's span is that of its triangle. A lattice point counts as
//! covered when its voxel centre is.
//!
//! [`VolumeCounts`] holds what a model covers: distinct covered voxels per class,
//! `inside` (target voxels: class weight above 0) and `outside` (the rest); repeated
//! coverage twice over, as `overlap_hits` (every hit of a voxel beyond its first) and
//! `overlap_voxels` (distinct voxels covered more than once); and what lies beyond the
//! grid twice over, as `out_of_grid_hits` (covered lattice points outside the grid, one
//! per instance and point) and `span_out_of_grid` (per instance, the voxels of its *span*
//! outside the grid, covered or not: see below). The fitness is, with
//! [`Form::Weighted`](crate::score::Form::Weighted) (the paper's text), `sum_c count_c
//! weight_c + out_of_grid_hits sum_i outside_i - w_self overlap_hits` and, with
//! [`Form::Smooth`](crate::score::Form::Smooth) (the original's code), `good S(0, T,
//! inside) - bad S(0, 2T, outside + overlap_voxels + span_out_of_grid)` where `T` is the
//! number of target voxels; with [`Form::Iou`](crate::score::Form::Iou), `good inside /
//! (T + outside + out_of_grid_hits)`: the voxel IoU that runs report
//! ([`voxel_iou`](crate::score::metrics::voxel_iou)) for a model within the grid, and
//! below it by what the model covers beyond the grid, so that a search gains nothing by
//! growing out of it.
//!
//! # The F-score form
//! With [`Form::FScore`](crate::score::Form::FScore), the scorer also counts the model's
//! surface voxels (those it covers with a face neighbour it does not cover), `surface`,
//! those within the threshold of the target's surface voxels, `surface_near`, and the
//! target's surface voxels within the threshold of the model's, `target_surface_near`;
//! the fitness is `good` times the harmonic mean of the precision `surface_near /
//! (surface + out_of_grid_hits)` and the recall `target_surface_near / T_s`, `T_s` the
//! target's surface voxels ([`VolumeScorer::target_surface_voxels`]). These counts are
//! made on the CPU only ([`GpuVolumeScorer::new`] refuses the form); the other forms
//! leave them 0.
//!
//! # As the original counts
//! The original voxelizes each instance on its own over its span, the box of voxel
//! indices between the rounded positions of its transformed vertices (each rounded to
//! the voxel containing it, in `f32`: [`Grid`] documents the expression); every span
//! voxel outside the grid adds 1 to its out-of-grid count, and every span voxel inside
//! the grid whose centre the instance covers adds 1 to that voxel's count. Its
//! `overlap` is the number of voxels whose count exceeds 1, and its smooth fitness
//! penalises `bad + overlap + out-of-grid`: `outside`, `overlap_voxels` and
//! `span_out_of_grid` here. With `inside`, they equal the original's for every model
//! whose voxel centres it decides as we do (the volume tests check them against a
//! transcription of the original's kernels on random spaceships).
//!
//! Which centres an instance covers is decided differently, with the same result
//! except on ties of measure zero. The original casts a ray from each centre along +y
//! and counts crossings with the instance's transformed triangles (Möller–Trumbore in
//! `f32`, a crossing at the centre itself included, triangles whose projection onto
//! the x-z plane has less than `5e-8` of area ignored). For a box that makes the faces
//! met by the ray half-open: an axis-aligned box covers the centres with `y` in
//! `(y_min, y_max]`, `x` and `z` in the closed ranges, and a centre whose ray passes
//! exactly through the diagonal shared by a face's two triangles meets that face twice,
//! so is left out; where `f32` rounding puts a centre on a face is decided by that
//! rounding. Here a box covers a centre whose local coordinates lie in the closed
//! `[-0.5, 0.5]^3`, decided exactly on its quantised form (within about 1e-6 of a voxel
//! of the exact box, see `quant.rs`); other meshes by parity along +x with ties broken
//! by symbolic perturbation, so that shared edges and vertices count once.
//!
//! [`count_batch`](super::count_batch) counts a population on the CPU threads;
//! [`GpuVolumeScorer`] counts it on the GPU in one submission, with the same counts:
//! box instances are rasterised there, other meshes and facets on the CPU threads
//! (their covered runs are then counted on the GPU with the boxes).
//!
//! ```
//! use glam::{Affine3A, Quat, Vec3};
//! use shapegen_runtime::{CUBE, Instance, Mesh, MeshLibrary};
//! use shapegen_runtime::score::{Form, Scorer};
//! use shapegen_runtime::score::volume::{Fill, Grid, VolumeScorer, VolumeTarget};
//!
//! // A 2 x 2 x 2 block of target voxels in the middle of a 4^3 grid of voxels of 0.5.
//! let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [4, 4, 4])?;
//! let target = VolumeTarget {
//!     name: "block".into(),
//!     mesh: Mesh::unit_cube(),
//!     inside: 1.0,
//!     outside: -1.0,
//!     fill: Fill::Parity,
//! };
//! let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
//! let form = Form::Smooth { good: 2.0, bad: 15.0 };
//! let scorer = VolumeScorer::new(grid, &[target], &meshes, form)?;
//! assert_eq!(scorer.target_voxels(), 8);
//!
//! // A box reaching one layer further up: the 8 target voxels and 4 others.
//! let taller = Instance {
//!     transform: Affine3A::from_scale_rotation_translation(
//!         Vec3::new(1.0, 1.0, 1.5),
//!         Quat::IDENTITY,
//!         Vec3::new(0.0, 0.0, 0.25),
//!     ),
//!     mesh: CUBE,
//! };
//! let mut scratch = scorer.scratch();
//! let counts = scorer.count(&[taller], &mut scratch);
//! let summary = (counts.inside, counts.outside, counts.overlap_voxels, counts.out_of_grid_hits);
//! assert_eq!(summary, (8, 4, 0, 0));
//! // Its top face lies on the grid's top, z = 1, which is rounded to voxel index 4 (the
//! // voxel that would hold it), beyond the grid: of its span of 3 x 3 x 4 voxels, 9 lie
//! // outside the grid although it covers none of their centres.
//! assert_eq!(counts.span_out_of_grid, 9);
//!
//! // Two of them: the 12 voxels are covered twice, once more each.
//! let twice = scorer.count(&[taller, taller], &mut scratch);
//! assert_eq!((twice.overlap_hits, twice.overlap_voxels), (12, 12));
//! // Three: 24 hits beyond the first, still 12 voxels.
//! let thrice = scorer.count(&[taller, taller, taller], &mut scratch);
//! assert_eq!((thrice.overlap_hits, thrice.overlap_voxels), (24, 12));
//!
//! // The target exactly: the optimum, `good`.
//! let exact = Instance { transform: Affine3A::IDENTITY, mesh: CUBE };
//! assert_eq!(scorer.fitness(&scorer.count(&[exact], &mut scratch)), 2.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod classes;
mod count;
mod counts;
#[cfg(feature = "gpu")]
mod gpu;
mod grid;
mod parity;
mod parts;
mod quant;
mod retained;
mod scorer;
mod scratch;
mod span;
mod surface;
mod target;
mod winding;

pub use classes::VoxelClasses;
pub use counts::VolumeCounts;
#[cfg(feature = "gpu")]
pub use gpu::GpuVolumeScorer;
pub use grid::{Grid, GridError, MAX_VOXELS};
pub use retained::VolumeState;
pub use scorer::VolumeScorer;
pub use scratch::VolumeScratch;
pub use surface::{MAX_HALF_WIDTH, fscore_half_width};
pub use target::{Fill, MAX_CLASSES, VolumeError, VolumeTarget};

#[cfg(test)]
mod tests;
