//! What the charts are handed: titles, lines, bands, spreads and x values, the colours
//! that series without their own take, and the drawn [`Figure`].

use image::{Rgb, RgbImage};

/// The words of a chart: its title and its axes' titles (with their units).
#[derive(Clone, Copy, Debug)]
pub struct Titles<'a> {
    /// Above the chart.
    pub title: &'a str,
    /// Under the x axis.
    pub x: &'a str,
    /// Beside the y axis.
    pub y: &'a str,
}

/// A chart drawn twice from one description: as pixels and as an SVG document.
#[derive(Clone, Debug)]
pub struct Figure {
    /// The chart as pixels, for the PNG file.
    pub png: RgbImage,
    /// The chart as SVG, with its text as text.
    pub svg: String,
}

/// One line of [`curves`]: a value per x value.
pub struct Line<'a> {
    /// The legend's name for it.
    pub name: &'a str,
    /// Its colour.
    pub colour: Rgb<u8>,
    /// The value per x value; non-finite values leave gaps.
    pub values: &'a [f64],
}

/// One curve of [`bands`] or [`error_bars`]: a mean and its standard deviation per point
/// of a common grid (the x values).
pub struct Band<'a> {
    /// The legend's name for it.
    pub name: &'a str,
    /// Its colour.
    pub colour: Rgb<u8>,
    /// The mean per grid point; non-finite values leave gaps.
    pub mean: &'a [f64],
    /// The standard deviation per grid point, shaded (or drawn as a bar) as mean +- std.
    pub std: &'a [f64],
}

/// One curve of [`spreads`]: a centre line (a median, say) over a shaded band from
/// `low` to `high` (its quartiles), per point of a common grid.
pub struct Spread<'a> {
    /// The legend's name for it.
    pub name: &'a str,
    /// Its colour.
    pub colour: Rgb<u8>,
    /// The line, per grid point; non-finite values leave gaps.
    pub centre: &'a [f64],
    /// The lower edge of the band, per grid point.
    pub low: &'a [f64],
    /// The upper edge of the band, per grid point.
    pub high: &'a [f64],
}

/// How [`spreads`] places y values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum YScale {
    /// By value, with round numbers as ticks.
    Linear,
    /// By their base-10 logarithm, over whole decades; values of 0 or less leave gaps.
    Log,
}

/// The x values of [`error_bars`]: numbers placed by value on a numbered axis, or names
/// placed evenly in their order, each under its own tick.
pub enum XValues<'a> {
    /// Numeric values.
    Numbers(&'a [f64]),
    /// Names (categories), in order.
    Names(&'a [String]),
}

impl XValues<'_> {
    /// How many values there are.
    pub(super) fn len(&self) -> usize {
        match self {
            XValues::Numbers(v) => v.len(),
            XValues::Names(v) => v.len(),
        }
    }

    /// Where value `i` lies on the x axis.
    pub(super) fn at(&self, i: usize) -> f64 {
        match self {
            XValues::Numbers(v) => v[i],
            XValues::Names(_) => i as f64,
        }
    }
}

/// Colours for lines that have no colour of their own, in the order they are handed out
/// ([`palette`]).
pub(super) const PALETTE: [Rgb<u8>; 8] = [
    Rgb([30, 80, 200]),
    Rgb([230, 120, 20]),
    Rgb([30, 150, 60]),
    Rgb([200, 30, 40]),
    Rgb([130, 60, 170]),
    Rgb([120, 80, 40]),
    Rgb([220, 90, 170]),
    Rgb([40, 160, 170]),
];

/// The `i`th colour of a plot's lines: eight distinct colours, then again from the first.
pub fn palette(i: usize) -> Rgb<u8> {
    PALETTE[i % PALETTE.len()]
}
