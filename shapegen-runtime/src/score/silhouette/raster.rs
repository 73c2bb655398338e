//! Scanline rasterization of convex polygons into a coverage bitset.
//!
//! A pixel `(x, y)` (row 0 at the top) is covered when its centre `(x + 0.5, y + 0.5)`
//! lies inside a polygon, with the top-left rule deciding centres exactly on an edge: a
//! centre on a left edge or on a horizontal top edge is inside, one on a right or bottom
//! edge is not. Projected vertices snap to 1/256 of a pixel, as GPUs snap them, and
//! centres on an edge are found exactly, so the CPU and GPU paths decide the same
//! centres, and two polygons sharing an edge split the centres on it exactly.

use glam::{Vec2, Vec4};
use wide::i32x8;

/// Most vertices a polygon handed to [`fill_convex`] may have.
pub(super) const MAX_POLYGON: usize = 128;

/// Which pixels of one image are covered, as one bit per pixel (rows padded to whole
/// 64-bit words), with the list of the words that became non-zero, so that reading and
/// clearing costs what was covered rather than the whole image.
#[derive(Clone, Debug, Default)]
pub(in crate::score) struct Coverage {
    words: Vec<u64>,
    touched: Vec<u32>,
    stride: usize,
    width: u32,
    height: u32,
    /// The left and right edges of the polygon being filled.
    left: Vec<Edge>,
    right: Vec<Edge>,
}

/// Words per row of an image `width` pixels wide.
pub(in crate::score) fn row_words(width: u32) -> usize {
    (width as usize).div_ceil(64)
}

/// The bits of word `w` (of a row's words `first..=last`) that pixels `col0..col1` of
/// the row take.
#[inline]
fn span_mask(w: usize, first: usize, last: usize, col0: usize, col1: usize) -> u64 {
    let lo = if w == first { col0 % 64 } else { 0 };
    let hi = if w == last { (col1 - 1) % 64 + 1 } else { 64 };
    if hi - lo == 64 {
        u64::MAX
    } else {
        ((1u64 << (hi - lo)) - 1) << lo
    }
}

impl Coverage {
    /// Prepares an empty coverage of `width` x `height` pixels, keeping the memory.
    pub(in crate::score) fn shape(&mut self, width: u32, height: u32) {
        debug_assert!(self.touched.is_empty(), "coverage cleared before reshaping");
        self.stride = row_words(width);
        self.width = width;
        self.height = height;
        let len = self.stride * height as usize;
        if self.words.len() < len {
            self.words.resize(len, 0);
        }
    }

    /// Marks pixels `col0..col1` of `row` covered.
    #[inline]
    fn fill_row(&mut self, row: usize, col0: usize, col1: usize) {
        let base = row * self.stride;
        let (first, last) = (col0 / 64, (col1 - 1) / 64);
        for w in first..=last {
            let mask = span_mask(w, first, last, col0, col1);
            let word = &mut self.words[base + w];
            if *word == 0 {
                self.touched.push((base + w) as u32);
            }
            *word |= mask;
        }
    }

    /// Whether pixels `col0..col1` of every row in `rows` are covered.
    #[inline]
    fn covers_box(&self, rows: std::ops::Range<usize>, col0: usize, col1: usize) -> bool {
        let (first, last) = (col0 / 64, (col1 - 1) / 64);
        rows.into_iter().all(|row| {
            let base = row * self.stride;
            (first..=last).all(|w| {
                let mask = span_mask(w, first, last, col0, col1);
                self.words[base + w] & mask == mask
            })
        })
    }

    /// Hands every non-zero word (its index and bits) to `visit` and clears the
    /// coverage.
    #[inline]
    pub(in crate::score) fn drain(&mut self, mut visit: impl FnMut(usize, u64)) {
        for &w in &self.touched {
            let word = &mut self.words[w as usize];
            visit(w as usize, *word);
            *word = 0;
        }
        self.touched.clear();
    }

    /// Whether pixel `(x, y)` is covered.
    pub(in crate::score) fn get(&self, x: u32, y: u32) -> bool {
        let bit = x as usize % 64;
        let word = self.words[y as usize * self.stride + x as usize / 64];
        word >> bit & 1 == 1
    }

