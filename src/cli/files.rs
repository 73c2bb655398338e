//! Reading and writing the commands' files: every output is written atomically.

use std::path::Path;

use anyhow::Context;
use image::RgbImage;

/// The text of `path`, or an error naming it.
pub fn read(path: &Path) -> anyhow::Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read `{}`", path.display()))
}

/// Writes `image` as a PNG file, atomically.
pub fn save_png(path: &Path, image: &RgbImage) -> anyhow::Result<()> {
    let mut bytes = Vec::new();
    image.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )?;
    atomic_write(path, &bytes)
}

/// Writes `bytes` to a temporary file beside `path`, then renames it over `path`: a
/// reader (or a run killed midway) sees the old file or the new one, never half of one.
pub fn atomic_write(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let tmp = path.with_extension(format!(
        "{}.tmp",
        path.extension().and_then(|e| e.to_str()).unwrap_or("")
    ));
    std::fs::write(&tmp, bytes).with_context(|| format!("cannot write `{}`", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("cannot write `{}`", path.display()))
}
