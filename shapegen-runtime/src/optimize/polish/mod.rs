//! Polishing: a derivation's continuous parameters (sizes, angles, ratios) tuned by a
//! separable CMA-ES ([`SepCmaEs`]) while its structure (its genes, their links and
//! their discrete parameters) stays as the search made it.
//!
//! A genome's *coordinates* are the words of its real-valued parameters (`f32`, angles,
//! and each component of `Vec2` and `Vec3` parameters) whose range is not a single
//! point, each mapped linearly from its `[lo, hi]` onto `[0, 1]`. Each generation,
//! polishing takes the population's best; when its structure is the one being polished
//! (every other word as it was), the strategy goes on, otherwise a new one starts at its
//! coordinates. `candidates` genomes are drawn, scored together, and the best replaces
//! the individual when it scores at least as well.
//!
//! Every single-fitness method polishes with the same two settings, `polish` (the
//! candidates a generation, 0 for none) and `polish_sigma` (a new strategy's step size):
//! the GA and the hybrid its population's best each generation, SMC and SOSMC their best
//! particle each step, RJMCMC its best chain's state each iteration.

mod cmaes;

pub use cmaes::SepCmaEs;

use serde::{Deserialize, Serialize};

use super::driver::Held;
use super::error::{CheckpointError, OptimizeError, SettingsError};
use super::fitness::{best_index, compare};
use super::run::Progress;
use super::run::stream;
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::{Genome, node_of};
use crate::graph::{Distribution, HEADER_WORDS};

/// The stream index of polishing within a generation's streams (after the GA's pairs
/// and the refinement chains' `2^31 + i`).
const STREAM: u64 = 3 << 30;

/// One real-valued parameter word of a genome and its range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coordinate {
    /// The word's index in the genome.
    pub word: u32,
    /// Its distribution's lower bound.
    pub lo: f32,
    /// Its distribution's upper bound, above `lo`.
    pub hi: f32,
}

impl Coordinate {
    /// The word's value mapped onto `[0, 1]`.
    pub fn unit(&self, words: &[u32]) -> f64 {
        let v = f64::from(f32::from_bits(words[self.word as usize]));
        ((v - f64::from(self.lo)) / (f64::from(self.hi) - f64::from(self.lo))).clamp(0.0, 1.0)
    }

    /// Writes the value at `u` of `[0, 1]` into the word, within `[lo, hi]`.
    pub fn set(&self, words: &mut [u32], u: f64) {
        let (lo, hi) = (f64::from(self.lo), f64::from(self.hi));
        let v = ((lo + u.clamp(0.0, 1.0) * (hi - lo)) as f32).clamp(self.lo, self.hi);
        words[self.word as usize] = v.to_bits();
    }
}

/// The coordinates of `genome`, in word order.
///
/// ```
/// use shapegen_runtime::optimize::polish_coordinates;
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// A box of any height on a stem.
///     pub Stem {
///         axiom Part;
///         node Part {
///             params { height: f32 ~ uniform(0.5, 2.0), turn: f32 ~ degrees(0.0, 90.0), kind: i32 ~ uniform(0..=3) }
///             children { next: Part = 0.0 }
///             derive(s) { s.resize(vec3(1.0, height, 1.0)).emit(CUBE); }
///         }
///     }
/// }
///
/// let genome = Genome::<Stem>::with_root(Part { height: 1.25, turn: 0.5, kind: 2 })?;
/// let coordinates = polish_coordinates(&genome);
/// // The height and the angle; the integer is discrete.
/// assert_eq!(coordinates.len(), 2);
/// assert_eq!(coordinates[0].unit(genome.words()), 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn polish_coordinates<G: Grammar>(genome: &Genome<G>) -> Vec<Coordinate> {
    let mut out = Vec::new();
    for gene in genome.genes() {
        let node = node_of::<G>(gene.kind());
        let first = gene.pos() + HEADER_WORDS + node.links;
        for param in node.params {
            let word = first + param.offset;
            let mut push = |k: u32, lo: f32, hi: f32| {
                if lo < hi {
                    out.push(Coordinate {
                        word: word + k,
                        lo,
                        hi,
                    });
                }
            };
            match param.dist {
                Distribution::Uniform { lo, hi } | Distribution::Angle { lo, hi, .. } => {
                    push(0, lo, hi)
                }
                Distribution::UniformVec2 { lo, hi } => {
                    (0..2).for_each(|k| push(k, lo[k as usize], hi[k as usize]))
                }
                Distribution::UniformVec3 { lo, hi } => {
                    (0..3).for_each(|k| push(k, lo[k as usize], hi[k as usize]))
                }
                Distribution::Int { .. }
                | Distribution::Index { .. }
                | Distribution::Weighted { .. }
                | Distribution::Bernoulli { .. } => {}
            }
        }
    }
    out
}

/// What polishing is doing, kept in checkpoints: the genome whose structure it polishes
/// and its strategy over that genome's coordinates.
#[derive(Serialize, Deserialize)]
#[serde(bound = "G: Grammar", deny_unknown_fields)]
pub struct PolishState<G> {
    /// The genome polishing started from (its structure is what is kept).
    pub origin: Genome<G>,
    /// The strategy, one dimension per coordinate of `origin`.
    pub strategy: SepCmaEs,
}

crate::grammar_struct_traits!(PolishState { origin, strategy });

impl<G: Grammar> PolishState<G> {
    /// Checks a resumed state: one dimension per coordinate, every number sound.
    pub(crate) fn check(&self) -> Result<(), OptimizeError> {
        let coordinates = polish_coordinates(&self.origin).len();
        if self.strategy.dimensions() != coordinates || !self.strategy.is_sound() {
            return Err(OptimizeError::Checkpoint(CheckpointError::Strategy {
                dimensions: self.strategy.dimensions(),
                coordinates,
            }));
        }
        Ok(())
    }

