//! Roofs over a box's top as instances of four fixed unit meshes, so that roofs on
//! rectangular scopes take the instance path of every scorer, exporter and preview.
//!
//! A flat, shed, gable or pyramid roof over a `w x d` rectangle is its unit mesh scaled
//! to the roof's box; a hip roof is not (its hip ends keep their pitch as the rectangle
//! stretches) and is placed as a gable prism over the middle with a hip end at each
//! side, three instances that meet without overlap.

use glam::{DVec3, Vec3, vec3};

use super::super::polygon::Polygon;
use super::super::solid::Solid;
use super::shape::{RoofError, RoofShape, check};
use crate::geometry::instance::{CUBE, Instance, MeshId};
use crate::geometry::mesh::Mesh;
use crate::geometry::scope::Scope;

/// A unit mesh roofs over boxes are made of, spanning `[-0.5, 0.5]` on each axis with
/// `+y` up and its floor at `y = -0.5`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RoofPiece {
    /// A triangular prism: the ridge along `x` at the top, gable ends facing `-x` and
    /// `+x`, the roof faces falling toward `-z` and `+z`.
    Gable,
    /// A wedge: one face rising from the front (`+z`) eave to the top of the back
    /// (`-z`) wall.
    Shed,
    /// A pyramid with its apex above the centre.
    Pyramid,
    /// Half a pyramid cut at `x = -0.5`: the apex above the middle of the cut, the hip
    /// face toward `+x`; the end of a hip roof.
    HipEnd,
}

impl RoofPiece {
    /// All pieces.
    pub const ALL: [RoofPiece; 4] = [
        RoofPiece::Gable,
        RoofPiece::Shed,
        RoofPiece::Pyramid,
        RoofPiece::HipEnd,
    ];

    /// The name a mesh library registers the piece under.
    pub fn name(self) -> &'static str {
        match self {
            RoofPiece::Gable => "roof_gable",
            RoofPiece::Shed => "roof_shed",
            RoofPiece::Pyramid => "roof_pyramid",
            RoofPiece::HipEnd => "roof_hip_end",
        }
    }

    /// The piece's closed unit mesh, flat-shaded.
    ///
    /// ```
    /// use shapegen_runtime::geometry::RoofPiece;
    ///
    /// for piece in RoofPiece::ALL {
    ///     let mesh = piece.mesh();
    ///     assert!(mesh.is_closed());
    ///     let (lo, hi) = mesh.bounds().unwrap();
    ///     assert!(lo.abs_diff_eq(glam::Vec3::splat(-0.5), 1e-6), "{piece:?}");
    ///     assert!(hi.abs_diff_eq(glam::Vec3::splat(0.5), 1e-6), "{piece:?}");
    /// }
    /// // A pyramid fills a third of its box, half a gable prism half.
    /// assert!((RoofPiece::Pyramid.mesh().volume() - 1.0 / 3.0).abs() < 1e-6);
    /// assert!((RoofPiece::Gable.mesh().volume() - 0.5).abs() < 1e-6);
    /// ```
    pub fn mesh(self) -> Mesh {
        let square = Polygon::rectangle(glam::Vec2::ONE).expect("a unit square");
        let pitch = std::f32::consts::FRAC_PI_4;
        // Built in plane coordinates (x, y on the floor, z up), then fitted to the unit
        // box with y up: plane y is the box's -z, as on a box's top face.
        let (mesh, lo, hi) = match self {
            RoofPiece::Gable => {
                let long = Polygon::rectangle(glam::vec2(2.0, 1.0)).expect("a rectangle");
                let roof = long.roof(RoofShape::Gable { pitch }, 0.0);
                (roof.expect("a gable over a rectangle").mesh, 0.0, 0.5)
            }
            RoofPiece::Shed => {
                let roof = square.roof(RoofShape::Shed { pitch }, 0.0);
                (roof.expect("a shed over a square").mesh, 0.0, 1.0)
            }
            RoofPiece::Pyramid => {
                let roof = square.roof(RoofShape::Pyramid { pitch }, 0.0);
                (roof.expect("a pyramid over a square").mesh, 0.0, 0.5)
            }
            RoofPiece::HipEnd => (hip_end(), 0.0, 0.5),
        };
        fit(mesh, lo, hi)
    }
}