    /// Fills the convex polygon `poly` (pixel coordinates, either winding); degenerate
    /// polygons cover nothing.
    pub(in crate::score) fn fill_convex(&mut self, poly: &[Vec2]) {
        let n = poly.len();
        if n < 3 {
            return;
        }
        let mut area2 = 0.0f32;
        let (mut ymin, mut ymax) = (f32::INFINITY, f32::NEG_INFINITY);
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            area2 += a.x * b.y - b.x * a.y;
            ymin = ymin.min(a.y);
            ymax = ymax.max(a.y);
        }
        if area2 == 0.0 || !area2.is_finite() {
            return;
        }
        let row0 = (ymin - 0.5).ceil().max(0.0);
        let row1 = (ymax - 0.5).ceil().min(self.height as f32);
        if row0 >= row1 {
            return;
        }
        // Each non-horizontal edge bounds the polygon on the left or on the right, from
        // its endpoint first in (y, x) order to the other.
        self.left.clear();
        self.right.clear();
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let dy = b.y - a.y;
            if dy == 0.0 {
                continue;
            }
            let (p, q) = if (a.y, a.x) < (b.y, b.x) {
                (a, b)
            } else {
                (b, a)
            };
            let edge = Edge::new(p, q);
            if (area2 > 0.0) == (dy > 0.0) {
                self.right.push(edge);
            } else {
                self.left.push(edge);
            }
        }
        let width = self.width as f32;
        for row in row0 as usize..row1 as usize {
            let yc = row as f32 + 0.5;
            let col0 = first_column(&self.left, yc, Bound::Left).max(0.0);
            let col1 = first_column(&self.right, yc, Bound::Right).min(width);
            if col0 < col1 {
                self.fill_row(row, col0 as usize, col1 as usize);
            }
        }
    }
}

impl Coverage {
    /// Fills the triangle `tri` (pixel coordinates snapped to [`SUBPIXEL`] steps, either
    /// winding), covering exactly the pixels [`Coverage::fill_convex`] covers, faster.
    ///
    /// Within [`EXACT_LIMIT`] pixels of the origin `fill_convex` decides every centre as
    /// the exact top-left rule on the snapped vertices does (its `f32` crossings err by
    /// well under [`TIE`] there, and ties are settled exactly), except that a triangle
    /// whose `f32` signed area is zero, or of the other sign than its exact one, covers
    /// nothing (its left and right edges swap, and no span is left between them). So
    /// here the triangle's vertices become integers in `1/256` pixel, its area's `f32`
    /// sign is checked as `fill_convex` computes it ([`f32_agrees`]), and
    /// [`Coverage::fill_exact`] fills it. Triangles farther out, or not finite, go to
    /// `fill_convex`.
    pub(in crate::score) fn fill_triangle(&mut self, tri: [Vec2; 3]) {
        let area2 = signed_area(&tri);
        if !area2.is_finite() {
            return;
        }
        if !tri.iter().all(|p| in_reach(*p)) {
            return self.fill_convex(&tri);
        }
        let v = tri.map(to_fixed);
        let exact = exact_area(&v);
        if exact != 0 && f32_agrees(area2, exact) {
            self.fill_exact(v, exact > 0);
        }
    }

    /// Fills the triangle `v` (in `1/256` pixel, within [`EXACT_LIMIT`] pixels of the
    /// origin; `ccw` whether its exact signed area is positive, which must not be zero),
    /// each centre decided by exact integer edge tests: one by one in a small box
    /// ([`Coverage::fill_small`]), by walking the edges row by row otherwise.
    #[inline]
    pub(super) fn fill_exact(&mut self, v: [[i32; 2]; 3], ccw: bool) {
        // Rows whose centre lies in [ymin, ymax), columns whose centre lies in
        // [xmin, xmax): no centre outside these is covered.
        let [xmin, xmax, ymin, ymax] = span(v);
        let row0 = first_centre(ymin).max(0);
        let row1 = first_centre(ymax).min(self.height as i32);
        let col_lo = first_centre(xmin).max(0);
        let col_hi = first_centre(xmax).min(self.width as i32);
        if row0 >= row1 || col_lo >= col_hi {
            return;
        }
        let (row0, row1, col_lo, col_hi) = (
            row0 as usize,
            row1 as usize,
            col_lo as usize,
            col_hi as usize,
        );
        // Nothing to add where the triangle's box is covered already.
        if self.covers_box(row0..row1, col_lo, col_hi) {
            return;
        }
        let v = v.map(|p| p.map(i64::from));
        let (cols, rows) = (col_hi - col_lo, row1 - row0);
        let small = cols <= SMALL_BOX_COLUMNS
            && cols * rows <= SMALL_BOX_CENTRES
            && xmax - xmin <= SMALL_EXTENT[0]
            && ymax - ymin <= SMALL_EXTENT[1];
        if small {
            return self.fill_small(&v, ccw, [row0, row1], col_lo, cols);
        }
        self.walk(&v, ccw, [row0, row1], [col_lo, col_hi]);
    }

