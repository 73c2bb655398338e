//! The two RJMCMC variants: the original's chain exponents, initial genomes and
//! settings, and the tempered variant's jumps, which never redraw a subtree that must
//! come back unchanged.

use generators::{City, Spaceship, city, spaceship};
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;

/// Chain `i`'s initial exponent in the original, `1 / (i + 1)^1.03` in `f32`.
fn exponent(i: usize) -> f32 {
    1.0 / ((i + 1) as f32).powf(1.03)
}

fn original(chains: u32, initial_length: u32) -> McmcSettings {
    McmcSettings {
        chains,
        initial_length,
        ..spaceship::paper_rjmcmc()
    }
}

/// Minus the distance of the number of emitted instances to 30.
fn instances(g: &Genome<Spaceship>) -> f64 {
    let mut v = Vec::new();
    g.derive_into(&mut v);
    -(v.len() as f64 - 30.0).abs()
}

#[test]
fn original_chains_start_at_their_exponents_with_exactly_l_genes() {
    for (chains, len) in [(12, 50), (5, 1), (5, 2), (3, 100)] {
        let mut mcmc =
            Mcmc::<Spaceship>::new(original(chains, len), spaceship::PAPER_LIMITS, 3).unwrap();
        mcmc.run(
            &mut FnEvaluator(instances),
            &Budget::generations(0),
            &mut Silent,
        )
        .unwrap();
        let state = mcmc.checkpoint();
        // Exactly L genes, even past max_len (100 here is at it, the limits ignored).
        assert!(state.chains.iter().all(|g| g.len() == len as usize));
        let want: Vec<f64> = (0..chains as usize)
            .map(|i| f64::from(exponent(i)))
            .collect();
        assert_eq!(mcmc.temperatures(), want);
        assert_eq!(state.log_priors, vec![1.0; chains as usize]);
    }
    // The city's start can take 100 lots, each its building: 201 genes at most.
    let mut mcmc = Mcmc::<City>::new(
        McmcSettings {
            chains: 4,
            initial_length: 150,
            ..city::paper_rjmcmc()
        },
        city::PAPER_LIMITS,
        1,
    )
    .unwrap();
    mcmc.run(
        &mut FnEvaluator(|g: &Genome<City>| g.len() as f64),
        &Budget::generations(0),
        &mut Silent,
    )
    .unwrap();
    assert!(mcmc.checkpoint().chains.iter().all(|g| g.len() == 150));
}

#[test]
fn original_exponents_grow_by_1_1_after_every_move() {
    let s = original(10, 20);
    let mut mcmc = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 5).unwrap();
    let mut eval = FnEvaluator(instances);
    for n in [1u64, 2, 7, 30] {
        mcmc.run(&mut eval, &Budget::generations(n), &mut Silent)
            .unwrap();
        // Swaps exchange genomes, not exponents: each position's exponent is its
        // initial one times 1.1 once per iteration, in f32.
        for (i, &t) in mcmc.temperatures().iter().enumerate() {
            let mut want = exponent(i);
            for _ in 0..n {
                want *= 1.1;
            }
            assert_eq!(t, f64::from(want), "chain {i} after {n} iterations");
        }
    }
}

#[test]
fn original_runs_reach_their_goal() {
    // 30 instances: the chains, accepting better models and ever more greedy, find it.
    for seed in [1, 2] {
        let s = McmcSettings {
            iterations: 150,
            ..original(16, 10)
        };
        let r = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, seed)
            .unwrap()
            .run(&mut FnEvaluator(instances), &s.budget(), &mut Silent)
            .unwrap();
        assert!(r.best_fitness > r.history[0].best, "{seed}: {r:?}");
        assert!(r.best_fitness >= -1.0, "{seed}: {}", r.best_fitness);
    }
}

#[test]
fn paper_settings_are_the_originals_mh_cfg() {
    let cases = [
        (spaceship::paper_rjmcmc(), 70, 250, 50),
        (generators::tree::paper_rjmcmc(), 100, 3000, 150),
        (city::paper_rjmcmc(), 50, 200, 50),
    ];
    for (s, chains, iterations, initial_length) in cases {
        assert_eq!(s.variant, McmcVariant::Original);
        assert_eq!(
            (s.chains, s.iterations, s.initial_length, s.jump_probability),
            (chains, iterations, initial_length, 0.5)
        );
        s.validate().unwrap();
    }
    assert_eq!(McmcSettings::default(), spaceship::paper_rjmcmc());
}

