//! [`NormalSpread`]: how far apart the model's distinct face normals are.

use serde::Deserialize;

use crate::evaluate::Sense;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{ObjectiveKind, ObjectiveSource};
use crate::score::objective::normals::check_tolerance;
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;

/// Sum over the distinct normals (as for [`UniqueNormals`](super::UniqueNormals)) of the
/// angle in radians to the nearest other distinct normal ([`Sense::Maximize`]); 0 with
/// fewer than two. A cube: `6 * pi / 2`. Its table: `kind = "normal_spread"` and
/// `tolerance_deg` (1 when left out).
///
/// ```
/// use glam::Affine3A;
/// use shapegen_runtime::score::objective::{NormalSpread, ObjectiveKind, ObjectiveScratch, Surface};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
/// let spread = NormalSpread { tolerance_deg: 1.0 }.measure(&cube, &mut ObjectiveScratch::default());
/// assert!((spread - 3.0 * std::f64::consts::PI).abs() < 1e-6);
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalSpread {
    /// Largest angle, in degrees (0 to 180), between normals counted as one.
    #[serde(default = "one_degree")]
    pub tolerance_deg: f32,
}

/// The tolerance of a table that leaves it out.
fn one_degree() -> f32 {
    1.0
}

impl ObjectiveKind for NormalSpread {
    type File = NormalSpread;
    const SENSE: Sense = Sense::Maximize;

    fn resolve<S: ObjectiveSource>(file: NormalSpread, _: &S) -> Result<Self, S::Error> {
        Ok(file)
    }

    /// A tolerance from 0 to 180 degrees.
    fn validate(&self) -> Result<(), ObjectiveError> {
        check_tolerance(self.tolerance_deg)
    }

    fn measure(&self, surface: &Surface, scratch: &mut ObjectiveScratch) -> f64 {
        scratch.spread(surface, self.tolerance_deg)
    }
}
