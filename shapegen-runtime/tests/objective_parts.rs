//! The objectives that read which part a triangle belongs to, `area_share` and
//! `roof_pitch`, on hand-built models with exact values, on generated roofs, in batches,
//! and the errors of bad parts and targets.

use glam::{Affine3A, Quat, Vec3, vec2, vec3};
use shapegen_runtime::error_chain;
use shapegen_runtime::evaluate::Sense;
use shapegen_runtime::geometry::{
    BoundMeshes, Mesh, MeshId, MeshLibrary, Polygon, RoofShape, facet_transform,
};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{
    AreaShare, Height, Objective, ObjectiveError, ObjectiveScratch, ObjectiveSet, Parts, RoofPitch,
    Surface,
};
use shapegen_runtime::{CUBE, Instance, Scope};

/// The meshes of a house: the cube, and the facet under each part's name.
const NAMES: [&str; 6] = ["cube", "wall", "roof", "window", "door", "solid_roof"];
const WALL: MeshId = MeshId(1);
const ROOF: MeshId = MeshId(2);
const WINDOW: MeshId = MeshId(3);
const DOOR: MeshId = MeshId(4);
/// A cube registered as a roof part (a flat slab).
const SOLID_ROOF: MeshId = MeshId(5);

fn meshes() -> BoundMeshes {
    let mut library = MeshLibrary::new();
    for name in ["wall", "roof", "window", "door"] {
        library.register(name, Mesh::facet()).unwrap();
    }
    library.register("solid_roof", Mesh::unit_cube()).unwrap();
    library.bind_names("House", &NAMES).unwrap()
}

fn parts(names: &[&str]) -> Parts {
    Parts::named(names, &NAMES).unwrap()
}

fn measure(objective: &Objective, model: &[Instance]) -> f64 {
    let surface = Surface::from_instances(model, &meshes());
    objective.measure(&surface, &mut ObjectiveScratch::default())
}

/// A box of `mesh` spanning `[lo, hi]`.
fn cuboid(mesh: MeshId, lo: Vec3, hi: Vec3) -> Instance {
    Instance {
        transform: Affine3A::from_scale_rotation_translation(
            hi - lo,
            Quat::IDENTITY,
            (lo + hi) / 2.0,
        ),
        mesh,
    }
}

/// The facet of `mesh` on the counter-clockwise triangle `a b c`.
fn facet(mesh: MeshId, a: Vec3, b: Vec3, c: Vec3) -> Instance {
    Instance {
        transform: facet_transform(a, b, c).unwrap(),
        mesh,
    }
}

/// The quad `a b c d` (counter-clockwise) as two facets of `mesh`.
fn quad(mesh: MeshId, [a, b, c, d]: [Vec3; 4]) -> [Instance; 2] {
    [facet(mesh, a, b, c), facet(mesh, a, c, d)]
}

/// A unit cube of wall, and a `w` by `h` quad of `mesh` in front of it, facing `+z`.
fn cube_and_front(mesh: MeshId, w: f32, h: f32) -> Vec<Instance> {
    let z = 0.6;
    let mut model = vec![Instance {
        transform: Affine3A::IDENTITY,
        mesh: WALL_CUBE,
    }];
    model.extend(quad(
        mesh,
        [
            vec3(0.0, 0.0, z),
            vec3(w, 0.0, z),
            vec3(w, h, z),
            vec3(0.0, h, z),
        ],
    ));
    model
}

/// The cube mesh counted as wall: the grammar's cube, here.
const WALL_CUBE: MeshId = CUBE;

fn share(parts_: &[&str], of: Option<&[&str]>, target: f32) -> Objective {
    Objective::AreaShare(AreaShare {
        parts: parts(parts_),
        of: of.map(parts),
        target,
    })
}

fn pitch(parts_: &[&str], target_deg: f32) -> Objective {
    Objective::RoofPitch(RoofPitch {
        parts: parts(parts_),
        target_deg,
    })
}

#[test]
fn a_window_on_a_unit_cube_of_wall_takes_a_seventh_of_the_area() {
    // The meshes as a building names them: a unit cube as the wall, facets as windows.
    let mut library = MeshLibrary::new();
    library.register("wall", Mesh::unit_cube()).unwrap();
    library.register("window", Mesh::facet()).unwrap();
    let names = ["cube", "wall", "window"];
    let meshes = library.bind_names("House", &names).unwrap();
    let (wall, window) = (MeshId(1), MeshId(2));
    let mut model = vec![Instance {
        transform: Affine3A::IDENTITY,
        mesh: wall,
    }];
    let z = 0.6;
    let corners = [
        vec3(0.0, 0.0, z),
        vec3(1.0, 0.0, z),
        vec3(1.0, 1.0, z),
        vec3(0.0, 1.0, z),
    ];
    model.extend(quad(window, corners));
    let surface = Surface::from_instances(&model, &meshes);
    let part = |wanted: &[&str]| Parts::named(wanted, &names).unwrap();
    let windows = Objective::AreaShare(AreaShare {
        parts: part(&["window"]),
        of: None,
        target: 0.0,
    });
    let mut scratch = ObjectiveScratch::default();
    assert_eq!(windows.measure(&surface, &mut scratch), 1.0 / 7.0);
    let of_walls = Objective::AreaShare(AreaShare {
        parts: part(&["window"]),
        of: Some(part(&["wall", "window"])),
        target: 0.4,
    });
    assert_eq!(
        of_walls.measure(&surface, &mut scratch),
        0.4f32 as f64 - 1.0 / 7.0
    );
}

