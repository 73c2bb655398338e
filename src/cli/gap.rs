//! The distance to a known optimum, shared by `compare` and `sweep` for scenes that
//! give one (`fitness.optimum`, a reachable target's own score): how long each group of
//! runs took to reach 90 %, 99 % and 99.9 % of the optimum (`targets.csv`), and the gap
//! `optimum - best` against time and against evaluations on a log scale
//! (`gap-time.png`, `gap-evaluations.png`, each with its SVG), as the median with its
//! quartile band.
//!
//! A run that never reached a level counts as infinitely slow, so a group's median time
//! is "not reached" once fewer than half its runs got there; `reached` says how many did
//! ([`stats::reached`](crate::search::stats::reached)).

use std::path::Path;

use image::Rgb;
use shapegen::optimize::HistoryEntry;

use super::files::{atomic_write, csv_bytes, save_figure};
use super::plot::{self, Spread, Titles, YScale};
use crate::search::stats::{Reached, quartile_curve, reached};

/// Gaps below this fraction of the optimum are drawn at it, so that runs at the optimum
/// (a gap of 0) stay on the log scale.
const FLOOR: f64 = 1e-5;

/// Points of the grids the curves are sampled on.
const POINTS: usize = 400;

/// Size of the plots.
const SIZE: (u32, u32) = (800, 500);

/// What the lines and the shading of a median-and-quartiles chart show, in its legend.
pub const QUARTILES: &str = "line: median, shaded: first to third quartile";

/// The x value of a history entry: its seconds or its evaluations.
type XOf = fn(&HistoryEntry) -> f64;

/// One group of runs (a method, a grid point) with its histories.
pub struct Group<'a> {
    /// Its name in the tables and legends.
    pub name: String,
    /// Its colour in the plots.
    pub colour: Rgb<u8>,
    /// Each run's history.
    pub runs: Vec<&'a [HistoryEntry]>,
}

/// `targets.csv`: per group and level, the runs, how many reached it, and the quartiles
/// of the seconds and evaluations it took (empty where not reached).
pub fn targets_csv(key: &str, rows: &[(String, Vec<Reached>)]) -> anyhow::Result<Vec<u8>> {
    let header = [
        key,
        "fraction",
        "level",
        "runs",
        "reached",
        "seconds_q1",
        "seconds_median",
        "seconds_q3",
        "evaluations_q1",
        "evaluations_median",
        "evaluations_q3",
    ]
    .map(str::to_owned);
    let shown = |v: f64| {
        if v.is_finite() {
            v.to_string()
        } else {
            String::new()
        }
    };
    let lines = rows.iter().flat_map(|(name, reached)| {
        reached.iter().map(move |r| {
            [name.clone(), r.fraction.to_string(), r.level.to_string()]
                .into_iter()
                .chain([r.runs.to_string(), r.reached.to_string()])
                .chain(r.seconds.iter().chain(&r.evaluations).map(|&v| shown(v)))
                .collect::<Vec<String>>()
        })
    });
    csv_bytes(&header, lines)
}

