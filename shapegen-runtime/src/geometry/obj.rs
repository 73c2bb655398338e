//! Loading meshes from Wavefront OBJ text.

use std::io::{self, BufRead, Read};
use std::path::Path;

use glam::Vec3;

use super::mesh::{Mesh, MeshError};

impl Mesh {
    /// Loads a mesh from an OBJ file; see [`from_obj_str`](Self::from_obj_str). Errors
    /// name the file.
    pub fn from_obj(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
        read_obj(path.as_ref(), Mesh::from_obj_str)
    }

    /// Loads a mesh from OBJ text, naming it `name` in errors.
    ///
    /// Polygons are triangulated as fans; all objects and groups in the text are merged
    /// into one mesh; materials, texture coordinates, points and lines are ignored. The
    /// file's normals are used when every vertex has one, and computed otherwise (see
    /// [`compute_normals`](Self::compute_normals) with
    /// [`DEFAULT_CREASE_ANGLE`](Self::DEFAULT_CREASE_ANGLE)). A mesh without triangles
    /// or with a non-finite coordinate is an error.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    /// let mesh = Mesh::from_obj_str("quad", quad).unwrap();
    /// assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (4, 2));
    /// assert_eq!(mesh.normals[0], glam::Vec3::Z);
    ///
    /// let bad = Mesh::from_obj_str("bad", "v 0 0 0\nv 1 x 0\n").unwrap_err();
    /// assert_eq!(bad.to_string(), "cannot parse OBJ `bad` at line 2: position parse error");
    /// ```
    pub fn from_obj_str(name: &str, text: &str) -> Result<Mesh, MeshError> {
        let parse_error = |(line, what)| MeshError::Parse {
            name: name.to_owned(),
            line,
            what,
        };
        let models = match check_indices(text) {
            Ok(()) => load(text).map_err(parse_error)?,
            // The first fault is reported: a line before the bad index may not parse.
            Err(bad) => {
                return Err(parse_error(match load(&text[..bad.offset]) {
                    Err(earlier @ (Some(_), _)) => earlier,
                    _ => (Some(bad.line), bad.what),
                }));
            }
        };
        let mut mesh = Mesh::default();
        let mut has_normals = true;
        for model in &models {
            let m = &model.mesh;
            let base = mesh.positions.len() as u32;
            mesh.positions
                .extend(m.positions.chunks_exact(3).map(Vec3::from_slice));
            mesh.indices.extend(m.indices.iter().map(|&i| base + i));
            has_normals &= m.normals.len() == m.positions.len();
            if has_normals {
                mesh.normals
                    .extend(m.normals.chunks_exact(3).map(Vec3::from_slice));
            }
        }
        if mesh.indices.is_empty() {
            return Err(MeshError::Empty {
                name: name.to_owned(),
            });
        }
        if let Some(vertex) = mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                name: name.to_owned(),
                vertex,
            });
        }
        let normalized: Option<Vec<Vec3>> = has_normals
            .then(|| mesh.normals.iter().map(|n| n.try_normalize()).collect())
            .flatten();
        match normalized {
            Some(normals) => mesh.normals = normals,
            None => mesh.compute_normals(Mesh::DEFAULT_CREASE_ANGLE),
        }
        mesh.validate(name)?;
        Ok(mesh)
    }
}

impl Mesh {
    /// Loads a generator part from an OBJ file and normalizes it as the original
    /// implementation does every generator mesh it loads; see
    /// [`from_obj_str_normalized`](Self::from_obj_str_normalized). Errors name the file.
    pub fn from_obj_normalized(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
        read_obj(path.as_ref(), Mesh::from_obj_str_normalized)
    }

