//! Volume scoring throughput on the paper's spaceship scene: evaluations per second for
//! a population of 200 random spaceship genomes (paper limits, initial length 50),
//! counted single-threaded, on all threads, and on the GPU when one is found.

use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use generators::spaceship::{PAPER_LIMITS, Spaceship};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::Grammar;
use shapegen::ops::Operators;
use shapegen_runtime::Mesh;
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::prelude::Vec3;
use shapegen_runtime::score::volume::{
    Fill, GpuVolumeScorer, Grid, VolumeCounts, VolumeScorer, VolumeTarget,
};
use shapegen_runtime::score::{Form, InstanceBatch, count_batch};

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

fn volume(c: &mut Criterion) {
    let scorer = paper_scorer();
    let batch = population();
    let mut out = vec![VolumeCounts::default(); batch.len()];
    let mut group = c.benchmark_group("volume/spaceship");
    group.throughput(Throughput::Elements(POPULATION as u64));
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    group.bench_function("cpu-1-thread", |b| {
        b.iter(|| single.install(|| count_batch(&scorer, &batch, &mut out)))
    });
    group.bench_function(
        format!("cpu-{}-threads", rayon::current_num_threads()),
        |b| b.iter(|| count_batch(&scorer, &batch, &mut out)),
    );
    match GpuContext::new() {
        Ok(gpu) => {
            let on_gpu =
                GpuVolumeScorer::new(&gpu, &scorer).expect("the spaceship scene runs on the GPU");
            let mut cpu = vec![VolumeCounts::default(); batch.len()];
            count_batch(&scorer, &batch, &mut cpu);
            on_gpu
                .count_batch(&batch, &mut out)
                .expect("the GPU counts");
            assert_eq!(cpu, out, "the GPU counts what the CPU counts");
            eprintln!("volume/spaceship/gpu runs on {}", gpu.describe());
            group.bench_function("gpu", |b| {
                b.iter(|| {
                    on_gpu
                        .count_batch(&batch, &mut out)
                        .expect("the GPU counts")
                })
            });
        }
        Err(err) => eprintln!("no GPU ({err}): volume/spaceship/gpu not measured"),
    }
    group.finish();
}

criterion_group!(benches, volume);
criterion_main!(benches);
