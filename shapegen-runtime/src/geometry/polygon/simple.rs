//! [`Polygon`]: a simple polygon, checked and cleaned when it is made.

use glam::{DVec2, Vec2};

use super::clean::{self, PolygonError};
use super::measure::{segment_distance, signed_area};

/// A simple polygon: at least three points, counter-clockwise, no two consecutive points
/// the same, no three consecutive points on a line, and no two edges that touch other
/// than consecutive edges at their shared point.
///
/// ```
/// use glam::vec2;
/// use shapegen_runtime::geometry::Polygon;
///
/// // Clockwise, with a repeated point and a point in the middle of an edge.
/// let square = Polygon::new([
///     vec2(0.0, 0.0), vec2(0.0, 2.0), vec2(0.0, 2.0), vec2(2.0, 2.0),
///     vec2(2.0, 1.0), vec2(2.0, 0.0),
/// ])?;
/// assert_eq!(square.len(), 4);
/// assert_eq!(square.area(), 4.0);
/// assert!(square.contains(vec2(1.0, 1.0)));
/// # Ok::<(), shapegen_runtime::geometry::PolygonError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    points: Vec<DVec2>,
}

impl Polygon {
    /// Checks and cleans an outline given in either orientation: drops repeated points
    /// and points on the line through their neighbours, and refuses outlines with a
    /// non-finite coordinate, fewer than three points left, no area, or edges that cross
    /// or touch. Errors name the points by their index in `points`.
    pub fn new(points: impl IntoIterator<Item = Vec2>) -> Result<Polygon, PolygonError> {
        let points: Vec<DVec2> = points.into_iter().map(|p| p.as_dvec2()).collect();
        Polygon::from_f64(&points)
    }

    /// [`new`](Self::new) for double-precision points.
    pub fn from_f64(points: &[DVec2]) -> Result<Polygon, PolygonError> {
        clean::clean(points).map(|points| Polygon { points })
    }

    /// The axis-aligned rectangle of `size` centred on the origin.
    ///
    /// ```
    /// use glam::vec2;
    /// use shapegen_runtime::geometry::Polygon;
    ///
    /// let lot = Polygon::rectangle(vec2(10.0, 6.0)).unwrap();
    /// assert_eq!(lot.area(), 60.0);
    /// ```
    pub fn rectangle(size: Vec2) -> Result<Polygon, PolygonError> {
        let h = size.as_dvec2() / 2.0;
        Polygon::from_f64(&[
            DVec2::new(-h.x, -h.y),
            DVec2::new(h.x, -h.y),
            DVec2::new(h.x, h.y),
            DVec2::new(-h.x, h.y),
        ])
    }

    /// The points, counter-clockwise.
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// Number of points (and of edges).
    #[allow(clippy::len_without_is_empty)] // a polygon has at least three points
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Edge `i`: from point `i` to point `i + 1` (cyclically).
    pub fn edge(&self, i: usize) -> (DVec2, DVec2) {
        let n = self.points.len();
        (self.points[i % n], self.points[(i + 1) % n])
    }

    /// The enclosed area (positive).
    pub fn area(&self) -> f64 {
        signed_area(&self.points)
    }

    /// The area centroid.
    pub fn centroid(&self) -> DVec2 {
        let mut c = DVec2::ZERO;
        let o = self.points[0];
        for i in 0..self.points.len() {
            let (a, b) = self.edge(i);
            let (a, b) = (a - o, b - o);
            c += (a + b) * a.perp_dot(b);
        }
        o + c / (6.0 * self.area())
    }

    /// The bounds `(min, max)` of the points.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.points
            .iter()
            .fold((self.points[0], self.points[0]), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            })
    }

    /// A length for tolerances: the diagonal of the bounds.
    pub fn scale(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (hi - lo).length()
    }

    /// Whether `p` is inside or on the outline.
    pub fn contains(&self, p: Vec2) -> bool {
        self.contains_f64(p.as_dvec2(), 0.0)
    }

    /// Whether `p` is inside the outline or within `tolerance` of it.
    pub fn contains_f64(&self, p: DVec2, tolerance: f64) -> bool {
        let mut inside = false;
        for i in 0..self.len() {
            let (a, b) = self.edge(i);
            if segment_distance(p, a, b) <= tolerance {
                return true;
            }
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if p.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// The unit normal of edge `i` pointing into the polygon.
    pub fn inward_normal(&self, i: usize) -> DVec2 {
        let (a, b) = self.edge(i);
        (b - a).normalize().perp()
    }
}

/// Concave footprints for tests.
#[cfg(test)]
impl Polygon {
    /// The polygon through `points`, in order.
    fn from_points(points: &[[f64; 2]]) -> Polygon {
        let points: Vec<DVec2> = points.iter().map(|&[x, y]| DVec2::new(x, y)).collect();
        Polygon::from_f64(&points).unwrap()
    }

    /// An 8 x 8 square less its upper right quarter.
    pub(crate) fn l_shape() -> Polygon {
        Polygon::from_points(&[
            [-4.0, -4.0],
            [4.0, -4.0],
            [4.0, 0.0],
            [0.0, 0.0],
            [0.0, 4.0],
            [-4.0, 4.0],
        ])
    }

    /// A 10 x 8 rectangle with a 4 x 5 notch in the middle of its upper side.
    pub(crate) fn u_shape() -> Polygon {
        Polygon::from_points(&[
            [-5.0, -4.0],
            [5.0, -4.0],
            [5.0, 4.0],
            [2.0, 4.0],
            [2.0, -1.0],
            [-2.0, -1.0],
            [-2.0, 4.0],
            [-5.0, 4.0],
        ])
    }

    /// A concave outline with slanted edges.
    pub(crate) fn slanted() -> Polygon {
        Polygon::from_points(&[
            [-4.0, -3.0],
            [4.0, -3.5],
            [1.5, 0.2],
            [4.5, 3.0],
            [-4.0, 3.0],
            [-1.0, -0.3],
        ])
    }
}