#[test]
fn a_window_in_front_of_a_unit_cube_takes_a_seventh_of_the_area() {
    let model = cube_and_front(WINDOW, 1.0, 1.0);
    assert_eq!(measure(&share(&["window"], None, 0.0), &model), 1.0 / 7.0);
    assert_eq!(
        measure(&share(&["window"], Some(&["cube", "window"]), 0.0), &model),
        1.0 / 7.0
    );
    assert_eq!(
        measure(&share(&["window"], Some(&["window"]), 0.25), &model),
        0.75
    );
    assert_eq!(
        measure(&share(&["cube"], None, 0.5), &model),
        6.0 / 7.0 - 0.5
    );
    // A part the model lacks, and meshes it lacks altogether: share 0.
    assert_eq!(measure(&share(&["door"], None, 0.375), &model), 0.375);
    assert_eq!(
        measure(&share(&["door"], Some(&["door", "roof"]), 0.375), &model),
        0.375
    );
    assert_eq!(measure(&share(&["window"], None, 0.125), &[]), 0.125);
    let ratio = share(&["window", "door"], Some(&["wall", "window", "door"]), 0.4);
    assert_eq!(ratio.sense(), Sense::Minimize);
    assert_eq!(ratio.name(), "area_share");
}

#[test]
fn areas_are_measured_in_world_space() {
    // A cube scaled to 2 x 1 x 3 (area 2 (2 + 6 + 3) = 22) and a 2 x 3 window (6) made
    // of unit facets stretched by their transforms.
    let mut model = vec![cuboid(WALL_CUBE, Vec3::ZERO, vec3(2.0, 1.0, 3.0))];
    model.extend(quad(
        WINDOW,
        [
            vec3(0.0, 0.0, 3.5),
            vec3(2.0, 0.0, 3.5),
            vec3(2.0, 3.0, 3.5),
            vec3(0.0, 3.0, 3.5),
        ],
    ));
    assert_eq!(measure(&share(&["window"], None, 0.0), &model), 6.0 / 28.0);
    // Doors and windows on the walls of a 4 x 3 facade: the window-to-wall ratio.
    let facade = |mesh, x0: f32, x1: f32, y0: f32, y1: f32| {
        quad(
            mesh,
            [
                vec3(x0, y0, 0.0),
                vec3(x1, y0, 0.0),
                vec3(x1, y1, 0.0),
                vec3(x0, y1, 0.0),
            ],
        )
    };
    let model: Vec<Instance> = [
        facade(WALL, 0.0, 4.0, 0.0, 1.0),
        facade(WALL, 0.0, 4.0, 2.0, 3.0),
        facade(DOOR, 0.0, 1.0, 1.0, 2.0),
        facade(WINDOW, 1.0, 3.0, 1.0, 2.0),
        facade(WALL, 3.0, 4.0, 1.0, 2.0),
    ]
    .concat();
    let ratio = share(&["window", "door"], Some(&["wall", "window", "door"]), 0.0);
    assert_eq!(measure(&ratio, &model), 0.25);
    // Mirrored and rotated facets keep their area.
    let turned: Vec<Instance> = model
        .iter()
        .map(|i| Instance {
            transform: Affine3A::from_scale(vec3(-1.0, 1.0, 1.0))
                * Affine3A::from_rotation_y(0.7)
                * i.transform,
            mesh: i.mesh,
        })
        .collect();
    assert!((measure(&ratio, &turned) - 0.25).abs() < 1e-6);
}

/// Two 45 degree slopes from the eaves at `z = -1` and `z = 1` to the ridge at `y = 1`,
/// `z = 0`, each a quad of two facets of `mesh`, over `x` in `[0, len]`.
fn gable(mesh: MeshId, len: f32) -> Vec<Instance> {
    let p = vec3;
    [
        quad(
            mesh,
            [
                p(0.0, 0.0, 1.0),
                p(len, 0.0, 1.0),
                p(len, 1.0, 0.0),
                p(0.0, 1.0, 0.0),
            ],
        ),
        quad(
            mesh,
            [
                p(len, 0.0, -1.0),
                p(0.0, 0.0, -1.0),
                p(0.0, 1.0, 0.0),
                p(len, 1.0, 0.0),
            ],
        ),
    ]
    .concat()
}

