//! The optimizers on the published generators, with cheap deterministic evaluators
//! computed from the derived instances.

mod support {
    pub mod evaluators;
    pub mod runs;
}

use generators::{City, Spaceship, city, spaceship};
use shapegen_runtime::ops::OperatorVariant;
use shapegen_runtime::optimize::multi::{MultiEvaluator, MultiGa, MultiGaSettings};
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;
use support::evaluators::{BoxTarget, Skyline};
use support::runs::{Poisoned, same_result, small_ga, threads};

/// [`small_ga`] with each operator variant.
fn both_variants() -> [GaSettings; 2] {
    OperatorVariant::ALL.map(|operators| GaSettings {
        operators,
        ..small_ga()
    })
}

fn initial_best<G: Grammar>(result: &RunResult<G>) -> f64 {
    result.history[0].best
}

#[test]
fn ga_improves_on_its_initial_population() {
    for (seed, s) in [1, 2, 3].into_iter().zip(both_variants().iter().cycle()) {
        let mut ga = Ga::<City>::new(*s, city::PAPER_LIMITS, seed).unwrap();
        let r = ga
            .run(&mut Skyline::new(), &s.budget(), &mut Silent)
            .unwrap();
        assert!(
            r.best_fitness > initial_best(&r) + 2.0,
            "seed {seed}: {r:?}"
        );
        let mut ga = Ga::<Spaceship>::new(*s, spaceship::PAPER_LIMITS, seed).unwrap();
        let r = ga
            .run(&mut BoxTarget::new(), &s.budget(), &mut Silent)
            .unwrap();
        assert!(
            r.best_fitness > initial_best(&r),
            "seed {seed}: {:?}",
            r.history
        );
        assert!(r.history.windows(2).all(|w| w[1].best >= w[0].best));
    }
}

