//! [`ObjectiveScratch`]: the working memory of measuring objectives.

use glam::Vec3;

use super::normals::{NormalGrid, cluster, spread};
use super::surface::Surface;
use crate::score::silhouette::raster::Coverage;

/// Reusable working memory for measuring [objectives](super::Objective): one per worker.
///
/// ```
/// use glam::Affine3A;
/// use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Surface, UniqueNormals};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
/// let mut scratch = ObjectiveScratch::default();
/// let unique = Objective::from(UniqueNormals { tolerance_deg: 1.0 });
/// assert_eq!(unique.measure(&cube, &mut scratch), 6.0);
/// assert_eq!(unique.measure(&Surface::new(), &mut scratch), 0.0);
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct ObjectiveScratch {
    coverage: Coverage,
    distinct: Vec<Vec3>,
    /// The tolerance `distinct` was clustered with, for the surface being measured.
    distinct_for: Option<f32>,
    grid: NormalGrid,
}

impl ObjectiveScratch {
    /// Forgets what was computed for the previous surface.
    pub(super) fn forget(&mut self) {
        self.distinct_for = None;
    }

    /// Clusters the normals of `surface` at `tolerance_deg` into `distinct`, unless the
    /// last ones were clustered for the same surface at the same tolerance.
    fn cluster(&mut self, surface: &Surface, tolerance_deg: f32) {
        if self.distinct_for != Some(tolerance_deg) {
            cluster(
                surface.normals(),
                tolerance_deg,
                &mut self.distinct,
                &mut self.grid,
            );
            self.distinct_for = Some(tolerance_deg);
        }
    }

    /// The distinct normals of `surface` at `tolerance_deg` (each more than the tolerance
    /// from the others), clustered unless they were for this surface already.
    pub(super) fn distinct(&mut self, surface: &Surface, tolerance_deg: f32) -> &[Vec3] {
        self.cluster(surface, tolerance_deg);
        &self.distinct
    }

    /// The sum over the [`distinct`](Self::distinct) normals of the angle in radians to
    /// the nearest other one.
    pub(super) fn spread(&mut self, surface: &Surface, tolerance_deg: f32) -> f64 {
        self.cluster(surface, tolerance_deg);
        spread(&self.distinct, &mut self.grid)
    }

    /// A coverage buffer to rasterize projections into.
    pub(super) fn coverage(&mut self) -> &mut Coverage {
        &mut self.coverage
    }
}
