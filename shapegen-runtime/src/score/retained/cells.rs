//! Per-cell hit counts (pixels or voxels) of one model, in copy-on-write tiles.

use std::sync::Arc;

/// Cells (64-cell words) per tile: a tile is [`TILE_WORDS`] words of 64 cells.
pub const TILE_WORDS: usize = 8;

/// Cells per tile.
const TILE_CELLS: usize = TILE_WORDS * 64;

/// One tile: a count per cell, and how many of its cells are not zero (so that a tile
/// emptied by removals is dropped).
#[derive(Clone, Debug)]
struct Tile {
    counts: [u16; TILE_CELLS],
    nonzero: u16,
}

impl Tile {
    fn empty() -> Tile {
        Tile {
            counts: [0; TILE_CELLS],
            nonzero: 0,
        }
    }
}

/// Which cells of one word changed how, by one [`CellCounts::add`] or
/// [`CellCounts::remove`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Changed {
    /// Cells whose count went from 0 to 1 (add) or from 1 to 0 (remove).
    pub first: u64,
    /// Cells whose count went from 1 to 2 (add) or from 2 to 1 (remove).
    pub second: u64,
}

/// A count of `u16` would overflow: more than 65 535 hits of one cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overflow;

/// How many times each cell of a grid of 64-cell words is hit, kept in tiles of
/// [`TILE_WORDS`] words that are allocated when first hit, dropped when emptied, and
/// shared between clones until one of them writes to a tile (copy on write).
///
/// A clone therefore costs the tile directory (8 bytes per tile of the grid) and a
/// reference count per tile in use, and a model differing from its parent by a few
/// instances owns only the tiles those instances touch. Which word of the grid a tile
/// slot holds is the caller's choice: the silhouette scorer tiles 8 rows of one column
/// of words, the volume scorer 8 consecutive words.
///
/// ```
/// use shapegen_runtime::score::retained::{CellCounts, Changed};
///
/// let mut counts = CellCounts::new(4);
/// assert_eq!(counts.add(1, 3, 0b110).unwrap(), Changed { first: 0b110, second: 0 });
/// let parent = counts.clone();
/// assert_eq!(counts.add(1, 3, 0b011).unwrap(), Changed { first: 0b001, second: 0b010 });
/// assert_eq!(counts.get(1, 3, 1), 2);
/// assert_eq!(parent.get(1, 3, 1), 1); // the clone kept its own counts
/// assert_eq!(counts.remove(1, 3, 0b110), Changed { first: 0b100, second: 0b010 });
/// ```
#[derive(Clone, Debug, Default)]
pub struct CellCounts {
    tiles: Vec<Option<Arc<Tile>>>,
}

impl CellCounts {
    /// Zero counts over `tiles` tiles.
    pub fn new(tiles: usize) -> CellCounts {
        CellCounts {
            tiles: vec![None; tiles],
        }
    }

    /// Number of tiles of the grid.
    pub fn tiles(&self) -> usize {
        self.tiles.len()
    }

    /// The count of cell `bit` of word `word` of tile `tile`.
    ///
    /// # Panics
    /// If `tile`, `word` or `bit` is out of range.
    pub fn get(&self, tile: usize, word: usize, bit: u32) -> u16 {
        assert!(word < TILE_WORDS && bit < 64, "word {word}, bit {bit}");
        self.tiles[tile]
            .as_ref()
            .map_or(0, |t| t.counts[word * 64 + bit as usize])
    }

