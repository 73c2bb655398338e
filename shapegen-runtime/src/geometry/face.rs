//! Component split of a box into its faces: [`Scope::face`], [`Scope::faces`] and
//! [`Scope::extrude`].

use std::iter::FusedIterator;

use glam::{Vec3, vec3};

use super::scope::Scope;

/// One of the six faces of a box, named as seen from the front: the box's local `+z`
/// is its front, `+y` its top and `+x` its right.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Face {
    /// The `+z` face.
    Front,
    /// The `-z` face.
    Back,
    /// The `-x` face.
    Left,
    /// The `+x` face.
    Right,
    /// The `+y` face.
    Top,
    /// The `-y` face.
    Bottom,
}

impl Face {
    /// All six faces, in the order [`Scope::faces`] yields them.
    pub const ALL: [Face; 6] = [
        Face::Front,
        Face::Back,
        Face::Left,
        Face::Right,
        Face::Top,
        Face::Bottom,
    ];

    /// The face's outward normal in the box's local axes.
    #[inline]
    pub const fn normal(self) -> Vec3 {
        self.axes()[2]
    }

    /// The face scope's local x, y and z axes, in the box's local axes. Columns of a
    /// rotation: each triple is right-handed.
    #[inline]
    const fn axes(self) -> [Vec3; 3] {
        match self {
            Face::Front => [Vec3::X, Vec3::Y, Vec3::Z],
            Face::Back => [Vec3::NEG_X, Vec3::Y, Vec3::NEG_Z],
            Face::Left => [Vec3::Z, Vec3::Y, Vec3::NEG_X],
            Face::Right => [Vec3::NEG_Z, Vec3::Y, Vec3::X],
            Face::Top => [Vec3::X, Vec3::NEG_Z, Vec3::Y],
            Face::Bottom => [Vec3::X, Vec3::Z, Vec3::NEG_Y],
        }
    }
}

/// The six face scopes of a box with their faces: see [`Scope::faces`].
#[derive(Clone, Debug)]
pub struct Faces {
    scope: Scope,
    next: usize,
}

impl Iterator for Faces {
    type Item = (Face, Scope);

    #[inline]
    fn next(&mut self) -> Option<(Face, Scope)> {
        let face = *Face::ALL.get(self.next)?;
        self.next += 1;
        Some((face, self.scope.face(face)))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = Face::ALL.len() - self.next;
        (left, Some(left))
    }
}

impl ExactSizeIterator for Faces {}
impl FusedIterator for Faces {}

impl Scope {
    /// The flat scope of one face of the box (CGA's component split): centred on the
    /// face, its local z the outward normal, size `(width, height, 0)`.
    ///
    /// Orientation, so that a face scope seen from outside has x to the right and y up:
    /// - side faces (front, back, left, right): y is the box's y (up), x = y × z;
    /// - top: y points to the box's back (`-z`), so x is the box's x;
    /// - bottom: y points to the box's front (`+z`), so x is the box's x.
    ///
    /// Sizes: front and back are `(size.x, size.y)`, left and right `(size.z, size.y)`,
    /// top and bottom `(size.x, size.z)`.
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::{Axis, Face, Scope};
    ///
    /// let house = Scope::UNIT.with_size(vec3(8.0, 6.0, 4.0));
    /// let side = house.face(Face::Right);
    /// assert_eq!(side.size(), vec3(4.0, 6.0, 0.0));
    /// assert_eq!(side.origin(), vec3(4.0, 0.0, 0.0));
    /// assert_eq!(side.axis(Axis::Z), vec3(1.0, 0.0, 0.0)); // outward
    /// assert_eq!(side.axis(Axis::Y), vec3(0.0, 1.0, 0.0)); // up
    /// ```
    pub fn face(self, face: Face) -> Scope {
        let s = self.size;
        let (centre, size) = match face {
            Face::Front => (vec3(0.0, 0.0, s.z / 2.0), vec3(s.x, s.y, 0.0)),
            Face::Back => (vec3(0.0, 0.0, -s.z / 2.0), vec3(s.x, s.y, 0.0)),
            Face::Left => (vec3(-s.x / 2.0, 0.0, 0.0), vec3(s.z, s.y, 0.0)),
            Face::Right => (vec3(s.x / 2.0, 0.0, 0.0), vec3(s.z, s.y, 0.0)),
            Face::Top => (vec3(0.0, s.y / 2.0, 0.0), vec3(s.x, s.z, 0.0)),
            Face::Bottom => (vec3(0.0, -s.y / 2.0, 0.0), vec3(s.x, s.z, 0.0)),
        };
        self.part(centre, face.axes(), size)
    }

    /// The six faces of the box with their flat scopes, in the order of [`Face::ALL`];
    /// see [`face`](Self::face) for their orientation.
    ///
    /// ```
    /// use shapegen_runtime::{Face, Scope};
    ///
    /// let (face, top) = Scope::UNIT.faces().nth(4).unwrap();
    /// assert_eq!(face, Face::Top);
    /// assert_eq!(top.origin().y, 0.5);
    /// ```
    #[inline]
    pub fn faces(self) -> Faces {
        Faces {
            scope: self,
            next: 0,
        }
    }

