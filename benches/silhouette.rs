//! Silhouette scoring throughput: evaluations per second of populations of 200 random
//! models against the paper's city whale and tree sketch targets (800 x 600), on one CPU
//! thread, on all CPU threads, and on the GPU when there is one; one city of 100
//! buildings on one thread; and single 250-gene trees on one thread, counted in full and
//! instance by instance as an incremental search counts them, with the published meshes
//! and with the built-in ones. On the GPU also 200 bred trees per operator, counted from
//! nothing and from their parents' kept slots.

mod breeding;

use std::hint::black_box;
use std::path::Path;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use generators::{city, tree};
use glam::{Vec3, vec2};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::evaluate::Bred;
use shapegen::genome::Limits;
use shapegen::ops::Operators;
use shapegen::score::retained::RetainedScorer;
use shapegen::score::silhouette::{
    Camera, GpuRetention, GpuSilhouetteScorer, ImageTarget, OrbitCamera, SilhouetteCounts,
    SilhouetteScorer, Weighting,
};
use shapegen::score::{Form, InstanceBatch, Scorer, count_batch};
use shapegen::{BoundMeshes, Genome, Grammar, gpu::GpuContext};

const POPULATION: usize = 200;

struct Scene {
    name: &'static str,
    scorer: SilhouetteScorer,
    batch: InstanceBatch,
}

fn target(scene: &str, file: &str, camera: OrbitCamera) -> ImageTarget {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/paper")
        .join(scene)
        .join(file);
    let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ImageTarget::new(
        file.into(),
        &image,
        Camera::Orbit(camera),
        Weighting::mask(1.0, -1.0),
    )
    .unwrap()
}

fn population<G: Grammar>(limits: Limits, initial_len: u32) -> InstanceBatch {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut ops = Operators::<G>::new(limits).unwrap();
    let mut batch = InstanceBatch::new();
    for _ in 0..POPULATION {
        batch.push_genome(&ops.random(initial_len, &mut rng));
    }
    batch
}

const SMOOTH: Form = Form::Smooth {
    good: 1.0,
    bad: 1.0,
};

fn city_whale() -> Scene {
    let camera = OrbitCamera {
        phi: -3.05161,
        theta: 0.0479887,
        radius: 12.4346,
        lookat: Vec3::new(1.82669, 4.65407, -0.620025),
        fov_degrees: 60.0,
        near: 0.1,
        far: 100.0,
    };
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    let target = target("city_whale", "city_target_whale.png", camera);
    Scene {
        name: "city_whale",
        scorer: SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap(),
        batch: population::<city::City>(city::PAPER_LIMITS, 50),
    }
}

/// The tree sketch's camera.
const TREE_CAMERA: OrbitCamera = OrbitCamera {
    phi: -std::f32::consts::FRAC_PI_2,
    theta: 0.0,
    radius: 9.4716,
    lookat: Vec3::new(-0.680994, 3.2558, 0.0),
    fov_degrees: 60.0,
    near: 0.1,
    far: 100.0,
};

fn tree_sketch1() -> Scene {
    let meshes = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let target = target("tree_sketch1", "tree_target_sketch1.png", TREE_CAMERA);
    Scene {
        name: "tree_sketch1",
        scorer: SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap(),
        batch: population::<tree::Tree>(tree::PAPER_LIMITS, 250),
    }
}

