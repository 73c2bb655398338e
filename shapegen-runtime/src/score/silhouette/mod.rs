//! The image score: how well the silhouettes a model casts through cameras match target
//! images.
//!
//! Each [`ImageTarget`] is an image of per-pixel weights with a [`Camera`]; the
//! [`SilhouetteScorer`] projects a model's triangles through every target's camera,
//! counts the pixels its silhouette covers ([`SilhouetteCounts`]) and turns the counts
//! into fitness.
//!
//! Image orientation: row 0 of a target PNG is the top of the picture, and clip space
//! maps to pixels as `x = (ndc_x + 1) / 2 * width`, `y = (1 - ndc_y) / 2 * height`;
//! the published scenes' targets line up with their generators through their cameras
//! this way.

mod camera;
mod counts;
mod gpu;
mod meshes;
mod raster;
mod scorer;
mod target;
#[cfg(test)]
mod tests;

pub use camera::{Camera, CameraError, OrbitCamera};
pub use counts::{MAX_TARGETS, SilhouetteCounts, TargetCounts};
pub use gpu::GpuSilhouetteScorer;
pub use scorer::{SilhouetteError, SilhouetteScorer, SilhouetteScratch};
pub use target::{ImageTarget, MAX_TARGET_PIXELS, TargetError, TargetKind};
