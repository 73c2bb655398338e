//! Objectives of bred children: measured from their parents' kept state
//! ([`BredObjectives`]) they equal their full measurement exactly, for every kind of
//! objective, over random operator sequences on the building generator, at 1 and 2
//! threads; and the distinct-normals objectives equal their definitions (every normal
//! compared with every distinct normal) to the bit, on random buildings and on triangle
//! soups made to sit on the tolerance. The weighted objectives of single-objective
//! searches count bred children the same way. The objectives that read a triangle's part
//! (`area_share`, `roof_pitch`) are measured on roofed buildings, whose roof pieces are
//! meshes of their own, beside the projections counted from parents.
//!
//! The number of sequences scales with `SHAPEGEN_PROPERTY_SCALE` (default 1; the debug
//! build runs a fifth of the release build's).

mod support {
    pub mod breeding;
    pub mod objective_scenes;
}

use generators::RoofedBuilding;
use generators::building::{self, Building};
use glam::{Affine3A, Quat, Vec2, Vec3};
use rand::{Rng, RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::evaluate::{Bred, Evaluator};
use shapegen_runtime::geometry::{BoundMeshes, Mesh, MeshId, MeshLibrary};
use shapegen_runtime::ops::{OperatorVariant, Operators};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{
    AreaShare, BredObjectives, FootprintExcess, Height, NormalSpread, Objective, ObjectiveScratch,
    ObjectiveSet, Parts, RoofPitch, Surface, UniqueNormals, WeightedObjectives,
};
use shapegen_runtime::{Genome, Grammar, Instance};
use support::breeding::{bred, sequences};
use support::objective_scenes::building_projections;

/// Generations bred from each population: every lineage is an operator sequence this
/// long.
const STEPS: usize = 12;

/// Every kind of objective: the building scene's two projections, the height, the
/// footprint, and distinct normals and their spread at `tolerance_deg`.
fn every_kind(tolerance_deg: f32) -> ObjectiveSet {
    let [top, front] = building_projections();
    ObjectiveSet::new(vec![
        ("top".into(), Objective::from(top)),
        ("height".into(), Objective::Height(Height { target: 20.0 })),
        (
            "facets".into(),
            Objective::UniqueNormals(UniqueNormals { tolerance_deg }),
        ),
        ("front".into(), Objective::from(front)),
        (
            "spread".into(),
            Objective::NormalSpread(NormalSpread { tolerance_deg }),
        ),
        (
            "footprint".into(),
            Objective::FootprintExcess(FootprintExcess {
                min: Vec2::splat(-5.0),
                max: Vec2::splat(5.0),
            }),
        ),
    ])
    .unwrap()
}

/// [`every_kind`] and the objectives that read a triangle's part, on the roofed
/// building's meshes: the share of the area of gable and hip-end pieces, among the cubes
/// and those, and the pitch of every roof piece.
fn every_kind_with_parts(tolerance_deg: f32) -> ObjectiveSet {
    let names = RoofedBuilding::GRAPH.meshes;
    let parts = |wanted: &[&str]| Parts::named(wanted, names).unwrap();
    let mut entries = every_kind(tolerance_deg).entries().to_vec();
    entries.insert(
        1,
        (
            "share".into(),
            Objective::AreaShare(AreaShare {
                parts: parts(&["roof_gable", "roof_hip_end"]),
                of: Some(parts(&["cube", "roof_gable", "roof_hip_end"])),
                target: 0.3,
            }),
        ),
    );
    entries.push((
        "pitch".into(),
        Objective::RoofPitch(RoofPitch {
            parts: parts(&["roof_gable", "roof_shed", "roof_pyramid", "roof_hip_end"]),
            target_deg: 30.0,
        }),
    ));
    entries.push((
        "roofs".into(),
        Objective::AreaShare(AreaShare {
            parts: parts(&["roof_gable", "roof_shed", "roof_pyramid", "roof_hip_end"]),
            of: None,
            target: 0.0,
        }),
    ));
    ObjectiveSet::new(entries).unwrap()
}

fn building_meshes() -> BoundMeshes {
    grammar_meshes::<Building>()
}

fn grammar_meshes<G: Grammar>() -> BoundMeshes {
    generators::default_meshes().bind(G::GRAPH).unwrap()
}

/// The distinct normals of `normals` by their definition: each normal, in order, joins
/// the first representative within the tolerance (`n . r >= cos`, in `f64`), else it
/// is one.
fn distinct_by_definition(normals: &[Vec3], tolerance_deg: f32) -> Vec<Vec3> {
    let cos = f64::from(tolerance_deg).to_radians().cos();
    let mut reps: Vec<Vec3> = Vec::new();
    for &n in normals {
        if !reps.iter().any(|&r| dot(n, r) >= cos) {
            reps.push(n);
        }
    }
    reps
}

/// The spread of `reps` by its definition: the sum, in order, of the angle from each to
/// its nearest other (largest dot product over all others).
fn spread_by_definition(reps: &[Vec3]) -> f64 {
    if reps.len() < 2 {
        return 0.0;
    }
    reps.iter()
        .enumerate()
        .map(|(i, &a)| {
            let nearest = reps
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, &b)| dot(a, b))
                .fold(f64::NEG_INFINITY, f64::max);
            nearest.clamp(-1.0, 1.0).acos()
        })
        .sum()
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    f64::from(a.x) * f64::from(b.x)
        + f64::from(a.y) * f64::from(b.y)
        + f64::from(a.z) * f64::from(b.z)
}

