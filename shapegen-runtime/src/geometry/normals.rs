//! Vertex normals for meshes that come without them.

use std::collections::HashMap;

use glam::Vec3;

use super::mesh::Mesh;
use super::weld::weld;

impl Mesh {
    /// The crease angle [`from_obj`](Self::from_obj) computes missing normals with:
    /// 60 degrees, in radians.
    pub const DEFAULT_CREASE_ANGLE: f32 = std::f32::consts::FRAC_PI_3;

    /// Replaces the normals with angle-weighted vertex normals, smoothing across edges
    /// whose faces meet at less than `crease_angle` (radians) and keeping sharper edges
    /// hard: vertices at the same position are welded first, then split again where a
    /// hard edge needs two normals. Positions and triangles are kept; vertices may be
    /// merged or repeated. Degenerate triangles get an arbitrary unit normal.
    ///
    /// # Panics
    ///
    /// If an index is out of range (see [`validate`](Self::validate)).
    ///
    /// ```
    /// use glam::Vec3;
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let mut cube = Mesh::unit_cube();
    /// cube.normals.clear();
    /// cube.compute_normals(Mesh::DEFAULT_CREASE_ANGLE);
    /// // Square edges stay hard: the cube keeps its 4 vertices per face.
    /// assert_eq!(cube, Mesh::unit_cube());
    /// ```
    pub fn compute_normals(&mut self, crease_angle: f32) {
        let cos_crease = crease_angle.cos();
        let (welded, vertex_count) = weld(&self.positions);
        // Unit face normals, and each corner's share of its vertex normal: the face
        // normal weighted by the corner's angle, which keeps the result independent of
        // how polygons were cut into triangles.
        let unit: Vec<Vec3> = self
            .triangles()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize]);
                (b - a).cross(c - a).normalize_or_zero()
            })
            .collect();
        let share: Vec<Vec3> = (0..self.indices.len())
            .map(|corner| {
                let tri = corner - corner % 3;
                let at = |k: usize| self.positions[self.indices[tri + (corner + k) % 3] as usize];
                let angle = (at(1) - at(0)).angle_between(at(2) - at(0));
                if angle.is_finite() {
                    unit[corner / 3] * angle
                } else {
                    Vec3::ZERO
                }
            })
            .collect();
        // Corners around each welded vertex, as ranges of one flat list.
        let mut start = vec![0u32; vertex_count + 1];
        for &i in &self.indices {
            start[welded[i as usize] as usize + 1] += 1;
        }
        for v in 0..vertex_count {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut around = vec![0u32; self.indices.len()];
        for (corner, &i) in self.indices.iter().enumerate() {
            let w = welded[i as usize] as usize;
            around[fill[w] as usize] = corner as u32;
            fill[w] += 1;
        }
        // One normal per corner, then one vertex per distinct (position, normal).
        let mut positions = Vec::with_capacity(self.positions.len());
        let mut normals = Vec::with_capacity(self.positions.len());
        let mut vertex_of: HashMap<(u32, [u32; 3]), u32> = HashMap::new();
        let mut indices = Vec::with_capacity(self.indices.len());
        for corner in 0..self.indices.len() {
            let w = welded[self.indices[corner] as usize];
            let mut n = Vec3::ZERO;
            for &other in &around[start[w as usize] as usize..start[w as usize + 1] as usize] {
                let other = other as usize;
                if unit[corner / 3].dot(unit[other / 3]) >= cos_crease {
                    n += share[other];
                }
            }
            // +0.0 folds -0.0 into 0.0, so equal normals share a vertex.
            let n = n.try_normalize().unwrap_or(Vec3::Y) + 0.0;
            let key = (w, n.to_array().map(f32::to_bits));
            let next = positions.len() as u32;
            let v = *vertex_of.entry(key).or_insert(next);
            if v == next {
                positions.push(self.positions[self.indices[corner] as usize]);
                normals.push(n);
            }
            indices.push(v);
        }
        *self = Mesh {
            positions,
            normals,
            indices,
        };
    }
}

#[cfg(test)]
mod tests {
    use glam::vec3;

    use super::*;

    /// An octagonal prism with shared vertices and no normals.
    fn prism() -> Mesh {
        let mut positions = Vec::new();
        for y in [-0.5, 0.5] {
            for k in 0..8 {
                let a = k as f32 * std::f32::consts::FRAC_PI_4;
                positions.push(vec3(a.cos() * 0.5, y, -a.sin() * 0.5));
            }
        }
        let mut indices = Vec::new();
        for k in 0..8u32 {
            let (b0, b1, t0, t1) = (k, (k + 1) % 8, k + 8, (k + 1) % 8 + 8);
            indices.extend([b0, b1, t1, b0, t1, t0]);
        }
        for k in 1..7u32 {
            indices.extend([0, k + 1, k]); // bottom, facing -y
            indices.extend([8, 8 + k, 8 + k + 1]); // top, facing +y
        }
        Mesh {
            positions,
            normals: Vec::new(),
            indices,
        }
    }

    #[test]
    fn crease_angle_smooths_sides_and_keeps_caps_hard() {
        let mut m = prism();
        assert!(m.is_closed());
        m.compute_normals(Mesh::DEFAULT_CREASE_ANGLE);
        m.validate("prism").unwrap();
        assert!(m.is_closed());
        // Sides smooth (16 vertices), caps hard (8 each).
        assert_eq!(m.vertex_count(), 32);
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert!((n.length() - 1.0).abs() < 1e-6);
            if n.y.abs() > 0.5 {
                assert!(n.abs_diff_eq(vec3(0.0, p.y.signum(), 0.0), 1e-6));
            } else {
                let radial = vec3(p.x, 0.0, p.z).normalize();
                assert!(n.abs_diff_eq(radial, 1e-5), "{n} vs {radial}");
            }
        }
        // A small crease angle makes every side flat: 4 vertices per side.
        let mut flat = prism();
        flat.compute_normals(0.1);
        assert_eq!(flat.vertex_count(), 8 * 4 + 16);
    }
}
