//! Generated geometry placed as facets goes through the scorers, the objectives and the
//! exporters as the same solid placed as a mesh does.

mod support {
    pub mod pavilions;
}

use glam::{Affine3A, Quat, Vec3, vec2, vec3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::export::{Model, Palette, glb_bytes, write_obj};
use shapegen_runtime::geometry::{Mesh, MeshId, MeshLibrary, Polygon, RoofShape};
use shapegen_runtime::score::objective::{Objective, ObjectiveScratch, Surface, UniqueNormals};
use shapegen_runtime::score::volume::{Fill, Grid, VolumeCounts, VolumeScorer, VolumeTarget};
use shapegen_runtime::score::{Form, Scorer};
use shapegen_runtime::{BoundMeshes, CUBE, Instance, Operators, Scope};
use support::pavilions::Pavilions;
use support::pavilions::{footprint, roof_shape};

const FACET: MeshId = MeshId(1);
const SOLID: MeshId = MeshId(2);

/// The cube, the facet, and `solid` as a mesh of its own.
fn meshes(solid: Mesh) -> BoundMeshes {
    let mut library = MeshLibrary::new();
    library.register("facet", Mesh::facet()).unwrap();
    library.register("solid", solid).unwrap();
    library
        .bind_names("Test", &["cube", "facet", "solid"])
        .unwrap()
}

/// A volume scorer on a grid whose voxel centres avoid the round coordinates the
/// solids' corners take, with a target block.
fn volume(meshes: &BoundMeshes) -> VolumeScorer {
    let grid = Grid::new(
        Vec3::new(-10.013, -0.037, -10.029),
        Vec3::new(9.987, 19.963, 9.971),
        [40, 40, 40],
    )
    .unwrap();
    let target = VolumeTarget {
        name: "block".into(),
        mesh: {
            let mut m = Mesh::unit_cube();
            for p in &mut m.positions {
                *p = *p * vec3(10.0, 12.0, 8.0) + vec3(0.0, 6.0, 0.0);
            }
            m
        },
        inside: 1.0,
        outside: -1.0,
        fill: Fill::Parity,
    };
    VolumeScorer::new(grid, &[target], meshes, Form::Weighted { overlap: 0.5 }).unwrap()
}

/// The counts that do not depend on how an instance's span is measured.
fn covered(c: VolumeCounts) -> [u64; 5] {
    [
        c.inside,
        c.outside,
        c.overlap_hits,
        c.overlap_voxels,
        c.out_of_grid_hits,
    ]
}

/// Whether the counts of a solid as a mesh (`a`) and as facets (`b`) agree: exactly, or
/// up to one row of the grid per count. The mesh path places corners in `f64` from the
/// mesh's `f32` positions; facets carry their corners in `f32`, so where the placement
/// turns the solid a corner moves by rounding (about 1e-6 of its coordinate, 1e-5 of a
/// voxel here): a voxel centre that close to a face may fall on its other side, and a
/// row of lattice points whose ray passes that close to an edge may see it on its
/// other side. Returns the largest difference.
fn agree(a: VolumeCounts, b: VolumeCounts, exact: bool, what: &str) -> u64 {
    let (a, b) = (covered(a), covered(b));
    if exact {
        assert_eq!(a, b, "{what}");
    }
    let worst = a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).max().unwrap();
    assert!(worst <= 40, "{what}: {a:?} {b:?}");
    worst
}

/// The placements the solids are tried at: moved (where the facets' corners are the
/// mesh's exactly), turned, partly out of the grid.
fn placements() -> Vec<Affine3A> {
    vec![
        Affine3A::from_translation(vec3(0.3, 0.0, -0.2)),
        Affine3A::from_rotation_translation(Quat::from_rotation_y(0.7), vec3(-2.0, 1.0, 3.0)),
        Affine3A::from_rotation_translation(
            Quat::from_rotation_y(-1.1) * Quat::from_rotation_x(0.2),
            vec3(7.0, 4.0, 1.0),
        ),
    ]
}

