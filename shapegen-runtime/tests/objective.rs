//! Geometric objectives on hand-built models with known values, batch determinism, and
//! the errors of bad parameters.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use glam::{Affine3A, Quat, Vec2, Vec3};
use image::{GrayImage, Luma};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::error_chain;
use shapegen_runtime::geometry::{BoundMeshes, Mesh, MeshId, MeshLibrary};
use shapegen_runtime::optimize::Sense;
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{
    FootprintExcess, Height, NormalSpread, Objective, ObjectiveError, ObjectiveScratch,
    ObjectiveSet, ProjectionMatch, Surface, UniqueNormals, View,
};
use shapegen_runtime::{CUBE, Instance};

const ICOSAHEDRON: MeshId = MeshId(1);
const TRIANGLE: MeshId = MeshId(2);

/// A regular icosahedron of circumradius 0.5, wound counter-clockwise seen from outside.
fn icosahedron() -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let raw = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ];
    let positions: Vec<Vec3> = raw
        .iter()
        .map(|&(x, y, z)| Vec3::new(x, y, z).normalize() * 0.5)
        .collect();
    let faces: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut indices = Vec::new();
    for [a, b, c] in faces {
        let (pa, pb, pc) = (
            positions[a as usize],
            positions[b as usize],
            positions[c as usize],
        );
        let outward = (pb - pa).cross(pc - pa).dot(pa + pb + pc) > 0.0;
        indices.extend(if outward { [a, b, c] } else { [a, c, b] });
    }
    let normals = positions.iter().map(|p| p.normalize()).collect();
    Mesh {
        positions,
        normals,
        indices,
    }
}

/// One counter-clockwise triangle in the plane z = 0, facing +z: an open mesh.
fn triangle() -> Mesh {
    Mesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        normals: vec![Vec3::Z; 3],
        indices: vec![0, 1, 2],
    }
}

fn meshes() -> BoundMeshes {
    let mut library = MeshLibrary::new();
    library
        .register("icosahedron", icosahedron())
        .expect("the icosahedron is valid");
    library
        .register("triangle", triangle())
        .expect("the triangle is valid");
    library
        .bind_names("Test", &["cube", "icosahedron", "triangle"])
        .expect("the meshes bind")
}

fn instance(transform: Affine3A) -> Instance {
    Instance {
        transform,
        mesh: CUBE,
    }
}

/// A box spanning `[lo, hi]`.
fn cuboid(lo: Vec3, hi: Vec3) -> Instance {
    instance(Affine3A::from_scale_rotation_translation(
        hi - lo,
        Quat::IDENTITY,
        (lo + hi) / 2.0,
    ))
}

fn surface(model: &[Instance]) -> Surface {
    Surface::from_instances(model, &meshes())
}

fn measure(objective: &Objective, model: &[Instance]) -> f64 {
    objective.measure(&surface(model), &mut ObjectiveScratch::default())
}

const UNIQUE: Objective = Objective::UniqueNormals(UniqueNormals { tolerance_deg: 1.0 });
const SPREAD: Objective = Objective::NormalSpread(NormalSpread { tolerance_deg: 1.0 });

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-5
}

#[test]
fn a_cube_has_twelve_triangles_six_normals_and_a_right_angle_to_each_neighbour() {
    let cube = [instance(Affine3A::IDENTITY)];
    let s = surface(&cube);
    assert_eq!(s.triangles().len(), 12);
    assert_eq!(s.bounds(), Some((Vec3::splat(-0.5), Vec3::splat(0.5))));
    for (tri, n) in s.triangles().iter().zip(s.normals()) {
        let centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
        assert!((n.length() - 1.0).abs() < 1e-6);
        assert!(n.dot(centroid) > 0.0, "normal {n} points out of the cube");
    }
    assert_eq!(measure(&UNIQUE, &cube), 6.0);
    assert!(close(measure(&SPREAD, &cube), 6.0 * FRAC_PI_2));
    assert_eq!(
        measure(&Objective::Height(Height { target: 2.0 }), &cube),
        1.5
    );
    assert_eq!(
        measure(&Objective::Height(Height { target: 0.25 }), &cube),
        0.25
    );
}

