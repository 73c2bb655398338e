//! Means with error bars against swept x values, numbers or names.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::chart::{
    Chart, Failure, Plot, decimals, extent, fixed, font_failed, frame, mesh, padded,
};
use super::series::{Band, Titles, XValues};
use super::sketch::Sketch;
use super::style::{
    CAP, DODGE, KEY, LEGEND_INSET, LEGEND_TEXT, SMALLEST_TEXT, STROKE, TICK_TEXT, rgb, text,
};

/// The chart of [`error_bars`].
pub(super) struct ErrorBars<'a> {
    pub(super) titles: &'a Titles<'a>,
    pub(super) x: &'a XValues<'a>,
    pub(super) bands: &'a [Band<'a>],
}

impl ErrorBars<'_> {
    /// The x range: the numbers with a little room, or half a step beyond the first
    /// and the last name.
    pub(super) fn x_range(&self) -> Range<f64> {
        match self.x {
            XValues::Numbers(values) => padded(extent(values.iter().copied())),
            XValues::Names(names) => -0.5..names.len() as f64 - 0.5,
        }
    }

    /// Every finite mean +- std of the bands (a non-finite std counted as 0).
    pub(super) fn values(&self) -> impl Iterator<Item = f64> + '_ {
        self.bands.iter().flat_map(|b| {
            b.mean.iter().enumerate().flat_map(|(i, &m)| {
                let s = b.std.get(i).copied().filter(|s| s.is_finite());
                let s = s.unwrap_or(0.0);
                [m - s, m + s]
            })
        })
    }

    /// The legend's entries, as [`Self::draw`] adds them.
    pub(super) fn sketch(&self) -> Sketch {
        let mut names: Vec<String> = self.bands.iter().map(|b| b.name.to_owned()).collect();
        names.push(Self::KEY.to_owned());
        Sketch {
            names,
            ink: Vec::new(),
        }
    }

    /// What the legend says the dots and bars are.
    pub(super) const KEY: &'static str = "dot: mean, bar: mean +- std";

    /// The tick value text of the names on the x axis: as large as the tick values
    /// elsewhere where the widest name fits its share of the axis, smaller where it
    /// does not.
    pub(super) fn name_text<DB: DrawingBackend>(
        &self,
        chart: &Plot<'_, DB, RangedCoordf64>,
    ) -> Result<f64, Failure<DB>> {
        let XValues::Names(names) = self.x else {
            return Ok(TICK_TEXT);
        };
        let area = chart.plotting_area();
        let room = f64::from(area.dim_in_pixel().0) / names.len().max(1) as f64 - 6.0;
        let mut widest = 0;
        for name in *names {
            widest = widest.max(area.estimate_text_size(name, &text(TICK_TEXT))?.0);
        }
        let fit = TICK_TEXT * room / f64::from(widest.max(1));
        Ok(fit.clamp(SMALLEST_TEXT, TICK_TEXT))
    }

    /// Draws each band's joining lines and bars, `dodge` data units apart at each x.
    pub(super) fn draw_bands<DB: DrawingBackend>(
        &self,
        chart: &mut Plot<'_, DB, RangedCoordf64>,
        sketch: &mut Sketch,
        dodge: f64,
    ) -> Result<(), Failure<DB>> {
        let middle = (self.bands.len() as f64 - 1.0) / 2.0;
        for (k, band) in self.bands.iter().enumerate() {
            let shift = (k as f64 - middle) * dodge;
            let n = self.x.len().min(band.mean.len());
            let point = |i: usize| {
                let (x, m) = (self.x.at(i), band.mean[i]);
                (x.is_finite() && m.is_finite()).then_some((x + shift, m))
            };
            let colour = rgb(band.colour);
            sketch.line(chart, band.name, colour, (0..n).map(point))?;
            let style = colour.filled().stroke_width(STROKE);
            let bars: Vec<_> = (0..n)
                .filter_map(|i| {
                    let (x, m) = point(i)?;
                    let s = band.std.get(i).copied().filter(|s| s.is_finite());
                    let s = s.unwrap_or(0.0);
                    sketch.ink.extend([(x, m - s), (x, m + s)]);
                    Some(ErrorBar::new_vertical(x, m - s, m, m + s, style, CAP))
                })
                .collect();
            chart.draw_series(bars)?;
        }
        Ok(())
    }
}

impl Chart for ErrorBars<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), Failure<DB>> {
        let x = self.x_range();
        let (lo, hi) = {
            let y = padded(extent(self.values()));
            (y.start, y.end)
        };
        // Room above the data for the legend, so that it hides no bar.
        let (_, legend) = self
            .sketch()
            .legend_size(LEGEND_TEXT)
            .map_err(font_failed::<DB>)?;
        let y = |area: u32| {
            let (area, room) = (f64::from(area), f64::from(legend + 2 * LEGEND_INSET + 6));
            lo..hi + (hi - lo) * room / (area - room).max(1.0)
        };
        let numbers = fixed(decimals(&x));
        let x_text = |v: &f64| match self.x {
            XValues::Numbers(_) => numbers(v),
            XValues::Names(names) if (v - v.round()).abs() < 1e-9 && *v >= 0.0 => {
                names.get(v.round() as usize).cloned().unwrap_or_default()
            }
            XValues::Names(_) => String::new(),
        };
        let y_text = fixed(decimals(&(lo..hi)));
        let mut chart = frame(root, self.titles.title, x.clone(), y)?;
        let name_text = self.name_text(&chart)?;
        let mut mesh = mesh(&mut chart, self.titles, &x_text, &y_text);
        if let XValues::Names(names) = self.x {
            // One tick per name: the step of 1 fits exactly that many.
            mesh.x_labels(names.len()).x_label_style(text(name_text));
        }
        mesh.draw()?;
        let width = f64::from(chart.plotting_area().dim_in_pixel().0.max(1));
        let dodge = DODGE * (x.end - x.start) / width;
        let mut sketch = Sketch::default();
        self.draw_bands(&mut chart, &mut sketch, dodge)?;
        let swatch = |(x, y): (i32, i32)| {
            let style = KEY.filled().stroke_width(STROKE);
            ErrorBar::new_vertical(x + 10, y - 6, y, y + 6, style, CAP)
        };
        sketch.key(&mut chart, Self::KEY, swatch)?;
        sketch.legend(&mut chart)
    }
}
