//! Charts as pictures: best and mean fitness against generations for one run, several
//! methods' curves with their spread against time or evaluations for a comparison (on a
//! linear or a log scale), final values with error bars against a swept setting (numbers
//! or names), and the values of two objectives across a multi-objective front.
//!
//! Every chart is drawn with `plotters` twice from one description: into an image for
//! the PNG file and as an SVG document beside it ([`Figure`]). Each has a title, axis
//! titles, tick values on both axes and a legend naming every series and what its
//! shading or bars show. The text is set in DejaVu Sans, compiled into the program
//! (`assets/fonts/`, with its licence), so that no font or font library of the machine
//! is needed. Nothing in the drawing depends on the time or on hashing: the same data
//! give the same bytes.
//!
//! This module is the only one that knows `plotters`: the others hand it numbers, names
//! and colours.

mod chart;
mod curves;
mod error_bars;
mod scatter;
mod series;
mod sketch;
mod spreads;
mod style;

pub use series::{Band, Figure, Line, Spread, Titles, XValues, YScale, palette};

use image::{Rgb, RgbImage};
use plotters::prelude::*;

use chart::{failed, register, render};
use curves::Curves;
use error_bars::ErrorBars;
use scatter::Scatter;
use spreads::Spreads;
use style::{LABEL_TEXT, text};

/// Plots each line against `x`, whole numbers such as generations (one per value of the
/// line; the x ticks fall on whole numbers), all on one scale: x spans the finite x
/// values and y every finite value of the lines. Non-finite values leave gaps.
pub fn curves(
    size: (u32, u32),
    titles: &Titles<'_>,
    x: &[f64],
    lines: &[Line<'_>],
) -> anyhow::Result<Figure> {
    render(size, &Curves { titles, x, lines })
}

/// Plots each band's mean as a line over its shaded mean +- std, against x from 0 to
/// `x_max` (point `i` of `n` at `x_max * i / (n - 1)`). The y range spans every finite
/// mean +- std, with a little room.
pub fn bands(
    size: (u32, u32),
    titles: &Titles<'_>,
    x_max: f64,
    bands: &[Band<'_>],
) -> anyhow::Result<Figure> {
    let edges: Vec<(Vec<f64>, Vec<f64>)> = bands
        .iter()
        .map(|b| {
            b.mean
                .iter()
                .zip(b.std)
                .map(|(&m, &s)| {
                    let s = if s.is_finite() { s } else { 0.0 };
                    (m - s, m + s)
                })
                .unzip()
        })
        .collect();
    let spreads: Vec<Spread<'_>> = bands
        .iter()
        .zip(&edges)
        .map(|(b, (low, high))| Spread {
            name: b.name,
            colour: b.colour,
            centre: b.mean,
            low,
            high,
        })
        .collect();
    self::spreads(
        size,
        titles,
        x_max,
        &spreads,
        YScale::Linear,
        "line: mean, shaded: mean +- std",
    )
}

/// Plots each curve's centre as a line over its shaded band from `low` to `high`,
/// against x from 0 to `x_max` (point `i` of `n` at `x_max * i / (n - 1)`), y placed by
/// `scale`; the legend names the curves and, last, says what the lines and the
/// shading are (`key`). The y range spans every finite value of the centres and the
/// bands (on a log scale, whole decades).
pub fn spreads(
    size: (u32, u32),
    titles: &Titles<'_>,
    x_max: f64,
    curves: &[Spread<'_>],
    scale: YScale,
    key: &str,
) -> anyhow::Result<Figure> {
    render(
        size,
        &Spreads {
            titles,
            x_max,
            curves,
            scale,
            key,
        },
    )
}

/// Plots each band as error bars at the `x` values: a dot at the mean, a bar from mean -
/// std to mean + std with caps, and lines joining neighbouring means (a non-finite mean
/// leaves a gap); names stand each under its own tick. The bands are set a few pixels
/// apart at each x, and the legend, naming them and saying what the dots and bars are,
/// stands in room left for it above the data. Each band holds one mean and one std per
/// x value.
pub fn error_bars(
    size: (u32, u32),
    titles: &Titles<'_>,
    x: &XValues<'_>,
    bands: &[Band<'_>],
) -> anyhow::Result<Figure> {
    render(size, &ErrorBars { titles, x, bands })
}

/// Plots `points` `(x, y)` as dots named `name` in the legend, against axes spanning
/// every finite point (with a little room). Points with a non-finite coordinate are
/// left out.
pub fn scatter(
    size: (u32, u32),
    titles: &Titles<'_>,
    points: &[(f64, f64)],
    colour: Rgb<u8>,
    name: &str,
) -> anyhow::Result<Figure> {
    render(
        size,
        &Scatter {
            titles,
            points,
            colour,
            name,
        },
    )
}

/// Writes `text` at the top-left corner of `image`, on a white box.
pub fn label(image: &mut RgbImage, text: &str) -> anyhow::Result<()> {
    register()?;
    let size = image.dimensions();
    let root = BitMapBackend::with_buffer(image, size).into_drawing_area();
    let style = self::text(LABEL_TEXT);
    let (w, h) = root.estimate_text_size(text, &style).map_err(failed)?;
    let corner = (w as i32 + 8, h as i32 + 8);
    root.draw(&Rectangle::new([(0, 0), corner], WHITE.filled()))
        .map_err(failed)?;
    root.draw_text(text, &style, (4, 4)).map_err(failed)?;
    root.present().map_err(failed)
}

#[cfg(test)]
mod tests;
