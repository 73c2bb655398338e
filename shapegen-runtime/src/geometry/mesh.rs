//! Triangle meshes: the parts that mesh instances place.

use std::collections::HashMap;
use std::path::PathBuf;

use glam::Vec3;

/// An indexed triangle mesh with one normal per vertex.
///
/// Part meshes are modelled centred at the origin and spanning `[-0.5, 0.5]` on each
/// axis, so that an instance's transform (a scope's frame times its size) fills the
/// scope; meshes emitted "unscaled" keep their own size.
///
/// Build one with [`unit_cube`](Self::unit_cube), load one with
/// [`from_obj`](Self::from_obj), or fill the fields and [`validate`](Self::validate).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position: flat (vertices repeated per face) or
    /// smooth, as loaded or computed.
    pub normals: Vec<Vec3>,
    /// Triangles as triples of vertex indices, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

/// Why a mesh could not be loaded, checked or bound.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh file could not be read.
    #[error("cannot read mesh file `{}`", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The OBJ text is malformed.
    #[error("cannot parse OBJ `{name}`{}: {what}", at_line(*line))]
    Parse {
        /// The file or the name the text was given.
        name: String,
        /// The 1-based line at fault, where it is known.
        line: Option<usize>,
        /// What was wrong.
        what: String,
    },
    /// The file's extension is not one of a mesh format.
    #[error("cannot read mesh file `{}`: its extension is not one of {valid}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// The extensions read.
        valid: String,
    },
    /// A mesh file other than OBJ is malformed.
    #[error("cannot read {format} `{name}`: {what}")]
    Decode {
        /// The format, as `STL`, `PLY`, `glTF`.
        format: String,
        /// The file or the name the bytes were given.
        name: String,
        /// What was wrong.
        what: String,
    },
    /// The mesh has no triangles.
    #[error("mesh `{name}` has no triangles")]
    Empty {
        /// The file or the mesh's name.
        name: String,
    },
    /// A vertex position or normal is infinite or NaN.
    #[error("mesh `{name}`: vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// The file or the mesh's name.
        name: String,
        /// Index of the vertex.
        vertex: usize,
    },
    /// The mesh's arrays do not fit together.
    #[error("mesh `{name}` is malformed: {what}")]
    Malformed {
        /// The file or the mesh's name.
        name: String,
        /// What was wrong.
        what: String,
    },
    /// A grammar uses a mesh that the library lacks.
    #[error(
        "generator `{generator}` uses mesh `{mesh}`, which is not registered; \
         register it with MeshLibrary::register_obj(\"{mesh}\", path)"
    )]
    Unregistered {
        /// The grammar's name.
        generator: String,
        /// The missing mesh.
        mesh: String,
    },
}

fn at_line(line: Option<usize>) -> String {
    line.map(|l| format!(" at line {l}")).unwrap_or_default()
}

impl Mesh {
    /// The unit cube centred at the origin, spanning `[-0.5, 0.5]`: 24 vertices (4 per
    /// face, with the face's outward normal) and 12 triangles.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let cube = Mesh::unit_cube();
    /// assert_eq!((cube.vertex_count(), cube.triangle_count()), (24, 12));
    /// assert!(cube.validate("cube").is_ok());
    /// ```
    pub fn unit_cube() -> Mesh {
        let mut mesh = Mesh::default();
        // Each face: outward normal n, an in-plane axis u and v = n x u, so that
        // u x v = n and the corners (n + a u + b v) / 2 run counter-clockwise seen
        // from outside.
        let faces = [
            (Vec3::X, Vec3::Y),
            (Vec3::NEG_X, Vec3::Y),
            (Vec3::Y, Vec3::Z),
            (Vec3::NEG_Y, Vec3::Z),
            (Vec3::Z, Vec3::X),
            (Vec3::NEG_Z, Vec3::X),
        ];
        for (n, u) in faces {
            let v = n.cross(u);
            let base = mesh.positions.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push((n + a * u + b * v) * 0.5);
                mesh.normals.push(n);
            }
            mesh.indices
                .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        }
        mesh
    }

    /// Number of vertices.
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[inline]
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The triangles as index triples.
    #[inline]
    pub fn triangles(&self) -> impl ExactSizeIterator<Item = [u32; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]])
    }

    /// The axis-aligned bounds `(min, max)` of the positions; `None` when there are
    /// none.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }

    /// Checks that the mesh is usable, naming it `name` in the error: at least one
    /// triangle, whole triangles, indices in range, one normal per position, finite
    /// coordinates.
    pub fn validate(&self, name: &str) -> Result<(), MeshError> {
        let malformed = |what: String| MeshError::Malformed {
            name: name.to_owned(),
            what,
        };
        if self.indices.is_empty() {
            return Err(MeshError::Empty {
                name: name.to_owned(),
            });
        }
        if !self.indices.len().is_multiple_of(3) {
            return Err(malformed(format!(
                "{} indices do not make whole triangles",
                self.indices.len()
            )));
        }
        if self.normals.len() != self.positions.len() {
            return Err(malformed(format!(
                "{} normals for {} positions",
                self.normals.len(),
                self.positions.len()
            )));
        }
        if let Some(&i) = self
            .indices
            .iter()
            .find(|&&i| i as usize >= self.positions.len())
        {
            return Err(malformed(format!(
                "index {i} is out of range for {} vertices",
                self.positions.len()
            )));
        }
        let bad = self
            .positions
            .iter()
            .zip(&self.normals)
            .position(|(p, n)| !p.is_finite() || !n.is_finite());
        if let Some(vertex) = bad {
            return Err(MeshError::NonFinite {
                name: name.to_owned(),
                vertex,
            });
        }
        Ok(())
    }
}

