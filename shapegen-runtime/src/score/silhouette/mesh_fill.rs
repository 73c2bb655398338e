//! Filling a whole projected mesh, leaving out the triangles that cannot add a pixel.
//!
//! A mesh covers the union of what its triangles cover, so a triangle whose pixels other
//! triangles of the same mesh always cover need not be filled. For a closed mesh the
//! triangles facing away from the camera are such triangles, and for a mesh with holes
//! those away from the holes are. The argument, exact for the rule
//! [`Coverage::fill_triangle`] applies:
//!
//! 1. The top-left rule covers a pixel centre `p` exactly when `p + d` lies in the
//!    open triangle, for the perturbation `d = (e, e^2)` with `e > 0` small enough: a
//!    centre on a left edge is in (moving right enters the triangle), on a right edge
//!    out; on a horizontal edge the move down decides (a top edge in, a bottom edge
//!    out), and at a vertex every edge through it agrees with the move. `p + d` lies on
//!    no edge's line.
//! 2. For a point `q` on no edge's line, the triangles containing `q`, each counted +1
//!    or -1 by the sign of its area, number the winding number around `q` of the
//!    mesh's boundary: each triangle's count is the winding number of its own three
//!    directed edges, and summed over the mesh, an edge two triangles run in opposite
//!    directions cancels, leaving the edges of the boundary
//!    ([`RasterMesh::boundary`](super::meshes::RasterMesh)). Triangles of zero area
//!    count nothing.
//! 3. Outside the box of the boundary's projected positions that winding number is 0.
//!    So there, a centre `p` that a triangle of negative area covers, a triangle of
//!    positive area covers as well (apply 2 to `q = p + d`), and the negative triangles
//!    whose box lies apart from the boundary's box add no pixel. For a closed mesh,
//!    that is every negative triangle.
//!
//! The counts in 2 are of the triangles as their exact areas give them, while a
//! triangle whose `f32` area disagrees with its exact one covers nothing at all
//! ([`f32_agrees`]; no triangle whose exact area is above [`f32_safe_area`] is). So when
//! a triangle is dropped that way, the negative triangles left out are filled after
//! all.

use glam::Vec2;

use super::meshes::RasterMesh;
use super::raster::{Coverage, exact_area, f32_agrees, f32_safe_area, signed_area, span};

/// A mesh projected to pixels, as [`Coverage::fill_mesh`] fills it.
pub(super) struct ProjectedMesh<'a> {
    /// The mesh.
    pub mesh: &'a RasterMesh,
    /// Its positions in pixels, snapped to `1/256` pixel.
    pub points: &'a [Vec2],
    /// The same in `1/256` pixel, all within the rasterizer's exact range.
    pub fixed: &'a [[i32; 2]],
}

/// Working memory of [`Coverage::fill_mesh`]: the negative triangles put off.
#[derive(Clone, Debug, Default)]
pub(super) struct MeshScratch {
    deferred: Vec<u32>,
}

impl MeshScratch {
    /// How many triangles the last fill left out.
    #[cfg(test)]
    pub(super) fn left_out(&self) -> usize {
        self.deferred.len()
    }
}

impl Coverage {
    /// Fills every triangle of `projected`, covering exactly what filling each with
    /// [`Coverage::fill_triangle`] covers, without filling the triangles that cannot add
    /// a pixel (see the [module documentation](self)).
    pub(super) fn fill_mesh(&mut self, projected: &ProjectedMesh<'_>, scratch: &mut MeshScratch) {
        let ProjectedMesh {
            mesh,
            points,
            fixed,
        } = *projected;
        let boundary = (!mesh.boundary.is_empty())
            .then(|| span(mesh.boundary.iter().map(|&i| fixed[i as usize])));
        scratch.deferred.clear();
        let reach = fixed.iter().flatten().fold(0, |m, &c| m.max(c.abs()));
        let safe = f32_safe_area(reach);
        let mut dropped = false;
        for (i, tri) in mesh.triangles.iter().enumerate() {
            let v = tri.map(|k| fixed[k as usize]);
            let exact = exact_area(&v);
            if exact == 0 {
                continue;
            }
            if exact.abs() <= safe
                && !f32_agrees(signed_area(&tri.map(|k| points[k as usize])), exact)
            {
                dropped = true;
            } else if exact < 0 && boundary.is_none_or(|b| apart(&span(v), &b)) {
                scratch.deferred.push(i as u32);
            } else {
                self.fill_exact(v, exact > 0);
            }
        }
        if dropped {
            for &i in &scratch.deferred {
                let v = mesh.triangles[i as usize].map(|k| fixed[k as usize]);
                self.fill_exact(v, false);
            }
            scratch.deferred.clear();
        }
    }
}

/// Whether the closed boxes `a` and `b` (`[xmin, xmax, ymin, ymax]`) share no point.
#[inline]
fn apart(a: &[i32; 4], b: &[i32; 4]) -> bool {
    a[1] < b[0] || b[1] < a[0] || a[3] < b[2] || b[3] < a[2]
}
