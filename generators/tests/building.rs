//! The building generator: hand-built building programs whose instances are checked
//! against transforms worked out by hand, random programs that always derive into
//! plausible buildings, and the generator's name at run time.
//!
//! An instance `scope_frame * scale(scope_size) * mesh` has as matrix columns the scope's
//! world axes times its size along them, and as translation the scope's centre. The
//! expected values are written out as numbers (with the working in the comments), never
//! through the runtime's scope code.

use generators::building::{
    self, BASE_HEIGHT, Building, Extrude, Insert, LIMITS, LOT, Lot, MAX_TILES, Program, Repeat,
    RotateY, Scale, Split, Twist,
};
use generators::{GeneratorVisitor, Published};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::graph::Distribution;
use shapegen_runtime::prelude::*;
use shapegen_runtime::{Grammar, Mesh, MeshId};

const EPS: f32 = 1e-5;
/// `sqrt(3) / 2`: cos 30 degrees.
const S3_2: f32 = 0.866_025_4;

/// An instance as worked out by hand: mesh, the three matrix columns, the translation.
#[derive(Clone, Copy, Debug)]
struct Expected {
    mesh: MeshId,
    x: Vec3,
    y: Vec3,
    z: Vec3,
    centre: Vec3,
}

/// The world axes.
const WORLD: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];

/// A box of size `size` whose local axes are `axes`, centred at `centre`.
fn boxed(mesh: MeshId, axes: [Vec3; 3], size: Vec3, centre: Vec3) -> Expected {
    Expected {
        mesh,
        x: axes[0] * size.x,
        y: axes[1] * size.y,
        z: axes[2] * size.z,
        centre,
    }
}

/// The world axes turned by `angle` about y, given its cosine and sine: x goes to
/// `(c, 0, -s)`, z to `(s, 0, c)`.
fn turned(c: f32, s: f32) -> [Vec3; 3] {
    [vec3(c, 0.0, -s), Vec3::Y, vec3(s, 0.0, c)]
}

fn matches(actual: &Instance, e: &Expected) -> bool {
    let m = actual.transform.matrix3;
    actual.mesh == e.mesh
        && Vec3::from(m.x_axis).abs_diff_eq(e.x, EPS)
        && Vec3::from(m.y_axis).abs_diff_eq(e.y, EPS)
        && Vec3::from(m.z_axis).abs_diff_eq(e.z, EPS)
        && Vec3::from(actual.transform.translation).abs_diff_eq(e.centre, EPS)
}

fn describe(i: &Instance) -> String {
    let m = i.transform.matrix3;
    format!(
        "mesh {} x {:?} y {:?} z {:?} at {:?}",
        i.mesh.0,
        Vec3::from(m.x_axis),
        Vec3::from(m.y_axis),
        Vec3::from(m.z_axis),
        Vec3::from(i.transform.translation)
    )
}

/// Checks that `actual` holds exactly the `expected` instances, in order.
fn assert_instances(actual: &[Instance], expected: &[Expected]) {
    let listing = || actual.iter().map(describe).collect::<Vec<_>>().join("\n  ");
    assert_eq!(
        actual.len(),
        expected.len(),
        "instance count; got:\n  {}",
        listing()
    );
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        assert!(
            matches(a, e),
            "instance {i} is not {e:?}; got:\n  {}",
            listing()
        );
    }
}

fn derive(g: &Genome<Building>) -> Vec<Instance> {
    g.validate().expect("hand-built genomes are valid");
    let mut out = Vec::new();
    g.derive_into(&mut out);
    out
}

/// A genome of the lot alone, with a program gene on it; returns the program's position.
fn lot_with_program(base_height: f32) -> (Genome<Building>, u32) {
    let mut g = Genome::<Building>::with_root(Lot { base_height }).unwrap();
    let program = g.attach(0, "program", Program {}).unwrap();
    (g, program)
}

// --- hand-built programs --------------------------------------------------------------------

#[test]
fn a_lot_without_a_program_is_its_mass() {
    // 10 x 5 x 10 on the ground: centre (0, 2.5, 0).
    let mass = [boxed(
        CUBE,
        WORLD,
        vec3(10.0, 5.0, 10.0),
        vec3(0.0, 2.5, 0.0),
    )];
    let g = Genome::<Building>::with_root(Lot { base_height: 5.0 }).unwrap();
    assert_instances(&derive(&g), &mass);
    // A program without operations fills its scope with a box too.
    let (g, _) = lot_with_program(5.0);
    assert_instances(&derive(&g), &mass);
}

