//! Meshes prepared for rasterization.

use std::collections::HashMap;

use glam::Vec3;

use super::raster::MAX_POLYGON;
use crate::geometry::{BoundMeshes, Mesh};

/// One mesh as the rasterizer reads it.
#[derive(Clone, Debug)]
pub(super) struct RasterMesh {
    /// The mesh's distinct vertex positions (equal bit patterns stored once), so that
    /// each is projected once per instance.
    pub positions: Vec<Vec3>,
    /// Triangles as index triples into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// The positions on the mesh's boundary: the ends of the edges that the triangles
    /// sharing them do not run as often one way as the other (none for a closed,
    /// consistently wound mesh), in increasing order.
    pub boundary: Vec<u32>,
    /// For a convex mesh with at most [`MAX_POLYGON`] distinct vertices: those vertices,
    /// whose projected convex hull is the mesh's silhouette when all are in front of the
    /// camera. A mesh counts as convex when no vertex lies outside any face's plane by
    /// more than 0.1% of the mesh's size (OBJ files round their coordinates), so the
    /// hull may exceed the mesh's own silhouette by that much.
    pub hull: Option<Vec<Vec3>>,
}

/// Relative tolerance of the convexity test.
const CONVEX_EPS: f32 = 1e-3;

impl RasterMesh {
    pub(super) fn new(mesh: &Mesh) -> Self {
        let mut index = HashMap::new();
        let mut positions = Vec::new();
        let slot: Vec<u32> = mesh
            .positions
            .iter()
            .map(|p| {
                *index
                    .entry(p.to_array().map(f32::to_bits))
                    .or_insert_with(|| {
                        positions.push(*p);
                        positions.len() as u32 - 1
                    })
            })
            .collect();
        let triangles: Vec<[u32; 3]> = mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| slot[i as usize]))
            .collect();
        let mut distinct: Vec<Vec3> = Vec::new();
        for &p in &mesh.positions {
            if !distinct.contains(&p) {
                distinct.push(p);
                if distinct.len() > MAX_POLYGON {
                    break;
                }
            }
        }
        let hull =
            (distinct.len() <= MAX_POLYGON && is_convex(mesh, &distinct)).then_some(distinct);
        RasterMesh {
            boundary: boundary(&triangles),
            positions,
            triangles,
            hull,
        }
    }
}

/// The ends of the edges of `triangles` that they do not run as often one way as the
/// other (each `a -> b` counted +1 and `b -> a` -1), sorted and once each.
fn boundary(triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut runs: HashMap<[u32; 2], i64> = HashMap::new();
    for t in triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            if a != b {
                *runs.entry([a.min(b), a.max(b)]).or_default() += if a < b { 1 } else { -1 };
            }
        }
    }
    let mut ends: Vec<u32> = runs
        .into_iter()
        .filter(|&(_, n)| n != 0)
        .flat_map(|(ends, _)| ends)
        .collect();
    ends.sort_unstable();
    ends.dedup();
    ends
}

/// Whether every vertex lies on or behind the plane of every triangle (outward
/// counter-clockwise winding), so that the mesh is the boundary of a convex solid.
fn is_convex(mesh: &Mesh, points: &[Vec3]) -> bool {
    let scale = points
        .iter()
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()))
        .max(f32::MIN_POSITIVE);
    let mut any_face = false;
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a);
        let len = n.length();
        if len <= 1e-6 * scale * scale {
            continue;
        }
        any_face = true;
        let n = n / len;
        if points.iter().any(|&p| n.dot(p - a) > CONVEX_EPS * scale) {
            return false;
        }
    }
    any_face
}

/// A grammar's meshes prepared, indexed by mesh id.
pub(super) fn prepare(meshes: &BoundMeshes) -> Vec<RasterMesh> {
    meshes
        .iter()
        .map(|(_, _, mesh)| RasterMesh::new(mesh))
        .collect()
}