    /// Fills the triangle `v` (in `1/256` pixel; `ccw` whether its exact signed area is
    /// positive) in the box of rows `rows[0]..rows[1]` and columns `cols[0]..cols[1]`
    /// by walking its left and right edges down the rows ([`FixedEdge`]).
    fn walk(&mut self, v: &[[i64; 2]; 3], ccw: bool, rows: [usize; 2], cols: [usize; 2]) {
        let mut left = [FixedEdge::default(); 3];
        let mut right = [FixedEdge::default(); 3];
        let (mut n_left, mut n_right) = (0, 0);
        for (p, q, on_right) in sloped_edges(v, ccw).into_iter().flatten() {
            let edge = FixedEdge::new(p, q, rows[0] as i64);
            if on_right {
                right[n_right] = edge;
                n_right += 1;
            } else {
                left[n_left] = edge;
                n_left += 1;
            }
        }
        let (left, right) = (&mut left[..n_left], &mut right[..n_right]);
        let (col_lo, col_hi) = (cols[0] as i64, cols[1] as i64);
        for row in rows[0]..rows[1] {
            let mut col0 = col_lo;
            for e in left.iter_mut() {
                col0 = col0.max(e.c);
                e.step();
            }
            let mut col1 = col_hi;
            for e in right.iter_mut() {
                col1 = col1.min(e.c);
                e.step();
            }
            if col0 < col1 {
                self.fill_row(row, col0 as usize, col1 as usize);
            }
        }
    }
}

impl Coverage {
    /// [`Coverage::fill_exact`] for a small box of pixel centres (`cols` columns from
    /// `col0`, rows `rows[0]..rows[1]`) of a triangle whose vertices span at most
    /// [`SMALL_EXTENT`]: every centre tested against every non-horizontal edge, the same
    /// tests the row walk's columns stand for, eight columns at a time. `v` are the
    /// vertices in `1/256` pixel, `ccw` whether their exact signed area is positive.
    fn fill_small(
        &mut self,
        v: &[[i64; 2]; 3],
        ccw: bool,
        rows: [usize; 2],
        col0: usize,
        cols: usize,
    ) {
        // Per edge, `g = s f - bias` at the box's first centre and its steps, where
        // `f = (xc - px) dy - (yc - py) dx` (`p` the upper end, `dy > 0`): a centre is
        // inside a left edge (`s = 1`) when `f >= 0`, a right edge (`s = -1`) when
        // `f < 0`; so inside every edge when every `g >= 0`, when the sign bit of
        // their bitwise or is clear. A horizontal edge bounds nothing here (the rows
        // do): `g = 0` throughout. Every centre of the box lies within the vertices'
        // span, so `|f| <= 2 * 2^14 * 2^15 = 2^30` there: `i32` holds every `g`. The
        // lanes past the box's last column may wrap; their bits are dropped.
        let mut g = [0i32; 3];
        let mut per_col = [0i32; 3];
        let mut per_row = [0i32; 3];
        let (x0, y0) = (256 * col0 as i64 + 128, 256 * rows[0] as i64 + 128);
        for (i, edge) in sloped_edges(v, ccw).into_iter().enumerate() {
            let Some((p, q, on_right)) = edge else {
                continue;
            };
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let (s, bias) = if on_right { (-1, 1) } else { (1, 0) };
            g[i] = (s * ((x0 - p[0]) * dy - (y0 - p[1]) * dx) - bias) as i32;
            per_col[i] = (s * 256 * dy) as i32;
            per_row[i] = (-s * 256 * dx) as i32;
        }
        let edges = EdgeLanes::new(per_col);
        let chunks = cols.div_ceil(LANES);
        let keep = u64::MAX >> (64 - cols);
        let (word, shift) = (col0 / 64, (col0 % 64) as u32);
        for row in rows[0]..rows[1] {
            let bits = edges.outside(g, chunks);
            let bits = !bits & keep;
            g = std::array::from_fn(|k| g[k].wrapping_add(per_row[k]));
            if bits != 0 {
                let base = row * self.stride + word;
                self.or_word(base, bits << shift);
                if shift > 0 && bits >> (64 - shift) != 0 {
                    self.or_word(base + 1, bits >> (64 - shift));
                }
            }
        }
    }

