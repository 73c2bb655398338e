//! The surface F-score of [`Form::FScore`](crate::score::Form::FScore), counted on the
//! grid's voxels.
//!
//! A *surface voxel* of a set of voxels is one of them with a face neighbour outside the
//! set (or outside the grid). The target's surface voxels are those of its target
//! voxels (class weight above 0), found once; a model's, those of the voxels it covers.
//! Two voxels are *within* the threshold `d` when the distance between their centres is
//! at most `d`. Then, with `S` the model's surface voxels and `T` the target's:
//!
//! - precision is the share of `S` within `d` of some voxel of `T`, where every covered
//!   lattice point beyond the grid counts as a model surface voxel far from it (so that
//!   a search gains nothing by growing out of the grid);
//! - recall is the share of `T` within `d` of some voxel of `S`;
//! - the F-score is their harmonic mean, 0 when both are 0.
//!
//! This is the F-score at a threshold that reconstruction papers report (Tatarchenko et
//! al. 2019), on voxel centres rather than on points sampled from the surfaces: it
//! differs from the sampled measure runs report
//! ([`SurfaceDistance`](crate::score::metrics::SurfaceDistance)) by up to about a voxel
//! in where a surface lies.
//!
//! Counting a model costs one pass over the words it covers (its surface) and one over
//! the words of the target's surface for each row of the ball of radius `d` (recall):
//! the model's surface near the target is dilated along x once per voxel of the ball's
//! half-width, then each row of the ball is a shift of whole grid rows.

use super::classes::VoxelClasses;
use super::grid::Grid;

/// Whether voxels `(dx, dy, dz)` apart on a grid of voxel size `cell` lie within
/// `threshold` of each other. The one test of the distance, so that every count agrees.
#[inline]
pub(super) fn within(cell: [f64; 3], [dx, dy, dz]: [i64; 3], threshold: f64) -> bool {
    let (x, y, z) = (
        dx as f64 * cell[0],
        dy as f64 * cell[1],
        dz as f64 * cell[2],
    );
    x * x + y * y + z * z <= threshold * threshold
}

/// The largest half-width along x, in voxels, that the ball may have: a model surface
/// word is dilated into its neighbours only.
pub const MAX_HALF_WIDTH: i64 = 63;

/// How many voxels of `grid` the F-score's `threshold` spans along x: what may be at
/// most [`MAX_HALF_WIDTH`].
///
/// ```
/// use glam::Vec3;
/// use shapegen_runtime::score::volume::{Grid, fscore_half_width};
///
/// let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [8, 8, 8])?;
/// assert_eq!(fscore_half_width(&grid, 0.6), 2.0); // voxels of 0.25
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fscore_half_width(grid: &Grid, threshold: f64) -> f64 {
    (threshold / grid.cell().x).floor()
}

/// The word whose bit `b` is bit `64 w + b + offset` of `bits` (0 beyond its ends).
#[inline]
fn shifted(bits: &[u64], w: usize, offset: i64) -> u64 {
    let start = w as i64 * 64 + offset;
    let (q, r) = (start.div_euclid(64), start.rem_euclid(64) as u32);
    let word = |i: i64| usize::try_from(i).ok().and_then(|i| bits.get(i)).copied();
    let lo = word(q).unwrap_or(0);
    if r == 0 {
        lo
    } else {
        (lo >> r) | (word(q + 1).unwrap_or(0) << (64 - r))
    }
}

/// One row of the ball: the voxels `(-half..=half, dy, dz)` from its centre.
#[derive(Clone, Copy, Debug)]
struct Row {
    /// `dy nx + dz nx ny`: where the row lies, in voxel numbers.
    offset: i64,
    /// Its half-width along x.
    half: usize,
    /// The index of its `dy` in [`SurfaceBand::dys`], `None` for `dy = 0`.
    dy: Option<usize>,
}

