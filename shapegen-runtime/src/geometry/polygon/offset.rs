//! Outward offset of a polygon with mitred corners: a roof's eave line.

use glam::DVec2;

use super::simple::Polygon;

impl Polygon {
    /// The polygon with every edge moved outward by `distance` and the corners mitred
    /// (each corner moves along its bisector to where its moved edges meet), or `None`
    /// when that outline is not simple or an edge would turn around: a notch narrower
    /// than twice the distance closes.
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    ///
    /// let square = Polygon::rectangle(vec2(2.0, 2.0))?;
    /// let eave = square.offset(0.5).unwrap();
    /// assert!((eave.area() - 9.0).abs() < 1e-12);
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn offset(&self, distance: f64) -> Option<Polygon> {
        if distance == 0.0 {
            return Some(self.clone());
        }
        let moved: Vec<DVec2> = (0..self.len())
            .map(|i| self.points()[i] - self.corner_velocity(i) * distance)
            .collect();
        self.moved_to(&moved)
    }

    /// The polygon with each edge `i` moved inward by its own `distance(i)` (CGA's
    /// `setback` by edge: a street setback on the front, less on the sides), each corner
    /// where its two moved edges meet; `None` when that outline is not simple, loses an
    /// edge or turns one around, or a distance is not finite. A negative distance moves
    /// its edge outward.
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    ///
    /// // A 10 x 6 lot, 2 back from the front edge (edge 0, along y = -3), 0.5 from the others.
    /// let lot = Polygon::rectangle(vec2(10.0, 6.0))?;
    /// let built = lot.offset_edges(|i| if i == 0 { 2.0 } else { 0.5 }).unwrap();
    /// assert!((built.area() - 9.0 * 3.5).abs() < 1e-9);
    /// assert!(lot.offset_edges(|i| if i == 0 { 6.0 } else { 0.0 }).is_none());
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn offset_edges(&self, distance: impl Fn(usize) -> f64) -> Option<Polygon> {
        let n = self.len();
        let d: Vec<f64> = (0..n).map(distance).collect();
        if d.iter().any(|d| !d.is_finite()) {
            return None;
        }
        let moved: Vec<DVec2> = (0..n)
            .map(|i| {
                let before = (i + n - 1) % n;
                let (a, b) = (self.inward_normal(before), self.inward_normal(i));
                // The corner x - p with a . x = d[before] and b . x = d[i].
                let det = a.perp_dot(b);
                let x = DVec2::new(d[before] * b.y - d[i] * a.y, a.x * d[i] - b.x * d[before]);
                self.points()[i] + x / det
            })
            .collect();
        self.moved_to(&moved)
    }

    /// The polygon of `moved`, the polygon's points moved, where it keeps every edge the
    /// same way round.
    pub(super) fn moved_to(&self, moved: &[DVec2]) -> Option<Polygon> {
        let n = self.len();
        let out = Polygon::from_f64(moved).ok()?;
        let kept = out.len() == n
            && (0..n).all(|i| {
                let (a, b) = self.edge(i);
                let (c, d) = (moved[i], moved[(i + 1) % n]);
                (d - c).dot(b - a) > 0.0
            });
        kept.then_some(out)
    }

    /// The largest distance of `distance`, its halves down to a 256th, and zero, at
    /// which [`offset`](Self::offset) gives a polygon, with that polygon.
    pub fn offset_at_most(&self, distance: f64) -> (f64, Polygon) {
        let mut d = distance;
        for _ in 0..9 {
            if let Some(p) = self.offset(d) {
                return (d, p);
            }
            d /= 2.0;
        }
        (0.0, self.clone())
    }

    /// How point `i` moves when every edge moves inward at unit speed: the velocity that
    /// keeps it on both its edges' moved lines.
    pub(crate) fn corner_velocity(&self, i: usize) -> DVec2 {
        let n = self.len();
        let before = self.inward_normal((i + n - 1) % n);
        let after = self.inward_normal(i);
        (before + after) / (1.0 + before.dot(after))
    }
}