#[test]
fn two_cubes_share_their_normals_and_the_higher_sets_the_height() {
    let two = [
        instance(Affine3A::IDENTITY),
        instance(Affine3A::from_translation(Vec3::new(3.0, 2.0, 0.0))),
    ];
    assert_eq!(surface(&two).triangles().len(), 24);
    assert_eq!(measure(&UNIQUE, &two), 6.0);
    assert!(close(measure(&SPREAD, &two), 6.0 * FRAC_PI_2));
    assert_eq!(
        measure(&Objective::Height(Height { target: 1.0 }), &two),
        1.5
    );
}

#[test]
fn a_cube_turned_45_degrees_with_an_upright_one_has_ten_normals() {
    let turned = Affine3A::from_quat(Quat::from_rotation_y(std::f32::consts::FRAC_PI_4));
    let model = [instance(Affine3A::IDENTITY), instance(turned)];
    assert_eq!(measure(&UNIQUE, &model), 10.0);
    // Eight sides 45 degrees apart, top and bottom a right angle from every side.
    assert!(close(
        measure(&SPREAD, &model),
        8.0 * FRAC_PI_4 + 2.0 * FRAC_PI_2
    ));
    // Alone, the turned cube still has 6, whatever the order of its instances.
    assert_eq!(measure(&UNIQUE, &[instance(turned)]), 6.0);
    let reversed = [instance(turned), instance(Affine3A::IDENTITY)];
    assert_eq!(measure(&UNIQUE, &reversed), 10.0);
    // A tolerance of 50 degrees merges the sides 45 degrees apart.
    let wide = Objective::UniqueNormals(UniqueNormals {
        tolerance_deg: 50.0,
    });
    assert!(measure(&wide, &model) < 10.0);
}

#[test]
fn scaled_and_mirrored_instances_keep_outward_normals() {
    let mirror = Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    let open = [Instance {
        transform: mirror,
        mesh: TRIANGLE,
    }];
    let s = surface(&open);
    assert_eq!(s.normals(), [Vec3::Z]);
    let upright = surface(&[Instance {
        transform: Affine3A::IDENTITY,
        mesh: TRIANGLE,
    }]);
    assert_eq!(upright.normals(), [Vec3::Z]);
    // A triangle turned over faces -z.
    let flipped = surface(&[Instance {
        transform: Affine3A::from_rotation_x(std::f32::consts::PI),
        mesh: TRIANGLE,
    }]);
    assert!((flipped.normals()[0] + Vec3::Z).length() < 1e-6);

    let squashed = Affine3A::from_scale(Vec3::new(-2.0, 0.5, 3.0))
        * Affine3A::from_quat(Quat::from_rotation_z(0.3));
    let s = surface(&[instance(squashed)]);
    assert_eq!(s.triangles().len(), 12);
    let centre = Vec3::ZERO;
    for (tri, n) in s.triangles().iter().zip(s.normals()) {
        let centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
        assert!(
            n.dot(centroid - centre) > 0.0,
            "normal {n} points out of the box"
        );
        // Perpendicular to the transformed triangle.
        assert!(n.dot(tri[1] - tri[0]).abs() < 1e-5 && n.dot(tri[2] - tri[0]).abs() < 1e-5);
    }
    assert_eq!(measure(&UNIQUE, &[instance(squashed)]), 6.0);
}

#[test]
fn flat_boxes_keep_only_their_faces_with_area() {
    let flat = [instance(Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0)))];
    let s = surface(&flat);
    // The four side quads collapse to segments; the top and bottom remain.
    assert_eq!(s.triangles().len(), 4);
    assert_eq!(measure(&UNIQUE, &flat), 2.0);
    assert!(close(measure(&SPREAD, &flat), 2.0 * PI));
    let gone = [instance(Affine3A::from_scale(Vec3::ZERO))];
    assert!(surface(&gone).is_empty());
    let nan = [instance(Affine3A::from_translation(Vec3::NAN))];
    assert!(surface(&nan).is_empty());
    let unknown = [Instance {
        transform: Affine3A::IDENTITY,
        mesh: MeshId(9),
    }];
    assert!(surface(&unknown).is_empty());
}

