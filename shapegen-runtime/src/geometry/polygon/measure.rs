//! Measures of outlines that cleaning and polygons share: signed area, distance to a
//! segment.

use glam::DVec2;

/// The signed area, positive when `points` run counter-clockwise.
pub(crate) fn signed_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    let o = points.first().copied().unwrap_or_default();
    (0..n)
        .map(|i| (points[i] - o).perp_dot(points[(i + 1) % n] - o))
        .sum::<f64>()
        / 2.0
}

/// The distance from `p` to the segment `ab`.
pub(crate) fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * s - p).length()
}
