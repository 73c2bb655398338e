//! Point clouds: the points of a scan, from XYZ text or a PLY file's vertices.

use std::path::Path;

use glam::Vec3;

use super::decode::decode;
use super::ply::ply_points;
use crate::geometry::mesh::MeshError;

/// A set of points in world space, as a scanner writes them: a target for the Chamfer
/// distance and the F-score ([`crate::score::metrics`]).
///
/// ```
/// use shapegen_runtime::geometry::PointCloud;
///
/// let cloud = PointCloud::from_xyz_str("scan.xyz", "# x y z r g b\n0 0 0 255 0 0\n1,2,3\n")?;
/// assert_eq!(cloud.points.len(), 2);
/// let err = PointCloud::from_xyz_str("scan.xyz", "0 0 0\n1 two 3\n").unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "cannot read XYZ `scan.xyz`: line 2: `two` is not a number; each line holds x y z \
///      (then anything), separated by spaces or commas"
/// );
/// # Ok::<(), shapegen_runtime::geometry::MeshError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointCloud {
    /// The points.
    pub points: Vec<Vec3>,
}

impl PointCloud {
    /// The file extensions read: XYZ text, and PLY (its `vertex` element).
    pub const EXTENSIONS: [&'static str; 3] = ["xyz", "txt", "ply"];

    /// Loads a point cloud from `.xyz` or `.txt` text
    /// ([`from_xyz_str`](Self::from_xyz_str)) or a `.ply` file's vertices (faces, if
    /// any, are ignored). Errors name the file.
    pub fn load(path: impl AsRef<Path>) -> Result<PointCloud, MeshError> {
        let path = path.as_ref();
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .filter(|e| Self::EXTENSIONS.contains(&e.as_str()))
            .ok_or_else(|| MeshError::Format {
                path: path.to_owned(),
                valid: ".xyz, .txt, .ply".into(),
            })?;
        let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
            path: path.to_owned(),
            source,
        })?;
        let name = path.display().to_string();
        if extension == "ply" {
            PointCloud::new(&name, ply_points(&name, &bytes)?)
        } else {
            let text = std::str::from_utf8(&bytes)
                .map_err(|e| decode("XYZ", &name, format!("the file is not UTF-8 text: {e}")))?;
            PointCloud::from_xyz_str(&name, text)
        }
    }

    /// Reads XYZ text, naming it `name` in errors: one point per line, its first three
    /// fields `x y z`, separated by spaces, tabs or commas; further fields (normals,
    /// colours) are ignored, as are empty lines and lines starting with `#` or `//`.
    pub fn from_xyz_str(name: &str, text: &str) -> Result<PointCloud, MeshError> {
        let mut points = Vec::new();
        for (at, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') || line.starts_with("//") {
                continue;
            }
            let mut fields = line
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|f| !f.is_empty());
            let mut coordinate = || -> Result<f32, MeshError> {
                let field = fields.next().unwrap_or("");
                field.parse::<f32>().map_err(|_| {
                    let what = if field.is_empty() {
                        "fewer than 3 numbers".to_owned()
                    } else {
                        format!("`{field}` is not a number")
                    };
                    decode(
                        "XYZ",
                        name,
                        format!(
                            "line {}: {what}; each line holds x y z (then anything), \
                             separated by spaces or commas",
                            at + 1
                        ),
                    )
                })
            };
            points.push(Vec3::new(coordinate()?, coordinate()?, coordinate()?));
        }
        PointCloud::new(name, points)
    }

    /// A cloud of `points`, checked non-empty and finite.
    fn new(name: &str, points: Vec<Vec3>) -> Result<PointCloud, MeshError> {
        if points.is_empty() {
            return Err(decode("point cloud", name, "it has no points"));
        }
        if let Some(vertex) = points.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                name: name.to_owned(),
                vertex,
            });
        }
        Ok(PointCloud { points })
    }

    /// The axis-aligned bounds `(min, max)` of the points.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.points.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    }
}
