//! Voxelization of triangle meshes by ray parity, and of closed surfaces by winding
//! number.
//!
//! A lattice point is inside a mesh when the ray from it along +x crosses the mesh's
//! triangles an odd number of times. Work is done in lattice coordinates (lattice point
//! `(I, J, K)` sits at `(I, J, K)`), in `f64`. Whether the ray of row `(J, K)` meets a
//! triangle is decided on the triangle's projection onto the y-z plane with symbolic
//! perturbation: the ray's origin is taken as `(J + e, K + e^2)` for an infinitesimal
//! `e`, so a ray through a shared edge or vertex meets exactly one of the triangles
//! there (two, or none, where the surface folds back: parity is unchanged). Each edge's
//! side test is evaluated from its endpoints in a fixed order, so the two triangles
//! sharing an edge see exactly opposite values. A crossing at `x = c` counts for the
//! lattice points `I < c`.
//!
//! Only lattice points within the mesh's bounding box can be inside. Meshes need not be
//! closed: parity does what it does on any triangle soup. The winding number counts
//! the same crossings with a sign (`+1` where the triangle faces `+x`, `-1` where it
//! faces `-x`): around a point it is the number of closed, outward-wound surfaces that
//! hold it, however they overlap.

use glam::{DVec2, DVec3, Vec3, Vec3Swizzles};

use super::quant::lattice_box;
use crate::geometry::Mesh;

/// Reusable buffers for voxelizing meshes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Voxelizer {
    points: Vec<DVec3>,
    /// `(row within the bounding box, x of the crossing, +1 where the triangle faces
    /// +x and -1 where it faces -x)`.
    crossings: Vec<(u64, f64, i8)>,
}

/// Which lattice points a run may consider.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Bounds {
    /// Only those of the grid of this resolution (no size limit).
    Grid([u32; 3]),
    /// Any, within the rasterisation limits of [`lattice_box`].
    Lattice,
}

/// `Err(TooLarge)`: the mesh's bounding box exceeds the rasterisation limits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TooLarge;

/// The side of `p` relative to the directed edge `a -> b` (positive on the left),
/// evaluated with the endpoints in lexicographic order so that `edge(a, b, p) ==
/// -edge(b, a, p)` exactly.
#[inline]
fn edge(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let flip = (b.x, b.y) < (a.x, a.y);
    let (lo, hi) = if flip { (b, a) } else { (a, b) };
    let e = (hi.x - lo.x) * (p.y - lo.y) - (hi.y - lo.y) * (p.x - lo.x);
    if flip { -e } else { e }
}

/// Whether `p + (e, e^2)` lies strictly left of `a -> b`.
#[inline]
fn left_of(a: DVec2, b: DVec2, p: DVec2) -> bool {
    let e = edge(a, b, p);
    if e != 0.0 {
        return e > 0.0;
    }
    // e(p + (t, t^2)) = e(p) + d.x t^2 - d.y t: the t term decides, then the t^2 term.
    let d = b - a;
    d.y < 0.0 || (d.y == 0.0 && d.x > 0.0)
}

/// What a run counts a lattice point as covered by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rule {
    /// Once, when its ray crosses an odd number of triangles.
    Parity,
    /// As many times as the winding number around it, when positive: its ray's
    /// crossings counted `+1` where a triangle faces `+x` (the ray leaves the surface)
    /// and `-1` where it faces `-x`.
    Winding,
}

impl Voxelizer {
    /// Voxelizes `mesh`, each vertex placed by `place` (returning lattice coordinates),
    /// calling `emit(J, K, I_first, I_last)` for each run of inside lattice points,
    /// rows in order of `(K, J)`. A mesh with a non-finite placed vertex covers nothing.
    pub(crate) fn run(
        &mut self,
        mesh: &Mesh,
        place: impl Fn(Vec3) -> DVec3,
        bounds: Bounds,
        emit: impl FnMut(i64, i64, i64, i64),
    ) -> Result<(), TooLarge> {
        self.points.clear();
        self.points.extend(mesh.positions.iter().map(|&p| place(p)));
        self.sweep(mesh.triangles(), bounds, Rule::Parity, emit)
    }

