//! Plots as pictures: best and mean fitness against generations for one run, several
//! methods' curves with their spread against time or evaluations for a comparison (on a
//! linear or a log scale), final values
//! with error bars against a swept setting (numbers or names), and the values of two
//! objectives across a multi-objective front.

mod font;

use image::{Rgb, RgbImage};

const BACKGROUND: Rgb<u8> = Rgb([255, 255, 255]);
const GRID: Rgb<u8> = Rgb([225, 225, 225]);
const AXES: Rgb<u8> = Rgb([90, 90, 90]);
const MARGIN: u32 = 24;

/// Plots each `(colour, series)` against its index, all on one scale: the y range spans
/// every finite value, with grid lines at tenths. Non-finite values leave gaps.
pub fn curves(width: u32, height: u32, series: &[(Rgb<u8>, &[f64])]) -> RgbImage {
    let mut image = RgbImage::from_pixel(width, height, BACKGROUND);
    let (x0, x1) = (MARGIN as f64, f64::from(width - MARGIN));
    let (y0, y1) = (f64::from(height - MARGIN), MARGIN as f64);
    for i in 0..=10 {
        let y = (y0 + (y1 - y0) * f64::from(i) / 10.0) as u32;
        let x = (x0 + (x1 - x0) * f64::from(i) / 10.0) as u32;
        for px in MARGIN..=width - MARGIN {
            image.put_pixel(px, y, GRID);
        }
        for py in MARGIN..=height - MARGIN {
            image.put_pixel(x, py, GRID);
        }
    }
    let finite = series
        .iter()
        .flat_map(|(_, s)| s.iter().copied())
        .filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let (lo, hi) = if lo < hi {
        (lo, hi)
    } else {
        (lo - 1.0, lo + 1.0)
    };
    let longest = series
        .iter()
        .map(|(_, s)| s.len())
        .max()
        .unwrap_or(0)
        .max(2);
    let at = |i: usize, v: f64| {
        let x = x0 + (x1 - x0) * i as f64 / (longest - 1) as f64;
        let y = y0 + (y1 - y0) * (v - lo) / (hi - lo);
        (x, y)
    };
    for (colour, values) in series {
        for (i, pair) in values.windows(2).enumerate() {
            if pair[0].is_finite() && pair[1].is_finite() {
                line(&mut image, at(i, pair[0]), at(i + 1, pair[1]), *colour);
            }
        }
    }
    for px in MARGIN..=width - MARGIN {
        image.put_pixel(px, height - MARGIN, AXES);
    }
    for py in MARGIN..=height - MARGIN {
        image.put_pixel(MARGIN, py, AXES);
    }
    image
}

/// A line two pixels thick from `a` to `b`.
fn line(image: &mut RgbImage, a: (f64, f64), b: (f64, f64), colour: Rgb<u8>) {
    let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil() as usize).max(1);
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        let (x, y) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
        for (dx, dy) in [(0.0, 0.0), (0.0, 1.0)] {
            let (px, py) = ((x + dx) as u32, (y + dy) as u32);
            if px < image.width() && py < image.height() {
                image.put_pixel(px, py, colour);
            }
        }
    }
}

/// One curve of [`bands`] or [`error_bars`]: a mean and its standard deviation per point
/// of a common grid (the x values).
pub struct Band<'a> {
    /// The legend's name for it; a plot whose bands all have empty names has no legend.
    pub name: &'a str,
    /// Its colour.
    pub colour: Rgb<u8>,
    /// The mean per grid point; non-finite values leave gaps.
    pub mean: &'a [f64],
    /// The standard deviation per grid point, shaded (or drawn as a bar) as mean +- std.
    pub std: &'a [f64],
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