/// Checks the normals objectives of `surface` against their definitions, to the bit;
/// returns the number of distinct normals.
fn check_normals(surface: &Surface, tolerance_deg: f32, scratch: &mut ObjectiveScratch) -> usize {
    let reps = distinct_by_definition(surface.normals(), tolerance_deg);
    let unique =
        Objective::UniqueNormals(UniqueNormals { tolerance_deg }).measure(surface, scratch);
    assert_eq!(
        unique,
        reps.len() as f64,
        "{} normals at {tolerance_deg} degrees",
        surface.normals().len()
    );
    let spread = Objective::NormalSpread(NormalSpread { tolerance_deg }).measure(surface, scratch);
    let expected = spread_by_definition(&reps);
    assert_eq!(
        spread.to_bits(),
        expected.to_bits(),
        "spread of {} distinct normals at {tolerance_deg} degrees: {spread} against {expected}",
        reps.len()
    );
    reps.len()
}

/// Breeds lineages of building programs on a pool of `threads` threads: a population
/// of `lineages` random genomes, each generation's child `i` bred from parent `i` (one
/// operator; every fifth child from a random parent instead, as a GA picks them), for
/// [`STEPS`] generations. Each generation's children are measured from their parents'
/// states and in full; both must agree to the bit, and their distinct normals must equal
/// the definition's. Returns every generation's values.
fn bred_values<G: Grammar>(
    set: &ObjectiveSet,
    lineages: usize,
    threads: usize,
    seed: u64,
) -> Vec<Vec<f64>> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let meshes = grammar_meshes::<G>();
    let tolerance = set
        .entries()
        .iter()
        .find_map(|(_, o)| match o {
            Objective::UniqueNormals(UniqueNormals { tolerance_deg }) => Some(*tolerance_deg),
            _ => None,
        })
        .expect("the set counts distinct normals");
    pool.install(|| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut ops = Operators::<G>::new(building::LIMITS).unwrap();
        let mut population: Vec<Genome<G>> =
            (0..lineages).map(|_| ops.random(30, &mut rng)).collect();
        let mut bred_objectives = BredObjectives::new(set, &meshes).unwrap();
        let (mut scratch, mut surface) = (ObjectiveScratch::default(), Surface::new());
        let mut all = Vec::new();
        for step in 0..STEPS {
            let variant = if step % 2 == 0 {
                OperatorVariant::Weighted
            } else {
                OperatorVariant::Original
            };
            ops = ops.with_variant(variant);
            let from: Vec<u32> = (0..lineages as u32)
                .map(|i| {
                    if i % 5 == 4 {
                        rng.random_range(0..lineages as u32)
                    } else {
                        i
                    }
                })
                .collect();
            let children: Vec<Genome<G>> = from
                .iter()
                .map(|&p| bred(&mut ops, &population[p as usize], 30, &mut rng))
                .collect();
            let mut batch = InstanceBatch::new();
            for child in &children {
                batch.push_genome(child);
            }
            let k = set.len();
            let mut values = vec![f64::NAN; children.len() * k];
            let lineage = Bred {
                children: &children,
                parents: &population,
                from: &from,
            };
            bred_objectives.measure_bred(lineage, &batch, &mut values);
            let mut full = vec![f64::NAN; children.len() * k];
            set.measure_batch(&batch, &meshes, &mut full);
            for (i, (row, expected)) in values.chunks(k).zip(full.chunks(k)).enumerate() {
                let bits = |r: &[f64]| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(row),
                    bits(expected),
                    "step {step}, child {i} of parent {}: {row:?} against {expected:?}\n{:?}",
                    from[i],
                    children[i]
                );
                surface.fill(batch.model(i), &meshes);
                check_normals(&surface, tolerance, &mut scratch);
            }
            all.push(values);
            population = children;
        }
        let stats = bred_objectives.stats();
        assert_eq!(
            stats.incremental + stats.full,
            (STEPS * lineages) as u64,
            "{stats:?}"
        );
        assert!(stats.incremental > 3 * stats.full, "{stats:?}");
        all
    })
}

