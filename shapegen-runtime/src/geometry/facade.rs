//! Facade operations on flat scopes: [`Scope::emit_rect`], which emits a scope's front
//! rectangle as facets, and [`Scope::inset`], which recesses an opening (a window or a
//! door) into a facade tile.
//!
//! Both keep a surface closed: the parts of an [`Inset`], each emitted with
//! [`emit_rect`](Scope::emit_rect), have the tile's rectangle as their boundary and
//! face the way the tile does, so a wall tile of a closed solid replaced by its inset
//! leaves the solid closed, less the recess.

use glam::{Vec3, vec3};

use super::facet::facet_transform;
use super::instance::{Instance, MeshId};
use super::scope::Scope;

/// The margins of an [`inset`](Scope::inset): absolute lengths from the tile's sides to
/// the opening's, in the tile's local axes (left is `-x`, bottom is `-y`).
///
/// ```
/// use shapegen_runtime::geometry::Margins;
///
/// let window = Margins::new(0.5, 0.5, 0.9, 0.4);
/// assert_eq!(window.bottom, 0.9);
/// assert_eq!(Margins::uniform(0.3), Margins::new(0.3, 0.3, 0.3, 0.3));
/// // A door stands on the tile's bottom.
/// assert_eq!(Margins::door(0.6, 0.5), Margins::new(0.6, 0.6, 0.0, 0.5));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Margins {
    /// From the tile's left side (`-x`) to the opening's.
    pub left: f32,
    /// From the tile's right side (`+x`) to the opening's.
    pub right: f32,
    /// From the tile's bottom (`-y`) to the opening's.
    pub bottom: f32,
    /// From the tile's top (`+y`) to the opening's.
    pub top: f32,
}

impl Margins {
    /// Margins from the left, right, bottom and top sides.
    pub const fn new(left: f32, right: f32, bottom: f32, top: f32) -> Self {
        Margins {
            left,
            right,
            bottom,
            top,
        }
    }

    /// The same margin on all four sides.
    pub const fn uniform(margin: f32) -> Self {
        Margins::new(margin, margin, margin, margin)
    }

    /// A door's margins: `side` left and right, `top` above, none below, so that the
    /// opening stands on the tile's bottom.
    pub const fn door(side: f32, top: f32) -> Self {
        Margins::new(side, side, 0.0, top)
    }
}

/// The parts of an [`inset`](Scope::inset) of a facade tile: the frame of wall around
/// the opening, the reveals lining the recess, and the opening at the recess's back.
/// Every part is a flat scope (size `z = 0`); parts of zero width or height are kept,
/// so that the arrays always have four entries, and emit nothing.
///
/// Generic over the scope type so that [`Shape::inset`](crate::Shape::inset) returns
/// shapes; [`map`](Self::map) turns one into the other.
///
/// ```
/// use glam::vec3;
/// use shapegen_runtime::geometry::{Inset, Margins};
/// use shapegen_runtime::Scope;
///
/// let tile = Scope::UNIT.with_size(vec3(3.0, 3.0, 0.0));
/// let inset: Inset = tile.inset(Margins::new(1.0, 0.5, 0.8, 0.6), 0.25).unwrap();
/// let [bottom, top, left, right] = inset.frame.map(|s| s.size());
/// assert_eq!((bottom, top), (vec3(3.0, 0.8, 0.0), vec3(3.0, 0.6, 0.0)));
/// assert!(left.abs_diff_eq(vec3(1.0, 1.6, 0.0), 1e-6));
/// assert!(right.abs_diff_eq(vec3(0.5, 1.6, 0.0), 1e-6));
/// assert!(inset.opening.size().abs_diff_eq(vec3(1.5, 1.6, 0.0), 1e-6));
/// assert!(inset.opening.origin().abs_diff_eq(vec3(0.25, 0.1, -0.25), 1e-6));
/// let widths = inset.map(|s| s.size().x).parts();
/// assert_eq!(widths.len(), 9);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inset<S = Scope> {
    /// The wall strips around the opening, in the tile's plane and facing as the tile
    /// does (local axes the tile's): bottom and top span the tile's full width, left
    /// and right the opening's height between them. Order: bottom, top, left, right.
    pub frame: [S; 4],
    /// The recess's four sides, `depth` deep, each facing into the opening (its local
    /// `z` points to the opening's centre line): local `x` along the opening's edge,
    /// local `y` toward the tile's plane, size `(edge length, depth, 0)`. Order: the
    /// sill (bottom), the head (top), the left jamb and the right jamb.
    pub reveals: [S; 4],
    /// The opening's rectangle moved back by `depth` along the tile's `-z`, facing `+z`
    /// with the tile's axes: where a window or a door goes.
    pub opening: S,
}

