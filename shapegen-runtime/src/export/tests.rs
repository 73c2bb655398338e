//! Tests of the exporters, on instance lists built by hand.

use std::f32::consts::FRAC_PI_3;
use std::path::Path;

use glam::{Affine3A, Quat, Vec3, vec3};

use super::*;
use crate::geometry::{BoundMeshes, Instance, Mesh, MeshId, MeshLibrary};

const CUBE: MeshId = MeshId(0);
const TRUNK: MeshId = MeshId(1);
const LEAF: MeshId = MeshId(2);

/// cube, trunk and leaf from the tree generator's meshes, and `spare`, bound but unused.
fn meshes() -> BoundMeshes {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../generators/meshes");
    let mut library = MeshLibrary::new();
    library
        .register_obj("trunk", dir.join("trunk.obj"))
        .unwrap()
        .register_obj("leaf", dir.join("leaf.obj"))
        .unwrap()
        .register("spare", Mesh::unit_cube())
        .unwrap();
    library
        .bind_names("Test", &["cube", "trunk", "leaf", "spare"])
        .unwrap()
}

/// Three cubes (plain, turned and stretched, mirrored), two trunks and a leaf, mixed.
fn instances() -> Vec<Instance> {
    let at = |transform, mesh| Instance { transform, mesh };
    vec![
        at(Affine3A::from_translation(vec3(1.0, 2.0, 3.0)), CUBE),
        at(Affine3A::from_scale(vec3(0.5, 2.0, 0.5)), TRUNK),
        at(
            Affine3A::from_scale_rotation_translation(
                vec3(2.0, 1.0, 0.5),
                Quat::from_rotation_y(FRAC_PI_3),
                vec3(-4.0, 0.0, 1.0),
            ),
            CUBE,
        ),
        at(Affine3A::from_translation(vec3(0.0, 1.5, 0.0)), LEAF),
        at(mirrored(), CUBE),
        at(
            Affine3A::from_rotation_translation(Quat::from_rotation_z(0.5), Vec3::Y),
            TRUNK,
        ),
    ]
}

/// A mirroring transform (negative determinant) placing a cube at (5, 0, 0).
fn mirrored() -> Affine3A {
    Affine3A::from_translation(vec3(5.0, 0.0, 0.0)) * Affine3A::from_scale(vec3(-1.0, 1.0, 2.0))
}

/// The world-space vertices of all instances of `id`, in export order.
fn expected_positions(instances: &[Instance], meshes: &BoundMeshes, id: MeshId) -> Vec<Vec3> {
    instances
        .iter()
        .filter(|i| i.mesh == id)
        .flat_map(|i| {
            meshes[id]
                .positions
                .iter()
                .map(|&p| i.transform.transform_point3(p))
        })
        .collect()
}

fn bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    let lo = points.iter().fold(Vec3::INFINITY, |a, &p| a.min(p));
    let hi = points.iter().fold(Vec3::NEG_INFINITY, |a, &p| a.max(p));
    (lo, hi)
}

/// Every triangle's winding agrees with its vertex normals, which point away from the
/// centre of the instance (all test meshes are convex about their centre).
fn assert_outward(positions: &[Vec3], normals: &[Vec3], triangles: &[u32], centre: Vec3) {
    for t in triangles.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| positions[t[k] as usize]);
        let face = (b - a).cross(c - a);
        for &i in t {
            let n = normals[i as usize];
            assert!((n.length() - 1.0).abs() < 1e-5, "unit normal {n}");
            assert!(n.dot(face) > 0.0, "winding against normal {n} at {a}");
            assert!(
                n.dot(positions[i as usize] - centre) > 0.0,
                "inward normal {n}"
            );
        }
    }
}

