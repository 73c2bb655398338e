//! Target images: reading the file, and decoding its bytes.

use std::path::PathBuf;

/// Why a target image file cannot be used ([`read_image`](crate::scene::read_image)):
/// the file, and what the system or the decoder said as the source.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ImageError {
    /// The file could not be read.
    #[error("cannot read `{}`", path.display())]
    Read {
        /// The image file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The file's bytes are not an image that can be a target.
    #[error("`{}`", path.display())]
    Decode {
        /// The image file.
        path: PathBuf,
        /// Why they do not decode.
        #[source]
        source: DecodeError,
    },
}

/// Why bytes do not decode as a target image ([`decode_image`](crate::scene::decode_image)).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DecodeError {
    /// The decoder refused them: not an image of a format it reads, or a broken one.
    /// Its message is this error's own rather than a `source()`: the `image` crate's
    /// errors print their cause and give it as their `source()` too, which would print
    /// it twice.
    #[error("{0}")]
    Decoder(image::ImageError),
    /// The header claims more pixels than a target may have.
    #[error("the image is {width} x {height} pixels; at most {max} pixels are supported")]
    TooLarge {
        /// Width claimed.
        width: u32,
        /// Height claimed.
        height: u32,
        /// The most pixels a target may have
        /// ([`MAX_TARGET_PIXELS`](shapegen_runtime::score::silhouette::MAX_TARGET_PIXELS)).
        max: u64,
    },
}
