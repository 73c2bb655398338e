//! Breeding one generation of a GA population: parents chosen by tournament and
//! roulette (or as [`ParentSelection`] says), mutated or crossed over, pair by pair in
//! parallel, each pair from its own random stream.

use rand::{Rng, RngExt};
use rayon::prelude::*;

use super::settings::{GaSettings, ParentSelection};
use crate::derive::Grammar;
use crate::genome::Genome;
use crate::ops::{OperatorVariant, Operators};
use crate::optimize::error::{OptimizeError, SettingsError};
use crate::optimize::fitness::{Roulette, compare, rank};
use crate::optimize::run::stream;

/// With the original's breeding, how many breeding events a pair of slots may take to
/// fill with children within the length window before the GA gives up with an error
/// (the original would loop forever).
const ORIGINAL_BREEDS_PER_PAIR: u32 = 10_000;

/// One population, the fitness it is selected on and the scores its elites keep, as a
/// generation is bred from them.
pub(crate) struct Parents<'a, G> {
    /// The population.
    pub(crate) population: &'a [Genome<G>],
    /// The higher-is-better fitness it is selected on, one value per genome.
    pub(crate) fitness: &'a [f64],
    /// Its scores, the same number per genome: the fitness itself, or the objective
    /// vectors a multi-objective selection fitness is computed from.
    pub(crate) scores: &'a [f64],
}

/// What breeding one generation of a GA population needs besides the population: the
/// settings and operators, and the seed and number of the generation being bred. The
/// [`Ga`](super::Ga) breeds its one population with it, the island model each of its islands.
pub(crate) struct Generation<'a, G> {
    /// The GA's settings.
    pub(crate) settings: &'a GaSettings,
    /// The operators, keeping to the limits.
    pub(crate) ops: &'a Operators<G>,
    /// The seed of the population's random streams.
    pub(crate) seed: u64,
    /// The number of the generation being bred (the first bred is 1).
    pub(crate) generation: u64,
}

impl<G: Grammar> Generation<'_, G> {
    /// Breeds the next generation of `parents`: copies its `elitism` best, with their
    /// scores, into `elites`, and breeds `children` (see [`Breed::children`]), each
    /// child's parent index into `from`. `order` and `roulette` are scratch.
    pub(crate) fn breed(
        &self,
        parents: Parents<'_, G>,
        order: &mut Vec<u32>,
        roulette: &mut Roulette,
        (elites, elite_scores): (&mut [Genome<G>], &mut [f64]),
        (children, from): (&mut [Genome<G>], &mut [u32]),
    ) -> Result<(), OptimizeError> {
        rank(parents.fitness, order);
        roulette.build(parents.fitness);
        let k = parents.scores.len() / parents.population.len();
        let kept = elite_scores.chunks_exact_mut(k);
        for ((elite, kept), &i) in elites.iter_mut().zip(kept).zip(order.iter()) {
            let i = i as usize;
            elite.clone_from(&parents.population[i]);
            kept.copy_from_slice(&parents.scores[i * k..(i + 1) * k]);
        }
        Breed {
            settings: self.settings,
            population: parents.population,
            fitness: parents.fitness,
            roulette,
            worst: *order.last().expect("a population of at least 2"),
        }
        .children(self.ops, self.seed, self.generation, children, from)
    }
}

/// What breeding reads: the current generation, the higher-is-better fitness it is
/// selected on (the GA's own fitness, or a multi-objective selection fitness) and the
/// roulette wheel built on that fitness.
pub(crate) struct Breed<'a, G> {
    /// Mutation probability and weights, tournament size, operator rules.
    pub(crate) settings: &'a GaSettings,
    /// The parents to choose from.
    pub(crate) population: &'a [Genome<G>],
    /// Their selection fitness, one per genome.
    pub(crate) fitness: &'a [f64],
    /// The roulette wheel built on `fitness`.
    pub(crate) roulette: &'a Roulette,
    /// The index of the worst-ranked individual, which the original's tournament never
    /// draws.
    pub(crate) worst: u32,
}

