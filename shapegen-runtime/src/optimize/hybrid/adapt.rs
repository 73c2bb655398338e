//! Operator rates that follow which ways of breeding have been producing improvements:
//! probability matching on each one's recent rate of children better than their parent.

use serde::{Deserialize, Serialize};

use super::super::GaSettings;
use super::super::fitness::compare;
use super::super::ga::Made;

/// Weight of the newest generation in each way's moving average of improvement.
const SMOOTHING: f64 = 0.3;

/// The smallest share of the children any way of breeding that the settings use is
/// given, so that none is starved by a few unlucky generations.
const FLOOR: f64 = 0.05;

/// What the adaptation has learned: for each way of breeding (crossover, grow, cut,
/// alter), a moving average of the share of its children that beat the parent they were
/// made from, `None` until one of its children has been scored.
///
/// With `SHAPEGEN_ADAPT_CREDIT=gain` in the environment, the average is instead of each
/// way's mean gain over the parent (0 for a child no better).
///
/// The GA makes a share `1 - mutation_probability` of its children by crossover and
/// `mutation_probability * w / (grow + cut + alter weights)` by the mutation of weight
/// `w`. Once every way the settings use has an average, those shares are set in
/// proportion to the averages, each at least [`FLOOR`]; ways the settings give no
/// share stay at none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Adaptation {
    quality: [Option<f64>; 4],
}

impl Adaptation {
    /// Takes in a scored generation's children: how each was made, its fitness and its
    /// parent's.
    pub(super) fn observe(&mut self, children: impl Iterator<Item = (Made, f64, f64)>) {
        let gain = std::env::var("SHAPEGEN_ADAPT_CREDIT").as_deref() == Ok("gain");
        let mut used = [0u32; 4];
        let mut improved = [0f64; 4];
        for (made, child, parent) in children {
            used[made.index()] += 1;
            improved[made.index()] += if gain {
                let d = child - parent;
                if d.is_finite() && d > 0.0 { d } else { 0.0 }
            } else {
                f64::from(u32::from(compare(child, parent).is_gt()))
            };
        }
        for (q, (&n, &k)) in self.quality.iter_mut().zip(used.iter().zip(&improved)) {
            if n > 0 {
                let rate = k / f64::from(n);
                *q = Some(q.map_or(rate, |q| (1.0 - SMOOTHING) * q + SMOOTHING * rate));
            }
        }
    }

    /// The mutation probability and the grow, cut and alter weights to breed with, from
    /// `settings` (the run's own rates) and what has been learned.
    pub(super) fn rates(&self, settings: &GaSettings) -> (f64, [f64; 3]) {
        let own = (
            settings.mutation_probability,
            [
                settings.grow_weight,
                settings.cut_weight,
                settings.alter_weight,
            ],
        );
        let shares = shares(own);
        let used: Vec<usize> = (0..4).filter(|&k| shares[k] > 0.0).collect();
        let Some(quality) = used
            .iter()
            .map(|&k| self.quality[k].map(|q| (k, q)))
            .collect::<Option<Vec<_>>>()
        else {
            return own;
        };
        let total: f64 = quality.iter().map(|(_, q)| q).sum();
        if total <= 0.0 {
            return own;
        }
        let spread = 1.0 - FLOOR * used.len() as f64;
        let mut share = [0.0; 4];
        for (k, q) in quality {
            share[k] = FLOOR + spread * q / total;
        }
        (1.0 - share[0], [share[1], share[2], share[3]])
    }
}

/// The share of children each way of breeding makes under these rates.
fn shares((mutation, [grow, cut, alter]): (f64, [f64; 3])) -> [f64; 4] {
    let weights = grow + cut + alter;
    let m = |w: f64| mutation * w / weights;
    [1.0 - mutation, m(grow), m(cut), m(alter)]
}
