//! The hybrid method: the GA to the bit with its additions off; deterministic at any
//! thread count; resumable anywhere, also while its first population is being seeded;
//! safe with NaN fitness; its settings checked field by field.

mod support {
    pub mod evaluators;
    pub mod runs;
}

use generators::{City, Spaceship, city, spaceship};
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;
use support::evaluators::{BoxTarget, Skyline};
use support::runs::{Poisoned, same_result, small_ga, threads};

/// Every addition on: seeding, refinement and polishing.
fn full() -> HybridSettings {
    HybridSettings {
        seed_steps: 2,
        seed_share: 0.5,
        refine: 4,
        refine_moves: 3,
        jump_probability: 0.5,
        ga: GaSettings {
            polish: 6,
            polish_sigma: 0.1,
            ..small_ga()
        },
    }
}

/// Every addition off: the GA.
fn none() -> HybridSettings {
    HybridSettings {
        ga: small_ga(),
        seed_steps: 0,
        refine: 0,
        refine_moves: 0,
        ..HybridSettings::default()
    }
}

/// [`full`] and each addition on alone.
fn variants() -> [HybridSettings; 4] {
    [
        full(),
        HybridSettings {
            refine: 4,
            refine_moves: 2,
            ..none()
        },
        HybridSettings {
            seed_steps: 3,
            ..none()
        },
        HybridSettings {
            ga: GaSettings {
                polish: 8,
                ..small_ga()
            },
            ..none()
        },
    ]
}

/// [`Skyline`] capped at 3: many individuals tie at the cap.
struct Capped(Skyline);

impl Evaluator<City> for Capped {
    fn evaluate(&mut self, genomes: &[Genome<City>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.0.evaluate(genomes, out)?;
        out.iter_mut().for_each(|o| *o = o.min(3.0));
        Ok(())
    }
}

#[test]
fn hybrid_with_every_addition_off_is_the_ga() {
    for seed in [1, 2] {
        let budget = Budget::generations(12);
        let ga = Ga::<City>::new(small_ga(), city::PAPER_LIMITS, seed)
            .unwrap()
            .run(&mut Skyline::new(), &budget, &mut Silent)
            .unwrap();
        let hybrid = Hybrid::<City>::new(none(), city::PAPER_LIMITS, seed)
            .unwrap()
            .run(&mut Skyline::new(), &budget, &mut Silent)
            .unwrap();
        same_result(&ga, &hybrid);
    }
}

#[test]
fn hybrid_improves_and_counts_every_evaluation() {
    for (k, s) in variants().into_iter().enumerate() {
        let mut eval = Skyline::new();
        let r = Hybrid::<City>::new(s, city::PAPER_LIMITS, 3)
            .unwrap()
            .run(&mut eval, &Budget::generations(15), &mut Silent)
            .unwrap();
        assert!(r.best_fitness > r.history[0].best, "variant {k}: {r:?}");
        assert_eq!(eval.genomes, r.evaluations, "variant {k}");
        // An evaluation budget stops it within one generation's cost.
        let mut eval = Skyline::new();
        let r = Hybrid::<City>::new(s, city::PAPER_LIMITS, 3)
            .unwrap()
            .run(&mut eval, &Budget::evaluations(500), &mut Silent)
            .unwrap();
        assert_eq!(r.stopped, StopReason::Evaluations, "variant {k}");
        assert!(r.evaluations <= 500, "variant {k}: {}", r.evaluations);
        assert_eq!(eval.genomes, r.evaluations, "variant {k}");
    }
}

#[test]
fn hybrid_refinement_keeps_or_betters_its_elites_when_it_hill_climbs() {
    // A refined individual only ever moves to an equal or better one, so
    // with the GA's elitism the best never falls from one generation to the next.
    let s = HybridSettings {
        refine: 6,
        refine_moves: 4,
        ..none()
    };
    let r = Hybrid::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 4)
        .unwrap()
        .run(&mut BoxTarget::new(), &Budget::generations(10), &mut Silent)
        .unwrap();
    assert!(r.history.windows(2).all(|w| w[1].best >= w[0].best));
    assert_eq!(r.evaluations, 40 + 10 * (32 + 6 * 4));
}