#[test]
fn an_icosahedron_has_one_normal_per_face() {
    let ball = [Instance {
        transform: Affine3A::from_quat(Quat::from_rotation_x(0.7)),
        mesh: ICOSAHEDRON,
    }];
    assert_eq!(measure(&UNIQUE, &ball), 20.0);
    // Adjacent faces' normals are acos(sqrt(5) / 3) apart.
    let adjacent = (5f64.sqrt() / 3.0).acos();
    assert!(close(measure(&SPREAD, &ball), 20.0 * adjacent));
    // Every normal joins one of fewer representatives when the tolerance exceeds that.
    let coarse = Objective::UniqueNormals(UniqueNormals {
        tolerance_deg: 45.0,
    });
    let n = measure(&coarse, &ball);
    assert!((2.0..20.0).contains(&n), "{n}");
}

#[test]
fn an_empty_model_stands_on_the_ground() {
    let empty: [Instance; 0] = [];
    assert_eq!(
        measure(&Objective::Height(Height { target: 4.0 }), &empty),
        4.0
    );
    assert_eq!(measure(&UNIQUE, &empty), 0.0);
    assert_eq!(measure(&SPREAD, &empty), 0.0);
    let footprint = Objective::FootprintExcess(FootprintExcess {
        min: Vec2::ZERO,
        max: Vec2::ONE,
    });
    assert_eq!(measure(&footprint, &empty), 0.0);
    let mut mask = vec![false; 16];
    mask[5] = true;
    let top = ProjectionMatch::new(View::Top, Vec2::ZERO, Vec2::ONE, 4, 4, &mask).unwrap();
    assert_eq!(measure(&Objective::from(top), &empty), 15.0 / 16.0);
    // A single normal has no other to be apart from.
    let one = [Instance {
        transform: Affine3A::IDENTITY,
        mesh: TRIANGLE,
    }];
    assert_eq!(measure(&SPREAD, &one), 0.0);
    assert_eq!(measure(&UNIQUE, &one), 1.0);
}

#[test]
fn footprint_excess_adds_up_the_overhang_on_each_side() {
    let footprint = Objective::FootprintExcess(FootprintExcess {
        min: Vec2::new(0.0, 0.0),
        max: Vec2::new(2.0, 1.0),
    });
    // x from -1 to 3 (1 over on each side), z from 0.5 to 1.5 (0.5 over the far side).
    let model = [cuboid(Vec3::new(-1.0, 0.0, 0.5), Vec3::new(3.0, 1.0, 1.5))];
    assert_eq!(measure(&footprint, &model), 2.5);
    let inside = [cuboid(Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 9.0, 1.0))];
    assert_eq!(measure(&footprint, &inside), 0.0);
    // Two boxes: the extent is their union's.
    let two = [
        cuboid(Vec3::new(-0.5, 0.0, 0.0), Vec3::new(0.5, 1.0, 0.5)),
        cuboid(Vec3::new(1.0, 0.0, -0.25), Vec3::new(2.0, 1.0, 0.5)),
    ];
    assert_eq!(measure(&footprint, &two), 0.75);
    assert_eq!(footprint.sense(), Sense::Minimize);
}

/// An 8 x 8 mask over `[0, 8]^2` with the given pixels set.
fn mask_of(pixels: &[(u32, u32)]) -> Vec<bool> {
    let mut mask = vec![false; 64];
    for &(x, y) in pixels {
        mask[(y * 8 + x) as usize] = true;
    }
    mask
}

#[test]
fn a_top_projection_covers_pixel_centres_inside_the_box() {
    // The box covers x in [1, 4] and z in [2, 3]: pixel centres x = 1.5, 2.5, 3.5 of
    // row 2 (row 0 at z = 0, the far edge).
    let model = [cuboid(Vec3::new(1.0, 0.0, 2.0), Vec3::new(4.0, 5.0, 3.0))];
    let mask = mask_of(&[(2, 2), (3, 2), (4, 2), (5, 2)]);
    let top = ProjectionMatch::new(View::Top, Vec2::ZERO, Vec2::splat(8.0), 8, 8, &mask).unwrap();
    assert_eq!(top.mask_pixels(), 4);
    assert!(top.mask(5, 2) && !top.mask(1, 2) && !top.mask(9, 0));
    // Covered and black: (2, 2), (3, 2); neither: 64 - 5 pixels.
    let objective = Objective::from(top.clone());
    assert_eq!(measure(&objective, &model), 61.0 / 64.0);
    assert_eq!(
        (objective.name(), objective.sense()),
        ("top_match", Sense::Maximize)
    );

    let image = top.render(&surface(&model));
    let black: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0 == [0])
        .map(|(x, y, _)| (x, y))
        .collect();
    assert_eq!(black, [(1, 2), (2, 2), (3, 2)]);
    // A target drawn from the model matches it everywhere.
    let own = ProjectionMatch::from_image(View::Top, Vec2::ZERO, Vec2::splat(8.0), &image).unwrap();
    assert_eq!(own.score(&surface(&model)), 1.0);
}

