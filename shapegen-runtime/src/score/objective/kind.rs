//! The objectives and how each is measured.

use glam::{Vec2, Vec3};

use super::chamfer::ChamferMatch;
use super::error::ObjectiveError;
use super::normals::{NormalGrid, cluster, spread};
use super::parts::{Parts, area_share, roof_pitch};
use super::projection::{ProjectionMatch, View};
use super::surface::Surface;
use crate::evaluate::Sense;
use crate::score::silhouette::raster::Coverage;

/// One geometric objective: a raw value measured on a model's [`Surface`], with the
/// direction ([`sense`](Self::sense)) in which it is better.
///
/// ```
/// use glam::{Affine3A, Vec2};
/// use shapegen_runtime::evaluate::Sense;
/// use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Surface};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
/// let mut scratch = ObjectiveScratch::default();
///
/// let height = Objective::Height { target: 2.0 };
/// assert_eq!(height.measure(&cube, &mut scratch), 1.5);
/// assert_eq!((height.name(), height.sense()), ("height", Sense::Minimize));
///
/// let normals = Objective::UniqueNormals { tolerance_deg: 1.0 };
/// assert_eq!(normals.measure(&cube, &mut scratch), 6.0);
///
/// let footprint = Objective::FootprintExcess { min: Vec2::splat(-0.25), max: Vec2::splat(1.0) };
/// assert_eq!(footprint.measure(&cube, &mut scratch), 0.5);
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Objective {
    /// Distance of the model's top to a target height, `|max_y - target|`, `max_y` the
    /// largest `y` of the surface's vertices ([`Sense::Minimize`]). An empty model
    /// stands on the ground, `max_y = 0`: its value is `|target|`.
    Height {
        /// The height the model's top should reach.
        target: f32,
    },
    /// Number of distinct face normals ([`Sense::Maximize`]). The surface's normals are
    /// clustered greedily in triangle order: each joins the first distinct normal found
    /// so far within `tolerance_deg` of it (`n . r >= cos(tolerance)`), else it is a new
    /// distinct normal. Any two distinct normals are thus more than the tolerance apart;
    /// a unit cube has 6; an empty model 0. Use a tolerance above rounding (a degree,
    /// say), so that the two triangles of a rotated quad agree.
    UniqueNormals {
        /// Largest angle, in degrees (0 to 180), between normals counted as one.
        tolerance_deg: f32,
    },
    /// Sum over the distinct normals (as for [`UniqueNormals`](Self::UniqueNormals)) of
    /// the angle in radians to the nearest other distinct normal ([`Sense::Maximize`]);
    /// 0 with fewer than two. A cube: `6 * pi / 2`.
    NormalSpread {
        /// Largest angle, in degrees (0 to 180), between normals counted as one.
        tolerance_deg: f32,
    },
    /// How far the model's x/z extent `[lo, hi]` (its bounding box) exceeds the
    /// rectangle `[min, max]` (`x`, then `z`): `sum over x, z of max(0, min - lo) +
    /// max(0, hi - max)` ([`Sense::Minimize`]); 0 for an empty model.
    FootprintExcess {
        /// Smallest allowed `x` and `z`.
        min: Vec2,
        /// Largest allowed `x` and `z`.
        max: Vec2,
    },
    /// Fraction of the pixels of an orthographic projection that match a target image,
    /// in `[0, 1]` ([`Sense::Maximize`]); see [`ProjectionMatch`].
    Projection(ProjectionMatch),
    /// Symmetric Chamfer distance to a point cloud, in world units
    /// ([`Sense::Minimize`]); see [`ChamferMatch`].
    Chamfer(ChamferMatch),
    /// How far the share of the surface area that some parts take is from a target,
    /// `|share - target|` ([`Sense::Minimize`]): `share` is the world-space area of the
    /// triangles whose instance's mesh is in `parts` over that of the triangles whose
    /// mesh is in `of` (every triangle when `of` is `None`), in `[0, 1]`; 0 when the
    /// model has no area in `of`. Every mesh of `parts` must be in `of`. A window-to-wall
    /// ratio: `parts` the windows and doors, `of` those and the walls.
    ///
    /// ```
    /// use glam::{Affine3A, Vec3};
    /// use shapegen_runtime::geometry::{Mesh, MeshLibrary, facet_transform};
    /// use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Parts, Surface};
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
    /// let of_all = Objective::AreaShare { parts: windows.clone(), of: None, target: 0.0 };
    /// assert_eq!(of_all.measure(&surface, &mut scratch), 1.0 / 7.0);
    /// let of_both = Parts::bound(&["cube", "window"], &meshes)?;
    /// let ratio = Objective::AreaShare { parts: windows, of: Some(of_both), target: 0.5 };
    /// assert_eq!(ratio.measure(&surface, &mut scratch), 0.5 - 1.0 / 7.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    AreaShare {
        /// The meshes whose area is counted.
        parts: Parts,
        /// The meshes whose area it is a share of; every mesh when `None`.
        of: Option<Parts>,
        /// The share to reach, from 0 to 1.
        target: f32,
    },
    /// How far the area-weighted mean pitch of a roof is from a target, in degrees,
    /// `|mean - target_deg|` ([`Sense::Minimize`]).
    ///
    /// A triangle's pitch is the angle between its plane and the horizontal,
    /// `atan2(|(n.x, n.z)|, n.y)` for its unit normal `n`: 0 flat, towards 90 vertical.
    /// Counted are the triangles whose instance's mesh is in `parts` and that face up,
    /// `n.y >` [`MIN_UPWARD_Y`](super::MIN_UPWARD_Y) (`1e-4`, a pitch below about 89.994
    /// degrees), each weighted by its world-space area: a roof's underside (`n.y < 0`)
    /// and its vertical gable ends (`n.y = 0`, give or take rounding) are not its pitch.
    /// A model with no such triangle has mean 0.
    ///
    /// ```
    /// use glam::Vec3;
    /// use shapegen_runtime::geometry::{Mesh, MeshLibrary, facet_transform};
    /// use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Parts, Surface};
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
    /// let pitch = Objective::RoofPitch { parts: Parts::bound(&["roof"], &meshes)?, target_deg: 30.0 };
    /// assert_eq!(pitch.measure(&surface, &mut ObjectiveScratch::default()), 15.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    RoofPitch {
        /// The meshes of the roof.
        parts: Parts,
        /// The mean pitch to reach, in degrees from 0 to 90.
        target_deg: f32,
    },
}