/// The F-score counts of one model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct SurfaceCounts {
    /// Its surface voxels in the grid.
    pub surface: u64,
    /// Those within the threshold of the target's surface.
    pub near: u64,
    /// The target's surface voxels within the threshold of the model's surface.
    pub target_near: u64,
}

/// What the F-score needs of the grid and the targets, made once per scorer (see the
/// [module](self) docs).
#[derive(Clone, Debug)]
pub(crate) struct SurfaceBand {
    /// `nx` and `nx ny`: the voxel numbers one step along y and along z.
    steps: [i64; 2],
    /// Voxels at the first x, the last x, the first y and the last y of the grid.
    edges: [Vec<u64>; 4],
    /// The target's surface voxels.
    target: Vec<u64>,
    /// The words of `target` that are not zero.
    target_words: Vec<u32>,
    /// How many target surface voxels there are.
    target_count: u64,
    /// Voxels within the threshold of the target's surface.
    near: Vec<u64>,
    /// The words of `near` that are not zero.
    near_words: Vec<u32>,
    /// Those words and their neighbours either side, where the dilation along x may
    /// reach.
    region: Vec<u32>,
    /// The rows of the ball.
    rows: Vec<Row>,
    /// The distinct `dy` of the rows but 0.
    dys: Vec<i64>,
    /// Per word of `target_words` and per `dy` of `dys`, the voxels whose `y + dy` lies
    /// in the grid.
    y_masks: Vec<u64>,
    /// The ball's half-width along x.
    half: usize,
}

/// Sets bit `v` of `bits`.
pub(super) fn set(bits: &mut [u64], v: usize) {
    bits[v / 64] |= 1 << (v % 64);
}

/// Whether bit `v` of `bits` is set.
pub(super) fn get(bits: &[u64], v: usize) -> bool {
    bits[v / 64] >> (v % 64) & 1 == 1
}

/// The voxels of word `w` whose `y + dy` lies in the grid.
fn y_mask(grid: &Grid, w: usize, dy: i64) -> u64 {
    let ny = i64::from(grid.resolution()[1]);
    let count = grid.voxel_count() as usize;
    (0..64)
        .filter(|b| {
            let v = w * 64 + b;
            v < count && (0..ny).contains(&(grid.voxel(v)[1] + dy))
        })
        .fold(0, |m, b| m | 1 << b)
}

/// The surface voxels of `inside` (a bitset over `grid`), by their face neighbours.
pub(super) fn surface_voxels(grid: &Grid, inside: &[u64]) -> Vec<u64> {
    let mut out = vec![0u64; inside.len()];
    for v in (0..grid.voxel_count() as usize).filter(|&v| get(inside, v)) {
        let [i, j, k] = grid.voxel(v);
        let open = [
            [1, 0, 0],
            [-1, 0, 0],
            [0, 1, 0],
            [0, -1, 0],
            [0, 0, 1],
            [0, 0, -1],
        ]
        .iter()
        .any(|[a, b, c]| {
            grid.index([i + a, j + b, k + c])
                .is_none_or(|n| !get(inside, n))
        });
        if open {
            set(&mut out, v);
        }
    }
    out
}

/// The words of `bits` that are not zero.
fn nonzero_words(bits: &[u64]) -> Vec<u32> {
    (0..bits.len() as u32)
        .filter(|&w| bits[w as usize] != 0)
        .collect()
}

/// The rows of the ball of radius `threshold` (world units) in `grid`'s voxels, each
/// spanning `-half..=half` along x, and the distinct non-zero y offsets they have.
fn ball_rows(grid: &Grid, threshold: f64) -> (Vec<Row>, Vec<i64>) {
    let cell = grid.cell().to_array();
    let [nx, ny, _] = grid.resolution().map(i64::from);
    let reach = |axis: usize| (threshold / cell[axis]).floor() as i64;
    let mut rows = Vec::new();
    let mut dys = Vec::new();
    for dz in -reach(2)..=reach(2) {
        for dy in -reach(1)..=reach(1) {
            if !within(cell, [0, dy, dz], threshold) {
                continue;
            }
            let mut half = 0;
            while within(cell, [half + 1, dy, dz], threshold) {
                half += 1;
            }
            let dy_index = (dy != 0).then(|| match dys.iter().position(|&d| d == dy) {
                Some(p) => p,
                None => {
                    dys.push(dy);
                    dys.len() - 1
                }
            });
            rows.push(Row {
                offset: dy * nx + dz * nx * ny,
                half: half as usize,
                dy: dy_index,
            });
        }
    }
    (rows, dys)
}