#[test]
fn pixel_centres_on_an_edge_follow_the_top_left_rule() {
    // x from 1.5 to 3.5 and z from 1.5 to 2.5 run through pixel centres: those on the
    // left and top edges are covered, those on the right and bottom edges are not.
    let model = [cuboid(Vec3::new(1.5, 0.0, 1.5), Vec3::new(3.5, 1.0, 2.5))];
    let top =
        ProjectionMatch::new(View::Top, Vec2::ZERO, Vec2::splat(8.0), 8, 8, &mask_of(&[])).unwrap();
    let image = top.render(&surface(&model));
    let black: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0 == [0])
        .map(|(x, y, _)| (x, y))
        .collect();
    assert_eq!(black, [(1, 1), (2, 1)]);
    assert_eq!(top.score(&surface(&model)), 62.0 / 64.0);
}

#[test]
fn a_front_projection_has_world_up_at_the_top_of_the_image() {
    // y from 6 to 7 is row 1 of 8 over y in [0, 8]; x from 0 to 2 is columns 0 and 1.
    let model = [cuboid(Vec3::new(0.0, 6.0, -3.0), Vec3::new(2.0, 7.0, 3.0))];
    let front = ProjectionMatch::new(
        View::Front,
        Vec2::ZERO,
        Vec2::splat(8.0),
        8,
        8,
        &mask_of(&[(0, 1), (1, 1)]),
    )
    .unwrap();
    assert_eq!(front.score(&surface(&model)), 1.0);
    assert_eq!(Objective::from(front.clone()).name(), "front_match");
    // Seen from above, the same box is a band along z at columns 0 and 1.
    let top = ProjectionMatch::new(
        View::Top,
        Vec2::new(0.0, -4.0),
        Vec2::new(8.0, 4.0),
        8,
        8,
        &mask_of(&[(0, 1), (1, 1)]),
    )
    .unwrap();
    let band: Vec<bool> = (0..64)
        .map(|i| i % 8 < 2 && (1..7).contains(&(i / 8)))
        .collect();
    let expected = ProjectionMatch::new(
        View::Top,
        Vec2::new(0.0, -4.0),
        Vec2::new(8.0, 4.0),
        8,
        8,
        &band,
    )
    .unwrap();
    assert_eq!(expected.score(&surface(&model)), 1.0);
    // (0, 1) and (1, 1) match; 10 more band pixels are covered but white.
    assert_eq!(top.score(&surface(&model)), 54.0 / 64.0);
}

#[test]
fn projection_images_read_black_as_the_mask() {
    let mut image = GrayImage::from_pixel(3, 2, Luma([255]));
    image.put_pixel(2, 1, Luma([127]));
    image.put_pixel(0, 0, Luma([128]));
    let p = ProjectionMatch::from_image(View::Front, Vec2::ZERO, Vec2::ONE, &image).unwrap();
    assert_eq!((p.width(), p.height(), p.mask_pixels()), (3, 2, 1));
    assert!(p.mask(2, 1) && !p.mask(0, 0));
    assert_eq!(p.area(), (Vec2::ZERO, Vec2::ONE));
}

