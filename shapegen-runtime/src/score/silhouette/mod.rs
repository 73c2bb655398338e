//! The image score: how well the silhouettes a model casts through cameras match target
//! images.
//!
//! Each [`ImageTarget`] is an image of per-pixel weights with a [`Camera`]; the
//! [`SilhouetteScorer`] projects a model's triangles through every target's camera,
//! counts the pixels its silhouette covers ([`SilhouetteCounts`]) and turns the counts
//! into fitness.
//!
//! Image orientation: row 0 of a target PNG is the top of the picture, and clip space
//! maps to pixels as `x = (ndc_x + 1) / 2 * width`, `y = (1 - ndc_y) / 2 * height`. The
//! orbit camera is the original implementation's: its `u = v x w` points to the right of
//! the picture, which in this right-handed world is the viewer's left, so the picture is
//! the mirror image of what a right-handed camera would show. The published targets are
//! drawn that way: through their cameras, the tree sketch's trunk lies where the tree
//! generator's trunk projects (0.68 to the right of the look-at point) and the whale sits
//! on the city's skyline, which the tests check.
//!
//! [`GpuSilhouetteScorer`] counts whole populations on the GPU, with the same counts up
//! to pixels whose centres lie within rounding of an edge.
//!
//! ```
//! use glam::{Affine3A, Vec3};
//! use image::{DynamicImage, GrayImage, Luma};
//! use shapegen_runtime::score::silhouette::{Camera, ImageTarget, OrbitCamera, SilhouetteScorer, Weighting};
//! use shapegen_runtime::score::{Form, Scorer};
//! use shapegen_runtime::{CUBE, Instance, MeshLibrary};
//!
//! // A target whose middle is black, and a camera 5 away looking along +z.
//! let image = GrayImage::from_fn(40, 30, |x, y| {
//!     Luma([if (10..30).contains(&x) && (5..25).contains(&y) { 0 } else { 255 }])
//! });
//! let camera = Camera::Orbit(OrbitCamera {
//!     phi: -std::f32::consts::FRAC_PI_2, theta: 0.0, radius: 5.0, lookat: Vec3::ZERO,
//!     fov_degrees: 60.0, near: 0.1, far: 100.0,
//! });
//! let target = ImageTarget::new("square".into(), &DynamicImage::ImageLuma8(image), camera, Weighting::mask(1.0, -1.0))?;
//! let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
//! let scorer = SilhouetteScorer::new(vec![target], &meshes, Form::Smooth { good: 1.0, bad: 1.0 })?;
//!
//! let cube = [Instance { transform: Affine3A::IDENTITY, mesh: CUBE }];
//! let counts = scorer.count(&cube, &mut scorer.scratch());
//! let t = counts.targets()[0];
//! assert!(t.on_target > 0 && t.off_target == 0);
//! assert!(scorer.fitness(&counts) > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod camera;
mod counts;
#[cfg(feature = "gpu")]
mod gpu;
#[cfg(feature = "gpu")]
mod gpu_draw;
#[cfg(feature = "gpu")]
mod gpu_retained;
mod mesh_fill;
mod meshes;
pub(in crate::score) mod raster;
mod retained;
mod scorer;
mod target;
#[cfg(test)]
mod tests;

pub use camera::{Camera, CameraError, OrbitCamera};
pub use counts::{MAX_TARGETS, SilhouetteCounts, TargetCounts};
#[cfg(feature = "gpu")]
pub use gpu::GpuSilhouetteScorer;
#[cfg(feature = "gpu")]
pub use gpu_retained::GpuRetention;
pub use retained::SilhouetteState;
pub use scorer::{SilhouetteError, SilhouetteScorer, SilhouetteScratch};
pub use target::{ImageTarget, MAX_TARGET_PIXELS, MaskRule, TargetError, TargetKind, Weighting};
