//! Statistics over repeated runs, those of [`Compare`](super::Compare)'s summaries and of
//! the tool's `compare` and `sweep` tables: mean, spread, median and quartiles of final
//! values, the mean or the quartile curves of several runs' histories sampled on a common
//! grid, when runs first reached a fitness level, and how a group of runs reached
//! fractions of a known optimum ([`reached`]).
//!
//! A run that never reached a level counts as infinitely slow, so a group's median time
//! is "not reached" once fewer than half its runs got there; [`Reached::reached`] says
//! how many did.

use serde::Serialize;
use shapegen_runtime::optimize::HistoryEntry;

/// The fractions of the optimum whose times are measured.
pub const FRACTIONS: [f64; 3] = [0.9, 0.99, 0.999];

/// How a group's runs reached one level.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Reached {
    /// The fraction of the optimum.
    pub fraction: f64,
    /// The fitness level: `fraction * optimum`.
    pub level: f64,
    /// Runs in the group.
    pub runs: usize,
    /// Runs that reached the level.
    pub reached: usize,
    /// First quartile, median and third quartile over all runs of the seconds to the
    /// level (infinite, written `null`, where too few runs reached it).
    pub seconds: [f64; 3],
    /// Likewise of the evaluations to the level.
    pub evaluations: [f64; 3],
}

/// How `runs` reached each level of [`FRACTIONS`] of `optimum`.
pub fn reached(optimum: f64, runs: &[&[HistoryEntry]]) -> Vec<Reached> {
    FRACTIONS
        .iter()
        .map(|&fraction| {
            let level = fraction * optimum;
            let firsts: Vec<Option<(f64, u64)>> =
                runs.iter().map(|h| first_reaching(h, level)).collect();
            let never = f64::INFINITY;
            let seconds: Vec<f64> = firsts.iter().map(|f| f.map_or(never, |f| f.0)).collect();
            let evaluations: Vec<f64> = firsts
                .iter()
                .map(|f| f.map_or(never, |f| f.1 as f64))
                .collect();
            Reached {
                fraction,
                level,
                runs: runs.len(),
                reached: firsts.iter().flatten().count(),
                seconds: quartiles(&seconds),
                evaluations: quartiles(&evaluations),
            }
        })
        .collect()
}

/// Mean and sample standard deviation (0 for one value) of `values`; NaN for none.
pub fn mean_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    if values.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let mean = values.iter().sum::<f64>() / n;
    if values.len() == 1 {
        return (mean, 0.0);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// `values` sorted, NaN ranked lowest.
fn sorted(values: &[f64]) -> Vec<f64> {
    let mut sorted = values.to_vec();
    sorted.sort_by(|a, b| match (a.is_nan(), b.is_nan()) {
        (true, true) => std::cmp::Ordering::Equal,
        (true, false) => std::cmp::Ordering::Less,
        (false, true) => std::cmp::Ordering::Greater,
        (false, false) => a.total_cmp(b),
    });
    sorted
}

/// The `p` quantile (`p` in `[0, 1]`) of `sorted`, interpolated linearly between the
/// two values around position `p (n - 1)` (R's and NumPy's default); NaN for none. An
/// infinite value on either side gives that infinity.
fn quantile(sorted: &[f64], p: f64) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    let h = p * (n - 1) as f64;
    let (k, t) = (h.floor() as usize, h - h.floor());
    let (a, b) = (sorted[k], sorted[(k + 1).min(n - 1)]);
    if t == 0.0 || a == b {
        a
    } else {
        (1.0 - t) * a + t * b
    }
}

/// The median of `values` (the mean of the two middle ones for an even count, NaN ranked
/// lowest); NaN for none.
pub fn median(values: &[f64]) -> f64 {
    quantile(&sorted(values), 0.5)
}

/// The first quartile, the median and the third quartile of `values` (NaN ranked
/// lowest; each interpolated linearly between the two values around position
/// `p (n - 1)`, as R's and NumPy's defaults do); NaN for none.
pub fn quartiles(values: &[f64]) -> [f64; 3] {
    let sorted = sorted(values);
    [0.25, 0.5, 0.75].map(|p| quantile(&sorted, p))
}

