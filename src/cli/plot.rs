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

use std::ops::Range;
use std::sync::OnceLock;

use anyhow::anyhow;
use image::{Rgb, RgbImage};
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::element::MultiLineText;
use plotters::prelude::*;
use plotters::style::{FontError, register_font};

/// The plots' typeface: DejaVu Sans, regular.
const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// The family [`FONT`] is known by, to `plotters` and in the SVG files (where a viewer
/// without it uses its own sans-serif face).
const FAMILY: &str = "sans-serif";

/// The size of a chart's title, as `plotters` takes text sizes (an em is 1/1.24 of it,
/// in pixels).
const TITLE_TEXT: f64 = 24.0;
/// The size of the axis titles.
const AXIS_TEXT: f64 = 18.0;
/// The size of the tick values.
const TICK_TEXT: f64 = 16.0;
/// The size of the legend's entries.
const LEGEND_TEXT: f64 = 16.0;
/// The size of a picture's [`label`].
const LABEL_TEXT: f64 = 20.0;
/// The smallest size that names on the x axis shrink to, so that they do not touch, and
/// a legend's entries, so that it fits across the plot area.
const SMALLEST_TEXT: f64 = 10.0;

/// Pixels around a chart.
const MARGIN: u32 = 10;
/// Pixels right of a chart, wider: the last x tick value stands out past the plot area.
const RIGHT_MARGIN: u32 = 28;
/// Pixels below the plot area, for the x tick values and the x axis title.
const X_AREA: u32 = 50;
/// Pixels left of the plot area, for the y tick values and the y axis title.
const Y_AREA: u32 = 86;
/// Tick values wanted on each axis, at most.
const TICKS: usize = 8;

/// Text and axes.
const INK: RGBColor = RGBColor(40, 40, 40);
/// Grid lines at the tick values.
const GRID: RGBColor = RGBColor(225, 225, 225);
/// The swatch of a legend's key: what a shading or a bar shows, for every series.
const KEY: RGBColor = RGBColor(120, 120, 120);
/// How much of a band's colour its shading mixes in.
const SHADE: f64 = 0.2;
/// Width of the lines, in pixels.
const STROKE: u32 = 2;

/// Pixels between the legend box's edge and its entries.
const LEGEND_MARGIN: i32 = 8;
/// The width of the legend's column of swatches, in pixels.
const SWATCH: i32 = 26;
/// Pixels between a legend and the plot area's edge.
const LEGEND_INSET: i32 = 5;

/// Pixels between the error bars of neighbouring bands at one x value, so that they do
/// not hide each other.
const DODGE: f64 = 7.0;
/// The width of an error bar's caps and of the dot at its mean, in pixels.
const CAP: u32 = 8;
/// The radius of a scatter chart's dots, in pixels.
const DOT: u32 = 3;

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
    fn len(&self) -> usize {
        match self {
            XValues::Numbers(v) => v.len(),
            XValues::Names(v) => v.len(),
        }
    }

    /// Where value `i` lies on the x axis.
    fn at(&self, i: usize) -> f64 {
        match self {
            XValues::Numbers(v) => v[i],
            XValues::Names(_) => i as f64,
        }
    }
}

/// Colours for lines that have no colour of their own, in the order they are handed out
/// ([`palette`]).
const PALETTE: [Rgb<u8>; 8] = [
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

/// The error of drawing on any backend.
type Failure<DB> = DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>;

/// The plot area of a chart: x by value, y as its scale places it.
type Plot<'a, DB, Y> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>;

/// A chart that draws itself on any `plotters` backend: the image's and the SVG's.
trait Chart {
    /// Draws the whole chart on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), Failure<DB>>;
}

/// `chart` drawn into an image and as SVG, both `size` pixels.
fn render(size: (u32, u32), chart: &impl Chart) -> anyhow::Result<Figure> {
    register()?;
    let mut png = RgbImage::new(size.0, size.1);
    {
        let root = BitMapBackend::with_buffer(&mut png, size).into_drawing_area();
        chart.draw(&root).map_err(failed)?;
        root.present().map_err(failed)?;
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        chart.draw(&root).map_err(failed)?;
        root.present().map_err(failed)?;
    }
    Ok(Figure { png, svg })
}

/// Registers [`FONT`] with `plotters` the first time it is called.
fn register() -> anyhow::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the plots' font cannot be read"))
    }
}

/// A drawing error as the commands report it.
fn failed(err: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("cannot draw a chart: {err}")
}

/// A font error met while laying a chart out, as a drawing error.
fn font_failed<DB: DrawingBackend>(_: FontError) -> Failure<DB> {
    DrawingAreaErrorKind::LayoutError
}