#[test]
fn glb_parses_validates_and_holds_every_instance() {
    let (instances, meshes) = (instances(), meshes());
    let glb = glb_bytes(Model::new(&instances, &meshes, &Palette::new())).unwrap();
    let gltf = gltf::Gltf::from_slice(&glb).expect("valid glTF");
    let blob = gltf.blob.as_deref().expect("BIN chunk");

    assert_eq!(gltf.meshes().count(), 3, "one mesh per mesh used");
    assert_eq!(gltf.materials().count(), 3);
    assert_eq!(gltf.nodes().count(), 3);
    assert_eq!(gltf.buffers().count(), 1);
    assert_eq!(gltf.default_scene().unwrap().nodes().count(), 3);
    let palette = Palette::new();
    for (mesh, (id, count)) in gltf.meshes().zip([(CUBE, 3), (TRUNK, 2), (LEAF, 1)]) {
        let name = meshes.name(id).unwrap();
        assert_eq!(mesh.name(), Some(name));
        assert_eq!(mesh.primitives().count(), 1);
        let primitive = mesh.primitives().next().unwrap();
        let source = &meshes[id];
        let pos = primitive.get(&gltf::Semantic::Positions).unwrap();
        let nor = primitive.get(&gltf::Semantic::Normals).unwrap();
        let idx = primitive.indices().unwrap();
        assert_eq!(pos.count(), count * source.vertex_count(), "{name}");
        assert_eq!(nor.count(), count * source.vertex_count(), "{name}");
        assert_eq!(idx.count(), count * source.indices.len(), "{name}");
        assert_eq!(idx.data_type(), gltf::accessor::DataType::U32);

        // Bounds: the accessor's min/max are exactly those of the stored positions,
        // which match the instances' transformed vertices.
        let reader = primitive.reader(|_| Some(blob));
        let read: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
        let expected = expected_positions(&instances, &meshes, id);
        for (r, e) in read.iter().zip(&expected) {
            assert!(r.abs_diff_eq(*e, 1e-5), "{name}: {r} vs {e}");
        }
        let bb = primitive.bounding_box();
        let (lo, hi) = bounds(&read);
        assert_eq!((Vec3::from(bb.min), Vec3::from(bb.max)), (lo, hi), "{name}");
        let (elo, ehi) = bounds(&expected);
        assert!(lo.abs_diff_eq(elo, 1e-5) && hi.abs_diff_eq(ehi, 1e-5));

        let normals: Vec<Vec3> = reader.read_normals().unwrap().map(Vec3::from).collect();
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        assert!(indices.iter().all(|&i| (i as usize) < read.len()));
        let material = primitive.material();
        assert_eq!(material.name(), Some(name));
        let [r, g, b] = palette.color(id, name);
        assert_eq!(
            material.pbr_metallic_roughness().base_color_factor(),
            [r, g, b, 1.0]
        );

        // The mirrored cube (third cube) keeps outward normals and matching winding.
        if id == CUBE {
            let (v, t) = (source.vertex_count(), source.indices.len());
            assert_outward(
                &read[2 * v..],
                &normals[2 * v..],
                &indices[2 * t..]
                    .iter()
                    .map(|i| i - 2 * v as u32)
                    .collect::<Vec<_>>(),
                vec3(5.0, 0.0, 0.0),
            );
        }
    }
}