/// Quartile curves: the first quartile, the median and the third quartile per grid
/// point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct QuartileCurve {
    /// The first quartile.
    pub q1: Vec<f64>,
    /// The median.
    pub median: Vec<f64>,
    /// The third quartile.
    pub q3: Vec<f64>,
}

/// The quartiles over `runs` of the best fitness so far, sampled as [`curve`] samples
/// its mean.
pub fn quartile_curve(
    runs: &[&[HistoryEntry]],
    x: impl Fn(&HistoryEntry) -> f64,
    x_max: f64,
    points: usize,
) -> QuartileCurve {
    let mut out = QuartileCurve::default();
    sample(runs, x, x_max, points, |values| {
        let [q1, m, q3] = match values {
            Some(values) => quartiles(values),
            None => [f64::NAN; 3],
        };
        out.q1.push(q1);
        out.median.push(m);
        out.q3.push(q3);
    });
    out
}

/// When a run first had a best of at least `level`: its elapsed seconds and its
/// evaluations at that history entry; `None` if it never did.
pub fn first_reaching(history: &[HistoryEntry], level: f64) -> Option<(f64, u64)> {
    history
        .iter()
        .find(|h| h.best >= level)
        .map(|h| (h.elapsed_s, h.evaluations))
}

/// Calls `reduce` at each of `points` values of `x` evenly spaced over `0..=x_max` with
/// every run's best fitness so far there, or `None` while some run has no entry yet. A
/// run's best at `x` is that of its last history entry at or before `x` (a step
/// function), and its last value once it has ended.
fn sample(
    runs: &[&[HistoryEntry]],
    x: impl Fn(&HistoryEntry) -> f64,
    x_max: f64,
    points: usize,
    mut reduce: impl FnMut(Option<&[f64]>),
) {
    let mut next = vec![0usize; runs.len()];
    let mut values = Vec::with_capacity(runs.len());
    for k in 0..points {
        let t = x_max * k as f64 / (points.max(2) - 1) as f64;
        values.clear();
        for (history, i) in runs.iter().zip(&mut next) {
            while *i < history.len() && x(&history[*i]) <= t {
                *i += 1;
            }
            if *i > 0 {
                values.push(history[*i - 1].best);
            }
        }
        reduce(
            Some(&values)
                .filter(|v| v.len() == runs.len())
                .map(|v| &v[..]),
        );
    }
}

