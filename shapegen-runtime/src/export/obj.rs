//! Wavefront OBJ and MTL export.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use super::bake::{placements, used_meshes};
use super::error::ExportError;
use super::model::Model;

/// Writes the model as OBJ text referring to the material library `mtl_name` (a
/// file name such as `"tree.mtl"`, written with [`write_mtl`]).
///
/// One object (`o`) per mesh used, named after the mesh, in [`MeshId`] order, with
/// `usemtl` of the same name; within it every instance of the mesh in input order, as
/// world-space `v` and `vn` lines (one normal per vertex, numbered alike) and
/// triangles `f a//a b//b c//c`. Each vertex also carries its mesh's palette colour
/// (the common `v x y z r g b` extension), for viewers that ignore the MTL file.
/// Numbers are written in Rust's shortest round-trip form, so the text is exact and
/// deterministic.
///
/// [`MeshId`]: crate::MeshId
///
/// ```
/// use glam::{Affine3A, vec3};
/// use shapegen_runtime::{CUBE, Instance, export::{Model, Palette, write_obj}, geometry::MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let boxes = [Instance { transform: Affine3A::from_translation(vec3(2.0, 0.0, 0.0)), mesh: CUBE }];
/// let mut text = Vec::new();
/// write_obj(&mut text, "boxes.mtl", Model::new(&boxes, &meshes, &Palette::new()))?;
/// let text = String::from_utf8(text)?;
/// assert!(text.contains("mtllib boxes.mtl\no cube\nusemtl cube\nv 2.5 -0.5 -0.5 0.2542 0.3278 0.4341\n"));
/// assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_obj<W: Write>(writer: W, mtl_name: &str, model: Model<'_>) -> Result<(), ExportError> {
    let Model {
        instances,
        meshes,
        palette,
    } = model;
    let used = used_meshes(instances, meshes)?;
    let mut out = BufWriter::new(writer);
    writeln!(
        out,
        "# shapegen OBJ export: {} instances of {} meshes",
        instances.len(),
        used.len()
    )?;
    writeln!(out, "mtllib {mtl_name}")?;
    let mut next = 1u64; // OBJ indices are 1-based and global.
    for id in used {
        let (name, mesh) = (meshes.name(id).unwrap_or_default(), &meshes[id]);
        let [r, g, b] = palette.color(id, name);
        writeln!(out, "o {name}\nusemtl {name}")?;
        for place in placements(instances, id) {
            for p in &mesh.positions {
                let p = place.position(*p);
                writeln!(out, "v {} {} {} {r} {g} {b}", p.x, p.y, p.z)?;
            }
            for n in &mesh.normals {
                let n = place.normal(*n);
                writeln!(out, "vn {} {} {}", n.x, n.y, n.z)?;
            }
            for t in mesh.triangles() {
                let [a, b, c] = place.triangle(t, 0).map(|i| next + u64::from(i));
                writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}")?;
            }
            next += mesh.positions.len() as u64;
        }
    }
    out.flush()?;
    Ok(())
}

/// Writes the MTL material library for [`write_obj`]: one material per mesh used,
/// named after the mesh, with its palette colour as diffuse colour (`Kd`), no ambient
/// or specular part, opaque.
pub fn write_mtl<W: Write>(writer: W, model: Model<'_>) -> Result<(), ExportError> {
    let used = used_meshes(model.instances, model.meshes)?;
    let mut out = BufWriter::new(writer);
    writeln!(out, "# shapegen materials: {} meshes", used.len())?;
    for id in used {
        let name = model.meshes.name(id).unwrap_or_default();
        let [r, g, b] = model.palette.color(id, name);
        writeln!(out, "\nnewmtl {name}")?;
        writeln!(out, "Ka 0 0 0\nKd {r} {g} {b}\nKs 0 0 0\nd 1\nillum 1")?;
    }
    out.flush()?;
    Ok(())
}

/// Writes `path` with its extension set to `obj` and, next to it, the material library
/// with extension `mtl`: `save_obj("out/tree", ..)` writes `out/tree.obj` and
/// `out/tree.mtl`.
pub fn save_obj(path: impl AsRef<Path>, model: Model<'_>) -> Result<(), ExportError> {
    let obj_path = path.as_ref().with_extension("obj");
    let mtl_path = path.as_ref().with_extension("mtl");
    let mtl_name = mtl_path.file_name().unwrap_or_default().to_string_lossy();
    write_file(&obj_path, |f| write_obj(f, &mtl_name, model))?;
    write_file(&mtl_path, |f| write_mtl(f, model))
}

/// Creates `path` and writes it with `write`, naming the file in I/O errors.
pub(crate) fn write_file(
    path: &Path,
    write: impl FnOnce(&mut File) -> Result<(), ExportError>,
) -> Result<(), ExportError> {
    let named = |source| ExportError::File {
        path: path.to_owned(),
        source,
    };
    let mut file = File::create(path).map_err(named)?;
    match write(&mut file) {
        Err(ExportError::Io(source)) => Err(named(source)),
        other => other,
    }
}
