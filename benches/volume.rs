//! Volume scoring throughput: evaluations per second for a population of 200 random
//! models, counted on the CPU threads and on the GPU when one is found. On the paper's
//! spaceship scene (paper limits, initial length 50; box instances only), also
//! single-threaded; on lot buildings on an L-shaped lot (initial length 30), whose
//! generated facets the GPU path rasterises on the CPU threads before counting on the
//! device.

use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use generators::lot_building::{self, LotBuilding};
use generators::spaceship::{PAPER_LIMITS, Spaceship};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::Grammar;
use shapegen::ops::Operators;
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::prelude::Vec3;
use shapegen_runtime::score::volume::{
    Fill, GpuVolumeScorer, Grid, VolumeCounts, VolumeScorer, VolumeTarget,
};
use shapegen_runtime::score::{Form, InstanceBatch, count_batch};
use shapegen_runtime::{Mesh, Site};

const POPULATION: usize = 200;

/// The paper's spaceship scene: grid, target, smooth form good 2 bad 15.
fn paper_scorer() -> VolumeScorer {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper/spaceship_volume");
    let mesh = Mesh::from_obj(dir.join("spaceship_target.obj")).expect("the paper's target loads");
    let grid = Grid::new(
        Vec3::new(-5.0, -5.0, -2.0),
        Vec3::new(5.0, 5.0, 18.0),
        [100, 200, 100],
    )
    .expect("the paper's grid is valid");
    let target = VolumeTarget {
        name: "spaceship".into(),
        mesh,
        inside: 1.0,
        outside: -1.0,
        fill: Fill::Parity,
    };
    let meshes = generators::default_meshes()
        .bind(Spaceship::GRAPH)
        .expect("spaceship meshes bind");
    VolumeScorer::new(
        grid,
        &[target],
        &meshes,
        Form::Smooth {
            good: 2.0,
            bad: 15.0,
        },
    )
    .expect("the paper's scene scores")
}

/// A population of random spaceship genomes, derived into one batch.
fn population() -> InstanceBatch {
    let mut ops = Operators::<Spaceship>::new(PAPER_LIMITS).expect("paper limits are valid");
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut batch = InstanceBatch::new();
    for _ in 0..POPULATION {
        batch.push_genome(&ops.random(50, &mut rng));
    }
    batch
}

/// 200 random lot buildings on an L-shaped lot, and a scorer whose grid cuts them.
fn lot_buildings() -> (VolumeScorer, InstanceBatch) {
    let mut ops = Operators::<LotBuilding>::new(lot_building::LIMITS).expect("limits are valid");
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut batch = InstanceBatch::new().on_site(Site::with_lot(lot_building::L_LOT.clone()));
    for _ in 0..POPULATION {
        batch.push_genome(&ops.random(30, &mut rng));
    }
    let grid = Grid::new(
        Vec3::new(-9.0, 0.0, -7.0),
        Vec3::new(9.0, 12.0, 7.0),
        [90, 60, 70],
    )
    .expect("the grid is valid");
    let mut mass = Mesh::unit_cube();
    for p in &mut mass.positions {
        *p = *p * Vec3::new(12.0, 8.0, 10.0) + Vec3::new(-2.0, 4.0, 0.0);
    }
    let target = VolumeTarget {
        name: "mass".into(),
        mesh: mass,
        inside: 1.0,
        outside: -1.0,
        fill: Fill::Parity,
    };
    let meshes = generators::default_meshes()
        .bind(LotBuilding::GRAPH)
        .expect("lot building meshes bind");
    let scorer = VolumeScorer::new(grid, &[target], &meshes, Form::Weighted { overlap: 0.5 })
        .expect("the scene scores");
    (scorer, batch)
}

fn volume(c: &mut Criterion) {
    let gpu = GpuContext::new();
    if let Err(err) = &gpu {
        eprintln!("no GPU ({err}): volume/*/gpu not measured");
    }
    let gpu = gpu.as_ref().ok();
    measure(
        c,
        "volume/spaceship",
        &paper_scorer(),
        &population(),
        true,
        gpu,
    );
    let (scorer, batch) = lot_buildings();
    measure(c, "volume/lot_building", &scorer, &batch, false, gpu);
}

/// Times counting `batch` with `scorer` on all threads (and on one with `single`), and on
/// `gpu` when given, after checking that it counts what the CPU counts.
fn measure(
    c: &mut Criterion,
    name: &str,
    scorer: &VolumeScorer,
    batch: &InstanceBatch,
    single: bool,
    gpu: Option<&GpuContext>,
) {
    let mut out = vec![VolumeCounts::default(); batch.len()];
    let mut group = c.benchmark_group(name);
    group.throughput(Throughput::Elements(batch.len() as u64));
    if single {
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a thread pool");
        group.bench_function("cpu-1-thread", |b| {
            b.iter(|| one.install(|| count_batch(scorer, batch, &mut out)))
        });
    }
    group.bench_function(
        format!("cpu-{}-threads", rayon::current_num_threads()),
        |b| b.iter(|| count_batch(scorer, batch, &mut out)),
    );
    if let Some(gpu) = gpu {
        let on_gpu = GpuVolumeScorer::new(gpu, scorer).expect("the scene runs on the GPU");
        let mut cpu = vec![VolumeCounts::default(); batch.len()];
        count_batch(scorer, batch, &mut cpu);
        on_gpu.count_batch(batch, &mut out).expect("the GPU counts");
        assert_eq!(cpu, out, "the GPU counts what the CPU counts");
        eprintln!("{name}/gpu runs on {}", gpu.describe());
        group.bench_function("gpu", |b| {
            b.iter(|| on_gpu.count_batch(batch, &mut out).expect("the GPU counts"))
        });
    }
    group.finish();
}

criterion_group!(benches, volume);
criterion_main!(benches);