impl<S> Inset<S> {
    /// The same inset with `f` applied to every part.
    pub fn map<T>(self, mut f: impl FnMut(S) -> T) -> Inset<T> {
        Inset {
            frame: self.frame.map(&mut f),
            reveals: self.reveals.map(&mut f),
            opening: f(self.opening),
        }
    }

    /// All nine parts: the frame, then the reveals, then the opening.
    pub fn parts(self) -> [S; 9] {
        let Inset {
            frame: [f0, f1, f2, f3],
            reveals: [r0, r1, r2, r3],
            opening,
        } = self;
        [f0, f1, f2, f3, r0, r1, r2, r3, opening]
    }
}

impl Scope {
    /// Emits the scope's front rectangle (its `x`, `y` extent at local
    /// `z = size.z / 2`: a flat scope's own plane) as two facet instances of `facet`
    /// facing the scope's `+z`, appended to `out`. Returns how many: none for a
    /// rectangle without area.
    ///
    /// ```
    /// use glam::{Vec3, vec3};
    /// use shapegen_runtime::{Face, MeshId, Scope};
    ///
    /// let wall = Scope::UNIT.with_size(vec3(4.0, 3.0, 2.0)).face(Face::Right);
    /// let mut out = Vec::new();
    /// assert_eq!(wall.emit_rect(MeshId(1), &mut out), 2);
    /// for i in &out {
    ///     // Facing the box's +x, on its plane x = 2.
    ///     assert!(i.transform.transform_vector3(Vec3::Z).abs_diff_eq(Vec3::X, 1e-6));
    ///     assert_eq!(i.transform.translation.x, 2.0);
    /// }
    /// assert_eq!(wall.with_size(vec3(0.0, 3.0, 0.0)).emit_rect(MeshId(1), &mut out), 0);
    /// ```
    pub fn emit_rect(self, facet: MeshId, out: &mut Vec<Instance>) -> usize {
        let h = self.size / 2.0;
        let [a, b, c, d] = [
            vec3(-h.x, -h.y, h.z),
            vec3(h.x, -h.y, h.z),
            vec3(h.x, h.y, h.z),
            vec3(-h.x, h.y, h.z),
        ]
        .map(|p| self.frame.transform_point3(p));
        let before = out.len();
        out.extend(
            [(a, b, c), (a, c, d)]
                .into_iter()
                .filter_map(|(a, b, c)| facet_transform(a, b, c))
                .map(|transform| Instance {
                    transform,
                    mesh: facet,
                }),
        );
        out.len() - before
    }

