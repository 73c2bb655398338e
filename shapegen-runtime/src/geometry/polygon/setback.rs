//! CGA's `setback`: a footprint cut into the footprint moved inward and the strips
//! between.

use glam::DVec2;

use super::simple::Polygon;

/// A footprint cut by [`Polygon::setback`]: the footprint moved inward, and one strip
/// per edge between the edge and its moved copy. The remainder and the strips tile the
/// footprint.
#[derive(Clone, Debug, PartialEq)]
pub struct Setback {
    /// The footprint with every edge moved inward by the distance, the corners mitred
    /// ([`Polygon::offset`] by the negated distance): the same number of edges, edge
    /// `i` the moved edge `i` of the footprint.
    pub remainder: Polygon,
    /// Strip `i` belongs to the footprint's edge `i`: the quadrilateral between the
    /// edge and its moved copy, its points the edge's start and end, then the moved
    /// edge's end and start (its edge 0 the footprint's edge `i`).
    pub strips: Vec<Polygon>,
}

impl Polygon {
    /// CGA's `setback`: the footprint with every edge moved inward by `distance` (the
    /// [`remainder`](Setback::remainder), where a tower stands back from the street)
    /// and the strips between each edge and its moved copy (where a lower podium or a
    /// front yard goes).
    ///
    /// `None` when `distance` is not positive and finite, or when moving the edges
    /// inward does not keep one simple polygon with the same edges: when an edge
    /// shrinks to nothing or turns around (a part of the footprint narrower than twice
    /// the distance), or the outline splits or crosses itself (a reflex corner reaching
    /// across to an opposite edge). Then the strips would not tile the footprint.
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    ///
    /// let lot = Polygon::rectangle(vec2(10.0, 6.0))?;
    /// let setback = lot.setback(1.0).unwrap();
    /// assert!((setback.remainder.area() - 8.0 * 4.0).abs() < 1e-9);
    /// assert_eq!(setback.strips.len(), 4);
    /// // The front strip, on edge 0 (along y = -3): a trapezoid 1 deep.
    /// assert!((setback.strips[0].area() - (10.0 + 8.0) / 2.0).abs() < 1e-9);
    /// assert_eq!(setback.strips[0].edge(0), lot.edge(0));
    /// // Too deep: the lot is 6 wide.
    /// assert!(lot.setback(3.5).is_none());
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn setback(&self, distance: f64) -> Option<Setback> {
        if !(distance > 0.0 && distance.is_finite()) {
            return None;
        }
        let n = self.len();
        let moved: Vec<DVec2> = (0..n)
            .map(|i| self.points()[i] + self.corner_velocity(i) * distance)
            .collect();
        // The offset by -distance: the same moved points.
        let remainder = self.moved_to(&moved)?;
        let tolerance = super::clean::EPS * self.scale();
        let same = remainder.len() == n
            && remainder
                .points()
                .iter()
                .zip(&moved)
                .all(|(p, q)| p.distance(*q) <= tolerance);
        if !same {
            return None;
        }
        let strips = (0..n)
            .map(|i| {
                let (a, b) = self.edge(i);
                let strip = [a, b, moved[(i + 1) % n], moved[i]];
                Polygon::from_f64(&strip)
                    .ok()
                    .filter(|s| s.len() == 4 && s.points()[0] == a)
            })
            .collect::<Option<Vec<Polygon>>>()?;
        // The strips and the remainder tile the footprint only if none overlap.
        let covered = remainder.area() + strips.iter().map(Polygon::area).sum::<f64>();
        let tiled = (covered - self.area()).abs() <= 1e-9 * self.area().max(1.0);
        tiled.then_some(Setback { remainder, strips })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every footprint with a distance that keeps it whole.
    fn cases() -> Vec<(Polygon, f64)> {
        vec![
            (Polygon::rectangle(glam::vec2(10.0, 6.0)).unwrap(), 1.5),
            (Polygon::l_shape(), 1.0),
            (Polygon::l_shape(), 1.9),
            (Polygon::u_shape(), 1.2),
            (Polygon::slanted(), 0.4),
        ]
    }

    #[test]
    fn strips_and_remainder_tile_the_footprint() {
        for (footprint, distance) in cases() {
            let Setback { remainder, strips } = footprint.setback(distance).unwrap();
            let n = footprint.len();
            assert_eq!((remainder.len(), strips.len()), (n, n));
            let area = remainder.area() + strips.iter().map(Polygon::area).sum::<f64>();
            assert!((area - footprint.area()).abs() < 1e-9, "{area}");
            for (i, strip) in strips.iter().enumerate() {
                // Between edge i and the remainder's edge i, `distance` apart.
                let (a, b) = footprint.edge(i);
                let (c, d) = remainder.edge(i);
                assert_eq!(strip.edge(0), (a, b));
                assert_eq!(strip.edge(2), (d, c));
                let inward = footprint.inward_normal(i);
                assert!(((c - a).dot(inward) - distance).abs() < 1e-9);
                assert!(((d - a).dot(inward) - distance).abs() < 1e-9);
                assert!((d - c).dot(b - a) > 0.0);
            }
            // The remainder lies inside, at `distance` from every edge.
            assert!(
                remainder
                    .points()
                    .iter()
                    .all(|&p| footprint.contains_f64(p, 0.0))
            );
        }
    }

    #[test]
    fn a_setback_past_half_the_narrowest_width_is_refused() {
        // The rectangle is 6 wide, the L's arms 4, the U's sides 3.
        let rectangle = Polygon::rectangle(glam::vec2(10.0, 6.0)).unwrap();
        assert!(rectangle.setback(2.9).is_some());
        assert!(rectangle.setback(3.0).is_none());
        assert!(rectangle.setback(3.1).is_none());
        assert!(Polygon::l_shape().setback(2.1).is_none());
        assert!(Polygon::u_shape().setback(1.6).is_none());
        assert!(Polygon::slanted().setback(3.0).is_none());
        for distance in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(rectangle.setback(distance).is_none(), "{distance}");
        }
    }
}