    /// Calls `visit(tile, word, bits)` for each word of every tile in use whose cells
    /// are not all zero, `bits` the cells holding at least one hit.
    ///
    /// ```
    /// use shapegen_runtime::score::retained::CellCounts;
    ///
    /// let mut counts = CellCounts::new(4);
    /// counts.add(2, 5, 0b1010).unwrap();
    /// counts.add(2, 5, 0b0010).unwrap();
    /// let mut seen = Vec::new();
    /// counts.visit_words(|tile, word, bits| seen.push((tile, word, bits)));
    /// assert_eq!(seen, [(2, 5, 0b1010)]);
    /// ```
    pub fn visit_words(&self, mut visit: impl FnMut(usize, usize, u64)) {
        for (t, tile) in self.tiles.iter().enumerate() {
            let Some(tile) = tile else { continue };
            for (word, cells) in tile.counts.chunks_exact(64).enumerate() {
                let bits = cells
                    .iter()
                    .enumerate()
                    .fold(0u64, |m, (b, &c)| m | u64::from(c != 0) << b);
                if bits != 0 {
                    visit(t, word, bits);
                }
            }
        }
    }

    /// Adds one hit to each cell set in `bits`, in word `word` of tile `tile`. Fails,
    /// leaving the counts unspecified, when a count would pass 65 535.
    ///
    /// # Panics
    /// If `tile` or `word` is out of range.
    #[inline]
    pub fn add(&mut self, tile: usize, word: usize, bits: u64) -> Result<Changed, Overflow> {
        if bits == 0 {
            return Ok(Changed::default());
        }
        let tile = Arc::make_mut(self.tiles[tile].get_or_insert_with(|| Arc::new(Tile::empty())));
        let cells = &mut tile.counts[word * 64..word * 64 + 64];
        let mut changed = Changed::default();
        for bit in set_bits(bits) {
            let cell = &mut cells[bit as usize];
            match *cell {
                0 => changed.first |= 1 << bit,
                1 => changed.second |= 1 << bit,
                u16::MAX => return Err(Overflow),
                _ => {}
            }
            *cell += 1;
        }
        tile.nonzero += changed.first.count_ones() as u16;
        Ok(changed)
    }

    /// Takes one hit from each cell set in `bits`, in word `word` of tile `tile`, which
    /// must each hold at least one.
    ///
    /// # Panics
    /// If `tile` or `word` is out of range, or a cell in `bits` holds no hit.
    #[inline]
    pub fn remove(&mut self, tile: usize, word: usize, bits: u64) -> Changed {
        if bits == 0 {
            return Changed::default();
        }
        let slot = &mut self.tiles[tile];
        let shared = slot.as_mut().expect("cells removed from an empty tile");
        let t = Arc::make_mut(shared);
        let cells = &mut t.counts[word * 64..word * 64 + 64];
        let mut changed = Changed::default();
        for bit in set_bits(bits) {
            let cell = &mut cells[bit as usize];
            match *cell {
                0 => panic!("a hit removed from a cell that has none"),
                1 => changed.first |= 1 << bit,
                2 => changed.second |= 1 << bit,
                _ => {}
            }
            *cell -= 1;
        }
        t.nonzero -= changed.first.count_ones() as u16;
        if t.nonzero == 0 {
            *slot = None;
        }
        changed
    }

    /// Bytes of memory this grid holds: its directory and every tile in use, shared or
    /// not (an upper bound for grids that share tiles; see
    /// [`tile_addresses`](Self::tile_addresses) to count shared tiles once).
    pub fn bytes(&self) -> usize {
        self.directory_bytes() + self.tiles.iter().flatten().count() * TILE_BYTES
    }

    /// Bytes of the tile directory alone.
    pub fn directory_bytes(&self) -> usize {
        size_of_val(self.tiles.as_slice())
    }

    /// The address of every tile in use, each [`TILE_BYTES`] large: equal addresses in
    /// two grids are one tile they share.
    pub fn tile_addresses(&self) -> impl Iterator<Item = usize> + '_ {
        self.tiles.iter().flatten().map(|t| Arc::as_ptr(t) as usize)
    }
}

/// Bytes of one tile.
pub const TILE_BYTES: usize = size_of::<Tile>();

/// The positions of the bits set in `bits`, lowest first.
#[inline]
fn set_bits(bits: u64) -> impl Iterator<Item = u32> {
    let mut rest = bits;
    std::iter::from_fn(move || {
        let bit = rest.trailing_zeros();
        rest &= rest.wrapping_sub(1);
        (bit < 64).then_some(bit)
    })
}
