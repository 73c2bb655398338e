//! Distinct surface normals: greedy clustering in triangle order.

use glam::Vec3;

/// Writes the distinct normals of `normals` into `reps`: each normal, in order, joins
/// the first representative already in `reps` within `tolerance_deg` of it
/// (`n . r >= cos(tolerance)`, computed in `f64`), or becomes a new representative.
pub(super) fn cluster(normals: &[Vec3], tolerance_deg: f32, reps: &mut Vec<Vec3>) {
    reps.clear();
    let cos = f64::from(tolerance_deg).to_radians().cos();
    for &n in normals {
        let joins = reps.iter().any(|&r| dot(n, r) >= cos);
        if !joins {
            reps.push(n);
        }
    }
}

/// Sum over `reps` of the angle (radians) from each to its nearest other; 0 with fewer
/// than two.
pub(super) fn spread(reps: &[Vec3]) -> f64 {
    if reps.len() < 2 {
        return 0.0;
    }
    reps.iter()
        .enumerate()
        .map(|(i, &a)| {
            let nearest = reps
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, &b)| dot(a, b))
                .fold(f64::NEG_INFINITY, f64::max);
            nearest.clamp(-1.0, 1.0).acos()
        })
        .sum()
}

/// `a . b` in `f64`.
#[inline]
fn dot(a: Vec3, b: Vec3) -> f64 {
    f64::from(a.x) * f64::from(b.x)
        + f64::from(a.y) * f64::from(b.y)
        + f64::from(a.z) * f64::from(b.z)
}