/// Checks that no run passed `optimum`: a run above it means the scene's optimum is
/// wrong. `groups` name the runs.
pub fn check_optimum(optimum: f64, groups: &[Group<'_>]) -> anyhow::Result<()> {
    let slack = 1e-9 * optimum.abs().max(1.0);
    for group in groups {
        for (i, run) in group.runs.iter().enumerate() {
            if let Some(best) = run.last().map(|h| h.best).filter(|b| *b > optimum + slack) {
                anyhow::bail!(
                    "fitness.optimum = {optimum}, but run {i} of {} reached {best}: the \
                     optimum must be the best fitness the scene can reach (`shapegen score` \
                     of the target's own genome gives it)",
                    group.name
                );
            }
        }
    }
    Ok(())
}

/// Writes `targets.csv`, `gap-time.png` and `gap-evaluations.png` (each with its SVG)
/// into `dir` for `groups`, and returns each group's [`reached`].
pub fn write(
    dir: &Path,
    key: &str,
    optimum: f64,
    groups: &[Group<'_>],
) -> anyhow::Result<Vec<Vec<Reached>>> {
    let rows: Vec<(String, Vec<Reached>)> = groups
        .iter()
        .map(|g| (g.name.clone(), reached(optimum, &g.runs)))
        .collect();
    atomic_write(&dir.join("targets.csv"), &targets_csv(key, &rows)?)?;
    let last = |f: XOf| {
        groups
            .iter()
            .flat_map(|g| g.runs.iter().filter_map(|h| h.last().map(f)))
            .fold(0.0, f64::max)
    };
    let axes: [(&str, XOf, &str, &str); 2] = [
        (
            "gap-time.png",
            |h| h.elapsed_s,
            "time",
            "wall time (seconds)",
        ),
        (
            "gap-evaluations.png",
            |h| h.evaluations as f64,
            "evaluations",
            "evaluations",
        ),
    ];
    for (file, x, against, label) in axes {
        let x_max = last(x);
        let curves: Vec<[Vec<f64>; 3]> = groups
            .iter()
            .map(|g| gaps(optimum, &g.runs, x, x_max))
            .collect();
        let spreads: Vec<Spread<'_>> = groups
            .iter()
            .zip(&curves)
            .map(|(g, [low, centre, high])| Spread {
                name: &g.name,
                colour: g.colour,
                centre,
                low,
                high,
            })
            .collect();
        let title = format!("Gap to the optimum ({optimum}) against {against}");
        let titles = Titles {
            title: &title,
            x: label,
            y: "optimum - best (median and quartiles over runs)",
        };
        let figure = plot::spreads(SIZE, &titles, x_max, &spreads, YScale::Log, QUARTILES)?;
        save_figure(&dir.join(file), &figure)?;
    }
    Ok(rows.into_iter().map(|(_, r)| r).collect())
}

/// The gap to `optimum` of `runs` against `x`: its lower quartile, median and upper
/// quartile per grid point (the gaps of the upper quartile, median and lower quartile
/// of the best), each at least [`FLOOR`] times the optimum.
fn gaps(optimum: f64, runs: &[&[HistoryEntry]], x: XOf, x_max: f64) -> [Vec<f64>; 3] {
    let q = quartile_curve(runs, x, x_max, POINTS);
    let floor = FLOOR * optimum.abs();
    let gap = |v: &Vec<f64>| -> Vec<f64> {
        v.iter()
            .map(|b| {
                let g = optimum - b;
                if g.is_nan() { g } else { g.max(floor) }
            })
            .collect()
    };
    [gap(&q.q3), gap(&q.median), gap(&q.q1)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::search::stats::tests::entry;

    #[test]
    fn levels_are_reached_by_some_runs_and_timed_over_all() {
        let fast = [entry(0.1, 10, 0.5), entry(0.2, 20, 1.0)];
        let slow = [entry(0.1, 10, 0.5), entry(1.0, 100, 0.95)];
        let never = [entry(0.1, 10, 0.5)];
        let r = reached(1.0, &[&fast, &slow, &never]);
        assert_eq!(r.len(), 3);
        // 90 %: two of three runs, at 0.2 s and 1 s; the third counts as never.
        assert_eq!((r[0].level, r[0].runs, r[0].reached), (0.9, 3, 2));
        assert_eq!(r[0].seconds[1], 1.0);
        assert_eq!(r[0].evaluations[0], 60.0);
        assert_eq!(r[0].seconds[2], f64::INFINITY);
        // 99 %: one run; not even the first quartile is reached.
        assert_eq!(r[1].reached, 1);
        assert_eq!(r[1].seconds, [f64::INFINITY; 3]);
        let csv = String::from_utf8(targets_csv("method", &[("ga".into(), r)]).unwrap()).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 4, "{csv}");
        assert!(
            lines[0].starts_with("method,fraction,level,runs,reached,"),
            "{csv}"
        );
        assert_eq!(lines[1], "ga,0.9,0.9,3,2,0.6,1,,60,100,", "{csv}");
        assert_eq!(lines[2], "ga,0.99,0.99,3,1,,,,,,", "{csv}");
    }

    #[test]
    fn a_run_above_the_optimum_is_refused() {
        let run = [entry(0.1, 10, 1.5)];
        let group = Group {
            name: "ga".into(),
            colour: Rgb([0, 0, 0]),
            runs: vec![&run],
        };
        assert!(check_optimum(1.5, std::slice::from_ref(&group)).is_ok());
        let err = check_optimum(1.0, &[group]).unwrap_err().to_string();
        assert!(
            err.contains("fitness.optimum = 1") && err.contains("ga"),
            "{err}"
        );
    }

    #[test]
    fn gaps_are_floored_and_flip_the_quartiles() {
        // Bests 0.5, 0.9 and 1: quartiles 0.7, 0.9, 0.95.
        let runs = [0.5, 0.9, 1.0].map(|b| [entry(0.0, 1, b)]);
        let runs: Vec<&[HistoryEntry]> = runs.iter().map(|r| &r[..]).collect();
        let [low, centre, high] = gaps(1.0, &runs, |h| h.elapsed_s, 1.0);
        assert!((low[0] - 0.05).abs() < 1e-12 && (high[0] - 0.3).abs() < 1e-12);
        assert!((centre[0] - 0.1).abs() < 1e-12);
        // At the optimum the gap is drawn at the floor.
        let at = [entry(0.0, 1, 2.0)];
        let [low, centre, _] = gaps(2.0, &[&at], |h| h.elapsed_s, 1.0);
        assert_eq!((low[0], centre[0]), (2.0 * FLOOR, 2.0 * FLOOR));
    }
}
