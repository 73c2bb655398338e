//! Subdivision of a scope along one of its axes: [`Scope::split`] and [`Scope::repeat`].

use std::iter::FusedIterator;

use super::axis::Axis;
use super::scope::Scope;

/// The length of one part of a [`Scope::split`].
///
/// Negative lengths, fractions and weights count as zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Part {
    /// An absolute length.
    Abs(f32),
    /// A fraction of the whole length being split.
    Rel(f32),
    /// A share of what the absolute and relative parts leave over, in proportion to its
    /// weight among all floating parts (CGA's `~`).
    Float(f32),
}

/// The scopes of a [`Scope::split`], in order along the axis. Allocation-free.
#[derive(Clone, Debug)]
pub struct Split<'p> {
    scope: Scope,
    axis: Axis,
    parts: std::slice::Iter<'p, Part>,
    /// Factor on absolute lengths (1, or less when the fixed parts overflow).
    abs_scale: f32,
    /// Length per unit of relative fraction.
    rel_scale: f32,
    /// Length per unit of floating weight.
    float_scale: f32,
    /// Where the next part starts, measured from the box's centre along the axis.
    cursor: f32,
}

impl Iterator for Split<'_> {
    type Item = Scope;

    #[inline]
    fn next(&mut self) -> Option<Scope> {
        let len = match *self.parts.next()? {
            Part::Abs(a) => a.max(0.0) * self.abs_scale,
            Part::Rel(r) => r.max(0.0) * self.rel_scale,
            Part::Float(w) => w.max(0.0) * self.float_scale,
        };
        let centre = self.cursor + len / 2.0;
        self.cursor += len;
        Some(self.scope.slab(self.axis, centre, len))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.parts.size_hint()
    }
}

impl ExactSizeIterator for Split<'_> {}
impl FusedIterator for Split<'_> {}

/// The equal tiles of a [`Scope::repeat`], in order along the axis. Allocation-free.
#[derive(Clone, Debug)]
pub struct Repeat {
    scope: Scope,
    axis: Axis,
    next: u32,
    count: u32,
    step: f32,
}

impl Iterator for Repeat {
    type Item = Scope;

    #[inline]
    fn next(&mut self) -> Option<Scope> {
        if self.next == self.count {
            return None;
        }
        let half = self.scope.size()[self.axis.index()] / 2.0;
        let centre = -half + (self.next as f32 + 0.5) * self.step;
        self.next += 1;
        Some(self.scope.slab(self.axis, centre, self.step))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = (self.count - self.next) as usize;
        (left, Some(left))
    }
}

impl ExactSizeIterator for Repeat {}
impl FusedIterator for Repeat {}

impl Scope {
    /// Splits the box along `axis` into consecutive boxes, one per part, from the
    /// negative end of the axis to the positive end (CGA's `split`).
    ///
    /// Absolute parts take their length, relative parts their fraction of the box's
    /// length, and floating parts share what is left in proportion to their weights.
    /// The iterator yields exactly one scope per part, so it can be zipped with the
    /// parts or enumerated.
    ///
    /// - When the absolute and relative parts together exceed the box's length, they
    ///   are all scaled down proportionally to fit exactly, and floating parts get
    ///   zero length.
    /// - When there are no floating parts and the others fall short, the parts are laid
    ///   out from the negative end and the rest of the box is left uncovered.
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::{Axis, Part, Scope};
    ///
    /// let facade = Scope::UNIT.with_size(vec3(10.0, 4.0, 0.0));
    /// let sizes: Vec<f32> = facade
    ///     .split(Axis::X, &[Part::Abs(1.0), Part::Float(1.0), Part::Rel(0.2), Part::Float(2.0)])
    ///     .map(|s| s.size().x)
    ///     .collect();
    /// assert_eq!(sizes, [1.0, 7.0 / 3.0, 2.0, 14.0 / 3.0]);
    /// ```
    pub fn split(self, axis: Axis, parts: &[Part]) -> Split<'_> {
        let length = self.size[axis.index()];
        let (mut fixed, mut weights) = (0.0f32, 0.0f32);
        for part in parts {
            match *part {
                Part::Abs(a) => fixed += a.max(0.0),
                Part::Rel(r) => fixed += r.max(0.0) * length,
                Part::Float(w) => weights += w.max(0.0),
            }
        }
        let (fit, left) = if fixed > length {
            (length / fixed, 0.0)
        } else {
            (1.0, length - fixed)
        };
        Split {
            scope: self,
            axis,
            parts: parts.iter(),
            abs_scale: fit,
            rel_scale: length * fit,
            float_scale: if weights > 0.0 { left / weights } else { 0.0 },
            cursor: -length / 2.0,
        }
    }

    /// Splits the box along `axis` into as many equal tiles of about `tile` length as
    /// fit: `n = max(1, round(length / tile))` tiles of `length / n` each (CGA's
    /// `split(axis) { ~tile : X }*`). A `tile` that is not positive and finite gives
    /// one tile, the whole box.
    ///
    /// ```
    /// use glam::vec3;
    /// use shapegen_runtime::{Axis, Scope};
    ///
    /// let floor = Scope::UNIT.with_size(vec3(10.0, 3.0, 0.0));
    /// let windows: Vec<f32> = floor.repeat(Axis::X, 2.3).map(|s| s.size().x).collect();
    /// assert_eq!(windows, [2.5; 4]);
    /// ```
    pub fn repeat(self, axis: Axis, tile: f32) -> Repeat {
        let length = self.size[axis.index()];
        let count = if tile > 0.0 && tile.is_finite() {
            // Saturating float-to-int conversion; NaN (0 / 0) gives 0, then 1.
            ((length / tile).round() as u32).max(1)
        } else {
            1
        };
        Repeat {
            scope: self,
            axis,
            next: 0,
            count,
            step: length / count as f32,
        }
    }

    /// The slab of this box along `axis` centred at `centre` (measured from the box's
    /// centre) with length `len`.
    #[inline]
    fn slab(self, axis: Axis, centre: f32, len: f32) -> Scope {
        let mut size = self.size;
        size[axis.index()] = len;
        self.translate(axis.unit() * centre).with_size(size)
    }
}

