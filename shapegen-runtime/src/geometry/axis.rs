//! [`Axis`]: one of a scope's local axes.

use glam::Vec3;

/// One of a scope's local axes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The local x axis.
    X,
    /// The local y axis.
    Y,
    /// The local z axis.
    Z,
}

impl Axis {
    /// The component index of the axis: 0, 1 or 2.
    #[inline]
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The unit vector along the axis.
    #[inline]
    pub const fn unit(self) -> Vec3 {
        match self {
            Axis::X => Vec3::X,
            Axis::Y => Vec3::Y,
            Axis::Z => Vec3::Z,
        }
    }
}