#[test]
fn settings_name_their_variant_and_validate_what_it_reads() {
    let parsed: McmcSettings = serde_json::from_str(r#"{"variant": "tempered"}"#).unwrap();
    assert_eq!(
        parsed,
        McmcSettings {
            variant: McmcVariant::Tempered,
            ..McmcSettings::default()
        }
    );
    let parsed: McmcSettings = serde_json::from_str(r#"{"chains": 3}"#).unwrap();
    assert_eq!(parsed.variant, McmcVariant::Original);
    let json = serde_json::to_string(&generators::tree::paper_rjmcmc()).unwrap();
    assert!(json.contains(r#""variant":"original""#), "{json}");
    assert!(serde_json::from_str::<McmcSettings>(r#"{"variant": "talton"}"#).is_err());
    // The tempered variant's own fields bind it only.
    let odd = McmcSettings {
        hot_acceptance: 1.0,
        anneal_interval: 0,
        ..McmcSettings::default()
    };
    odd.validate().unwrap();
    let err = McmcSettings {
        variant: McmcVariant::Tempered,
        ..odd
    }
    .validate()
    .unwrap_err();
    assert_eq!(err.field, "anneal_interval");
    for variant in [McmcVariant::Original, McmcVariant::Tempered] {
        let d = McmcSettings {
            variant,
            ..McmcSettings::default()
        };
        for (bad, field) in [
            (McmcSettings { chains: 0, ..d }, "chains"),
            (
                McmcSettings {
                    initial_length: 0,
                    ..d
                },
                "initial_length",
            ),
            (
                McmcSettings {
                    jump_probability: 1.5,
                    ..d
                },
                "jump_probability",
            ),
        ] {
            assert_eq!(bad.validate().unwrap_err().field, field);
        }
    }
}

#[test]
fn original_checkpoints_need_their_log_priors() {
    let s = original(6, 10);
    let mut mcmc = Mcmc::<Spaceship>::new(s, spaceship::PAPER_LIMITS, 2).unwrap();
    mcmc.run(
        &mut FnEvaluator(instances),
        &Budget::generations(3),
        &mut Silent,
    )
    .unwrap();
    let mut state = mcmc.checkpoint();
    assert_eq!(state.log_priors.len(), 6);
    state.log_priors.clear();
    let err = Mcmc::resume(state).unwrap_err();
    assert!(matches!(err, OptimizeError::Checkpoint(_)), "{err}");
}

generator! {
    /// Every link has probability 1; `Leaf` has a parameter, `Mid` none.
    pub Fixed {
        axiom Start;
        node Start { children { a: Leaf = 1.0, b: Mid = 1.0 } }
        node Mid { children { c: Leaf = 1.0 } }
        node Leaf {
            params { x: f32 ~ uniform(0.0, 1.0) }
            derive(s) { s.resize(vec3(x, 1.0, 1.0)).emit(CUBE); }
        }
    }
}

/// Records every genome it scores, which it scores by its first instance's width.
#[derive(Default)]
struct Recorder(Vec<Genome<Fixed>>);

impl Evaluator<Fixed> for Recorder {
    fn evaluate(
        &mut self,
        genomes: &[Genome<Fixed>],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        let mut v = Vec::new();
        for (g, o) in genomes.iter().zip(out) {
            self.0.push(g.clone());
            g.derive_into(&mut v);
            *o = v
                .first()
                .map_or(0.0, |i| f64::from(i.transform.matrix3.x_axis.x));
        }
        Ok(())
    }
}

#[test]
fn tempered_jumps_never_redraw_what_must_come_back_unchanged() {
    // Cutting Start.a or Mid.c and redrawing it gives the same leaf with the same
    // parameter back: a jump there would only cost an evaluation. Start.b is a jump:
    // the leaf below Mid is redrawn. So every proposal differs from its chain.
    let s = McmcSettings {
        variant: McmcVariant::Tempered,
        chains: 12,
        initial_length: 4,
        jump_probability: 1.0,
        delayed_rejection: 0,
        ..city::paper_rjmcmc()
    };
    let limits = Limits::new(1, 10, 10).unwrap();
    let mut mcmc = Mcmc::<Fixed>::new(s, limits, 9).unwrap();
    let mut rec = Recorder::default();
    for n in 1..=5 {
        mcmc.run(&mut rec, &Budget::generations(n - 1), &mut Silent)
            .unwrap();
        let chains = mcmc.checkpoint().chains;
        rec.0.clear();
        mcmc.run(&mut rec, &Budget::generations(n), &mut Silent)
            .unwrap();
        assert_eq!(rec.0.len(), chains.len());
        for (i, (chain, proposal)) in chains.iter().zip(&rec.0).enumerate() {
            assert_ne!(chain, proposal, "iteration {n}, chain {i}: {chain}");
        }
    }
}