#[test]
fn ga_beats_random_sampling_at_equal_evaluations() {
    let settings = small_ga();
    let mut wins = 0;
    for seed in 0..5 {
        let mut ga = Ga::<City>::new(settings, city::PAPER_LIMITS, seed).unwrap();
        let r = ga
            .run(&mut Skyline::new(), &settings.budget(), &mut Silent)
            .unwrap();
        let mut ops = Operators::<City>::new(city::PAPER_LIMITS).unwrap();
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(seed);
        let mut eval = Skyline::new();
        let random_best = (0..r.evaluations)
            .map(|_| {
                let g = ops.random(settings.initial_length, &mut rng);
                eval.score(&g)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        wins += u32::from(r.best_fitness > random_best);
    }
    assert_eq!(wins, 5);
}

#[test]
fn ga_elites_are_not_reevaluated() {
    let s = small_ga();
    let mut ga = Ga::<City>::new(s, city::PAPER_LIMITS, 9).unwrap();
    let mut eval = Skyline::new();
    let r = ga
        .run(&mut eval, &Budget::generations(5), &mut Silent)
        .unwrap();
    assert_eq!(eval.calls, 6);
    let expected = u64::from(s.population) + 5 * u64::from(s.population - s.elitism);
    assert_eq!(eval.genomes, expected);
    assert_eq!(r.evaluations, expected);
}

#[test]
fn ga_same_seed_same_result_at_any_thread_count() {
    for s in both_variants() {
        let run = || {
            let mut ga = Ga::<City>::new(s, city::PAPER_LIMITS, 5).unwrap();
            ga.run(&mut Skyline::new(), &Budget::generations(8), &mut Silent)
                .unwrap()
        };
        same_result(&threads(1, run), &threads(2, run));
    }
}

#[test]
fn ga_resume_equals_uninterrupted() {
    for s in both_variants() {
        let full = Ga::<City>::new(s, city::PAPER_LIMITS, 4)
            .unwrap()
            .run(&mut Skyline::new(), &Budget::generations(10), &mut Silent)
            .unwrap();
        let mut first = Ga::<City>::new(s, city::PAPER_LIMITS, 4).unwrap();
        first
            .run(&mut Skyline::new(), &Budget::generations(4), &mut Silent)
            .unwrap();
        let json = serde_json::to_string(&first.checkpoint()).unwrap();
        let state: GaState<City> = serde_json::from_str(&json).unwrap();
        assert_eq!(state.settings.operators, s.operators);
        let resumed = Ga::resume(state)
            .unwrap()
            .run(&mut Skyline::new(), &Budget::generations(10), &mut Silent)
            .unwrap();
        same_result(&full, &resumed);
    }
}

/// Scores a genome by its length, and records every length it scores.
#[derive(Default)]
struct Lengths(Vec<usize>);

impl Evaluator<Spaceship> for Lengths {
    fn evaluate(
        &mut self,
        genomes: &[Genome<Spaceship>],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        for (g, o) in genomes.iter().zip(out) {
            self.0.push(g.len());
            *o = g.len() as f64;
        }
        Ok(())
    }
}

#[test]
fn ga_original_keeps_children_shorter_than_max_len() {
    // Longer is better: children press against max_len 12.
    let limits = Limits::new(4, 12, 30).unwrap();
    let s = GaSettings {
        population: 30,
        elitism: 4,
        initial_length: 8,
        ..spaceship::paper_ga()
    };
    let mut eval = Lengths::default();
    Ga::<Spaceship>::new(s, limits, 6)
        .unwrap()
        .run(&mut eval, &Budget::generations(20), &mut Silent)
        .unwrap();
    let (initial, children) = eval.0.split_at(30);
    assert!(initial.iter().all(|&len| len == 8), "{initial:?}");
    assert!(children.iter().all(|&len| (4..12).contains(&len)));
    assert!(children.contains(&11));
    // The weighted operators keep genomes within the limits, max_len included.
    let mut eval = Lengths::default();
    let weighted = GaSettings {
        operators: OperatorVariant::Weighted,
        ..s
    };
    Ga::<Spaceship>::new(weighted, limits, 6)
        .unwrap()
        .run(&mut eval, &Budget::generations(20), &mut Silent)
        .unwrap();
    assert!(eval.0.contains(&12));
    assert!(eval.0.iter().all(|&len| (4..=12).contains(&len)));
}

#[test]
fn ga_original_drops_failed_crossovers() {
    // Genomes of the root alone, and only crossover: it never finds a gene to exchange.
    // The weighted GA copies the parents; the original's gives no children and breeds
    // again, until it gives up.
    let s = GaSettings {
        population: 6,
        elitism: 2,
        initial_length: 1,
        mutation_probability: 0.0,
        ..small_ga()
    };
    let limits = Limits::new(1, 10, 10).unwrap();
    let mut eval = FnEvaluator(|g: &Genome<Spaceship>| g.len() as f64);
    let weighted = GaSettings {
        operators: OperatorVariant::Weighted,
        ..s
    };
    let r = Ga::<Spaceship>::new(weighted, limits, 1).unwrap().run(
        &mut eval,
        &Budget::generations(3),
        &mut Silent,
    );
    assert!(r.is_ok());
    let err = Ga::<Spaceship>::new(s, limits, 1)
        .unwrap()
        .run(&mut eval, &Budget::generations(3), &mut Silent)
        .unwrap_err();
    let OptimizeError::Settings(err) = err else {
        panic!("{err}");
    };
    assert_eq!(err.field, "limits", "{err}");
    assert!(
        err.to_string().contains("10 000 breedings did not fill"),
        "{err}"
    );
}

#[test]
fn ga_original_tournament_never_draws_the_worst() {
    // Two individuals, no elite, tournaments of one, only alter: every child is a copy of
    // a parent with new parameters, the same tree. The roulette gives the worst weight 0,
    // and the original's tournament never draws it: both children are the best's tree.
    let shape = |g: &Genome<Spaceship>| -> Vec<(u32, Option<u32>)> {
        g.genes().map(|v| (v.kind(), v.parent())).collect()
    };
    let s = GaSettings {
        population: 2,
        elitism: 0,
        initial_length: 12,
        tournament: 1,
        mutation_probability: 1.0,
        grow_weight: 0.0,
        cut_weight: 0.0,
        alter_weight: 1.0,
        ..small_ga()
    };
    let limits = Limits::new(1, 100, 30).unwrap();
    let mut worst_bred = [0, 0];
    for (v, operators) in OperatorVariant::ALL.into_iter().enumerate() {
        let s = GaSettings { operators, ..s };
        for seed in 0..20 {
            let mut eval = FnEvaluator(|g: &Genome<Spaceship>| {
                g.words().iter().map(|&w| f64::from(w)).sum::<f64>()
            });
            let mut ga = Ga::<Spaceship>::new(s, limits, seed).unwrap();
            ga.run(&mut eval, &Budget::generations(0), &mut Silent)
                .unwrap();
            let first = ga.checkpoint();
            if first.fitness[0] == first.fitness[1] {
                continue;
            }
            let (best, worst) = if first.fitness[0] > first.fitness[1] {
                (0, 1)
            } else {
                (1, 0)
            };
            let (best, worst) = (
                shape(&first.population[best]),
                shape(&first.population[worst]),
            );
            if best == worst {
                continue;
            }
            ga.run(&mut eval, &Budget::generations(1), &mut Silent)
                .unwrap();
            for child in &ga.checkpoint().population {
                worst_bred[v] += usize::from(shape(child) == worst);
            }
        }
    }
    assert_eq!(worst_bred[1], 0);
    assert!(worst_bred[0] > 3, "{worst_bred:?}");
}

/// Two objectives of a spaceship: its length (maximized) and its number of wings
/// (minimized).
struct LongFewWings;

impl MultiEvaluator<Spaceship> for LongFewWings {
    fn senses(&self) -> &[Sense] {
        &[Sense::Maximize, Sense::Minimize]
    }

    fn evaluate(
        &mut self,
        genomes: &[Genome<Spaceship>],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        for (g, o) in genomes.iter().zip(out.chunks_exact_mut(2)) {
            let wings = g.genes().filter(|v| g.node(*v).name == "Wing").count();
            o.copy_from_slice(&[g.len() as f64, wings as f64]);
        }
        Ok(())
    }
}

#[test]
fn multi_ga_breeds_with_the_original_rules() {
    let settings = MultiGaSettings {
        ga: GaSettings {
            population: 24,
            elitism: 4,
            initial_length: 10,
            ..spaceship::paper_ga()
        },
        ..MultiGaSettings::thesis()
    };
    let limits = Limits::new(4, 14, 30).unwrap();
    let run = || {
        let mut ga = MultiGa::<Spaceship>::new(settings.clone(), limits, 3).unwrap();
        ga.run(&mut LongFewWings, &Budget::generations(6), &mut Silent)
            .unwrap();
        ga.checkpoint()
    };
    let (a, b) = (threads(1, run), threads(2, run));
    let (fa, fb) = (&a.progress.record, &b.progress.record);
    assert!(a.population == b.population && fa.archive.len() == fb.archive.len());
    assert!(a.population.iter().all(|g| (4..14).contains(&g.len())));
    assert!(a.population.iter().any(|g| g.len() == 13));
}

#[test]
fn ga_survives_nan_fitness() {
    let mut ga = Ga::<City>::new(small_ga(), city::PAPER_LIMITS, 2).unwrap();
    let r = ga
        .run(
            &mut Poisoned(Skyline::new(), 0),
            &Budget::generations(10),
            &mut Silent,
        )
        .unwrap();
    assert!(r.best_fitness.is_finite() && r.best_fitness > initial_best(&r));
    assert!(r.history.iter().all(|h| h.mean.is_finite()));
    // All NaN: nothing breaks, the best stays NaN.
    let mut ga = Ga::<City>::new(small_ga(), city::PAPER_LIMITS, 2).unwrap();
    let r = ga
        .run(
            &mut FnEvaluator(|_: &Genome<City>| f64::NAN),
            &Budget::generations(3),
            &mut Silent,
        )
        .unwrap();
    assert!(r.best_fitness.is_nan());
    // +inf is the best value there is.
    let mut ga = Ga::<City>::new(small_ga(), city::PAPER_LIMITS, 2).unwrap();
    let r = ga
        .run(
            &mut FnEvaluator(|g: &Genome<City>| {
                if g.len().is_multiple_of(7) {
                    f64::INFINITY
                } else {
                    g.len() as f64
                }
            }),
            &Budget::generations(3),
            &mut Silent,
        )
        .unwrap();
    assert_eq!(r.best_fitness, f64::INFINITY);
}

#[test]
fn ga_settings_are_validated() {
    let check = |s: GaSettings, field: &str| {
        let e = s.validate().unwrap_err();
        assert_eq!(e.field, field, "{e}");
        assert!(matches!(
            Ga::<City>::new(s, city::PAPER_LIMITS, 0),
            Err(OptimizeError::Settings(_))
        ));
    };
    let d = GaSettings::default();
    check(GaSettings { population: 1, ..d }, "population");
    check(GaSettings { elitism: 200, ..d }, "elitism");
    check(
        GaSettings {
            initial_length: 0,
            ..d
        },
        "initial_length",
    );
    check(
        GaSettings {
            mutation_probability: 1.5,
            ..d
        },
        "mutation_probability",
    );
    check(
        GaSettings {
            mutation_probability: f64::NAN,
            ..d
        },
        "mutation_probability",
    );
    check(
        GaSettings {
            cut_weight: -1.0,
            ..d
        },
        "cut_weight",
    );
    check(
        GaSettings {
            grow_weight: 0.0,
            cut_weight: 0.0,
            alter_weight: 0.0,
            ..d
        },
        "alter_weight",
    );
    check(GaSettings { tournament: 0, ..d }, "tournament");
    for s in [
        spaceship::paper_ga(),
        generators::tree::paper_ga(),
        city::paper_ga(),
        d,
    ] {
        s.validate().unwrap();
    }
    let parsed: GaSettings = serde_json::from_str(r#"{"population": 50}"#).unwrap();
    assert_eq!(
        parsed,
        GaSettings {
            population: 50,
            ..d
        }
    );
    assert!(serde_json::from_str::<GaSettings>(r#"{"populaton": 50}"#).is_err());
    // The operators by name; the window [min_len, max_len) must hold a length.
    let parsed: GaSettings =
        serde_json::from_str(r#"{"operators": "original", "cross_array_index": true}"#).unwrap();
    assert_eq!(
        (parsed.operators, parsed.cross_array_index),
        (OperatorVariant::Original, true)
    );
    let err = serde_json::from_str::<GaSettings>(r#"{"operators": "paper"}"#).unwrap_err();
    assert!(
        err.to_string()
            .contains("expected `weighted` or `original`"),
        "{err}"
    );
    let no_window = Ga::<City>::new(parsed, Limits::new(5, 5, 8).unwrap(), 0).unwrap_err();
    assert!(
        no_window.to_string().starts_with("limits.max_len = 5"),
        "{no_window}"
    );
    let weighted = GaSettings {
        operators: OperatorVariant::Weighted,
        ..parsed
    };
    assert!(Ga::<City>::new(weighted, Limits::new(5, 5, 8).unwrap(), 0).is_ok());
}

#[test]
fn ga_paper_settings_are_the_original_configurations() {
    // run/experiments/<scene>/ga.cfg: population_size, elitism, initial_genome_length,
    // max_generations, basic_prob, grow_prob / cut_prob / permutate_prob,
    // tournament_size.
    let row = |s: GaSettings| {
        (
            s.population,
            s.elitism,
            s.initial_length,
            s.generations,
            s.mutation_probability,
            [s.grow_weight, s.cut_weight, s.alter_weight],
            s.tournament,
            s.operators,
            s.cross_array_index,
        )
    };
    let original = OperatorVariant::Original;
    assert_eq!(
        row(spaceship::paper_ga()),
        (
            150,
            30,
            50,
            130,
            0.3,
            [45.0, 45.0, 10.0],
            10,
            original,
            false
        )
    );
    assert_eq!(
        row(generators::tree::paper_ga()),
        (
            200,
            30,
            250,
            1500,
            0.3,
            [35.0, 35.0, 30.0],
            10,
            original,
            false
        )
    );
    assert_eq!(
        row(city::paper_ga()),
        (
            100,
            30,
            50,
            100,
            0.3,
            [45.0, 45.0, 10.0],
            10,
            original,
            false
        )
    );
    assert_eq!(GaSettings::default().operators, OperatorVariant::Weighted);
}

#[test]
fn ga_budgets_are_honoured() {
    let s = small_ga();
    let mut ga = Ga::<City>::new(s, city::PAPER_LIMITS, 3).unwrap();
    let r = ga
        .run(&mut Skyline::new(), &Budget::generations(3), &mut Silent)
        .unwrap();
    assert_eq!((r.generations, r.stopped), (3, StopReason::Generations));
    assert_eq!(r.history.len(), 4);
    // 40 + 32k <= 150: three generations fit, a fourth would not.
    let mut ga = Ga::<City>::new(s, city::PAPER_LIMITS, 3).unwrap();
    let r = ga
        .run(&mut Skyline::new(), &Budget::evaluations(150), &mut Silent)
        .unwrap();
    assert_eq!(
        (r.generations, r.evaluations, r.stopped),
        (3, 136, StopReason::Evaluations)
    );
    let mut ga = Ga::<City>::new(s, city::PAPER_LIMITS, 3).unwrap();
    let r = ga
        .run(
            &mut Skyline::new(),
            &Budget::generations(100).and_wall_time(std::time::Duration::ZERO),
            &mut Silent,
        )
        .unwrap();
    assert_eq!((r.generations, r.stopped), (0, StopReason::WallTime));
    // The observer stops it, and sees every generation.
    let mut seen = Vec::new();
    let mut ga = Ga::<City>::new(s, city::PAPER_LIMITS, 3).unwrap();
    let r = ga
        .run(
            &mut Skyline::new(),
            &Budget::default(),
            &mut |snap: &Snapshot<'_, City>| {
                seen.push((snap.generation, snap.evaluations));
                if snap.generation == 2 {
                    Control::Stop
                } else {
                    Control::Continue
                }
            },
        )
        .unwrap();
    assert_eq!((r.generations, r.stopped), (2, StopReason::Observer));
    assert_eq!(seen, [(0, 40), (1, 72), (2, 104)]);
}

/// Small SMC settings of every variant and order.
fn small_smcs() -> impl Iterator<Item = SmcSettings> {
    SmcVariant::ALL.into_iter().flat_map(|variant| {
        [Order::Chromosome, Order::Stochastic].map(|order| SmcSettings {
            particles: 40,
            steps: 12,
            variant,
            ..city::paper_smc(order)
        })
    })
}

#[test]
fn smc_and_sosmc_improve_on_the_axiom() {
    for s in small_smcs() {
        for seed in [1, 2, 3] {
            let r = Smc::<City>::new(s, city::PAPER_LIMITS, seed)
                .unwrap()
                .run(&mut Skyline::new(), &s.budget(), &mut Silent)
                .unwrap();
            assert!(
                r.best_fitness >= initial_best(&r) + 2.0,
                "{s:?} {seed}: {r:?}"
            );
            assert!(r.history.last().unwrap().mean > r.history[0].mean);
            let r = Smc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, seed)
                .unwrap()
                .run(&mut BoxTarget::new(), &s.budget(), &mut Silent)
                .unwrap();
            assert!(r.best_fitness > initial_best(&r), "{s:?} {seed}: {r:?}");
        }
    }
}

#[test]
fn smc_same_seed_same_result_at_any_thread_count() {
    for s in small_smcs() {
        let run = || {
            Smc::<City>::new(s, city::PAPER_LIMITS, 5)
                .unwrap()
                .run(&mut Skyline::new(), &Budget::generations(8), &mut Silent)
                .unwrap()
        };
        same_result(&threads(1, run), &threads(2, run));
    }
}

#[test]
fn smc_resume_equals_uninterrupted() {
    for s in small_smcs() {
        let full = Smc::<City>::new(s, city::PAPER_LIMITS, 4)
            .unwrap()
            .run(&mut Skyline::new(), &Budget::generations(10), &mut Silent)
            .unwrap();
        let mut first = Smc::<City>::new(s, city::PAPER_LIMITS, 4).unwrap();
        first
            .run(&mut Skyline::new(), &Budget::generations(3), &mut Silent)
            .unwrap();
        let json = serde_json::to_string(&first.checkpoint()).unwrap();
        let state: SmcState<City> = serde_json::from_str(&json).unwrap();
        let resumed = Smc::resume(state)
            .unwrap()
            .run(&mut Skyline::new(), &Budget::generations(10), &mut Silent)
            .unwrap();
        same_result(&full, &resumed);
    }
}

#[test]
fn smc_survives_nan_fitness_and_honours_budgets() {
    for s in small_smcs() {
        let r = Smc::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(&mut Poisoned(Skyline::new(), 0), &s.budget(), &mut Silent)
            .unwrap();
        assert!(
            r.best_fitness.is_finite() && r.best_fitness > initial_best(&r),
            "{s:?}: {r:?}"
        );
        let r = Smc::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(&mut Skyline::new(), &Budget::evaluations(130), &mut Silent)
            .unwrap();
        assert_eq!(
            (r.generations, r.evaluations, r.stopped),
            (2, 120, StopReason::Evaluations)
        );
    }
    let bad = SmcSettings {
        particles: 0,
        ..SmcSettings::default()
    };
    assert_eq!(bad.validate().unwrap_err().field, "particles");
    let bad = SmcSettings {
        max_grows_per_step: 0,
        ..SmcSettings::default()
    };
    assert!(matches!(
        Smc::<City>::new(bad, city::PAPER_LIMITS, 0),
        Err(OptimizeError::Settings(e)) if e.field == "max_grows_per_step"
    ));
    let bad = SmcSettings {
        step_back_probability: 1.5,
        ..city::paper_smc(Order::Chromosome)
    };
    assert_eq!(bad.validate().unwrap_err().field, "step_back_probability");
    let parsed: SmcSettings = serde_json::from_str(r#"{"order": "stochastic"}"#).unwrap();
    assert_eq!(
        parsed,
        SmcSettings {
            order: Order::Stochastic,
            ..SmcSettings::default()
        }
    );
    assert!(serde_json::from_str::<SmcSettings>(r#"{"order": "random"}"#).is_err());
    let err = serde_json::from_str::<SmcSettings>(r#"{"variant": "paper"}"#).unwrap_err();
    assert!(
        err.to_string().contains("`original` or `generative`"),
        "{err}"
    );
}

fn small_mcmc(variant: McmcVariant) -> McmcSettings {
    McmcSettings {
        variant,
        chains: 16,
        iterations: 30,
        initial_length: 30,
        ..city::paper_rjmcmc()
    }
}

const VARIANTS: [McmcVariant; 2] = [McmcVariant::Original, McmcVariant::Tempered];

#[test]
fn mcmc_improves_on_its_initial_chains() {
    // Chains move slowly: the test asks the chains' mean to rise well above where it
    // started.
    for variant in VARIANTS {
        for seed in [1, 2, 3] {
            let s = McmcSettings {
                iterations: 60,
                ..small_mcmc(variant)
            };
            let r = Mcmc::<City>::new(s, city::PAPER_LIMITS, seed)
                .unwrap()
                .run(&mut Skyline::new(), &s.budget(), &mut Silent)
                .unwrap();
            let (first, last) = (r.history[0], r.history[r.history.len() - 1]);
            assert!(
                last.mean > first.mean + 1.0,
                "{variant:?} {seed}: {first:?} {last:?}"
            );
            let r = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, seed)
                .unwrap()
                .run(&mut BoxTarget::new(), &s.budget(), &mut Silent)
                .unwrap();
            let (first, last) = (r.history[0], r.history[r.history.len() - 1]);
            assert!(
                last.mean > first.mean,
                "{variant:?} {seed}: {first:?} {last:?}"
            );
        }
    }
}

#[test]
fn mcmc_temperatures_follow_the_acceptance_targets_and_anneal() {
    let s = McmcSettings {
        anneal_interval: 2,
        ..small_mcmc(McmcVariant::Tempered)
    };
    let mut mcmc = Mcmc::<City>::new(s, city::PAPER_LIMITS, 1).unwrap();
    mcmc.run(&mut Skyline::new(), &Budget::generations(0), &mut Silent)
        .unwrap();
    let t = mcmc.temperatures().to_vec();
    let ratio = t[t.len() - 1] / t[0];
    assert!((ratio - 0.01f64.ln() / 0.7f64.ln()).abs() < 1e-9, "{t:?}");
    assert!(t.windows(2).all(|w| w[1] > w[0]));
    mcmc.run(&mut Skyline::new(), &Budget::generations(4), &mut Silent)
        .unwrap();
    let annealed = mcmc.temperatures();
    assert!((annealed[0] - t[0] / 1.1 / 1.1).abs() < 1e-12);
}

#[test]
fn mcmc_same_seed_same_result_at_any_thread_count() {
    for variant in VARIANTS {
        let run = || {
            Mcmc::<City>::new(small_mcmc(variant), city::PAPER_LIMITS, 5)
                .unwrap()
                .run(&mut Skyline::new(), &Budget::generations(10), &mut Silent)
                .unwrap()
        };
        same_result(&threads(1, run), &threads(2, run));
        let run = || {
            Mcmc::<Spaceship>::new(small_mcmc(variant), spaceship::PAPER_LIMITS, 5)
                .unwrap()
                .run(&mut BoxTarget::new(), &Budget::generations(10), &mut Silent)
                .unwrap()
        };
        same_result(&threads(1, run), &threads(2, run));
    }
}

#[test]
fn mcmc_resume_equals_uninterrupted() {
    for variant in VARIANTS {
        let s = small_mcmc(variant);
        let full = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 4)
            .unwrap()
            .run(&mut BoxTarget::new(), &Budget::generations(12), &mut Silent)
            .unwrap();
        let mut first = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 4).unwrap();
        first
            .run(&mut BoxTarget::new(), &Budget::generations(5), &mut Silent)
            .unwrap();
        let json = serde_json::to_string(&first.checkpoint()).unwrap();
        let state: McmcState<Spaceship> = serde_json::from_str(&json).unwrap();
        let mut resumed = Mcmc::resume(state).unwrap();
        let resumed_result = resumed
            .run(&mut BoxTarget::new(), &Budget::generations(12), &mut Silent)
            .unwrap();
        same_result(&full, &resumed_result);
        let mut again = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 4).unwrap();
        again
            .run(&mut BoxTarget::new(), &Budget::generations(12), &mut Silent)
            .unwrap();
        assert_eq!(again.checkpoint().chains, resumed.checkpoint().chains);
        assert_eq!(again.temperatures(), resumed.temperatures(), "{variant:?}");
    }
}

#[test]
fn mcmc_survives_nan_fitness_and_honours_budgets() {
    for variant in VARIANTS {
        let s = small_mcmc(variant);
        let r = Mcmc::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(&mut Poisoned(Skyline::new(), 0), &s.budget(), &mut Silent)
            .unwrap();
        assert!(
            r.best_fitness.is_finite() && r.best_fitness > initial_best(&r),
            "{variant:?}"
        );
        assert!(r.history.iter().all(|h| h.mean.is_finite()), "{variant:?}");
        let r = Mcmc::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(
                &mut FnEvaluator(|_: &Genome<City>| f64::NAN),
                &Budget::generations(3),
                &mut Silent,
            )
            .unwrap();
        assert!(r.best_fitness.is_nan());
        // Each iteration uses 16 evaluations, and the tempered variant up to 16 more for
        // delayed rejection.
        let step = match variant {
            McmcVariant::Original => 16,
            McmcVariant::Tempered => 32,
        };
        let mut eval = Skyline::new();
        let r = Mcmc::<City>::new(s, city::PAPER_LIMITS, 2)
            .unwrap()
            .run(&mut eval, &Budget::evaluations(200), &mut Silent)
            .unwrap();
        assert_eq!(r.stopped, StopReason::Evaluations);
        assert!(
            r.evaluations <= 200 && r.evaluations + step > 200,
            "{}",
            r.evaluations
        );
        assert_eq!(eval.genomes, r.evaluations);
    }
    let d = McmcSettings {
        variant: McmcVariant::Tempered,
        ..McmcSettings::default()
    };
    for (bad, field) in [
        (McmcSettings { chains: 0, ..d }, "chains"),
        (
            McmcSettings {
                jump_probability: -0.1,
                ..d
            },
            "jump_probability",
        ),
        (
            McmcSettings {
                anneal_factor: 0.5,
                ..d
            },
            "anneal_factor",
        ),
        (
            McmcSettings {
                anneal_interval: 0,
                ..d
            },
            "anneal_interval",
        ),
        (
            McmcSettings {
                delayed_rejection: 99,
                ..d
            },
            "delayed_rejection",
        ),
        (
            McmcSettings {
                hot_acceptance: 1.0,
                ..d
            },
            "hot_acceptance",
        ),
        (
            McmcSettings {
                cold_acceptance: 0.8,
                ..d
            },
            "cold_acceptance",
        ),
        (
            McmcSettings {
                initial_length: 0,
                ..d
            },
            "initial_length",
        ),
    ] {
        assert_eq!(bad.validate().unwrap_err().field, field);
    }
    for s in [
        spaceship::paper_rjmcmc(),
        generators::tree::paper_rjmcmc(),
        city::paper_rjmcmc(),
    ] {
        s.validate().unwrap();
    }
    assert!(serde_json::from_str::<McmcSettings>(r#"{"chain": 3}"#).is_err());
}

/// The checkpoint of `optimizer` after one generation, with its settings' `key` (the
/// number of genomes it holds) set to `u32::MAX`, as a hand-edited or damaged file might.
fn inflated<O: Optimizer<City, Record = Best<City>>>(mut optimizer: O, key: &str) -> O::State
where
    O::State: serde::Serialize + serde::de::DeserializeOwned,
{
    optimizer
        .run(&mut Skyline::new(), &Budget::generations(1), &mut Silent)
        .unwrap();
    let mut json = serde_json::to_value(optimizer.checkpoint()).unwrap();
    json["settings"][key] = u32::MAX.into();
    serde_json::from_value(json).unwrap()
}

/// Found with the checkpoint fuzz target (`fuzz/fuzz_targets/checkpoint.rs`) on a
/// hand-made input: the state's settings made the optimizer before its genomes were
/// counted against them, so a checkpoint whose settings claim four billion genomes
/// allocated for them (the process aborted) instead of being refused.
#[test]
fn a_checkpoint_whose_settings_disagree_with_its_genomes_is_refused_before_allocating() {
    let ga = Ga::<City>::new(small_ga(), city::PAPER_LIMITS, 1).unwrap();
    let err = Ga::resume(inflated(ga, "population")).err().unwrap();
    assert!(err.to_string().contains("genomes"), "{err}");

    let smc = small_smcs().next().unwrap();
    let smc = Smc::<City>::new(smc, city::PAPER_LIMITS, 1).unwrap();
    let err = Smc::resume(inflated(smc, "particles")).err().unwrap();
    assert!(err.to_string().contains("particles"), "{err}");

    let mcmc = Mcmc::<City>::new(small_mcmc(McmcVariant::Original), city::PAPER_LIMITS, 1);
    let err = Mcmc::resume(inflated(mcmc.unwrap(), "chains"))
        .err()
        .unwrap();
    assert!(err.to_string().contains("chains"), "{err}");
}