/// Text of size `size` in the plots' font.
fn text(size: f64) -> TextStyle<'static> {
    (FAMILY, size).into_font().color(&INK)
}

/// `colour` as `plotters` takes it.
fn rgb(colour: Rgb<u8>) -> RGBColor {
    let [r, g, b] = colour.0;
    RGBColor(r, g, b)
}

/// Fills `root` white, writes `title` at its top and returns its plot area, x spanning
/// `x` and y made by `y` from the plot area's height in pixels.
fn frame<'a, DB, Y>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x: Range<f64>,
    y: impl FnOnce(u32) -> Y,
) -> Result<Plot<'a, DB, Y::CoordDescType>, Failure<DB>>
where
    DB: DrawingBackend,
    Y: AsRangedCoord<Value = f64>,
{
    root.fill(&WHITE)?;
    let area = root
        .margin(MARGIN, MARGIN, MARGIN, RIGHT_MARGIN)
        .titled(title, text(TITLE_TEXT))?;
    let height = area.dim_in_pixel().1.saturating_sub(X_AREA);
    ChartBuilder::on(&area)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(x, y(height))
}

/// The grid, the axes with their tick values (written by `x` and `y`), and the axis
/// titles, ready to be drawn (a caller may change the ticks first).
fn mesh<'a, 'b, DB, Y>(
    chart: &'b mut Plot<'a, DB, Y>,
    titles: &Titles<'_>,
    x: &'b dyn Fn(&f64) -> String,
    y: &'b dyn Fn(&f64) -> String,
) -> plotters::chart::MeshStyle<'a, 'b, RangedCoordf64, Y, DB>
where
    DB: DrawingBackend,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(titles.x)
        .y_desc(titles.y)
        .axis_desc_style(text(AXIS_TEXT))
        .label_style(text(TICK_TEXT))
        .axis_style(INK)
        .bold_line_style(GRID)
        .light_line_style(TRANSPARENT)
        .x_labels(TICKS)
        .y_labels(TICKS)
        .x_label_formatter(x)
        .y_label_formatter(y);
    mesh
}

/// The decimals that the tick values of an axis spanning `range` need: those of the
/// smallest step `plotters` may choose for [`TICKS`] ticks.
fn decimals(range: &Range<f64>) -> usize {
    let step = (range.end - range.start).abs() / TICKS as f64;
    if step.is_finite() && step > 0.0 {
        (-step.log10()).ceil().clamp(0.0, 12.0) as usize
    } else {
        0
    }
}

/// Tick values with `decimals` decimals; never "-0".
fn fixed(decimals: usize) -> impl Fn(&f64) -> String {
    move |v| {
        let text = format!("{v:.decimals$}");
        match text.strip_prefix('-') {
            Some(zero) if zero.chars().all(|c| c == '0' || c == '.') => zero.to_owned(),
            _ => text,
        }
    }
}

/// Tick values of a log scale, as powers of ten: `1e-3`.
fn power(v: &f64) -> String {
    format!("{v:.0e}")
}

/// What has been drawn on a chart: the legend's entries so far and the data points
/// (with points along the lines) that the legend should not hide.
#[derive(Default)]
struct Sketch {
    /// The legend's entries, in order.
    names: Vec<String>,
    /// Data points, in data coordinates.
    ink: Vec<(f64, f64)>,
}