    /// Loads a generator part from OBJ text as [`from_obj_str`](Self::from_obj_str) does,
    /// then normalizes it exactly as the original implementation's `normalizeShape` does
    /// when it loads a generator mesh, so that instances of it have the original's size:
    ///
    /// - over the file's `v` lines, in file order and in `f32`: `mean = sum / count` and
    ///   `size = max - min` per axis;
    /// - every position becomes `p * (1 / size) - mean` per axis: the extent becomes 1
    ///   on every axis, but the mean is subtracted after scaling and is not itself
    ///   scaled, so the mesh is centred only when its mean is 0.
    ///
    /// An axis of zero extent (a flat part) keeps its scale, where the original would
    /// divide by zero. Normals follow the scaling (they are transformed by its inverse
    /// transpose and renormalized), where the original leaves them as they were; they
    /// only shade pictures and never change a score.
    ///
    /// ```
    /// use glam::{Vec3, vec3};
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// // A 2 x 4 x 1 box from 0 to (2, 4, 1): mean (1, 2, 0.5).
    /// let mut text = String::new();
    /// for corner in 0..8 {
    ///     let (x, y, z) = (2 * (corner & 1), 4 * (corner >> 1 & 1), corner >> 2 & 1);
    ///     text += &format!("v {x} {y} {z}\n");
    /// }
    /// text += "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
    /// let box_ = Mesh::from_obj_str_normalized("box", &text)?;
    /// let (lo, hi) = box_.bounds().unwrap();
    /// // Scaled to unit extent, then moved by minus the unscaled mean.
    /// assert_eq!(lo, vec3(-1.0, -2.0, -0.5));
    /// assert_eq!(hi - lo, Vec3::ONE);
    /// # Ok::<(), shapegen_runtime::geometry::MeshError>(())
    /// ```
    pub fn from_obj_str_normalized(name: &str, text: &str) -> Result<Mesh, MeshError> {
        let mut mesh = Mesh::from_obj_str(name, text)?;
        let Some((mean, size)) = vertex_stats(text) else {
            return Ok(mesh);
        };
        let scale = Vec3::select(size.cmpgt(Vec3::ZERO), size.recip(), Vec3::ONE);
        for p in &mut mesh.positions {
            *p = *p * scale - mean;
        }
        for n in &mut mesh.normals {
            *n = (*n / scale).normalize_or(*n);
        }
        mesh.validate(name)?;
        Ok(mesh)
    }
}

/// The mean and the bounding-box size of the `v` lines of OBJ text that has already
/// parsed, accumulated in `f32` in file order as the original does; `None` without
/// vertices.
fn vertex_stats(text: &str) -> Option<(Vec3, Vec3)> {
    let (mut sum, mut count) = (Vec3::ZERO, 0u32);
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for line in text.lines() {
        let mut words = line.split_whitespace();
        if words.next() != Some("v") {
            continue;
        }
        let mut coordinate = || words.next().and_then(|w| w.parse::<f32>().ok());
        let (Some(x), Some(y), Some(z)) = (coordinate(), coordinate(), coordinate()) else {
            continue;
        };
        let v = Vec3::new(x, y, z);
        sum += v;
        count += 1;
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (count > 0).then(|| (sum / count as f32, hi - lo))
}

/// Reads OBJ text with tobj: its models, or the line at fault (where known) and what
/// was wrong.
fn load(text: &str) -> Result<Vec<tobj::Model>, (Option<usize>, String)> {
    let mut reader = LineCounter {
        rest: text.as_bytes(),
        lines: 0,
    };
    tobj::load_obj_buf(&mut reader, &tobj::GPU_LOAD_OPTIONS, |_| {
        Ok(Default::default())
    })
    .map(|(models, _materials)| models)
    .map_err(|e| {
        let line = per_line(&e).then(|| reader.line_at_fault(text));
        (line, e.to_string())
    })
}

/// An index of a face or line element that refers to no position, texture coordinate
/// or normal of the file.
struct BadIndex {
    /// The byte offset of the start of its line.
    offset: usize,
    /// Its 1-based line.
    line: usize,
    what: String,
}

/// Checks every index of the `f` and `l` lines of OBJ text before tobj reads it: an
/// index is 1-based and at most the number of its kind in the file, or negative and
/// at most as many back as precede its line. tobj does not check such indices before
/// it multiplies them, so one far out of range overflows there. Words that do not
/// parse as indices are left to tobj, which reports their line.
fn check_indices(text: &str) -> Result<(), BadIndex> {
    const KINDS: [(&str, &str); 3] = [
        ("v", "position"),
        ("vt", "texture coordinate"),
        ("vn", "normal"),
    ];
    let kind_of = |word| KINDS.iter().position(|&(tag, _)| tag == word);
    let mut total = [0usize; 3];
    for line in text.lines() {
        if let Some(kind) = line.split_whitespace().next().and_then(kind_of) {
            total[kind] += 1;
        }
    }
    let mut before = [0usize; 3];
    let mut next = 0;
    for (number, line) in text.split_inclusive('\n').enumerate() {
        let offset = next;
        next += line.len();
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f" | "l") => {
                let parts = words.flat_map(|word| word.split('/').enumerate());
                let indices: Option<Vec<(usize, isize)>> = parts
                    .filter(|(_, part)| !part.is_empty())
                    .map(|(kind, part)| Some((kind, part.parse().ok()?)))
                    .collect();
                // tobj reports a line that does not parse before it uses any index.
                let Some(indices) = indices.filter(|i| i.iter().all(|&(kind, _)| kind < 3)) else {
                    continue;
                };
                for (kind, index) in indices {
                    let (count, range) = match index {
                        1.. => (total[kind], "in the file"),
                        _ => (before[kind], "before this line"),
                    };
                    if index == 0 || index.unsigned_abs() > count {
                        let noun = KINDS[kind].1;
                        return Err(BadIndex {
                            offset,
                            line: number + 1,
                            what: format!(
                                "{noun} index {index} refers to no {noun}: there are {count} \
                                 {range} (indices count from 1, or back from -1)"
                            ),
                        });
                    }
                }
            }
            Some(word) => {
                if let Some(kind) = kind_of(word) {
                    before[kind] += 1;
                }
            }
            None => {}
        }
    }
    Ok(())
}