#[test]
fn bad_projections_are_refused_with_what_is_wrong() {
    let ok = vec![false; 4];
    let new = |min: Vec2, max: Vec2, w: u32, h: u32, mask: &[bool]| {
        ProjectionMatch::new(View::Top, min, max, w, h, mask).unwrap_err()
    };
    assert_eq!(
        new(Vec2::ZERO, Vec2::ONE, 0, 4, &[]),
        ObjectiveError::EmptyImage {
            width: 0,
            height: 4
        }
    );
    let e = new(Vec2::ZERO, Vec2::ONE, 2, 2, &ok[..3]);
    assert!(
        e.to_string().contains("3 entries") && e.to_string().contains("needs 4"),
        "{e}"
    );
    let e = new(Vec2::ZERO, Vec2::new(1.0, 0.0), 2, 2, &ok);
    assert!(
        matches!(e, ObjectiveError::Area { .. }) && e.to_string().contains("area_min"),
        "{e}"
    );
    assert!(matches!(
        new(Vec2::ONE, Vec2::ZERO, 2, 2, &ok),
        ObjectiveError::Area { .. }
    ));
    assert!(matches!(
        new(Vec2::NAN, Vec2::ONE, 2, 2, &ok),
        ObjectiveError::Area { .. }
    ));
    assert!(matches!(
        new(Vec2::ZERO, Vec2::ONE, 5000, 5000, &ok),
        ObjectiveError::TooLarge { .. }
    ));
    let empty = GrayImage::new(0, 0);
    assert!(matches!(
        ProjectionMatch::from_image(View::Top, Vec2::ZERO, Vec2::ONE, &empty),
        Err(ObjectiveError::EmptyImage { .. })
    ));
}

#[test]
fn bad_sets_and_weights_are_refused_naming_the_objective() {
    assert_eq!(ObjectiveSet::new(vec![]), Err(ObjectiveError::NoObjectives));
    let height = Objective::Height(Height { target: 1.0 });
    assert_eq!(
        ObjectiveSet::new(vec![(String::new(), height.clone())]),
        Err(ObjectiveError::EmptyName { index: 0 })
    );
    assert_eq!(
        ObjectiveSet::new(vec![("h".into(), height.clone()), ("h".into(), UNIQUE)]),
        Err(ObjectiveError::DuplicateName("h".into()))
    );
    let cases = [
        (Objective::Height(Height { target: f32::NAN }), "`target`"),
        (
            Objective::UniqueNormals(UniqueNormals {
                tolerance_deg: -1.0,
            }),
            "`tolerance_deg`",
        ),
        (
            Objective::NormalSpread(NormalSpread {
                tolerance_deg: 200.0,
            }),
            "`tolerance_deg`",
        ),
        (
            Objective::FootprintExcess(FootprintExcess {
                min: Vec2::ONE,
                max: Vec2::ZERO,
            }),
            "footprint",
        ),
    ];
    for (objective, field) in cases {
        let e = ObjectiveSet::new(vec![("mine".into(), objective)]).unwrap_err();
        let text = error_chain(&e);
        assert!(text.contains("`mine`") && text.contains(field), "{text}");
    }
    let set = ObjectiveSet::new(vec![("h".into(), height), ("u".into(), UNIQUE)]).unwrap();
    assert_eq!(
        set.weighted(&[1.0, 2.0], &[1.0]),
        Err(ObjectiveError::WeightCount {
            given: 1,
            expected: 2
        })
    );
    assert_eq!(
        set.weighted(&[1.0], &[1.0, 1.0]),
        Err(ObjectiveError::ValueCount {
            given: 1,
            expected: 2
        })
    );
    let e = set
        .weighted(&[1.0, 2.0], &[1.0, f64::INFINITY])
        .unwrap_err();
    assert!(e.to_string().contains("`u`"), "{e}");
    assert_eq!(set.weighted(&[1.0, 2.0], &[2.0, 0.5]), Ok(-1.0));
}

