//! A fitness curve as a picture: best and mean fitness against generations.

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
