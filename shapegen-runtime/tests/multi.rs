//! Multi-objective ranking on hand-made populations, and the multi-objective GA on a toy
//! grammar with two conflicting objectives.

use shapegen_runtime::optimize::multi::*;
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;

const MAX: Sense = Sense::Maximize;
const MIN: Sense = Sense::Minimize;
const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

fn close(a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert!(
            x == y || (x - y).abs() < 1e-12,
            "{a:?} is not {b:?} (at {x} vs {y})"
        );
    }
}

#[test]
fn dominance_with_mixed_senses_and_nan() {
    let s = [MAX, MIN];
    assert!(dominates(&[2.0, 1.0], &[1.0, 2.0], &s));
    assert!(dominates(&[2.0, 2.0], &[1.0, 2.0], &s));
    assert!(!dominates(&[2.0, 2.0], &[2.0, 2.0], &s));
    assert!(!dominates(&[2.0, 1.0], &[3.0, 0.0], &s));
    assert!(!dominates(&[1.0, 2.0], &[2.0, 1.0], &s));
    // NaN is worse than any number, even -inf when maximized and +inf when minimized.
    assert!(dominates(&[-INF, INF], &[NAN, NAN], &s));
    assert!(dominates(&[1.0, NAN], &[NAN, NAN], &s));
    assert!(!dominates(&[NAN, NAN], &[NAN, NAN], &s));
    assert!(!dominates(&[NAN, 0.0], &[0.0, 1.0], &s));
}

/// Maximize the first objective, minimize the second. Dominance, worked out by hand:
/// 0 and 4 are equal and dominate 2, 3, 5; 1 dominates 3, 5 and 6 (equal second value,
/// NaN first); 2 dominates 3 and 5; 3 dominates 5; 6 is dominated by 1 only.
const POPULATION: [f64; 14] = [
    5.0, 1.0, //
    3.0, 0.0, //
    4.0, 2.0, //
    2.0, 3.0, //
    5.0, 1.0, //
    1.0, 4.0, //
    NAN, 0.0,
];

#[test]
fn fronts_of_a_hand_made_population() {
    let mut fronts = Fronts::default();
    fronts.sort(&POPULATION, 2, &[MAX, MIN]);
    assert_eq!(fronts.ranks(), [1, 1, 2, 3, 1, 4, 2]);
    assert_eq!(fronts.len(), 4);
    assert_eq!(fronts.front(0), [0, 1, 4]);
    assert_eq!(fronts.front(1), [2, 6]);
    assert_eq!(fronts.front(2), [3]);
    assert_eq!(fronts.front(3), [5]);
    // The buffers are reused: a smaller population after a larger one.
    fronts.sort(&[1.0, 2.0, 0.0], 1, &[MIN]);
    assert_eq!(fronts.ranks(), [2, 3, 1]);
    fronts.sort(&[], 1, &[MIN]);
    assert!(fronts.is_empty());
}

#[test]
fn crowding_of_a_hand_made_front() {
    // Both maximized; ranges 10 and 10. By the first objective the order is
    // 4, 3, 2, 1, 0: member 3 gets (10 - 3) / 10, member 2 (6 - 1) / 10, member 1
    // (3 - 0) / 10. By the second it is 0, 1, 2, 3, 4: member 1 gets (10 - 5) / 10,
    // member 2 (6 - 2) / 10, member 3 (5 - 0) / 10.
    let values = [0.0, 10.0, 1.0, 6.0, 3.0, 5.0, 6.0, 2.0, 10.0, 0.0];
    let mut out = [0.0; 5];
    let mut order = Vec::new();
    crowding(
        &values,
        2,
        &[MAX, MAX],
        &[0, 1, 2, 3, 4],
        &mut order,
        &mut out,
    );
    close(&out, &[INF, 0.8, 0.9, 1.2, INF]);
    // A sub-front, listed out of order: distances follow the list; 2 is interior in
    // both objectives, (10 - 0) / 10 each.
    let mut out = [0.0; 3];
    crowding(&values, 2, &[MAX, MAX], &[4, 0, 2], &mut order, &mut out);
    close(&out, &[INF, INF, 2.0]);
    // A constant objective adds nothing; a NaN range adds nothing.
    let values = [1.0, 7.0, 2.0, 7.0, 4.0, 7.0];
    let mut out = [0.0; 3];
    crowding(&values, 2, &[MIN, MIN], &[0, 1, 2], &mut order, &mut out);
    close(&out, &[INF, 1.0, INF]);
    let values = [1.0, NAN, 2.0, 3.0, 4.0, 1.0];
    crowding(&values, 2, &[MIN, MIN], &[0, 1, 2], &mut order, &mut out);
    close(&out, &[INF, 1.0, INF]);
}

