//! Whether generated facets close: every edge run as often one way as the other, so that
//! the volume scorer's winding number sees an inside.

use std::collections::HashMap;

use glam::DVec3;

use super::facet::{FACET_CORNERS, is_facet};
use super::instance::Instance;
use super::library::BoundMeshes;

/// Corners closer than this are one vertex.
const WELD: f64 = 1e-4;

/// A piece of edge where the facets do not close: used by `uses` triangles, run `net`
/// more times from `from` to `to` than back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenEdge {
    /// One end.
    pub from: DVec3,
    /// The other end.
    pub to: DVec3,
    /// How many triangles have it as (part of) an edge.
    pub uses: u32,
    /// How many more run it from `from` to `to` than back.
    pub net: i32,
}

/// The triangles of the facet instances among `instances` (those whose mesh in `meshes`
/// is the unit facet), corners in double precision; other instances are left out.
pub fn facet_triangles(instances: &[Instance], meshes: &BoundMeshes) -> Vec<[DVec3; 3]> {
    instances
        .iter()
        .filter(|i| meshes.get(i.mesh).is_some_and(is_facet))
        .map(|i| FACET_CORNERS.map(|p| i.transform.transform_point3(p).as_dvec3()))
        .collect()
}

/// The signed volume `triangles` enclose: positive for closed surfaces facing out.
pub fn signed_volume(triangles: &[[DVec3; 3]]) -> f64 {
    triangles
        .iter()
        .map(|[a, b, c]| a.dot(b.cross(*c)) / 6.0)
        .sum()
}

