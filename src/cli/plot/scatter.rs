//! Dots at two objectives' values: a multi-objective front.

use image::Rgb;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::chart::{Chart, Failure, decimals, extent, fixed, frame, mesh, padded};
use super::series::Titles;
use super::sketch::Sketch;
use super::style::{DOT, rgb};

/// The chart of [`scatter`].
pub(super) struct Scatter<'a> {
    pub(super) titles: &'a Titles<'a>,
    pub(super) points: &'a [(f64, f64)],
    pub(super) colour: Rgb<u8>,
    pub(super) name: &'a str,
}

impl Chart for Scatter<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), Failure<DB>> {
        let finite: Vec<(f64, f64)> = self
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        let x = padded(extent(finite.iter().map(|p| p.0)));
        let y = padded(extent(finite.iter().map(|p| p.1)));
        let (x_text, y_text) = (fixed(decimals(&x)), fixed(decimals(&y)));
        let mut chart = frame(root, self.titles.title, x, |_| y)?;
        mesh(&mut chart, self.titles, &x_text, &y_text).draw()?;
        let style = rgb(self.colour).filled();
        chart
            .draw_series(finite.iter().map(|&p| Circle::new(p, DOT, style)))?
            .label(self.name)
            .legend(move |(x, y)| Circle::new((x + 10, y), DOT, style));
        let sketch = Sketch {
            names: vec![self.name.to_owned()],
            ink: finite,
        };
        sketch.legend(&mut chart)
    }
}