#[test]
fn summed_and_normalized_rank_of_a_hand_made_population() {
    // First objective maximized: 1 ranks 1, 0 and 2 share 2, NaN (3) ranks 4 (largest 4).
    // Second minimized: 3 ranks 1, 0 ranks 2, 1 and 2 share 3 (largest 3).
    let values = [3.0, 1.0, 5.0, 2.0, 3.0, 2.0, NAN, 0.0];
    let mut out = [0.0; 4];
    let mut order = Vec::new();
    summed_rank(&values, 2, &[MAX, MIN], false, &mut order, &mut out);
    assert_eq!(out, [4.0, 4.0, 5.0, 5.0]);
    summed_rank(&values, 2, &[MAX, MIN], true, &mut order, &mut out);
    close(
        &out,
        &[
            2.0 / 4.0 + 2.0 / 3.0,
            1.0 / 4.0 + 3.0 / 3.0,
            2.0 / 4.0 + 3.0 / 3.0,
            4.0 / 4.0 + 1.0 / 3.0,
        ],
    );
    // All equal: everyone ranks 1.
    let mut out = [0.0; 3];
    summed_rank(&[NAN, NAN, NAN], 1, &[MAX], true, &mut order, &mut out);
    assert_eq!(out, [1.0, 1.0, 1.0]);
}

#[test]
fn weighted_sum_orients_and_skips_zero_weights() {
    let values = [2.0, 3.0, NAN, 1.0, 4.0, 0.0, 4.0, 4.0, INF];
    let mut out = [0.0; 3];
    weighted_sum(&values, 3, &[MAX, MIN, MAX], &[1.0, 2.0, 0.0], &mut out);
    assert_eq!(out, [-4.0, -7.0, -4.0]);
    weighted_sum(&values, 3, &[MAX, MIN, MAX], &[1.0, 2.0, 1.0], &mut out);
    assert!(out[0].is_nan());
    assert_eq!(&out[1..], [-7.0, INF]);
}

#[test]
fn clones_lose_the_penalty_except_the_first() {
    let values = [1.0, NAN, 0.0, 2.0, 1.0, NAN, -0.0, 2.0, 0.0, 2.0, 1.0, 3.0];
    let mut fitness = [5.0; 6];
    penalize_clones(
        &values,
        2,
        20.0,
        &mut Vec::new(),
        &mut Vec::new(),
        &mut fitness,
    );
    assert_eq!(fitness, [5.0, 5.0, -15.0, -15.0, -15.0, 5.0]);
}