    /// Sets `bits` in word `w`, recording it when it becomes non-zero.
    #[inline]
    fn or_word(&mut self, w: usize, bits: u64) {
        let word = &mut self.words[w];
        if *word == 0 && bits != 0 {
            self.touched.push(w as u32);
        }
        *word |= bits;
    }
}

/// Columns [`Coverage::fill_small`] tests at once.
const LANES: usize = 8;

/// The three edge functions of a triangle over [`LANES`] consecutive pixel centres of a
/// row, as [`Coverage::fill_small`] tests them: per edge, its value at the row's first
/// centre plus its step per column times the lane, all lanes at once.
struct EdgeLanes {
    /// Per edge, the step per column times each lane.
    ramp: [i32x8; 3],
    /// Per edge, the step over all [`LANES`].
    per_chunk: [i32; 3],
}

impl EdgeLanes {
    /// The lanes of edges whose values step by `per_col` per column.
    #[inline]
    fn new(per_col: [i32; 3]) -> EdgeLanes {
        const LANE: i32x8 = i32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
        EdgeLanes {
            ramp: per_col.map(|p| LANE * i32x8::splat(p)),
            per_chunk: per_col.map(|p| p.wrapping_mul(LANES as i32)),
        }
    }

    /// Of the first `chunks * LANES` centres of a row whose edge values at its first
    /// centre are `e`, those outside some edge (a negative value: the sign bit of the
    /// values' bitwise or), as bits.
    #[inline]
    fn outside(&self, mut e: [i32; 3], chunks: usize) -> u64 {
        let mut bits = u64::from(self.outside_chunk(e));
        for chunk in 1..chunks {
            e = std::array::from_fn(|k| e[k].wrapping_add(self.per_chunk[k]));
            bits |= u64::from(self.outside_chunk(e)) << (chunk * LANES);
        }
        bits
    }

    /// [`EdgeLanes::outside`] for the first [`LANES`] centres.
    #[inline(always)]
    fn outside_chunk(&self, e: [i32; 3]) -> u32 {
        let any = (i32x8::splat(e[0]) + self.ramp[0])
            | (i32x8::splat(e[1]) + self.ramp[1])
            | (i32x8::splat(e[2]) + self.ramp[2]);
        any.to_bitmask()
    }
}

/// The signed area (twice it) of the triangle `tri`, in `f32`, summed as
/// [`Coverage::fill_convex`] sums it.
#[inline]
pub(super) fn signed_area(tri: &[Vec2; 3]) -> f32 {
    let mut area2 = 0.0f32;
    for i in 0..3 {
        let (a, b) = (tri[i], tri[(i + 1) % 3]);
        area2 += a.x * b.y - b.x * a.y;
    }
    area2
}

/// Twice the signed area of the triangle `v` (in `1/256` pixel), exactly.
#[inline]
pub(super) fn exact_area(v: &[[i32; 2]; 3]) -> i64 {
    let v = v.map(|p| p.map(i64::from));
    (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0])
}

/// Whether a triangle's `f32` signed area `area2` ([`signed_area`]) is not zero and has
/// the sign of its exact one, `exact` (not zero): otherwise [`Coverage::fill_convex`]
/// covers nothing of the triangle, and so neither does [`Coverage::fill_triangle`].
#[inline]
pub(super) fn f32_agrees(area2: f32, exact: i64) -> bool {
    area2 != 0.0 && (exact > 0) == (area2 > 0.0)
}

/// An area (twice it, in `1/256` pixel squared) above which the `f32` signed area of a
/// triangle whose coordinates are at most `reach` (in `1/256` pixel) from the origin
/// has its exact one's sign, so that [`f32_agrees`] need not be asked.
///
/// With `M` that reach in pixels and `u = 2^-24`, each of the three terms
/// `a.x b.y - b.x a.y` that [`signed_area`] sums errs by at most `2uM^2` from its two
/// products and `2uM^2(1 + u)` from their difference, and the two sums by `4uM^2` and
/// `6uM^2` (their sizes, `4M^2` and `6M^2`, times `u`), less than `23uM^2` in all. In
/// `1/256` pixel, `23 u M^2 65536 = 23 reach^2 / 2^24`.
#[inline]
pub(super) fn f32_safe_area(reach: i32) -> i64 {
    ((23 * i64::from(reach) * i64::from(reach)) >> 24) + 1
}

