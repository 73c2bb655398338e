//! Per-pixel hit counts of one image, tiled as its coverage rows are laid out.

use super::cells::{CellCounts, Overflow, TILE_WORDS};
use crate::score::silhouette::raster::row_words;

/// Which way an instance's cells go: added to a model's counts or removed from them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hit {
    /// One more hit of each cell.
    Add,
    /// One hit less of each cell.
    Remove,
}

/// How many times each pixel of a `width x height` image is hit, in the [`CellCounts`]
/// tiles of 8 rows of one 64-pixel word: the layout of the rasterizer's coverage rows
/// (`row_words(width)` words a row), whose word `w` is what [`apply`](Self::apply)
/// takes.
///
/// ```
/// use shapegen_runtime::score::retained::{Hit, PixelCounts};
///
/// // 100 x 20 pixels: rows of 2 words; word 3 is pixels 64..100 of row 1.
/// let mut counts = PixelCounts::new(100, 20);
/// assert_eq!(counts.apply(Hit::Add, 3, 0b11), Ok(0b11));
/// assert_eq!(counts.apply(Hit::Add, 3, 0b10), Ok(0)); // already hit: none newly covered
/// assert_eq!(counts.get(65, 1), 2);
/// assert_eq!(counts.apply(Hit::Remove, 3, 0b11), Ok(0b01)); // pixel 64 uncovered
/// ```
#[derive(Clone, Debug)]
pub struct PixelCounts {
    cells: CellCounts,
    stride: usize,
}

impl PixelCounts {
    /// Zero counts over a `width x height` image.
    pub fn new(width: u32, height: u32) -> PixelCounts {
        let stride = row_words(width);
        let bands = (height as usize).div_ceil(TILE_WORDS);
        PixelCounts {
            cells: CellCounts::new(bands * stride),
            stride,
        }
    }

    /// The tile and the word in it of coverage word `w`.
    #[inline]
    fn locate(&self, w: usize) -> (usize, usize) {
        let (row, col) = (w / self.stride, w % self.stride);
        (row / TILE_WORDS * self.stride + col, row % TILE_WORDS)
    }

    /// Adds a hit to (or removes one from) each pixel set in `bits` of coverage word
    /// `w`, and returns the pixels that went from 0 to 1 hit (or from 1 to 0): those
    /// whose coverage changed. Fails as [`CellCounts::add`] does.
    ///
    /// # Panics
    /// If `w` is outside the image, or (removing) a pixel in `bits` holds no hit.
    #[inline]
    pub fn apply(&mut self, hit: Hit, w: usize, bits: u64) -> Result<u64, Overflow> {
        let (tile, word) = self.locate(w);
        Ok(match hit {
            Hit::Add => self.cells.add(tile, word, bits)?.first,
            Hit::Remove => self.cells.remove(tile, word, bits).first,
        })
    }

    /// The hits of pixel `(x, y)`.
    ///
    /// # Panics
    /// If the pixel is outside the image.
    pub fn get(&self, x: u32, y: u32) -> u16 {
        let w = y as usize * self.stride + x as usize / 64;
        let (tile, word) = self.locate(w);
        self.cells.get(tile, word, x % 64)
    }

    /// The cells, to measure memory.
    pub fn cells(&self) -> &CellCounts {
        &self.cells
    }
}
