//! Geometric objective throughput: a population of 300 building-sized models (50 to 300
//! boxes each, some turned, and a low-poly dome) measured against all six objective kinds
//! (128 x 128 projection images), on one thread and on all threads; and each objective
//! alone on one thread.
//!
//! Then the building scene's (`scenes/building.toml`) generator, on one thread: the
//! distinct-normals objectives alone on 64 random building programs of [`GENES`] genes;
//! and bred children, per operator, measured against the scene's objectives (its top and
//! front projections and distinct normals): each row measures 64 children, each one
//! operator applied to one of those programs (the crossover's partner another random
//! genome), with the scene's operators.
//! `full` measures them as the first generation is ([`ObjectiveSet::measure_batch`]),
//! `incremental` as the multi-objective GA does, the projections from the parents' kept
//! states ([`BredObjectives::measure_bred`], the parents' states counted before the
//! timing); both start from the children's derived instances.

mod breeding;

use std::f32::consts::{FRAC_PI_4, PI, TAU};
use std::path::Path;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use generators::Building;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen::evaluate::Bred;
use shapegen::ops::{OperatorVariant, Operators};
use shapegen::registry::Registry;
use shapegen::scene::{Overrides, Scene};
use shapegen::{Genome, Grammar};
use shapegen_runtime::geometry::{BoundMeshes, Mesh, MeshId, MeshLibrary};
use shapegen_runtime::prelude::{Affine3A, Quat, Vec2, Vec3};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{
    BredObjectives, FootprintExcess, Height, NormalSpread, Objective, ObjectiveSet,
    ProjectionMatch, UniqueNormals, View,
};
use shapegen_runtime::{CUBE, Instance};

const POPULATION: usize = 300;
const DOME: MeshId = MeshId(1);
const IMAGE: u32 = 128;

/// A UV sphere of radius 0.5 with 8 segments and 6 rings (80 triangles).
fn sphere() -> Mesh {
    let (segments, rings) = (8u32, 6u32);
    let mut mesh = Mesh::default();
    for r in 0..=rings {
        let (sin_t, cos_t) = (PI * r as f32 / rings as f32).sin_cos();
        for s in 0..segments {
            let (sin_p, cos_p) = (TAU * s as f32 / segments as f32).sin_cos();
            let n = Vec3::new(sin_t * cos_p, cos_t, sin_t * sin_p);
            mesh.positions.push(n * 0.5);
            mesh.normals.push(n);
        }
    }
    let at = |r: u32, s: u32| r * segments + s % segments;
    for r in 0..rings {
        for s in 0..segments {
            let (a, b, c, d) = (at(r, s), at(r, s + 1), at(r + 1, s), at(r + 1, s + 1));
            if r > 0 {
                mesh.indices.extend([a, b, c]);
            }
            if r + 1 < rings {
                mesh.indices.extend([b, d, c]);
            }
        }
    }
    mesh
}

fn meshes() -> BoundMeshes {
    let mut library = MeshLibrary::new();
    library
        .register("dome", sphere())
        .expect("the sphere is valid");
    library
        .bind_names("Building", &["cube", "dome"])
        .expect("the meshes bind")
}

/// Buildings: a few wings of stacked floors with window boxes on their fronts, a
/// quarter of the wings turned 45 degrees, and a dome on top.
fn population() -> InstanceBatch {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut batch = InstanceBatch::new();
    for _ in 0..POPULATION {
        let boxes = rng.random_range(50..=300usize);
        batch.push_with(|out| {
            let start = out.len();
            let mut top = 0.0f32;
            while out.len() - start < boxes {
                let size = Vec3::new(rng.random_range(2.0..6.0), 1.0, rng.random_range(2.0..6.0));
                let at = Vec3::new(
                    rng.random_range(-4.0..4.0),
                    0.0,
                    rng.random_range(-4.0..4.0),
                );
                let turn = if rng.random_bool(0.25) {
                    FRAC_PI_4
                } else {
                    0.0
                };
                let frame = Affine3A::from_rotation_translation(Quat::from_rotation_y(turn), at);
                let floors = rng.random_range(1..8);
                for f in 0..floors {
                    let y = f as f32 + 0.5;
                    out.push(Instance {
                        transform: frame
                            * Affine3A::from_scale_rotation_translation(
                                size,
                                Quat::IDENTITY,
                                Vec3::Y * y,
                            ),
                        mesh: CUBE,
                    });
                    let windows = (size.x as usize).max(1);
                    for w in 0..windows {
                        let x = -size.x / 2.0 + (w as f32 + 0.5) * size.x / windows as f32;
                        let centre = Vec3::new(x, y, size.z / 2.0 + 0.05);
                        out.push(Instance {
                            transform: frame
                                * Affine3A::from_scale_rotation_translation(
                                    Vec3::new(0.5, 0.6, 0.1),
                                    Quat::IDENTITY,
                                    centre,
                                ),
                            mesh: CUBE,
                        });
                    }
                }
                top = top.max(floors as f32);
            }
            out.truncate(start + boxes);
            out.push(Instance {
                transform: Affine3A::from_scale_rotation_translation(
                    Vec3::splat(3.0),
                    Quat::IDENTITY,
                    Vec3::Y * top,
                ),
                mesh: DOME,
            });
        });
    }
    batch
}