    /// Whether `genome` has the structure of the origin: the same words but at the
    /// coordinates.
    fn polishes(&self, genome: &Genome<G>, coordinates: &[Coordinate]) -> bool {
        let (a, b) = (self.origin.words(), genome.words());
        if a.len() != b.len() {
            return false;
        }
        let mut at = coordinates.iter().map(|c| c.word as usize).peekable();
        a.iter().zip(b).enumerate().all(|(i, (x, y))| {
            if at.peek() == Some(&i) {
                at.next();
                true
            } else {
                x == y
            }
        })
    }
}

/// Checks a method's polishing settings: `polish` 0 or at least 2, `polish_sigma` in
/// `(0, 1]`.
pub(crate) fn check_settings(polish: u32, polish_sigma: f64) -> Result<(), SettingsError> {
    if polish == 1 {
        return Err(SettingsError::new("polish", polish, "0, or at least 2"));
    }
    if !(polish_sigma > 0.0 && polish_sigma <= 1.0) {
        return Err(SettingsError::new(
            "polish_sigma",
            polish_sigma,
            "above 0 and at most 1",
        ));
    }
    Ok(())
}

/// The genomes polishing holds: its candidates and its origin, which checkpoints keep.
pub(crate) fn held(polish: u32) -> Held {
    Held {
        genomes: u64::from(polish) + u64::from(polish > 0),
        saved: u64::from(polish > 0),
        setting: "optimizer.polish",
        value: polish.into(),
    }
}

/// Refuses `polish` in a method that has no single best to polish.
pub(crate) fn refuse(polish: u32, why: &'static str) -> Result<(), SettingsError> {
    if polish == 0 {
        return Ok(());
    }
    Err(SettingsError::new("polish", polish, why))
}

/// Polishing: the strategy under way, if any, and buffers reused from generation to
/// generation.
pub(crate) struct Polisher<G> {
    state: Option<PolishState<G>>,
    genomes: Vec<Genome<G>>,
    fitness: Vec<f64>,
}

impl<G: Grammar> Polisher<G> {
    /// No polishing under way.
    pub(crate) fn new() -> Self {
        Polisher {
            state: None,
            genomes: Vec::new(),
            fitness: Vec::new(),
        }
    }

    /// The polishing under way, for a checkpoint.
    pub(crate) fn save(&self) -> Option<PolishState<G>> {
        self.state.clone()
    }

    /// Checks a checkpoint's polishing.
    pub(crate) fn check(state: Option<&PolishState<G>>) -> Result<(), OptimizeError> {
        state.map_or(Ok(()), PolishState::check)
    }

    /// Goes on with a checkpoint's polishing.
    pub(crate) fn restore(&mut self, state: Option<PolishState<G>>) {
        self.state = state;
    }

    /// Polishes the best of `population` (see the [module](self) docs) in the
    /// generation (step, iteration) that follows `progress`, with a method's `polish`
    /// and `polish_sigma` settings, scoring the candidates from nothing and
    /// counting them in `progress`. Nothing happens when `polish` is under 2 or the best
    /// has no coordinates.
    pub(crate) fn polish<R>(
        &mut self,
        (candidates, sigma): (u32, f64),
        progress: &mut Progress<R>,
        evaluator: &mut (dyn Evaluator<G> + '_),
        (population, fitness): (&mut [Genome<G>], &mut [f64]),
    ) -> Result<(), OptimizeError> {
        if candidates < 2 {
            return Ok(());
        }
        let state = &mut self.state;
        let Some(best) = best_index(fitness) else {
            return Ok(());
        };
        let coordinates = polish_coordinates(&population[best]);
        if coordinates.is_empty() || fitness[best].is_nan() {
            return Ok(());
        }
        if !state
            .as_ref()
            .is_some_and(|s| s.polishes(&population[best], &coordinates))
        {
            let words = population[best].words();
            let mean = coordinates.iter().map(|c| c.unit(words)).collect();
            *state = Some(PolishState {
                origin: population[best].clone(),
                strategy: SepCmaEs::new(mean, sigma),
            });
        }
        let polishing = state.as_mut().expect("made above");
        let mut rng = stream(progress.seed, progress.generation + 1, STREAM);
        let points = polishing.strategy.ask(candidates as usize, &mut rng);
        self.genomes
            .resize_with(points.len(), || Genome::from_parts(Vec::new(), 0));
        for (genome, point) in self.genomes.iter_mut().zip(&points) {
            genome.clone_from(&population[best]);
            for (c, &u) in coordinates.iter().zip(point) {
                c.set(&mut genome.words, u);
            }
        }
        self.fitness.clear();
        self.fitness.resize(points.len(), f64::NAN);
        // Scored from nothing, not as children of the best: a candidate moves every
        // continuous parameter, so counting it from the best's kept state would count
        // all its instances again anyway, and keeping the state of every candidate, of
        // which at most one stays, costs more than it saves.
        evaluator.evaluate(&self.genomes, &mut self.fitness)?;
        polishing.strategy.tell(&points, &self.fitness);
        if let Some(top) = best_index(&self.fitness)
            && !self.fitness[top].is_nan()
            && compare(self.fitness[top], fitness[best]).is_ge()
        {
            std::mem::swap(&mut population[best], &mut self.genomes[top]);
            fitness[best] = self.fitness[top];
        }
        progress.evaluations += points.len() as u64;
        Ok(())
    }
}