#[test]
fn extrude_then_insert_is_one_taller_box() {
    let (mut g, program) = lot_with_program(4.0);
    let extrude = g
        .attach(program, "extrude", Extrude { height: 6.0 })
        .unwrap();
    let next = g.attach(extrude, "next", Program {}).unwrap();
    g.attach(next, "insert", Insert { mesh: 0 }).unwrap();
    // Height 4 + 6 = 10, bottom kept at y = 0: centre y 5.
    let tower = boxed(CUBE, WORLD, vec3(10.0, 10.0, 10.0), vec3(0.0, 5.0, 0.0));
    assert_instances(&derive(&g), &[tower]);

    // Without its child program, the extrusion is filled with a box all the same.
    let (mut g, program) = lot_with_program(4.0);
    g.attach(program, "extrude", Extrude { height: 6.0 })
        .unwrap();
    assert_instances(&derive(&g), &[tower]);
}

#[test]
fn split_makes_parts_of_the_weighted_lengths() {
    // Along x, 3 parts of weights 1, 2, 1 (the third ratio is unused): lengths 2.5, 5,
    // 2.5 of the lot's 10, from x = -5: centres -3.75, 0, 3.75. Height 6, centre y 3.
    let (mut g, program) = lot_with_program(6.0);
    let split = Split {
        axis: 0,
        count: 3,
        ratios: vec3(2.0, 1.0, 2.0),
    };
    let split = g.attach(program, "split", split).unwrap();
    // Part 1 runs a program inserting the sphere; parts 0 and 2 are boxes.
    let middle = g.attach_at(split, "parts", 1, Program {}).unwrap();
    g.attach(middle, "insert", Insert { mesh: 1 }).unwrap();
    // A program on slot 3 is past `count` and not derived.
    g.attach_at(split, "parts", 3, Program {}).unwrap();
    assert_instances(
        &derive(&g),
        &[
            boxed(CUBE, WORLD, vec3(2.5, 6.0, 10.0), vec3(-3.75, 3.0, 0.0)),
            boxed(
                building::SPHERE,
                WORLD,
                vec3(5.0, 6.0, 10.0),
                vec3(0.0, 3.0, 0.0),
            ),
            boxed(CUBE, WORLD, vec3(2.5, 6.0, 10.0), vec3(3.75, 3.0, 0.0)),
        ],
    );

    // Along y, 2 parts of weights 1 and 2 of the height 9: 3 and 6 high, from y = 0:
    // centres 1.5 and 6.
    let (mut g, program) = lot_with_program(9.0);
    let split = Split {
        axis: 1,
        count: 2,
        ratios: vec3(2.0, 1.0, 1.0),
    };
    g.attach(program, "split", split).unwrap();
    assert_instances(
        &derive(&g),
        &[
            boxed(CUBE, WORLD, vec3(10.0, 3.0, 10.0), vec3(0.0, 1.5, 0.0)),
            boxed(CUBE, WORLD, vec3(10.0, 6.0, 10.0), vec3(0.0, 6.0, 0.0)),
        ],
    );
}

#[test]
fn repeat_runs_one_program_on_every_tile() {
    // Along z, tiles of 5 on the lot's 10: two tiles, centres z -2.5 and 2.5, each
    // turned by 30 degrees about its own vertical centre line. Height 3, centre y 1.5.
    let (mut g, program) = lot_with_program(3.0);
    let repeat = g
        .attach(program, "repeat", Repeat { axis: 2, tile: 5.0 })
        .unwrap();
    let tile = g.attach(repeat, "tile_program", Program {}).unwrap();
    let angle = 30f32.to_radians();
    g.attach(tile, "rotate", RotateY { angle }).unwrap();
    let axes = turned(S3_2, 0.5);
    assert_instances(
        &derive(&g),
        &[
            boxed(CUBE, axes, vec3(10.0, 3.0, 5.0), vec3(0.0, 1.5, -2.5)),
            boxed(CUBE, axes, vec3(10.0, 3.0, 5.0), vec3(0.0, 1.5, 2.5)),
        ],
    );
}