impl Sketch {
    /// Draws `points` joined by a line in `colour`, the line broken at every `None`,
    /// and names it `name` in the legend.
    fn line<'a, DB, Y>(
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
    fn shade<'a, DB, Y>(
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
    fn key<'a, DB, Y, E>(
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
    fn trace<DB, Y>(&mut self, chart: &Plot<'_, DB, Y>, lines: &[Vec<(f64, f64)>])
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
    fn legend_size(&self, size: f64) -> Result<(i32, i32), FontError> {
        let mut lines = MultiLineText::<_, &str>::new((0, 0), text(size));
        for name in &self.names {
            lines.push_line(name.as_str());
        }
        let (w, h) = lines.estimate_dimension()?;
        Ok((w + SWATCH + 2 * LEGEND_MARGIN, h + 2 * LEGEND_MARGIN))
    }

    /// The size of the legend's text: [`LEGEND_TEXT`], or smaller (down to
    /// [`SMALLEST_TEXT`]) where the legend would be wider than `room` pixels.
    fn legend_text(&self, room: i32) -> Result<f64, FontError> {
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
    fn legend<'a, DB, Y>(&self, chart: &mut Plot<'a, DB, Y>) -> Result<(), Failure<DB>>
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

/// The maximal runs of `Some` in `items`.
fn runs<T>(items: impl IntoIterator<Item = Option<T>>) -> Vec<Vec<T>> {
    let mut runs = vec![Vec::new()];
    for item in items {
        match item {
            Some(v) => runs.last_mut().expect("one run at least").push(v),
            None if runs.last().is_some_and(|r| !r.is_empty()) => runs.push(Vec::new()),
            None => {}
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// The least and the greatest finite value of `values`, if any.
fn extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// The range `lo..hi` with 5% room on each side; one unit each side of a single value,
/// and `-1..1` when there is no value.
fn padded(range: Option<(f64, f64)>) -> Range<f64> {
    match range {
        Some((lo, hi)) if lo < hi => {
            let pad = (hi - lo) * 0.05;
            lo - pad..hi + pad
        }
        Some((lo, _)) => lo - 1.0..lo + 1.0,
        None => -1.0..1.0,
    }
}

/// The range `lo..hi` as it is; `lo..lo + 1` for a single value and `0..1` for none.
fn tight(range: Option<(f64, f64)>) -> Range<f64> {
    match range {
        Some((lo, hi)) if lo < hi => lo..hi,
        Some((lo, _)) => lo..lo + 1.0,
        None => 0.0..1.0,
    }
}

/// The chart of [`curves`].
struct Curves<'a> {
    titles: &'a Titles<'a>,
    x: &'a [f64],
    lines: &'a [Line<'a>],
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

/// The chart of [`spreads`].
struct Spreads<'a> {
    titles: &'a Titles<'a>,
    x_max: f64,
    curves: &'a [Spread<'a>],
    scale: YScale,
    key: &'a str,
}

impl Spreads<'_> {
    /// Whether `y` can be placed on the chart's scale.
    fn shown(&self, y: f64) -> bool {
        y.is_finite() && (self.scale == YScale::Linear || y > 0.0)
    }

    /// The x axis's end: `x_max`, or 1 where it is not a positive number.
    fn x_end(&self) -> f64 {
        if self.x_max.is_finite() && self.x_max > 0.0 {
            self.x_max
        } else {
            1.0
        }
    }

    /// The finite values of the chart that its scale can place.
    fn values(&self) -> impl Iterator<Item = f64> + '_ {
        self.curves
            .iter()
            .flat_map(|c| [c.centre, c.low, c.high])
            .flatten()
            .copied()
            .filter(|&v| self.shown(v))
    }

    /// Draws the bands, then the lines over them, then the legend.
    fn curves<'a, DB, Y>(&self, chart: &mut Plot<'a, DB, Y>) -> Result<(), Failure<DB>>
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

/// The chart of [`error_bars`].
struct ErrorBars<'a> {
    titles: &'a Titles<'a>,
    x: &'a XValues<'a>,
    bands: &'a [Band<'a>],
}

