//! The plots' look: the typeface, text sizes, margins, colours and strokes, and the
//! text styles and colours made from them.

use image::Rgb;
use plotters::prelude::*;

/// The plots' typeface: DejaVu Sans, regular.
pub(super) const FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

/// The family [`FONT`] is known by, to `plotters` and in the SVG files (where a viewer
/// without it uses its own sans-serif face).
pub(super) const FAMILY: &str = "sans-serif";

/// The size of a chart's title, as `plotters` takes text sizes (an em is 1/1.24 of it,
/// in pixels).
pub(super) const TITLE_TEXT: f64 = 24.0;

/// The size of the axis titles.
pub(super) const AXIS_TEXT: f64 = 18.0;

/// The size of the tick values.
pub(super) const TICK_TEXT: f64 = 16.0;

/// The size of the legend's entries.
pub(super) const LEGEND_TEXT: f64 = 16.0;

/// The size of a picture's [`label`].
pub(super) const LABEL_TEXT: f64 = 20.0;

/// The smallest size that names on the x axis shrink to, so that they do not touch, and
/// a legend's entries, so that it fits across the plot area.
pub(super) const SMALLEST_TEXT: f64 = 10.0;

/// Pixels around a chart.
pub(super) const MARGIN: u32 = 10;

/// Pixels right of a chart, wider: the last x tick value stands out past the plot area.
pub(super) const RIGHT_MARGIN: u32 = 28;

/// Pixels below the plot area, for the x tick values and the x axis title.
pub(super) const X_AREA: u32 = 50;

/// Pixels left of the plot area, for the y tick values and the y axis title.
pub(super) const Y_AREA: u32 = 86;

/// Tick values wanted on each axis, at most.
pub(super) const TICKS: usize = 8;

/// Text and axes.
pub(super) const INK: RGBColor = RGBColor(40, 40, 40);

/// Grid lines at the tick values.
pub(super) const GRID: RGBColor = RGBColor(225, 225, 225);

/// The swatch of a legend's key: what a shading or a bar shows, for every series.
pub(super) const KEY: RGBColor = RGBColor(120, 120, 120);

/// How much of a band's colour its shading mixes in.
pub(super) const SHADE: f64 = 0.2;

/// Width of the lines, in pixels.
pub(super) const STROKE: u32 = 2;

/// Pixels between the legend box's edge and its entries.
pub(super) const LEGEND_MARGIN: i32 = 8;

/// The width of the legend's column of swatches, in pixels.
pub(super) const SWATCH: i32 = 26;

/// Pixels between a legend and the plot area's edge.
pub(super) const LEGEND_INSET: i32 = 5;

/// Pixels between the error bars of neighbouring bands at one x value, so that they do
/// not hide each other.
pub(super) const DODGE: f64 = 7.0;

/// The width of an error bar's caps and of the dot at its mean, in pixels.
pub(super) const CAP: u32 = 8;

/// The radius of a scatter chart's dots, in pixels.
pub(super) const DOT: u32 = 3;

/// Text of size `size` in the plots' font.
pub(super) fn text(size: f64) -> TextStyle<'static> {
    (FAMILY, size).into_font().color(&INK)
}

/// `colour` as `plotters` takes it.
pub(super) fn rgb(colour: Rgb<u8>) -> RGBColor {
    let [r, g, b] = colour.0;
    RGBColor(r, g, b)
}
