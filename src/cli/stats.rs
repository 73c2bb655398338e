//! Statistics over repeated runs, shared by `compare` and `sweep`: mean, spread and
//! median of final values, and the mean curve of several runs' histories sampled on a
//! common grid.

use shapegen::optimize::HistoryEntry;

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

/// The median of `values` (the mean of the two middle ones for an even count, NaN ranked
/// lowest); NaN for none.
pub fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(|a, b| match (a.is_nan(), b.is_nan()) {
        (true, true) => std::cmp::Ordering::Equal,
        (true, false) => std::cmp::Ordering::Less,
        (false, true) => std::cmp::Ordering::Greater,
        (false, false) => a.total_cmp(b),
    });
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
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
    let mut next = vec![0usize; runs.len()];
    let mut values = Vec::with_capacity(runs.len());
    let mut mean = Vec::with_capacity(points);
    let mut std = Vec::with_capacity(points);
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
        let (m, s) = if values.len() == runs.len() {
            mean_std(&values)
        } else {
            (f64::NAN, f64::NAN)
        };
        mean.push(m);
        std.push(s);
    }
    (mean, std)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(elapsed_s: f64, evaluations: u64, best: f64) -> HistoryEntry {
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
}
