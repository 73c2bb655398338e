//! Centre lines over shaded bands against a common grid, on a linear or a log scale:
//! bands of mean +- std, and a comparison's medians with their quartiles.

use plotters::coord::Shift;
use plotters::coord::ranged1d::Ranged;
use plotters::prelude::*;

use super::chart::{Chart, Failure, Plot, decimals, extent, fixed, frame, mesh, padded, power};
use super::series::{Spread, Titles, YScale};
use super::sketch::Sketch;
use super::style::{KEY, SWATCH, rgb};

/// The chart of [`spreads`].
pub(super) struct Spreads<'a> {
    pub(super) titles: &'a Titles<'a>,
    pub(super) x_max: f64,
    pub(super) curves: &'a [Spread<'a>],
    pub(super) scale: YScale,
    pub(super) key: &'a str,
}

impl Spreads<'_> {
    /// Whether `y` can be placed on the chart's scale.
    pub(super) fn shown(&self, y: f64) -> bool {
        y.is_finite() && (self.scale == YScale::Linear || y > 0.0)
    }

    /// The x axis's end: `x_max`, or 1 where it is not a positive number.
    pub(super) fn x_end(&self) -> f64 {
        if self.x_max.is_finite() && self.x_max > 0.0 {
            self.x_max
        } else {
            1.0
        }
    }

    /// The finite values of the chart that its scale can place.
    pub(super) fn values(&self) -> impl Iterator<Item = f64> + '_ {
        self.curves
            .iter()
            .flat_map(|c| [c.centre, c.low, c.high])
            .flatten()
            .copied()
            .filter(|&v| self.shown(v))
    }

    /// Draws the bands, then the lines over them, then the legend.
    pub(super) fn curves<'a, DB, Y>(&self, chart: &mut Plot<'a, DB, Y>) -> Result<(), Failure<DB>>
    where
        DB: DrawingBackend + 'a,
        Y: Ranged<ValueType = f64>,
    {
        let mut sketch = Sketch::default();
        let x_end = self.x_end();
        let at = |i: usize, n: usize| x_end * i as f64 / (n.max(2) - 1) as f64;
        for c in self.curves {
            let n = c.low.len().min(c.high.len());
            let edges = (0..n).map(|i| {
                let (low, high) = (c.low[i], c.high[i]);
                (self.shown(low) && self.shown(high)).then_some((at(i, n), low, high))
            });
            sketch.shade(chart, rgb(c.colour), edges)?;
        }
        for c in self.curves {
            let n = c.centre.len();
            let points = (0..n).map(|i| self.shown(c.centre[i]).then_some((at(i, n), c.centre[i])));
            sketch.line(chart, c.name, rgb(c.colour), points)?;
        }
        sketch.key(chart, self.key, |(x, y)| {
            Rectangle::new([(x, y - 6), (x + SWATCH - 6, y + 6)], KEY.mix(0.4).filled())
        })?;
        sketch.legend(chart)
    }
}

impl Chart for Spreads<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), Failure<DB>> {
        let x = 0.0..self.x_end();
        let range = extent(self.values());
        match self.scale {
            YScale::Linear => {
                let y = padded(range);
                let (x_text, y_text) = (fixed(decimals(&x)), fixed(decimals(&y)));
                let mut chart = frame(root, self.titles.title, x, |_| y)?;
                mesh(&mut chart, self.titles, &x_text, &y_text).draw()?;
                self.curves(&mut chart)
            }
            YScale::Log => {
                let (lo, hi) = match range {
                    Some((lo, hi)) => {
                        let (lo, hi) = (lo.log10().floor(), hi.log10().ceil());
                        (lo, hi.max(lo + 1.0))
                    }
                    None => (-1.0, 0.0),
                };
                // Ticks at the powers of ten, placed by hand: those `plotters` finds
                // miss the lowest when rounding puts its logarithm a hair above it.
                let powers: Vec<f64> = (lo as i32..=hi as i32).map(|k| 10f64.powi(k)).collect();
                let decades = powers[0]..powers[powers.len() - 1];
                let y = |_| decades.log_scale().with_key_points(powers);
                let x_text = fixed(decimals(&x));
                let mut chart = frame(root, self.titles.title, x, y)?;
                mesh(&mut chart, self.titles, &x_text, &power).draw()?;
                self.curves(&mut chart)
            }
        }
    }
}
