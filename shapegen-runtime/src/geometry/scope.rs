//! The oriented box a derivation rule works in, and the operations on it.

use glam::{Affine3A, Mat3A, Vec3, Vec3A};

use super::axis::Axis;

/// An oriented box: a rigid frame (rotation and translation, no scale) placing the box's
/// centre and axes in the world, and the box's size along its own axes.
///
/// All operations work in the box's local axes and return a new scope, so rules read as
/// chains: `s.translate(vec3(0.0, 0.0, s.size().z / 2.0)).resize(child.size)`.
///
/// ```
/// use glam::{vec3, Vec3};
/// use shapegen_runtime::Scope;
///
/// let s = Scope::UNIT.resize(vec3(2.0, 1.0, 1.0)).translate(vec3(1.0, 0.0, 0.0));
/// assert_eq!(s.size(), vec3(2.0, 1.0, 1.0));
/// assert_eq!(s.origin(), Vec3::X);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scope {
    pub(super) frame: Affine3A,
    pub(super) size: Vec3,
}

impl Default for Scope {
    fn default() -> Self {
        Self::UNIT
    }
}

impl Scope {
    /// The axiom's scope: a unit box centred at the origin, aligned with the world axes.
    pub const UNIT: Scope = Scope {
        frame: Affine3A::IDENTITY,
        size: Vec3::ONE,
    };

    /// A scope from a rigid frame and a size. The frame should hold no scale or shear:
    /// scale belongs in `size`.
    #[inline]
    pub fn new(frame: Affine3A, size: Vec3) -> Self {
        Scope { frame, size }
    }

    /// The rigid frame: the box's centre and axes in world space.
    #[inline]
    pub fn frame(&self) -> Affine3A {
        self.frame
    }

    /// The box's size along its local axes.
    #[inline]
    pub fn size(&self) -> Vec3 {
        self.size
    }

    /// The box's centre in world space.
    #[inline]
    pub fn origin(&self) -> Vec3 {
        self.frame.translation.into()
    }

    /// The world direction of one of the box's local axes (a unit vector).
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::{Axis, Scope};
    ///
    /// let s = Scope::UNIT.rotate_z(std::f32::consts::FRAC_PI_2);
    /// assert!(s.axis(Axis::X).abs_diff_eq(vec3(0.0, 1.0, 0.0), 1e-6));
    /// ```
    #[inline]
    pub fn axis(&self, axis: Axis) -> Vec3 {
        self.frame.matrix3.col(axis.index()).into()
    }

    /// The world position of a point given in the box's unit coordinates, where
    /// `[-0.5, 0.5]` on each axis spans the box: `to_world(vec3(0.5, 0.5, 0.5))` is a
    /// corner.
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::Scope;
    ///
    /// let s = Scope::UNIT.with_size(vec3(2.0, 4.0, 6.0)).translate(vec3(1.0, 0.0, 0.0));
    /// assert_eq!(s.to_world(vec3(0.5, -0.5, 0.0)), vec3(2.0, -2.0, 0.0));
    /// ```
    #[inline]
    pub fn to_world(&self, unit: Vec3) -> Vec3 {
        self.frame.transform_point3(unit * self.size)
    }

    /// Moves the box by `v`, measured along its own axes.
    #[inline]
    pub fn translate(self, v: Vec3) -> Self {
        let mut frame = self.frame;
        frame.translation += frame.matrix3 * Vec3A::from(v);
        Scope { frame, ..self }
    }

    /// Rotates the box's axes by `angle` radians about its own `axis` (which need not be
    /// normalized), keeping its centre.
    #[inline]
    pub fn rotate(self, axis: Vec3, angle: f32) -> Self {
        self.rotated_by(Mat3A::from_axis_angle(axis.normalize(), angle))
    }

    /// Rotates the box by `angle` radians about its own x axis.
    #[inline]
    pub fn rotate_x(self, angle: f32) -> Self {
        self.rotated_by(Mat3A::from_rotation_x(angle))
    }

    /// Rotates the box by `angle` radians about its own y axis.
    #[inline]
    pub fn rotate_y(self, angle: f32) -> Self {
        self.rotated_by(Mat3A::from_rotation_y(angle))
    }

    /// Rotates the box by `angle` radians about its own z axis.
    #[inline]
    pub fn rotate_z(self, angle: f32) -> Self {
        self.rotated_by(Mat3A::from_rotation_z(angle))
    }

    /// The scope of a part of this box: centred at `centre` and turned so that its
    /// local axes are `axes` (columns of a rotation, in this box's local axes), of
    /// `size`. A face of the box, a wall of a prism, a piece of a window's recess.
    #[inline]
    pub(super) fn part(self, centre: Vec3, axes: [Vec3; 3], size: Vec3) -> Scope {
        let [x, y, z] = axes;
        let turned =
            self.translate(centre)
                .rotated_by(Mat3A::from_cols(x.into(), y.into(), z.into()));
        Scope { size, ..turned }
    }

    /// The box-local point of a polygon's plane point `p`, the plane lifted by `lift`
    /// above the box's bottom face: the plane's `(x, y)` at the box's `(x, -z)`, its
    /// `+z` up the box's `y` (a proper rotation, so windings keep their sense).
    #[inline]
    pub(super) fn plane_point(self, p: Vec3, lift: f32) -> Vec3 {
        Vec3::new(p.x, p.z + (lift - self.size.y / 2.0), -p.y)
    }

    #[inline]
    fn rotated_by(self, r: Mat3A) -> Self {
        let mut frame = self.frame;
        frame.matrix3 *= r;
        Scope { frame, ..self }
    }

    /// Multiplies the box's size component-wise by `factor`.
    #[inline]
    pub fn resize(self, factor: Vec3) -> Self {
        Scope {
            size: self.size * factor,
            ..self
        }
    }

    /// Sets the box's size.
    #[inline]
    pub fn with_size(self, size: Vec3) -> Self {
        Scope { size, ..self }
    }

    /// The transform that places a unit mesh (spanning `[-0.5, 0.5]`) to fill this box.
    #[inline]
    pub fn transform(&self) -> Affine3A {
        self.frame * Affine3A::from_scale(self.size)
    }
}
