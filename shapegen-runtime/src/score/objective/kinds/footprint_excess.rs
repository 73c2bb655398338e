//! [`FootprintExcess`]: how far the model's x/z extent leaves a rectangle.

use glam::Vec2;
use serde::Deserialize;

use crate::evaluate::Sense;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{FromTable, ObjectiveKind, ObjectiveSource};
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;

/// How far the model's x/z extent `[lo, hi]` (its bounding box) exceeds the rectangle
/// `[min, max]` (`x`, then `z`): `sum over x, z of max(0, min - lo) + max(0, hi - max)`
/// ([`Sense::Minimize`]); 0 for an empty model. Its table: `kind = "footprint_excess"`,
/// `min` and `max` (each `[x, z]`).
///
/// ```
/// use glam::{Affine3A, Vec2};
/// use shapegen_runtime::score::objective::{FootprintExcess, ObjectiveKind, ObjectiveScratch, Surface};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
/// // The cube runs from -0.5 to 0.5: 0.25 beyond the rectangle on both x and z.
/// let excess = FootprintExcess { min: Vec2::splat(-0.25), max: Vec2::splat(1.0) };
/// assert_eq!(excess.measure(&cube, &mut ObjectiveScratch::default()), 0.5);
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FootprintExcess {
    /// Smallest allowed `x` and `z`.
    pub min: Vec2,
    /// Largest allowed `x` and `z`.
    pub max: Vec2,
}

/// The keys of a `footprint_excess` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FootprintExcessFile {
    /// Smallest allowed `[x, z]`.
    pub min: [f32; 2],
    /// Largest allowed `[x, z]`.
    pub max: [f32; 2],
}

impl FromTable for FootprintExcess {
    type File = FootprintExcessFile;

    fn resolve<S: ObjectiveSource>(file: FootprintExcessFile, _: &S) -> Result<Self, S::Error> {
        Ok(FootprintExcess {
            min: Vec2::from(file.min),
            max: Vec2::from(file.max),
        })
    }
}

impl ObjectiveKind for FootprintExcess {
    const SENSE: Sense = Sense::Minimize;

    /// A finite rectangle with `min <= max` in both coordinates.
    fn validate(&self) -> Result<(), ObjectiveError> {
        let FootprintExcess { min, max } = *self;
        if min.is_finite() && max.is_finite() && min.cmple(max).all() {
            return Ok(());
        }
        Err(ObjectiveError::Footprint { min, max })
    }

    fn measure(&self, surface: &Surface, _: &mut ObjectiveScratch) -> f64 {
        let FootprintExcess { min, max } = *self;
        surface.bounds().map_or(0.0, |(lo, hi)| {
            let (lo, hi) = (Vec2::new(lo.x, lo.z), Vec2::new(hi.x, hi.z));
            let excess = |limit: f32, v: f32| (f64::from(v) - f64::from(limit)).max(0.0);
            excess(lo.x, min.x) + excess(lo.y, min.y) + excess(max.x, hi.x) + excess(max.y, hi.y)
        })
    }
}