    /// Sets the box's depth (local z size) to `depth`, keeping its back plane (local
    /// `z = -size.z / 2`) in place: on a flat scope such as a [`face`](Self::face), a
    /// box standing on the face, outward for a positive `depth` and inward for a
    /// negative one.
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::{Face, Scope};
    ///
    /// let roof = Scope::UNIT.face(Face::Top).extrude(0.5);
    /// assert_eq!(roof.size(), vec3(1.0, 1.0, 0.5));
    /// assert_eq!(roof.origin(), vec3(0.0, 0.75, 0.0));
    /// ```
    #[inline]
    pub fn extrude(self, depth: f32) -> Scope {
        let mut size = self.size;
        let shift = (depth - size.z) / 2.0;
        size.z = depth.abs();
        self.translate(vec3(0.0, 0.0, shift)).with_size(size)
    }
}

#[cfg(test)]
mod tests {
    use std::f32::consts::FRAC_PI_2;

    use glam::{Affine3A, Quat};

    use super::*;
    use crate::geometry::axis::Axis;

    /// A 2 x 4 x 6 box at (10, 20, 30), turned a quarter about world y: its local x
    /// is world -z and its local z is world +x.
    fn turned_box() -> Scope {
        Scope::new(
            Affine3A::from_rotation_translation(
                Quat::from_rotation_y(FRAC_PI_2),
                vec3(10.0, 20.0, 30.0),
            ),
            vec3(2.0, 4.0, 6.0),
        )
    }

    #[test]
    fn face_centres_normals_and_sizes_in_world_space() {
        // face, centre, outward normal, up axis, size (x, y)
        #[rustfmt::skip]
        let expected = [
            (Face::Front, vec3(13.0, 20.0, 30.0), Vec3::X, Vec3::Y, vec3(2.0, 4.0, 0.0)),
            (Face::Back, vec3(7.0, 20.0, 30.0), Vec3::NEG_X, Vec3::Y, vec3(2.0, 4.0, 0.0)),
            (Face::Left, vec3(10.0, 20.0, 31.0), Vec3::Z, Vec3::Y, vec3(6.0, 4.0, 0.0)),
            (Face::Right, vec3(10.0, 20.0, 29.0), Vec3::NEG_Z, Vec3::Y, vec3(6.0, 4.0, 0.0)),
            (Face::Top, vec3(10.0, 22.0, 30.0), Vec3::Y, Vec3::NEG_X, vec3(2.0, 6.0, 0.0)),
            (Face::Bottom, vec3(10.0, 18.0, 30.0), Vec3::NEG_Y, Vec3::X, vec3(2.0, 6.0, 0.0)),
        ];
        let faces: Vec<_> = turned_box().faces().collect();
        assert_eq!(faces.len(), 6);
        for ((face, scope), (want, centre, normal, up, size)) in faces.into_iter().zip(expected) {
            assert_eq!(face, want);
            assert!(
                scope.origin().abs_diff_eq(centre, 1e-5),
                "{face:?} centre {}",
                scope.origin()
            );
            assert!(
                scope.axis(Axis::Z).abs_diff_eq(normal, 1e-6),
                "{face:?} normal"
            );
            assert!(scope.axis(Axis::Y).abs_diff_eq(up, 1e-6), "{face:?} up");
            assert_eq!(scope.size(), size);
            // Right-handed rigid frame.
            assert!((scope.frame().matrix3.determinant() - 1.0).abs() < 1e-6);
            // Local normal agrees with the world one.
            let n = turned_box().frame().transform_vector3(face.normal());
            assert!(n.abs_diff_eq(normal, 1e-6));
        }
    }

    #[test]
    fn face_corners_lie_on_the_box() {
        let b = turned_box();
        for (face, scope) in b.faces() {
            for corner in [
                vec3(-0.5, -0.5, 0.0),
                vec3(0.5, 0.5, 0.0),
                vec3(0.5, -0.5, 0.0),
            ] {
                let world = scope.to_world(corner);
                // Back in the box's unit coordinates: on the face's plane, inside it.
                let local = b.transform().inverse().transform_point3(world);
                let n = face.normal();
                assert!((local.dot(n) - 0.5).abs() < 1e-5, "{face:?} {local}");
                assert!(local.abs().max_element() < 0.5 + 1e-5);
            }
        }
    }

    #[test]
    fn extrude_stands_on_the_face() {
        let side = turned_box().face(Face::Front).extrude(2.0);
        assert_eq!(side.size(), vec3(2.0, 4.0, 2.0));
        assert!(side.origin().abs_diff_eq(vec3(14.0, 20.0, 30.0), 1e-5));
        let inward = turned_box().face(Face::Front).extrude(-2.0);
        assert_eq!(inward.size(), vec3(2.0, 4.0, 2.0));
        assert!(inward.origin().abs_diff_eq(vec3(12.0, 20.0, 30.0), 1e-5));
        // On a box, the back plane stays.
        let deeper = Scope::UNIT.extrude(3.0);
        assert_eq!(deeper.size(), vec3(1.0, 1.0, 3.0));
        assert_eq!(deeper.origin(), vec3(0.0, 0.0, 1.0));
    }
}
