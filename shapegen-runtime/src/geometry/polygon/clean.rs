//! Checking and cleaning an outline into a [`Polygon`](super::Polygon).

use glam::DVec2;

use super::measure::{segment_distance, signed_area};

/// Why an outline is not a simple polygon. Points and edges are named by their index in
/// the outline as given: edge `i` runs from point `i` to point `i + 1`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PolygonError {
    /// A coordinate is infinite or NaN.
    #[error("point {index} has a non-finite coordinate")]
    NonFinite {
        /// The point.
        index: usize,
    },
    /// Fewer than three points are left once repeated points and points on a line
    /// through their neighbours are dropped.
    #[error(
        "a polygon needs at least 3 distinct points not all on one line; \
         {found} are left once repeated and collinear points are dropped"
    )]
    TooFewPoints {
        /// The points left.
        found: usize,
    },
    /// Two edges cross or touch.
    #[error("edges {first} and {second} cross or touch: the outline must not intersect itself")]
    SelfIntersecting {
        /// The first edge.
        first: usize,
        /// The second edge.
        second: usize,
    },
}

/// Relative tolerance: points closer than this times the outline's size are the same,
/// a point closer than this to the line through its neighbours lies on it, and edges
/// closer than this touch. Solids built on a polygon weld their corners at this
/// distance, so no corner of a polygon is that close to another or to an edge.
pub(crate) const EPS: f64 = 1e-5;

/// The cleaned, counter-clockwise points of `points`, or why there are none.
pub(super) fn clean(points: &[DVec2]) -> Result<Vec<DVec2>, PolygonError> {
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(PolygonError::NonFinite { index });
    }
    let (lo, hi) = points
        .iter()
        .fold((DVec2::MAX, DVec2::MIN), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let scale = (hi - lo).length();
    // The kept points with their index in the outline.
    let mut kept: Vec<(DVec2, usize)> = points.iter().copied().zip(0..).collect();
    loop {
        let before = kept.len();
        drop_repeated(&mut kept, EPS * scale);
        drop_collinear(&mut kept, EPS * scale);
        if kept.len() == before || kept.len() < 3 {
            break;
        }
    }
    if kept.len() < 3 {
        return Err(PolygonError::TooFewPoints { found: kept.len() });
    }
    if let Some((first, second)) = crossing(&kept, EPS * scale) {
        return Err(PolygonError::SelfIntersecting { first, second });
    }
    let mut out: Vec<DVec2> = kept.into_iter().map(|(p, _)| p).collect();
    if signed_area(&out) < 0.0 {
        out.reverse();
    }
    Ok(out)
}

/// Drops each point within `tolerance` of the point kept before it (cyclically).
fn drop_repeated(kept: &mut Vec<(DVec2, usize)>, tolerance: f64) {
    let mut out: Vec<(DVec2, usize)> = Vec::with_capacity(kept.len());
    for &(p, i) in kept.iter() {
        if out
            .last()
            .is_none_or(|&(q, _)| (p - q).length() > tolerance)
        {
            out.push((p, i));
        }
    }
    while out.len() > 1 && (out[0].0 - out[out.len() - 1].0).length() <= tolerance {
        out.pop();
    }
    *kept = out;
}

/// Drops each point within `tolerance` of the line through its neighbours, one pass.
fn drop_collinear(kept: &mut Vec<(DVec2, usize)>, tolerance: f64) {
    let mut k = 0;
    while kept.len() >= 3 && k < kept.len() {
        let n = kept.len();
        let a = kept[(k + n - 1) % n].0;
        let (b, c) = (kept[k].0, kept[(k + 1) % n].0);
        // On the line also when it folds back along it: a spike of no area.
        let off_line = (b - a).perp_dot(c - a).abs() / (c - a).length();
        if off_line.is_nan() || off_line <= tolerance {
            kept.remove(k);
        } else {
            k += 1;
        }
    }
}

