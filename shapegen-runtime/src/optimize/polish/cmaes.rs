//! The separable CMA-ES (Ros and Hansen 2008): the covariance matrix adaptation
//! evolution strategy with a diagonal covariance, for the box `[0, 1]^n`.
//!
//! Full CMA-ES adapts an `n x n` covariance and decomposes it every few generations
//! (`O(n^3)`); a derivation's continuous parameters number in the hundreds, and the
//! separable variant learns one scale per coordinate in `O(n)` a sample, with learning
//! rates raised by `(n + 2) / 3` as its authors recommend. Candidates outside the box are
//! repaired by clamping and the repaired points enter the update.

use rand::Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

use super::super::fitness::{bits, bits_vec, compare};

/// The state of a separable CMA-ES minimising or maximising over `[0, 1]^n`.
///
/// ```
/// use rand::SeedableRng;
/// use shapegen_runtime::optimize::SepCmaEs;
///
/// // Find the point (0.3, 0.7, 0.5) of the unit cube by its squared distance.
/// let target = [0.3, 0.7, 0.5];
/// let mut es = SepCmaEs::new(vec![0.5; 3], 0.2);
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
/// for _ in 0..150 {
///     let candidates = es.ask(8, &mut rng);
///     let fitness: Vec<f64> = candidates
///         .iter()
///         .map(|x| -x.iter().zip(&target).map(|(a, b)| (a - b).powi(2)).sum::<f64>())
///         .collect();
///     es.tell(&candidates, &fitness);
/// }
/// assert!(es.mean().iter().zip(&target).all(|(a, b)| (a - b).abs() < 1e-6));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SepCmaEs {
    // Every number as its bits, so that a resumed strategy goes on exactly.
    #[serde(with = "bits_vec")]
    mean: Vec<f64>,
    #[serde(with = "bits")]
    sigma: f64,
    /// The diagonal of the covariance.
    #[serde(with = "bits_vec")]
    variance: Vec<f64>,
    /// Evolution path of the step size.
    #[serde(with = "bits_vec")]
    path_sigma: Vec<f64>,
    /// Evolution path of the covariance.
    #[serde(with = "bits_vec")]
    path_c: Vec<f64>,
    /// Generations told.
    generations: u64,
}

/// The strategy's constants for `n` dimensions and `mu` parents (Hansen's tutorial,
/// 2016, with the separable rates).
struct Constants {
    weights: Vec<f64>,
    mu_eff: f64,
    c_sigma: f64,
    d_sigma: f64,
    c_c: f64,
    c_1: f64,
    c_mu: f64,
    /// `E |N(0, I)|`.
    chi_n: f64,
}

impl Constants {
    fn new(n: usize, lambda: usize) -> Constants {
        let nf = n as f64;
        let mu = (lambda / 2).max(1);
        let raw: Vec<f64> = (0..mu)
            .map(|i| ((lambda as f64 + 1.0) / 2.0).ln() - ((i + 1) as f64).ln())
            .collect();
        let sum: f64 = raw.iter().sum();
        let weights: Vec<f64> = raw.iter().map(|w| w / sum).collect();
        let mu_eff = 1.0 / weights.iter().map(|w| w * w).sum::<f64>();
        let c_sigma = (mu_eff + 2.0) / (nf + mu_eff + 5.0);
        let d_sigma = 1.0 + 2.0 * (((mu_eff - 1.0) / (nf + 1.0)).sqrt() - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / nf) / (nf + 4.0 + 2.0 * mu_eff / nf);
        let separable = (nf + 2.0) / 3.0;
        let c_1 = (separable * 2.0 / ((nf + 1.3).powi(2) + mu_eff)).min(1.0);
        let c_mu = (separable * 2.0 * (mu_eff - 2.0 + 1.0 / mu_eff)
            / ((nf + 2.0).powi(2) + mu_eff))
            .min(1.0 - c_1)
            .max(0.0);
        let chi_n = nf.sqrt() * (1.0 - 1.0 / (4.0 * nf) + 1.0 / (21.0 * nf * nf));
        Constants {
            weights,
            mu_eff,
            c_sigma,
            d_sigma,
            c_c,
            c_1,
            c_mu,
            chi_n,
        }
    }
}

