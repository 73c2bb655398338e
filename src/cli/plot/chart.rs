//! What every chart shares: drawing a [`Chart`] into an image and as SVG (with the
//! font registered once, and the errors of drawing), its frame and mesh, the tick
//! values' text, and the ranges its axes span.

use std::ops::Range;
use std::sync::OnceLock;

use anyhow::anyhow;
use image::RgbImage;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::{FontError, register_font};

use super::series::{Figure, Titles};
use super::style::{
    AXIS_TEXT, FAMILY, FONT, GRID, INK, MARGIN, RIGHT_MARGIN, TICK_TEXT, TICKS, TITLE_TEXT, X_AREA,
    Y_AREA, text,
};

/// The error of drawing on any backend.
pub(super) type Failure<DB> = DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>;

/// The plot area of a chart: x by value, y as its scale places it.
pub(super) type Plot<'a, DB, Y> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>;

/// A chart that draws itself on any `plotters` backend: the image's and the SVG's.
pub(super) trait Chart {
    /// Draws the whole chart on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), Failure<DB>>;
}

/// `chart` drawn into an image and as SVG, both `size` pixels.
pub(super) fn render(size: (u32, u32), chart: &impl Chart) -> anyhow::Result<Figure> {
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

/// Fills `root` white, writes `title` at its top and returns its plot area, x spanning
/// `x` and y made by `y` from the plot area's height in pixels.
pub(super) fn frame<'a, DB, Y>(
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
pub(super) fn mesh<'a, 'b, DB, Y>(
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
pub(super) fn decimals(range: &Range<f64>) -> usize {
    let step = (range.end - range.start).abs() / TICKS as f64;
    if step.is_finite() && step > 0.0 {
        (-step.log10()).ceil().clamp(0.0, 12.0) as usize
    } else {
        0
    }
}

/// Tick values with `decimals` decimals; never "-0".
pub(super) fn fixed(decimals: usize) -> impl Fn(&f64) -> String {
    move |v| {
        let text = format!("{v:.decimals$}");
        match text.strip_prefix('-') {
            Some(zero) if zero.chars().all(|c| c == '0' || c == '.') => zero.to_owned(),
            _ => text,
        }
    }
}

/// Tick values of a log scale, as powers of ten: `1e-3`.
pub(super) fn power(v: &f64) -> String {
    format!("{v:.0e}")
}

/// The maximal runs of `Some` in `items`.
pub(super) fn runs<T>(items: impl IntoIterator<Item = Option<T>>) -> Vec<Vec<T>> {
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
pub(super) fn extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
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
pub(super) fn padded(range: Option<(f64, f64)>) -> Range<f64> {
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
pub(super) fn tight(range: Option<(f64, f64)>) -> Range<f64> {
    match range {
        Some((lo, hi)) if lo < hi => lo..hi,
        Some((lo, _)) => lo..lo + 1.0,
        None => 0.0..1.0,
    }
}

/// Registers [`FONT`] with `plotters` the first time it is called.
pub(super) fn register() -> anyhow::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the plots' font cannot be read"))
    }
}

/// A drawing error as the commands report it.
pub(super) fn failed(err: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("cannot draw a chart: {err}")
}

/// A font error met while laying a chart out, as a drawing error.
pub(super) fn font_failed<DB: DrawingBackend>(_: FontError) -> Failure<DB> {
    DrawingAreaErrorKind::LayoutError
}