/// The first pair of edges that cross or come within `tolerance` of each other, other
/// than consecutive edges at their shared point, named by the outline's edge indices.
fn crossing(kept: &[(DVec2, usize)], tolerance: f64) -> Option<(usize, usize)> {
    let n = kept.len();
    let edge = |i: usize| (kept[i].0, kept[(i + 1) % n].0);
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let (a, b) = edge(i);
            let (c, d) = edge(j);
            // With no straight or folded-back corners left, consecutive edges meet
            // only at their shared point.
            let hit = !adjacent && segments_near(a, b, c, d, tolerance);
            if hit {
                let (first, second) = (kept[i].1, kept[j].1);
                return Some((first.min(second), first.max(second)));
            }
        }
    }
    None
}

/// Whether the closed segments `ab` and `cd` share a point or come within `tolerance`.
fn segments_near(a: DVec2, b: DVec2, c: DVec2, d: DVec2, tolerance: f64) -> bool {
    segments_touch(a, b, c, d)
        || [
            segment_distance(a, c, d),
            segment_distance(b, c, d),
            segment_distance(c, a, b),
            segment_distance(d, a, b),
        ]
        .into_iter()
        .any(|gap| gap <= tolerance)
}

/// Whether the closed segments `ab` and `cd` share a point.
fn segments_touch(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let o1 = orient(a, b, c);
    let o2 = orient(a, b, d);
    let o3 = orient(c, d, a);
    let o4 = orient(c, d, b);
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    (o1 == 0.0 && on_segment(a, b, c))
        || (o2 == 0.0 && on_segment(a, b, d))
        || (o3 == 0.0 && on_segment(c, d, a))
        || (o4 == 0.0 && on_segment(c, d, b))
}

/// Twice the signed area of the triangle `abc`: positive when it turns left.
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Whether `p`, on the line through `ab`, lies within the segment's bounds.
fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    p.cmpge(a.min(b)).all() && p.cmple(a.max(b)).all()
}

#[cfg(test)]
mod tests {
    use glam::dvec2;

    use super::*;

    #[test]
    fn cleans_repeated_collinear_and_orientation() {
        let pts = [
            dvec2(0.0, 0.0),
            dvec2(0.0, 3.0),
            dvec2(0.0, 3.0),
            dvec2(2.0, 3.0),
            dvec2(4.0, 3.0),
            dvec2(4.0, 0.0),
            dvec2(0.0, 0.0),
        ];
        let out = clean(&pts).unwrap();
        assert_eq!(out.len(), 4);
        assert!(signed_area(&out) > 0.0);
        assert_eq!(signed_area(&out), 12.0);
    }

    #[test]
    fn refuses_bad_outlines_naming_what_is_wrong() {
        let bowtie = [
            dvec2(0.0, 0.0),
            dvec2(2.0, 2.0),
            dvec2(2.0, 0.0),
            dvec2(0.0, 2.0),
        ];
        assert_eq!(
            clean(&bowtie),
            Err(PolygonError::SelfIntersecting {
                first: 0,
                second: 2
            })
        );
        let line = [dvec2(0.0, 0.0), dvec2(1.0, 0.0), dvec2(2.0, 0.0)];
        assert_eq!(clean(&line), Err(PolygonError::TooFewPoints { found: 2 }));
        let nan = [dvec2(0.0, 0.0), dvec2(f64::NAN, 0.0), dvec2(2.0, 1.0)];
        assert_eq!(clean(&nan), Err(PolygonError::NonFinite { index: 1 }));
        // A point touching another edge: a pinched outline.
        let pinched = [
            dvec2(0.0, 0.0),
            dvec2(4.0, 0.0),
            dvec2(4.0, 4.0),
            dvec2(2.0, 0.0),
            dvec2(0.0, 4.0),
        ];
        assert!(matches!(
            clean(&pinched),
            Err(PolygonError::SelfIntersecting { .. })
        ));
        assert_eq!(
            PolygonError::SelfIntersecting {
                first: 0,
                second: 2
            }
            .to_string(),
            "edges 0 and 2 cross or touch: the outline must not intersect itself"
        );
    }
}
