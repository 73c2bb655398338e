//! CGA's component split of an extruded footprint: [`Scope::walls`], one flat scope per
//! wall, and [`Scope::top_cap`] and [`Scope::bottom_cap`], the footprint's caps.
//!
//! The footprint lies on the box's bottom face as [`Scope::extrude_polygon`] lays it:
//! the polygon's `(x, y)` at the box's local `(x, -z)`, its `+z` up the box's `y`. The
//! walls, each emitted with [`emit_rect`](Scope::emit_rect) (or replaced by a facade
//! whose parts have the wall's boundary, such as an [`inset`](Scope::inset)), and the
//! two caps make the same closed, outward-facing surface as the extruded prism.

use std::iter::FusedIterator;

use glam::{Vec3, vec3};

use super::face::Face;
use super::facet::facet_transform;
use super::instance::{Instance, MeshId};
use super::polygon::Polygon;
use super::scope::Scope;

/// The walls of an extruded footprint with the faces of the box they face: see
/// [`Scope::walls`].
#[derive(Clone, Debug)]
pub struct Walls<'p> {
    scope: Scope,
    footprint: &'p Polygon,
    height: f32,
    next: usize,
}

impl Iterator for Walls<'_> {
    type Item = (Face, Scope);

    #[inline]
    fn next(&mut self) -> Option<(Face, Scope)> {
        if self.next == self.footprint.len() {
            return None;
        }
        let wall = self.scope.wall(self.footprint, self.height, self.next);
        self.next += 1;
        Some(wall)
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.footprint.len() - self.next;
        (left, Some(left))
    }
}

impl ExactSizeIterator for Walls<'_> {}
impl FusedIterator for Walls<'_> {}