#[test]
fn repeat_makes_at_most_max_tiles() {
    // 12 + 3 x 12 = 48 high, scaled by 2 in height to 96: tiles of 2 would be 48, so
    // there are 24 tiles of 4, centres y 2, 6, .., 94.
    let (mut g, mut program) = lot_with_program(12.0);
    for _ in 0..3 {
        let extrude = g
            .attach(program, "extrude", Extrude { height: 12.0 })
            .unwrap();
        program = g.attach(extrude, "next", Program {}).unwrap();
    }
    let factor = vec3(1.0, 2.0, 1.0);
    let scale = g.attach(program, "scale", Scale { factor }).unwrap();
    let next = g.attach(scale, "next", Program {}).unwrap();
    g.attach(next, "repeat", Repeat { axis: 1, tile: 2.0 })
        .unwrap();
    let expected: Vec<Expected> = (0..24)
        .map(|i| {
            let centre = vec3(0.0, 2.0 + 4.0 * i as f32, 0.0);
            boxed(CUBE, WORLD, vec3(10.0, 4.0, 10.0), centre)
        })
        .collect();
    assert_eq!(expected.len(), MAX_TILES as usize);
    assert_instances(&derive(&g), &expected);
}

#[test]
fn twist_turns_floor_i_by_i_times_the_angle() {
    // Floors of 3 in the height 9: three floors, centres y 1.5, 4.5, 7.5, turned by 0,
    // 10 and 20 degrees.
    let (mut g, program) = lot_with_program(9.0);
    let angle = 10f32.to_radians();
    let twist = Twist {
        floor_height: 3.0,
        angle,
    };
    g.attach(program, "twist", twist).unwrap();
    let size = vec3(10.0, 3.0, 10.0);
    let (c10, s10) = (0.984_807_7, 0.173_648_18);
    let (c20, s20) = (0.939_692_6, 0.342_020_15);
    assert_instances(
        &derive(&g),
        &[
            boxed(CUBE, WORLD, size, vec3(0.0, 1.5, 0.0)),
            boxed(CUBE, turned(c10, s10), size, vec3(0.0, 4.5, 0.0)),
            boxed(CUBE, turned(c20, s20), size, vec3(0.0, 7.5, 0.0)),
        ],
    );
}

#[test]
fn scale_is_about_the_bottom_centre() {
    // 10 x 4 x 10 scaled by (2, 2, 0.5): 20 x 8 x 5, bottom kept at y = 0: centre y 4.
    let (mut g, program) = lot_with_program(4.0);
    let factor = vec3(2.0, 2.0, 0.5);
    g.attach(program, "scale", Scale { factor }).unwrap();
    let scaled = boxed(CUBE, WORLD, vec3(20.0, 8.0, 5.0), vec3(0.0, 4.0, 0.0));
    assert_instances(&derive(&g), &[scaled]);

    // A scale of 2 doubles every side: 20 x 8 x 20, centre y 4.
    let (mut g, program) = lot_with_program(4.0);
    let doubled = Scale {
        factor: Vec3::splat(2.0),
    };
    let scale = g.attach(program, "scale", doubled).unwrap();
    let doubled = boxed(CUBE, WORLD, vec3(20.0, 8.0, 20.0), vec3(0.0, 4.0, 0.0));
    assert_instances(&derive(&g), &[doubled]);
    // Then a scale of 0 flattens it onto its bottom.
    let next = g.attach(scale, "next", Program {}).unwrap();
    g.attach(next, "scale", Scale { factor: Vec3::ZERO })
        .unwrap();
    assert_instances(
        &derive(&g),
        &[boxed(CUBE, WORLD, Vec3::ZERO, vec3(0.0, 0.0, 0.0))],
    );
}

#[test]
fn a_program_runs_each_operation_on_its_own_copy_of_the_scope() {
    // Push / pop: the extrusion (10 x 6 x 10, centre y 3) and the sphere inserted in the
    // lot's own 10 x 4 x 10 scope (centre y 2) both start from the lot's scope.
    let (mut g, program) = lot_with_program(4.0);
    g.attach(program, "extrude", Extrude { height: 2.0 })
        .unwrap();
    g.attach(program, "insert", Insert { mesh: 1 }).unwrap();
    assert_instances(
        &derive(&g),
        &[
            boxed(CUBE, WORLD, vec3(10.0, 6.0, 10.0), vec3(0.0, 3.0, 0.0)),
            boxed(
                building::SPHERE,
                WORLD,
                vec3(10.0, 4.0, 10.0),
                vec3(0.0, 2.0, 0.0),
            ),
        ],
    );
}

#[test]
fn the_sphere_insert_places_the_low_poly_sphere() {
    let (mut g, program) = lot_with_program(4.0);
    g.attach(program, "insert", Insert { mesh: 1 }).unwrap();
    let instances = derive(&g);
    assert_eq!(instances.len(), 1);
    let bound = generators::default_meshes()
        .bind(Building::GRAPH)
        .expect("the default meshes hold the building's");
    assert_eq!(bound[instances[0].mesh], generators::low_poly_sphere());
    assert_eq!(bound[CUBE], Mesh::unit_cube());
}