#[test]
fn selection_fitness_of_each_ranking() {
    let senses = [MAX, MIN];
    let mut scratch = RankScratch::default();
    let mut out = [0.0; 7];
    let pareto = Selection {
        ranking: Ranking::Pareto,
        diversity_penalty: 0.0,
    };
    selection_fitness(&pareto, &POPULATION, 2, &senses, &mut out, &mut scratch);
    // Front 1 (0, 1, 4): every member is an extreme of some objective; so are both
    // members of front 2 and the lone members of fronts 3 and 4.
    assert_eq!(out, [-0.5, -0.5, -1.5, -2.5, -0.5, -3.5, -1.5]);
    let penalized = Selection {
        diversity_penalty: 20.0,
        ..pareto.clone()
    };
    selection_fitness(&penalized, &POPULATION, 2, &senses, &mut out, &mut scratch);
    assert_eq!(out, [-0.5, -0.5, -1.5, -2.5, -20.5, -3.5, -1.5]);
    let summed = Selection {
        ranking: Ranking::SummedRank,
        diversity_penalty: 1.0,
    };
    selection_fitness(&summed, &POPULATION, 2, &senses, &mut out, &mut scratch);
    // First objective: 0, 4 rank 1; 2 ranks 3; 1 4; 3 5; 5 6; 6 (NaN) 7. Second: 1, 6
    // rank 1; 0, 4 3; 2 5; 3 6; 5 7.
    assert_eq!(out, [-4.0, -5.0, -8.0, -11.0, -5.0, -13.0, -8.0]);
    let weighted = Selection {
        ranking: Ranking::WeightedSum {
            weights: vec![1.0, 1.0],
        },
        diversity_penalty: 0.0,
    };
    selection_fitness(&weighted, &POPULATION, 2, &senses, &mut out, &mut scratch);
    assert_eq!(&out[..6], [4.0, 3.0, 2.0, -1.0, 4.0, -3.0]);
    assert!(out[6].is_nan());
    // Within a front, a larger crowding distance ranks higher, below the front above.
    let line = [0.0, 10.0, 1.0, 6.0, 3.0, 5.0, 6.0, 2.0, 10.0, 0.0];
    let mut out = [0.0; 5];
    selection_fitness(&pareto, &line, 2, &[MAX, MAX], &mut out, &mut scratch);
    close(
        &out,
        &[
            -0.5,
            -1.0 + 0.8 / 3.6,
            -1.0 + 0.9 / 3.8,
            -1.0 + 1.2 / 4.4,
            -0.5,
        ],
    );
    assert_eq!(pareto_fitness(3, 0.0), -3.0);
    assert!(pareto_fitness(3, 10.0) < pareto_fitness(3, INF));
    assert!(pareto_fitness(2, 0.0) > pareto_fitness(3, INF));
}

