//! [`Height`]: how far the model's top is from a target height.

use serde::Deserialize;

use crate::evaluate::Sense;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{AsWritten, ObjectiveKind};
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;

/// Distance of the model's top to a target height, `|max_y - target|`, `max_y` the
/// largest `y` of the surface's vertices ([`Sense::Minimize`]). An empty model stands on
/// the ground, `max_y = 0`: its value is `|target|`. Its table: `kind = "height"` and
/// `target`.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::score::objective::{Height, ObjectiveKind, ObjectiveScratch, Surface};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let raised = Instance { transform: Affine3A::from_translation(Vec3::Y), mesh: CUBE };
/// let surface = Surface::from_instances(&[raised], &meshes);
/// // The cube's top is at 1.5.
/// assert_eq!(Height { target: 2.0 }.measure(&surface, &mut ObjectiveScratch::default()), 0.5);
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Height {
    /// The height the model's top should reach.
    pub target: f32,
}

impl AsWritten for Height {}

impl ObjectiveKind for Height {
    const SENSE: Sense = Sense::Minimize;

    /// A finite `target`.
    fn validate(&self) -> Result<(), ObjectiveError> {
        ObjectiveError::check("target", self.target, f32::is_finite, "a finite number")
    }

    fn measure(&self, surface: &Surface, _: &mut ObjectiveScratch) -> f64 {
        let top = surface.bounds().map_or(0.0, |(_, hi)| hi.y);
        (f64::from(top) - f64::from(self.target)).abs()
    }
}
