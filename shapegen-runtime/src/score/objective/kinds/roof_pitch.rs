//! [`RoofPitch`]: how far the mean pitch of a roof is from a target.

use glam::DVec3;
use serde::Deserialize;

use crate::evaluate::Sense;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{FromTable, ObjectiveKind, ObjectiveSource};
use crate::score::objective::parts::{MIN_UPWARD_Y, Parts, area};
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;

/// How far the area-weighted mean pitch of a roof is from a target, in degrees,
/// `|mean - target_deg|` ([`Sense::Minimize`]).
///
/// A triangle's pitch is the angle between its plane and the horizontal,
/// `atan2(|(n.x, n.z)|, n.y)` for its unit normal `n`: 0 flat, towards 90 vertical.
/// Counted are the triangles whose instance's mesh is in `parts` and that face up,
/// `n.y >` [`MIN_UPWARD_Y`] (`1e-4`, a pitch below about 89.994 degrees), each weighted
/// by its world-space area: a roof's underside (`n.y < 0`) and its vertical gable ends
/// (`n.y = 0`, give or take rounding) are not its pitch. A model with no such triangle
/// has mean 0. Its table: `kind = "roof_pitch"`, `parts` (mesh names, `["roof"]` when
/// left out) and `target_deg`.
///
/// ```
/// use glam::Vec3;
/// use shapegen_runtime::geometry::{Mesh, MeshLibrary, facet_transform};
/// use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Parts, RoofPitch, Surface};
/// use shapegen_runtime::Instance;
///
/// let mut library = MeshLibrary::new();
/// library.register("roof", Mesh::facet())?;
/// let meshes = library.bind_names("House", &["cube", "roof"])?;
/// let roof = meshes.iter().find(|(_, name, _)| *name == "roof").unwrap().0;
/// let facet = |a, b, c| Instance { transform: facet_transform(a, b, c).unwrap(), mesh: roof };
/// // A gable roof: two 45 degree slopes from the eaves at z = -1 and z = 1 to the
/// // ridge at y = 1, z = 0, each a quad of two facets.
/// let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
/// let model = [
///     facet(p(0.0, 0.0, 1.0), p(1.0, 0.0, 1.0), p(1.0, 1.0, 0.0)),
///     facet(p(0.0, 0.0, 1.0), p(1.0, 1.0, 0.0), p(0.0, 1.0, 0.0)),
///     facet(p(1.0, 0.0, -1.0), p(0.0, 0.0, -1.0), p(0.0, 1.0, 0.0)),
///     facet(p(1.0, 0.0, -1.0), p(0.0, 1.0, 0.0), p(1.0, 1.0, 0.0)),
/// ];
/// let surface = Surface::from_instances(&model, &meshes);
/// let pitch = RoofPitch { parts: Parts::bound(&["roof"], &meshes)?, target_deg: 30.0 };
/// assert_eq!(Objective::from(pitch).measure(&surface, &mut ObjectiveScratch::default()), 15.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RoofPitch {
    /// The meshes of the roof.
    pub parts: Parts,
    /// The mean pitch to reach, in degrees from 0 to 90.
    pub target_deg: f32,
}

/// The keys of a `roof_pitch` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoofPitchFile {
    /// The names of the roof's meshes.
    #[serde(default = "roof_parts")]
    pub parts: Vec<String>,
    /// The mean pitch to reach, in degrees.
    pub target_deg: f32,
}

/// The parts of a table that leaves them out: the mesh a building names its roofs.
fn roof_parts() -> Vec<String> {
    vec!["roof".to_owned()]
}

impl FromTable for RoofPitch {
    type File = RoofPitchFile;

    fn resolve<S: ObjectiveSource>(file: RoofPitchFile, source: &S) -> Result<Self, S::Error> {
        Ok(RoofPitch {
            parts: source.parts("parts", &file.parts)?,
            target_deg: file.target_deg,
        })
    }
}

impl ObjectiveKind for RoofPitch {
    const SENSE: Sense = Sense::Minimize;

    /// Parts that name at least one mesh and a pitch from 0 to 90 degrees.
    fn validate(&self) -> Result<(), ObjectiveError> {
        self.parts.check_named("parts")?;
        let angle = |t: f32| (0.0..=90.0).contains(&t);
        ObjectiveError::check("target_deg", self.target_deg, angle, "an angle from 0 to 90 degrees")
    }

    fn measure(&self, surface: &Surface, _: &mut ObjectiveScratch) -> f64 {
        let (mut weighted, mut total) = (0.0, 0.0);
        let triangles = surface.triangles().iter().zip(surface.normals());
        for ((t, n), &mesh) in triangles.zip(surface.mesh_ids()) {
            if n.y <= MIN_UPWARD_Y || !self.parts.contains(mesh) {
                continue;
            }
            let a = area(t);
            weighted += a * pitch_deg(n.as_dvec3());
            total += a;
        }
        let mean = if total > 0.0 { weighted / total } else { 0.0 };
        (mean - f64::from(self.target_deg)).abs()
    }
}

/// The angle in degrees between the plane of unit normal `n` and the horizontal:
/// `atan2(|(n.x, n.z)|, n.y)`.
#[inline]
fn pitch_deg(n: DVec3) -> f64 {
    n.x.hypot(n.z).atan2(n.y).to_degrees()
}