/// The span of the points `v` (in `1/256` pixel): `[xmin, xmax, ymin, ymax]`.
#[inline]
pub(super) fn span(v: impl IntoIterator<Item = [i32; 2]>) -> [i32; 4] {
    v.into_iter()
        .fold([i32::MAX, i32::MIN, i32::MAX, i32::MIN], |s, p| {
            [
                s[0].min(p[0]),
                s[1].max(p[0]),
                s[2].min(p[1]),
                s[3].max(p[1]),
            ]
        })
}

/// Whether `p` lies within [`EXACT_LIMIT`] pixels of the origin on both axes.
#[inline]
pub(super) fn in_reach(p: Vec2) -> bool {
    p.x.abs() <= EXACT_LIMIT && p.y.abs() <= EXACT_LIMIT
}

/// A snapped point [`in_reach`] in `1/256` pixel.
#[inline]
pub(super) fn to_fixed(p: Vec2) -> [i32; 2] {
    debug_assert!(
        (p.x * SUBPIXEL).fract() == 0.0 && (p.y * SUBPIXEL).fract() == 0.0,
        "vertices snapped to 1/256 pixel: {p:?}"
    );
    [(p.x * SUBPIXEL) as i32, (p.y * SUBPIXEL) as i32]
}

/// The non-horizontal edges of the triangle `v` (in `1/256` pixel; `ccw` whether its
/// exact signed area is positive), in order: each from its upper end to its lower end,
/// and whether it bounds the triangle on the right (the triangle lies left of it) rather
/// than on the left. A horizontal edge is `None`.
#[inline]
fn sloped_edges(v: &[[i64; 2]; 3], ccw: bool) -> [Option<SlopedEdge>; 3] {
    std::array::from_fn(|i| {
        let (a, b) = (v[i], v[(i + 1) % 3]);
        let dy = b[1] - a[1];
        let on_right = ccw == (dy > 0);
        match dy.cmp(&0) {
            std::cmp::Ordering::Equal => None,
            std::cmp::Ordering::Greater => Some((a, b, on_right)),
            std::cmp::Ordering::Less => Some((b, a, on_right)),
        }
    })
}

/// A non-horizontal edge as [`sloped_edges`] gives it: upper end, lower end, whether it
/// bounds the triangle on the right.
type SlopedEdge = ([i64; 2], [i64; 2], bool);

/// Widest box of pixel centres, in columns, that [`Coverage::fill_triangle`] tests
/// centre by centre rather than walking edges (its row of tests fits one word).
const SMALL_BOX_COLUMNS: usize = 32;

/// Most centres in a box that [`Coverage::fill_triangle`] tests one by one.
const SMALL_BOX_CENTRES: usize = 96;

/// Widest and tallest span of a triangle's vertices, in `1/256` pixel (64 and 128
/// pixels), that [`Coverage::fill_small`] takes, so that its edge values fit `i32`.
const SMALL_EXTENT: [i32; 2] = [64 * 256, 128 * 256];

/// How far from the origin, in pixels, [`Coverage::fill_triangle`] takes a triangle's
/// vertices itself: there every crossing `fill_convex` estimates (from coordinates and
/// edge spans below 4096 pixels) errs by less than 2e-3 px, under [`TIE`].
const EXACT_LIMIT: f32 = 2048.0;

/// The first pixel index whose centre lies at or past `t` (in `1/256` pixel): the
/// smallest `i` with `256 i + 128 >= t`.
#[inline]
fn first_centre(t: i32) -> i32 {
    (t - 128 + 255) >> 8
}

/// A non-horizontal triangle edge in `1/256` pixel, from `p` to `q` (`q` below), as
/// [`Coverage::fill_triangle`] walks it row by row. In the row whose centre is at `yc`
/// (`256 row + 128`), the first column whose centre lies on or right of the edge's line
/// is the smallest `c` with `c d >= n`, where `n = (yc - py) dx - (128 - px) dy` and
/// `d = 256 dy`. The walk keeps that `c` and the excess `e = c d - n` (`0 <= e < d`);
/// a row down adds `256 dx = a d - b` (`0 <= b < d`) to `n`, so `c` gains `a`, and loses
/// 1 again when `e + b` reaches `d`: exact integer steps, no division per row.
#[derive(Clone, Copy, Debug, Default)]
struct FixedEdge {
    /// The first column on or right of the line in the current row.
    c: i64,
    /// `c d - n`.
    e: i64,
    /// `d = 256 dy`, positive.
    d: i64,
    /// Whole columns per row, rounded up: `a = ceil(256 dx / d)`.
    a: i64,
    /// `a d - 256 dx`.
    b: i64,
}

