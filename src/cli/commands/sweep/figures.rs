//! A study's plots, made from its finished cells alone, each as a PNG file and an SVG
//! file beside it:
//! - `final-KEY.png` for each swept key: final best fitness against the key's values
//!   (placed by value when all are numbers, in the order given otherwise), mean +- std
//!   over runs as error bars, one line per value of a second swept key when there is one
//!   (the first other key; further keys pooled);
//! - `curves.png`: best fitness so far against evaluations, mean +- std over runs, of
//!   the grid points with the highest and the lowest mean final best;
//! - for a scene with a known optimum, `gap-time.png` and `gap-evaluations.png` (every
//!   grid point's gap to it, median and quartiles on a log scale) and `targets.csv`
//!   (each point's time and evaluations to 90 %, 99 % and 99.9 % of it), as `compare`
//!   writes them ([`gap`](crate::cli::gap)).

use std::collections::BTreeMap;
use std::path::Path;

use super::cell::Finished;
use super::plan::Plan;
use super::tables::{best_and_worst, summarize};
use crate::cli::files::save_figure;
use crate::cli::gap::{self, Group};
use crate::cli::plot::{self, Band, Figure, Titles, XValues};
use crate::search::stats::{curve, mean_std};

/// Size of every plot.
const SIZE: (u32, u32) = (800, 500);
/// Points of the evaluation grid the mean curves are sampled on.
const CURVE_POINTS: usize = 400;

/// Writes every plot of the study for the finished cells `done`.
pub fn write(plan: &Plan, dir: &Path, done: &BTreeMap<u64, Finished>) -> anyhow::Result<()> {
    for (k, axis) in plan.grid.iter().enumerate() {
        save_figure(
            &dir.join(final_file(&axis.key)),
            &finals_against(plan, done, k)?,
        )?;
    }
    save_figure(&dir.join("curves.png"), &curves(plan, done)?)?;
    match plan.optimum {
        Some(optimum) => {
            let groups: Vec<Group<'_>> = (0..plan.points())
                .map(|point| Group {
                    name: plan.describe(point),
                    colour: plot::palette(point as usize),
                    runs: (0..plan.runs)
                        .filter_map(|run| done.get(&(point * plan.runs + run)))
                        .map(|f| f.history.as_slice())
                        .collect(),
                })
                .collect();
            gap::write(dir, "point", optimum, &groups)?;
            gap::check_optimum(optimum, &groups)
        }
        None => Ok(()),
    }
}

/// The file of the plot against `key`: `final-KEY.png`, with any character of the key
/// but letters, digits, `.`, `-` and `_` written `_`.
pub fn final_file(key: &str) -> String {
    let safe: String = key
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("final-{safe}.png")
}

/// Final best fitness against the values of swept key `k`.
fn finals_against(plan: &Plan, done: &BTreeMap<u64, Finished>, k: usize) -> anyhow::Result<Figure> {
    let axis = &plan.grid[k];
    let lines = (0..plan.grid.len()).find(|&j| j != k);
    let line_count = lines.map_or(1, |j| plan.grid[j].values.len());
    // finals[line][value of k]
    let mut finals = vec![vec![Vec::new(); axis.values.len()]; line_count];
    for (&index, f) in done {
        let at = plan.coordinates(plan.cell(index).point);
        finals[lines.map_or(0, |j| at[j])][at[k]].push(f.record.best);
    }
    let stats: Vec<(Vec<f64>, Vec<f64>)> = finals
        .iter()
        .map(|line| line.iter().map(|values| mean_std(values)).unzip())
        .collect();
    let names: Vec<String> = (0..line_count)
        .map(|i| {
            lines.map_or_else(
                || "final best of each value".to_owned(),
                |j| format!("{}={}", plan.grid[j].key, plan.grid[j].values[i]),
            )
        })
        .collect();
    let bands: Vec<Band<'_>> = stats
        .iter()
        .zip(&names)
        .enumerate()
        .map(|(i, ((mean, std), name))| Band {
            name,
            colour: plot::palette(i),
            mean,
            std,
        })
        .collect();
    let numbers: Option<Vec<f64>> = axis
        .values
        .iter()
        .map(|v| v.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect();
    let x = match &numbers {
        Some(numbers) => XValues::Numbers(numbers),
        None => XValues::Names(&axis.values),
    };
    let y = if plan.grid.len() > 2 {
        "final best fitness (mean +- std over runs; other keys pooled)"
    } else {
        "final best fitness (mean +- std over runs)"
    };
    let title = format!("Final best fitness against {}", axis.key);
    let titles = Titles {
        title: &title,
        x: &axis.key,
        y,
    };
    plot::error_bars(SIZE, &titles, &x, &bands)
}

/// The mean curves of the best and the worst grid points.
fn curves(plan: &Plan, done: &BTreeMap<u64, Finished>) -> anyhow::Result<Figure> {
    let points = summarize(plan, done);
    let shown: Vec<(&str, u64)> = match best_and_worst(&points) {
        None => Vec::new(),
        Some((best, worst)) if best == worst => vec![("best", best)],
        Some((best, worst)) => vec![("best", best), ("worst", worst)],
    };
    let histories = |point: u64| -> Vec<&[shapegen::optimize::HistoryEntry]> {
        (0..plan.runs)
            .filter_map(|run| done.get(&(point * plan.runs + run)))
            .map(|f| f.history.as_slice())
            .collect()
    };
    let x_max = shown
        .iter()
        .flat_map(|&(_, point)| histories(point))
        .filter_map(|h| h.last().map(|h| h.evaluations as f64))
        .fold(0.0, f64::max);
    let lines: Vec<(String, Vec<f64>, Vec<f64>)> = shown
        .iter()
        .map(|&(which, point)| {
            let (mean, std) = curve(
                &histories(point),
                |h| h.evaluations as f64,
                x_max,
                CURVE_POINTS,
            );
            (format!("{which}: {}", plan.describe(point)), mean, std)
        })
        .collect();
    let bands: Vec<Band<'_>> = lines
        .iter()
        .enumerate()
        .map(|(i, (name, mean, std))| Band {
            name,
            colour: plot::palette(i),
            mean,
            std,
        })
        .collect();
    let titles = Titles {
        title: "Best fitness against evaluations: the best and the worst grid point",
        x: "evaluations",
        y: "best fitness so far (mean +- std over runs)",
    };
    plot::bands(SIZE, &titles, x_max, &bands)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plot_files_are_named_for_their_keys() {
        assert_eq!(
            final_file("optimizer.population"),
            "final-optimizer.population.png"
        );
        assert_eq!(
            final_file("silhouette.target[0].kind"),
            "final-silhouette.target_0_.kind.png"
        );
    }
}