impl SepCmaEs {
    /// A strategy centred on `mean` (clamped into `[0, 1]`) with step size `sigma`.
    pub fn new(mean: Vec<f64>, sigma: f64) -> SepCmaEs {
        let n = mean.len();
        SepCmaEs {
            mean: mean.into_iter().map(|m| m.clamp(0.0, 1.0)).collect(),
            sigma,
            variance: vec![1.0; n],
            path_sigma: vec![0.0; n],
            path_c: vec![0.0; n],
            generations: 0,
        }
    }

    /// The number of dimensions.
    pub fn dimensions(&self) -> usize {
        self.mean.len()
    }

    /// The centre of the search distribution.
    pub fn mean(&self) -> &[f64] {
        &self.mean
    }

    /// The overall step size.
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// Generations told so far.
    pub fn generations(&self) -> u64 {
        self.generations
    }

    /// Whether every number of the state is finite and the step size positive: what a
    /// resumed state must hold.
    pub fn is_sound(&self) -> bool {
        let n = self.mean.len();
        self.sigma.is_finite()
            && self.sigma > 0.0
            && [&self.variance, &self.path_sigma, &self.path_c]
                .iter()
                .all(|v| v.len() == n && v.iter().all(|x| x.is_finite()))
            && self.variance.iter().all(|&v| v > 0.0)
            && self.mean.iter().all(|m| (0.0..=1.0).contains(m))
    }

    /// `lambda` candidates `mean + sigma * sqrt(variance) * z`, `z` standard normal from
    /// `rng`, each clamped into `[0, 1]`.
    pub fn ask(&self, lambda: usize, rng: &mut impl Rng) -> Vec<Vec<f64>> {
        (0..lambda)
            .map(|_| {
                self.mean
                    .iter()
                    .zip(&self.variance)
                    .map(|(&m, &v)| {
                        let z: f64 = StandardNormal.sample(rng);
                        (m + self.sigma * v.sqrt() * z).clamp(0.0, 1.0)
                    })
                    .collect()
            })
            .collect()
    }

    /// Updates the distribution from `candidates` (as [`ask`](Self::ask) gave them, all
    /// of its dimension) and their `fitness`, higher better; NaN ranks last, ties keep
    /// the candidates' order. Fewer than two candidates teach nothing.
    pub fn tell(&mut self, candidates: &[Vec<f64>], fitness: &[f64]) {
        let (n, lambda) = (self.mean.len(), candidates.len());
        if lambda < 2 || n == 0 {
            return;
        }
        let k = Constants::new(n, lambda);
        let mut order: Vec<usize> = (0..lambda).collect();
        order.sort_by(|&a, &b| compare(fitness[b], fitness[a]));
        // The weighted mean step, in units of sigma.
        let mut step = vec![0.0; n];
        for (w, &i) in k.weights.iter().zip(&order) {
            for (s, (x, m)) in step.iter_mut().zip(candidates[i].iter().zip(&self.mean)) {
                *s += w * (x - m) / self.sigma;
            }
        }
        let before = self.mean.clone();
        for (m, s) in self.mean.iter_mut().zip(&step) {
            *m = (*m + self.sigma * s).clamp(0.0, 1.0);
        }
        // Step-size path: the step whitened by the covariance's inverse square root.
        let a = (k.c_sigma * (2.0 - k.c_sigma) * k.mu_eff).sqrt();
        for ((p, s), v) in self.path_sigma.iter_mut().zip(&step).zip(&self.variance) {
            *p = (1.0 - k.c_sigma) * *p + a * s / v.sqrt();
        }
        let norm = self.path_sigma.iter().map(|p| p * p).sum::<f64>().sqrt();
        self.generations += 1;
        let decay = 1.0 - (1.0 - k.c_sigma).powi(2 * self.generations.min(1 << 20) as i32);
        let stalls = norm / decay.sqrt() >= (1.4 + 2.0 / (n as f64 + 1.0)) * k.chi_n;
        let h = if stalls { 0.0 } else { 1.0 };
        let a = (k.c_c * (2.0 - k.c_c) * k.mu_eff).sqrt();
        for (p, s) in self.path_c.iter_mut().zip(&step) {
            *p = (1.0 - k.c_c) * *p + h * a * s;
        }
        // Rank-one and rank-mu updates of the diagonal.
        let correction = (1.0 - h) * k.c_c * (2.0 - k.c_c);
        for d in 0..n {
            let rank_mu: f64 = k
                .weights
                .iter()
                .zip(&order)
                .map(|(w, &i)| {
                    let y = (candidates[i][d] - before[d]) / self.sigma;
                    w * y * y
                })
                .sum();
            let v = &mut self.variance[d];
            *v = (1.0 - k.c_1 - k.c_mu) * *v
                + k.c_1 * (self.path_c[d].powi(2) + correction * *v)
                + k.c_mu * rank_mu;
            *v = v.max(1e-300);
        }
        self.sigma *= ((k.c_sigma / k.d_sigma) * (norm / k.chi_n - 1.0))
            .min(1.0)
            .exp();
        // Past this, every candidate would clamp to the box.
        self.sigma = self.sigma.clamp(1e-12, 1.0);
    }
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;

