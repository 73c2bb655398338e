//! Fitness arithmetic shared by the optimizers, safe with NaN and infinities: ordering,
//! population statistics, roulette-wheel weights, and exact serde of `f64`.

use std::cmp::Ordering;

use rand::{Rng, RngExt};

/// Orders fitness values, NaN below everything (`-inf` included); NaNs are equal.
pub(crate) fn compare(a: f64, b: f64) -> Ordering {
    match (a.is_nan(), b.is_nan()) {
        (true, true) => Ordering::Equal,
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        (false, false) => a.partial_cmp(&b).unwrap_or(Ordering::Equal),
    }
}

/// Fills `order` with the indices of `fitness`, best first; ties keep index order.
pub(crate) fn rank(fitness: &[f64], order: &mut Vec<u32>) {
    order.clear();
    order.extend(0..fitness.len() as u32);
    order.sort_by(|&a, &b| compare(fitness[b as usize], fitness[a as usize]));
}

/// Index of the best value (the first of equals); `None` for an empty slice.
pub(crate) fn best_index(fitness: &[f64]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, &f) in fitness.iter().enumerate() {
        if best.is_none_or(|b| compare(f, fitness[b]) == Ordering::Greater) {
            best = Some(i);
        }
    }
    best
}

/// Mean and (population) standard deviation of the finite values; NaN when there are
/// none.
pub(crate) fn mean_std(fitness: &[f64]) -> (f64, f64) {
    let (mut n, mut sum) = (0u32, 0.0);
    for &f in fitness.iter().filter(|f| f.is_finite()) {
        n += 1;
        sum += f;
    }
    if n == 0 {
        return (f64::NAN, f64::NAN);
    }
    let mean = sum / f64::from(n);
    let var = fitness
        .iter()
        .filter(|f| f.is_finite())
        .map(|f| (f - mean) * (f - mean))
        .sum::<f64>()
        / f64::from(n);
    (mean, var.sqrt())
}

/// Roulette-wheel selection on shifted fitness: `P(i) = w_i / sum w`.
///
/// Weights: if any value is `+inf`, those individuals share the wheel equally; otherwise
/// each finite value weighs `f - f_min` (the worst finite value weighs 0), and `-inf` and
/// NaN weigh 0. When all weights are 0 (equal fitness), the wheel is uniform over the
/// non-NaN individuals, or over everyone if all are NaN.
#[derive(Clone, Debug, Default)]
pub(crate) struct Roulette {
    cum: Vec<f64>,
}

impl Roulette {
    /// Builds the wheel for `fitness`, reusing its buffer.
    pub(crate) fn build(&mut self, fitness: &[f64]) {
        let any_inf = fitness.contains(&f64::INFINITY);
        let min = fitness
            .iter()
            .copied()
            .filter(|f| f.is_finite())
            .fold(f64::INFINITY, f64::min);
        let weight = |f: f64| {
            if any_inf {
                f64::from(u8::from(f == f64::INFINITY))
            } else if f.is_finite() {
                f - min
            } else {
                0.0
            }
        };
        self.fill(fitness, weight);
        if self.total() > 0.0 && self.total().is_finite() {
            return;
        }
        let any_number = fitness.iter().any(|f| !f.is_nan());
        self.fill(fitness, |f| f64::from(u8::from(!any_number || !f.is_nan())));
    }

    fn fill(&mut self, fitness: &[f64], weight: impl Fn(f64) -> f64) {
        self.cum.clear();
        let mut total = 0.0;
        for &f in fitness {
            total += weight(f);
            self.cum.push(total);
        }
    }

    fn total(&self) -> f64 {
        self.cum.last().copied().unwrap_or(0.0)
    }

    /// Draws an index. The wheel must have been built on a non-empty population.
    pub(crate) fn spin(&self, rng: &mut impl Rng) -> usize {
        let r = rng.random::<f64>() * self.total();
        self.cum
            .partition_point(|&c| c <= r)
            .min(self.cum.len() - 1)
    }
}

/// Serde of an `f64` as its exact bit pattern, so that NaN and infinities survive JSON.
pub(crate) mod bits {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the bits.
    pub(crate) fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u64(v.to_bits())
    }

    /// Reads the bits.
    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        u64::deserialize(d).map(f64::from_bits)
    }
}

/// Serde of a `Vec<f64>` as exact bit patterns.
pub(crate) mod bits_vec {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the bits.
    pub(crate) fn serialize<S: Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|x| x.to_bits()))
    }

    /// Reads the bits.
    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Vec::<u64>::deserialize(d).map(|v| v.into_iter().map(f64::from_bits).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn nan_ranks_last_and_inf_first() {
        let f = [1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 2.0];
        let mut order = Vec::new();
        rank(&f, &mut order);
        assert_eq!(order, [2, 4, 0, 3, 1]);
        assert_eq!(best_index(&f), Some(2));
        assert_eq!(best_index(&[f64::NAN, 0.0]), Some(1));
    }

    #[test]
    fn roulette_never_picks_nan_or_worst() {
        let mut wheel = Roulette::default();
        wheel.build(&[f64::NAN, 0.0, 1.0, f64::NEG_INFINITY]);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..1000 {
            assert_eq!(wheel.spin(&mut rng), 2);
        }
        wheel.build(&[f64::NAN, 5.0, 5.0]);
        let picks: Vec<usize> = (0..200).map(|_| wheel.spin(&mut rng)).collect();
        assert!(picks.contains(&1) && picks.contains(&2) && !picks.contains(&0));
        wheel.build(&[f64::NAN, f64::NAN]);
        assert!(wheel.spin(&mut rng) < 2);
        wheel.build(&[1.0, f64::INFINITY]);
        assert_eq!(wheel.spin(&mut rng), 1);
    }

    #[test]
    fn stats_skip_non_finite() {
        let (m, s) = mean_std(&[1.0, 3.0, f64::NAN, f64::INFINITY]);
        assert_eq!((m, s), (2.0, 1.0));
        assert!(mean_std(&[f64::NAN]).0.is_nan());
    }
}