/// The mean and standard deviation over `runs` of the best fitness so far, at `points`
/// values of `x` (a history entry's elapsed seconds, say, or its evaluations) evenly
/// spaced over `0..=x_max`. A run's best at `x` is that of its last history entry at or
/// before `x` (a step function), and its last value once it has ended; a point before
/// every run has its first entry is NaN (a gap in a plot).
pub fn curve(
    runs: &[&[HistoryEntry]],
    x: impl Fn(&HistoryEntry) -> f64,
    x_max: f64,
    points: usize,
) -> (Vec<f64>, Vec<f64>) {
    let mut mean = Vec::with_capacity(points);
    let mut std = Vec::with_capacity(points);
    sample(runs, x, x_max, points, |values| {
        let (m, s) = values.map_or((f64::NAN, f64::NAN), mean_std);
        mean.push(m);
        std.push(s);
    });
    (mean, std)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A history entry at this time and evaluation count, with its mean equal to its best.
    pub(crate) fn entry(elapsed_s: f64, evaluations: u64, best: f64) -> HistoryEntry {
        HistoryEntry {
            generation: 0,
            elapsed_s,
            evaluations,
            best,
            mean: best,
            std: 0.0,
        }
    }

    #[test]
    fn curves_are_step_functions_held_to_the_end() {
        let a = [entry(0.5, 10, 1.0), entry(1.5, 30, 3.0)];
        let b = [entry(0.2, 20, 2.0), entry(0.9, 40, 5.0)];
        let (mean, std) = curve(&[&a, &b], |h| h.elapsed_s, 2.0, 5);
        // t = 0: no run has its first entry yet.
        assert!(mean[0].is_nan() && std[0].is_nan());
        // t = 0.5: a = 1, b = 2; t = 1: 1 and 5; t = 1.5: 3 and 5; t = 2: held.
        assert_eq!(&mean[1..], &[1.5, 3.0, 4.0, 4.0]);
        assert_eq!(std[1], 0.5f64.sqrt());
        assert_eq!(std[2], 8f64.sqrt());
        // By evaluations: at 0 none, 20: a = 1, b = 2; 40: 3 and 5.
        let (mean, _) = curve(&[&a, &b], |h| h.evaluations as f64, 40.0, 3);
        assert!(mean[0].is_nan());
        assert_eq!(&mean[1..], &[1.5, 4.0]);
    }

    #[test]
    fn spread_is_the_sample_standard_deviation() {
        assert_eq!(mean_std(&[2.0]), (2.0, 0.0));
        assert_eq!(mean_std(&[1.0, 3.0]), (2.0, 2f64.sqrt()));
        assert!(mean_std(&[]).0.is_nan());
    }

    #[test]
    fn the_median_is_the_middle_value_or_the_mean_of_the_two() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(&[f64::NAN, 1.0, 2.0]), 1.0);
        assert!(median(&[]).is_nan());
    }

    #[test]
    fn quartiles_interpolate_and_rank_nan_lowest() {
        assert_eq!(quartiles(&[4.0, 1.0, 3.0, 2.0, 5.0]), [2.0, 3.0, 4.0]);
        // Positions 0.75, 1.5 and 2.25 of 1, 2, 3, 4.
        assert_eq!(quartiles(&[4.0, 1.0, 3.0, 2.0]), [1.75, 2.5, 3.25]);
        assert_eq!(quartiles(&[7.0]), [7.0; 3]);
        assert!(quartiles(&[]).iter().all(|q| q.is_nan()));
        let [q1, m, q3] = quartiles(&[f64::NAN, 1.0, 2.0, 3.0, 4.0]);
        assert!(q1 == 1.0 && m == 2.0 && q3 == 3.0);
        // Runs that never reached a level count as infinitely slow.
        let [q1, m, q3] = quartiles(&[1.0, 2.0, f64::INFINITY, f64::INFINITY]);
        assert_eq!((q1, m), (1.75, f64::INFINITY));
        assert_eq!(q3, f64::INFINITY);
    }

    #[test]
    fn quartile_curves_follow_the_runs() {
        let a = [entry(0.0, 10, 1.0), entry(1.0, 30, 3.0)];
        let b = [entry(0.0, 10, 2.0)];
        let c = [entry(0.5, 20, 5.0)];
        let q = quartile_curve(&[&a, &b, &c], |h| h.elapsed_s, 1.0, 3);
        // t = 0: c has no entry yet; t = 0.5: 1, 2, 5; t = 1: 3, 2, 5.
        assert!(q.median[0].is_nan() && q.q1[0].is_nan() && q.q3[0].is_nan());
        assert_eq!((q.q1[1], q.median[1], q.q3[1]), (1.5, 2.0, 3.5));
        assert_eq!((q.q1[2], q.median[2], q.q3[2]), (2.5, 3.0, 4.0));
    }

    #[test]
    fn a_level_is_reached_at_the_first_entry_at_or_above_it() {
        let h = [
            entry(0.1, 10, 0.5),
            entry(0.2, 20, 0.9),
            entry(0.3, 30, 0.95),
        ];
        assert_eq!(first_reaching(&h, 0.9), Some((0.2, 20)));
        assert_eq!(first_reaching(&h, 0.5), Some((0.1, 10)));
        assert_eq!(first_reaching(&h, 0.99), None);
        assert_eq!(first_reaching(&[], 0.0), None);
    }
}
