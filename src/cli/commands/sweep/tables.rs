//! A study's tables, made from its finished cells alone (so a local sweep and
//! `--collect` make the same): `sweep.csv`, one row per run, and `summary.md`, one row
//! per grid point with the best marked.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use super::cell::Finished;
use super::plan::Plan;
use crate::cli::files::{atomic_write, csv_bytes};
use crate::search::stats::{mean_std, median};
use shapegen::scene::METRIC_COLUMNS;

/// The fractions of the way from the sweep's lowest initial best to its highest final
/// best whose evaluations `sweep.csv` gives, in percent.
pub const PERCENTS: [u32; 3] = [50, 90, 99];

/// One grid point's final values over its finished runs.
pub struct PointSummary {
    /// The grid point.
    pub point: u64,
    /// Each finished run's final best fitness, by run.
    pub finals: Vec<f64>,
    /// Their mean.
    pub mean: f64,
    /// Their sample standard deviation.
    pub std: f64,
    /// Their median.
    pub median: f64,
}

/// Every grid point's summary over the finished cells `done`, in point order.
pub fn summarize(plan: &Plan, done: &BTreeMap<u64, Finished>) -> Vec<PointSummary> {
    (0..plan.points())
        .map(|point| {
            let finals: Vec<f64> = (0..plan.runs)
                .filter_map(|run| done.get(&(point * plan.runs + run)))
                .map(|f| f.record.best)
                .collect();
            let (mean, std) = mean_std(&finals);
            PointSummary {
                point,
                median: median(&finals),
                finals,
                mean,
                std,
            }
        })
        .collect()
}

/// The grid points with the highest and the lowest mean final best (the first of
/// equals); `None` when no point has a finished run with a number.
pub fn best_and_worst(points: &[PointSummary]) -> Option<(u64, u64)> {
    let ranked = points.iter().filter(|p| !p.mean.is_nan());
    let best = ranked
        .clone()
        .reduce(|a, b| if b.mean > a.mean { b } else { a })?;
    let worst = ranked.reduce(|a, b| if b.mean < a.mean { b } else { a })?;
    Some((best.point, worst.point))
}

/// The fitness levels of [`PERCENTS`]: `low + p (high - low)` for the lowest best of any
/// run's initial population, `low`, and the highest final best, `high`, over `done`.
fn levels(done: &BTreeMap<u64, Finished>) -> Option<[f64; 3]> {
    let finite = |v: &f64| v.is_finite();
    let low = done
        .values()
        .filter_map(|f| f.history.first().map(|h| h.best))
        .filter(finite)
        .reduce(f64::min)?;
    let high = done
        .values()
        .map(|f| f.record.best)
        .filter(finite)
        .reduce(f64::max)?;
    Some(PERCENTS.map(|p| low + f64::from(p) / 100.0 * (high - low)))
}

/// Evaluations done when `finished` first had a best of at least `level`.
fn evaluations_to(finished: &Finished, level: f64) -> Option<u64> {
    finished
        .history
        .iter()
        .find(|h| h.best >= level)
        .map(|h| h.evaluations)
}

/// Writes `sweep.csv` and `summary.md` for the finished cells `done`.
pub fn write(plan: &Plan, dir: &Path, done: &BTreeMap<u64, Finished>) -> anyhow::Result<()> {
    atomic_write(&dir.join("sweep.csv"), &sweep_csv(plan, done)?)?;
    atomic_write(&dir.join("summary.md"), summary_md(plan, done).as_bytes())
}

/// `sweep.csv`: per finished cell, in index order, its grid values, run, seed, final
/// best, evaluations, generations, seconds, the evaluations it took to reach each
/// level of [`PERCENTS`] (empty when it never did), and its best model's measures
/// ([`Metrics::columns`](shapegen::scene::Metrics::columns); empty for a cell written
/// without them).
fn sweep_csv(plan: &Plan, done: &BTreeMap<u64, Finished>) -> anyhow::Result<Vec<u8>> {
    let header: Vec<String> = std::iter::once("cell".to_owned())
        .chain(plan.grid.iter().map(|a| a.key.clone()))
        .chain(
            [
                "run",
                "seed",
                "best",
                "evaluations",
                "generations",
                "seconds",
            ]
            .map(str::to_owned),
        )
        .chain(PERCENTS.map(|p| format!("evaluations_to_{p}")))
        .chain(METRIC_COLUMNS.map(str::to_owned))
        .collect();
    let levels = levels(done);
    let rows = done.iter().map(|(&index, f)| {
        let cell = plan.cell(index);
        let r = &f.record;
        let reached = levels
            .iter()
            .flatten()
            .map(|&level| evaluations_to(f, level).map_or_else(String::new, |n| n.to_string()));
        std::iter::once(index.to_string())
            .chain(plan.values(cell.point).into_iter().map(str::to_owned))
            .chain([
                r.run.to_string(),
                r.seed.to_string(),
                r.best.to_string(),
                r.evaluations.to_string(),
                r.generations.to_string(),
                r.seconds.to_string(),
            ])
            .chain(reached)
            .chain(match &r.metrics {
                Some(m) => m.columns(),
                None => Default::default(),
            })
            .collect::<Vec<String>>()
    });
    csv_bytes(&header, rows)
}

