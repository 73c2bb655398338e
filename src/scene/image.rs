//! Target images as a scene reads them: the size is read from the header and checked
//! before anything is decoded, so that a file claiming a huge image is refused at once
//! rather than allocating for it.
//!
//! ```
//! use shapegen::scene::decode_image;
//!
//! let mut png = Vec::new();
//! image::GrayImage::new(4, 3)
//!     .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)?;
//! assert_eq!(decode_image(&png)?.into_luma8().dimensions(), (4, 3));
//! assert!(decode_image(b"not an image").is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::io::Cursor;
use std::path::Path;

use image::{DynamicImage, ImageReader, Limits};
use shapegen_runtime::score::silhouette::MAX_TARGET_PIXELS;

use super::error::{DecodeError, ImageError};

/// Bytes a decoder may allocate: the largest target at 16-bit RGBA, and a little more.
const MAX_DECODE_BYTES: u64 = MAX_TARGET_PIXELS * 8 + (1 << 20);

/// Decodes a target image (PNG, or another format the `image` crate reads here) from
/// `bytes`. Images of more than [`MAX_TARGET_PIXELS`] pixels are refused from their
/// header.
///
/// # Errors
/// [`DecodeError::Decoder`] when the bytes are not an image of a known format or do not
/// decode, [`DecodeError::TooLarge`] when the image is too large.
pub fn decode_image(bytes: &[u8]) -> Result<DynamicImage, DecodeError> {
    let reader = || {
        let mut reader = ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|err| DecodeError::Decoder(err.into()))?;
        let mut limits = Limits::default();
        limits.max_alloc = Some(MAX_DECODE_BYTES);
        reader.limits(limits);
        Ok::<_, DecodeError>(reader)
    };
    let (width, height) = reader()?.into_dimensions().map_err(DecodeError::Decoder)?;
    let pixels = u64::from(width) * u64::from(height);
    if pixels > MAX_TARGET_PIXELS {
        return Err(DecodeError::TooLarge {
            width,
            height,
            max: MAX_TARGET_PIXELS,
        });
    }
    reader()?.decode().map_err(DecodeError::Decoder)
}

/// Reads and decodes the target image at `path` ([`decode_image`]).
///
/// # Errors
/// [`ImageError`], naming the file, when it cannot be read or decoded.
pub fn read_image(path: &Path) -> Result<DynamicImage, ImageError> {
    let bytes = std::fs::read(path).map_err(|source| ImageError::Read {
        path: path.to_owned(),
        source,
    })?;
    decode_image(&bytes).map_err(|source| ImageError::Decode {
        path: path.to_owned(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::{decode_image, read_image};

    /// A PNG whose header claims `width x height` grey pixels, with one row of data.
    fn claiming(width: u32, height: u32) -> Vec<u8> {
        let mut png = Vec::new();
        image::GrayImage::new(1, 1)
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        // IHDR's width and height follow the 8-byte signature, the chunk's length and
        // its type; its CRC (of the type and the 13 bytes of data) follows the data.
        png[16..20].copy_from_slice(&width.to_be_bytes());
        png[20..24].copy_from_slice(&height.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        png
    }

    /// PNG's CRC-32, bit by bit.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }

    #[test]
    fn an_image_claiming_too_many_pixels_is_refused_from_its_header() {
        let err = decode_image(&claiming(100_000, 100_000))
            .unwrap_err()
            .to_string();
        assert!(err.contains("100000 x 100000"), "{err}");
        assert!(err.contains("at most 16777216 pixels"), "{err}");
    }

    #[test]
    fn what_is_not_an_image_is_refused() {
        assert!(decode_image(b"").is_err());
        assert!(decode_image(b"\x89PNG\r\n\x1a\n").is_err());
    }

    #[test]
    fn a_file_that_does_not_decode_is_named_with_the_decoders_message_once() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("broken.png");
        // A broken CRC: the decoder's error prints its cause and also gives it as its
        // `source()`.
        let mut png = claiming(4, 3);
        png[30] ^= 0xff;
        std::fs::write(&path, &png).unwrap();
        let decoder = decode_image(&png).unwrap_err().to_string();
        assert!(decoder.contains("CRC error"), "{decoder}");
        let err = read_image(&path).unwrap_err();
        assert_eq!(err.to_string(), format!("`{}`", path.display()));
        let chain = shapegen_runtime::error_chain(&err);
        assert_eq!(chain, format!("`{}`: {decoder}", path.display()));
        let missing = read_image(&dir.path().join("missing.png")).unwrap_err();
        let chain = shapegen_runtime::error_chain(&missing);
        assert!(chain.starts_with("cannot read `"), "{chain}");
        assert!(chain.contains("missing.png`: "), "{chain}");
    }
}