#[test]
fn settings_validation_names_the_field() {
    assert_eq!(MultiGaSettings::thesis().validate(), Ok(()));
    assert_eq!(MultiGaSettings::default(), MultiGaSettings::thesis());
    let t = MultiGaSettings::thesis;
    let cases = [
        (MultiGaSettings { archive: 0, ..t() }, "archive"),
        (
            MultiGaSettings {
                selection: Selection {
                    ranking: Ranking::Pareto,
                    diversity_penalty: -1.0,
                },
                ..t()
            },
            "selection.diversity_penalty",
        ),
        (
            MultiGaSettings {
                selection: Selection {
                    ranking: Ranking::Pareto,
                    diversity_penalty: NAN,
                },
                ..t()
            },
            "selection.diversity_penalty",
        ),
        (
            MultiGaSettings {
                selection: Selection {
                    ranking: Ranking::WeightedSum {
                        weights: vec![0.0, 0.0],
                    },
                    diversity_penalty: 0.0,
                },
                ..t()
            },
            "selection.weights",
        ),
        (
            MultiGaSettings {
                selection: Selection {
                    ranking: Ranking::WeightedSum {
                        weights: vec![1.0, INF],
                    },
                    diversity_penalty: 0.0,
                },
                ..t()
            },
            "selection.weights",
        ),
        (
            MultiGaSettings {
                ga: GaSettings {
                    elitism: 300,
                    ..t().ga
                },
                ..t()
            },
            "elitism",
        ),
    ];
    let limits = Limits::new(1, 30, 30).unwrap();
    for (settings, field) in cases {
        assert_eq!(settings.validate().unwrap_err().field, field);
        match MultiGa::<Chain>::new(settings, limits, 1) {
            Err(OptimizeError::Settings(e)) => assert_eq!(e.field, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    // Weights must be one per objective of the evaluator.
    let settings = MultiGaSettings {
        selection: Selection {
            ranking: Ranking::WeightedSum { weights: vec![1.0] },
            diversity_penalty: 0.0,
        },
        ..small()
    };
    let mut ga = MultiGa::<Chain>::new(settings, limits, 1).unwrap();
    match ga.run(
        &mut LengthWidth::new(),
        &Budget::generations(1),
        &mut Silent,
    ) {
        Err(OptimizeError::Settings(e)) => assert_eq!(e.field, "selection.weights"),
        other => panic!("{other:?}"),
    }
}

generator! {
    /// A chain of blocks of random widths.
    pub Chain {
        axiom Seg;
        node Seg {
            params { width: f32 ~ uniform(0.1, 2.0) }
            children { next: Seg = 0.5 }
            derive(s) {
                s.with_size(vec3(width, 1.0, 1.0)).emit(CUBE);
                if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
            }
        }
    }
}

/// Two conflicting objectives: few blocks (minimized), much total width (maximized).
/// The true front: `n` blocks all 2 wide, for every `n`.
struct LengthWidth {
    instances: Vec<Instance>,
    calls: u64,
    genomes: u64,
}

impl LengthWidth {
    fn new() -> Self {
        LengthWidth {
            instances: Vec::new(),
            calls: 0,
            genomes: 0,
        }
    }
}

impl MultiEvaluator<Chain> for LengthWidth {
    fn senses(&self) -> &[Sense] {
        &[MIN, MAX]
    }

    fn evaluate(
        &mut self,
        genomes: &[Genome<Chain>],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        self.calls += 1;
        self.genomes += genomes.len() as u64;
        for (g, o) in genomes.iter().zip(out.chunks_exact_mut(2)) {
            g.derive_into(&mut self.instances);
            let width: f32 = self
                .instances
                .iter()
                .map(|i| i.transform.matrix3.x_axis.length())
                .sum();
            o[0] = self.instances.len() as f64;
            o[1] = f64::from(width);
        }
        Ok(())
    }
}

fn small() -> MultiGaSettings {
    MultiGaSettings {
        ga: GaSettings {
            population: 40,
            elitism: 4,
            initial_length: 8,
            generations: 25,
            mutation_probability: 0.3,
            ..MultiGaSettings::thesis().ga
        },
        archive: 20,
        ..MultiGaSettings::thesis()
    }
}

/// Hypervolume of (blocks, width) points against the reference (31 blocks, width 0).
fn hypervolume(front: &[Vec<f64>]) -> f64 {
    let mut points: Vec<(f64, f64)> = front.iter().map(|v| (31.0 - v[0], v[1])).collect();
    points.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (mut area, mut top) = (0.0, 0.0);
    for (x, y) in points {
        if y > top {
            area += x * (y - top);
            top = y;
        }
    }
    area
}

fn values(front: &[Member<Chain>]) -> Vec<Vec<f64>> {
    front.iter().map(|m| m.values.clone()).collect()
}

fn run(settings: MultiGaSettings, seed: u64, generations: u64) -> MultiResult<Chain> {
    let limits = Limits::new(1, 30, 30).unwrap();
    let mut ga = MultiGa::<Chain>::new(settings, limits, seed).unwrap();
    ga.run(
        &mut LengthWidth::new(),
        &Budget::generations(generations),
        &mut Silent,
    )
    .unwrap()
}

/// The result without wall-clock times.
fn timeless(r: &MultiResult<Chain>) -> impl PartialEq + std::fmt::Debug {
    let history: Vec<_> = r
        .history
        .iter()
        .map(|h| {
            let best: Vec<u64> = h.best.iter().map(|b| b.to_bits()).collect();
            (h.generation, h.evaluations, h.front, best)
        })
        .collect();
    let front: Vec<_> = r
        .front
        .iter()
        .map(|m| {
            (
                m.genome.clone(),
                m.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            )
        })
        .collect();
    (front, history, r.evaluations, r.generations, r.stopped)
}

#[test]
fn multi_ga_improves_on_its_initial_front_with_every_ranking() {
    let rankings = [
        Ranking::Pareto,
        Ranking::SummedRank,
        Ranking::NormalizedSummedRank,
        Ranking::WeightedSum {
            weights: vec![1.0, 1.0],
        },
    ];
    for ranking in rankings {
        let limits = Limits::new(1, 30, 30).unwrap();
        let settings = MultiGaSettings {
            selection: Selection {
                ranking: ranking.clone(),
                diversity_penalty: 20.0,
            },
            ..small()
        };
        let mut ga = MultiGa::<Chain>::new(settings, limits, 11).unwrap();
        let mut initial = Vec::new();
        let mut observer = |s: &MultiSnapshot<'_, Chain>| {
            if s.generation == 0 {
                initial = values(s.front);
            }
            Control::Continue
        };
        let mut ev = LengthWidth::new();
        let result = ga
            .run(&mut ev, &Budget::generations(25), &mut observer)
            .unwrap();
        let (before, after) = (hypervolume(&initial), hypervolume(&values(&result.front)));
        assert!(after > before * 1.1, "{ranking:?}: {before} -> {after}");
        // Everything in the archive is mutually non-dominated and distinct.
        for a in &result.front {
            for b in &result.front {
                assert!(!dominates(&a.values, &b.values, &[MIN, MAX]), "{ranking:?}");
            }
        }
        assert!(result.front.len() <= 20);
        // Initial population once, then only the 36 children per generation, in one call.
        assert_eq!(ev.calls, 26);
        assert_eq!(ev.genomes, 40 + 25 * 36);
        assert_eq!(result.evaluations, ev.genomes);
        let last = result.history.last().unwrap();
        assert_eq!(last.front as usize, result.front.len());
        // The best values so far: 1 block is the fewest; the widest is in the archive.
        assert_eq!(last.best[0], 1.0);
        let widest = result.front.iter().map(|m| m.values[1]).fold(0.0, f64::max);
        assert_eq!(last.best[1], widest);
    }
}

#[test]
fn multi_ga_pareto_front_approaches_the_true_front() {
    let result = run(small(), 5, 40);
    // On the true front every block is 2 wide, and random blocks are 1.05 wide on
    // average; after 40 generations the archive spreads over the lengths from 1 to at
    // least 25, every member at least 1.5 wide per block.
    assert!(result.front.len() >= 15, "{}", result.front.len());
    for m in &result.front {
        assert!(m.values[1] >= 1.5 * m.values[0], "{:?}", m.values);
    }
    let lengths = result.front.iter().map(|m| m.values[0]);
    assert_eq!(lengths.clone().fold(INF, f64::min), 1.0);
    assert!(lengths.fold(0.0, f64::max) >= 25.0);
}

#[test]
fn multi_ga_with_one_weighted_objective_acts_like_the_ga() {
    struct Width;
    impl MultiEvaluator<Chain> for Width {
        fn senses(&self) -> &[Sense] {
            &[MAX]
        }
        fn evaluate(
            &mut self,
            genomes: &[Genome<Chain>],
            out: &mut [f64],
        ) -> Result<(), EvaluateError> {
            for (g, o) in genomes.iter().zip(out) {
                *o = -(g.len() as f64 - 12.0).abs();
            }
            Ok(())
        }
    }
    let settings = MultiGaSettings {
        selection: Selection {
            ranking: Ranking::WeightedSum { weights: vec![1.0] },
            diversity_penalty: 0.0,
        },
        ..small()
    };
    let limits = Limits::new(1, 30, 30).unwrap();
    let mut ga = MultiGa::<Chain>::new(settings.clone(), limits, 3).unwrap();
    let result = ga
        .run(&mut Width, &Budget::generations(20), &mut Silent)
        .unwrap();
    // With one objective the archive is the single best model.
    assert_eq!(result.front.len(), 1);
    assert_eq!(result.front[0].genome.len(), 12);
    let mut single = Ga::<Chain>::new(settings.ga, limits, 3).unwrap();
    let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 12.0).abs());
    let r = single
        .run(&mut eval, &Budget::generations(20), &mut Silent)
        .unwrap();
    assert_eq!(r.best_fitness, result.front[0].values[0]);
}