impl Scope {
    /// CGA's `comp(f)` of the prism of `height` on `footprint` (laid on the box's
    /// bottom face as [`extrude_polygon`](Self::extrude_polygon) lays it): one flat
    /// scope per footprint edge, in the footprint's counter-clockwise order (wall `i`
    /// stands on edge `i`), with the face of the box it faces.
    ///
    /// A wall's local `x` runs along its edge in the footprint's order, its `y` up the
    /// box's `y` and its `z` is its outward normal; it is centred on the wall's
    /// rectangle, of size `(edge length, height, 0)`, so that
    /// [`emit_rect`](Self::emit_rect) emits the wall facing out. Its [`Face`] is the
    /// box's side whose local axis is nearest its outward normal (`+z` front, `-z`
    /// back, `-x` left, `+x` right; a normal halfway between counts as front or back),
    /// so that rules can treat the front differently.
    ///
    /// With [`top_cap`](Self::top_cap) and [`bottom_cap`](Self::bottom_cap), the walls
    /// emitted close the prism that [`extrude_polygon`](Self::extrude_polygon) emits.
    /// `height` should not be negative.
    ///
    /// ```
    /// use glam::{vec2, vec3};
    /// use shapegen_runtime::geometry::Polygon;
    /// use shapegen_runtime::{Axis, Face, Scope};
    ///
    /// let l = Polygon::new([
    ///     vec2(-4.0, -4.0), vec2(4.0, -4.0), vec2(4.0, 0.0),
    ///     vec2(0.0, 0.0), vec2(0.0, 4.0), vec2(-4.0, 4.0),
    /// ])?;
    /// let lot = Scope::UNIT.with_size(vec3(8.0, 10.0, 8.0));
    /// let walls: Vec<_> = lot.walls(&l, 10.0).collect();
    /// let faces: Vec<Face> = walls.iter().map(|(f, _)| *f).collect();
    /// use Face::*;
    /// assert_eq!(faces, [Front, Right, Back, Right, Back, Left]);
    /// // The first wall stands on the edge at plane y = -4: the box's z = 4, its front.
    /// let (_, front) = walls[0];
    /// assert_eq!(front.size(), vec3(8.0, 10.0, 0.0));
    /// assert_eq!(front.origin(), vec3(0.0, 0.0, 4.0));
    /// assert_eq!(front.axis(Axis::Z), vec3(0.0, 0.0, 1.0));
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn walls(self, footprint: &Polygon, height: f32) -> Walls<'_> {
        Walls {
            scope: self,
            footprint,
            height,
            next: 0,
        }
    }

    /// Wall `i` of [`walls`](Self::walls).
    fn wall(self, footprint: &Polygon, height: f32, i: usize) -> (Face, Scope) {
        let (a, b) = footprint.edge(i);
        let length = a.distance(b);
        let d = ((b - a) / length).as_vec2();
        let middle = ((a + b) / 2.0).as_vec2();
        // Plane (x, y, z) is the box's (x, -z, y): the edge's direction, up, and the
        // outward normal (d.y, -d.x) of a counter-clockwise polygon.
        let x = vec3(d.x, 0.0, -d.y);
        let z = vec3(d.y, 0.0, d.x);
        let centre = self.plane_point(vec3(middle.x, middle.y, 0.0), height / 2.0);
        let face = if z.z.abs() >= z.x.abs() {
            if z.z > 0.0 { Face::Front } else { Face::Back }
        } else if z.x > 0.0 {
            Face::Right
        } else {
            Face::Left
        };
        let size = vec3(length as f32, height, 0.0);
        (face, self.part(centre, [x, Vec3::Y, z], size))
    }

    /// The top of the prism of `height` on `footprint` (see [`walls`](Self::walls)):
    /// the footprint triangulated at `height` above the box's bottom face, facing up
    /// (the box's `+y`), as facet instances of `facet` appended to `out`. Returns how
    /// many: `footprint.len() - 2`.
    ///
    /// ```
    /// use glam::{Vec3, vec2, vec3};
    /// use shapegen_runtime::geometry::Polygon;
    /// use shapegen_runtime::{MeshId, Scope};
    ///
    /// let lot = Scope::UNIT.with_size(vec3(4.0, 6.0, 4.0));
    /// let square = Polygon::rectangle(vec2(4.0, 4.0))?;
    /// let mut out = Vec::new();
    /// assert_eq!(lot.top_cap(&square, 2.0, MeshId(1), &mut out), 2);
    /// assert_eq!(lot.bottom_cap(&square, MeshId(1), &mut out), 2);
    /// let up = |i: usize| out[i].transform.transform_vector3(Vec3::Z);
    /// assert_eq!((out[0].transform.translation.y, up(0)), (-1.0, Vec3::Y));
    /// assert_eq!((out[2].transform.translation.y, up(2)), (-3.0, Vec3::NEG_Y));
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn top_cap(
        self,
        footprint: &Polygon,
        height: f32,
        facet: MeshId,
        out: &mut Vec<Instance>,
    ) -> usize {
        self.cap(footprint, height, true, facet, out)
    }

    /// The bottom of the prism on `footprint` (see [`walls`](Self::walls)): the
    /// footprint triangulated on the box's bottom face, facing down (the box's `-y`),
    /// as facet instances of `facet` appended to `out`. Returns how many:
    /// `footprint.len() - 2`. See [`top_cap`](Self::top_cap) for an example.
    pub fn bottom_cap(self, footprint: &Polygon, facet: MeshId, out: &mut Vec<Instance>) -> usize {
        self.cap(footprint, 0.0, false, facet, out)
    }

    /// The footprint's triangles at `height` above the bottom face, facing up or down.
    fn cap(
        self,
        footprint: &Polygon,
        height: f32,
        up: bool,
        facet: MeshId,
        out: &mut Vec<Instance>,
    ) -> usize {
        let points: Vec<Vec3> = footprint
            .points()
            .iter()
            .map(|p| {
                let p = p.as_vec2();
                self.frame
                    .transform_point3(self.plane_point(vec3(p.x, p.y, 0.0), height))
            })
            .collect();
        let before = out.len();
        out.extend(
            footprint
                .triangulate()
                .into_iter()
                .filter_map(|[a, b, c]| {
                    let (a, b, c) = (points[a], points[b], points[c]);
                    if up {
                        facet_transform(a, b, c)
                    } else {
                        facet_transform(a, c, b)
                    }
                })
                .map(|transform| Instance {
                    transform,
                    mesh: facet,
                }),
        );
        out.len() - before
    }
}

#[cfg(test)]
mod tests {
    use glam::{Affine3A, DVec2, Quat};

