//! The GA's cost: one generation's own overhead (selection and breeding of population
//! 200, 170 children) on the spaceship with a trivial evaluator, single-threaded; and a
//! whole search, the paper's spaceship scene at population 200 for 50 generations with
//! the scene's real scorer on the CPU, on all threads.
//!
//! For the overhead, each batch of criterion iterations resumes the same warmed-up run (two generations
//! done, so every buffer is grown) and times that many further generations in one run,
//! so per-generation bookkeeping (best so far, statistics, history) is included and the
//! result's copy at the end is amortized.

use std::path::Path;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use generators::{Spaceship, spaceship};
use shapegen::Genome;
use shapegen::optimize::{Budget, FnEvaluator, Ga, GaSettings, Silent};
use shapegen::optimize::{Optimizer, Settings};
use shapegen::scene::{BackendChoice, Scene, SceneEvaluator, SceneScorer};

fn ga_generation(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    let settings = GaSettings {
        population: 200,
        ..spaceship::paper_ga()
    };
    // Trivial fitness that keeps lengths near the initial length.
    let fitness = |g: &Genome<Spaceship>| -(g.len() as f64 - 50.0).abs();
    let mut warm = Ga::<Spaceship>::new(settings, spaceship::PAPER_LIMITS, 1).expect("valid");
    pool.install(|| {
        warm.run(
            &mut FnEvaluator(fitness),
            &Budget::generations(2),
            &mut Silent,
        )
    })
    .expect("the trivial evaluator never fails");
    let state = warm.checkpoint();
    c.bench_function("optimize/ga_generation/spaceship/200", |b| {
        b.iter_custom(|iters| {
            let mut ga = Ga::resume(state.clone()).expect("a fresh checkpoint resumes");
            pool.install(|| {
                // Grow this copy's buffers, untimed.
                ga.run(
                    &mut FnEvaluator(fitness),
                    &Budget::generations(4),
                    &mut Silent,
                )
                .expect("evaluates");
                let t0 = Instant::now();
                ga.run(
                    &mut FnEvaluator(fitness),
                    &Budget::generations(4 + iters),
                    &mut Silent,
                )
                .expect("evaluates");
                t0.elapsed()
            })
        })
    });
}

/// The whole search of the paper's spaceship scene, population 200 x 50 generations (the
/// paper's other GA settings), scoring on the CPU with every thread; one iteration is one
/// search from a fresh random population, seed 1. The scene and its voxelized target are
/// loaded once, outside the timing.
fn ga_search(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper/spaceship_volume.toml");
    let scene = Scene::load(&path).expect("the paper's spaceship scene loads");
    let scorer = SceneScorer::new::<Spaceship>(&scene).expect("the paper's scene scores");
    let backend = scorer
        .on(BackendChoice::Cpu, None)
        .expect("the CPU backend is always there");
    let settings = GaSettings {
        population: 200,
        generations: 50,
        ..spaceship::paper_ga()
    };
    let mut group = c.benchmark_group("optimize/ga_search");
    group.sample_size(10);
    group.bench_function("spaceship_volume/200x50", |b| {
        b.iter(|| {
            let mut ga = Ga::<Spaceship>::new(settings, scene.limits, 1).expect("valid settings");
            let mut evaluator = SceneEvaluator::new(&backend);
            ga.run(&mut evaluator, &settings.budget(), &mut Silent)
                .expect("the scene evaluates")
                .best_fitness
        })
    });
    group.finish();
}

criterion_group!(benches, ga_generation, ga_search);
criterion_main!(benches);
