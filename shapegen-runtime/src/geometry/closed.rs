//! Checks that emitted facets make closed, outward-facing surfaces, for the tests of
//! the operations that build them.

use std::collections::HashMap;

use glam::DVec3;

use super::{FACET_CORNERS, Instance};

/// Corners closer than this are one vertex.
const WELD: f64 = 1e-4;

/// The facets' triangles, corners in double precision.
pub(crate) fn triangles(out: &[Instance]) -> Vec<[DVec3; 3]> {
    out.iter()
        .map(|i| FACET_CORNERS.map(|p| i.transform.transform_point3(p).as_dvec3()))
        .collect()
}

/// The signed volume the facets enclose: positive for a closed surface facing out.
pub(crate) fn signed_volume(out: &[Instance]) -> f64 {
    triangles(out)
        .iter()
        .map(|[a, b, c]| a.dot(b.cross(*c)) / 6.0)
        .sum()
}

/// Panics unless the facets make closed surfaces wound consistently: corners closer
/// than [`WELD`] are welded into one vertex, each triangle edge is cut at every vertex
/// lying on it (a T-junction, where a wall split into tiles meets a neighbour that is
/// not), and then every piece of edge must be shared by exactly two triangles that run
/// along it in opposite directions.
pub(crate) fn assert_watertight(out: &[Instance]) {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut weld = |p: DVec3| {
        vertices
            .iter()
            .position(|v| v.distance(p) < WELD)
            .unwrap_or_else(|| {
                vertices.push(p);
                vertices.len() - 1
            })
    };
    let corners: Vec<[usize; 3]> = triangles(out)
        .into_iter()
        .map(|t| t.map(&mut weld))
        .collect();
    // Per undirected piece: how many triangles use it, and forward minus backward.
    let mut pieces: HashMap<(usize, usize), (u32, i32)> = HashMap::new();
    for t in &corners {
        for k in 0..3 {
            let (i, j) = (t[k], t[(k + 1) % 3]);
            let (a, b) = (vertices[i], vertices[j]);
            let ab = b - a;
            // The vertices inside the edge, by where they lie along it.
            let mut inside: Vec<(f64, usize)> = vertices
                .iter()
                .enumerate()
                .filter(|&(v, _)| v != i && v != j)
                .filter_map(|(v, &p)| {
                    let s = (p - a).dot(ab) / ab.length_squared();
                    let on = s > 0.0 && s < 1.0 && (a + ab * s).distance(p) < WELD;
                    on.then_some((s, v))
                })
                .collect();
            inside.sort_by(|x, y| x.0.total_cmp(&y.0));
            let chain: Vec<usize> = std::iter::once(i)
                .chain(inside.into_iter().map(|(_, v)| v))
                .chain(std::iter::once(j))
                .collect();
            for w in chain.windows(2) {
                let (u, v) = (w[0], w[1]);
                let entry = pieces.entry((u.min(v), u.max(v))).or_default();
                entry.0 += 1;
                entry.1 += if u < v { 1 } else { -1 };
            }
        }
    }
    for ((u, v), (uses, direction)) in pieces {
        assert!(
            uses == 2 && direction == 0,
            "edge {} - {} used {uses} times, {direction} more forward than back",
            vertices[u],
            vertices[v]
        );
    }
}

#[cfg(test)]
mod tests {
    use glam::Affine3A;

    use super::super::{Face, MeshId, Scope};
    use super::*;

    /// A unit box's six faces, emitted as rectangles, `flip` turned over.
    fn faces(skip: Option<Face>, flip: Option<Face>) -> Vec<Instance> {
        let mut out = Vec::new();
        for (face, scope) in Scope::UNIT.faces() {
            let scope = if Some(face) == flip {
                Scope::new(
                    scope.frame() * Affine3A::from_rotation_y(std::f32::consts::PI),
                    scope.size(),
                )
            } else {
                scope
            };
            if Some(face) != skip {
                scope.emit_rect(MeshId(1), &mut out);
            }
        }
        out
    }

    #[test]
    fn a_box_is_closed() {
        assert_watertight(&faces(None, None));
        assert!((signed_volume(&faces(None, None)) - 1.0).abs() < 1e-6);
    }

    #[test]
    #[should_panic(expected = "used 1 times")]
    fn a_box_without_a_face_is_open() {
        assert_watertight(&faces(Some(Face::Left), None));
    }

    #[test]
    #[should_panic(expected = "used 2 times")]
    fn a_box_with_a_face_turned_over_is_not_wound_consistently() {
        assert_watertight(&faces(None, Some(Face::Top)));
    }
}
