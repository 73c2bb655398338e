//! A method written outside the crate: a (1+λ) hill climber implementing the public
//! `Optimizer` trait with the public operators, its checkpoint declared with the public
//! `checkpoint!` macro, run by the crate's own driver and `Session`: budgets stop it, a
//! checkpointed and resumed session ends as an uninterrupted one, and the stop flag
//! interrupts it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use rand::RngExt;
use serde::{Deserialize, Serialize};
use shapegen_runtime::checkpoint;
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;

generator! {
    /// A chain of blocks.
    pub Chain {
        axiom Seg;
        node Seg {
            children { next: Seg = 0.5 }
            derive(s) {
                s.emit(CUBE);
                if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
            }
        }
    }
}

/// Settings of the climber.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
struct ClimbSettings {
    /// Children per generation.
    lambda: u32,
    /// Length of the initial genome.
    initial_length: u32,
    /// Generations a run takes.
    generations: u64,
}

impl Settings for ClimbSettings {
    const GENERATIONS: &'static str = "generations";

    fn generations(&self) -> u64 {
        self.generations
    }

    fn set_generations(&mut self, generations: u64) {
        self.generations = generations;
    }

    fn validate(&self) -> Result<(), SettingsError> {
        Ok(())
    }
}

checkpoint! {
    /// Its checkpoint: the parent and its fitness.
    struct ClimbState<G>: ClimbSettings, Best<G> {
        parent: Genome<G>,
        #[serde(with = "bits")]
        parent_fitness: f64,
    }
}

/// Fitness values as exact bits.
mod bits {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u64(v.to_bits())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        u64::deserialize(d).map(f64::from_bits)
    }
}

/// The (1+λ) climber: each generation mutates the parent into λ children (grow, cut or
/// alter, drawn uniformly) and keeps the best child if it is not worse. The population
/// the driver records is the parent and its children.
struct Climb {
    core: Core<ClimbSettings, Best<Chain>>,
    ops: Operators<Chain>,
    /// The parent first, then the children.
    population: Vec<Genome<Chain>>,
    fitness: Vec<f64>,
}

impl Optimizer<Chain> for Climb {
    type Settings = ClimbSettings;
    type State = ClimbState<Chain>;
    type Record = Best<Chain>;

    /// The parent and its children; a checkpoint saves the parent.
    fn genomes_held(settings: &ClimbSettings) -> Vec<Held> {
        vec![Held {
            genomes: u64::from(settings.lambda) + 1,
            saved: 1,
            setting: "lambda",
            value: settings.lambda.into(),
        }]
    }

    fn new(settings: ClimbSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        let n = settings.lambda as usize + 1;
        let mut rng = stream(seed, 0, 0);
        let axiom = Genome::<Chain>::axiom(&mut rng);
        Ok(Climb {
            core: Core::new(settings, limits, seed),
            ops: Operators::new(limits)?,
            population: vec![axiom; n],
            fitness: vec![f64::NAN; n],
        })
    }

    fn core(&self) -> &Core<ClimbSettings, Best<Chain>> {
        &self.core
    }

    fn parts(
        &mut self,
    ) -> (
        &mut Core<ClimbSettings, Best<Chain>>,
        &[Genome<Chain>],
        &[f64],
    ) {
        (&mut self.core, &self.population, &self.fitness)
    }

    fn save_body(&self) -> (Genome<Chain>, f64) {
        (self.population[0].clone(), self.fitness[0])
    }