impl FixedEdge {
    fn new(p: [i64; 2], q: [i64; 2], row: i64) -> FixedEdge {
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let yc = 256 * row + 128;
        let n = (yc - p[1]) * dx - (128 - p[0]) * dy;
        let (d, dn) = (256 * dy, 256 * dx);
        let (c, a) = (ceil_div(n, d), ceil_div(dn, d));
        FixedEdge {
            c,
            e: c * d - n,
            d,
            a,
            b: a * d - dn,
        }
    }

    /// On to the next row.
    #[inline]
    fn step(&mut self) {
        self.e += self.b;
        let wrap = i64::from(self.e >= self.d);
        self.e -= wrap * self.d;
        self.c += self.a - wrap;
    }
}

/// `ceil(n / d)` for `d > 0` and `|n| < 2^52`: the `f64` quotient (within far less than 1
/// of the exact one), truncated, then corrected exactly.
#[inline]
fn ceil_div(n: i64, d: i64) -> i64 {
    let mut c = (n as f64 / d as f64) as i64;
    if c * d < n {
        c += 1;
    } else if (c - 1) * d >= n {
        c -= 1;
    }
    c
}

/// Which side of a polygon a set of edges bounds.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Bound {
    /// The polygon lies right of every left edge.
    Left,
    /// The polygon ends at the first right edge.
    Right,
}

/// In the scanline at height `yc`, the first column whose centre lies on or right of
/// every one of the left `edges` (the first covered column), or of any one of the right
/// `edges` (the first column past the polygon).
///
/// The crossings' `f32` estimates decide, unless the bounding crossing falls within
/// their rounding (well under [`TIE`]) of a centre; then cross products in `f64` settle
/// it: a centre `xc` lies on or right of an edge's line when
/// `(xc - px) dy >= (yc - py) dx`. On vertices snapped to [`SUBPIXEL`] steps within
/// `2^18` pixels of the origin every factor has at most 26 significant bits, so these
/// products are exact and centres exactly on an edge are decided exactly, as a GPU's
/// fixed-point rasterizer decides them.
#[inline]
fn first_column(edges: &[Edge], yc: f32, bound: Bound) -> f32 {
    // The bounding crossing, less half a pixel: the first column is its ceiling.
    let mut x = match bound {
        Bound::Left => f32::NEG_INFINITY,
        Bound::Right => f32::INFINITY,
    };
    for e in edges {
        let crossing = e.px + (yc - e.py) * e.slope - 0.5;
        x = match bound {
            Bound::Left => x.max(crossing),
            Bound::Right => x.min(crossing),
        };
    }
    let col = x.ceil();
    let above = col - x;
    if !x.is_finite() || (TIE..=1.0 - TIE).contains(&above) {
        return col;
    }
    // Within rounding of the centre of column `nearest`.
    let nearest = if above < 0.5 { col } else { col - 1.0 };
    let (centre, yc) = (f64::from(nearest) + 0.5, f64::from(yc));
    let on_or_right = |e: &Edge| {
        let (px, py) = (f64::from(e.px), f64::from(e.py));
        (centre - px) * f64::from(e.dy) >= (yc - py) * f64::from(e.dx)
    };
    let inside = match bound {
        Bound::Left => edges.iter().all(on_or_right),
        Bound::Right => edges.iter().any(on_or_right),
    };
    if inside { nearest } else { nearest + 1.0 }
}

/// How near, in pixels, an estimated crossing must come to a pixel centre for the exact
/// test to decide: far more than the `f32` estimate's rounding in an image up to 8192
/// pixels wide.
const TIE: f32 = 2e-3;

/// A non-horizontal polygon edge from `p` to `q`, `p` first in `(y, x)` order.
#[derive(Clone, Copy, Debug, Default)]
struct Edge {
    px: f32,
    py: f32,
    dx: f32,
    dy: f32,
    slope: f32,
}