/// The voxels of `classes`' grid on each of its four x and y edges (`x = 0`, `x` last,
/// `y = 0`, `y` last), and its target voxels, as bitsets.
fn edges_and_inside(classes: &VoxelClasses) -> ([Vec<u64>; 4], Vec<u64>) {
    let grid = classes.grid();
    let [nx, ny, _] = grid.resolution().map(i64::from);
    let count = grid.voxel_count() as usize;
    let words = count.div_ceil(64);
    let mut edges: [Vec<u64>; 4] = std::array::from_fn(|_| vec![0u64; words]);
    let mut inside = vec![0u64; words];
    for v in 0..count {
        let [i, j, _] = grid.voxel(v);
        for (e, on) in [i == 0, i == nx - 1, j == 0, j == ny - 1]
            .into_iter()
            .enumerate()
        {
            if on {
                set(&mut edges[e], v);
            }
        }
        if classes.is_target(usize::from(classes.voxels()[v])) {
            set(&mut inside, v);
        }
    }
    (edges, inside)
}

impl SurfaceBand {
    /// The band of the target voxels of `classes` at `threshold` (world units, above 0
    /// and finite). Fails, saying why, when the threshold is not such a number or spans
    /// more than [`MAX_HALF_WIDTH`] voxels along x.
    pub(crate) fn new(classes: &VoxelClasses, threshold: f64) -> Result<SurfaceBand, String> {
        let grid = classes.grid();
        if !(threshold.is_finite() && threshold > 0.0) {
            return Err(format!(
                "threshold {threshold} is not a distance (a finite number above 0)"
            ));
        }
        let cell = grid.cell().to_array();
        let [nx, ny, _] = grid.resolution().map(i64::from);
        let words = (grid.voxel_count() as usize).div_ceil(64);
        let half_width = fscore_half_width(grid, threshold);
        if half_width > MAX_HALF_WIDTH as f64 {
            return Err(format!(
                "threshold {threshold} spans {half_width} voxels of {} along x; at most \
                 {MAX_HALF_WIDTH} are supported (a smaller threshold or coarser grid)",
                cell[0]
            ));
        }
        let (rows, dys) = ball_rows(grid, threshold);
        let half = rows.iter().map(|r| r.half).max().unwrap_or(0);
        let (edges, inside) = edges_and_inside(classes);
        let target = surface_voxels(grid, &inside);
        let target_words = nonzero_words(&target);
        let mut band = SurfaceBand {
            steps: [nx, nx * ny],
            edges,
            target_count: target.iter().map(|w| u64::from(w.count_ones())).sum(),
            y_masks: target_words
                .iter()
                .flat_map(|&w| dys.iter().map(move |&dy| y_mask(grid, w as usize, dy)))
                .collect(),
            target,
            target_words,
            near: Vec::new(),
            near_words: Vec::new(),
            region: Vec::new(),
            rows,
            dys,
            half,
        };
        band.near = band.near_target(grid);
        band.near_words = nonzero_words(&band.near);
        let mut region: Vec<u32> = band
            .near_words
            .iter()
            .flat_map(|&w| [w.saturating_sub(1), w, w + 1])
            .filter(|&w| (w as usize) < words)
            .collect();
        region.sort_unstable();
        region.dedup();
        band.region = region;
        Ok(band)
    }

