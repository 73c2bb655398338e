//! What the GA's and the hybrid's tests share: the small city GA they run, comparing two
//! runs, a thread pool of a given size, and an evaluator that poisons fitness.

use generators::{City, city};
use shapegen_runtime::Genome;
use shapegen_runtime::derive::Grammar;
use shapegen_runtime::optimize::{EvaluateError, Evaluator, GaSettings, RunResult};

use super::evaluators::{Skyline, timeless};

/// The paper's city settings (the original's operators and breeding), smaller.
pub fn small_ga() -> GaSettings {
    GaSettings {
        population: 40,
        elitism: 8,
        initial_length: 30,
        generations: 15,
        ..city::paper_ga()
    }
}

/// Asserts that two runs ended the same, history included (times aside).
pub fn same_result<G: Grammar>(a: &RunResult<G>, b: &RunResult<G>) {
    assert_eq!(a.best, b.best);
    assert_eq!(a.best_fitness.to_bits(), b.best_fitness.to_bits());
    assert_eq!(a.evaluations, b.evaluations);
    assert_eq!(a.generations, b.generations);
    assert_eq!(timeless(&a.history), timeless(&b.history));
}

/// Runs `f` on a pool of `n` threads.
pub fn threads<T: Send>(n: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(f)
}

/// Scores like [`Skyline`] but gives NaN to every third genome and -inf to some.
pub struct Poisoned(pub Skyline, pub u64);

impl Evaluator<City> for Poisoned {
    fn evaluate(&mut self, genomes: &[Genome<City>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.0.evaluate(genomes, out)?;
        for o in out.iter_mut() {
            self.1 += 1;
            if self.1.is_multiple_of(3) {
                *o = f64::NAN;
            } else if self.1.is_multiple_of(17) {
                *o = f64::NEG_INFINITY;
            }
        }
        Ok(())
    }
}
