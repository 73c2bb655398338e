//! [`BoundingBox`]: how far the size of the model's bounding box is from a target size.

use glam::Vec3;
use serde::Deserialize;

use crate::evaluate::Sense;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{FromTable, ObjectiveKind, ObjectiveSource};
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;

/// How far the size of the model's axis-aligned bounding box is from a target size,
/// `sum over x, y, z of |extent - target|` ([`Sense::Minimize`]), `extent = hi - lo` the
/// box's size along the axis; an empty model's extent is 0 on every axis, so its value is
/// `target.x + target.y + target.z`. Unlike [`Height`](super::Height) and
/// [`FootprintExcess`](super::FootprintExcess), it does not care where the box is, only
/// how big it is: a model of the right proportions anywhere on its lot. Its table:
/// `kind = "bounding_box"` and `target` (`[x, y, z]`, each finite and at least 0).
///
/// ```
/// use glam::{Affine3A, Quat, Vec3};
/// use shapegen_runtime::score::objective::{BoundingBox, Objective, ObjectiveScratch, Surface};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// // A unit cube stretched to 4 x 2 x 1, anywhere.
/// let slab = Affine3A::from_scale_rotation_translation(
///     Vec3::new(4.0, 2.0, 1.0),
///     Quat::IDENTITY,
///     Vec3::new(10.0, 5.0, -3.0),
/// );
/// let surface = Surface::from_instances(&[Instance { transform: slab, mesh: CUBE }], &meshes);
/// let mut scratch = ObjectiveScratch::default();
/// let size = Objective::from(BoundingBox { target: Vec3::new(3.0, 2.0, 1.5) });
/// assert_eq!((size.name(), size.measure(&surface, &mut scratch)), ("bounding_box", 1.5));
/// // An empty model has no extent.
/// assert_eq!(size.measure(&Surface::new(), &mut scratch), 6.5);
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingBox {
    /// The size to reach along `x`, `y` and `z`.
    pub target: Vec3,
}

/// The keys of a `bounding_box` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundingBoxFile {
    /// The size to reach, `[x, y, z]`.
    pub target: [f32; 3],
}

impl FromTable for BoundingBox {
    type File = BoundingBoxFile;

    /// The size of `target`; one that is not a size is an error of `target`.
    fn resolve<S: ObjectiveSource>(file: BoundingBoxFile, source: &S) -> Result<Self, S::Error> {
        let size = BoundingBox {
            target: Vec3::from(file.target),
        };
        size.validate().map_err(|err| source.refused("target", err))?;
        Ok(size)
    }
}

impl ObjectiveKind for BoundingBox {
    const SENSE: Sense = Sense::Minimize;

    /// A target that is finite and at least 0 along every axis.
    fn validate(&self) -> Result<(), ObjectiveError> {
        let size = |t: f32| t.is_finite() && t >= 0.0;
        let valid = "a size: finite and at least 0 along x, y and z";
        for t in self.target.to_array() {
            ObjectiveError::check("target", t, size, valid)?;
        }
        Ok(())
    }

    fn measure(&self, surface: &Surface, _: &mut ObjectiveScratch) -> f64 {
        let (lo, hi) = surface.bounds().unwrap_or((Vec3::ZERO, Vec3::ZERO));
        let axis = |lo: f32, hi: f32, target: f32| {
            (f64::from(hi) - f64::from(lo) - f64::from(target)).abs()
        };
        axis(lo.x, hi.x, self.target.x)
            + axis(lo.y, hi.y, self.target.y)
            + axis(lo.z, hi.z, self.target.z)
    }
}

#[cfg(test)]
mod tests {
    use glam::{Affine3A, Vec3};

    use super::*;
    use crate::geometry::{CUBE, Instance, MeshLibrary};

    fn measure(target: [f32; 3], transforms: &[Affine3A]) -> f64 {
        let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
        let model: Vec<Instance> = transforms
            .iter()
            .map(|&transform| Instance { transform, mesh: CUBE })
            .collect();
        let surface = Surface::from_instances(&model, &meshes);
        let size = BoundingBox {
            target: Vec3::from(target),
        };
        size.measure(&surface, &mut ObjectiveScratch::default())
    }

    #[test]
    fn the_value_is_the_summed_distance_of_the_extents_to_the_target() {
        let cube = Affine3A::IDENTITY;
        assert_eq!(measure([1.0, 1.0, 1.0], &[cube]), 0.0);
        assert_eq!(measure([2.0, 1.0, 0.5], &[cube]), 1.5);
        // A second cube 3 along x and 1 up: the box runs from -0.5 to 3.5 along x and
        // from -0.5 to 1.5 along y.
        let beside = Affine3A::from_translation(Vec3::new(3.0, 1.0, 0.0));
        assert_eq!(measure([4.0, 2.0, 1.0], &[cube, beside]), 0.0);
        assert_eq!(measure([1.0, 3.0, 0.25], &[cube, beside]), 3.0 + 1.0 + 0.75);
        // Where the box is does not matter.
        let far = Affine3A::from_translation(Vec3::new(-40.0, 7.0, 12.5));
        assert_eq!(measure([2.0, 1.0, 0.5], &[far]), 1.5);
    }

    #[test]
    fn an_empty_model_has_no_extent() {
        assert_eq!(measure([3.0, 2.0, 1.0], &[]), 6.0);
        assert_eq!(measure([0.0, 0.0, 0.0], &[]), 0.0);
    }

    #[test]
    fn a_target_must_be_a_size() {
        let size = |target: [f32; 3]| BoundingBox {
            target: Vec3::from(target),
        };
        assert_eq!(size([0.0, 1.0, 2.0]).validate(), Ok(()));
        for (target, value) in [([1.0, -1.0, 2.0], -1.0), ([f32::INFINITY, 1.0, 1.0], f32::INFINITY)] {
            let err = size(target).validate().unwrap_err();
            assert_eq!(
                err,
                ObjectiveError::Parameter {
                    field: "target",
                    value,
                    valid: "a size: finite and at least 0 along x, y and z",
                }
            );
        }
        let err = size([1.0, 1.0, f32::NAN]).validate().unwrap_err();
        assert!(err.to_string().starts_with("`target` is NaN; it must be a size"), "{err}");
    }
}