/// `summary.md`: the study in a sentence, then per grid point its runs done, the mean +-
/// std and the median of its final best, the best point marked; then the missing cells.
fn summary_md(plan: &Plan, done: &BTreeMap<u64, Finished>) -> String {
    let points = summarize(plan, done);
    let best = best_and_worst(&points).map(|(best, _)| best);
    let mut md = String::new();
    let method = plan.method.map_or("the scene's method", |m| m.name());
    let _ = writeln!(md, "# Sweep of `{}`\n", plan.scene.display());
    let _ = writeln!(
        md,
        "Method: {}; {} per run; {} runs per grid point on seeds {} to {}; {} grid points; \
         {} of {} cells done.\n",
        method,
        plan.budget.describe(),
        plan.runs,
        plan.seed,
        plan.seed + plan.runs - 1,
        plan.points(),
        done.len(),
        plan.cells()
    );
    let _ = writeln!(
        md,
        "Final best fitness per grid point over its runs: mean +- sample standard \
         deviation, and median. **best** marks the highest mean.\n"
    );
    let keys: Vec<String> = plan.grid.iter().map(|a| cell_text(&a.key)).collect();
    let _ = writeln!(
        md,
        "| {} | runs | mean +- std | median | |",
        keys.join(" | ")
    );
    let _ = writeln!(md, "|{}", "---|".repeat(keys.len() + 4));
    for p in &points {
        let values: Vec<String> = plan.values(p.point).into_iter().map(cell_text).collect();
        let (stats, median) = if p.finals.is_empty() {
            ("-".to_owned(), "-".to_owned())
        } else {
            (
                format!("{:.5} +- {:.5}", p.mean, p.std),
                format!("{:.5}", p.median),
            )
        };
        let mark = if best == Some(p.point) {
            "**best**"
        } else {
            ""
        };
        let _ = writeln!(
            md,
            "| {} | {} of {} | {stats} | {median} | {mark} |",
            values.join(" | "),
            p.finals.len(),
            plan.runs
        );
    }
    let missing = missing(plan, done);
    if !missing.is_empty() {
        let _ = writeln!(
            md,
            "\nMissing cells ({}): {}.",
            missing.len(),
            ranges(&missing)
        );
    }
    md
}

/// The cells of `plan` not in `done`, in order.
pub fn missing(plan: &Plan, done: &BTreeMap<u64, Finished>) -> Vec<u64> {
    (0..plan.cells())
        .filter(|i| !done.contains_key(i))
        .collect()
}

/// Increasing `indices` as runs, the way `sbatch --array` takes them: `0,3-5,9`.
pub fn ranges(indices: &[u64]) -> String {
    let mut runs: Vec<(u64, u64)> = Vec::new();
    for &i in indices {
        match runs.last_mut() {
            Some((_, end)) if *end + 1 == i => *end = i,
            _ => runs.push((i, i)),
        }
    }
    runs.iter()
        .map(|&(a, b)| {
            if a == b {
                a.to_string()
            } else {
                format!("{a}-{b}")
            }
        })
        .collect::<Vec<_>>()
        .join(",")
}