impl Mesh {
    /// Whether the mesh, with vertices welded by position, is a closed, consistently
    /// wound surface: every edge is used exactly once in each direction. With
    /// counter-clockwise triangles and a positive [`volume`](Self::volume), every normal
    /// of such a surface points outward.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let mut cube = Mesh::unit_cube();
    /// assert!(cube.is_closed());
    /// cube.indices.truncate(33);
    /// assert!(!cube.is_closed());
    /// ```
    pub fn is_closed(&self) -> bool {
        let (welded, _) = super::weld::weld(&self.positions);
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for t in self.triangles() {
            let t = t.map(|i| welded[i as usize]);
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    /// The signed volume enclosed by the triangles: positive for a closed surface whose
    /// triangles run counter-clockwise seen from outside.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// assert!((Mesh::unit_cube().volume() - 1.0).abs() < 1e-6);
    /// ```
    pub fn volume(&self) -> f32 {
        self.triangles()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3());
                a.dot(b.cross(c)) / 6.0
            })
            .sum::<f64>() as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_cube_is_closed_with_outward_normals() {
        let cube = Mesh::unit_cube();
        cube.validate("cube").unwrap();
        assert_eq!(cube.bounds(), Some((Vec3::splat(-0.5), Vec3::splat(0.5))));
        for [a, b, c] in cube.triangles() {
            let [pa, pb, pc] = [a, b, c].map(|i| cube.positions[i as usize]);
            let face_normal = (pb - pa).cross(pc - pa).normalize();
            for i in [a, b, c] {
                // Flat, outward, and agreeing with the winding.
                assert_eq!(cube.normals[i as usize], face_normal);
                assert_eq!(cube.positions[i as usize].dot(face_normal), 0.5);
            }
        }
        assert!(cube.is_closed());
    }

    #[test]
    fn validate_names_what_is_wrong() {
        let mut m = Mesh::unit_cube();
        m.indices.push(99);
        let e = m.validate("box").unwrap_err().to_string();
        assert_eq!(
            e,
            "mesh `box` is malformed: 37 indices do not make whole triangles"
        );
        m.indices.extend([0, 0]);
        let e = m.validate("box").unwrap_err().to_string();
        assert_eq!(
            e,
            "mesh `box` is malformed: index 99 is out of range for 24 vertices"
        );
        let mut m = Mesh::unit_cube();
        m.positions[5].y = f32::NAN;
        let e = m.validate("box").unwrap_err().to_string();
        assert_eq!(e, "mesh `box`: vertex 5 has a non-finite coordinate");
        let e = Mesh::default().validate("nothing").unwrap_err().to_string();
        assert_eq!(e, "mesh `nothing` has no triangles");
        let mut m = Mesh::unit_cube();
        m.normals.pop();
        let e = m.validate("box").unwrap_err().to_string();
        assert_eq!(e, "mesh `box` is malformed: 23 normals for 24 positions");
    }
}
