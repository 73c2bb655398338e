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

/// A CSV file's bytes: `header`, then one record per row, each field quoted where it
/// holds a comma, a quote or a line break (names given by users may).
pub fn csv_bytes<R, F>(header: &[String], rows: R) -> anyhow::Result<Vec<u8>>
where
    R: IntoIterator<Item = Vec<F>>,
    F: AsRef<[u8]>,
{
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for row in rows {
        writer.write_record(row)?;
    }
    writer
        .into_inner()
        .map_err(|err| anyhow::anyhow!("cannot write CSV: {}", err.error()))
}

#[cfg(test)]
mod tests {
    use super::csv_bytes;

    #[test]
    fn names_with_commas_and_quotes_stay_one_field() {
        let header = [
            "model".to_owned(),
            "width, m".to_owned(),
            "say \"hi\"".to_owned(),
        ];
        let bytes = csv_bytes(&header, [vec!["0", "1.5", "2"]]).unwrap();
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "model,\"width, m\",\"say \"\"hi\"\"\"\n0,1.5,2\n"
        );
    }
}
