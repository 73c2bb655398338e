//! The GA's own overhead: one generation (selection and breeding of population 200,
//! 170 children) on the spaceship with a trivial evaluator, single-threaded.
//!
//! Each batch of criterion iterations resumes the same warmed-up run (two generations
//! done, so every buffer is grown) and times that many further generations in one run,
//! so per-generation bookkeeping (best so far, statistics, history) is included and the
//! result's copy at the end is amortized.

use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use generators::{Spaceship, spaceship};
use shapegen::Genome;
use shapegen::optimize::{Budget, FnEvaluator, Ga, GaSettings, Silent};

fn ga_generation(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    let settings = GaSettings {
        population: 200,
        ..GaSettings::paper_spaceship()
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

criterion_group!(benches, ga_generation);
criterion_main!(benches);