/// Whether tobj raises `e` while reading the line at fault (rather than when it
/// assembles a finished object).
fn per_line(e: &tobj::LoadError) -> bool {
    use tobj::LoadError::*;
    !matches!(
        e,
        FaceVertexOutOfBounds
            | FaceTexCoordOutOfBounds
            | FaceNormalOutOfBounds
            | FaceColorOutOfBounds
            | InvalidPolygon
            | InvalidLoadOptionConfig
            | GenericFailure
    )
}

/// A reader over text that counts the lines consumed, so that a parse error can name
/// its line: tobj reads line by line and stops at the first bad one.
struct LineCounter<'a> {
    rest: &'a [u8],
    lines: usize,
}

impl LineCounter<'_> {
    /// The 1-based number of the last line read.
    fn line_at_fault(&self, text: &str) -> usize {
        let unterminated = self.rest.is_empty() && !text.is_empty() && !text.ends_with('\n');
        self.lines + usize::from(unterminated)
    }
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = buf.len().min(self.rest.len());
        buf[..n].copy_from_slice(&self.rest[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        Ok(self.rest)
    }

    fn consume(&mut self, amt: usize) {
        let (done, rest) = self.rest.split_at(amt);
        self.lines += done.iter().filter(|&&b| b == b'\n').count();
        self.rest = rest;
    }
}

/// Reads the OBJ file at `path` and makes a mesh of its text with `parse`, which names
/// it by its path; a file that cannot be read is an error naming it.
fn read_obj(
    path: &Path,
    parse: impl FnOnce(&str, &str) -> Result<Mesh, MeshError>,
) -> Result<Mesh, MeshError> {
    let text = std::fs::read_to_string(path).map_err(|source| MeshError::Io {
        path: path.to_owned(),
        source,
    })?;
    parse(&path.display().to_string(), &text)
}

#[cfg(test)]
mod tests {
    use glam::vec3;

    use super::*;

    #[test]
    fn merges_objects_and_keeps_file_normals() {
        let text = "\
o a
v 0 0 0
v 1 0 0
v 0 1 0
vn 0 0 2
f 1//1 2//1 3//1
o b
v 0 0 1
v 1 0 1
v 0 1 1
f 4//1 5//1 6//1
";
        let m = Mesh::from_obj_str("two", text).unwrap();
        assert_eq!((m.vertex_count(), m.triangle_count()), (6, 2));
        assert_eq!(m.indices, [0, 1, 2, 3, 4, 5]);
        assert_eq!(m.positions[4], vec3(1.0, 0.0, 1.0));
        assert!(
            m.normals.iter().all(|&n| n == Vec3::Z),
            "normalized file normals"
        );
    }