#[test]
fn a_gable_of_two_45_degree_slopes_has_a_pitch_of_45() {
    let roof = gable(ROOF, 1.0);
    assert_eq!(measure(&pitch(&["roof"], 45.0), &roof), 0.0);
    assert_eq!(measure(&pitch(&["roof"], 30.0), &roof), 15.0);
    assert_eq!(measure(&pitch(&["roof"], 90.0), &roof), 45.0);

    // Its underside (the slopes again, facing down) and its gable ends (vertical
    // triangles) are not counted; nor are the walls below, of another part.
    let mut closed = roof.clone();
    for slope in roof.chunks(2) {
        for f in slope {
            let placed = [Vec3::ZERO, Vec3::X, Vec3::Y].map(|p| f.transform.transform_point3(p));
            closed.push(facet(ROOF, placed[0], placed[2], placed[1]));
        }
    }
    let p = vec3;
    closed.push(facet(
        ROOF,
        p(0.0, 0.0, 1.0),
        p(0.0, 1.0, 0.0),
        p(0.0, 0.0, -1.0),
    ));
    closed.push(facet(
        ROOF,
        p(1.0, 0.0, -1.0),
        p(1.0, 1.0, 0.0),
        p(1.0, 0.0, 1.0),
    ));
    closed.push(cuboid(
        WALL_CUBE,
        vec3(0.0, -2.0, -1.0),
        vec3(1.0, 0.0, 1.0),
    ));
    assert_eq!(measure(&pitch(&["roof"], 30.0), &closed), 15.0);
    let name = pitch(&["roof"], 0.0);
    assert_eq!((name.name(), name.sense()), ("roof_pitch", Sense::Minimize));
}

#[test]
fn pitches_are_weighted_by_world_area() {
    // A 45 degree gable 2 long (area 4 sqrt 2) beside a flat slab 1 x 1 (top area 1):
    // the slab's top counts with pitch 0, its sides and bottom not at all.
    let mut model = gable(ROOF, 2.0);
    model.push(cuboid(SOLID_ROOF, vec3(3.0, 0.0, 0.0), vec3(4.0, 0.2, 1.0)));
    let slopes = 4.0 * 2f64.sqrt();
    let mean = slopes * 45.0 / (slopes + 1.0);
    let value = measure(&pitch(&["roof", "solid_roof"], 0.0), &model);
    assert!((value - mean).abs() < 1e-9, "{value} against {mean}");
    // The slab alone is flat.
    assert_eq!(measure(&pitch(&["solid_roof"], 10.0), &model), 10.0);
    // A roof of none of the parts, and an empty model: mean 0.
    assert_eq!(measure(&pitch(&["door"], 20.0), &model), 20.0);
    assert_eq!(measure(&pitch(&["roof"], 20.0), &[]), 20.0);
    // Turning the whole model about the vertical changes nothing; a mirror neither.
    let turned: Vec<Instance> = model
        .iter()
        .map(|i| Instance {
            transform: Affine3A::from_rotation_y(1.1)
                * Affine3A::from_scale(vec3(1.0, 1.0, -1.0))
                * i.transform,
            mesh: i.mesh,
        })
        .collect();
    let value = measure(&pitch(&["roof", "solid_roof"], 0.0), &turned);
    assert!((value - mean).abs() < 1e-5, "{value} against {mean}");
}

#[test]
fn generated_roofs_measure_their_pitch() {
    // Straight-skeleton roofs over an L-shaped house, emitted as facets: the slopes all
    // have the roof's pitch; the gable ends and the underside are left out.
    let l = Polygon::new([
        vec2(-4.0, -4.0),
        vec2(4.0, -4.0),
        vec2(4.0, 0.0),
        vec2(0.0, 0.0),
        vec2(0.0, 4.0),
        vec2(-4.0, 4.0),
    ])
    .unwrap();
    let house = Scope::UNIT.with_size(vec3(8.0, 6.0, 8.0));
    for (shape, deg) in [
        (
            RoofShape::Gable {
                pitch: 35f32.to_radians(),
            },
            35.0,
        ),
        (
            RoofShape::Hip {
                pitch: 50f32.to_radians(),
            },
            50.0,
        ),
        (
            RoofShape::Shed {
                pitch: 20f32.to_radians(),
            },
            20.0,
        ),
    ] {
        let mut model = Vec::new();
        house
            .roof_polygon(&l, shape, 0.3, ROOF, &mut model)
            .unwrap();
        let value = measure(&pitch(&["roof"], deg), &model);
        assert!(value < 1e-3, "{shape:?}: {value} from {deg}");
    }
}