    /// Voxelizes closed surfaces given as triangles (corners in lattice coordinates,
    /// counter-clockwise seen from outside) by their winding number: `emit(J, K,
    /// I_first, I_last)` is called once for each run of lattice points inside at least
    /// one surface, once more for each run inside at least two, and so on, so that a
    /// point is emitted as many times as the number of surfaces holding it. Triangles
    /// with a non-finite corner cover nothing.
    pub(crate) fn run_winding(
        &mut self,
        triangles: impl IntoIterator<Item = [DVec3; 3]>,
        bounds: Bounds,
        emit: impl FnMut(i64, i64, i64, i64),
    ) -> Result<(), TooLarge> {
        self.points.clear();
        self.points.extend(
            triangles
                .into_iter()
                .filter(|t| t.iter().all(|p| p.is_finite()))
                .flatten(),
        );
        let n = (self.points.len() / 3) as u32;
        let triangles = (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]);
        self.sweep(triangles, bounds, Rule::Winding, emit)
    }

    /// Voxelizes the `triangles` of the placed points by `rule`.
    fn sweep(
        &mut self,
        triangles: impl Iterator<Item = [u32; 3]>,
        bounds: Bounds,
        rule: Rule,
        emit: impl FnMut(i64, i64, i64, i64),
    ) -> Result<(), TooLarge> {
        if self.points.iter().any(|p| !p.is_finite()) || self.points.is_empty() {
            return Ok(());
        }
        let Some(lattice) = self.lattice(bounds)? else {
            return Ok(());
        };
        self.crossings.clear();
        for triangle in triangles {
            self.cross(triangle, &lattice);
        }
        self.crossings
            .sort_unstable_by(|p, q| p.0.cmp(&q.0).then(p.1.total_cmp(&q.1)));
        self.emit_runs(&lattice, rule, emit);
        Ok(())
    }

    /// The lattice points the placed points' box holds (within the grid, for
    /// [`Bounds::Grid`]), or `None` when it holds none.
    fn lattice(&self, bounds: Bounds) -> Result<Option<Lattice>, TooLarge> {
        let (mut lo, mut hi) = self
            .points
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let limited = match bounds {
            Bounds::Grid(res) => {
                let top = DVec3::new(
                    f64::from(res[0]) - 1.0,
                    f64::from(res[1]) - 1.0,
                    f64::from(res[2]) - 1.0,
                );
                lo = lo.max(DVec3::ZERO);
                hi = hi.min(top);
                false
            }
            Bounds::Lattice => true,
        };
        let found = lattice_box(lo, hi, limited).map_err(|()| TooLarge)?;
        Ok(found.map(|(first, count)| Lattice {
            first,
            last: std::array::from_fn(|a| first[a] + count[a] - 1),
        }))
    }

    /// Adds the crossings of the x-parallel lines through `lattice`'s (J, K) points
    /// with the triangle `[a, b, c]` of the placed points: per line (its row, `K` major),
    /// where it crosses and the sign of the triangle's normal's x.
    fn cross(&mut self, [a, b, c]: [u32; 3], lattice: &Lattice) {
        let [_, j0, k0] = lattice.first;
        let [_, j1, k1] = lattice.last;
        let nj = j1 - j0 + 1;
        let [pa, mut pb, mut pc] = [a, b, c].map(|v| self.points[v as usize]);
        // The x component of the triangle's normal: positive where it faces +x.
        let area = edge(pa.yz(), pb.yz(), pc.yz());
        if area == 0.0 {
            return;
        }
        let sign = if area > 0.0 { 1 } else { -1 };
        if area < 0.0 {
            std::mem::swap(&mut pb, &mut pc);
        }
        let (a2, b2, c2) = (pa.yz(), pb.yz(), pc.yz());
        let lo2 = a2.min(b2).min(c2);
        let hi2 = a2.max(b2).max(c2);
        let (ja, jb) = (
            (lo2.x.ceil() as i64).max(j0),
            (hi2.x.floor() as i64).min(j1),
        );
        let (ka, kb) = (
            (lo2.y.ceil() as i64).max(k0),
            (hi2.y.floor() as i64).min(k1),
        );
        for k in ka..=kb {
            for j in ja..=jb {
                let p = DVec2::new(j as f64, k as f64);
                if !(left_of(a2, b2, p) && left_of(b2, c2, p) && left_of(c2, a2, p)) {
                    continue;
                }
                let (wa, wb, wc) = (edge(b2, c2, p), edge(c2, a2, p), edge(a2, b2, p));
                let sum = wa + wb + wc;
                let x = if sum > 0.0 {
                    (wa * pa.x + wb * pb.x + wc * pc.x) / sum
                } else {
                    (pa.x + pb.x + pc.x) / 3.0
                };
                let row = ((k - k0) * nj + (j - j0)) as u64;
                self.crossings.push((row, x, sign));
            }
        }
    }

    /// Emits the runs of `lattice` points inside by `rule`, from the sorted crossings:
    /// lattice point I counts the crossings c > I; between consecutive crossings that
    /// count, and their signs' sum, are constant.
    fn emit_runs(&self, lattice: &Lattice, rule: Rule, mut emit: impl FnMut(i64, i64, i64, i64)) {
        let [i0, j0, k0] = lattice.first;
        let i1 = lattice.last[0];
        let nj = lattice.last[1] - j0 + 1;
        let (below, above) = ((i0 - 1) as f64, (i1 + 1) as f64);
        let first_after = |c: f64| c.clamp(below, above).ceil() as i64;
        let mut rest = &self.crossings[..];
        while let Some(&(row, _, _)) = rest.first() {
            let n = rest.iter().take_while(|c| c.0 == row).count();
            let (group, tail) = rest.split_at(n);
            rest = tail;
            let (j, k) = (j0 + row as i64 % nj, k0 + row as i64 / nj);
            // The signs' sum of the crossings after the m-th, for m = 0 first.
            let mut winding: i64 = group.iter().map(|c| i64::from(c.2)).sum();
            for m in 0..=n {
                let times = match rule {
                    Rule::Parity => ((n - m) % 2) as i64,
                    Rule::Winding => winding,
                };
                if m < n {
                    winding -= i64::from(group[m].2);
                }
                if times <= 0 {
                    continue;
                }
                let from = if m == 0 {
                    i0
                } else {
                    first_after(group[m - 1].1).max(i0)
                };
                let to = if m == n {
                    i1
                } else {
                    (first_after(group[m].1) - 1).min(i1)
                };
                if from <= to {
                    for _ in 0..times {
                        emit(j, k, from, to);
                    }
                }
            }
        }
    }
}

