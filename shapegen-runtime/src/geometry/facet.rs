//! Generated geometry: triangles built by a rule from its scope (a roof over a polygon,
//! an extruded footprint), placed as instances of one fixed mesh, the unit *facet*.
//!
//! Any triangle `abc` is the image of the facet `(0, 0, 0), (1, 0, 0), (0, 1, 0)` under
//! the affine map with columns `b - a`, `c - a` and the triangle's unit normal, and
//! translation `a` ([`facet_transform`]). So a generated surface is a run of facet
//! instances, and takes the instance path of every scorer, objective, exporter and
//! preview, on the CPU and the GPU, with no per-model meshes: the fixed-mesh instance
//! path is unchanged.
//!
//! A facet instance is one triangle, not a solid. The silhouette scorers and the
//! objectives measure triangles, so a facet is what it is there. The volume scorer
//! counts a model's facets together, as closed surfaces: a lattice point is covered
//! by the facets as many times as their winding number around it (the number of
//! closed, outward-wound facet surfaces it lies in), see
//! [`VolumeScorer`](crate::score::volume::VolumeScorer). A generated solid must
//! therefore be emitted whole and wound outward, as [`Polygon::extrude`] and
//! [`Polygon::roof`] build theirs.
//!
//! A grammar names the facet meshes it uses like any other mesh; the mesh registered
//! under each name must be [`Mesh::facet`]. Several names (say `facet_wall`,
//! `facet_roof`, `facet_window`) let an exporter give generated parts their own
//! materials.
//!
//! [`Polygon::extrude`]: super::Polygon::extrude
//! [`Polygon::roof`]: super::Polygon::roof

use glam::{Affine3A, Mat3A, Vec3};

use super::instance::{Instance, MeshId};
use super::mesh::Mesh;
use super::polygon::Polygon;
use super::roof::{Roof, RoofError, RoofShape};
use super::scope::Scope;

/// The facet's corners: the unit right triangle in the `z = 0` plane, facing `+z`.
pub const FACET_CORNERS: [Vec3; 3] = [Vec3::ZERO, Vec3::X, Vec3::Y];

impl Mesh {
    /// The unit facet, one triangle with corners [`FACET_CORNERS`] facing `+z`: the
    /// mesh that generated geometry is placed as (see [`facet_transform`]).
    ///
    /// ```
    /// use shapegen_runtime::geometry::{Mesh, is_facet};
    ///
    /// let facet = Mesh::facet();
    /// assert_eq!(facet.triangle_count(), 1);
    /// assert!(is_facet(&facet));
    /// assert!(!is_facet(&Mesh::unit_cube()));
    /// ```
    pub fn facet() -> Mesh {
        Mesh {
            positions: FACET_CORNERS.to_vec(),
            normals: vec![Vec3::Z; 3],
            indices: vec![0, 1, 2],
        }
    }
}

/// Whether `mesh`'s geometry is exactly the unit facet: one triangle whose corners are
/// [`FACET_CORNERS`] in that winding (normals are not read).
pub fn is_facet(mesh: &Mesh) -> bool {
    let mut triangles = mesh.triangles();
    let (Some(t), None) = (triangles.next(), triangles.next()) else {
        return false;
    };
    let corners = t.map(|i| mesh.positions.get(i as usize).copied());
    // The same triangle from any of its three corners.
    (0..3).any(|r| (0..3).all(|k| corners[(k + r) % 3] == Some(FACET_CORNERS[k])))
}