#[cfg(test)]
mod tests {
    use glam::{Affine3A, vec3};

    use super::*;

    fn box_10() -> Scope {
        Scope::new(
            Affine3A::from_translation(vec3(1.0, 2.0, 3.0)),
            vec3(10.0, 4.0, 2.0),
        )
    }

    fn sizes_and_centres(it: impl Iterator<Item = Scope>, axis: Axis) -> Vec<(f32, f32)> {
        it.map(|s| (s.size()[axis.index()], s.origin()[axis.index()]))
            .collect()
    }

    #[test]
    fn split_mixes_absolute_relative_and_floating_parts() {
        let parts = [
            Part::Abs(1.0),
            Part::Float(1.0),
            Part::Rel(0.25),
            Part::Float(3.0),
        ];
        let split = box_10().split(Axis::X, &parts);
        assert_eq!(split.len(), 4);
        // Fixed 1 + 2.5 = 3.5; floating share 6.5 split 1 : 3.
        assert_eq!(
            sizes_and_centres(split, Axis::X),
            [
                (1.0, 1.0 - 4.5),
                (1.625, 1.0 - 4.0 + 0.8125),
                (2.5, 1.0 - 2.375 + 1.25),
                (4.875, 1.0 + 0.125 + 2.4375),
            ]
        );
        // Other axes keep the box's size and centre.
        for s in box_10().split(Axis::X, &parts) {
            assert_eq!((s.size().y, s.size().z), (4.0, 2.0));
            assert_eq!((s.origin().y, s.origin().z), (2.0, 3.0));
        }
    }

    #[test]
    fn split_scales_overflowing_fixed_parts_down_and_starves_floats() {
        let parts = [
            Part::Abs(3.0),
            Part::Float(1.0),
            Part::Rel(0.5),
            Part::Abs(3.0),
        ];
        // Along y (length 4): fixed 3 + 2 + 3 = 8, scaled by 1/2.
        assert_eq!(
            sizes_and_centres(box_10().split(Axis::Y, &parts), Axis::Y),
            [
                (1.5, 2.0 - 1.25),
                (0.0, 2.0 - 0.5),
                (1.0, 2.0),
                (1.5, 2.0 + 1.25)
            ]
        );
    }

    #[test]
    fn split_without_floats_leaves_the_rest_uncovered() {
        let parts = [Part::Abs(0.5), Part::Rel(0.25), Part::Abs(-1.0)];
        assert_eq!(
            sizes_and_centres(box_10().split(Axis::Z, &parts), Axis::Z),
            [(0.5, 3.0 - 0.75), (0.5, 3.0 - 0.25), (0.0, 3.0)]
        );
        assert_eq!(box_10().split(Axis::Z, &[]).count(), 0);
    }

    #[test]
    fn split_follows_a_rotated_frame() {
        let s = Scope::new(
            Affine3A::from_rotation_translation(
                glam::Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
                vec3(5.0, 0.0, 0.0),
            ),
            vec3(4.0, 1.0, 1.0),
        );
        // Local x is world y.
        let centres: Vec<_> = s
            .split(Axis::X, &[Part::Float(1.0), Part::Float(1.0)])
            .map(|p| p.origin())
            .collect();
        assert!(centres[0].abs_diff_eq(vec3(5.0, -1.0, 0.0), 1e-6));
        assert!(centres[1].abs_diff_eq(vec3(5.0, 1.0, 0.0), 1e-6));
    }

    #[test]
    fn repeat_rounds_the_tile_count() {
        let r = box_10().repeat(Axis::X, 3.0);
        assert_eq!(r.len(), 3);
        let tiles = sizes_and_centres(r, Axis::X);
        let third = 10.0f32 / 3.0;
        assert_eq!(tiles.len(), 3);
        for (i, (len, centre)) in tiles.into_iter().enumerate() {
            assert_eq!(len, third);
            assert!((centre - (1.0 - 5.0 + (i as f32 + 0.5) * third)).abs() < 1e-5);
        }
        // 10 / 4 = 2.5 rounds to 3 (half away from zero); 10 / 8 = 1.25 rounds to 1.
        assert_eq!(box_10().repeat(Axis::X, 4.0).count(), 3);
        assert_eq!(box_10().repeat(Axis::X, 8.0).count(), 1);
        assert_eq!(
            sizes_and_centres(box_10().repeat(Axis::Y, 1.0), Axis::Y),
            [(1.0, 0.5), (1.0, 1.5), (1.0, 2.5), (1.0, 3.5)]
        );
    }

    #[test]
    fn repeat_never_yields_fewer_than_one_tile() {
        for tile in [100.0, 0.0, -1.0, f32::NAN, f32::INFINITY] {
            let tiles: Vec<_> = box_10().repeat(Axis::X, tile).collect();
            assert_eq!(tiles, [box_10()], "tile {tile}");
        }
        let flat = box_10().with_size(vec3(0.0, 1.0, 1.0));
        assert_eq!(flat.repeat(Axis::X, 1.0).count(), 1);
    }
}