impl<G: Grammar> Breed<'_, G> {
    /// Breeds `children` in parallel, in pairs: pair `p` (children `2p` and `2p + 1`; the
    /// last pair may hold one) draws from stream (seed, `generation`, `p`), so the
    /// children never depend on the thread count. `from[i]` is set to the index of the
    /// parent child `i` was made from (the one it is a mutated copy of, or whose tree
    /// received the other parent's subtree). Fails only with the original's breeding,
    /// when [`ORIGINAL_BREEDS_PER_PAIR`] breeding events do not fill a pair with children
    /// within the length window.
    pub(crate) fn children(
        &self,
        ops: &Operators<G>,
        seed: u64,
        generation: u64,
        children: &mut [Genome<G>],
        from: &mut [u32],
    ) -> Result<(), OptimizeError> {
        debug_assert_eq!(children.len(), from.len());
        let empty = || Genome::from_parts(Vec::new(), 0);
        children
            .par_chunks_mut(2)
            .zip(from.par_chunks_mut(2))
            .enumerate()
            .try_for_each_init(
                || (ops.clone(), [empty(), empty()]),
                |(ops, spare), (pair, (children, from))| {
                    let rng = &mut stream(seed, generation, pair as u64);
                    if self.settings.operators == OperatorVariant::Original {
                        return self.original_pair(ops, children, from, spare, rng);
                    }
                    let (a, b) = match children {
                        [a, b] => (a, b),
                        [a] => (a, &mut spare[0]),
                        _ => unreachable!("chunks hold one or two children"),
                    };
                    let parents = self.pair(ops, a, b, rng);
                    from.copy_from_slice(&parents[..from.len()]);
                    Ok(())
                },
            )
    }

    /// Breeds two children into `a` and `b`, and returns the parents they were made
    /// from, in that order.
    fn pair(
        &self,
        ops: &mut Operators<G>,
        a: &mut Genome<G>,
        b: &mut Genome<G>,
        rng: &mut impl Rng,
    ) -> [u32; 2] {
        let (i1, i2) = self.parents(rng);
        let (p1, p2) = (&self.population[i1], &self.population[i2]);
        if self.mutates(rng) {
            a.clone_from(p1);
            self.mutate(ops, a, rng);
            b.clone_from(p2);
            self.mutate(ops, b, rng);
        } else if !ops.crossover_into(p1, p2, a, b, rng) {
            a.clone_from(p1);
            b.clone_from(p2);
        }
        [i1 as u32, i2 as u32]
    }

    /// Fills `slots` (one or two) as the original's `createNewGeneration` fills the
    /// generation: breeds a pair of children into `kids` (none when the crossover
    /// fails), keeps each child with `min_len <= len < max_len` in the next empty slot
    /// (swapping buffers, so nothing is allocated once warmed up), and breeds again until
    /// the slots are full. `from` gets the parent of each slot's child.
    fn original_pair(
        &self,
        ops: &mut Operators<G>,
        slots: &mut [Genome<G>],
        from: &mut [u32],
        kids: &mut [Genome<G>; 2],
        rng: &mut impl Rng,
    ) -> Result<(), OptimizeError> {
        let limits = *ops.limits();
        let fits = |g: &Genome<G>| (limits.min_len..limits.max_len).contains(&(g.len() as u32));
        let mut filled = 0;
        for _ in 0..ORIGINAL_BREEDS_PER_PAIR {
            let (i1, i2) = self.parents(rng);
            let (p1, p2) = (&self.population[i1], &self.population[i2]);
            let [c, d] = kids;
            let bred = if self.mutates(rng) {
                c.clone_from(p1);
                self.mutate(ops, c, rng);
                d.clone_from(p2);
                self.mutate(ops, d, rng);
                true
            } else {
                ops.crossover_into(p1, p2, c, d, rng)
            };
            if !bred {
                continue;
            }
            for (kid, parent) in kids.iter_mut().zip([i1, i2]) {
                if !fits(kid) {
                    continue;
                }
                std::mem::swap(kid, &mut slots[filled]);
                from[filled] = parent as u32;
                filled += 1;
                if filled == slots.len() {
                    return Ok(());
                }
            }
        }
        Err(SettingsError::new(
            "limits",
            format!("min_len {} and max_len {}", limits.min_len, limits.max_len),
            "a length window [min_len, max_len) that bred children fall in: 10 000 \
             breedings did not fill one pair of slots",
        )
        .into())
    }

    /// The two parents of a pair, chosen as [`GaSettings::selection`] says.
    fn parents(&self, rng: &mut impl Rng) -> (usize, usize) {
        match self.settings.selection {
            ParentSelection::TournamentRoulette => (self.tournament(rng), self.roulette.spin(rng)),
            ParentSelection::Tournament => (self.tournament(rng), self.tournament(rng)),
            ParentSelection::Roulette => (self.roulette.spin(rng), self.roulette.spin(rng)),
            ParentSelection::Random => {
                let n = self.population.len();
                (rng.random_range(0..n), rng.random_range(0..n))
            }
        }
    }

    /// Best of `tournament` individuals drawn uniformly with replacement (the first drawn
    /// wins ties); with the original's rules, drawn among all but the worst-ranked.
    fn tournament(&self, rng: &mut impl Rng) -> usize {
        let mut best = self.entrant(rng);
        for _ in 1..self.settings.tournament {
            let i = self.entrant(rng);
            if compare(self.fitness[i], self.fitness[best]).is_gt() {
                best = i;
            }
        }
        best
    }

    /// One tournament entrant, drawn uniformly; with the original's rules, among all but
    /// the worst-ranked individual.
    fn entrant(&self, rng: &mut impl Rng) -> usize {
        let n = self.population.len();
        match self.settings.operators {
            OperatorVariant::Weighted => rng.random_range(0..n),
            OperatorVariant::Original => {
                let i = rng.random_range(0..n - 1);
                i + usize::from(i >= self.worst as usize)
            }
        }
    }

    /// Whether a pair is mutated (rather than crossed over), with the mutation
    /// probability.
    fn mutates(&self, rng: &mut impl Rng) -> bool {
        rng.random::<f64>() < self.settings.mutation_probability
    }

    /// Which mutation to apply, grow / cut / alter by their weights.
    fn mutation(&self, rng: &mut impl Rng) -> Mutation {
        let s = self.settings;
        let r = rng.random::<f64>() * (s.grow_weight + s.cut_weight + s.alter_weight);
        if r < s.grow_weight {
            Mutation::Grow
        } else if r < s.grow_weight + s.cut_weight {
            Mutation::Cut
        } else {
            Mutation::Alter
        }
    }

    /// One mutation, grow / cut / alter by their weights.
    fn mutate(&self, ops: &mut Operators<G>, g: &mut Genome<G>, rng: &mut impl Rng) {
        match self.mutation(rng) {
            Mutation::Grow => ops.grow(g, rng),
            Mutation::Cut => ops.cut(g, rng),
            Mutation::Alter => ops.alter(g, rng),
        };
    }
}