/// Every kind of objective, bred children measured from their parents equal to their
/// full measurement, at 1 and 2 threads alike.
#[test]
fn bred_children_measure_as_in_full_at_one_and_two_threads() {
    let lineages = sequences(600);
    for (tolerance, seed) in [(1.0, 1), (5.0, 2)] {
        let set = every_kind(tolerance);
        let one = bred_values::<Building>(&set, lineages, 1, seed);
        let two = bred_values::<Building>(&set, lineages, 2, seed);
        assert_eq!(one, two, "tolerance {tolerance}");
        eprintln!(
            "tolerance {tolerance}: {lineages} lineages of {STEPS} operators, {} children \
             equal to their full measurement at 1 and 2 threads",
            lineages * STEPS
        );
    }
}

/// The objectives that read a triangle's part, on roofed buildings: bred children
/// measured from their parents equal their full measurement, at 1 and 2 threads alike,
/// and the roofs give them values that vary.
#[test]
fn part_objectives_of_bred_roofed_buildings_measure_as_in_full() {
    let lineages = sequences(300);
    let set = every_kind_with_parts(1.0);
    let one = bred_values::<RoofedBuilding>(&set, lineages, 1, 3);
    let two = bred_values::<RoofedBuilding>(&set, lineages, 2, 3);
    assert_eq!(one, two);
    let k = set.len();
    for (slot, name) in [(1, "share"), (k - 2, "pitch"), (k - 1, "roofs")] {
        assert_eq!(set.entries()[slot].0, name);
        let values: Vec<f64> = one
            .iter()
            .flat_map(|generation| generation.iter().skip(slot).step_by(k).copied())
            .collect();
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        assert!(lo.is_finite() && lo < hi, "{name}: from {lo} to {hi}");
    }
    eprintln!(
        "{lineages} lineages of {STEPS} operators on roofed buildings, {} children equal to \
         their full measurement at 1 and 2 threads",
        lineages * STEPS
    );
}

/// A bred child's state is updated only from the instances it was counted from, so an
/// unrelated parent still gives exact values: every child here is "bred" from a random
/// member of an unrelated population.
#[test]
fn unrelated_parents_still_give_exact_values() {
    let set = every_kind(1.0);
    let meshes = building_meshes();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut ops = Operators::<Building>::new(building::LIMITS).unwrap();
    let n = sequences(50);
    let parents: Vec<Genome<Building>> = (0..n).map(|_| ops.random(30, &mut rng)).collect();
    let children: Vec<Genome<Building>> = (0..n).map(|_| ops.random(30, &mut rng)).collect();
    let from: Vec<u32> = (0..n).map(|_| rng.random_range(0..n as u32)).collect();
    let mut batch = InstanceBatch::new();
    for child in &children {
        batch.push_genome(child);
    }
    let mut bred_objectives = BredObjectives::new(&set, &meshes).unwrap();
    let mut values = vec![0.0; n * set.len()];
    let lineage = Bred {
        children: &children,
        parents: &parents,
        from: &from,
    };
    bred_objectives.measure_bred(lineage, &batch, &mut values);
    let mut full = vec![0.0; n * set.len()];
    set.measure_batch(&batch, &meshes, &mut full);
    assert_eq!(values, full);
}

/// The weighted objectives of a single-objective search count bred children the same
/// way: their fitness from the parents equals their fitness in full.
#[test]
fn weighted_objectives_score_bred_children_as_in_full() {
    let set = every_kind(1.0);
    let weights = vec![1.0, 0.5, 0.01, 2.0, 0.1, 1.0];
    let mut bred_fitness =
        WeightedObjectives::new(set.clone(), weights.clone(), building_meshes()).unwrap();
    let mut full_fitness = WeightedObjectives::new(set, weights, building_meshes())
        .unwrap()
        .with_incremental(false);
    assert!(bred_fitness.bred().is_some() && full_fitness.bred().is_none());
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut ops = Operators::<Building>::new(building::LIMITS).unwrap();
    let n = sequences(40);
    let mut population: Vec<Genome<Building>> = (0..n).map(|_| ops.random(30, &mut rng)).collect();
    for _ in 0..4 {
        let from: Vec<u32> = (0..n).map(|_| rng.random_range(0..n as u32)).collect();
        let children: Vec<Genome<Building>> = from
            .iter()
            .map(|&p| bred(&mut ops, &population[p as usize], 30, &mut rng))
            .collect();
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        let bred = Bred {
            children: &children,
            parents: &population,
            from: &from,
        };
        bred_fitness.evaluate_bred(bred, &mut a).unwrap();
        full_fitness.evaluate_bred(bred, &mut b).unwrap();
        assert_eq!(a, b);
        population = children;
    }
    let stats = bred_fitness.bred().unwrap().stats();
    assert!(stats.incremental > stats.full, "{stats:?}");
}