    /// CGA's `inset` of a window or a door into a facade tile: the opening left by
    /// `margins` on the scope's front rectangle (as [`emit_rect`](Self::emit_rect)
    /// takes it: a flat scope's plane) recessed `depth` deep, as the wall frame around
    /// it, the reveals lining the recess and the opening at its back; see [`Inset`]. A
    /// door is an inset with no bottom margin ([`Margins::door`]).
    ///
    /// `None` when a margin or the depth is negative or not finite, or the margins
    /// leave no opening (no width or no height).
    ///
    /// The parts emitted with [`emit_rect`](Self::emit_rect) make one surface with the
    /// tile's rectangle as its boundary, facing as the tile does: replacing a wall tile
    /// of a closed solid by them keeps the solid closed, less the recess's
    /// `width * height * depth`.
    ///
    /// Splits and repeats tile flat scopes too (along `x` and `y`; `z` stays 0), so a
    /// facade is a wall split into floors, each repeated into tiles, each inset:
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::geometry::Margins;
    /// use shapegen_runtime::{Axis, MeshId, Scope};
    ///
    /// // A 12 x 9 wall: three floors of four 3 x 3 tiles, a 1.5 x 1.6 window in each.
    /// let wall = Scope::UNIT.with_size(vec3(12.0, 9.0, 0.0));
    /// let (mut out, mut windows) = (Vec::new(), 0);
    /// for floor in wall.repeat(Axis::Y, 3.0) {
    ///     for tile in floor.repeat(Axis::X, 3.0) {
    ///         let inset = tile.inset(Margins::new(0.75, 0.75, 0.8, 0.6), 0.3).unwrap();
    ///         for part in inset.frame.into_iter().chain(inset.reveals) {
    ///             part.emit_rect(MeshId(1), &mut out);
    ///         }
    ///         assert!(inset.opening.size().abs_diff_eq(vec3(1.5, 1.6, 0.0), 1e-5));
    ///         windows += inset.opening.emit_rect(MeshId(2), &mut out) / 2;
    ///     }
    /// }
    /// assert_eq!(windows, 12);
    /// // Per tile: four frame strips and four reveals of two triangles each.
    /// assert_eq!(out.len(), 12 * (8 * 2 + 2));
    /// ```
    pub fn inset(self, margins: Margins, depth: f32) -> Option<Inset> {
        let Margins {
            left,
            right,
            bottom,
            top,
        } = margins;
        let measures = [left, right, bottom, top, depth];
        if !measures.iter().all(|m| m.is_finite() && *m >= 0.0) {
            return None;
        }
        let (w, h) = (self.size.x, self.size.y);
        let (x0, x3, y0, y3) = (-w / 2.0, w / 2.0, -h / 2.0, h / 2.0);
        let (x1, x2, y1, y2) = (x0 + left, x3 - right, y0 + bottom, y3 - top);
        let (width, height) = (x2 - x1, y2 - y1);
        if !(width > 0.0 && height > 0.0) {
            return None;
        }
        let (ox, oy) = ((x1 + x2) / 2.0, (y1 + y2) / 2.0);
        let front = self.size.z / 2.0;
        let back = front - depth;
        let middle = front - depth / 2.0;
        // A flat part centred at `centre`, with axes `axes` (columns, in the tile's
        // local axes) and size `(sx, sy)`.
        let part = |centre: Vec3, axes: [Vec3; 3], sx: f32, sy: f32| {
            self.part(centre, axes, vec3(sx, sy, 0.0))
        };
        // A reveal: a side of the opening centred at `(x, y)` halfway in, `length` long
        // and `depth` deep.
        let reveal = |x: f32, y: f32, axes: [Vec3; 3], length: f32| {
            part(vec3(x, y, middle), axes, length, depth)
        };
        let facing = [Vec3::X, Vec3::Y, Vec3::Z];
        Some(Inset {
            frame: [
                part(vec3(0.0, (y0 + y1) / 2.0, front), facing, w, bottom),
                part(vec3(0.0, (y2 + y3) / 2.0, front), facing, w, top),
                part(vec3((x0 + x1) / 2.0, oy, front), facing, left, height),
                part(vec3((x2 + x3) / 2.0, oy, front), facing, right, height),
            ],
            reveals: [
                reveal(ox, y1, [Vec3::NEG_X, Vec3::Z, Vec3::Y], width),
                reveal(ox, y2, [Vec3::X, Vec3::Z, Vec3::NEG_Y], width),
                reveal(x1, oy, [Vec3::Y, Vec3::Z, Vec3::X], height),
                reveal(x2, oy, [Vec3::NEG_Y, Vec3::Z, Vec3::NEG_X], height),
            ],
            opening: part(vec3(ox, oy, back), facing, width, height),
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::{Affine3A, Quat, vec2};

    use super::super::closed::tests::{assert_watertight, volume as signed_volume};
    use super::*;
    use crate::geometry::axis::Axis;
    use crate::geometry::face::Face;
    use crate::geometry::polygon::Polygon;

    const WALL: MeshId = MeshId(1);

    /// A 12 x 9 x 8 box, turned and moved away from the origin.
    fn lot() -> Scope {
        Scope::new(
            Affine3A::from_rotation_translation(
                Quat::from_rotation_y(-0.4) * Quat::from_rotation_z(0.1),
                vec3(-7.0, 3.0, 15.0),
            ),
            vec3(12.0, 9.0, 8.0),
        )
    }

    fn tile() -> Scope {
        lot().face(Face::Front).with_size(vec3(3.0, 2.5, 0.0))
    }

    #[test]
    fn emit_rect_covers_the_front_rectangle_facing_z() {
        let mut out = Vec::new();
        let b = lot();
        assert_eq!(b.emit_rect(WALL, &mut out), 2);
        // The box's front face, facing its +z, 12 x 9.
        let area: f32 = out
            .iter()
            .map(|i| i.transform.matrix3.determinant() / 2.0)
            .sum();
        assert!((area - 108.0).abs() < 1e-3);
        for i in &out {
            let n = i.transform.transform_vector3(Vec3::Z);
            assert!(n.abs_diff_eq(b.axis(Axis::Z), 1e-5));
            let p = b
                .frame()
                .inverse()
                .transform_point3(i.transform.translation.into());
            assert!((p.z - 4.0).abs() < 1e-4);
        }
    }

    #[test]
    fn inset_parts_line_the_recess() {
        let t = tile();
        let inset = t.inset(Margins::new(0.5, 1.0, 0.7, 0.3), 0.4).unwrap();
        let local = |s: Scope, p: Vec3| t.frame().inverse().transform_point3(s.to_world(p));
        let normal = |s: Scope| t.frame().inverse().transform_vector3(s.axis(Axis::Z));
        // The opening: x in [-1, 0.5], y in [-0.55, 0.95], 0.4 back.
        let o = inset.opening;
        assert!(local(o, vec3(-0.5, -0.5, 0.0)).abs_diff_eq(vec3(-1.0, -0.55, -0.4), 1e-5));
        assert!(local(o, vec3(0.5, 0.5, 0.0)).abs_diff_eq(vec3(0.5, 0.95, -0.4), 1e-5));
        assert!(normal(o).abs_diff_eq(Vec3::Z, 1e-6));
        let centre = vec3(-0.25, 0.2, 0.0);
        for r in inset.reveals {
            // Spanning the depth, on the opening's side, facing its centre line.
            let (front, back) = (
                local(r, vec3(0.0, 0.5, 0.0)),
                local(r, vec3(0.0, -0.5, 0.0)),
            );
            assert!(front.z.abs() < 1e-5 && (back.z + 0.4).abs() < 1e-5);
            let towards = (centre - front) * vec3(1.0, 1.0, 0.0);
            assert!(
                towards.normalize().abs_diff_eq(normal(r), 1e-5),
                "{towards}"
            );
            assert!((r.frame().matrix3.determinant() - 1.0).abs() < 1e-5);
        }
        for f in inset.frame {
            assert!(normal(f).abs_diff_eq(Vec3::Z, 1e-6));
        }
        let sizes = inset.map(|s| s.size()).parts();
        assert_eq!(sizes[0], vec3(3.0, 0.7, 0.0));
        assert!(sizes[3].abs_diff_eq(vec3(1.0, 1.5, 0.0), 1e-6));
        assert!(sizes[4].abs_diff_eq(vec3(1.5, 0.4, 0.0), 1e-6));
        assert!(sizes[6].abs_diff_eq(vec3(1.5, 0.4, 0.0), 1e-6));
    }

    #[test]
    fn inset_refuses_margins_that_leave_no_opening() {
        let t = tile();
        assert!(t.inset(Margins::uniform(0.0), 0.0).is_some());
        assert!(t.inset(Margins::new(1.5, 1.5, 0.0, 0.0), 0.1).is_none());
        assert!(t.inset(Margins::new(0.0, 0.0, 2.0, 0.6), 0.1).is_none());
        assert!(t.inset(Margins::new(-0.1, 0.5, 0.5, 0.5), 0.1).is_none());
        assert!(
            t.inset(Margins::new(f32::NAN, 0.5, 0.5, 0.5), 0.1)
                .is_none()
        );
        assert!(t.inset(Margins::uniform(0.5), -0.1).is_none());
        assert!(t.inset(Margins::uniform(0.5), f32::INFINITY).is_none());
    }

    /// A box standing on the lot's bottom, built from its walls and caps, its front
    /// wall split into three floors of four tiles, each inset (a door, a window flush
    /// with a side, a window not recessed): still closed, less the recesses.
    #[test]
    fn insets_keep_a_prism_closed_less_their_recesses() {
        let footprint = Polygon::rectangle(vec2(12.0, 8.0)).unwrap();
        let (lot, mut out, mut recesses) = (lot(), Vec::new(), 0.0f64);
        for (face, wall) in lot.walls(&footprint, 9.0) {
            if face != Face::Front {
                wall.emit_rect(WALL, &mut out);
                continue;
            }
            assert_eq!(wall.size(), vec3(12.0, 9.0, 0.0));
            for (floor, level) in wall.repeat(Axis::Y, 3.0).enumerate() {
                for (k, tile) in level.repeat(Axis::X, 3.0).enumerate() {
                    let (margins, depth) = match (floor, k) {
                        (0, 1) => (Margins::door(0.8, 0.7), 0.3),
                        (1, 3) => (Margins::new(0.0, 0.9, 0.8, 0.6), 0.5),
                        (2, 0) => (Margins::uniform(0.6), 0.0),
                        _ => (Margins::new(0.75, 0.75, 0.8, 0.6), 0.3),
                    };
                    let inset = tile.inset(margins, depth).unwrap();
                    for part in inset.parts() {
                        part.emit_rect(WALL, &mut out);
                    }
                    let o = inset.opening.size();
                    recesses += f64::from(o.x * o.y * depth);
                }
            }
        }
        lot.top_cap(&footprint, 9.0, WALL, &mut out);
        lot.bottom_cap(&footprint, WALL, &mut out);
        assert_watertight(&out);
        let volume = signed_volume(&out);
        let want = 12.0 * 8.0 * 9.0 - recesses;
        assert!(recesses > 4.0);
        assert!((volume - want).abs() < 1e-3, "{volume} {want}");
    }
}