    /// Minimises `f` from the box's centre for `generations`; the best value seen.
    fn minimise(n: usize, lambda: usize, generations: usize, f: impl Fn(&[f64]) -> f64) -> f64 {
        let mut es = SepCmaEs::new(vec![0.5; n], 0.3);
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut best = f64::INFINITY;
        for _ in 0..generations {
            let candidates = es.ask(lambda, &mut rng);
            let values: Vec<f64> = candidates.iter().map(|x| f(x)).collect();
            best = values.iter().copied().fold(best, f64::min);
            let fitness: Vec<f64> = values.iter().map(|v| -v).collect();
            es.tell(&candidates, &fitness);
            assert!(es.is_sound());
        }
        best
    }

    #[test]
    fn it_solves_a_shifted_sphere_and_an_ill_conditioned_ellipsoid() {
        let centre = |i: usize| 0.2 + 0.6 * (i as f64 / 19.0);
        let sphere = |x: &[f64]| {
            x.iter()
                .enumerate()
                .map(|(i, v)| (v - centre(i)).powi(2))
                .sum()
        };
        assert!(minimise(20, 12, 400, sphere) < 1e-12);
        // Scales over six orders of magnitude: the diagonal learns them.
        let ellipsoid = |x: &[f64]| {
            x.iter()
                .enumerate()
                .map(|(i, v)| 1e6f64.powf(i as f64 / 19.0) * (v - centre(i)).powi(2))
                .sum()
        };
        assert!(minimise(20, 12, 1500, ellipsoid) < 1e-8);
    }

    #[test]
    fn it_finds_an_optimum_on_the_boundary_and_stays_in_the_box() {
        let corner = |x: &[f64]| x.iter().map(|v| (v + 0.5).powi(2)).sum::<f64>();
        // The optimum of the box is the corner 0, where the value is 5 * 0.25.
        assert!((minimise(5, 10, 300, corner) - 1.25).abs() < 1e-9);
    }

    #[test]
    fn a_seed_gives_the_same_search_and_a_state_round_trips() {
        let run = || {
            let mut es = SepCmaEs::new(vec![0.1, 0.9, 0.5], 0.2);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            for _ in 0..20 {
                let c = es.ask(6, &mut rng);
                let f: Vec<f64> = c.iter().map(|x| x[0] - x[1] + x[2]).collect();
                es.tell(&c, &f);
            }
            es
        };
        let es = run();
        assert_eq!(es, run());
        let json = serde_json::to_string(&es).unwrap();
        assert_eq!(serde_json::from_str::<SepCmaEs>(&json).unwrap(), es);
        assert_eq!(es.generations(), 20);
    }
}