/// The lattice points a sweep visits: the first and the last along each axis.
struct Lattice {
    first: [i64; 3],
    last: [i64; 3],
}

#[cfg(test)]
mod tests {
    use super::*;

    fn runs(mesh: &Mesh, place: impl Fn(Vec3) -> DVec3, bounds: Bounds) -> Vec<[i64; 4]> {
        let mut out = Vec::new();
        Voxelizer::default()
            .run(mesh, place, bounds, |j, k, a, b| out.push([j, k, a, b]))
            .unwrap();
        out
    }

    #[test]
    fn edges_are_exact_opposites() {
        let (a, b) = (DVec2::new(0.1, 0.7), DVec2::new(3.3, -1.9));
        for p in [
            DVec2::new(0.3, 0.2),
            DVec2::new(-5.0, 2.0),
            DVec2::new(1.7, -0.9),
        ] {
            assert_eq!(edge(a, b, p), -edge(b, a, p));
            assert_ne!(left_of(a, b, p), left_of(b, a, p));
        }
        // On the edge itself exactly one of the two directions claims the point.
        let (a, b) = (DVec2::new(0.0, 0.0), DVec2::new(2.0, 2.0));
        let p = DVec2::new(1.0, 1.0);
        assert_eq!(edge(a, b, p), 0.0);
        assert_ne!(left_of(a, b, p), left_of(b, a, p));
    }

    #[test]
    fn cube_through_lattice_points_counts_each_once() {
        // A cube whose faces, edges and corners pass exactly through lattice points and
        // rows: [0, 4]^3 holds the points 0..4 on each axis, 0 on the faces included and
        // 4 excluded, by the perturbation and the crossing rule.
        let cube = Mesh::unit_cube();
        let r = runs(&cube, |p| (p.as_dvec3() + 0.5) * 4.0, Bounds::Lattice);
        let mut points = 0;
        for &[j, k, a, b] in &r {
            assert!((0..4).contains(&j) && (0..4).contains(&k), "row {j} {k}");
            assert_eq!((a, b), (0, 3));
            points += b - a + 1;
        }
        assert_eq!(points, 64);
    }

    #[test]
    fn open_mesh_just_does_parity_and_grid_bounds_clip() {
        // One square (two triangles) at x = 2.5 spanning y, z in [0, 3]: the points with
        // x < 2.5 in the box are "inside" (one crossing), none beyond.
        let mut square = Mesh::unit_cube();
        square.indices.truncate(6); // the +x face only
        let place =
            |p: Vec3| DVec3::new(2.5, f64::from(p.y + 0.5) * 3.0, f64::from(p.z + 0.5) * 3.0);
        // The bounding box in x is the plane x = 2.5 alone: no lattice point.
        assert!(runs(&square, place, Bounds::Lattice).is_empty());
        let mut with_corner = square.clone();
        with_corner.positions.push(Vec3::new(-0.5, -0.5, -0.5));
        with_corner.normals.push(Vec3::X);
        let place = |p: Vec3| {
            if p.x < 0.0 {
                DVec3::new(-10.0, 0.0, 0.0)
            } else {
                DVec3::new(2.5, f64::from(p.y + 0.5) * 3.0, f64::from(p.z + 0.5) * 3.0)
            }
        };
        let r = runs(&with_corner, place, Bounds::Grid([5, 5, 5]));
        assert_eq!(r.len(), 9, "{r:?}");
        assert!(r.iter().all(|&[_, _, a, b]| (a, b) == (0, 2)));
    }
}