#[test]
fn the_low_poly_sphere_is_closed_and_faces_outward() {
    let sphere = generators::low_poly_sphere();
    sphere.validate("sphere").unwrap();
    for [a, b, c] in sphere.triangles() {
        let [a, b, c] = [a, b, c].map(|i| sphere.positions[i as usize]);
        // Counter-clockwise seen from outside: the winding normal points away from the
        // centre, and every corner lies on the sphere of radius 0.5.
        assert!((b - a).cross(c - a).dot(a + b + c) > 0.0);
        for p in [a, b, c] {
            assert!((p.length() - 0.5).abs() < EPS);
        }
    }
    // Each triangle's vertices carry its own face normal.
    for t in sphere.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| sphere.positions[i as usize]);
        let face = (b - a).cross(c - a).normalize();
        for &i in t {
            assert!(sphere.normals[i as usize].abs_diff_eq(face, EPS));
        }
    }
}

// --- the graph ------------------------------------------------------------------------------

#[test]
fn the_lot_and_its_constants_agree_with_the_graph() {
    let graph = Building::GRAPH;
    assert_eq!(graph.name, "Building");
    assert_eq!(graph.meshes, ["cube", "sphere"]);
    let lot = &graph.nodes[graph.axiom as usize];
    assert_eq!(lot.name, "Lot");
    assert_eq!(
        lot.params[0].dist,
        Distribution::Uniform {
            lo: *BASE_HEIGHT.start(),
            hi: *BASE_HEIGHT.end()
        }
    );
    assert_eq!(LOT, vec2(10.0, 10.0));
    assert!(LIMITS.check().is_ok());
}

// --- random programs ------------------------------------------------------------------------

/// What a derived building measures: instances, height of its highest point, and the
/// share of its instances centred over the lot.
struct Measure {
    instances: usize,
    height: f32,
    on_lot: f32,
}

fn measure(instances: &[Instance]) -> Measure {
    let half = LOT / 2.0;
    let mut top = 0.0f32;
    for i in instances {
        for k in 0..8 {
            let unit = vec3(
                (k & 1) as f32 - 0.5,
                ((k >> 1) & 1) as f32 - 0.5,
                ((k >> 2) & 1) as f32 - 0.5,
            );
            top = top.max(i.transform.transform_point3(unit).y);
        }
    }
    let on_lot = instances
        .iter()
        .filter(|i| {
            let c = i.transform.translation;
            c.x.abs() <= half.x && c.z.abs() <= half.y
        })
        .count();
    Measure {
        instances: instances.len(),
        height: top,
        on_lot: on_lot as f32 / instances.len().max(1) as f32,
    }
}

/// Most instances a random program within the limits may give in these tests. Repeats
/// and twists multiply their subtree's instances by their tile count (at most
/// [`MAX_TILES`]); over the seeds below the longest programs give at most 844.
const MOST_INSTANCES: usize = 2_000;

fn check_random(genome: &Genome<Building>, out: &mut Vec<Instance>, what: &str) -> Measure {
    genome.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    genome
        .validate_limits(&LIMITS)
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    genome.derive_into(out);
    assert!(
        (1..=MOST_INSTANCES).contains(&out.len()),
        "{what}: {} instances\n{genome}",
        out.len()
    );
    for i in out.iter() {
        assert!(i.transform.is_finite(), "{what}: {}", describe(i));
        assert!(i.mesh == CUBE || i.mesh == building::SPHERE, "{what}");
    }
    measure(out)
}

fn median(mut values: Vec<f32>) -> f32 {
    values.sort_by(f32::total_cmp);
    values[values.len() / 2]
}

#[test]
fn random_programs_are_plausible_buildings() {
    let mut ops = Operators::<Building>::new(LIMITS).unwrap();
    let mut out = Vec::new();
    for initial_len in [10, 50, 150] {
        let (mut counts, mut heights, mut on_lot) = (Vec::new(), Vec::new(), Vec::new());
        for seed in 0..200 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let g = ops.random(initial_len, &mut rng);
            let m = check_random(&g, &mut out, &format!("random({initial_len}) seed {seed}"));
            counts.push(m.instances as f32);
            heights.push(m.height);
            on_lot.push(m.on_lot);
        }
        let most = counts.iter().copied().fold(0.0, f32::max);
        let (count, height, lot) = (median(counts), median(heights), median(on_lot));
        println!(
            "random({initial_len}): median {count} instances (most {most}), height {height}, \
             share on the lot {lot}"
        );
        assert!(
            (5.0..=200.0).contains(&count),
            "random({initial_len}): {count}"
        );
        assert!(
            (5.0..=60.0).contains(&height),
            "random({initial_len}): {height}"
        );
        assert!(lot >= 0.9, "random({initial_len}): {lot}");
    }
}

