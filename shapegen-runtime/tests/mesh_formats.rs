//! Target meshes in every format read the same triangles, voxelize to the same voxels,
//! and bad files are refused with the file's name; open meshes fill by winding number.

use std::fmt::Write as _;
use std::path::Path;

use base64::Engine as _;
use glam::{Affine3A, Quat, Vec3};
use shapegen_runtime::export::{Model, Palette, glb_bytes};
use shapegen_runtime::geometry::{Mesh, MeshFormat, PointCloud};
use shapegen_runtime::score::volume::{Fill, Grid, VolumeTarget, VoxelClasses};
use shapegen_runtime::{CUBE, Instance, MeshLibrary};

/// A box turned and moved off the axes, so that no lattice point lies on its surface.
fn placed_box() -> Mesh {
    let t = Affine3A::from_scale_rotation_translation(
        Vec3::new(1.3, 0.9, 1.1),
        Quat::from_rotation_y(0.3),
        Vec3::new(0.05, -0.02, 0.03),
    );
    let mut mesh = Mesh::unit_cube();
    for p in &mut mesh.positions {
        *p = t.transform_point3(*p);
    }
    mesh
}

/// The mesh's triangles as sorted position triples, in a canonical order.
fn triangles(mesh: &Mesh) -> Vec<[[u32; 3]; 3]> {
    let mut tris: Vec<[[u32; 3]; 3]> = mesh
        .triangles()
        .map(|t| {
            let mut corners = t.map(|i| mesh.positions[i as usize].to_array().map(f32::to_bits));
            // Rotate to start at the smallest corner, keeping the winding.
            let first = (0..3).min_by_key(|&k| corners[k]).unwrap();
            corners.rotate_left(first);
            corners
        })
        .collect();
    tris.sort();
    tris
}

fn obj(mesh: &Mesh) -> String {
    let mut text = String::new();
    for p in &mesh.positions {
        writeln!(text, "v {} {} {}", p.x, p.y, p.z).unwrap();
    }
    for [a, b, c] in mesh.triangles() {
        writeln!(text, "f {} {} {}", a + 1, b + 1, c + 1).unwrap();
    }
    text
}

fn stl_ascii(mesh: &Mesh) -> String {
    let mut text = "solid box\n".to_owned();
    for t in mesh.triangles() {
        text += "facet normal 0 0 0\nouter loop\n";
        for i in t {
            let p = mesh.positions[i as usize];
            writeln!(text, "vertex {} {} {}", p.x, p.y, p.z).unwrap();
        }
        text += "endloop\nendfacet\n";
    }
    text + "endsolid box\n"
}

fn stl_binary(mesh: &Mesh) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes.extend((mesh.triangle_count() as u32).to_le_bytes());
    for t in mesh.triangles() {
        bytes.extend([0u8; 12]);
        for i in t {
            for c in mesh.positions[i as usize].to_array() {
                bytes.extend(c.to_le_bytes());
            }
        }
        bytes.extend([0u8; 2]);
    }
    bytes
}

fn ply_header(format: &str, mesh: &Mesh) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment a box\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        mesh.vertex_count(),
        mesh.triangle_count()
    )
}

fn ply_ascii(mesh: &Mesh) -> String {
    let mut text = ply_header("ascii", mesh);
    for p in &mesh.positions {
        writeln!(text, "{} {} {}", p.x, p.y, p.z).unwrap();
    }
    for [a, b, c] in mesh.triangles() {
        writeln!(text, "3 {a} {b} {c}").unwrap();
    }
    text
}

fn ply_binary(mesh: &Mesh) -> Vec<u8> {
    let mut bytes = ply_header("binary_little_endian", mesh).into_bytes();
    for p in &mesh.positions {
        for c in p.to_array() {
            bytes.extend(c.to_le_bytes());
        }
    }
    for t in mesh.triangles() {
        bytes.push(3);
        for i in t {
            bytes.extend((i as i32).to_le_bytes());
        }
    }
    bytes
}

