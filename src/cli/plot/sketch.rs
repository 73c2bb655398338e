//! The legend and the lines, bands and bars of a chart, drawn on its plot area
//! ([`Sketch`]).

use plotters::coord::ranged1d::Ranged;
use plotters::element::MultiLineText;
use plotters::prelude::*;
use plotters::style::FontError;

use super::chart::{Failure, Plot, font_failed, runs};
use super::style::{
    INK, LEGEND_INSET, LEGEND_MARGIN, LEGEND_TEXT, SHADE, SMALLEST_TEXT, STROKE, SWATCH, text,
};

/// What has been drawn on a chart: the legend's entries so far and the data points
/// (with points along the lines) that the legend should not hide.
#[derive(Default)]
pub(super) struct Sketch {
    /// The legend's entries, in order.
    pub(super) names: Vec<String>,
    /// Data points, in data coordinates.
    pub(super) ink: Vec<(f64, f64)>,
}

impl Sketch {
    /// Draws `points` joined by a line in `colour`, the line broken at every `None`,
    /// and names it `name` in the legend.
    pub(super) fn line<'a, DB, Y>(
        &mut self,
        chart: &mut Plot<'a, DB, Y>,
        name: &str,
        colour: RGBColor,
        points: impl IntoIterator<Item = Option<(f64, f64)>>,
    ) -> Result<(), Failure<DB>>
    where
        DB: DrawingBackend,
        Y: Ranged<ValueType = f64>,
    {
        let style = colour.stroke_width(STROKE);
        let runs = runs(points);
        self.trace(chart, &runs);
        chart
            .draw_series(runs.into_iter().map(|run| PathElement::new(run, style)))?
            .label(name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + SWATCH - 6, y)], style));
        self.names.push(name.to_owned());
        Ok(())
    }

    /// Shades the band between `low` and `high` in a light tint of `colour`, broken at
    /// every `None`.
    pub(super) fn shade<'a, DB, Y>(
        &mut self,
        chart: &mut Plot<'a, DB, Y>,
        colour: RGBColor,
        edges: impl IntoIterator<Item = Option<(f64, f64, f64)>>,
    ) -> Result<(), Failure<DB>>
    where
        DB: DrawingBackend,
        Y: Ranged<ValueType = f64>,
    {
        let runs = runs(edges);
        let outlines: Vec<Vec<(f64, f64)>> = runs
            .iter()
            .map(|run| {
                let upper = run.iter().map(|&(x, _, high)| (x, high));
                let lower = run.iter().rev().map(|&(x, low, _)| (x, low));
                upper.chain(lower).collect()
            })
            .collect();
        self.trace(chart, &outlines);
        chart.draw_series(
            outlines
                .into_iter()
                .map(|outline| Polygon::new(outline, colour.mix(SHADE).filled())),
        )?;
        Ok(())
    }

    /// Adds a legend entry `name` with the neutral swatch `swatch` that says what the
    /// shadings or bars of every series show.
    pub(super) fn key<'a, DB, Y, E>(
        &mut self,
        chart: &mut Plot<'a, DB, Y>,
        name: &str,
        swatch: impl Fn((i32, i32)) -> E + 'a,
    ) -> Result<(), Failure<DB>>
    where
        DB: DrawingBackend + 'a,
        Y: Ranged<ValueType = f64>,
        E: IntoDynElement<'a, DB, (i32, i32)>,
    {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())?
            .label(name)
            .legend(swatch);
        self.names.push(name.to_owned());
        Ok(())
    }

    /// Adds the points of `lines` to the ink, with points every few pixels along them
    /// so that a legend box between two far apart points still counts the line.
    pub(super) fn trace<DB, Y>(&mut self, chart: &Plot<'_, DB, Y>, lines: &[Vec<(f64, f64)>])
    where
        DB: DrawingBackend,
        Y: Ranged<ValueType = f64>,
    {
        for line in lines {
            self.ink.extend(line.first().copied());
            for pair in line.windows(2) {
                let (a, b) = (chart.backend_coord(&pair[0]), chart.backend_coord(&pair[1]));
                let pixels = (a.0 - b.0).abs().max((a.1 - b.1).abs());
                let steps = (pixels / 4).max(1);
                for s in 1..=steps {
                    let t = f64::from(s) / f64::from(steps);
                    let (x0, y0) = pair[0];
                    let (x1, y1) = pair[1];
                    self.ink.push((x0 + (x1 - x0) * t, y0 + (y1 - y0) * t));
                }
            }
        }
    }

    /// The size in pixels of the legend's box with its entries in text of size `size`.
    pub(super) fn legend_size(&self, size: f64) -> Result<(i32, i32), FontError> {
        let mut lines = MultiLineText::<_, &str>::new((0, 0), text(size));
        for name in &self.names {
            lines.push_line(name.as_str());
        }
        let (w, h) = lines.estimate_dimension()?;
        Ok((w + SWATCH + 2 * LEGEND_MARGIN, h + 2 * LEGEND_MARGIN))
    }

    /// The size of the legend's text: [`LEGEND_TEXT`], or smaller (down to
    /// [`SMALLEST_TEXT`]) where the legend would be wider than `room` pixels.
    pub(super) fn legend_text(&self, room: i32) -> Result<f64, FontError> {
        let (w, _) = self.legend_size(LEGEND_TEXT)?;
        let fixed = SWATCH + 2 * LEGEND_MARGIN;
        if w <= room || w <= fixed {
            return Ok(LEGEND_TEXT);
        }
        let fit = LEGEND_TEXT * f64::from(room - fixed) / f64::from(w - fixed);
        Ok(fit.max(SMALLEST_TEXT))
    }

    /// Draws the legend in the corner of the plot area where it hides the fewest data
    /// points: the bottom right, the top right, the top left or the bottom left, the
    /// first among equals; nothing when there is no entry.
    pub(super) fn legend<'a, DB, Y>(&self, chart: &mut Plot<'a, DB, Y>) -> Result<(), Failure<DB>>
    where
        DB: DrawingBackend + 'a,
        Y: Ranged<ValueType = f64>,
    {
        if self.names.is_empty() {
            return Ok(());
        }
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        let size = self
            .legend_text(xs.end - xs.start - 2 * LEGEND_INSET)
            .map_err(font_failed::<DB>)?;
        let (w, h) = self.legend_size(size).map_err(font_failed::<DB>)?;
        let pixels: Vec<(i32, i32)> = self
            .ink
            .iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|p| chart.backend_coord(p))
            .collect();
        let (left, right) = (xs.start + LEGEND_INSET, xs.end - w - LEGEND_INSET);
        let (top, bottom) = (ys.start + LEGEND_INSET, ys.end - h - LEGEND_INSET);
        let corners = [
            (SeriesLabelPosition::LowerRight, (right, bottom)),
            (SeriesLabelPosition::UpperRight, (right, top)),
            (SeriesLabelPosition::UpperLeft, (left, top)),
            (SeriesLabelPosition::LowerLeft, (left, bottom)),
        ];
        let hidden = |&(x0, y0): &(i32, i32)| {
            pixels
                .iter()
                .filter(|&&(x, y)| (x0..=x0 + w).contains(&x) && (y0..=y0 + h).contains(&y))
                .count()
        };
        let corner = corners
            .into_iter()
            .min_by_key(|(_, at)| hidden(at))
            .map_or(SeriesLabelPosition::LowerRight, |(corner, _)| corner);
        chart
            .configure_series_labels()
            .position(corner)
            .margin(LEGEND_MARGIN as u32)
            .legend_area_size(SWATCH as u32)
            .label_font(text(size))
            .background_style(WHITE.mix(0.8))
            .border_style(INK)
            .draw()
    }
}