/// Every footprint's prism and every roof over it, as facets, covers the voxels the same
/// solid covers as one mesh instance (see [`agree`]), alone and overlapping a copy of
/// itself.
#[test]
fn facets_cover_what_the_solid_covers() {
    let (mut cases, mut empty, mut overlaps, mut differ, mut total) = (0, 0, 0, 0, 0);
    for shape in 0..4 {
        let lot = footprint(shape, 7.0);
        let mut solids = vec![lot.extrude(6.0)];
        for roof in 0..5 {
            solids.push(lot.roof(roof_shape(roof, 0.6), 0.4).unwrap().mesh);
        }
        for solid in solids {
            let meshes = meshes(solid.clone());
            let scorer = volume(&meshes);
            let mut scratch = scorer.scratch();
            for (k, place) in placements().into_iter().enumerate() {
                let exact = k == 0;
                let as_mesh = [Instance {
                    transform: place,
                    mesh: SOLID,
                }];
                let mut as_facets = Vec::new();
                let n = Scope::new(place, Vec3::ONE).surface(&solid, FACET, &mut as_facets);
                assert_eq!(n, solid.triangle_count());
                let a = scorer.count(&as_mesh, &mut scratch);
                let b = scorer.count(&as_facets, &mut scratch);
                empty += usize::from(a.inside + a.outside == 0);
                differ += agree(a, b, exact, &format!("shape {shape}, {place:?}"));
                total += a.inside + a.outside;

                // Twice, the second moved by half its size: the overlap counts too.
                let moved = Affine3A::from_translation(vec3(2.1, 0.5, 1.3)) * place;
                let both_meshes = [
                    as_mesh[0],
                    Instance {
                        transform: moved,
                        mesh: SOLID,
                    },
                ];
                let mut both_facets = as_facets.clone();
                Scope::new(moved, Vec3::ONE).surface(&solid, FACET, &mut both_facets);
                // Boxes mixed in change nothing in how the facets count.
                let cube = Instance {
                    transform: Affine3A::from_scale_rotation_translation(
                        vec3(3.0, 5.0, 2.0),
                        Quat::IDENTITY,
                        vec3(-1.0, 2.5, 0.0),
                    ),
                    mesh: CUBE,
                };
                both_facets.insert(3, cube);
                let a = scorer.count(&[both_meshes[0], cube, both_meshes[1]], &mut scratch);
                let b = scorer.count(&both_facets, &mut scratch);
                overlaps += usize::from(a.overlap_voxels > 0);
                differ += agree(a, b, exact, &format!("shape {shape}, twice, {place:?}"));
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 4 * 6 * 3);
    // Only a thin flat roof may fall between voxel centres.
    assert!(empty <= 4, "{empty} placements covered nothing");
    assert!(
        overlaps >= cases / 2,
        "{overlaps} of {cases} pairs overlapped"
    );
    eprintln!("{differ} of {total} voxels differ; {overlaps} of {cases} pairs overlap");
    // Rounding moves a few voxels in all: under 0.1% of those covered.
    assert!(differ * 1000 < total, "{differ} of {total} voxels differ");
}

/// Triangles parallel to the rays add nothing to the winding number: a prism's two walls
/// facing `-x` and `+x` cover what the whole prism covers, and one wall alone covers
/// nothing.
#[test]
fn open_facets_cover_nothing_alone() {
    let meshes = meshes(Mesh::unit_cube());
    let scorer = volume(&meshes);
    let mut scratch = scorer.scratch();
    let mut wall = Vec::new();
    let quad = Polygon::rectangle(vec2(6.0, 4.0)).unwrap();
    let slab = quad.extrude(3.0);
    // Only the triangles facing +x or -x of a prism: its two x walls, open elsewhere.
    let mut walls = slab.clone();
    walls.indices = slab
        .triangles()
        .filter(|t| {
            let [a, b, c] = t.map(|i| slab.positions[i as usize]);
            (b - a).cross(c - a).normalize().x.abs() > 0.9
        })
        .flatten()
        .collect();
    Scope::new(Affine3A::from_translation(vec3(0.2, 0.0, 0.1)), Vec3::ONE)
        .surface(&walls, FACET, &mut wall);
    assert_eq!(wall.len(), 4);
    let c = scorer.count(&wall, &mut scratch);
    // The two walls face away from each other: the points between them have winding
    // number 1, as for the whole prism; a single wall alone covers nothing.
    let whole = {
        let mut all = Vec::new();
        Scope::new(Affine3A::from_translation(vec3(0.2, 0.0, 0.1)), Vec3::ONE)
            .surface(&slab, FACET, &mut all);
        scorer.count(&all, &mut scratch)
    };
    assert_eq!(covered(c), covered(whole));
    let c = scorer.count(&wall[..2], &mut scratch);
    assert_eq!(c.inside + c.outside, 0, "{c:?}");
}

/// The objectives read a roof's faces through its facets: a hip roof on an L adds its
/// sloped faces' normals to the walls', and the surface is the solid's.
#[test]
fn objectives_count_generated_roof_faces() {
    let lot = footprint(0, 8.0);
    let meshes = meshes(Mesh::unit_cube());
    let house = Scope::UNIT
        .translate(vec3(0.0, 3.0, 0.0))
        .with_size(vec3(8.0, 6.0, 8.0));
    let mut model = Vec::new();
    house.extrude_polygon(&lot, 6.0, FACET, &mut model);
    let walls = Surface::from_instances(&model, &meshes);
    let mut scratch = ObjectiveScratch::default();
    let unique = Objective::UniqueNormals(UniqueNormals { tolerance_deg: 1.0 });
    // An L's six walls face four ways; with the top and the bottom, six normals.
    assert_eq!(unique.measure(&walls, &mut scratch), 6.0);
    let roof = house
        .roof_polygon(&lot, RoofShape::Hip { pitch: 0.6 }, 0.0, FACET, &mut model)
        .unwrap();
    let roofed = Surface::from_instances(&model, &meshes);
    // The hip faces slope four ways more; the roof's floor faces down as the prism's
    // bottom does, and the prism's top stays facing up.
    assert_eq!(unique.measure(&roofed, &mut scratch), 10.0);
    let (lo, hi) = roofed.bounds().unwrap();
    assert!(lo.abs_diff_eq(vec3(-4.0, 0.0, -4.0), 1e-4), "{lo}");
    // The roof stands on the walls' top.
    let ridge = roof.mesh.bounds().unwrap().1.z;
    assert!(ridge > 1.0);
    assert!((hi.y - (6.0 + ridge)).abs() < 1e-4, "{hi}");
}

/// Generated walls and roofs export under their facet meshes' names, so that each gets
/// its own material, every triangle of them once.
#[test]
fn exports_name_generated_parts_by_their_facet_mesh() {
    let meshes = support::pavilions::meshes();
    let mut ops = Operators::<Pavilions>::new(support::pavilions::LIMITS).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut exported = 0;
    for _ in 0..20 {
        let mut model = Vec::new();
        ops.random(4, &mut rng).derive_into(&mut model);
        let mut obj = Vec::new();
        write_obj(
            &mut obj,
            "site.mtl",
            Model::new(&model, &meshes, &Palette::new()),
        )
        .unwrap();
        let obj = String::from_utf8(obj).unwrap();
        let facets = model.iter().filter(|i| i.mesh != CUBE).count();
        let boxes = model.len() - facets;
        let faces = obj.lines().filter(|l| l.starts_with("f ")).count();
        assert_eq!(faces, facets + 12 * boxes);
        let glb = glb_bytes(Model::new(&model, &meshes, &Palette::new())).unwrap();
        let gltf = gltf::Gltf::from_slice(&glb).unwrap();
        let names: Vec<_> = gltf.materials().filter_map(|m| m.name()).collect();
        if facets > 0 {
            assert!(obj.contains("usemtl facet_wall") && obj.contains("usemtl facet_roof"));
            assert!(names.contains(&"facet_wall") && names.contains(&"facet_roof"));
            exported += 1;
        }
    }
    assert!(exported > 5, "{exported} sites with pavilions");
}