    /// The voxels within the threshold of the target's surface: the same dilation as a
    /// model's recall, over the whole grid.
    fn near_target(&self, grid: &Grid) -> Vec<u64> {
        let words = self.target.len();
        let all: Vec<u32> = (0..words as u32).collect();
        let mut dilated = vec![self.target.clone()];
        self.dilate_x(&all, &mut dilated);
        let mut near = vec![0u64; words];
        let mut masks = vec![0u64; self.dys.len()];
        for (w, out) in near.iter_mut().enumerate() {
            for (mask, &dy) in masks.iter_mut().zip(&self.dys) {
                *mask = y_mask(grid, w, -dy);
            }
            for row in &self.rows {
                let mut m = shifted(&dilated[row.half], w, -row.offset);
                if let Some(d) = row.dy {
                    m &= masks[d];
                }
                *out |= m;
            }
        }
        near
    }

    /// Fills `dilated[h]` (for `h` in `1..=half`) on the words `over` with `dilated[0]`
    /// dilated by `h` voxels along x, within rows.
    fn dilate_x(&self, over: &[u32], dilated: &mut Vec<Vec<u64>>) {
        let words = self.target.len();
        dilated.resize_with(self.half + 1, || vec![0; words]);
        let [first, last, ..] = &self.edges;
        for h in 1..=self.half {
            let (done, rest) = dilated.split_at_mut(h);
            let (prev, next) = (&done[h - 1], &mut rest[0]);
            for &w in over {
                let w = w as usize;
                next[w] =
                    prev[w] | (shifted(prev, w, 1) & !last[w]) | (shifted(prev, w, -1) & !first[w]);
            }
        }
    }

    /// The surface voxels of word `w` of `covered`.
    #[inline]
    fn surface_word(&self, covered: &[u64], w: usize) -> u64 {
        let c = covered[w];
        if c == 0 {
            return 0;
        }
        let [x_first, x_last, y_first, y_last] = &self.edges;
        let [ny, nz] = self.steps;
        let interior = shifted(covered, w, 1)
            & !x_last[w]
            & shifted(covered, w, -1)
            & !x_first[w]
            & shifted(covered, w, ny)
            & !y_last[w]
            & shifted(covered, w, -ny)
            & !y_first[w]
            & shifted(covered, w, nz)
            & shifted(covered, w, -nz);
        c & !interior
    }

    /// The counts of the model covering `covered` (a bitset over the grid whose words
    /// not listed in `touched` are zero), with `dilated` as working memory.
    pub(crate) fn count(
        &self,
        covered: &[u64],
        touched: impl Iterator<Item = usize>,
        dilated: &mut Vec<Vec<u64>>,
    ) -> SurfaceCounts {
        let mut counts = SurfaceCounts::default();
        // The model's surface near the target, in `dilated[0]`, whose other words stay
        // zero: the near words cleared, then each covered word's written.
        if dilated.is_empty() {
            dilated.push(vec![0; self.target.len()]);
        }
        for &w in &self.near_words {
            dilated[0][w as usize] = 0;
        }
        for w in touched {
            let s = self.surface_word(covered, w);
            let near = s & self.near[w];
            counts.surface += u64::from(s.count_ones());
            counts.near += u64::from(near.count_ones());
            if near != 0 {
                dilated[0][w] = near;
            }
        }
        if counts.near == 0 {
            return counts;
        }
        self.dilate_x(&self.region, dilated);
        let dys = self.dys.len();
        for (p, &w) in self.target_words.iter().enumerate() {
            let (w, target) = (w as usize, self.target[w as usize]);
            let mut hit = 0;
            for row in &self.rows {
                let mut m = shifted(&dilated[row.half], w, row.offset);
                if let Some(d) = row.dy {
                    m &= self.y_masks[p * dys + d];
                }
                hit |= m;
                if hit & target == target {
                    break;
                }
            }
            counts.target_near += u64::from((hit & target).count_ones());
        }
        counts
    }

    /// How many surface voxels the target has.
    pub(crate) fn target_count(&self) -> u64 {
        self.target_count
    }
}