/// `text` as the text of a Markdown table cell: pipes escaped.
fn cell_text(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::backend::BackendArgs;
    use crate::cli::commands::sweep::cell::Record;
    use crate::cli::commands::sweep::plan::{Axis, StudyBudget};
    use shapegen::optimize::HistoryEntry;

    fn plan() -> Plan {
        Plan {
            version: Plan::VERSION.to_owned(),
            scene: "/s.toml".into(),
            grid: vec![Axis::parse("a=1,2").unwrap()],
            runs: 2,
            budget: StudyBudget::Evaluations(100),
            seed: 1,
            method: None,
            sets: Vec::new(),
            backend: BackendArgs::default(),
            optimum: None,
        }
    }

    /// A finished cell whose best went through `bests` at 10, 20, .. evaluations.
    fn finished(plan: &Plan, index: u64, bests: &[f64]) -> Finished {
        let cell = plan.cell(index);
        let history: Vec<HistoryEntry> = bests
            .iter()
            .enumerate()
            .map(|(g, &best)| HistoryEntry {
                generation: g as u64,
                elapsed_s: 0.1 * g as f64,
                evaluations: 10 * (g as u64 + 1),
                best,
                mean: best,
                std: 0.0,
            })
            .collect();
        Finished {
            record: Record {
                index,
                point: BTreeMap::new(),
                run: cell.run,
                seed: cell.seed,
                best: *bests.last().unwrap(),
                evaluations: 10 * bests.len() as u64,
                generations: bests.len() as u64 - 1,
                seconds: 0.1,
                stopped: "evaluations".into(),
                // Cell 3 measured its model; the others were written without measures.
                metrics: (index == 3).then(|| shapegen::scene::Metrics {
                    genes: 7,
                    instances: 9,
                    triangles: 108,
                    voxel_iou: Some(0.5),
                    surface: None,
                    point_clouds: Vec::new(),
                    silhouette_iou: Vec::new(),
                }),
            },
            history,
        }
    }

    #[test]
    fn levels_run_from_the_lowest_start_to_the_highest_end() {
        let plan = plan();
        let done: BTreeMap<u64, Finished> = [
            (0, finished(&plan, 0, &[-1.0, 0.0, 1.0])),
            (1, finished(&plan, 1, &[0.0, 2.0, 2.0])),
            (3, finished(&plan, 3, &[1.0, 3.0])),
        ]
        .into();
        // From -1 (cell 0's start) to 3 (cell 3's end): 50 % is 1, 90 % 2.6, 99 % 2.96.
        let levels = levels(&done).unwrap();
        assert_eq!(levels, [1.0, -1.0 + 0.9 * 4.0, -1.0 + 0.99 * 4.0]);
        let csv = String::from_utf8(sweep_csv(&plan, &done).unwrap()).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines[0],
            "cell,a,run,seed,best,evaluations,generations,seconds,\
             evaluations_to_50,evaluations_to_90,evaluations_to_99,\
             genes,instances,triangles,voxel_iou,silhouette_iou,chamfer,f_score"
        );
        assert_eq!(lines[1], "0,1,0,1,1,30,2,0.1,30,,,,,,,,,");
        assert_eq!(lines[2], "1,1,1,2,2,30,2,0.1,20,,,,,,,,,");
        assert_eq!(lines[3], "3,2,1,2,3,20,1,0.1,10,20,20,7,9,108,0.5,,,");
        assert_eq!(lines.len(), 4);
    }

    #[test]
    fn the_summary_marks_the_best_mean_and_lists_what_is_missing() {
        let plan = plan();
        let done: BTreeMap<u64, Finished> = [
            (0, finished(&plan, 0, &[1.0])),
            (1, finished(&plan, 1, &[3.0])),
            (2, finished(&plan, 2, &[2.5])),
        ]
        .into();
        let points = summarize(&plan, &done);
        assert_eq!((points[0].mean, points[0].median), (2.0, 2.0));
        assert_eq!(points[1].finals, [2.5]);
        assert_eq!(best_and_worst(&points), Some((1, 0)));
        let md = summary_md(&plan, &done);
        assert!(
            md.contains("| 1 | 2 of 2 | 2.00000 +- 1.41421 | 2.00000 |  |"),
            "{md}"
        );
        assert!(
            md.contains("| 2 | 1 of 2 | 2.50000 +- 0.00000 | 2.50000 | **best** |"),
            "{md}"
        );
        assert!(md.contains("3 of 4 cells done"), "{md}");
        assert!(md.contains("Missing cells (1): 3."), "{md}");
    }

    #[test]
    fn missing_cells_are_listed_as_runs() {
        assert_eq!(ranges(&[0, 3, 4, 5, 9]), "0,3-5,9");
        assert_eq!(ranges(&[7]), "7");
        assert_eq!(ranges(&[]), "");
    }
}