impl Edge {
    fn new(p: Vec2, q: Vec2) -> Edge {
        let (dx, dy) = (q.x - p.x, q.y - p.y);
        Edge {
            px: p.x,
            py: p.y,
            dx,
            dy,
            slope: dx / dy,
        }
    }
}

/// Steps per pixel to which vertex positions snap before rasterization: 8 sub-pixel bits,
/// as GPUs snap them (Vulkan's `subPixelPrecisionBits`, 8 on common hardware and on
/// llvmpipe), so that both paths decide the same centres.
pub(super) const SUBPIXEL: f32 = 256.0;

/// Clip space to pixel coordinates of a `width` x `height` image, row 0 at the top:
/// `x = (ndc_x + 1) / 2 * width`, `y = (1 - ndc_y) / 2 * height`, snapped to the nearest
/// [`SUBPIXEL`] step.
#[inline]
pub(super) fn to_pixels(clip: Vec4, width: f32, height: f32) -> Vec2 {
    let inv = 1.0 / clip.w;
    let p = Vec2::new(
        (clip.x * inv + 1.0) * 0.5 * width,
        (1.0 - clip.y * inv) * 0.5 * height,
    );
    Vec2::new(snap(p.x * SUBPIXEL), snap(p.y * SUBPIXEL)) / SUBPIXEL
}

/// `t` rounded to the nearest integer, ties to even, as a float-to-fixed conversion
/// rounds: adding and taking away `1.5 * 2^23` leaves no fraction bits below 1 for any
/// `|t| < 2^22`; larger values (vertices thousands of pixels outside the image) keep
/// what fraction `f32` has left.
#[inline]
fn snap(t: f32) -> f32 {
    const MAGIC: f32 = 12_582_912.0;
    if t.abs() < 4_194_304.0 {
        (t + MAGIC) - MAGIC
    } else {
        t
    }
}

/// Whether a clip-space point lies in front of the near plane (`z >= -w`, `w > 0`).
#[inline]
pub(super) fn in_front(clip: Vec4) -> bool {
    clip.z + clip.w >= 0.0 && clip.w > 0.0
}

/// Smallest `w` kept when clipping, so that the divide stays finite.
const MIN_W: f32 = 1e-6;

/// Clips the triangle `tri` (clip space) to the near plane `z + w >= 0` (and `w >= 1e-6`,
/// which a perspective camera's near plane implies), writing the convex polygon left
/// into `out` and returning its vertex count (0, 3, 4 or 5).
pub(super) fn clip_triangle(tri: [Vec4; 3], out: &mut [Vec4; 5]) -> usize {
    let mut a = [Vec4::ZERO; 5];
    a[..3].copy_from_slice(&tri);
    let n = clip_plane(&a, 3, out, |v| v.z + v.w);
    if n == 0 {
        return 0;
    }
    a[..n].copy_from_slice(&out[..n]);
    clip_plane(&a, n, out, |v| v.w - MIN_W)
}

/// One Sutherland-Hodgman step: keeps the part of `poly[..n]` where `d >= 0`.
fn clip_plane(poly: &[Vec4; 5], n: usize, out: &mut [Vec4; 5], d: impl Fn(Vec4) -> f32) -> usize {
    let mut m = 0;
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let (dp, dq) = (d(p), d(q));
        if dp >= 0.0 {
            out[m] = p;
            m += 1;
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            out[m] = p + (q - p) * (dp / (dp - dq));
            m += 1;
        }
    }
    // A triangle clipped by two planes has at most 5 vertices.
    debug_assert!(m <= 5);
    m
}

/// Writes the convex hull of `points` (at most [`MAX_POLYGON`] of them) into `hull`, in
/// either winding, and returns its vertex count; collinear points are dropped. Sorts
/// `points` in place.
#[inline]
pub(super) fn convex_hull(points: &mut [Vec2], hull: &mut [Vec2; MAX_POLYGON + 1]) -> usize {
    points.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut k = 0;
    for &p in points.iter() {
        while k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0 {
            k -= 1;
        }
        hull[k] = p;
        k += 1;
    }
    let lower = k + 1;
    for &p in points.iter().rev().skip(1) {
        while k >= lower && cross(hull[k - 2], hull[k - 1], p) <= 0.0 {
            k -= 1;
        }
        hull[k] = p;
        k += 1;
    }
    k.saturating_sub(1)
}