/// The transform that places the unit facet on the triangle `abc`: columns `b - a`,
/// `c - a` and the unit normal of `abc` (counter-clockwise seen from the side it
/// faces), translation `a`. `None` for a triangle with a non-finite corner or no area,
/// which a facet cannot place.
///
/// ```
/// use glam::{Vec3, vec3};
/// use shapegen_runtime::geometry::{FACET_CORNERS, facet_transform};
///
/// let (a, b, c) = (vec3(1.0, 0.0, 0.0), vec3(1.0, 2.0, 0.0), vec3(1.0, 0.0, 3.0));
/// let t = facet_transform(a, b, c).unwrap();
/// let placed = FACET_CORNERS.map(|p| t.transform_point3(p));
/// assert_eq!(placed, [a, b, c]);
/// // The facet's normal, +z, goes to the triangle's: +x here.
/// assert!(t.transform_vector3(Vec3::Z).abs_diff_eq(Vec3::X, 1e-6));
/// assert!(t.matrix3.determinant() > 0.0);
/// assert_eq!(facet_transform(a, a, c), None);
/// ```
pub fn facet_transform(a: Vec3, b: Vec3, c: Vec3) -> Option<Affine3A> {
    let (u, v) = (b - a, c - a);
    let n = u.cross(v);
    let length = n.length();
    let usable = a.is_finite() && u.is_finite() && v.is_finite() && length > 0.0;
    if !usable {
        return None;
    }
    Some(Affine3A::from_mat3_translation(
        Mat3A::from_cols(u.into(), v.into(), (n / length).into()).into(),
        a,
    ))
}

/// Appends every triangle of `mesh`, its positions placed by `place`, to `out` as an
/// instance of the facet mesh `facet`; triangles without area are left out. Returns
/// how many were appended.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::geometry::{Mesh, MeshId, emit_facets};
///
/// let mut out = Vec::new();
/// let up = Affine3A::from_translation(Vec3::Y);
/// let n = emit_facets(&Mesh::unit_cube(), |p| up.transform_point3(p), MeshId(1), &mut out);
/// assert_eq!((n, out.len()), (12, 12));
/// assert!(out.iter().all(|i| i.mesh == MeshId(1)));
/// ```
pub fn emit_facets(
    mesh: &Mesh,
    place: impl Fn(Vec3) -> Vec3,
    facet: MeshId,
    out: &mut Vec<Instance>,
) -> usize {
    let before = out.len();
    out.extend(mesh.triangles().filter_map(|t| {
        let [a, b, c] = t.map(|i| place(mesh.positions[i as usize]));
        facet_transform(a, b, c).map(|transform| Instance {
            transform,
            mesh: facet,
        })
    }));
    out.len() - before
}

/// Footprints on a box: a polygon's plane coordinates `(x, y)` lie on a face of the box
/// with `x` along the box's `x` and `y` along its `-z`, the origin at the face's
/// centre, and the polygon's `+z` up the box's `y` (a proper rotation, so windings
/// keep their sense).
impl Scope {
    /// Emits `mesh`, given in the box's frame without scaling (as
    /// [`emit_unscaled`](crate::Shape::emit_unscaled) places a mesh), as facet
    /// instances of `facet` appended to `out`. Returns how many.
    pub fn surface(self, mesh: &Mesh, facet: MeshId, out: &mut Vec<Instance>) -> usize {
        emit_facets(mesh, |p| self.frame.transform_point3(p), facet, out)
    }

    /// CGA's `extrude` of a footprint: the prism of `height` standing on `footprint`
    /// laid on the box's bottom face, as facet instances of `facet` appended to `out`.
    /// Returns how many.
    ///
    /// ```
    /// use glam::{vec2, vec3};
    /// use shapegen_runtime::geometry::{MeshId, Polygon};
    /// use shapegen_runtime::Scope;
    ///
    /// let l = Polygon::new([
    ///     vec2(-4.0, -4.0), vec2(4.0, -4.0), vec2(4.0, 0.0),
    ///     vec2(0.0, 0.0), vec2(0.0, 4.0), vec2(-4.0, 4.0),
    /// ])?;
    /// let lot = Scope::UNIT.with_size(vec3(8.0, 2.0, 8.0));
    /// let mut out = Vec::new();
    /// // Six walls of two triangles each, and the two caps of four triangles each.
    /// assert_eq!(lot.extrude_polygon(&l, 10.0, MeshId(1), &mut out), 20);
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn extrude_polygon(
        self,
        footprint: &Polygon,
        height: f32,
        facet: MeshId,
        out: &mut Vec<Instance>,
    ) -> usize {
        self.on_face(&footprint.extrude(height), 0.0, facet, out)
    }