    #[test]
    fn computes_missing_normals() {
        // A tetrahedron without normals: every edge is sharp, 3 vertices per face.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        let m = Mesh::from_obj_str("tetra", text).unwrap();
        assert_eq!((m.vertex_count(), m.triangle_count()), (12, 4));
        assert!(m.is_closed());
        let centre = vec3(0.25, 0.25, 0.25);
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert!((n.length() - 1.0).abs() < 1e-6);
            assert!((*p - centre).dot(*n) > 0.0, "outward");
        }
    }

    #[test]
    fn errors_name_the_file_and_the_line() {
        let err = |text: &str| {
            Mesh::from_obj_str("leaf.obj", text)
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\n\nvn 0 zero 1\n"),
            "cannot parse OBJ `leaf.obj` at line 4: normal parse error"
        );
        assert_eq!(
            err("v 0 0 0\nf 1 2 x"),
            "cannot parse OBJ `leaf.obj` at line 2: face parse error"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nf 1 2 3\n"),
            "cannot parse OBJ `leaf.obj` at line 3: position index 3 refers to no position: \
             there are 2 in the file (indices count from 1, or back from -1)"
        );
        assert_eq!(
            err("v 0 0 0\n# nothing\n"),
            "mesh `leaf.obj` has no triangles"
        );
        assert_eq!(err(""), "mesh `leaf.obj` has no triangles");
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n"),
            "mesh `leaf.obj`: vertex 2 has a non-finite coordinate"
        );
    }

    /// Indices far out of range (the fuzzer found the first, `fuzz/fuzz_targets/obj_mesh.rs`)
    /// are errors that name their line, not overflows inside tobj.
    #[test]
    fn out_of_range_indices_name_their_line() {
        let err = |text: &str| Mesh::from_obj_str("fuzz", text).unwrap_err().to_string();
        let triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n";
        assert_eq!(
            err(&format!("{triangle}f -3/1/-012 -2/1/1 -1/1/1\n")),
            "cannot parse OBJ `fuzz` at line 6: normal index -12 refers to no normal: there \
             are 1 before this line (indices count from 1, or back from -1)"
        );
        assert_eq!(
            err(&format!("{triangle}f 1//1 2//6148914691236517206 3//1\n")),
            "cannot parse OBJ `fuzz` at line 6: normal index 6148914691236517206 refers to no \
             normal: there are 1 in the file (indices count from 1, or back from -1)"
        );
        assert_eq!(
            err(&format!("{triangle}f 1/0 2 3\n")),
            "cannot parse OBJ `fuzz` at line 6: texture coordinate index 0 refers to no \
             texture coordinate: there are 1 before this line (indices count from 1, or back \
             from -1)"
        );
        // A line before the bad index that does not parse is the fault reported.
        assert_eq!(
            err("v 0 0 0\nv 0 x 0\nf 1 2 -9\n"),
            "cannot parse OBJ `fuzz` at line 2: position parse error"
        );
        // A face may refer forward to positions later in the file.
        let forward = Mesh::from_obj_str("fuzz", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
        assert_eq!(forward.unwrap().triangle_count(), 1);
        let fuzzed = "o/\0\0\0 tri\nv 0 0 0\nv 0 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n\
                      f -3/1/-012/ /1 -1/1/1\ng second\nv 0 0 1\nf 1 2 4\n";
        for result in [
            Mesh::from_obj_str("fuzz", fuzzed),
            Mesh::from_obj_str_normalized("fuzz", fuzzed),
        ] {
            assert!(
                result
                    .unwrap_err()
                    .to_string()
                    .contains("at line 7: normal index -12")
            );
        }
    }

    /// The paper's scenes' meshes (`scenes/paper/` of the repository).
    #[test]
    fn loads_the_paper_meshes() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/paper");
        // (file, triangles in the file, vertex positions in the file)
        for (file, triangles, positions) in [
            ("spaceship_volume/cube.obj", 12, 8),
            ("spaceship_volume/spaceship_target.obj", 84, 44),
            ("tree_sketch1/trunk.obj", 64, 34),
            ("tree_sketch1/leaf.obj", 574, 294),
        ] {
            let m = Mesh::from_obj(dir.join(file)).unwrap();
            assert_eq!(m.triangle_count(), triangles, "{file}");
            assert_eq!(
                super::super::weld::weld(&m.positions).1,
                positions,
                "{file}"
            );
            assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-3));
        }
        let (lo, hi) = Mesh::from_obj(dir.join("spaceship_volume/spaceship_target.obj"))
            .unwrap()
            .bounds()
            .unwrap();
        assert!(lo.abs_diff_eq(vec3(-2.94, -0.37, 0.20), 0.01), "{lo}");
        assert!(hi.abs_diff_eq(vec3(2.94, 1.21, 7.96), 0.01), "{hi}");
    }

    #[test]
    fn missing_file_is_named() {
        let e = Mesh::from_obj("/no/such/dir/trunk.obj").unwrap_err();
        assert!(matches!(e, MeshError::Io { .. }));
        assert!(
            crate::error::error_chain(&e)
                .starts_with("cannot read mesh file `/no/such/dir/trunk.obj`: "),
            "{e}"
        );
    }
}