#[test]
fn the_longest_programs_stay_within_the_instance_bound() {
    let mut ops = Operators::<Building>::new(LIMITS).unwrap();
    let mut out = Vec::new();
    let mut most = 0;
    for seed in 0..200 {
        let mut rng = ChaCha8Rng::seed_from_u64(500 + seed);
        let g = ops.random(LIMITS.max_len, &mut rng);
        let m = check_random(&g, &mut out, &format!("random(max_len) seed {seed}"));
        most = most.max(m.instances);
    }
    println!("random({}): most {most} instances", LIMITS.max_len);
}

#[test]
fn samples_derive_into_buildings() {
    let mut ops = Operators::<Building>::new(LIMITS).unwrap();
    let mut out = Vec::new();
    let mut heights = Vec::new();
    for seed in 0..300 {
        let mut rng = ChaCha8Rng::seed_from_u64(1_000 + seed);
        let g = ops.sample(&mut rng);
        heights.push(check_random(&g, &mut out, &format!("sample seed {seed}")).height);
    }
    let height = median(heights);
    assert!((5.0..=60.0).contains(&height), "median height {height}");
}

#[test]
fn operators_keep_programs_buildings() {
    let mut ops = Operators::<Building>::new(LIMITS).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut out = Vec::new();
    let mut population: Vec<_> = (0..8).map(|_| ops.random(50, &mut rng)).collect();
    for step in 0..400 {
        let i = step % population.len();
        match step % 4 {
            0 => _ = ops.grow(&mut population[i], &mut rng),
            1 => _ = ops.cut(&mut population[i], &mut rng),
            2 => _ = ops.alter(&mut population[i], &mut rng),
            _ => {
                let j = (i + 1) % population.len();
                if let Some((a, b)) = ops.crossover(&population[i], &population[j], &mut rng) {
                    population[i] = a;
                    population[j] = b;
                }
            }
        }
        check_random(&population[i], &mut out, &format!("step {step}"));
    }
}

// --- the name -------------------------------------------------------------------------------

struct GraphName;

impl GeneratorVisitor for GraphName {
    type Output = (&'static str, &'static str, Limits);
    fn visit<G: Grammar>(self, limits: Limits) -> Self::Output {
        (G::GRAPH.name, G::GRAPH.key, limits)
    }
}

#[test]
fn the_building_is_published_with_its_limits() {
    let b = Published::Building;
    assert!(Published::ALL.contains(&b));
    assert_eq!(b.paper_limits(), LIMITS);
    assert_eq!(b.visit(GraphName), ("Building", "building", LIMITS));
}

#[test]
fn roofed_programs_grow_roofs_of_every_shape_and_leave_the_building_as_it_was() {
    use generators::building::roofed::{self, RoofedBuilding};
    // The published grammar has no roof; the roofed one has it in every program.
    let names = |g: &shapegen_runtime::GeneratorGraph| -> Vec<&str> {
        g.nodes.iter().map(|n| n.name).collect()
    };
    assert!(!names(Building::GRAPH).contains(&"Roof"));
    assert!(names(RoofedBuilding::GRAPH).contains(&"Roof"));
    assert_eq!(Building::GRAPH.meshes, ["cube", "sphere"]);
    assert_eq!(Building::GRAPH.key, "building");
    assert_eq!(RoofedBuilding::GRAPH.key, "roofed_building");
    let meshes = generators::default_meshes()
        .bind(RoofedBuilding::GRAPH)
        .unwrap();
    let mut ops = Operators::<RoofedBuilding>::new(LIMITS).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(41);
    let mut seen = [0usize; 6];
    let mut out = Vec::new();
    for _ in 0..200 {
        let genome = ops.random(60, &mut rng);
        genome.validate().unwrap();
        genome.derive_into(&mut out);
        assert!(!out.is_empty());
        for i in &out {
            assert!(i.transform.is_finite());
            assert!(meshes.get(i.mesh).is_some(), "mesh {:?} is bound", i.mesh);
            seen[i.mesh.0 as usize] += 1;
        }
    }
    // Boxes, spheres and every roof piece appear.
    for (id, count) in seen.iter().enumerate() {
        assert!(*count > 0, "mesh {id} never appears: {seen:?}");
    }
    assert_eq!(roofed::ROOF_PIECES.hip_end, roofed::ROOF_HIP_END);
}