    /// The roof of `shape` with `overhang` over `footprint` laid on the box's top face
    /// ([`Polygon::roof`]: a straight-skeleton roof on any simple polygon), as facet
    /// instances of `facet` appended to `out`. Returns the roof built, whose
    /// [`shape`](Roof::shape) says where a simpler one was built instead. A measure out
    /// of range emits nothing and says why.
    ///
    /// ```
    /// use glam::{vec2, vec3};
    /// use shapegen_runtime::geometry::{MeshId, Polygon, RoofShape};
    /// use shapegen_runtime::Scope;
    ///
    /// let l = Polygon::new([
    ///     vec2(-4.0, -4.0), vec2(4.0, -4.0), vec2(4.0, 0.0),
    ///     vec2(0.0, 0.0), vec2(0.0, 4.0), vec2(-4.0, 4.0),
    /// ])?;
    /// let house = Scope::UNIT.with_size(vec3(8.0, 6.0, 8.0));
    /// let mut out = Vec::new();
    /// let roof = house.roof_polygon(&l, RoofShape::Hip { pitch: 0.5 }, 0.3, MeshId(2), &mut out)?;
    /// assert_eq!(roof.shape, RoofShape::Hip { pitch: 0.5 });
    /// assert_eq!(out.len(), roof.mesh.triangle_count());
    /// // The roof stands on the top face: nothing of it lies below the eave.
    /// let eave = 3.0 - 0.3 * 0.5f32.tan();
    /// assert!(out.iter().all(|i| i.transform.translation.y >= eave - 1e-4));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn roof_polygon(
        self,
        footprint: &Polygon,
        shape: RoofShape,
        overhang: f32,
        facet: MeshId,
        out: &mut Vec<Instance>,
    ) -> Result<Roof, RoofError> {
        let roof = footprint.roof(shape, overhang)?;
        self.on_face(&roof.mesh, self.size.y, facet, out);
        Ok(roof)
    }

    /// Emits `mesh`, in a polygon's plane coordinates, raised by `lift` above the box's
    /// bottom face (`0` on the bottom, the box's height on the top).
    fn on_face(self, mesh: &Mesh, lift: f32, facet: MeshId, out: &mut Vec<Instance>) -> usize {
        emit_facets(
            mesh,
            |p| self.frame.transform_point3(self.plane_point(p, lift)),
            facet,
            out,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_facets_are_facets_and_others_are_not() {
        let mut m = Mesh::facet();
        m.indices = vec![1, 2, 0];
        assert!(is_facet(&m));
        m.indices = vec![0, 2, 1];
        assert!(!is_facet(&m), "the other winding faces -z");
        let mut two = Mesh::facet();
        two.indices.extend([0, 1, 2]);
        assert!(!is_facet(&two));
        let mut moved = Mesh::facet();
        moved.positions[2].y = 2.0;
        assert!(!is_facet(&moved));
    }

    #[test]
    fn placed_facets_keep_the_solid_s_volume_and_outward_normals() {
        let l = Polygon::new([
            glam::vec2(0.0, 0.0),
            glam::vec2(2.0, 0.0),
            glam::vec2(2.0, 1.0),
            glam::vec2(1.0, 1.0),
            glam::vec2(1.0, 2.0),
            glam::vec2(0.0, 2.0),
        ])
        .unwrap();
        let prism = l.extrude(3.0);
        let mut out = Vec::new();
        emit_facets(&prism, |p| p, MeshId(1), &mut out);
        let facet = FACET_CORNERS;
        let volume: f32 = out
            .iter()
            .map(|i| {
                let [a, b, c] = facet.map(|p| i.transform.transform_point3(p));
                let n = i.transform.transform_vector3(Vec3::Z);
                assert!(n.abs_diff_eq((b - a).cross(c - a).normalize(), 1e-5));
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        assert!((volume - prism.volume()).abs() < 1e-4, "{volume}");
        assert!((volume - 9.0).abs() < 1e-4);
    }
}