/// Runs `hybrid` on until it has made `generations` generations; returns how many
/// evaluations the run reports and how many `eval` made.
fn run_to(hybrid: &mut Hybrid<City>, eval: &mut Skyline, generations: u64) -> (u64, u64) {
    let r = hybrid
        .run(eval, &Budget::generations(generations), &mut Silent)
        .unwrap();
    (r.evaluations, eval.genomes)
}

#[test]
fn hybrid_seeds_its_first_population_by_sosmc() {
    let s = HybridSettings {
        seed_steps: 2,
        seed_share: 1.0,
        ..none()
    };
    let mut hybrid = Hybrid::<City>::new(s, city::PAPER_LIMITS, 1).unwrap();
    let mut eval = Skyline::new();
    // The axiom's particles, then two SOSMC steps of 40 each.
    assert_eq!(run_to(&mut hybrid, &mut eval, 1).0, 2 * 40);
    let state = hybrid.checkpoint();
    assert!(state.seeding.is_some() && state.population.is_empty());
    assert_eq!(run_to(&mut hybrid, &mut eval, 2).0, 3 * 40);
    let state = hybrid.checkpoint();
    assert!(state.seeding.is_none() && state.population.len() == 40);
    assert_eq!(run_to(&mut hybrid, &mut eval, 3).0, 3 * 40 + 32);
}

#[test]
fn hybrid_seeds_a_share_of_its_first_population_and_draws_the_rest_as_the_ga_does() {
    let s = HybridSettings {
        seed_steps: 2,
        seed_share: 0.25,
        ..none()
    };
    let mut hybrid = Hybrid::<City>::new(s, city::PAPER_LIMITS, 1).unwrap();
    let mut eval = Skyline::new();
    // 10 of the 40 are seeded: the axiom's 10 particles, a step of 10, then the last
    // step of 10 with the 30 random genomes.
    assert_eq!(run_to(&mut hybrid, &mut eval, 1), (20, 20));
    assert_eq!(run_to(&mut hybrid, &mut eval, 2), (60, 60));
    let state = hybrid.checkpoint();
    assert!(state.seeding.is_none() && state.population.len() == 40);
    // The random ones are the GA's own first genomes in those places, scored.
    let mut ga = Ga::<City>::new(small_ga(), city::PAPER_LIMITS, 1).unwrap();
    ga.run(&mut Skyline::new(), &Budget::generations(0), &mut Silent)
        .unwrap();
    let first = ga.checkpoint();
    assert_eq!(state.population[10..], first.population[10..]);
    assert_eq!(state.fitness[10..], first.fitness[10..]);
    // The seeded ones are SOSMC's particles, grown from the axiom, not random genomes.
    assert_ne!(state.population[..10], first.population[..10]);
    // A budget that ends on the last seeding step stops before it.
    let r = Hybrid::<City>::new(s, city::PAPER_LIMITS, 1)
        .unwrap()
        .run(&mut Skyline::new(), &Budget::evaluations(59), &mut Silent)
        .unwrap();
    assert_eq!(r.evaluations, 20);
}

#[test]
fn hybrid_same_seed_same_result_at_any_thread_count() {
    for (k, s) in variants().into_iter().enumerate() {
        let run = || {
            Hybrid::<City>::new(s, city::PAPER_LIMITS, 5)
                .unwrap()
                .run(
                    &mut Capped(Skyline::new()),
                    &Budget::generations(12),
                    &mut Silent,
                )
                .unwrap()
        };
        let (a, b) = (threads(1, run), threads(2, run));
        same_result(&a, &b);
        let run = || {
            Hybrid::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 5)
                .unwrap()
                .run(&mut BoxTarget::new(), &Budget::generations(12), &mut Silent)
                .unwrap()
        };
        same_result(&threads(1, run), &threads(2, run));
        assert!(a.generations == 12, "variant {k}");
    }
}