    fn restore_body(&mut self, (parent, f): (Genome<Chain>, f64)) -> Result<(), OptimizeError> {
        self.population[0] = parent;
        self.fitness[0] = f;
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        u64::from(self.core.settings.lambda)
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<Chain> + '_)) -> Result<(), OptimizeError> {
        let rng = &mut stream(self.core.progress.seed, 0, 1);
        self.ops.random_into(
            self.core.settings.initial_length,
            &mut self.population[0],
            rng,
        );
        evaluator.evaluate(&self.population[..1], &mut self.fitness[..1])?;
        self.core.progress.evaluations += 1;
        let (parent, children) = self.population.split_first_mut().unwrap();
        children.iter_mut().for_each(|c| c.clone_from(parent));
        let f = self.fitness[0];
        self.fitness[1..].fill(f);
        Ok(())
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<Chain> + '_)) -> Result<(), OptimizeError> {
        let (seed, generation) = (self.core.progress.seed, self.core.progress.generation + 1);
        let (parent, children) = self.population.split_first_mut().unwrap();
        for (i, child) in children.iter_mut().enumerate() {
            let rng = &mut stream(seed, generation, i as u64);
            child.clone_from(parent);
            match rng.random_range(0..3) {
                0 => self.ops.grow(child, rng),
                1 => self.ops.cut(child, rng),
                _ => self.ops.alter(child, rng),
            };
        }
        evaluator.evaluate(children, &mut self.fitness[1..])?;
        self.core.progress.evaluations += children.len() as u64;
        let best = (1..self.fitness.len())
            .max_by(|&a, &b| self.fitness[a].total_cmp(&self.fitness[b]).then(b.cmp(&a)))
            .unwrap();
        if self.fitness[best] >= self.fitness[0] {
            self.population.swap(0, best);
            self.fitness.swap(0, best);
        }
        Ok(())
    }
}

fn settings() -> ClimbSettings {
    ClimbSettings {
        lambda: 6,
        initial_length: 2,
        generations: 100,
    }
}

fn limits() -> Limits {
    Limits::new(1, 40, 40).unwrap()
}

/// Chains of 15 blocks are best.
fn fifteen() -> FnEvaluator<impl FnMut(&Genome<Chain>) -> f64> {
    FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 15.0).abs())
}

fn timeless(h: &[HistoryEntry]) -> Vec<(u64, u64, u64, u64)> {
    h.iter()
        .map(|e| {
            (
                e.generation,
                e.evaluations,
                e.best.to_bits(),
                e.mean.to_bits(),
            )
        })
        .collect()
}

#[test]
fn budgets_stop_it() {
    let run = |budget| {
        Session::<Chain, Climb>::start(settings(), limits(), 3, budget)
            .unwrap()
            .run(&mut fifteen())
            .unwrap()
    };
    let r = run(Budget::generations(7));
    assert_eq!(
        (r.stopped, r.generations, r.evaluations),
        (StopReason::Generations, 7, 43)
    );
    assert_eq!(r.history.len(), 8);
    // 1 + 6k <= 20: three generations fit, a fourth would need 25.
    let r = run(Budget::evaluations(20));
    assert_eq!(
        (r.stopped, r.generations, r.evaluations),
        (StopReason::Evaluations, 3, 19)
    );
    let r = run(Budget::default().and_wall_time(Duration::ZERO));
    assert_eq!((r.stopped, r.generations), (StopReason::WallTime, 0));
    assert_eq!(r.stopped.name(), "time");
    // The provided `run`, as the built-in methods have it, drives it just the same.
    let mut climb = Climb::new(settings(), limits(), 3).unwrap();
    let direct = climb
        .run(&mut fifteen(), &Budget::generations(7), &mut Silent)
        .unwrap();
    let session = run(Budget::generations(7));
    assert_eq!(direct.best, session.best);
    assert_eq!(timeless(&direct.history), timeless(&session.history));
    assert!(direct.best_fitness > -13.0);
}

