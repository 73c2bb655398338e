//! [`AreaShare`]: how far the share of the surface area that some parts take is from a
//! target.

use serde::Deserialize;

use crate::evaluate::Sense;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{FromTable, ObjectiveKind, ObjectiveSource};
use crate::score::objective::parts::{Parts, area};
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;

/// How far the share of the surface area that some parts take is from a target,
/// `|share - target|` ([`Sense::Minimize`]): `share` is the world-space area of the
/// triangles whose instance's mesh is in `parts` over that of the triangles whose mesh is
/// in `of` (every triangle when `of` is `None`), in `[0, 1]`; 0 when the model has no
/// area in `of`. Every mesh of `parts` must be in `of`. A window-to-wall ratio: `parts`
/// the windows and doors, `of` those and the walls. Its table: `kind = "area_share"`,
/// `parts` and `of` (lists of mesh names; `of` may be left out) and `target`.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::geometry::{Mesh, MeshLibrary, facet_transform};
/// use shapegen_runtime::score::objective::{AreaShare, Objective, ObjectiveScratch, Parts, Surface};
/// use shapegen_runtime::{CUBE, Instance};
///
/// let mut library = MeshLibrary::new();
/// library.register("window", Mesh::facet())?;
/// let meshes = library.bind_names("House", &["cube", "window"])?;
/// let window = meshes.iter().find(|(_, name, _)| *name == "window").unwrap().0;
/// // A unit cube (area 6) and a 1 x 1 window of two facets (area 1) in front of it.
/// let corner = |x: f32, y: f32| Vec3::new(x, y, 0.6);
/// let facet = |a, b, c| Instance { transform: facet_transform(a, b, c).unwrap(), mesh: window };
/// let model = [
///     Instance { transform: Affine3A::IDENTITY, mesh: CUBE },
///     facet(corner(0.0, 0.0), corner(1.0, 0.0), corner(1.0, 1.0)),
///     facet(corner(0.0, 0.0), corner(1.0, 1.0), corner(0.0, 1.0)),
/// ];
/// let surface = Surface::from_instances(&model, &meshes);
/// let mut scratch = ObjectiveScratch::default();
///
/// let windows = Parts::bound(&["window"], &meshes)?;
/// let of_all = Objective::from(AreaShare { parts: windows.clone(), of: None, target: 0.0 });
/// assert_eq!(of_all.measure(&surface, &mut scratch), 1.0 / 7.0);
/// let of_both = Parts::bound(&["cube", "window"], &meshes)?;
/// let ratio = Objective::from(AreaShare { parts: windows, of: Some(of_both), target: 0.5 });
/// assert_eq!(ratio.measure(&surface, &mut scratch), 0.5 - 1.0 / 7.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct AreaShare {
    /// The meshes whose area is counted.
    pub parts: Parts,
    /// The meshes whose area it is a share of; every mesh when `None`.
    pub of: Option<Parts>,
    /// The share to reach, from 0 to 1.
    pub target: f32,
}

/// The keys of an `area_share` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AreaShareFile {
    /// The names of the meshes whose area is counted.
    pub parts: Vec<String>,
    /// The names of the meshes whose area it is a share of; every mesh when left out.
    #[serde(default)]
    pub of: Option<Vec<String>>,
    /// The share to reach.
    pub target: f32,
}

impl FromTable for AreaShare {
    type File = AreaShareFile;

    fn resolve<S: ObjectiveSource>(file: AreaShareFile, source: &S) -> Result<Self, S::Error> {
        Ok(AreaShare {
            parts: source.parts("parts", &file.parts)?,
            of: file.of.map(|of| source.parts("of", &of)).transpose()?,
            target: file.target,
        })
    }
}

impl ObjectiveKind for AreaShare {
    const SENSE: Sense = Sense::Minimize;

    /// Parts and `of` that name at least one mesh, parts all among `of`, and a target
    /// share from 0 to 1.
    fn validate(&self) -> Result<(), ObjectiveError> {
        self.parts.check_named("parts")?;
        if let Some(of) = &self.of {
            of.check_named("of")?;
            if !self.parts.is_subset(of) {
                return Err(ObjectiveError::PartsOutsideOf);
            }
        }
        let share = |t: f32| (0.0..=1.0).contains(&t);
        ObjectiveError::check("target", self.target, share, "a share from 0 to 1")
    }

    fn measure(&self, surface: &Surface, _: &mut ObjectiveScratch) -> f64 {
        let (mut part, mut whole) = (0.0, 0.0);
        for (t, &mesh) in surface.triangles().iter().zip(surface.mesh_ids()) {
            if self.of.as_ref().is_some_and(|of| !of.contains(mesh)) {
                continue;
            }
            let a = area(t);
            whole += a;
            if self.parts.contains(mesh) {
                part += a;
            }
        }
        let share = if whole > 0.0 { part / whole } else { 0.0 };
        (share - f64::from(self.target)).abs()
    }
}