/// The x values of [`error_bars`]: numbers placed by value on a numbered axis, or names
/// placed evenly in their order, each under its own tick.
pub enum XValues<'a> {
    /// Numeric values.
    Numbers(&'a [f64]),
    /// Names (categories), in order.
    Names(&'a [String]),
}

impl XValues<'_> {
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

/// Space around the plot area of [`bands`]: left (tick labels), right, top (the y
/// label), bottom (tick labels and the x label).
const LEFT: u32 = 80;
const RIGHT: u32 = 24;
const TOP: u32 = 40;
const BOTTOM: u32 = 56;
/// Font pixels per glyph pixel.
const SCALE: u32 = 2;
/// How much of a band's colour its shading mixes in.
const SHADE: f64 = 0.2;

/// Plots each band's mean as a line over its shaded mean +- std, against x from 0 to
/// `x_max` (point `i` of `n` at `x_max * i / (n - 1)`), with numbered axes, the axis
/// labels `labels` (x, y) and a legend naming the bands. The y range spans every finite
/// mean +- std.
pub fn bands(
    width: u32,
    height: u32,
    x_max: f64,
    labels: (&str, &str),
    bands: &[Band<'_>],
) -> RgbImage {
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
    self::spreads(width, height, x_max, labels, &spreads, YScale::Linear)
}

/// One curve of [`spreads`]: a centre line (a median, say) over a shaded band from
/// `low` to `high` (its quartiles), per point of a common grid.
pub struct Spread<'a> {
    /// The legend's name for it; a plot whose curves all have empty names has no legend.
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
    /// By their base-10 logarithm, with powers of ten as ticks; values of 0 or less
    /// leave gaps.
    Log,
}

/// Plots each curve's centre as a line over its shaded band from `low` to `high`,
/// against x from 0 to `x_max` (point `i` of `n` at `x_max * i / (n - 1)`), y placed by
/// `scale`, with numbered axes, the axis labels `labels` (x, y) and a legend naming the
/// curves. The y range spans every finite value of the centres and the bands (on a log
/// scale, whole decades).
pub fn spreads(
    width: u32,
    height: u32,
    x_max: f64,
    labels: (&str, &str),
    curves: &[Spread<'_>],
    scale: YScale,
) -> RgbImage {
    let mut image = RgbImage::from_pixel(width, height, BACKGROUND);
    let x_max = if x_max.is_finite() && x_max > 0.0 {
        x_max
    } else {
        1.0
    };
    let to_y = |v: f64| match scale {
        YScale::Linear => v,
        YScale::Log if v > 0.0 => v.log10(),
        YScale::Log => f64::NAN,
    };
    let mapped: Vec<[Vec<f64>; 3]> = curves
        .iter()
        .map(|c| [c.centre, c.low, c.high].map(|v| v.iter().map(|&v| to_y(v)).collect()))
        .collect();
    let finite = mapped
        .iter()
        .flatten()
        .flatten()
        .copied()
        .filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let (y_range, y_ticks) = match scale {
        YScale::Linear => (padded(lo, hi), None),
        YScale::Log => {
            let (lo, hi) = if lo <= hi {
                (lo.floor(), hi.ceil().max(lo.floor() + 1.0))
            } else {
                (-1.0, 0.0)
            };
            let ticks = (lo as i32..=hi as i32)
                .map(|k| (f64::from(k), format!("1e{k}")))
                .collect::<Vec<_>>();
            ((lo, hi), Some(ticks))
        }
    };
    let axes = Axes::draw(
        &mut image,
        (0.0, x_max),
        y_range,
        labels,
        None,
        y_ticks.as_deref(),
    );
    for (c, [_, low, high]) in curves.iter().zip(&mapped) {
        shade(
            &mut image,
            c.colour,
            (low, high),
            (axes.left, axes.right),
            &|y| axes.py(y),
        );
    }
    for (c, [centre, _, _]) in curves.iter().zip(&mapped) {
        let n = centre.len();
        let at = |i: usize| axes.px(x_max * i as f64 / (n.max(2) - 1) as f64);
        for (i, pair) in centre.windows(2).enumerate() {
            if pair[0].is_finite() && pair[1].is_finite() {
                line(
                    &mut image,
                    (at(i), axes.py(pair[0])),
                    (at(i + 1), axes.py(pair[1])),
                    c.colour,
                );
            }
        }
    }
    let names: Vec<(&str, Rgb<u8>)> = curves.iter().map(|c| (c.name, c.colour)).collect();
    legend(&mut image, &names);
    image
}

/// Plots `points` `(x, y)` as dots, against numbered axes spanning every finite point
/// (with a little room), labelled `labels` (x, y). Points with a non-finite coordinate
/// are left out.
pub fn scatter(
    width: u32,
    height: u32,
    labels: (&str, &str),
    points: &[(f64, f64)],
    colour: Rgb<u8>,
) -> RgbImage {
    let mut image = RgbImage::from_pixel(width, height, BACKGROUND);
    let finite: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let range = |values: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        padded(lo, hi)
    };
    let xs = range(&mut finite.iter().map(|p| p.0));
    let ys = range(&mut finite.iter().map(|p| p.1));
    let axes = Axes::draw(&mut image, xs, ys, labels, None, None);
    for &(x, y) in &finite {
        dot(&mut image, (axes.px(x), axes.py(y)), colour);
    }
    image
}

/// A filled disc of radius 3 around `(cx, cy)`.
fn dot(image: &mut RgbImage, (cx, cy): (f64, f64), colour: Rgb<u8>) {
    for dy in -3i32..=3 {
        for dx in -3i32..=3 {
            if dx * dx + dy * dy > 10 {
                continue;
            }
            let (px, py) = ((cx + f64::from(dx)) as u32, (cy + f64::from(dy)) as u32);
            if px < image.width() && py < image.height() {
                image.put_pixel(px, py, colour);
            }
        }
    }
}

/// Pixels between the error bars of neighbouring bands at one x value, so that they do
/// not hide each other.
const DODGE: f64 = 7.0;
/// Half the width of an error bar's caps.
const CAP: f64 = 5.0;

/// Plots each band as error bars at the `x` values: a dot at the mean, a bar from mean -
/// std to mean + std with caps, and lines joining neighbouring means (a non-finite mean
/// leaves a gap), against numbered y axis and, for names, one labelled tick per name; the bands
/// are set a few pixels apart at each x. Labels `labels` (x, y) and a legend naming the
/// bands above the data. Each band holds one mean and one std per x value.
pub fn error_bars(
    width: u32,
    height: u32,
    labels: (&str, &str),
    x: &XValues<'_>,
    bands: &[Band<'_>],
) -> RgbImage {
    let mut image = RgbImage::from_pixel(width, height, BACKGROUND);
    let n = x.len();
    let (x_range, named_ticks) = match x {
        XValues::Numbers(values) => {
            let finite = values.iter().copied().filter(|v| v.is_finite());
            let lo = finite.clone().fold(f64::INFINITY, f64::min);
            let hi = finite.fold(f64::NEG_INFINITY, f64::max);
            (padded(lo, hi), None)
        }
        XValues::Names(names) => {
            let ticks: Vec<(f64, String)> = names
                .iter()
                .enumerate()
                .map(|(i, name)| (i as f64, name.clone()))
                .collect();
            ((-0.5, n as f64 - 0.5), Some(ticks))
        }
    };
    // Room above the data for the legend, so that it hides no bar.
    let (lo, hi) = y_range(bands);
    let names: Vec<(&str, Rgb<u8>)> = bands.iter().map(|b| (b.name, b.colour)).collect();
    let area = f64::from(height.saturating_sub(TOP + BOTTOM));
    let room = Legend::size(width, &names).map_or(0.0, |l| f64::from(l.h + 16));
    let hi = hi + (hi - lo) * room / (area - room).max(1.0);
    let axes = Axes::draw(
        &mut image,
        x_range,
        (lo, hi),
        labels,
        named_ticks.as_deref(),
        None,
    );
    let middle = (bands.len() as f64 - 1.0) / 2.0;
    for (k, band) in bands.iter().enumerate() {
        let shift = (k as f64 - middle) * DODGE;
        let point = |i: usize| (axes.px(x.at(i)) + shift, axes.py(band.mean[i]));
        let shown = |i: usize| band.mean[i].is_finite() && x.at(i).is_finite();
        let n = n.min(band.mean.len());
        for i in 1..n {
            if shown(i - 1) && shown(i) {
                line(&mut image, point(i - 1), point(i), band.colour);
            }
        }
        for i in (0..n).filter(|&i| shown(i)) {
            let (px, py) = point(i);
            let s = band
                .std
                .get(i)
                .copied()
                .filter(|s| s.is_finite())
                .unwrap_or(0.0);
            let (top, bottom) = (axes.py(band.mean[i] + s), axes.py(band.mean[i] - s));
            line(&mut image, (px, top), (px, bottom), band.colour);
            for y in [top, bottom] {
                line(&mut image, (px - CAP, y), (px + CAP, y), band.colour);
            }
            dot(&mut image, (px, py), band.colour);
        }
    }
    legend(&mut image, &names);
    image
}

/// Writes `text` at the top-left corner of `image`, on a white box.
pub fn label(image: &mut RgbImage, text: &str) {
    let (w, h) = (font::text_width(text, SCALE) + 8, font::HEIGHT * SCALE + 8);
    for y in 0..h.min(image.height()) {
        for x in 0..w.min(image.width()) {
            image.put_pixel(x, y, BACKGROUND);
        }
    }
    font::draw(image, 4, 4, text, SCALE, AXES);
}

/// The plot area of [`bands`] and [`scatter`] and its mapping from data to pixels.
struct Axes {
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    x: (f64, f64),
    y: (f64, f64),
}

impl Axes {
    /// Draws the grid, the axes with their ticks and numbers, and the axis labels for the
    /// data ranges `x` and `y` on `image`; the x and y ticks are `x_ticks` and `y_ticks`
    /// where given (their positions and labels), round numbers otherwise.
    fn draw(
        image: &mut RgbImage,
        x: (f64, f64),
        y: (f64, f64),
        labels: (&str, &str),
        x_ticks: Option<&[(f64, String)]>,
        y_ticks: Option<&[(f64, String)]>,
    ) -> Axes {
        let (width, height) = image.dimensions();
        let axes = Axes {
            left: f64::from(LEFT),
            right: f64::from(width.saturating_sub(RIGHT)),
            bottom: f64::from(height.saturating_sub(BOTTOM)),
            top: f64::from(TOP),
            x,
            y,
        };
        let y_ticks = y_ticks.map_or_else(|| ticks(y.0, y.1, 6.0), <[_]>::to_vec);
        let x_ticks = x_ticks.map_or_else(|| ticks(x.0, x.1, 8.0), <[_]>::to_vec);
        for &(v, _) in &y_ticks {
            let py = axes.py(v) as u32;
            for px in LEFT..=width.saturating_sub(RIGHT) {
                image.put_pixel(px, py, GRID);
            }
        }
        for &(v, _) in &x_ticks {
            let px = axes.px(v) as u32;
            for py in TOP..=height.saturating_sub(BOTTOM) {
                image.put_pixel(px, py, GRID);
            }
        }
        let (x_axis, y_axis) = (height.saturating_sub(BOTTOM), LEFT);
        for px in LEFT..=width.saturating_sub(RIGHT) {
            image.put_pixel(px, x_axis, AXES);
        }
        for py in TOP..=x_axis {
            image.put_pixel(y_axis, py, AXES);
        }
        let glyph_h = font::HEIGHT * SCALE;
        for (v, label) in &y_ticks {
            let py = axes.py(*v) as u32;
            for px in LEFT.saturating_sub(5)..LEFT {
                image.put_pixel(px, py, AXES);
            }
            let w = font::text_width(label, SCALE);
            let px = LEFT.saturating_sub(8 + w);
            font::draw(
                image,
                px,
                py.saturating_sub(glyph_h / 2),
                label,
                SCALE,
                AXES,
            );
        }
        let (scale, rows) = x_label_layout(&axes, &x_ticks);
        for (k, (v, label)) in x_ticks.iter().enumerate() {
            let px = axes.px(*v) as u32;
            for py in x_axis..x_axis + 5 {
                image.put_pixel(px, py, AXES);
            }
            let w = font::text_width(label, scale);
            let row = (k % rows) as u32 * (font::HEIGHT * scale + 2);
            font::draw(
                image,
                px.saturating_sub(w / 2),
                x_axis + 8 + row,
                label,
                scale,
                AXES,
            );
        }
        let (x_label, y_label) = labels;
        let w = font::text_width(x_label, SCALE);
        font::draw(
            image,
            (LEFT + width.saturating_sub(RIGHT)) / 2 - w / 2,
            x_axis + 12 + glyph_h,
            x_label,
            SCALE,
            AXES,
        );
        font::draw(
            image,
            8,
            TOP.saturating_sub(glyph_h + 10),
            y_label,
            SCALE,
            AXES,
        );
        axes
    }

    /// The pixel column of data value `x`.
    fn px(&self, x: f64) -> f64 {
        self.left + (self.right - self.left) * (x - self.x.0) / (self.x.1 - self.x.0)
    }

    /// The pixel row of data value `y`.
    fn py(&self, y: f64) -> f64 {
        self.bottom + (self.top - self.bottom) * (y - self.y.0) / (self.y.1 - self.y.0)
    }
}

/// The font scale of the x tick labels and the rows they alternate over: full size on one
/// row when neighbouring labels do not touch, else half size, on two rows if still needed.
fn x_label_layout(axes: &Axes, ticks: &[(f64, String)]) -> (u32, usize) {
    let fits = |scale: u32, rows: usize| {
        ticks.windows(rows + 1).all(|w| {
            let (a, b) = (&w[0], &w[rows]);
            let room = (axes.px(b.0) - axes.px(a.0)).abs();
            let need =
                f64::from(font::text_width(&a.1, scale) + font::text_width(&b.1, scale)) / 2.0;
            room >= need + 4.0
        })
    };
    if fits(SCALE, 1) {
        (SCALE, 1)
    } else if fits(1, 1) {
        (1, 1)
    } else {
        (1, 2)
    }
}

/// The y range of `bands`: every finite mean +- std, with a little room above and below.
fn y_range(bands: &[Band<'_>]) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for band in bands {
        for (&m, &s) in band.mean.iter().zip(band.std) {
            let s = if s.is_finite() { s } else { 0.0 };
            for v in [m - s, m + s] {
                if v.is_finite() {
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
        }
    }
    padded(lo, hi)
}

/// The range `lo..hi` with 5% room on each side; one unit each side of a single value,
/// and `-1..1` when there is no value.
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if lo >= hi {
        let c = if lo.is_finite() { lo } else { 0.0 };
        return (c - 1.0, c + 1.0);
    }
    let pad = (hi - lo) * 0.05;
    (lo - pad, hi + pad)
}

/// Round tick values in `lo..=hi`, about `count` of them, with their labels.
fn ticks(lo: f64, hi: f64, count: f64) -> Vec<(f64, String)> {
    let raw = (hi - lo) / count;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = magnitude
        * match raw / magnitude {
            f if f <= 1.0 => 1.0,
            f if f <= 2.0 => 2.0,
            f if f <= 5.0 => 5.0,
            _ => 10.0,
        };
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            // `k == 0` prints "0", never "-0".
            let shown = if k == 0 { 0.0 } else { v };
            (v, format!("{shown:.decimals$}"))
        })
        .collect()
}

/// Shades the band from `low` to `high` (already in the axes' y values), column by
/// column across the plot area.
fn shade(
    image: &mut RgbImage,
    colour: Rgb<u8>,
    (low, high): (&[f64], &[f64]),
    (left, right): (f64, f64),
    py: &impl Fn(f64) -> f64,
) {
    let n = low.len().min(high.len());
    if n == 0 {
        return;
    }
    for x in left as u32..=right as u32 {
        let i = (((f64::from(x) - left) / (right - left)) * (n - 1) as f64).round() as usize;
        let (lo, hi) = (low[i.min(n - 1)], high[i.min(n - 1)]);
        if !(lo.is_finite() && hi.is_finite()) {
            continue;
        }
        let (a, b) = (py(hi), py(lo));
        for y in a.round() as u32..=b.round() as u32 {
            if x < image.width() && y < image.height() {
                let old = image.get_pixel(x, y).0;
                let mix =
                    |o: u8, c: u8| (f64::from(o) * (1.0 - SHADE) + f64::from(c) * SHADE) as u8;
                image.put_pixel(x, y, Rgb([0, 1, 2].map(|k| mix(old[k], colour.0[k]))));
            }
        }
    }
}

/// The size of a legend box.
struct Legend {
    /// Font pixels per glyph pixel.
    scale: u32,
    /// Pixels per band.
    row: u32,
    /// Width and height of the box.
    w: u32,
    h: u32,
}

impl Legend {
    /// The legend of `bands` in an image `width` pixels wide: at full size when it fits
    /// across the plot area, half size otherwise; `None` when every name is empty.
    fn size(width: u32, bands: &[(&str, Rgb<u8>)]) -> Option<Legend> {
        if bands.iter().all(|b| b.0.is_empty()) {
            return None;
        }
        let at = |scale: u32| {
            let longest = bands
                .iter()
                .map(|b| font::text_width(b.0, scale))
                .max()
                .unwrap_or(0);
            let row = font::HEIGHT * scale + 8;
            Legend {
                scale,
                row,
                w: 12 * scale + 18 + longest,
                h: row * bands.len() as u32 + 8,
            }
        };
        let room = width.saturating_sub(RIGHT + LEFT + 24);
        Some(
            Some(at(SCALE))
                .filter(|l| l.w <= room)
                .unwrap_or_else(|| at(1)),
        )
    }
}

/// The bands' names beside their colours, boxed, in the corner of the plot area where
/// the box hides the fewest drawn pixels (the bottom right among equals), at full size
/// when it fits across the plot area and half size otherwise; nothing when every name is
/// empty.
fn legend(image: &mut RgbImage, bands: &[(&str, Rgb<u8>)]) {
    let Some(Legend { scale, row, w, h }) = Legend::size(image.width(), bands) else {
        return;
    };
    let (left, top) = (LEFT + 12, TOP + 12);
    let right = image.width().saturating_sub(RIGHT + 12);
    let bottom = image.height().saturating_sub(BOTTOM + 12);
    let swatch = 12 * scale;
    let corners = [
        (right.saturating_sub(w), bottom.saturating_sub(h)),
        (right.saturating_sub(w), top),
        (left, top),
        (left, bottom.saturating_sub(h)),
    ];
    let hidden = |&(x0, y0): &(u32, u32)| {
        let (x1, y1) = ((x0 + w).min(image.width()), (y0 + h).min(image.height()));
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| ![BACKGROUND, GRID].contains(image.get_pixel(x, y)))
            .count()
    };
    let (x0, y0) = corners
        .iter()
        .copied()
        .min_by_key(hidden)
        .expect("four corners");
    let (x1, y1) = (
        (x0 + w).min(image.width() - 1),
        (y0 + h).min(image.height() - 1),
    );
    for y in y0..=y1 {
        for x in x0..=x1 {
            let edge = y == y0 || y == y1 || x == x0 || x == x1;
            image.put_pixel(x, y, if edge { AXES } else { BACKGROUND });
        }
    }
    for (k, &(name, colour)) in bands.iter().enumerate() {
        let y = y0 + 6 + row * k as u32;
        let mid = f64::from(y + font::HEIGHT * scale / 2);
        let x = f64::from(x0 + 6);
        for dy in [-2.0, 0.0] {
            line(
                image,
                (x, mid + dy),
                (x + f64::from(swatch), mid + dy),
                colour,
            );
        }
        font::draw(image, x0 + swatch + 12, y, name, scale, AXES);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The columns of `image` holding `colour`.
    fn columns(image: &RgbImage, colour: Rgb<u8>) -> Vec<u32> {
        (0..image.width())
            .filter(|&x| (0..image.height()).any(|y| *image.get_pixel(x, y) == colour))
            .collect()
    }

    #[test]
    fn error_bars_stand_at_their_names_and_span_the_spread() {
        let names = ["tournament_roulette", "tournament", "roulette", "random"].map(String::from);
        let colour = palette(3);
        let band = Band {
            name: "",
            colour,
            mean: &[1.0, 2.0, f64::NAN, 1.5],
            std: &[0.5, 0.0, 0.0, 0.25],
        };
        let image = error_bars(
            640,
            400,
            ("selection", "final"),
            &XValues::Names(&names),
            &[band],
        );
        // The plot area spans 80..616 for x in -0.5..3.5: names at 147, 281, 415, 549.
        let at = |i: f64| 80.0 + 536.0 * (i + 0.5) / 4.0;
        let drawn = columns(&image, colour);
        for i in [0.0, 1.0, 3.0] {
            assert!(
                drawn.contains(&(at(i) as u32)),
                "no bar at name {i}: {drawn:?}"
            );
        }
        // The missing mean leaves its name without a bar or a line through it.
        assert!(!drawn.contains(&(at(2.0) as u32)), "{drawn:?}");
        // The first bar spans 0.5..1.5 of a y range of 0.5..2 padded by 5 % each side.
        let x = at(0.0) as u32;
        let rows: Vec<u32> = (0..400)
            .filter(|&y| *image.get_pixel(x, y) == colour)
            .collect();
        let (top, bottom) = (rows[0], *rows.last().unwrap());
        let area = f64::from(400 - BOTTOM - TOP);
        let want = area * 1.0 / 1.65;
        assert!(
            (f64::from(bottom - top) - want).abs() < 8.0,
            "{top}..{bottom}, {want}"
        );
    }

    #[test]
    fn numbers_are_placed_by_value_and_bands_side_by_side() {
        let xs = [10.0, 20.0, 50.0];
        let (a, b) = (palette(0), palette(1));
        let mean = [1.0, 2.0, 3.0];
        let std = [0.1; 3];
        let bands = [
            Band {
                name: "a",
                colour: a,
                mean: &mean,
                std: &std,
            },
            Band {
                name: "b",
                colour: b,
                mean: &mean,
                std: &std,
            },
        ];
        let image = error_bars(640, 400, ("x", "y"), &XValues::Numbers(&xs), &bands);
        // x in 8..52 over 80..616: 10 at 104.4, 20 at 226.2, 50 at 591.6; the two bands
        // 7 pixels apart around each.
        for x in [104.4, 226.2, 591.6] {
            let (xa, xb) = ((x - DODGE / 2.0) as u32, (x + DODGE / 2.0) as u32);
            assert!((0..400).any(|y| *image.get_pixel(xa, y) == a), "a at {x}");
            assert!((0..400).any(|y| *image.get_pixel(xb, y) == b), "b at {x}");
        }
    }

    #[test]
    fn the_legend_keeps_out_of_the_data() {
        // A falling line ends in the bottom right corner, where the legend would go.
        let mean: Vec<f64> = (0..50).map(|i| 50.0 - f64::from(i)).collect();
        let std = vec![0.0; 50];
        let colour = palette(2);
        let band = Band {
            name: "falling",
            colour,
            mean: &mean,
            std: &std,
        };
        let image = bands(640, 400, 1.0, ("x", "y"), &[band]);
        // The line's last pixels, at the right end of the plot area, stay visible.
        let right = 640 - RIGHT - 2;
        assert!(
            (300..400).any(|y| *image.get_pixel(right, y) == colour),
            "the legend hides the end of the line"
        );
        // The legend went to the bottom left or the top right.
        let boxed = |x: u32, y: u32| *image.get_pixel(x, y) == AXES;
        assert!(boxed(LEFT + 12, 400 - BOTTOM - 12) || boxed(640 - RIGHT - 12, TOP + 12));
    }

    #[test]
    fn long_names_shrink_before_they_touch() {
        let axes = Axes {
            left: 80.0,
            right: 616.0,
            bottom: 344.0,
            top: 40.0,
            x: (-0.5, 3.5),
            y: (0.0, 1.0),
        };
        let ticks = |names: &[&str]| -> Vec<(f64, String)> {
            names
                .iter()
                .enumerate()
                .map(|(i, n)| (i as f64, (*n).to_owned()))
                .collect()
        };
        // 134 pixels between names: 8 characters fit at full size (128), 16 at half.
        assert_eq!(
            x_label_layout(&axes, &ticks(&["50", "100", "150", "200"])),
            (SCALE, 1)
        );
        let long = ["tournament_roulette", "tournament", "roulette", "random"];
        assert_eq!(x_label_layout(&axes, &ticks(&long)), (1, 1));
        let longer = [
            "a".repeat(20),
            "b".repeat(20),
            "c".repeat(20),
            "d".repeat(20),
        ];
        let longer: Vec<&str> = longer.iter().map(String::as_str).collect();
        assert_eq!(x_label_layout(&axes, &ticks(&longer)), (1, 2));
    }
}