/// All six objective kinds, the projections against a disc seen from above and a
/// stepped skyline seen from the front.
fn objectives() -> Vec<(String, Objective)> {
    let pixel = |i: u32| ((i % IMAGE) as f32 + 0.5, (i / IMAGE) as f32 + 0.5);
    let half = IMAGE as f32 / 2.0;
    let disc: Vec<bool> = (0..IMAGE * IMAGE)
        .map(|i| {
            let (x, y) = pixel(i);
            (x - half).powi(2) + (y - half).powi(2) < (0.6 * half).powi(2)
        })
        .collect();
    let skyline: Vec<bool> = (0..IMAGE * IMAGE)
        .map(|i| {
            let (x, y) = pixel(i);
            y > IMAGE as f32 * (0.3 + 0.4 * (x / IMAGE as f32 * 4.0).floor() / 4.0)
        })
        .collect();
    let top = ProjectionMatch::new(
        View::Top,
        Vec2::splat(-8.0),
        Vec2::splat(8.0),
        IMAGE,
        IMAGE,
        &disc,
    )
    .expect("the top target is valid");
    let front = ProjectionMatch::new(
        View::Front,
        Vec2::new(-8.0, 0.0),
        Vec2::new(8.0, 12.0),
        IMAGE,
        IMAGE,
        &skyline,
    )
    .expect("the front target is valid");
    vec![
        ("height".into(), Objective::Height(Height { target: 6.0 })),
        (
            "facets".into(),
            Objective::UniqueNormals(UniqueNormals { tolerance_deg: 5.0 }),
        ),
        (
            "spread".into(),
            Objective::NormalSpread(NormalSpread { tolerance_deg: 5.0 }),
        ),
        (
            "footprint".into(),
            Objective::FootprintExcess(FootprintExcess {
                min: Vec2::splat(-6.0),
                max: Vec2::splat(6.0),
            }),
        ),
        ("top".into(), Objective::from(top)),
        ("front".into(), Objective::from(front)),
    ]
}

fn objective(c: &mut Criterion) {
    let meshes = meshes();
    let batch = population();
    let all = ObjectiveSet::new(objectives()).expect("the objectives are valid");
    let mut out = vec![0.0; batch.len() * all.len()];
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");

    let mut group = c.benchmark_group("objective/buildings");
    group.throughput(Throughput::Elements(POPULATION as u64));
    group.bench_function("all-six-1-thread", |b| {
        b.iter(|| single.install(|| all.measure_batch(&batch, &meshes, &mut out)))
    });
    group.bench_function(
        format!("all-six-{}-threads", rayon::current_num_threads()),
        |b| b.iter(|| all.measure_batch(&batch, &meshes, &mut out)),
    );
    for entry in objectives() {
        let name = format!("{}-alone-1-thread", entry.1.name());
        let alone = ObjectiveSet::new(vec![entry]).expect("the objective is valid");
        let mut out = vec![0.0; batch.len()];
        group.bench_function(name, |b| {
            b.iter(|| single.install(|| alone.measure_batch(&batch, &meshes, &mut out)))
        });
    }
    group.finish();
}

/// Genes of the building programs of the rows below: the size the building scene's
/// search grows its models to (its front after 60 generations holds models of 49 to 288
/// genes).
const GENES: u32 = 150;

/// Models per row.
const MODELS: usize = 64;