#[test]
fn batches_measure_as_one_model_at_a_time() {
    let models = [
        cube_and_front(WINDOW, 1.0, 1.0),
        cube_and_front(DOOR, 0.5, 2.0),
        gable(ROOF, 3.0),
        [gable(ROOF, 1.0), cube_and_front(WINDOW, 2.0, 0.5)].concat(),
        Vec::new(),
    ];
    let set = ObjectiveSet::new(vec![
        ("openings".into(), share(&["window", "door"], None, 0.1)),
        (
            "ratio".into(),
            share(&["window"], Some(&["cube", "window", "door"]), 0.2),
        ),
        ("pitch".into(), pitch(&["roof"], 40.0)),
        ("height".into(), Objective::Height(Height { target: 1.0 })),
    ])
    .unwrap();
    let mut batch = InstanceBatch::new();
    for model in &models {
        batch.push_with(|out| out.extend_from_slice(model));
    }
    let meshes = meshes();
    let mut values = vec![f64::NAN; models.len() * set.len()];
    set.measure_batch(&batch, &meshes, &mut values);
    for (model, row) in models.iter().zip(values.chunks(set.len())) {
        let mut one = vec![0.0; set.len()];
        set.measure(model, &meshes, &mut one);
        assert_eq!(row, one);
    }
    assert_eq!(values[0], (1.0 / 7.0 - 0.1f32 as f64).abs());
    assert_eq!(values[2 * set.len() + 2], 5.0);
}

#[test]
fn unknown_part_names_are_refused_with_the_names_there_are() {
    let err = Parts::named(&["wall", "windw"], &NAMES).unwrap_err();
    assert_eq!(
        err,
        ObjectiveError::UnknownPart {
            name: "windw".into(),
            meshes: "`cube`, `wall`, `roof`, `window`, `door` and `solid_roof`".into(),
        }
    );
    assert!(
        err.to_string().starts_with("no mesh is named `windw`"),
        "{err}"
    );
    let err = Parts::bound(
        &["roof"],
        &MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap(),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "no mesh is named `roof`; the meshes are `cube`"
    );
    assert_eq!(
        Parts::bound(&["door", "wall"], &meshes()),
        Ok(parts(&["wall", "door"]))
    );
    assert_eq!(
        parts(&["door", "wall", "door"]).ids().collect::<Vec<_>>(),
        [WALL, DOOR]
    );
    let far = Parts::from_ids([MeshId(70), MeshId(3)]);
    assert!(far.contains(MeshId(70)) && far.contains(MeshId(3)) && !far.contains(MeshId(6)));
    assert_eq!(far.ids().collect::<Vec<_>>(), [MeshId(3), MeshId(70)]);
    assert!(!far.contains(MeshId(200)));
}

#[test]
fn bad_targets_and_parts_are_refused() {
    let cases = [
        (
            share(&["window"], None, f32::NAN),
            "`target` is NaN; it must be a share from 0 to 1",
        ),
        (share(&["window"], None, -0.1), "`target` is -0.1"),
        (share(&["window"], None, 1.5), "a share from 0 to 1"),
        (
            pitch(&["roof"], 91.0),
            "`target_deg` is 91; it must be an angle from 0 to 90 degrees",
        ),
        (pitch(&["roof"], f32::INFINITY), "`target_deg` is inf"),
        (pitch(&["roof"], -1.0), "from 0 to 90"),
        (
            Objective::RoofPitch(RoofPitch {
                parts: Parts::default(),
                target_deg: 30.0,
            }),
            "`parts` names no mesh; name at least one",
        ),
        (
            Objective::AreaShare(AreaShare {
                parts: Parts::default(),
                of: None,
                target: 0.5,
            }),
            "`parts` names no mesh",
        ),
        (
            Objective::AreaShare(AreaShare {
                parts: parts(&["window"]),
                of: Some(Parts::default()),
                target: 0.5,
            }),
            "`of` names no mesh",
        ),
        (
            share(&["window", "roof"], Some(&["wall", "window"]), 0.5),
            "`parts` has a mesh that `of` lacks",
        ),
    ];
    for (objective, want) in cases {
        let err = objective.validate().unwrap_err();
        assert!(err.to_string().contains(want), "{err} does not say {want}");
        let err = ObjectiveSet::new(vec![("wwr".into(), objective)]).unwrap_err();
        let message = error_chain(&err);
        assert!(message.starts_with("objective `wwr`: "), "{message}");
        assert!(message.contains(want), "{message}");
    }
    for ok in [
        share(&["window"], None, 0.0),
        share(&["window"], Some(&["window"]), 1.0),
        pitch(&["roof"], 0.0),
        pitch(&["roof"], 90.0),
    ] {
        assert_eq!(ok.validate(), Ok(()));
    }
}