fn populations(c: &mut Criterion) {
    let gpu = match GpuContext::new() {
        Ok(gpu) => {
            eprintln!("GPU benchmarks on {}", gpu.describe());
            Some(gpu)
        }
        Err(err) => {
            eprintln!("no GPU benchmarks: {err}");
            None
        }
    };
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for scene in [city_whale(), tree_sketch1()] {
        let mut group = c.benchmark_group(format!("silhouette/{}", scene.name));
        group.throughput(Throughput::Elements(POPULATION as u64));
        group.sample_size(10);
        let mut out = vec![SilhouetteCounts::default(); POPULATION];
        group.bench_function(BenchmarkId::new("cpu", "1 thread"), |b| {
            b.iter(|| one.install(|| count_batch(&scene.scorer, &scene.batch, &mut out)))
        });
        let threads = rayon::current_num_threads();
        group.bench_function(BenchmarkId::new("cpu", format!("{threads} threads")), |b| {
            b.iter(|| count_batch(&scene.scorer, &scene.batch, &mut out))
        });
        if let Some(gpu) = &gpu {
            match GpuSilhouetteScorer::new(gpu, &scene.scorer) {
                Ok(scorer) => {
                    group.bench_function(BenchmarkId::new("gpu", gpu.info.name.as_str()), |b| {
                        b.iter(|| scorer.count_batch(&scene.batch, &mut out).unwrap())
                    });
                }
                Err(err) => eprintln!("{}: no GPU benchmark: {err}", scene.name),
            }
        }
        group.finish();
    }
}

/// One city with a building on every lot, as the paper's skyline scene sees it.
fn hundred_buildings(c: &mut Criterion) {
    let scene = city_whale();
    let mut g = Genome::<city::City>::with_root(city::Start {}).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for k in 0..100 {
        let lot = g.attach_at(0, "lots", k, city::Lot {}).unwrap();
        let building = city::Building {
            footprint: vec2(0.44, 0.44)
                + 1.54
                    * vec2(
                        rand::RngExt::random(&mut rng),
                        rand::RngExt::random(&mut rng),
                    ),
            height: 0.36 + 9.64 * rand::RngExt::random::<f32>(&mut rng),
            floor_height: 0.3,
            rotation: std::f32::consts::PI * rand::RngExt::random::<f32>(&mut rng),
        };
        g.attach(lot, "building", building).unwrap();
    }
    let mut model = Vec::new();
    g.derive_append(&mut model);
    let mut scratch = scene.scorer.scratch();
    c.bench_function("silhouette/city_whale/100 buildings, 1 model", |b| {
        b.iter(|| scene.scorer.count(&model, &mut scratch))
    });
}

/// The tree's meshes as the paper's scene file (`scenes/paper/tree_sketch1.toml`) loads
/// them: the built-in library with the published trunk and leaf, normalized as the
/// original normalizes them.
fn published_tree_meshes() -> BoundMeshes {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper/tree_sketch1");
    let mut library = generators::default_meshes();
    for (name, file) in [("trunk", "trunk.obj"), ("leaf", "leaf.obj")] {
        library.register_obj(name, dir.join(file)).unwrap();
    }
    library.bind(tree::Tree::GRAPH).unwrap()
}

/// A random tree of exactly `genes` genes under the paper scene's limits.
fn random_tree(genes: u32, seed: u64) -> Genome<tree::Tree> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut ops = Operators::<tree::Tree>::new(tree::PAPER_LIMITS).unwrap();
    let mut genome = ops.random(4, &mut rng);
    ops.grow_to(&mut genome, genes, &mut rng);
    assert_eq!(
        genome.len(),
        genes as usize,
        "seed {seed}: the tree stopped growing"
    );
    genome
}