/// The building scene, its meshes and the operators of its GA.
fn building_scene() -> (Scene, BoundMeshes, OperatorVariant) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/building.toml");
    let scene = Scene::open(&path, &Registry::published(), &Overrides::default())
        .expect("the building scene loads");
    let meshes = scene.meshes.bind(Building::GRAPH).expect("its meshes bind");
    let operators = scene
        .multi_settings()
        .expect("it is a GA scene")
        .ga
        .operators;
    (scene, meshes, operators)
}

/// [`MODELS`] random building programs of [`GENES`] genes, and the operators that made
/// them, ready to breed.
fn building_programs(
    scene: &Scene,
    operators: OperatorVariant,
) -> (Vec<Genome<Building>>, Operators<Building>, ChaCha8Rng) {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let mut ops = Operators::<Building>::new(scene.limits)
        .expect("the scene's limits are valid")
        .with_variant(operators);
    let programs = (0..MODELS).map(|_| ops.random(GENES, &mut rng)).collect();
    (programs, ops, rng)
}

fn batch_of(genomes: &[Genome<Building>]) -> InstanceBatch {
    let mut batch = InstanceBatch::new();
    for genome in genomes {
        batch.push_genome(genome);
    }
    batch
}

fn one_thread() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool")
}

/// The distinct-normals objectives on building programs, whose turned and twisted parts
/// and spheres have thousands of distinct normals (unlike the synthetic buildings
/// above), on one thread.
fn building_normals(c: &mut Criterion) {
    let (scene, meshes, operators) = building_scene();
    let (programs, _, _) = building_programs(&scene, operators);
    let batch = batch_of(&programs);
    let single = one_thread();
    let mut group = c.benchmark_group("objective/building-models");
    group.throughput(Throughput::Elements(MODELS as u64));
    for tolerance_deg in [1.0, 5.0] {
        for objective in [
            Objective::UniqueNormals(UniqueNormals { tolerance_deg }),
            Objective::NormalSpread(NormalSpread { tolerance_deg }),
        ] {
            let name = format!("{}-{tolerance_deg}-degrees", objective.name());
            let alone =
                ObjectiveSet::new(vec![(name.clone(), objective)]).expect("the objective is valid");
            let mut out = vec![0.0; MODELS];
            group.bench_function(name, |b| {
                b.iter(|| single.install(|| alone.measure_batch(&batch, &meshes, &mut out)))
            });
        }
    }
    group.finish();
}

/// Bred children of the building scene, measured in full and from their parents.
fn bred_children(c: &mut Criterion) {
    let (scene, meshes, operators) = building_scene();
    let set = &scene.objectives.as_ref().expect("it has objectives").set;
    let single = one_thread();
    let mut group = c.benchmark_group("objective/building-children");
    group.throughput(Throughput::Elements(MODELS as u64));
    for op in breeding::Op::ALL {
        let (parents, mut ops, mut rng) = building_programs(&scene, operators);
        let children: Vec<_> = parents
            .iter()
            .map(|p| op.child(&mut ops, p, GENES, &mut rng))
            .collect();
        let batch = batch_of(&children);
        let from: Vec<u32> = (0..MODELS as u32).collect();
        let mut out = vec![0.0; MODELS * set.len()];
        group.bench_function(BenchmarkId::new("full", op.name()), |b| {
            b.iter(|| single.install(|| set.measure_batch(&batch, &meshes, &mut out)))
        });
        let lineage = Bred {
            children: &children,
            parents: &parents,
            from: &from,
        };
        let mut bred = BredObjectives::new(set, &meshes).expect("the scene has projections");
        single.install(|| bred.measure_bred(lineage, &batch, &mut out));
        group.bench_function(BenchmarkId::new("incremental", op.name()), |b| {
            b.iter(|| single.install(|| bred.measure_bred(lineage, &batch, &mut out)))
        });
        let stats = bred.stats();
        eprintln!(
            "objective/building-children/{}: {:.1} % of the children's instances changed, \
             {} of {} children counted from their parents",
            op.name(),
            100.0 * stats.changed_instances as f64 / stats.child_instances.max(1) as f64,
            stats.incremental,
            stats.incremental + stats.full
        );
    }
    group.finish();
}

criterion_group!(benches, objective, building_normals, bred_children);
criterion_main!(benches);