#[test]
fn a_resumed_session_ends_as_an_uninterrupted_one() {
    let budget = Budget::generations(40);
    let mut saves = 0;
    let full = Session::<Chain, Climb>::start(settings(), limits(), 5, budget)
        .unwrap()
        .save_every(Duration::ZERO)
        .on_save(|s| {
            saves += 1;
            assert_eq!(s.stopped.is_some(), s.progress.generation == 40);
            Ok::<_, std::io::Error>(())
        })
        .run(&mut fifteen())
        .unwrap();
    // Saved after every generation but the last, and once at the end.
    assert_eq!(saves, 41);

    // Stop after generation 13 by the progress hook, save, resume from the JSON.
    let mut saved = None;
    let mut stop_at_13 = |s: &Snapshot<'_, Chain>| {
        if s.generation == 13 {
            Control::Stop
        } else {
            Control::Continue
        }
    };
    let first = Session::<Chain, Climb>::start(settings(), limits(), 5, budget)
        .unwrap()
        .save_every(Duration::from_secs(3600))
        .on_progress(&mut stop_at_13)
        .on_save(|s| {
            saved = Some(serde_json::to_string(&s.state).unwrap());
            Ok::<_, std::io::Error>(())
        })
        .run(&mut fifteen())
        .unwrap();
    assert_eq!(
        (first.stopped, first.generations),
        (StopReason::Observer, 13)
    );
    let state: ClimbState<Chain> = serde_json::from_str(&saved.unwrap()).unwrap();
    let resumed = Session::<Chain, Climb>::resume(state, budget)
        .unwrap()
        .run(&mut fifteen())
        .unwrap();
    assert_eq!(resumed.best, full.best);
    assert_eq!(resumed.best_fitness.to_bits(), full.best_fitness.to_bits());
    assert_eq!(resumed.evaluations, full.evaluations);
    assert_eq!(resumed.stopped, StopReason::Generations);
    assert_eq!(timeless(&resumed.history), timeless(&full.history));
}

#[test]
fn the_stop_flag_interrupts_it_and_save_errors_come_back() {
    let stop = AtomicBool::new(false);
    let mut generations = 0;
    let mut set_flag = |s: &Snapshot<'_, Chain>| {
        generations += 1;
        if s.generation == 4 {
            stop.store(true, Ordering::SeqCst);
        }
        Control::Continue
    };
    let r = Session::<Chain, Climb>::start(settings(), limits(), 9, Budget::default())
        .unwrap()
        .stop_flag(&stop)
        .on_progress(&mut set_flag)
        .run(&mut fifteen())
        .unwrap();
    assert_eq!((r.stopped, r.generations), (StopReason::Observer, 4));
    assert_eq!(r.stopped.to_string(), "interrupted");
    assert_eq!(generations, 5);

    let err = Session::<Chain, Climb>::start(settings(), limits(), 9, Budget::generations(3))
        .unwrap()
        .on_save(|_| Err(std::io::Error::other("disk full")))
        .run(&mut fifteen())
        .unwrap_err();
    assert!(matches!(err, SessionError::Save(_)), "{err}");
    assert!(err.to_string().contains("disk full"));
}

/// Slow saves space out: after a save that took `t`, the next waits at least
/// `SAVE_SPACING * t`, so saving takes at most 5 % of a run however short the interval.
#[test]
fn slow_saves_space_out() {
    let took = Duration::from_millis(20);
    let mut during = 0u32;
    let start = std::time::Instant::now();
    let result = Session::<Chain, Climb>::start(settings(), limits(), 5, Budget::generations(300))
        .unwrap()
        .save_every(Duration::from_nanos(1))
        .on_save(|s| {
            during += u32::from(s.stopped.is_none());
            std::thread::sleep(took);
            Ok::<_, std::io::Error>(())
        })
        .run(&mut fifteen())
        .unwrap();
    let elapsed = start.elapsed();
    assert_eq!(result.generations, 300);
    // The first generation saves; each save after it came at least 19 x 20 ms later.
    let bound = 1 + (elapsed.as_secs_f64() / (took * SAVE_SPACING).as_secs_f64()) as u32;
    assert!(
        (1..=bound).contains(&during),
        "{during} saves during a run of {elapsed:?}, at most {bound} allowed"
    );
}
