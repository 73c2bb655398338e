//! Triangulation of a polygon by ear clipping.

use glam::DVec2;

use super::simple::Polygon;

impl Polygon {
    /// Cuts the polygon into `len() - 2` triangles of point indices, each
    /// counter-clockwise, by ear clipping.
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    ///
    /// // An L: six points, four triangles, the L's area.
    /// let l = Polygon::new([
    ///     vec2(0.0, 0.0), vec2(2.0, 0.0), vec2(2.0, 1.0),
    ///     vec2(1.0, 1.0), vec2(1.0, 2.0), vec2(0.0, 2.0),
    /// ])?;
    /// let triangles = l.triangulate();
    /// assert_eq!(triangles.len(), 4);
    /// let p = l.points();
    /// let area: f64 = triangles
    ///     .iter()
    ///     .map(|&[a, b, c]| (p[b] - p[a]).perp_dot(p[c] - p[a]) / 2.0)
    ///     .sum();
    /// assert!((area - 3.0).abs() < 1e-12);
    /// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
    /// ```
    pub fn triangulate(&self) -> Vec<[usize; 3]> {
        triangulate(self.points())
    }
}

/// Ear clipping of the counter-clockwise simple polygon `points`.
pub(crate) fn triangulate(points: &[DVec2]) -> Vec<[usize; 3]> {
    let mut left: Vec<usize> = (0..points.len()).collect();
    let mut out = Vec::with_capacity(points.len().saturating_sub(2));
    while left.len() > 3 {
        let n = left.len();
        let corner = |k: usize| [left[(k + n - 1) % n], left[k], left[(k + 1) % n]];
        let is_ear = |k: usize| {
            let [a, b, c] = corner(k).map(|i| points[i]);
            if (b - a).perp_dot(c - b) <= 0.0 {
                return false;
            }
            left.iter().all(|&i| {
                let p = points[i];
                p == a || p == b || p == c || !inside_or_on(p, a, b, c)
            })
        };
        // An ear always exists in a simple polygon; rounding may hide it, and then the
        // most convex corner is cut.
        let k = (0..n).find(|&k| is_ear(k)).unwrap_or_else(|| {
            (0..n)
                .max_by(|&i, &j| turn(points, corner(i)).total_cmp(&turn(points, corner(j))))
                .unwrap_or(0)
        });
        out.push(corner(k));
        left.remove(k);
    }
    if left.len() == 3 {
        out.push([left[0], left[1], left[2]]);
    }
    out
}

/// How far the corner `[a, b, c]` turns left: the sine of its turn.
fn turn(points: &[DVec2], [a, b, c]: [usize; 3]) -> f64 {
    let (u, v) = (points[b] - points[a], points[c] - points[b]);
    u.perp_dot(v) / (u.length() * v.length()).max(f64::MIN_POSITIVE)
}

/// Whether `p` lies in the counter-clockwise triangle `abc` or on its boundary.
fn inside_or_on(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    (b - a).perp_dot(p - a) >= 0.0
        && (c - b).perp_dot(p - b) >= 0.0
        && (a - c).perp_dot(p - c) >= 0.0
}
