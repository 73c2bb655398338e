//! Property tests: any sequence of operators keeps genomes valid and within their limits,
//! they derive without panicking, and JSON round-trips them exactly.

mod support {
    pub mod city_expanded;
    pub mod spaceship_expanded;
}

use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::genome::{Genome, GenomeSet, Limits};
use shapegen_runtime::ops::Operators;
use shapegen_runtime::{Grammar, Instance};
use support::city_expanded::City;
use support::spaceship_expanded::Spaceship;

/// Operations applied per case; with the case counts below, each grammar sees well over
/// 50 000 operations.
const OPS_PER_CASE: usize = 1000;
const CASES: u32 = 56;
const POPULATION: usize = 6;

/// Checks one genome fully: layout, limits, derivation.
fn check<G: Grammar>(g: &Genome<G>, limits: &Limits, out: &mut Vec<Instance>) {
    if let Err(e) = g.validate() {
        panic!("invalid genome: {e}\n{g:?}");
    }
    if let Err(e) = g.validate_limits(limits) {
        panic!("limits broken: {e}\n{g:?}");
    }
    g.derive_into(out);
    assert!(out.iter().all(|i| i.transform.is_finite()));
}

/// Runs `ops` operations drawn from `codes` on a population of random genomes.
fn run_sequence<G: Grammar>(seed: u64, limits: Limits, initial_len: u32, codes: &[u8]) -> usize {
    let mut ops = Operators::<G>::new(limits).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    let mut pop: Vec<Genome<G>> = (0..POPULATION)
        .map(|_| ops.random(initial_len, &mut rng))
        .collect();
    for g in &pop {
        check(g, &limits, &mut out);
    }
    let mut done = 0;
    for &code in codes {
        let i = rng.random_range(0..POPULATION);
        match code % 20 {
            0..=5 => {
                ops.grow(&mut pop[i], &mut rng);
            }
            6..=11 => {
                ops.cut(&mut pop[i], &mut rng);
            }
            12..=14 => {
                ops.alter(&mut pop[i], &mut rng);
            }
            15..=17 => {
                let j = rng.random_range(0..POPULATION);
                if let Some((a, b)) = ops.crossover(&pop[i], &pop[j], &mut rng) {
                    check(&a, &limits, &mut out);
                    check(&b, &limits, &mut out);
                    pop[i] = a;
                    pop[j] = b;
                }
            }
            18 => ops.random_into(initial_len, &mut pop[i], &mut rng),
            _ => {
                let s = ops.sample(&mut rng);
                s.validate().unwrap();
                assert!(s.len() <= limits.max_len as usize && s.depth() <= limits.max_depth);
                if let Some(s) = ops.sample_at_least(20, &mut rng) {
                    pop[i] = s;
                }
            }
        }
        check(&pop[i], &limits, &mut out);
        done += 1;
    }
    done
}

/// Limits every random genome can meet: min_len is small enough for any depth allowed.
fn limits(min_depth: u32) -> impl Strategy<Value = Limits> {
    (1u32..=8, 0u32..=120, min_depth..=16)
        .prop_map(|(min, extra, depth)| Limits::new(min, (min + extra).max(2), depth).unwrap())
}

fn codes() -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(any::<u8>(), OPS_PER_CASE)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, ..ProptestConfig::default() })]

    #[test]
    fn spaceship_operator_sequences_stay_valid(
        seed in any::<u64>(),
        limits in limits(4),
        initial in 1u32..60,
        codes in codes(),
    ) {
        prop_assert_eq!(run_sequence::<Spaceship>(seed, limits, initial, &codes), OPS_PER_CASE);
    }

    #[test]
    fn city_operator_sequences_stay_valid(
        seed in any::<u64>(),
        limits in limits(2),
        initial in 1u32..80,
        codes in codes(),
    ) {
        prop_assert_eq!(run_sequence::<City>(seed, limits, initial, &codes), OPS_PER_CASE);
    }

    #[test]
    fn json_round_trips_exactly(seed in any::<u64>(), initial in 1u32..150) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let limits = Limits::new(1, 400, 20).unwrap();
        let mut ships = Operators::<Spaceship>::new(limits).unwrap();
        let mut cities = Operators::<City>::new(limits).unwrap();
        let ship = ships.random(initial, &mut rng);
        let city = cities.random(initial, &mut rng);
        prop_assert_eq!(&Genome::<Spaceship>::from_json(&ship.to_json()).unwrap(), &ship);
        prop_assert_eq!(&Genome::<City>::from_json(&city.to_json()).unwrap(), &city);
        let compact = serde_json::to_string(&city).unwrap();
        prop_assert_eq!(&serde_json::from_str::<Genome<City>>(&compact).unwrap(), &city);
        let set = GenomeSet::new(vec![ship.clone(), ships.sample(&mut rng), ship]);
        prop_assert_eq!(GenomeSet::<Spaceship>::from_json(&set.to_json()).unwrap(), set);
    }
}
