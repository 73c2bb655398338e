//! What one model covers on the grid.

use super::surface::SurfaceCounts;
use super::target::MAX_CLASSES;

/// What one model covers on the grid. Equal counts give equal fitness, whichever
/// backend counted them. The [module documentation](super) says which fitness form uses
/// which count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct VolumeCounts {
    /// Distinct covered target voxels (class weight above 0).
    pub inside: u64,
    /// Distinct covered voxels that are not target voxels.
    pub outside: u64,
    /// Hits of in-grid voxels beyond each voxel's first: a voxel covered by three
    /// instances counts 2.
    pub overlap_hits: u64,
    /// Distinct in-grid voxels covered more than once: a voxel covered by three
    /// instances counts 1.
    pub overlap_voxels: u64,
    /// Covered lattice points outside the grid, one per instance and point.
    pub out_of_grid_hits: u64,
    /// Per instance, the voxels of its span (the box of voxel indices of its rounded
    /// vertices) outside the grid, whether it covers them or not; summed over
    /// instances.
    pub span_out_of_grid: u64,
    /// Distinct covered voxels of each class
    /// ([`VoxelClasses::weights`](super::VoxelClasses::weights)); classes the scene lacks
    /// stay 0. Not serialized: `inside` and `outside` sum them up.
    #[serde(skip)]
    pub classes: [u64; MAX_CLASSES],
    /// With [`Form::FScore`](crate::score::Form::FScore), the model's surface voxels in
    /// the grid (0 in other forms).
    #[serde(skip)]
    pub surface: u64,
    /// With [`Form::FScore`](crate::score::Form::FScore), those within the threshold of
    /// the target's surface.
    #[serde(skip)]
    pub surface_near: u64,
    /// With [`Form::FScore`](crate::score::Form::FScore), the target's surface voxels
    /// within the threshold of the model's surface.
    #[serde(skip)]
    pub target_surface_near: u64,
}

impl VolumeCounts {
    /// `self` with the F-score counts `c`.
    pub(super) fn with_surface(self, c: SurfaceCounts) -> VolumeCounts {
        VolumeCounts {
            surface: c.surface,
            surface_near: c.near,
            target_surface_near: c.target_near,
            ..self
        }
    }
}