/// The box as a binary glTF, written by the project's own exporter: one instance of
/// the unit cube placed by the box's transform.
fn glb() -> Vec<u8> {
    let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
    let t = Affine3A::from_scale_rotation_translation(
        Vec3::new(1.3, 0.9, 1.1),
        Quat::from_rotation_y(0.3),
        Vec3::new(0.05, -0.02, 0.03),
    );
    let model = [Instance {
        transform: t,
        mesh: CUBE,
    }];
    glb_bytes(Model::new(&model, &meshes, &Palette::new())).unwrap()
}

/// The same glTF as JSON with its buffer in a `data:` URI.
fn gltf_json(glb: &[u8]) -> Vec<u8> {
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&glb[20..20 + json_len])
        .unwrap()
        .trim_end();
    let bin = &glb[20 + json_len + 8..];
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bin)
    );
    let mut root: serde_json::Value = serde_json::from_str(json).unwrap();
    root["buffers"][0]["uri"] = serde_json::Value::String(uri);
    serde_json::to_vec(&root).unwrap()
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn classes(mesh: Mesh, fill: Fill) -> VoxelClasses {
    let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [16, 16, 16]).unwrap();
    let target = VolumeTarget {
        name: "box".into(),
        mesh,
        inside: 1.0,
        outside: -1.0,
        fill,
    };
    VoxelClasses::new(&grid, &[target]).unwrap()
}

#[test]
fn every_format_reads_the_same_triangles_and_voxels() {
    let dir = tempfile::tempdir().unwrap();
    let reference = placed_box();
    let glb = glb();
    let files = [
        write(dir.path(), "box.obj", obj(&reference)),
        write(dir.path(), "box.stl", stl_ascii(&reference)),
        write(dir.path(), "box_binary.STL", stl_binary(&reference)),
        write(dir.path(), "box.ply", ply_ascii(&reference)),
        write(dir.path(), "box_binary.ply", ply_binary(&reference)),
        write(dir.path(), "box.glb", &glb),
        write(dir.path(), "box.gltf", gltf_json(&glb)),
    ];
    let expected = classes(reference.clone(), Fill::Parity);
    assert!(
        expected.target_voxels() > 100,
        "{}",
        expected.target_voxels()
    );
    for file in &files {
        let mesh = Mesh::load(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert_eq!(mesh.triangle_count(), 12, "{}", file.display());
        let voxels = classes(mesh.clone(), Fill::Parity);
        assert_eq!(voxels.voxels(), expected.voxels(), "{}", file.display());
        // Text formats carry the same f32 values: the same triangles exactly. The glTF
        // places the unit cube by a node transform, so its corners are computed.
        if MeshFormat::of_path(file) != Some(MeshFormat::Gltf) {
            assert_eq!(
                triangles(&mesh),
                triangles(&reference),
                "{}",
                file.display()
            );
        } else {
            let (lo, hi) = mesh.bounds().unwrap();
            let (rlo, rhi) = reference.bounds().unwrap();
            assert!(lo.abs_diff_eq(rlo, 1e-5) && hi.abs_diff_eq(rhi, 1e-5));
        }
    }
}

#[test]
fn bad_files_are_refused_naming_the_file_and_the_fault() {
    let dir = tempfile::tempdir().unwrap();
    let reference = placed_box();
    let cases: [(&str, Vec<u8>, &str); 9] = [
        (
            "a.fbx",
            b"x".to_vec(),
            "is not one of .obj, .stl, .ply, .gltf, .glb",
        ),
        (
            "a.stl",
            b"solid x\nfacet normal 0 0 1\nouter lop\n".to_vec(),
            "cannot read STL",
        ),
        (
            "b.stl",
            stl_binary(&reference)[..200].to_vec(),
            "cannot read STL",
        ),
        ("c.stl", vec![0; 84], "has no triangles"),
        (
            "a.ply",
            ply_ascii(&reference).replace("3 0", "3 99").into_bytes(),
            "names vertex 99",
        ),
        (
            "b.ply",
            b"ply\nformat ascii 1.0\nend_header\n".to_vec(),
            "no `vertex` element",
        ),
        (
            "c.ply",
            ply_ascii(&reference)
                .replace("element face 12", "element face 0")
                .into_bytes(),
            "no faces",
        ),
        ("a.glb", glb()[..100].to_vec(), "cannot read glTF"),
        (
            "b.gltf",
            String::from_utf8(gltf_json(&glb()))
                .unwrap()
                .replace("data:application/octet-stream;base64,", "box.bin#")
                .into_bytes(),
            "cannot read buffer",
        ),
    ];
    for (name, bytes, fault) in cases {
        let path = write(dir.path(), name, bytes);
        let message = Mesh::load(&path).unwrap_err().to_string();
        assert!(message.contains(&path.display().to_string()), "{message}");
        assert!(
            message.contains(fault),
            "{name}: expected `{fault}` in: {message}"
        );
    }
    let missing = Mesh::load(dir.path().join("none.stl"))
        .unwrap_err()
        .to_string();
    assert!(missing.contains("none.stl"), "{missing}");
}

#[test]
fn a_binary_ply_declaring_more_entries_than_its_bytes_hold_is_refused_before_reading() {
    let reference = placed_box();
    let binary = ply_binary(&reference);
    let end = b"end_header\n";
    let header_end = binary.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let with = |from: &str, to: &str| {
        let header = std::str::from_utf8(&binary[..header_end]).unwrap();
        [
            header.replacen(from, to, 1).as_bytes(),
            &binary[header_end..],
        ]
        .concat()
    };
    // An element of no properties takes no payload bytes: a huge count of them
    // would be read entry by entry until memory ran out.
    let empty = with(
        "element vertex",
        "element note 888888888888888880\nelement vertex",
    );
    let message = Mesh::from_ply_bytes("e.ply", &empty)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("e.ply")
            && message.contains("element `note` declares 888888888888888880 entries")
            && message.contains(&format!(
                "only {} bytes follow",
                12 * reference.vertex_count() + 13 * reference.triangle_count()
            )),
        "{message}"
    );
    let vertices = with(
        &format!("element vertex {}", reference.vertex_count()),
        "element vertex 4000000000",
    );
    let message = Mesh::from_ply_bytes("v.ply", &vertices)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("element `vertex` declares 4000000000 entries of at least 12 bytes"),
        "{message}"
    );
    // A few entries of an element without properties are harmless and still read.
    let few = with("element vertex", "element note 3\nelement vertex");
    let mesh = Mesh::from_ply_bytes("few.ply", &few).unwrap();
    assert_eq!(triangles(&mesh), triangles(&reference));
}