#[test]
fn hybrid_resume_equals_uninterrupted() {
    for (k, s) in variants().into_iter().enumerate() {
        let end = Budget::generations(14);
        let mut whole = Hybrid::<City>::new(s, city::PAPER_LIMITS, 4).unwrap();
        let full = whole
            .run(&mut Capped(Skyline::new()), &end, &mut Silent)
            .unwrap();
        // Stopped before, during and after seeding.
        for stop in [0, 1, 2, 3, 5, 8] {
            let mut first = Hybrid::<City>::new(s, city::PAPER_LIMITS, 4).unwrap();
            first
                .run(
                    &mut Capped(Skyline::new()),
                    &Budget::generations(stop),
                    &mut Silent,
                )
                .unwrap();
            let json = serde_json::to_string(&first.checkpoint()).unwrap();
            let state: HybridState<City> = serde_json::from_str(&json).unwrap();
            let mut resumed = Hybrid::resume(state).unwrap();
            let r = resumed
                .run(&mut Capped(Skyline::new()), &end, &mut Silent)
                .unwrap();
            same_result(&full, &r);
            assert_eq!(
                whole.checkpoint().population,
                resumed.checkpoint().population,
                "variant {k}, stopped after {stop}"
            );
        }
    }
}

#[test]
fn hybrid_checkpoints_of_the_wrong_size_are_refused() {
    let mut hybrid = Hybrid::<City>::new(none(), city::PAPER_LIMITS, 2).unwrap();
    hybrid
        .run(&mut Skyline::new(), &Budget::generations(2), &mut Silent)
        .unwrap();
    let mut state = hybrid.checkpoint();
    state.fitness.pop();
    let err = Hybrid::resume(state).unwrap_err();
    assert!(matches!(err, OptimizeError::Checkpoint(_)), "{err}");
}

#[test]
fn hybrid_survives_nan_fitness() {
    for (k, s) in variants().into_iter().enumerate() {
        let r = Hybrid::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(
                &mut Poisoned(Skyline::new(), 0),
                &Budget::generations(12),
                &mut Silent,
            )
            .unwrap();
        assert!(
            r.best_fitness.is_finite() && r.best_fitness > r.history[0].best,
            "variant {k}: {}",
            r.best_fitness
        );
        assert!(r.history.iter().all(|h| h.mean.is_finite()), "variant {k}");
        // All NaN: nothing breaks, the best stays NaN.
        let r = Hybrid::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(
                &mut FnEvaluator(|_: &Genome<City>| f64::NAN),
                &Budget::generations(8),
                &mut Silent,
            )
            .unwrap();
        assert!(r.best_fitness.is_nan(), "variant {k}");
    }
}

#[test]
fn hybrid_settings_are_validated() {
    let check = |s: HybridSettings, field: &str| {
        let e = s.validate().unwrap_err();
        assert_eq!(e.field, field, "{e}");
        assert!(matches!(
            Hybrid::<City>::new(s, city::PAPER_LIMITS, 0),
            Err(OptimizeError::Settings(_))
        ));
    };
    let d = full();
    check(HybridSettings { refine: 41, ..d }, "refine");
    let ga = |polish, polish_sigma| GaSettings {
        polish,
        polish_sigma,
        ..d.ga
    };
    check(
        HybridSettings {
            ga: ga(1, 0.1),
            ..d
        },
        "polish",
    );
    for sigma in [0.0, -0.1, 1.5, f64::NAN] {
        check(
            HybridSettings {
                ga: ga(8, sigma),
                ..d
            },
            "polish_sigma",
        );
    }
    for p in [-0.1, 1.5, f64::NAN] {
        check(
            HybridSettings {
                jump_probability: p,
                ..d
            },
            "jump_probability",
        );
    }
    check(
        HybridSettings {
            ga: GaSettings {
                population: 1,
                ..small_ga()
            },
            refine: 0,
            ..d
        },
        "population",
    );
    HybridSettings::default().validate().unwrap();
    d.validate().unwrap();
    let parsed: HybridSettings =
        serde_json::from_str(r#"{"refine": 2, "ga": {"population": 50}}"#).unwrap();
    assert_eq!((parsed.refine, parsed.ga.population), (2, 50));
    assert!(serde_json::from_str::<HybridSettings>(r#"{"refines": 2}"#).is_err());
}