/// A set without projections has nothing to count from parents.
#[test]
fn only_projections_are_counted_from_parents() {
    let set = ObjectiveSet::new(vec![(
        "facets".into(),
        Objective::UniqueNormals(UniqueNormals { tolerance_deg: 1.0 }),
    )])
    .unwrap();
    assert!(BredObjectives::new(&set, &building_meshes()).is_none());
}

/// A unit right triangle in the `xy` plane, its normal `+z`.
fn triangle() -> Mesh {
    Mesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        normals: vec![Vec3::Z; 3],
        indices: vec![0, 1, 2],
    }
}

fn unit(rng: &mut impl Rng) -> Vec3 {
    loop {
        let v = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let len = v.length();
        if (0.1..=1.0).contains(&len) {
            return v / len;
        }
    }
}

/// A triangle facing `normal`, somewhere, of some size.
fn facing(normal: Vec3, rng: &mut impl Rng) -> Instance {
    let turn = Quat::from_rotation_arc(Vec3::Z, normal)
        * Quat::from_rotation_z(rng.random_range(0.0..std::f32::consts::TAU));
    let at = Vec3::new(
        rng.random_range(-9.0..9.0),
        rng.random_range(-9.0..9.0),
        rng.random_range(-9.0..9.0),
    );
    Instance {
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::splat(rng.random_range(0.1..5.0)),
            turn,
            at,
        ),
        mesh: MeshId(0),
    }
}

/// Triangle soups of one of several kinds, facing: anywhere; a few directions, each
/// also turned by a fraction of the tolerance on both sides of 1 (down to the last
/// bits); the axes and a building's few turns; and copies of the same triangles.
fn soup(case: usize, tolerance_deg: f32, rng: &mut impl Rng) -> Vec<Instance> {
    let n = [0, 1, 2, 7, 40, 300, 1500][case % 7];
    let tolerance = tolerance_deg.to_radians();
    let bases: Vec<Vec3> = (0..rng.random_range(1..12)).map(|_| unit(rng)).collect();
    let mut out: Vec<Instance> = (0..n)
        .map(|_| {
            let normal = match case % 3 {
                0 => unit(rng),
                1 => {
                    let base = bases[rng.random_range(0..bases.len())];
                    let factor =
                        [0.0, 0.5, 1.0 - 1e-6, 1.0, 1.0 + 1e-6, 2.0, 3.0][rng.random_range(0..7)];
                    let axis = base
                        .cross(unit(rng))
                        .normalize_or(base.any_orthonormal_vector());
                    Quat::from_axis_angle(axis, tolerance * factor) * base
                }
                _ => {
                    let axis = [Vec3::X, Vec3::Y, Vec3::Z][rng.random_range(0..3)];
                    let turn =
                        [0.0, 0.25, 0.5, std::f32::consts::FRAC_PI_4][rng.random_range(0..4)];
                    let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
                    Quat::from_rotation_y(turn) * axis * sign
                }
            };
            facing(normal, rng)
        })
        .collect();
    if case.is_multiple_of(11) {
        let again: Vec<Instance> = out.iter().rev().copied().collect();
        out.extend(again);
    }
    out
}

/// The distinct normals and their spread equal their definitions to the bit on triangle
/// soups whose normals lie on either side of the tolerance, at tolerances from 0 to 180
/// degrees.
#[test]
fn normals_of_triangle_soups_equal_their_definitions() {
    let mut library = MeshLibrary::new();
    library.register("triangle", triangle()).unwrap();
    let meshes = library.bind_names("Soup", &["triangle"]).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let (mut surface, mut scratch) = (Surface::new(), ObjectiveScratch::default());
    let mut largest = 0;
    for case in 0..sequences(3_000) {
        let tolerance_deg = match case % 9 {
            0 => 0.0,
            1 => 1e-4,
            2 => 180.0,
            3 => 90.0,
            4 => 1.0,
            5 => 5.0,
            _ => rng.random_range(0.0..180.0),
        };
        surface.fill(&soup(case, tolerance_deg, &mut rng), &meshes);
        largest = largest.max(check_normals(&surface, tolerance_deg, &mut scratch));
    }
    assert!(
        largest > 500,
        "some soups have many distinct normals: {largest}"
    );
}
