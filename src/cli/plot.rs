//! Plots as pictures: best and mean fitness against generations for one run, several
//! methods' mean curves with their spread against time for a comparison, and the values
//! of two objectives across a multi-objective front.

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

/// One curve of [`bands`]: a mean and its standard deviation per point of a common grid.
pub struct Band<'a> {
    /// The legend's name for it.
    pub name: &'a str,
    /// Its colour.
    pub colour: Rgb<u8>,
    /// The mean per grid point; non-finite values leave gaps.
    pub mean: &'a [f64],
    /// The standard deviation per grid point, shaded as mean +- std.
    pub std: &'a [f64],
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
    let mut image = RgbImage::from_pixel(width, height, BACKGROUND);
    let x_max = if x_max.is_finite() && x_max > 0.0 {
        x_max
    } else {
        1.0
    };
    let axes = Axes::draw(&mut image, (0.0, x_max), y_range(bands), labels);
    for band in bands {
        shade(&mut image, band, (axes.left, axes.right), &|y| axes.py(y));
    }
    for band in bands {
        let n = band.mean.len();
        let at = |i: usize| axes.px(x_max * i as f64 / (n.max(2) - 1) as f64);
        for (i, pair) in band.mean.windows(2).enumerate() {
            if pair[0].is_finite() && pair[1].is_finite() {
                line(
                    &mut image,
                    (at(i), axes.py(pair[0])),
                    (at(i + 1), axes.py(pair[1])),
                    band.colour,
                );
            }
        }
    }
    legend(&mut image, bands);
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
    let axes = Axes::draw(&mut image, xs, ys, labels);
    for &(x, y) in &finite {
        let (cx, cy) = (axes.px(x), axes.py(y));
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
    /// data ranges `x` and `y` on `image`.
    fn draw(image: &mut RgbImage, x: (f64, f64), y: (f64, f64), labels: (&str, &str)) -> Axes {
        let (width, height) = image.dimensions();
        let axes = Axes {
            left: f64::from(LEFT),
            right: f64::from(width.saturating_sub(RIGHT)),
            bottom: f64::from(height.saturating_sub(BOTTOM)),
            top: f64::from(TOP),
            x,
            y,
        };
        let y_ticks = ticks(y.0, y.1, 6.0);
        let x_ticks = ticks(x.0, x.1, 8.0);
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
        for (v, label) in &x_ticks {
            let px = axes.px(*v) as u32;
            for py in x_axis..x_axis + 5 {
                image.put_pixel(px, py, AXES);
            }
            let w = font::text_width(label, SCALE);
            font::draw(
                image,
                px.saturating_sub(w / 2),
                x_axis + 8,
                label,
                SCALE,
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

/// Shades `band`'s mean +- std, column by column across the plot area.
fn shade(
    image: &mut RgbImage,
    band: &Band<'_>,
    (left, right): (f64, f64),
    py: &impl Fn(f64) -> f64,
) {
    let n = band.mean.len();
    if n == 0 {
        return;
    }
    for x in left as u32..=right as u32 {
        let i = (((f64::from(x) - left) / (right - left)) * (n - 1) as f64).round() as usize;
        let (m, s) = (band.mean[i.min(n - 1)], band.std[i.min(n - 1)]);
        if !(m.is_finite() && s.is_finite()) {
            continue;
        }
        let (a, b) = (py(m + s), py(m - s));
        for y in a.round() as u32..=b.round() as u32 {
            if x < image.width() && y < image.height() {
                let old = image.get_pixel(x, y).0;
                let mix =
                    |o: u8, c: u8| (f64::from(o) * (1.0 - SHADE) + f64::from(c) * SHADE) as u8;
                image.put_pixel(x, y, Rgb([0, 1, 2].map(|k| mix(old[k], band.colour.0[k]))));
            }
        }
    }
}

/// The bands' names beside their colours, boxed, at the bottom right of the plot area.
fn legend(image: &mut RgbImage, bands: &[Band<'_>]) {
    let row = font::HEIGHT * SCALE + 8;
    let swatch = 24;
    let longest = bands
        .iter()
        .map(|b| font::text_width(b.name, SCALE))
        .max()
        .unwrap_or(0);
    let (w, h) = (swatch + 18 + longest, row * bands.len() as u32 + 8);
    let right = image.width().saturating_sub(RIGHT + 12);
    let bottom = image.height().saturating_sub(BOTTOM + 12);
    let (x0, y0) = (right.saturating_sub(w), bottom.saturating_sub(h));
    for y in y0..=bottom {
        for x in x0..=right {
            let edge = y == y0 || y == bottom || x == x0 || x == right;
            image.put_pixel(x, y, if edge { AXES } else { BACKGROUND });
        }
    }
    for (k, band) in bands.iter().enumerate() {
        let y = y0 + 6 + row * k as u32;
        let mid = f64::from(y + font::HEIGHT * SCALE / 2);
        let x = f64::from(x0 + 6);
        for dy in [-2.0, 0.0] {
            line(
                image,
                (x, mid + dy),
                (x + f64::from(swatch), mid + dy),
                band.colour,
            );
        }
        font::draw(image, x0 + swatch + 12, y, band.name, SCALE, AXES);
    }
}