impl ErrorBars<'_> {
    /// The x range: the numbers with a little room, or half a step beyond the first
    /// and the last name.
    fn x_range(&self) -> Range<f64> {
        match self.x {
            XValues::Numbers(values) => padded(extent(values.iter().copied())),
            XValues::Names(names) => -0.5..names.len() as f64 - 0.5,
        }
    }

    /// Every finite mean +- std of the bands (a non-finite std counted as 0).
    fn values(&self) -> impl Iterator<Item = f64> + '_ {
        self.bands.iter().flat_map(|b| {
            b.mean.iter().enumerate().flat_map(|(i, &m)| {
                let s = b.std.get(i).copied().filter(|s| s.is_finite());
                let s = s.unwrap_or(0.0);
                [m - s, m + s]
            })
        })
    }

    /// The legend's entries, as [`Self::draw`] adds them.
    fn sketch(&self) -> Sketch {
        let mut names: Vec<String> = self.bands.iter().map(|b| b.name.to_owned()).collect();
        names.push(Self::KEY.to_owned());
        Sketch {
            names,
            ink: Vec::new(),
        }
    }

    /// What the legend says the dots and bars are.
    const KEY: &'static str = "dot: mean, bar: mean +- std";

    /// The tick value text of the names on the x axis: as large as the tick values
    /// elsewhere where the widest name fits its share of the axis, smaller where it
    /// does not.
    fn name_text<DB: DrawingBackend>(
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
    fn draw_bands<DB: DrawingBackend>(
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

/// The chart of [`scatter`].
struct Scatter<'a> {
    titles: &'a Titles<'a>,
    points: &'a [(f64, f64)],
    colour: Rgb<u8>,
    name: &'a str,
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Names, titles and values with characters that XML escapes.
    const TITLES: Titles<'static> = Titles {
        title: "A chart <of> things",
        x: "time (seconds)",
        y: "best & worst",
    };

    /// Whether `svg` holds `text` as the text of an element (escaped as XML escapes it).
    fn holds(svg: &str, text: &str) -> bool {
        let escaped = text
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        svg.contains(&format!(">\n{escaped}\n<")) || svg.contains(&format!(">{escaped}\n<"))
    }

    /// Checks that `figure` is `size` pixels, not blank, and that its SVG holds the
    /// titles and every name in `legend`.
    fn check(figure: &Figure, size: (u32, u32), legend: &[&str]) {
        assert_eq!(figure.png.dimensions(), size);
        assert!(
            figure.png.pixels().any(|p| p.0 != [255, 255, 255]),
            "a blank picture"
        );
        let svg = &figure.svg;
        assert!(svg.starts_with("<svg"), "{svg}");
        for text in [TITLES.title, TITLES.x, TITLES.y].iter().chain(legend) {
            assert!(holds(svg, text), "no `{text}` in the SVG:\n{svg}");
        }
    }

    #[test]
    fn curves_name_every_line() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let lines = [
            Line {
                name: "best",
                colour: palette(0),
                values: &[1.0, 2.0, 2.5, 3.0],
            },
            Line {
                name: "mean",
                colour: palette(1),
                values: &[0.5, f64::NAN, 1.5, 2.0],
            },
        ];
        let figure = curves((640, 400), &TITLES, &x, &lines).unwrap();
        check(&figure, (640, 400), &["best", "mean"]);
    }

    #[test]
    fn bands_name_every_band_and_their_shading() {
        let bands_ = [Band {
            name: "population=40",
            colour: palette(2),
            mean: &[1.0, 2.0, 3.0],
            std: &[0.1, f64::NAN, 0.3],
        }];
        let figure = bands((800, 500), &TITLES, 300.0, &bands_).unwrap();
        check(
            &figure,
            (800, 500),
            &["population=40", "line: mean, shaded: mean +- std"],
        );
    }

    #[test]
    fn spreads_on_a_log_scale_write_powers_of_ten() {
        let spread = Spread {
            name: "ga",
            colour: palette(0),
            centre: &[1.0, 0.1, 0.01, 0.0],
            low: &[0.5, 0.05, 0.005, -1.0],
            high: &[2.0, 0.2, 0.02, 0.001],
        };
        let key = "line: median, shaded: quartiles";
        let figure = spreads((800, 500), &TITLES, 2.0, &[spread], YScale::Log, key).unwrap();
        check(&figure, (800, 500), &["ga", key]);
        for decade in ["1e-3", "1e-2", "1e-1", "1e0"] {
            assert!(holds(&figure.svg, decade), "no tick {decade}");
        }
    }

    #[test]
    fn error_bars_name_their_x_values_and_bands() {
        let names = ["tournament_roulette", "tournament", "roulette", "random"].map(String::from);
        let bands_ = [
            Band {
                name: "population=20",
                colour: palette(0),
                mean: &[1.0, 2.0, f64::NAN, 1.5],
                std: &[0.5, 0.0, 0.0, 0.25],
            },
            Band {
                name: "population=40",
                colour: palette(1),
                mean: &[1.5, 2.5, 1.0, 2.0],
                std: &[0.5, f64::INFINITY, 0.0, 0.25],
            },
        ];
        let figure = error_bars((800, 500), &TITLES, &XValues::Names(&names), &bands_).unwrap();
        let mut legend = vec!["population=20", "population=40", ErrorBars::KEY];
        legend.extend(names.iter().map(String::as_str));
        check(&figure, (800, 500), &legend);
        let numbers = error_bars(
            (800, 500),
            &TITLES,
            &XValues::Numbers(&[10.0, 20.0, 50.0, 100.0]),
            &bands_,
        )
        .unwrap();
        check(&numbers, (800, 500), &["population=20", ErrorBars::KEY]);
    }

    #[test]
    fn scatter_names_its_points() {
        let points = [(1.0, 2.0), (2.0, f64::NAN), (3.0, 1.0)];
        let figure = scatter((640, 480), &TITLES, &points, palette(0), "front").unwrap();
        check(&figure, (640, 480), &["front"]);
    }

    #[test]
    fn empty_and_non_finite_data_still_make_a_chart() {
        let nothing: [f64; 0] = [];
        let nan = [f64::NAN; 3];
        let figures = [
            curves((640, 400), &TITLES, &nothing, &[]).unwrap(),
            curves(
                (640, 400),
                &TITLES,
                &nan,
                &[Line {
                    name: "best",
                    colour: palette(0),
                    values: &nan,
                }],
            )
            .unwrap(),
            bands((800, 500), &TITLES, f64::NAN, &[]).unwrap(),
            spreads(
                (800, 500),
                &TITLES,
                0.0,
                &[Spread {
                    name: "ga",
                    colour: palette(0),
                    centre: &nan,
                    low: &nan,
                    high: &[0.0; 3],
                }],
                YScale::Log,
                "shaded",
            )
            .unwrap(),
            error_bars((800, 500), &TITLES, &XValues::Names(&[]), &[]).unwrap(),
            error_bars(
                (800, 500),
                &TITLES,
                &XValues::Numbers(&nan),
                &[Band {
                    name: "all",
                    colour: palette(0),
                    mean: &nan,
                    std: &nan,
                }],
            )
            .unwrap(),
            scatter((640, 480), &TITLES, &[(f64::NAN, 1.0)], palette(0), "front").unwrap(),
        ];
        for figure in &figures {
            assert!(holds(&figure.svg, TITLES.title));
        }
    }

    #[test]
    fn the_same_data_give_the_same_bytes() {
        let draw = || {
            let lines = [Line {
                name: "best",
                colour: palette(0),
                values: &[1.0, 2.0, 4.0],
            }];
            curves((640, 400), &TITLES, &[0.0, 1.0, 2.0], &lines).unwrap()
        };
        let (a, b) = (draw(), draw());
        assert_eq!(a.png, b.png);
        assert_eq!(a.svg, b.svg);
    }

    #[test]
    fn the_legend_keeps_out_of_the_data() {
        // A falling line ends in the bottom right corner, where the legend would go.
        let values: Vec<f64> = (0..50).map(|i| 50.0 - f64::from(i)).collect();
        let x: Vec<f64> = (0..50).map(f64::from).collect();
        let line = [Line {
            name: "falling",
            colour: palette(2),
            values: &values,
        }];
        let figure = curves((640, 400), &TITLES, &x, &line).unwrap();
        // The legend's box is drawn in the top right, bottom left or top left: its
        // border passes near one of those corners of the plot area, never the bottom
        // right, where the line's last pixels stay visible.
        let ink = rgb(palette(2));
        let (w, h) = figure.png.dimensions();
        let coloured = |x0: u32, y0: u32, x1: u32, y1: u32| {
            (y0..y1).any(|y| {
                (x0..x1).any(|x| {
                    let p = figure.png.get_pixel(x, y).0;
                    p == [ink.0, ink.1, ink.2]
                })
            })
        };
        assert!(
            coloured(w - 60, h - 90, w - 20, h - 50),
            "the line's end is hidden"
        );
    }

    #[test]
    fn tick_values_have_the_decimals_their_step_needs() {
        assert_eq!(decimals(&(0.0..300.0)), 0);
        assert_eq!(decimals(&(0.0..2.0)), 1);
        assert_eq!(decimals(&(1.5..1.6)), 2);
        assert_eq!(decimals(&(1.0..1.0)), 0);
        let one = fixed(1);
        assert_eq!(one(&0.30000000000000004), "0.3");
        assert_eq!(one(&-0.01), "0.0");
        assert_eq!(one(&-0.5), "-0.5");
        assert_eq!(power(&0.001), "1e-3");
    }

    #[test]
    fn a_long_legend_shrinks_to_fit_the_plot_area() {
        register().unwrap();
        let sketch = Sketch {
            names: vec!["a".repeat(200)],
            ink: Vec::new(),
        };
        let room = sketch.legend_size(LEGEND_TEXT).unwrap().0 * 3 / 4;
        let size = sketch.legend_text(room).unwrap();
        assert!((SMALLEST_TEXT..LEGEND_TEXT).contains(&size), "{size}");
        assert!(sketch.legend_size(size).unwrap().0 <= room + 2);
        assert_eq!(sketch.legend_text(10_000).unwrap(), LEGEND_TEXT);
    }

    #[test]
    fn a_label_is_drawn_in_the_corner() {
        let mut image = RgbImage::from_pixel(64, 64, Rgb([0, 0, 0]));
        label(&mut image, "12").unwrap();
        // The white box behind the text, and dark text on it.
        assert_eq!(image.get_pixel(1, 1).0, [255, 255, 255]);
        let inked = (0..24).any(|y| (0..32).any(|x| image.get_pixel(x, y).0[0] < 128));
        assert!(inked);
        assert_eq!(image.get_pixel(60, 60).0, [0, 0, 0]);
    }
}
