//! `fitness.csv`, a run's history one row per generation: written by `run` and by
//! `sweep`'s cells, which read it back to resume.

use std::path::Path;

use shapegen::optimize::HistoryEntry;

use super::files::{csv_bytes, read as read_text};

/// The columns of `fitness.csv`.
pub(super) const COLUMNS: [&str; 6] = [
    "generation",
    "elapsed_s",
    "evaluations",
    "best",
    "mean",
    "std",
];

/// How `elapsed_s` is written.
#[derive(Clone, Copy, Debug)]
pub(super) enum Elapsed {
    /// To the millisecond, for reading: a run's table.
    Milliseconds,
    /// Every digit, so that [`read`] gives back the same number: a sweep's cells.
    Exact,
}

/// `fitness.csv`'s bytes: a row per entry of `history`, the fitness values in full.
pub(super) fn csv(history: &[HistoryEntry], elapsed: Elapsed) -> anyhow::Result<Vec<u8>> {
    let rows = history.iter().map(|h| {
        vec![
            h.generation.to_string(),
            match elapsed {
                Elapsed::Milliseconds => format!("{:.3}", h.elapsed_s),
                Elapsed::Exact => h.elapsed_s.to_string(),
            },
            h.evaluations.to_string(),
            h.best.to_string(),
            h.mean.to_string(),
            h.std.to_string(),
        ]
    });
    csv_bytes(&COLUMNS.map(str::to_owned), rows)
}

/// Reads a `fitness.csv` written with [`Elapsed::Exact`] back: the history exactly as
/// it was.
pub(super) fn read(path: &Path) -> anyhow::Result<Vec<HistoryEntry>> {
    let bad = |what: String| anyhow::anyhow!("`{}`: {what}", path.display());
    let text = read_text(path)?;
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader.headers()?.iter().map(str::to_owned).collect();
    if header != COLUMNS {
        return Err(bad(format!("the columns are {header:?}, not {COLUMNS:?}")));
    }
    reader
        .records()
        .enumerate()
        .map(|(row, record)| {
            let record = record?;
            let field = |i: usize| -> anyhow::Result<f64> {
                record[i]
                    .parse()
                    .map_err(|_| bad(format!("row {}: `{}` is not a number", row + 1, &record[i])))
            };
            let count = |i: usize| -> anyhow::Result<u64> {
                record[i].parse().map_err(|_| {
                    bad(format!(
                        "row {}: `{}` is not a whole number",
                        row + 1,
                        &record[i]
                    ))
                })
            };
            Ok(HistoryEntry {
                generation: count(0)?,
                elapsed_s: field(1)?,
                evaluations: count(2)?,
                best: field(3)?,
                mean: field(4)?,
                std: field(5)?,
            })
        })
        .collect()
}
