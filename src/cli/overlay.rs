//! The pictures the commands write besides models: overlays of a model's coverage on
//! its target, and the numbering of one file per camera or objective.

use std::path::{Path, PathBuf};

use image::{Rgb, RgbImage};
use shapegen::score::objective::{ObjectiveSet, ProjectionMatch, Surface};
use shapegen::score::silhouette::ImageTarget;

/// Overlay colours: target alone, model alone, both.
const TARGET: Rgb<u8> = Rgb([150, 170, 215]);
const MODEL: Rgb<u8> = Rgb([225, 90, 70]);
const BOTH: Rgb<u8> = Rgb([40, 120, 60]);
const NEITHER: Rgb<u8> = Rgb([255, 255, 255]);

/// `path` with extension `ext`, and `_k` after its stem when there are several files.
pub fn numbered(path: &Path, k: usize, of: usize, ext: &str) -> PathBuf {
    if of <= 1 {
        return path.with_extension(ext);
    }
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!("{stem}_{k}.{ext}"))
}

/// The projection objectives of `set`, under their names.
pub fn projections(set: &ObjectiveSet) -> Vec<(&str, &ProjectionMatch)> {
    set.entries()
        .iter()
        .filter_map(|(name, objective)| Some((name.as_str(), objective.projection()?)))
        .collect()
}

/// The overlay of a model's coverage `mask` on `target`: target alone blue, model alone
/// red, both green, neither white.
pub fn overlay(target: &ImageTarget, mask: &[bool]) -> RgbImage {
    let w = target.width();
    overlay_with(w, target.height(), |x, y| {
        (target.is_target(x, y), mask[(y * w + x) as usize])
    })
}

/// The overlay of a model's orthographic projection on a projection objective's target,
/// coloured as [`overlay`]'s.
pub fn projection_overlay(projection: &ProjectionMatch, surface: &Surface) -> RgbImage {
    let covered = projection.render(surface);
    overlay_with(projection.width(), projection.height(), |x, y| {
        (projection.mask(x, y), covered.get_pixel(x, y).0[0] == 0)
    })
}

/// An overlay picture from `(is target, is covered)` per pixel.
fn overlay_with(width: u32, height: u32, pixel: impl Fn(u32, u32) -> (bool, bool)) -> RgbImage {
    RgbImage::from_fn(width, height, |x, y| match pixel(x, y) {
        (true, true) => BOTH,
        (true, false) => TARGET,
        (false, true) => MODEL,
        (false, false) => NEITHER,
    })
}