/// The three mutations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mutation {
    Grow,
    Cut,
    Alter,
}

/// Selection and mutation rates, each on its own: statistical tests with fixed seeds,
/// tolerances stated with each (about 5 standard deviations of the estimate or more).
#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::Limits;
    use crate::testing::Chain;

    const DRAWS: usize = 100_000;

    /// A breeding context over `fitness`, with everything else from `settings`.
    fn check<R>(
        settings: GaSettings,
        fitness: &[f64],
        f: impl FnOnce(&Breed<'_, Chain>) -> R,
    ) -> R {
        let population: Vec<Genome<Chain>> = (0..fitness.len())
            .map(|i| Genome::axiom(&mut stream(1, 0, i as u64)))
            .collect();
        let mut roulette = Roulette::default();
        roulette.build(fitness);
        let mut order = Vec::new();
        rank(fitness, &mut order);
        let breed = Breed {
            settings: &settings,
            population: &population,
            fitness,
            roulette: &roulette,
            worst: *order.last().unwrap(),
        };
        f(&breed)
    }

    /// Counts of `draw` over [`DRAWS`] draws from one stream, as frequencies.
    fn frequencies(
        n: usize,
        mut draw: impl FnMut(&mut rand_chacha::ChaCha8Rng) -> usize,
    ) -> Vec<f64> {
        let rng = &mut stream(42, 1, 0);
        let mut counts = vec![0usize; n];
        for _ in 0..DRAWS {
            counts[draw(rng)] += 1;
        }
        counts.iter().map(|&c| c as f64 / DRAWS as f64).collect()
    }

    #[test]
    fn a_tournament_returns_the_best_of_its_entrants() {
        let fitness = [
            3.0,
            f64::NAN,
            7.0,
            -1.0,
            7.0,
            0.5,
            2.0,
            f64::INFINITY,
            4.0,
            1.0,
        ];
        for operators in OperatorVariant::ALL {
            for k in [1, 2, 3, 10] {
                let settings = GaSettings {
                    tournament: k,
                    operators,
                    ..GaSettings::default()
                };
                check(settings, &fitness, |breed| {
                    let rng = &mut stream(5, 2, u64::from(k));
                    for _ in 0..2_000 {
                        // The same draws, replayed: the entrants, then the winner.
                        let mut replay = rng.clone();
                        let entrants: Vec<usize> =
                            (0..k).map(|_| breed.entrant(&mut replay)).collect();
                        let winner = breed.tournament(rng);
                        let best = entrants.iter().copied().fold(entrants[0], |b, i| {
                            if compare(fitness[i], fitness[b]).is_gt() {
                                i
                            } else {
                                b
                            }
                        });
                        assert_eq!(winner, best, "{operators:?}, k = {k}: {entrants:?}");
                        // The original's never draws the worst-ranked (the NaN, index 1).
                        if operators == OperatorVariant::Original {
                            assert!(!entrants.contains(&1));
                        }
                    }
                });
            }
        }
    }

    #[test]
    fn a_tournament_of_k_picks_rank_r_as_often_as_order_statistics_say() {
        // Ten distinct values, k = 3 with replacement: the best of three uniform draws
        // has rank r (0: best) with probability ((10 - r)^3 - (9 - r)^3) / 1000.
        let fitness: Vec<f64> = (0..10).map(|i| f64::from(i) * 1.5).collect();
        let settings = GaSettings {
            tournament: 3,
            ..GaSettings::default()
        };
        let freq = check(settings, &fitness, |breed| {
            frequencies(10, |rng| breed.tournament(rng))
        });
        for (i, &got) in freq.iter().enumerate() {
            let r = 9 - i as i32;
            let want = f64::from((10 - r).pow(3) - (9 - r).pow(3)) / 1000.0;
            // The standard deviation of an estimate is at most 0.0016.
            assert!((got - want).abs() < 0.008, "index {i}: {got} vs {want}");
        }
    }

    #[test]
    fn roulette_frequencies_follow_fitness_above_the_minimum() {
        let fitness = [1.0, 2.0, 4.0, 8.0, f64::NAN, 3.0];
        // Weights f - f_min: 0, 1, 3, 7, NaN 0, 2; sum 13.
        let want = [0.0, 1.0, 3.0, 7.0, 0.0, 2.0].map(|w| w / 13.0);
        let freq = check(GaSettings::default(), &fitness, |breed| {
            frequencies(6, |rng| breed.roulette.spin(rng))
        });
        for (i, (&got, &want)) in freq.iter().zip(&want).enumerate() {
            // At most 0.0016 of standard deviation; the zero weights are never drawn.
            assert!((got - want).abs() < 0.008, "index {i}: {got} vs {want}");
            if want == 0.0 {
                assert_eq!(got, 0.0, "index {i}");
            }
        }
    }

    #[test]
    fn each_selection_scheme_draws_both_parents_at_its_rates() {
        // Five distinct values; rank r (0: best) wins a 2-tournament with probability
        // ((5 - r)^2 - (4 - r)^2) / 25; roulette weights f - f_min are 0, 4, 1, 3, 2 of 10.
        let fitness = [1.0, 5.0, 2.0, 4.0, 3.0];
        let rank_of = [4, 0, 3, 1, 2];
        let tournament = rank_of.map(|r: i32| f64::from((5 - r).pow(2) - (4 - r).pow(2)) / 25.0);
        let roulette = [0.0, 0.4, 0.1, 0.3, 0.2];
        let uniform = [0.2; 5];
        for (selection, want) in [
            (ParentSelection::TournamentRoulette, [tournament, roulette]),
            (ParentSelection::Tournament, [tournament, tournament]),
            (ParentSelection::Roulette, [roulette, roulette]),
            (ParentSelection::Random, [uniform, uniform]),
        ] {
            let settings = GaSettings {
                tournament: 2,
                selection,
                ..GaSettings::default()
            };
            check(settings, &fitness, |breed| {
                for (parent, want) in want.iter().enumerate() {
                    let freq = frequencies(5, |rng| {
                        let (a, b) = breed.parents(rng);
                        [a, b][parent]
                    });
                    for (i, (&got, &want)) in freq.iter().zip(want).enumerate() {
                        // The standard deviation of an estimate is at most 0.0016.
                        assert!(
                            (got - want).abs() < 0.008,
                            "{selection:?}, parent {parent}, index {i}: {got} vs {want}"
                        );
                    }
                }
            });
        }
        // The default draws exactly as the paper's breeding always has: a tournament,
        // then a spin of the wheel, from the same stream.
        check(GaSettings::default(), &fitness, |breed| {
            let rng = &mut stream(9, 3, 0);
            for _ in 0..1_000 {
                let mut replay = rng.clone();
                let want = (
                    breed.tournament(&mut replay),
                    breed.roulette.spin(&mut replay),
                );
                assert_eq!(breed.parents(rng), want);
            }
        });
    }

    #[test]
    fn mutation_probability_and_weights_show_at_their_rates() {
        let settings = GaSettings {
            mutation_probability: 0.3,
            grow_weight: 45.0,
            cut_weight: 35.0,
            alter_weight: 20.0,
            ..GaSettings::default()
        };
        check(settings, &[1.0, 2.0], |breed| {
            let mutated = frequencies(2, |rng| usize::from(breed.mutates(rng)));
            // Standard deviation about 0.0015.
            assert!((mutated[1] - 0.3).abs() < 0.008, "{mutated:?}");
            let kinds = frequencies(3, |rng| breed.mutation(rng) as usize);
            for (got, want) in kinds.iter().zip([0.45, 0.35, 0.20]) {
                assert!((got - want).abs() < 0.008, "{kinds:?}");
            }
        });
    }

    #[test]
    fn children_are_mutated_copies_at_the_mutation_rate() {
        // Parents of different lengths, so that a child's origin shows: with mutation
        // probability 0 every pair is crossed over (lengths add up to the parents'), with
        // 1 and only grow every child is its parent grown by at least one gene.
        let limits = Limits::new(1, 60, 60).unwrap();
        let mut ops = Operators::<Chain>::new(limits).unwrap();
        let population: Vec<Genome<Chain>> = [3, 9]
            .iter()
            .map(|&n| {
                let mut g = Genome::axiom(&mut stream(1, 0, 0));
                ops.grow_to(&mut g, n, &mut stream(1, 0, 1));
                g
            })
            .collect();
        assert_eq!([population[0].len(), population[1].len()], [3, 9]);
        let fitness = [1.0, 2.0];
        let mut roulette = Roulette::default();
        roulette.build(&fitness);
        for (p, grow) in [(0.0, 1.0), (1.0, 1.0)] {
            let settings = GaSettings {
                mutation_probability: p,
                grow_weight: grow,
                cut_weight: 0.0,
                alter_weight: 0.0,
                tournament: 2,
                ..GaSettings::default()
            };
            let breed = Breed {
                settings: &settings,
                population: &population,
                fitness: &fitness,
                roulette: &roulette,
                worst: 0,
            };
            let mut children: Vec<Genome<Chain>> =
                (0..200).map(|_| population[0].clone()).collect();
            let mut from = vec![u32::MAX; children.len()];
            breed
                .children(&ops, 3, 1, &mut children, &mut from)
                .unwrap();
            assert!(
                from.iter().all(|&f| (f as usize) < population.len()),
                "{from:?}"
            );
            for pair in children.chunks(2) {
                let lens = (pair[0].len(), pair[1].len());
                if p == 0.0 {
                    assert!([6, 12, 18].contains(&(lens.0 + lens.1)), "{lens:?}");
                } else {
                    assert!(lens.0 > 3 && lens.1 > 3, "{lens:?}");
                }
            }
        }
    }
}
