//! Incremental scoring: counting a bred child from what was kept of its parent.
//!
//! A child made by grow, cut, alter or crossover shares almost all of its instances with
//! the parent it was bred from. A [`RetainedScorer`] keeps, per model, how many of the
//! model's instances hit each cell (pixel of each target, voxel) in [`CellCounts`], with
//! the model's counts; a child is then counted as its parent's state, less what the
//! instances the child lost covered, plus what the instances it gained cover
//! ([`InstanceDiff`]). The result is exactly the child's counts from nothing: a cell is
//! covered when its count is above 0, and every count a scorer reports is kept up to
//! date as cells go from 0 to 1 hit and back (and from 1 to 2, for the volume's
//! overlap). This holds for any pair of models, so lineage only decides how much work
//! is saved, never the result.
//!
//! [`Retention`] keeps the states of one search's current models, keyed by genome:
//! [`count_bred`](Retention::count_bred) counts the children an optimizer bred from its
//! population (what [`Evaluator::evaluate_bred`](crate::evaluate::Evaluator::evaluate_bred)
//! hands over), computing a parent's state first when none is kept (the first
//! generation, after a resume), and afterwards keeps only the parents' and the
//! children's states. Memory is bounded: a state is a tile directory (8 bytes per tile
//! of 8 x 64 cells) and the tiles it does not share with its relatives, 1 KiB each, and
//! for the silhouette and projection scorers the coverage words of the instances whose
//! rasterization is worth not repeating (shared between relatives too);
//! [`Retention::memory`] measures what is held, and above
//! [`max_bytes`](Retention::with_max_bytes) children are counted but not kept.
//!
//! ```
//! use glam::{Affine3A, Vec3};
//! use image::{DynamicImage, GrayImage, Luma};
//! use shapegen_runtime::score::retained::{InstanceDiff, RetainedScorer};
//! use shapegen_runtime::score::silhouette::{Camera, ImageTarget, OrbitCamera, SilhouetteScorer, Weighting};
//! use shapegen_runtime::score::{Form, Scorer};
//! use shapegen_runtime::{CUBE, Instance, MeshLibrary};
//!
//! let image = GrayImage::from_fn(40, 30, |x, _| Luma([if x < 20 { 0 } else { 255 }]));
//! let camera = Camera::Orbit(OrbitCamera {
//!     phi: -std::f32::consts::FRAC_PI_2, theta: 0.0, radius: 6.0, lookat: Vec3::ZERO,
//!     fov_degrees: 60.0, near: 0.1, far: 100.0,
//! });
//! let target = ImageTarget::new("half".into(), &DynamicImage::ImageLuma8(image), camera, Weighting::mask(1.0, -1.0))?;
//! let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
//! let scorer = SilhouetteScorer::new(vec![target], &meshes, Form::Smooth { good: 1.0, bad: 1.0 })?;
//!
//! let at = |x: f32| Instance { transform: Affine3A::from_translation(Vec3::X * x), mesh: CUBE };
//! let parent = [at(-1.0), at(0.0)];
//! let child = [at(-1.0), at(1.2)];
//! let mut scratch = scorer.scratch();
//!
//! // The child from the parent's state: one instance taken away, one added.
//! let mut state = scorer.count_retained(&parent, &mut scratch).unwrap();
//! let mut diff = InstanceDiff::default();
//! diff.between(&parent, &child);
//! scorer.update(&mut state, diff.removed(), diff.added(), &mut scratch).unwrap();
//! assert_eq!(scorer.state_counts(&state), scorer.count(&child, &mut scratch));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod cells;
mod diff;
mod footprint;
mod pixels;
mod retention;
mod scorer;

pub use cells::{CellCounts, Changed, Overflow, TILE_BYTES, TILE_WORDS};
pub use diff::InstanceDiff;
pub use footprint::WithFootprints;
pub(crate) use footprint::{Footprinted, Grids, MAX_GRIDS, Recorder};
pub use pixels::{Hit, PixelCounts};
#[cfg(feature = "gpu")]
pub(crate) use retention::genome_key;
pub use retention::{DEFAULT_MAX_BYTES, Retention, RetentionStats};
pub use scorer::RetainedScorer;