#[test]
fn glb_container_is_aligned_and_padded() {
    let glb = glb_bytes(Model::new(&instances(), &meshes(), &Palette::new())).unwrap();
    let word = |at: usize| u32::from_le_bytes(glb[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&glb[0..4], b"glTF");
    assert_eq!(word(4), 2);
    assert_eq!(word(8), glb.len());
    let json_len = word(12);
    assert_eq!(&glb[16..20], b"JSON");
    assert_eq!(json_len % 4, 0);
    let json = &glb[20..20 + json_len];
    let text = std::str::from_utf8(json).unwrap();
    assert!(
        text.trim_end().ends_with('}'),
        "JSON padded with spaces only"
    );
    let bin_at = 20 + json_len;
    assert_eq!(&glb[bin_at + 4..bin_at + 8], b"BIN\0");
    assert_eq!(word(bin_at) % 4, 0);
    assert_eq!(bin_at + 8 + word(bin_at), glb.len());
    let parsed = gltf::binary::Glb::from_slice(&glb).unwrap();
    assert_eq!(parsed.header.length as usize, glb.len());
}

#[test]
fn exports_are_deterministic() {
    let (instances, meshes) = (instances(), meshes());
    let palette = Palette::new().with("leaf", [0.1, 0.6, 0.2]);
    let glb = |m: &BoundMeshes| glb_bytes(Model::new(&instances, m, &palette)).unwrap();
    let obj = |m: &BoundMeshes| {
        let model = Model::new(&instances, m, &palette);
        let (mut obj, mut mtl) = (Vec::new(), Vec::new());
        write_obj(&mut obj, "t.mtl", model).unwrap();
        write_mtl(&mut mtl, model).unwrap();
        (obj, mtl)
    };
    // Same input, including meshes loaded afresh: identical bytes.
    assert_eq!(glb(&meshes), glb(&self::meshes()));
    assert_eq!(obj(&meshes), obj(&self::meshes()));
}

#[test]
fn obj_reloads_with_the_expected_geometry_and_materials() {
    let (instances, meshes) = (instances(), meshes());
    let dir = tempfile::tempdir().unwrap();
    save_obj(
        dir.path().join("scene.glb"),
        Model::new(&instances, &meshes, &Palette::new()),
    )
    .unwrap();
    let (models, materials) = tobj::load_obj(
        dir.path().join("scene.obj"),
        &tobj::LoadOptions {
            single_index: true,
            triangulate: true,
            ..Default::default()
        },
    )
    .unwrap();
    let materials = materials.unwrap();
    let names: Vec<_> = models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["cube", "trunk", "leaf"]);
    assert_eq!(materials.len(), 3);
    for (model, (id, count)) in models.iter().zip([(CUBE, 3), (TRUNK, 2), (LEAF, 1)]) {
        let source = &meshes[id];
        let m = &model.mesh;
        assert_eq!(
            m.positions.len() / 3,
            count * source.vertex_count(),
            "{}",
            model.name
        );
        assert_eq!(
            m.indices.len(),
            count * source.indices.len(),
            "{}",
            model.name
        );
        let positions: Vec<Vec3> = m.positions.chunks_exact(3).map(Vec3::from_slice).collect();
        // Per instance, the same vertices (tobj renumbers them in order of use, which
        // differs for mirrored instances, whose triangles are reversed).
        let sorted = |chunk: &[Vec3]| {
            let mut v: Vec<[f32; 3]> = chunk.iter().map(|p| p.to_array()).collect();
            v.sort_by(|a, b| a.partial_cmp(b).unwrap());
            v
        };
        let expected = expected_positions(&instances, &meshes, id);
        let v = source.vertex_count();
        for (got, want) in positions.chunks(v).zip(expected.chunks(v)) {
            for (p, e) in sorted(got).into_iter().zip(sorted(want)) {
                assert!(
                    Vec3::from(p).abs_diff_eq(Vec3::from(e), 1e-6),
                    "{p:?} vs {e:?}"
                );
            }
        }
        let material = &materials[m.material_id.unwrap()];
        assert_eq!(material.name, model.name);
        let [r, g, b] = Palette::new().color(id, &model.name);
        assert_eq!(material.diffuse, Some([r, g, b]));
        assert_eq!(&m.vertex_color[..3], &[r, g, b]);
        if id == CUBE {
            let normals: Vec<Vec3> = m.normals.chunks_exact(3).map(Vec3::from_slice).collect();
            let t = source.indices.len();
            let tris: Vec<u32> = m.indices[2 * t..]
                .iter()
                .map(|i| i - 2 * v as u32)
                .collect();
            assert_outward(
                &positions[2 * v..],
                &normals[2 * v..],
                &tris,
                vec3(5.0, 0.0, 0.0),
            );
        }
    }
}

#[test]
fn mirrored_and_flattened_instances_keep_outward_unit_normals() {
    let meshes = meshes();
    let flat = Affine3A::from_scale(vec3(1.0, 1.0, 0.0));
    for transform in [mirrored(), Affine3A::from_scale(Vec3::splat(-1.0)), flat] {
        let one = [Instance {
            transform,
            mesh: CUBE,
        }];
        let gltf =
            gltf::Gltf::from_slice(&glb_bytes(Model::new(&one, &meshes, &Palette::new())).unwrap())
                .unwrap();
        let blob = gltf.blob.as_deref().unwrap();
        let primitive = gltf.meshes().next().unwrap().primitives().next().unwrap();
        let reader = primitive.reader(|_| Some(blob));
        let p: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
        let n: Vec<Vec3> = reader.read_normals().unwrap().map(Vec3::from).collect();
        let t: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        if transform == flat {
            // Front and back stay facing out; the vanished sides get some unit normal.
            assert!(n.iter().all(|n| (n.length() - 1.0).abs() < 1e-6));
            assert_eq!(n.iter().filter(|n| **n == Vec3::Z).count(), 4);
            assert_eq!(n.iter().filter(|n| **n == Vec3::NEG_Z).count(), 4);
        } else {
            assert_outward(&p, &n, &t, transform.translation.into());
        }
    }
}