/// Every objective kind, over a 16 x 16 image of `[-8, 8]^2`.
fn all_six() -> ObjectiveSet {
    let disc: Vec<bool> = (0..256)
        .map(|i| {
            let (x, y) = ((i % 16) as f32 - 7.5, (i / 16) as f32 - 7.5);
            x * x + y * y < 30.0
        })
        .collect();
    let lower: Vec<bool> = (0..256).map(|i| i / 16 >= 8).collect();
    let area = (Vec2::splat(-8.0), Vec2::splat(8.0));
    ObjectiveSet::new(vec![
        ("height".into(), Objective::Height(Height { target: 6.0 })),
        ("unique".into(), UNIQUE),
        ("spread".into(), SPREAD),
        (
            "footprint".into(),
            Objective::FootprintExcess(FootprintExcess {
                min: Vec2::splat(-3.0),
                max: Vec2::splat(3.0),
            }),
        ),
        (
            "top".into(),
            Objective::from(
                ProjectionMatch::new(View::Top, area.0, area.1, 16, 16, &disc).unwrap(),
            ),
        ),
        (
            "front".into(),
            Objective::from(
                ProjectionMatch::new(
                    View::Front,
                    Vec2::new(-8.0, 0.0),
                    Vec2::new(8.0, 16.0),
                    16,
                    16,
                    &lower,
                )
                .unwrap(),
            ),
        ),
    ])
    .unwrap()
}

/// Random models of boxes and icosahedra, some rotated, some empty.
fn population(n: usize, seed: u64) -> InstanceBatch {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut batch = InstanceBatch::new();
    for _ in 0..n {
        let parts = rng.random_range(0..40);
        batch.push_with(|out| {
            for _ in 0..parts {
                let size = Vec3::new(
                    rng.random_range(0.1..3.0),
                    rng.random_range(0.1..5.0),
                    rng.random_range(0.1..3.0),
                );
                let at = Vec3::new(
                    rng.random_range(-5.0..5.0),
                    rng.random_range(0.0..8.0),
                    rng.random_range(-5.0..5.0),
                );
                let turn = Quat::from_rotation_y(rng.random_range(0..4) as f32 * 0.4);
                let mesh = if rng.random_bool(0.1) {
                    ICOSAHEDRON
                } else {
                    CUBE
                };
                out.push(Instance {
                    transform: Affine3A::from_scale_rotation_translation(size, turn, at),
                    mesh,
                });
            }
        });
    }
    batch
}

#[test]
fn batches_measure_as_single_models_at_any_thread_count() {
    let set = all_six();
    assert_eq!(
        set.names().collect::<Vec<_>>(),
        ["height", "unique", "spread", "footprint", "top", "front"]
    );
    assert_eq!(
        set.senses(),
        [
            Sense::Minimize,
            Sense::Maximize,
            Sense::Maximize,
            Sense::Minimize,
            Sense::Maximize,
            Sense::Maximize
        ]
    );
    let meshes = meshes();
    let batch = population(37, 3);
    let k = set.len();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = vec![f64::NAN; batch.len() * k];
        pool.install(|| set.measure_batch(&batch, &meshes, &mut out));
        out
    };
    let one = run(1);
    let two = run(2);
    assert_eq!(
        one.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        two.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );
    assert!(one.iter().all(|v| v.is_finite()));
    let mut row = vec![0.0; k];
    for i in 0..batch.len() {
        set.measure(batch.model(i), &meshes, &mut row);
        assert_eq!(row, one[i * k..(i + 1) * k], "model {i}");
        // Each objective alone gives the value the set gives.
        let s = Surface::from_instances(batch.model(i), &meshes);
        for (j, (_, objective)) in set.entries().iter().enumerate() {
            assert_eq!(
                objective.measure(&s, &mut ObjectiveScratch::default()),
                row[j]
            );
        }
    }
    // The models differ, so the values do too.
    let first = &one[..k];
    assert!(one.chunks(k).any(|r| r != first));
}

#[test]
fn a_surface_refilled_forgets_the_previous_model() {
    let meshes = meshes();
    let mut s = Surface::new();
    s.fill(&[instance(Affine3A::IDENTITY)], &meshes);
    let mut scratch = ObjectiveScratch::default();
    assert_eq!(UNIQUE.measure(&s, &mut scratch), 6.0);
    s.fill(
        &[Instance {
            transform: Affine3A::IDENTITY,
            mesh: ICOSAHEDRON,
        }],
        &meshes,
    );
    assert_eq!(UNIQUE.measure(&s, &mut scratch), 20.0);
    s.clear();
    assert!(s.is_empty() && s.bounds().is_none());
    assert_eq!(UNIQUE.measure(&s, &mut scratch), 0.0);
}