#[test]
fn an_open_mesh_fills_by_winding_number_as_the_closed_one_does_by_parity() {
    let closed = placed_box();
    let mut open = closed.clone();
    // Without its +x face, rays along +x cross the box once: parity streaks.
    open.indices.drain(..6);
    let reference = classes(closed.clone(), Fill::Parity);
    assert_ne!(
        classes(open.clone(), Fill::Parity).voxels(),
        reference.voxels()
    );
    assert_eq!(classes(open, Fill::Winding).voxels(), reference.voxels());
    // On a closed mesh both rules agree.
    assert_eq!(classes(closed, Fill::Winding).voxels(), reference.voxels());
}

#[test]
fn point_clouds_load_from_xyz_text_and_ply_vertices() {
    let dir = tempfile::tempdir().unwrap();
    let reference = placed_box();
    let xyz: String = reference
        .positions
        .iter()
        .map(|p| format!("{},{},{} 0 0 1\n", p.x, p.y, p.z))
        .collect();
    for path in [
        write(dir.path(), "scan.xyz", format!("# a scan\n\n{xyz}")),
        write(dir.path(), "scan.ply", ply_ascii(&reference)),
    ] {
        let cloud = PointCloud::load(&path).unwrap();
        assert_eq!(cloud.points, reference.positions, "{}", path.display());
    }
    let bad = write(dir.path(), "bad.xyz", "1 2\n");
    let message = PointCloud::load(&bad).unwrap_err().to_string();
    assert!(
        message.contains("bad.xyz") && message.contains("line 1"),
        "{message}"
    );
    let empty = write(dir.path(), "empty.xyz", "# nothing\n");
    assert!(
        PointCloud::load(&empty)
            .unwrap_err()
            .to_string()
            .contains("no points")
    );
}

#[test]
fn a_gltf_primitive_naming_a_missing_accessor_is_refused() {
    let json = r#"{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}"#;
    let message = Mesh::from_gltf_bytes("t.gltf", json.as_bytes(), None)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("names accessor 0, but the file has 0"),
        "{message}"
    );
}