/// One full silhouette evaluation (`count`, then `fitness`) of single 250-gene trees
/// against the tree sketch, on the calling thread, and the same counted instance by
/// instance into per-pixel counts (`count_retained`, as an incremental search counts):
/// with the published meshes (the paper scene's) and with the built-in ones (the
/// population rows'). Prints each tree's instances, triangles and counts.
fn tree_single(c: &mut Criterion) {
    const GENES: u32 = 250;
    let target = target("tree_sketch1", "tree_target_sketch1.png", TREE_CAMERA);
    let built_in = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let mut group = c.benchmark_group("silhouette/tree_single");
    for (meshes_name, meshes) in [
        ("published meshes", published_tree_meshes()),
        ("built-in meshes", built_in),
    ] {
        let scorer = SilhouetteScorer::new(vec![target.clone()], &meshes, SMOOTH).unwrap();
        let per_mesh: Vec<usize> = meshes.iter().map(|(_, _, m)| m.triangle_count()).collect();
        for seed in 1..=3 {
            let mut model = Vec::new();
            random_tree(GENES, seed).derive_append(&mut model);
            let triangles: usize = model.iter().map(|i| per_mesh[i.mesh.0 as usize]).sum();
            let mut scratch = scorer.scratch();
            let counts = scorer.count(&model, &mut scratch);
            let t = counts.targets()[0];
            eprintln!(
                "tree_single/{meshes_name}/seed {seed}: {GENES} genes, {} instances, \
                 {triangles} triangles; covered {}, on target {}, off target {}, fitness {:.4}",
                model.len(),
                t.covered,
                t.on_target,
                t.off_target,
                scorer.fitness(&counts)
            );
            group.bench_function(
                BenchmarkId::new(meshes_name, format!("{GENES} genes seed {seed}")),
                |b| {
                    b.iter(|| {
                        let counts = scorer.count(black_box(&model), &mut scratch);
                        black_box(scorer.fitness(&counts))
                    })
                },
            );
            // As an incremental search counts instances: each alone into a fresh
            // coverage, then into per-pixel instance counts.
            group.bench_function(
                BenchmarkId::new(meshes_name, format!("{GENES} genes seed {seed}, retained")),
                |b| {
                    b.iter(|| {
                        let state = scorer
                            .count_retained(black_box(&model), &mut scratch)
                            .unwrap();
                        black_box(scorer.fitness(&scorer.state_counts(&state)))
                    })
                },
            );
        }
    }
    group.finish();
}

/// Bred trees on the GPU, per operator: 200 children of 200 random 250-gene trees, all
/// by one operator, counted from nothing (`count_batch`) and from their parents' kept
/// slots (`GpuRetention::count_bred`, the parents' slots counted once before timing).
fn gpu_bred(c: &mut Criterion) {
    let Ok(gpu) = GpuContext::new() else {
        eprintln!("no GPU: no benchmark of bred children on the GPU");
        return;
    };
    let scene = tree_sketch1();
    let Ok(scorer) = GpuSilhouetteScorer::new(&gpu, &scene.scorer) else {
        return;
    };
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut ops = Operators::<tree::Tree>::new(tree::PAPER_LIMITS).unwrap();
    let parents: Vec<Genome<tree::Tree>> =
        (0..POPULATION).map(|_| ops.random(250, &mut rng)).collect();
    let from: Vec<u32> = (0..POPULATION as u32).collect();
    let mut group = c.benchmark_group("silhouette/tree_sketch1/bred 200");
    group.throughput(Throughput::Elements(POPULATION as u64));
    group.sample_size(10);
    for op in breeding::Op::ALL {
        let children: Vec<Genome<tree::Tree>> = parents
            .iter()
            .map(|parent| op.child(&mut ops, parent, 250, &mut rng))
            .collect();
        let mut batch = InstanceBatch::new();
        for child in &children {
            batch.push_genome(child);
        }
        let bred = Bred {
            children: &children,
            parents: &parents,
            from: &from,
        };
        let mut retention = GpuRetention::new(&scorer).unwrap();
        let mut kept = vec![SilhouetteCounts::default(); POPULATION];
        retention
            .count_bred(&scorer, bred, &batch, &mut kept)
            .unwrap();
        let mut full = vec![SilhouetteCounts::default(); POPULATION];
        scorer.count_batch(&batch, &mut full).unwrap();
        assert_eq!(kept, full, "the kept slots count as from nothing");
        group.bench_function(BenchmarkId::new("gpu, from nothing", op.name()), |b| {
            b.iter(|| scorer.count_batch(&batch, &mut full).unwrap())
        });
        group.bench_function(BenchmarkId::new("gpu, from parents", op.name()), |b| {
            b.iter(|| {
                retention
                    .count_bred(&scorer, bred, &batch, &mut kept)
                    .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    populations,
    hundred_buildings,
    tree_single,
    gpu_bred
);
criterion_main!(benches);
