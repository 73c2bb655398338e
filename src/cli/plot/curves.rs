//! Lines against whole-number x values: a run's fitness curves.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::chart::{Chart, Failure, decimals, extent, fixed, frame, mesh, tight};
use super::series::{Line, Titles};
use super::sketch::Sketch;
use super::style::{TICKS, rgb};

/// The chart of [`curves`].
pub(super) struct Curves<'a> {
    pub(super) titles: &'a Titles<'a>,
    pub(super) x: &'a [f64],
    pub(super) lines: &'a [Line<'a>],
}

impl Chart for Curves<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), Failure<DB>> {
        let x = tight(extent(self.x.iter().copied()));
        let values = self.lines.iter().flat_map(|l| l.values.iter().copied());
        let y = match extent(values) {
            Some((lo, hi)) if lo < hi => lo..hi,
            Some((lo, _)) => lo - 1.0..lo + 1.0,
            None => -1.0..1.0,
        };
        let span = (x.end - x.start).round() as usize;
        let y_text = fixed(decimals(&y));
        let mut chart = frame(root, self.titles.title, x, |_| y)?;
        // Whole-number steps: at most one tick per x value.
        mesh(&mut chart, self.titles, &fixed(0), &y_text)
            .x_labels(TICKS.min(span + 1))
            .draw()?;
        let mut sketch = Sketch::default();
        for line in self.lines {
            let points = self.x.iter().zip(line.values).map(|(&x, &y)| {
                let shown = x.is_finite() && y.is_finite();
                shown.then_some((x, y))
            });
            sketch.line(&mut chart, line.name, rgb(line.colour), points)?;
        }
        sketch.legend(&mut chart)
    }
}