    use super::super::closed::tests::{assert_watertight, volume as signed_volume};
    use super::*;
    use crate::geometry::axis::Axis;

    const FACET: MeshId = MeshId(1);

    /// A rectangle, an L, a U and a concave outline with slanted edges.
    fn footprints() -> Vec<Polygon> {
        vec![
            Polygon::rectangle(glam::vec2(10.0, 6.0)).unwrap(),
            Polygon::l_shape(),
            Polygon::u_shape(),
            Polygon::slanted(),
        ]
    }

    /// A 9 x 5 x 8 box, turned about two axes and moved away from the origin.
    fn lot() -> Scope {
        Scope::new(
            Affine3A::from_rotation_translation(
                Quat::from_rotation_y(0.7) * Quat::from_rotation_x(0.15),
                vec3(10.0, 20.0, -30.0),
            ),
            vec3(9.0, 5.0, 8.0),
        )
    }

    #[test]
    fn walls_and_caps_close_the_extruded_prism() {
        let height = 7.0;
        for footprint in footprints() {
            let mut out = Vec::new();
            let walls: Vec<_> = lot().walls(&footprint, height).collect();
            assert_eq!(walls.len(), footprint.len());
            for (_, wall) in &walls {
                assert_eq!(wall.emit_rect(FACET, &mut out), 2);
            }
            let n = footprint.len() - 2;
            assert_eq!(lot().top_cap(&footprint, height, FACET, &mut out), n);
            assert_eq!(lot().bottom_cap(&footprint, FACET, &mut out), n);
            assert_watertight(&out);

            let mut prism = Vec::new();
            lot().extrude_polygon(&footprint, height, FACET, &mut prism);
            let (volume, want) = (signed_volume(&out), signed_volume(&prism));
            let area = footprint.area() * f64::from(height);
            assert!((want - area).abs() < 1e-3 * area, "{want} {area}");
            assert!((volume - want).abs() < 1e-3 * area, "{volume} {want}");
        }
    }

    #[test]
    fn walls_stand_on_their_edges_facing_out() {
        let lot = lot();
        let inverse = lot.frame().inverse();
        for footprint in footprints() {
            for (i, (face, wall)) in lot.walls(&footprint, 7.0).enumerate() {
                let (a, b) = footprint.edge(i);
                assert!((f64::from(wall.size().x) - a.distance(b)).abs() < 1e-5);
                assert_eq!((wall.size().y, wall.size().z), (7.0, 0.0));
                // In the box's axes: the wall's bottom corners are the edge's ends laid
                // on the bottom face, x runs from a to b, y is up, z is outward.
                let local = |p: Vec3| inverse.transform_point3(wall.to_world(p));
                let on_face = |p: DVec2| vec3(p.x as f32, -2.5, -p.y as f32);
                assert!(local(vec3(-0.5, -0.5, 0.0)).abs_diff_eq(on_face(a), 1e-4));
                assert!(local(vec3(0.5, -0.5, 0.0)).abs_diff_eq(on_face(b), 1e-4));
                let top = local(vec3(-0.5, 0.5, 0.0));
                assert!(top.abs_diff_eq(on_face(a) + vec3(0.0, 7.0, 0.0), 1e-4));
                let axis = |k: Axis| inverse.transform_vector3(wall.axis(k));
                assert!(axis(Axis::Y).abs_diff_eq(Vec3::Y, 1e-5));
                let inward = footprint.inward_normal(i).as_vec2();
                let outward = -vec3(inward.x, 0.0, -inward.y);
                assert!(axis(Axis::Z).abs_diff_eq(outward, 1e-5));
                // The face is the box side nearest the normal.
                let nearest = Face::ALL[..4]
                    .iter()
                    .copied()
                    .max_by(|f, g| f.normal().dot(outward).total_cmp(&g.normal().dot(outward)))
                    .unwrap();
                assert_eq!(face, nearest, "edge {i} of {footprint:?}");
            }
        }
        use Face::*;
        let rectangle = &footprints()[0];
        let faces: Vec<Face> = lot.walls(rectangle, 1.0).map(|(f, _)| f).collect();
        assert_eq!(faces, [Front, Right, Back, Left]);
    }
}
