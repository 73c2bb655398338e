//! Assembling generated solids: triangles given by their corners, welded, with
//! T-junctions split, into a [`Mesh`] with flat normals.

use std::collections::HashMap;

use glam::{DVec3, Vec3};

use super::mesh::Mesh;
use super::polygon::Polygon;

/// Triangles collected by their corners. Corners closer than the weld tolerance are one
/// vertex, and a vertex within a tenth of it of another triangle's edge splits that
/// edge, so that
/// pieces made separately (the strips of a roof, its eave, its gables) close up into
/// one surface.
pub(crate) struct Solid {
    tolerance: f64,
    points: Vec<DVec3>,
    cells: HashMap<[i64; 3], Vec<u32>>,
    triangles: Vec<[u32; 3]>,
}

impl Solid {
    /// An empty solid welding corners within `tolerance`.
    pub(crate) fn new(tolerance: f64) -> Solid {
        Solid {
            tolerance,
            points: Vec::new(),
            cells: HashMap::new(),
            triangles: Vec::new(),
        }
    }

    fn cell(&self, p: DVec3) -> [i64; 3] {
        (p / self.tolerance).floor().to_array().map(|c| c as i64)
    }

    /// The vertex at `p`: an existing one within the tolerance, or a new one.
    fn point(&mut self, p: DVec3) -> u32 {
        let [x, y, z] = self.cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(ids) = self.cells.get(&[x + dx, y + dy, z + dz]) {
                        for &id in ids {
                            if (self.points[id as usize] - p).length() <= self.tolerance {
                                return id;
                            }
                        }
                    }
                }
            }
        }
        let id = self.points.len() as u32;
        self.points.push(p);
        self.cells.entry([x, y, z]).or_default().push(id);
        id
    }

    /// Adds the triangle `abc`, counter-clockwise seen from outside.
    pub(crate) fn triangle(&mut self, a: DVec3, b: DVec3, c: DVec3) {
        let t = [self.point(a), self.point(b), self.point(c)];
        if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
            self.triangles.push(t);
        }
    }

    /// Adds the quad `abcd` (planar, convex or a triangle with a repeated corner),
    /// counter-clockwise seen from outside.
    pub(crate) fn quad(&mut self, a: DVec3, b: DVec3, c: DVec3, d: DVec3) {
        self.triangle(a, b, c);
        self.triangle(a, c, d);
    }

    /// Adds the polygon at height `z` with heights `z_of` over it, facing up (`+z`) or
    /// down.
    pub(crate) fn cap(&mut self, polygon: &Polygon, up: bool, z_of: impl Fn(usize) -> f64) {
        let p = polygon.points();
        for [a, b, c] in polygon.triangulate() {
            let [a, b, c] = [a, b, c].map(|i| p[i].extend(z_of(i)));
            if up {
                self.triangle(a, b, c);
            } else {
                self.triangle(a, c, b);
            }
        }
    }

    /// The welded mesh: T-junctions split, one vertex per triangle corner with the
    /// triangle's normal.
    pub(crate) fn finish(mut self) -> Mesh {
        self.split_t_junctions();
        self.drop_fins();
        let mut mesh = Mesh::default();
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.points[i as usize]);
            let corners = [a, b, c].map(|p| p.as_vec3());
            if corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0] {
                continue;
            }
            let n = (b - a).cross(c - a).normalize_or_zero().as_vec3();
            let n = if n == Vec3::ZERO { Vec3::Z } else { n };
            for p in corners {
                mesh.indices.push(mesh.positions.len() as u32);
                mesh.positions.push(p);
                mesh.normals.push(n);
            }
        }
        mesh
    }

    /// Drops pairs of triangles on the same three vertices wound opposite ways: a sheet
    /// of no volume, where a part of the surface folded flat onto itself (a ridge of no
    /// length, a wall of no height).
    fn drop_fins(&mut self) {
        let key = |t: [u32; 3]| {
            let mut k = t;
            k.sort_unstable();
            // The winding: even or odd rotation of the sorted corners.
            let even = (0..3).any(|r| [t[r], t[(r + 1) % 3], t[(r + 2) % 3]] == k);
            (k, even)
        };
        let mut count: HashMap<([u32; 3], bool), i32> = HashMap::new();
        for &t in &self.triangles {
            *count.entry(key(t)).or_default() += 1;
        }
        let mut drop: HashMap<([u32; 3], bool), i32> = HashMap::new();
        for (&(k, even), &n) in &count {
            let opposite = count.get(&(k, !even)).copied().unwrap_or(0);
            drop.insert((k, even), n.min(opposite));
        }
        self.triangles.retain(|&t| {
            let k = key(t);
            let left = drop.get_mut(&k).expect("counted");
            if *left > 0 {
                *left -= 1;
                false
            } else {
                true
            }
        });
    }

    /// Splits every triangle edge that has a vertex on it, until none has.
    fn split_t_junctions(&mut self) {
        let mut done = Vec::with_capacity(self.triangles.len());
        let mut todo = std::mem::take(&mut self.triangles);
        // Each split puts a vertex strictly inside an edge, and vertices are further
        // apart than the split tolerance, so this ends; the budget guards against
        // rounding in surfaces folded flat onto themselves.
        let mut budget = 64 * todo.len() + 1024;
        while let Some(t) = todo.pop() {
            budget = budget.saturating_sub(1);
            if budget == 0 {
                done.push(t);
                continue;
            }
            match self.on_edge(t) {
                Some((k, ids)) => {
                    let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                    let mut chain = vec![a];
                    chain.extend(ids);
                    chain.push(b);
                    for w in chain.windows(2) {
                        todo.push([w[0], w[1], c]);
                    }
                }
                None => done.push(t),
            }
        }
        self.triangles = done;
    }

    /// The first edge `k` (from corner `k` to `k + 1`) of `t` with vertices strictly
    /// inside it, and those vertices in order from corner `k`.
    fn on_edge(&self, t: [u32; 3]) -> Option<(usize, Vec<u32>)> {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let (pa, pb) = (self.points[a as usize], self.points[b as usize]);
            let ab = pb - pa;
            let len2 = ab.length_squared();
            let mut on: Vec<(f64, u32)> = Vec::new();
            for (i, &p) in self.points.iter().enumerate() {
                let i = i as u32;
                if t.contains(&i) {
                    continue;
                }
                let s = (p - pa).dot(ab) / len2;
                if s <= 0.0 || s >= 1.0 {
                    continue;
                }
                if (pa + ab * s - p).length() <= self.tolerance / 10.0 {
                    on.push((s, i));
                }
            }
            if !on.is_empty() {
                on.sort_by(|x, y| x.0.total_cmp(&y.0));
                return Some((k, on.into_iter().map(|(_, i)| i).collect()));
            }
        }
        None
    }
}