/// Every piece of edge of `triangles` that is used other than by exactly two
/// triangles running it in opposite directions: empty for one closed surface wound
/// consistently. Corners closer than 1e-4 are welded into one vertex, and each edge is
/// cut at every vertex lying on it (a T-junction, where a wall split into tiles meets a
/// neighbour that is not). Closed surfaces that touch (a roof standing on a storey)
/// share pieces used four times with `net` 0; the winding number needs only `net == 0`
/// everywhere.
///
/// ```
/// use shapegen_runtime::geometry::{Mesh, MeshId, emit_facets, open_edges, signed_volume};
/// use shapegen_runtime::geometry::facet_triangles;
/// use shapegen_runtime::MeshLibrary;
///
/// let mut library = MeshLibrary::new();
/// library.register("facet", Mesh::facet())?;
/// let meshes = library.bind_names("Demo", &["cube", "facet"])?;
/// let mut out = Vec::new();
/// emit_facets(&Mesh::unit_cube(), |p| p, MeshId(1), &mut out);
/// let triangles = facet_triangles(&out, &meshes);
/// assert!(open_edges(&triangles).is_empty());
/// assert!((signed_volume(&triangles) - 1.0).abs() < 1e-6);
/// // Without its last triangle, the cube is open along that triangle's three edges.
/// let open = open_edges(&triangles[..11]);
/// assert_eq!(open.len(), 3);
/// assert!(open.iter().all(|e| e.uses == 1 && e.net.abs() == 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn open_edges(triangles: &[[DVec3; 3]]) -> Vec<OpenEdge> {
    let mut grid = Grid::new(triangles);
    let corners: Vec<[usize; 3]> = triangles.iter().map(|t| t.map(|p| grid.weld(p))).collect();
    // Per undirected piece: how many triangles use it, and forward minus backward.
    let mut pieces: HashMap<(usize, usize), (u32, i32)> = HashMap::new();
    let mut inside: Vec<(f64, usize)> = Vec::new();
    for t in &corners {
        for k in 0..3 {
            let (i, j) = (t[k], t[(k + 1) % 3]);
            grid.on_edge(i, j, &mut inside);
            let chain = std::iter::once(i)
                .chain(inside.iter().map(|&(_, v)| v))
                .chain(std::iter::once(j));
            let mut from = i;
            for to in chain.skip(1) {
                let entry = pieces.entry((from.min(to), from.max(to))).or_default();
                entry.0 += 1;
                entry.1 += if from < to { 1 } else { -1 };
                from = to;
            }
        }
    }
    let mut open: Vec<OpenEdge> = pieces
        .into_iter()
        .filter(|&(_, (uses, net))| uses != 2 || net != 0)
        .map(|((u, v), (uses, net))| OpenEdge {
            from: grid.vertices[u],
            to: grid.vertices[v],
            uses,
            net,
        })
        .collect();
    open.sort_by(|a, b| {
        (a.from.to_array(), a.to.to_array())
            .partial_cmp(&(b.from.to_array(), b.to.to_array()))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    open
}

/// The welded vertices, bucketed in cubic cells for finding the ones near a point or an
/// edge.
struct Grid {
    vertices: Vec<DVec3>,
    cell: f64,
    cells: HashMap<[i64; 3], Vec<usize>>,
}

impl Grid {
    /// An empty grid sized for `triangles`: about 64 cells across their extent, none
    /// smaller than the weld distance.
    fn new(triangles: &[[DVec3; 3]]) -> Grid {
        let (lo, hi) = triangles
            .iter()
            .flatten()
            .fold((DVec3::MAX, DVec3::MIN), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let extent = (hi - lo).max_element();
        let cell = if extent.is_finite() {
            (extent / 64.0).max(WELD * 4.0)
        } else {
            1.0
        };
        Grid {
            vertices: Vec::new(),
            cell,
            cells: HashMap::new(),
        }
    }

    fn key(&self, p: DVec3) -> [i64; 3] {
        (p / self.cell).floor().as_i64vec3().to_array()
    }

    /// The vertices in the cells that the box `[lo, hi]` overlaps.
    fn near(&self, lo: DVec3, hi: DVec3) -> impl Iterator<Item = usize> + '_ {
        let (a, b) = (self.key(lo), self.key(hi));
        (a[0]..=b[0])
            .flat_map(move |x| {
                (a[1]..=b[1]).flat_map(move |y| {
                    (a[2]..=b[2])
                        .flat_map(move |z| self.cells.get(&[x, y, z]).into_iter().flatten())
                })
            })
            .copied()
    }

    /// The vertex at `p`: one within the weld distance, or a new one.
    fn weld(&mut self, p: DVec3) -> usize {
        let pad = DVec3::splat(WELD);
        if let Some(v) = self
            .near(p - pad, p + pad)
            .find(|&v| self.vertices[v].distance(p) < WELD)
        {
            return v;
        }
        self.vertices.push(p);
        let v = self.vertices.len() - 1;
        self.cells.entry(self.key(p)).or_default().push(v);
        v
    }

    /// Writes to `inside` the vertices other than `i` and `j` that lie on the edge from
    /// `i` to `j`, with where along it, in order from `i`.
    fn on_edge(&self, i: usize, j: usize, inside: &mut Vec<(f64, usize)>) {
        inside.clear();
        let (a, b) = (self.vertices[i], self.vertices[j]);
        let ab = b - a;
        let pad = DVec3::splat(WELD);
        inside.extend(
            self.near(a.min(b) - pad, a.max(b) + pad)
                .filter(|&v| v != i && v != j)
                .filter_map(|v| {
                    let p = self.vertices[v];
                    let s = (p - a).dot(ab) / ab.length_squared();
                    let on = s > 0.0 && s < 1.0 && (a + ab * s).distance(p) < WELD;
                    on.then_some((s, v))
                }),
        );
        inside.sort_by(|x, y| x.0.total_cmp(&y.0));
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use glam::Affine3A;

    use super::*;
    use crate::geometry::face::Face;
    use crate::geometry::instance::MeshId;
    use crate::geometry::scope::Scope;

    /// The triangles of `out`, every instance a facet.
    pub(crate) fn triangles(out: &[Instance]) -> Vec<[DVec3; 3]> {
        out.iter()
            .map(|i| FACET_CORNERS.map(|p| i.transform.transform_point3(p).as_dvec3()))
            .collect()
    }

    /// Panics unless `out`, every instance a facet, is one closed surface wound
    /// consistently: [`open_edges`] finds nothing.
    pub(crate) fn assert_watertight(out: &[Instance]) {
        if let Some(e) = open_edges(&triangles(out)).first() {
            panic!(
                "edge {} - {} used {} times, {} more forward than back",
                e.from, e.to, e.uses, e.net
            );
        }
    }

    /// The signed volume `out`, every instance a facet, encloses.
    pub(crate) fn volume(out: &[Instance]) -> f64 {
        signed_volume(&triangles(out))
    }

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
        assert!((signed_volume(&triangles(&faces(None, None))) - 1.0).abs() < 1e-6);
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