/// Reusable working memory for measuring [objectives](Objective): one per worker.
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
}

impl Objective {
    /// The direction in which the objective's value is better.
    pub fn sense(&self) -> Sense {
        match self {
            Objective::Height { .. }
            | Objective::FootprintExcess { .. }
            | Objective::Chamfer(_)
            | Objective::AreaShare { .. }
            | Objective::RoofPitch { .. } => Sense::Minimize,
            Objective::UniqueNormals { .. }
            | Objective::NormalSpread { .. }
            | Objective::Projection(_) => Sense::Maximize,
        }
    }

    /// The kind of objective, in snake case: `height`, `unique_normals`,
    /// `normal_spread`, `footprint_excess`, `top_match`, `front_match`, `chamfer`,
    /// `area_share` or `roof_pitch`.
    pub fn name(&self) -> &'static str {
        match self {
            Objective::Height { .. } => "height",
            Objective::UniqueNormals { .. } => "unique_normals",
            Objective::NormalSpread { .. } => "normal_spread",
            Objective::FootprintExcess { .. } => "footprint_excess",
            Objective::Projection(p) => match p.view() {
                View::Top => "top_match",
                View::Front => "front_match",
            },
            Objective::Chamfer(_) => "chamfer",
            Objective::AreaShare { .. } => "area_share",
            Objective::RoofPitch { .. } => "roof_pitch",
        }
    }

    /// Checks the parameters: finite numbers, tolerances from 0 to 180 degrees, a
    /// footprint with `min <= max` in both coordinates, an area share from 0 to 1 of
    /// parts that are all among `of`, a pitch from 0 to 90 degrees, and parts that name
    /// at least one mesh (a [`ProjectionMatch`] is checked when it is made).
    pub fn validate(&self) -> Result<(), ObjectiveError> {
        match *self {
            Objective::AreaShare { ref parts, .. } | Objective::RoofPitch { ref parts, .. }
                if parts.is_empty() =>
            {
                Err(ObjectiveError::NoParts { field: "parts" })
            }
            Objective::AreaShare {
                of: Some(ref of), ..
            } if of.is_empty() => Err(ObjectiveError::NoParts { field: "of" }),
            Objective::AreaShare {
                ref parts,
                of: Some(ref of),
                ..
            } if !parts.is_subset(of) => Err(ObjectiveError::PartsOutsideOf),
            Objective::AreaShare { target, .. } if !(0.0..=1.0).contains(&target) => {
                Err(ObjectiveError::Parameter {
                    field: "target",
                    value: target,
                    valid: "a share from 0 to 1",
                })
            }
            Objective::RoofPitch { target_deg, .. } if !(0.0..=90.0).contains(&target_deg) => {
                Err(ObjectiveError::Parameter {
                    field: "target_deg",
                    value: target_deg,
                    valid: "an angle from 0 to 90 degrees",
                })
            }
            Objective::Height { target } if !target.is_finite() => Err(ObjectiveError::Parameter {
                field: "target",
                value: target,
                valid: "a finite number",
            }),
            Objective::UniqueNormals { tolerance_deg }
            | Objective::NormalSpread { tolerance_deg }
                if !(0.0..=180.0).contains(&tolerance_deg) =>
            {
                Err(ObjectiveError::Parameter {
                    field: "tolerance_deg",
                    value: tolerance_deg,
                    valid: "an angle from 0 to 180 degrees",
                })
            }
            Objective::FootprintExcess { min, max }
                if !(min.is_finite() && max.is_finite() && min.cmple(max).all()) =>
            {
                Err(ObjectiveError::Footprint { min, max })
            }
            _ => Ok(()),
        }
    }

    /// The objective's raw value for `surface` (see each variant for its formula).
    pub fn measure(&self, surface: &Surface, scratch: &mut ObjectiveScratch) -> f64 {
        scratch.forget();
        self.measure_same(surface, scratch)
    }

    /// [`measure`](Self::measure), reusing the distinct normals `scratch` holds if they
    /// were clustered for this `surface` (the caller calls
    /// [`forget`](ObjectiveScratch::forget) between surfaces).
    pub(super) fn measure_same(&self, surface: &Surface, scratch: &mut ObjectiveScratch) -> f64 {
        match self {
            Objective::Height { target } => {
                let top = surface.bounds().map_or(0.0, |(_, hi)| hi.y);
                (f64::from(top) - f64::from(*target)).abs()
            }
            Objective::UniqueNormals { tolerance_deg } => {
                scratch.cluster(surface, *tolerance_deg);
                scratch.distinct.len() as f64
            }
            Objective::NormalSpread { tolerance_deg } => {
                scratch.cluster(surface, *tolerance_deg);
                spread(&scratch.distinct, &mut scratch.grid)
            }
            Objective::FootprintExcess { min, max } => surface.bounds().map_or(0.0, |(lo, hi)| {
                let (lo, hi) = (Vec2::new(lo.x, lo.z), Vec2::new(hi.x, hi.z));
                let excess = |limit: f32, v: f32| (f64::from(v) - f64::from(limit)).max(0.0);
                excess(lo.x, min.x)
                    + excess(lo.y, min.y)
                    + excess(max.x, hi.x)
                    + excess(max.y, hi.y)
            }),
            Objective::Projection(p) => p.score_with(surface, &mut scratch.coverage),
            Objective::Chamfer(c) => c.measure(surface),
            Objective::AreaShare { parts, of, target } => {
                area_share(surface, parts, of.as_ref(), *target)
            }
            Objective::RoofPitch { parts, target_deg } => roof_pitch(surface, parts, *target_deg),
        }
    }
}