/// Half a pyramid over `[-0.5, 0.5]^2` of height 0.5 cut at `x = -0.5`: the apex over
/// `(-0.5, 0)`.
fn hip_end() -> Mesh {
    let floor = Polygon::rectangle(glam::Vec2::ONE).expect("a unit square");
    let apex = DVec3::new(-0.5, 0.0, 0.5);
    let mut solid = Solid::new(1e-6);
    solid.cap(&floor, false, |_| 0.0);
    for i in 0..floor.len() {
        let (a, b) = floor.edge(i);
        solid.triangle(a.extend(0.0), b.extend(0.0), apex);
    }
    solid.finish()
}

/// The mesh in plane coordinates, `z` from `lo` to `hi`, fitted to the unit box with `+y`
/// up: scaled so each axis spans 1, turned so plane `z` is `y` and plane `y` is `-z`.
fn fit(mut mesh: Mesh, lo: f32, hi: f32) -> Mesh {
    let (min, max) = mesh.bounds().expect("a roof has corners");
    let size = vec3(max.x - min.x, max.y - min.y, hi - lo);
    let centre = vec3(
        (min.x + max.x) / 2.0,
        (min.y + max.y) / 2.0,
        (lo + hi) / 2.0,
    );
    for p in &mut mesh.positions {
        let q = (*p - centre) / size;
        *p = vec3(q.x, q.z, -q.y);
    }
    // A positive scale and a rotation keep the winding; the normals are the faces'.
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a).normalize_or(Vec3::Y);
        for &i in t {
            mesh.normals[i as usize] = n;
        }
    }
    mesh
}

/// The mesh ids a grammar registered the [`RoofPiece`]s under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RoofMeshes {
    /// [`RoofPiece::Gable`].
    pub gable: MeshId,
    /// [`RoofPiece::Shed`].
    pub shed: MeshId,
    /// [`RoofPiece::Pyramid`].
    pub pyramid: MeshId,
    /// [`RoofPiece::HipEnd`].
    pub hip_end: MeshId,
}