#[test]
fn empty_and_invalid_input() {
    let meshes = meshes();
    let glb = glb_bytes(Model::new(&[], &meshes, &Palette::new())).unwrap();
    let gltf = gltf::Gltf::from_slice(&glb).unwrap();
    assert_eq!(gltf.meshes().count(), 0);
    assert!(gltf.blob.is_none());
    let mut obj = Vec::new();
    write_obj(
        &mut obj,
        "none.mtl",
        Model::new(&[], &meshes, &Palette::new()),
    )
    .unwrap();
    assert_eq!(
        String::from_utf8(obj).unwrap(),
        "# shapegen OBJ export: 0 instances of 0 meshes\nmtllib none.mtl\n"
    );
    let stray = [Instance {
        transform: Affine3A::IDENTITY,
        mesh: MeshId(7),
    }];
    let err = glb_bytes(Model::new(&stray, &meshes, &Palette::new())).unwrap_err();
    assert_eq!(
        err.to_string(),
        "instance 0 uses mesh id 7, but only 4 meshes are bound"
    );
    let err = save_obj(
        "/no/such/dir/out",
        Model::new(&stray[..0], &meshes, &Palette::new()),
    )
    .unwrap_err();
    assert!(
        crate::error::error_chain(&err).starts_with("cannot write `/no/such/dir/out.obj`: "),
        "{err}"
    );
}

#[test]
fn glb_leaves_out_instances_placed_at_nan_or_infinity() {
    // glTF allows finite floats only (the validator's ACCESSOR_INVALID_FLOAT), and the
    // positions' min and max must be those of finite data.
    let meshes = meshes();
    let at = |transform, mesh| Instance { transform, mesh };
    let nan = Affine3A::from_translation(vec3(f32::NAN, 0.0, 0.0));
    let overflow = Affine3A::from_scale_rotation_translation(
        Vec3::splat(f32::MAX),
        Quat::IDENTITY,
        Vec3::splat(f32::MAX),
    );
    let finite = [
        at(Affine3A::from_translation(vec3(1.0, 2.0, 3.0)), CUBE),
        at(mirrored(), CUBE),
    ];
    let model = [
        at(nan, CUBE),
        finite[0],
        at(overflow, CUBE),
        at(nan, LEAF),
        finite[1],
        at(overflow, LEAF),
    ];
    let glb = glb_bytes(Model::new(&model, &meshes, &Palette::new())).unwrap();
    // Exactly the file of the finite instances: the leaf, with none, is not in it.
    assert_eq!(
        glb,
        glb_bytes(Model::new(&finite, &meshes, &Palette::new())).unwrap()
    );
    let gltf = gltf::Gltf::from_slice(&glb).unwrap();
    let names: Vec<_> = gltf.materials().map(|m| m.name()).collect();
    assert_eq!(names, [Some("cube")]);
    let blob = gltf.blob.as_deref().unwrap();
    let primitive = gltf.meshes().next().unwrap().primitives().next().unwrap();
    let p: Vec<Vec3> = primitive
        .reader(|_| Some(blob))
        .read_positions()
        .unwrap()
        .map(Vec3::from)
        .collect();
    assert_eq!(p, expected_positions(&finite, &meshes, CUBE));
    let bbox = primitive.bounding_box();
    assert_eq!((Vec3::from(bbox.min), Vec3::from(bbox.max)), bounds(&p));
    // Nothing finite at all: the empty model's file.
    let none = glb_bytes(Model::new(&model[2..4], &meshes, &Palette::new())).unwrap();
    assert_eq!(
        none,
        glb_bytes(Model::new(&[], &meshes, &Palette::new())).unwrap()
    );
}