fn threads<T: Send>(n: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn multi_ga_same_seed_same_front_at_any_thread_count() {
    let one = threads(1, || run(small(), 9, 10));
    let two = threads(2, || run(small(), 9, 10));
    let four = threads(4, || run(small(), 9, 10));
    assert_eq!(timeless(&one), timeless(&two));
    assert_eq!(timeless(&one), timeless(&four));
    let other = run(small(), 10, 10);
    assert_ne!(timeless(&one), timeless(&other));
}

#[test]
fn multi_ga_resume_equals_uninterrupted() {
    for ranking in [Ranking::Pareto, Ranking::NormalizedSummedRank] {
        let settings = MultiGaSettings {
            selection: Selection {
                ranking,
                diversity_penalty: 20.0,
            },
            archive: 8,
            ..small()
        };
        let whole = run(settings.clone(), 4, 12);
        let limits = Limits::new(1, 30, 30).unwrap();
        let mut first = MultiGa::<Chain>::new(settings, limits, 4).unwrap();
        let mut ev = LengthWidth::new();
        first
            .run(&mut ev, &Budget::generations(5), &mut Silent)
            .unwrap();
        let json = serde_json::to_string(&first.checkpoint()).unwrap();
        let state: MultiGaState<Chain> = serde_json::from_str(&json).unwrap();
        assert_eq!(state, first.checkpoint());
        let mut resumed = MultiGa::resume(state).unwrap();
        let rest = resumed
            .run(&mut ev, &Budget::generations(12), &mut Silent)
            .unwrap();
        assert_eq!(timeless(&whole), timeless(&rest));
        assert_eq!(resumed.front(), &whole.front[..]);
    }
}

#[test]
fn multi_ga_checks_checkpoints_and_objectives() {
    let limits = Limits::new(1, 30, 30).unwrap();
    let mut ga = MultiGa::<Chain>::new(small(), limits, 2).unwrap();
    ga.run(
        &mut LengthWidth::new(),
        &Budget::generations(1),
        &mut Silent,
    )
    .unwrap();
    let mut state = ga.checkpoint();
    state.values.pop();
    assert!(matches!(
        MultiGa::resume(state),
        Err(OptimizeError::Checkpoint(_))
    ));
    struct OneObjective;
    impl MultiEvaluator<Chain> for OneObjective {
        fn senses(&self) -> &[Sense] {
            &[MAX]
        }
        fn evaluate(&mut self, _: &[Genome<Chain>], out: &mut [f64]) -> Result<(), EvaluateError> {
            out.fill(1.0);
            Ok(())
        }
    }
    assert!(matches!(
        ga.run(&mut OneObjective, &Budget::generations(2), &mut Silent),
        Err(OptimizeError::Checkpoint(_))
    ));
    struct NoObjective;
    impl MultiEvaluator<Chain> for NoObjective {
        fn senses(&self) -> &[Sense] {
            &[]
        }
        fn evaluate(&mut self, _: &[Genome<Chain>], _: &mut [f64]) -> Result<(), EvaluateError> {
            Ok(())
        }
    }
    let mut fresh = MultiGa::<Chain>::new(small(), limits, 2).unwrap();
    assert!(matches!(
        fresh.run(&mut NoObjective, &Budget::generations(2), &mut Silent),
        Err(OptimizeError::Evaluate(_))
    ));
}

#[test]
fn multi_ga_survives_nan_objectives_and_honours_budgets() {
    struct Sometimes(LengthWidth);
    impl MultiEvaluator<Chain> for Sometimes {
        fn senses(&self) -> &[Sense] {
            &[MIN, MAX]
        }
        fn evaluate(
            &mut self,
            genomes: &[Genome<Chain>],
            out: &mut [f64],
        ) -> Result<(), EvaluateError> {
            self.0.evaluate(genomes, out)?;
            for (g, o) in genomes.iter().zip(out.chunks_exact_mut(2)) {
                if g.len() % 3 == 0 {
                    o[1] = NAN;
                }
            }
            Ok(())
        }
    }
    let limits = Limits::new(1, 30, 30).unwrap();
    let mut ga = MultiGa::<Chain>::new(small(), limits, 6).unwrap();
    let r = ga
        .run(
            &mut Sometimes(LengthWidth::new()),
            &Budget::evaluations(40 + 3 * 36 + 35),
            &mut Silent,
        )
        .unwrap();
    assert_eq!(r.stopped, StopReason::Evaluations);
    assert_eq!(r.generations, 3);
    assert!(!r.front.is_empty());
    assert!(r.front.iter().all(|m| m.genome.len() % 3 != 0));
    assert!(r.front.iter().all(|m| !m.values[1].is_nan()));
    let mut stop_at_2 = |s: &MultiSnapshot<'_, Chain>| {
        if s.generation == 2 {
            Control::Stop
        } else {
            Control::Continue
        }
    };
    let mut ga = MultiGa::<Chain>::new(small(), limits, 6).unwrap();
    let r = ga
        .run(&mut LengthWidth::new(), &Budget::default(), &mut stop_at_2)
        .unwrap();
    assert_eq!((r.stopped, r.generations), (StopReason::Observer, 2));
    assert_eq!(r.history.len(), 3);
}