impl Scope {
    /// The roof of `shape` with `overhang` on the top of this box, as instances of the
    /// [`RoofPiece`] meshes (and [`CUBE`] for a flat slab), appended to `out`: the same
    /// solid [`Polygon::roof`] builds over the box's top rectangle. The ridge of a gable
    /// or hip roof runs along the longer of the box's `x` and `z`; a shed rises toward
    /// the box's back (`-z`).
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::geometry::{MeshId, RoofMeshes, RoofShape};
    /// use shapegen_runtime::Scope;
    ///
    /// let meshes = RoofMeshes { gable: MeshId(1), shed: MeshId(2), pyramid: MeshId(3), hip_end: MeshId(4) };
    /// let house = Scope::UNIT.with_size(vec3(10.0, 6.0, 4.0));
    /// let mut roof = Vec::new();
    /// house.roof(RoofShape::Hip { pitch: 0.6 }, 0.0, &meshes, &mut roof)?;
    /// // A gable prism over the middle, a hip end at each side.
    /// assert_eq!(roof.iter().map(|i| i.mesh.0).collect::<Vec<_>>(), [1, 4, 4]);
    /// # Ok::<(), shapegen_runtime::geometry::RoofError>(())
    /// ```
    pub fn roof(
        self,
        shape: RoofShape,
        overhang: f32,
        meshes: &RoofMeshes,
        out: &mut Vec<Instance>,
    ) -> Result<(), RoofError> {
        check(shape, overhang)?;
        let slope = shape.pitch().tan();
        // The eave's rectangle, along the box's x and z, and its height below the top.
        let w = self.size.x + 2.0 * overhang;
        let d = self.size.z + 2.0 * overhang;
        let top = self.size.y / 2.0 - overhang * slope;
        // The roof's frame: on the box's top, turned a quarter so its x is the long side.
        let (scope, long, short) = if w >= d || matches!(shape, RoofShape::Shed { .. }) {
            (self, w, d)
        } else {
            (self.rotate_y(std::f32::consts::FRAC_PI_2), d, w)
        };
        let mut place = |mesh: MeshId, along: f32, length: f32, height: f32, turn: bool| {
            let mut s = scope
                .translate(vec3(along, top + height / 2.0, 0.0))
                .with_size(vec3(length, height, short));
            if turn {
                s = s.rotate_y(std::f32::consts::PI);
            }
            out.push(Instance {
                transform: s.transform(),
                mesh,
            });
        };
        match shape {
            RoofShape::Flat { thickness } => place(CUBE, 0.0, long, thickness, false),
            RoofShape::Shed { .. } => place(meshes.shed, 0.0, long, short * slope, false),
            RoofShape::Gable { .. } => place(meshes.gable, 0.0, long, short / 2.0 * slope, false),
            RoofShape::Pyramid { .. } => {
                place(meshes.pyramid, 0.0, long, short / 2.0 * slope, false)
            }
            RoofShape::Hip { .. } => {
                let h = short / 2.0 * slope;
                let middle = long - short;
                if middle > 0.0 {
                    place(meshes.gable, 0.0, middle, h, false);
                }
                let end = short / 2.0;
                let at = middle / 2.0 + end / 2.0;
                place(meshes.hip_end, at, end, h, false);
                place(meshes.hip_end, -at, end, h, true);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat3, vec2};

    use super::*;

    /// Plane coordinates (`x`, `y` on the floor, `z` up) to a box's (`y` up, plane `y`
    /// the box's `-z`).
    fn plane_to_box() -> Mat3 {
        Mat3::from_cols(Vec3::X, Vec3::NEG_Z, Vec3::Y)
    }

    /// The volume of the instances, with each piece's mesh.
    fn volume(instances: &[Instance]) -> f32 {
        instances
            .iter()
            .map(|i| {
                let mesh = match i.mesh {
                    CUBE => Mesh::unit_cube(),
                    MeshId(1) => RoofPiece::Gable.mesh(),
                    MeshId(2) => RoofPiece::Shed.mesh(),
                    MeshId(3) => RoofPiece::Pyramid.mesh(),
                    _ => RoofPiece::HipEnd.mesh(),
                };
                mesh.volume() * i.transform.matrix3.determinant()
            })
            .sum()
    }

    #[test]
    fn instanced_roofs_match_the_polygon_roofs() {
        let meshes = RoofMeshes {
            gable: MeshId(1),
            shed: MeshId(2),
            pyramid: MeshId(3),
            hip_end: MeshId(4),
        };
        for (w, d) in [(10.0, 4.0), (4.0, 10.0), (5.0, 5.0), (3.0, 7.5)] {
            for shape in [
                RoofShape::Flat { thickness: 0.4 },
                RoofShape::Shed { pitch: 0.3 },
                RoofShape::Gable { pitch: 0.7 },
                RoofShape::Hip { pitch: 0.5 },
                RoofShape::Pyramid { pitch: 0.9 },
            ] {
                for overhang in [0.0, 0.5] {
                    let house = Scope::UNIT.with_size(vec3(w, 3.0, d));
                    let mut out = Vec::new();
                    house.roof(shape, overhang, &meshes, &mut out).unwrap();
                    let polygon = Polygon::rectangle(vec2(w, d)).unwrap();
                    let roof = polygon.roof(shape, overhang).unwrap();
                    let want = roof.mesh.volume();
                    let got = volume(&out);
                    assert!(
                        (got - want).abs() <= 1e-4 * want,
                        "{shape:?} {w}x{d} +{overhang}: {got} vs {want}"
                    );
                    // The same bounds, in the box's frame (plane y is the box's -z).
                    let (lo, hi) = roof.mesh.bounds().unwrap();
                    let turn = plane_to_box();
                    let (a, b) = (turn * lo, turn * hi);
                    let (want_lo, want_hi) = (
                        a.min(b) + vec3(0.0, 1.5, 0.0),
                        a.max(b) + vec3(0.0, 1.5, 0.0),
                    );
                    let mut got_lo = Vec3::MAX;
                    let mut got_hi = Vec3::MIN;
                    for i in &out {
                        for x in [-0.5, 0.5] {
                            for y in [-0.5, 0.5] {
                                for z in [-0.5, 0.5] {
                                    let p = i.transform.transform_point3(vec3(x, y, z));
                                    got_lo = got_lo.min(p);
                                    got_hi = got_hi.max(p);
                                }
                            }
                        }
                    }
                    assert!(
                        got_lo.abs_diff_eq(want_lo, 1e-4),
                        "{shape:?} {got_lo} {want_lo}"
                    );
                    assert!(
                        got_hi.abs_diff_eq(want_hi, 1e-4),
                        "{shape:?} {got_hi} {want_hi}"
                    );
                }
            }
        }
    }

    #[test]
    fn pieces_are_closed_unit_solids() {
        for piece in RoofPiece::ALL {
            let mesh = piece.mesh();
            mesh.validate(piece.name()).unwrap();
            assert!(mesh.is_closed(), "{piece:?}");
            assert!(mesh.volume() > 0.0);
        }
    }
}
