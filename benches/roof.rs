//! Roofs through the building scene's objectives (`scenes/building.toml`: its top and
//! front projections and distinct normals), on one thread: 64 random building programs
//! of 150 genes measured as they derive (instances of boxes and spheres only), and the
//! same models with a hip roof on the top of every box (instances of the roof pieces,
//! `Scope::roof`). The ratio of the two rows of one run is what the roofs cost. The
//! instance-only row runs the scorers' unchanged instance path.

use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use generators::Building;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::Grammar;
use shapegen::ops::Operators;
use shapegen::registry::Registry;
use shapegen::scene::{Overrides, Scene};
use shapegen_runtime::geometry::{MeshId, RoofMeshes, RoofPiece, RoofShape};
use shapegen_runtime::prelude::{Affine3A, Vec3};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::{CUBE, Instance, Scope};

/// Genes of each program, as in the objective bench's building rows.
const GENES: u32 = 150;
/// Models per row.
const MODELS: usize = 64;

/// The roof pieces, bound after the building's cube and sphere.
const PIECES: RoofMeshes = RoofMeshes {
    gable: MeshId(2),
    shed: MeshId(3),
    pyramid: MeshId(4),
    hip_end: MeshId(5),
};

/// Appends a hip roof on the top of every box among `instances`.
fn add_roofs(instances: &mut Vec<Instance>, from: usize) {
    for k in from..instances.len() {
        let i = instances[k];
        if i.mesh != CUBE {
            continue;
        }
        let size = Vec3::new(
            i.transform.matrix3.x_axis.length(),
            i.transform.matrix3.y_axis.length(),
            i.transform.matrix3.z_axis.length(),
        );
        if size.min_element() <= 1e-3 {
            continue;
        }
        let frame = Affine3A {
            matrix3: i.transform.matrix3 * glam::Mat3A::from_diagonal(size.recip()),
            translation: i.transform.translation,
        };
        Scope::new(frame, size)
            .roof(RoofShape::Hip { pitch: 0.5 }, 0.2, &PIECES, instances)
            .expect("a valid pitch and overhang");
    }
}

fn roofs(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/building.toml");
    let scene = Scene::open(&path, &Registry::published(), &Overrides::default())
        .expect("the building scene loads");
    let mut library = scene.meshes.clone();
    for piece in RoofPiece::ALL {
        library
            .register(piece.name(), piece.mesh())
            .expect("the roof pieces are valid");
    }
    let mut names: Vec<&str> = Building::GRAPH.meshes.to_vec();
    names.extend(RoofPiece::ALL.map(RoofPiece::name));
    let meshes = library
        .bind_names("Building", &names)
        .expect("the meshes bind");
    let set = &scene.objectives.as_ref().expect("it has objectives").set;
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let mut ops = Operators::<Building>::new(scene.limits).expect("the scene's limits are valid");
    let programs: Vec<_> = (0..MODELS).map(|_| ops.random(GENES, &mut rng)).collect();
    let mut plain = InstanceBatch::new();
    let mut roofed = InstanceBatch::new();
    for genome in &programs {
        plain.push_genome(genome);
        roofed.push_with(|out| {
            let from = out.len();
            genome.derive_append(out);
            add_roofs(out, from);
        });
    }
    eprintln!(
        "roof/building-objectives: {} instances without roofs, {} with",
        plain.instances().len(),
        roofed.instances().len()
    );
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let mut out = vec![0.0; MODELS * set.len()];
    let mut group = c.benchmark_group("roof/building-objectives");
    group.throughput(Throughput::Elements(MODELS as u64));
    group.bench_function("instances only", |b| {
        b.iter(|| single.install(|| set.measure_batch(&plain, &meshes, &mut out)))
    });
    group.bench_function("with hip roofs", |b| {
        b.iter(|| single.install(|| set.measure_batch(&roofed, &meshes, &mut out)))
    });
    group.finish();
}

criterion_group!(benches, roofs);
criterion_main!(benches);
