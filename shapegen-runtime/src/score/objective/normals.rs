//! Distinct surface normals: greedy clustering in triangle order, and how far apart the
//! distinct normals are.
//!
//! Both are defined by comparing normals with every distinct normal found (see
//! [`cluster`] and [`spread`]). Once there are more than a few dozen distinct normals,
//! both go through a [`NormalGrid`] of cubic cells instead, so that a normal is compared
//! only with the distinct normals of the cells that can hold one close enough to
//! matter. Whether a normal joins a representative, and
//! which representative is nearest, do not depend on the order the candidates are
//! visited in, and every cell that could hold a deciding candidate is visited (the
//! bounds below include the rounding of the `f64` dot products and cell indices), so
//! the results are exactly those of comparing with every representative: the same
//! representatives, in the same order, and the same sum.

use glam::Vec3;

/// Slack added to distances and dot-product bounds, far above the rounding of the
/// `f64` arithmetic on `f32` components (about `1e-15` here) and far below any
/// distance that matters.
const SLACK: f64 = 1e-9;

/// Most cells of a grid along one axis.
const MAX_CELLS_PER_AXIS: usize = 1024;

/// [`cluster`] compares each normal with every representative until it has found this
/// many, then goes through the grid: below about this many the comparisons cost less
/// than the grid (measured on `benches/objective.rs`'s synthetic buildings, 58 distinct
/// normals on average, and on building programs, some 1,700).
const CLUSTER_LINEAR: usize = 64;

/// Up to this many distinct normals, [`spread`] compares every pair (as cheap as the grid
/// there).
const SPREAD_BRUTE_FORCE: usize = 64;

/// Rings of cells [`spread`] searches around a normal before comparing it with all.
const SPREAD_MAX_RING: usize = 3;

/// No point in a bucket.
const NONE: u32 = u32::MAX;

/// A uniform grid of cubic cells over the bounding box of a set of points, holding the
/// points (numbered in the order they were added) in lists per cell.
///
/// A point's cell is `floor((p - origin) / side)` per axis, clamped to the grid, so that
/// the cells of `p - r` and `p + r` (per axis) bound the cells of every point within
/// `r` of `p` (with `r` a little above the true distance, for the rounding). The cells
/// hash into a table of about twice as many buckets as points, small enough to stay in
/// cache: a bucket may hold the points of several cells, so a walk over cells may see
/// points of other cells too, which only costs a comparison.
#[derive(Clone, Debug, Default)]
pub(super) struct NormalGrid {
    origin: [f64; 3],
    side: f64,
    /// `1 / side`.
    inverse: f64,
    dims: [usize; 3],
    /// The buckets in use less one (their number is a power of two).
    mask: usize,
    /// The first point of each bucket, or [`NONE`]; every entry is [`NONE`] outside a
    /// fill.
    heads: Vec<u32>,
    /// The next point of the same bucket, per point.
    next: Vec<u32>,
    /// The buckets that have points.
    touched: Vec<u32>,
}

/// A normal's coordinates in `f64`.
fn coords(n: Vec3) -> [f64; 3] {
    [f64::from(n.x), f64::from(n.y), f64::from(n.z)]
}

/// The smallest and largest coordinates of `points` and the largest squared norm.
fn bounds(points: &[Vec3]) -> ([f64; 3], [f64; 3], f64) {
    let (mut lo, mut hi, mut norm2) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3], 0.0f64);
    for &n in points {
        let p = coords(n);
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
        norm2 = norm2.max(dot(n, n));
    }
    (lo, hi, norm2)
}

impl NormalGrid {
    /// Empties the grid and lays it over the box `[lo, hi]` with cells of side at least
    /// `side` (more when the box would take more than [`MAX_CELLS_PER_AXIS`] cells), for
    /// up to `points` points.
    fn shape(&mut self, lo: [f64; 3], hi: [f64; 3], side: f64, points: usize) {
        self.clear();
        let extent = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
        let side = side
            .max(extent / (MAX_CELLS_PER_AXIS - 1) as f64)
            .max(SLACK);
        self.origin = lo;
        self.side = side;
        self.inverse = 1.0 / side;
        for a in 0..3 {
            self.dims[a] = (((hi[a] - lo[a]) / side) as usize + 1).min(MAX_CELLS_PER_AXIS);
        }
        let buckets = (2 * points).next_power_of_two().max(16);
        self.mask = buckets - 1;
        if self.heads.len() < buckets {
            self.heads.resize(buckets, NONE);
        }
    }

    /// Forgets every point, clearing only the buckets that had one.
    fn clear(&mut self) {
        for &bucket in &self.touched {
            self.heads[bucket as usize] = NONE;
        }
        self.touched.clear();
        self.next.clear();
    }

    /// The cell index of coordinate `x` along axis `a`: `floor((x - origin) / side)`
    /// clamped to the grid (a cast, which truncates and saturates: the same for the
    /// points inside the grid, and monotone in `x` everywhere).
    #[inline]
    fn index(&self, a: usize, x: f64) -> usize {
        (((x - self.origin[a]) * self.inverse) as usize).min(self.dims[a] - 1)
    }

    /// The cell of point `p`.
    #[inline]
    fn cell_of(&self, p: [f64; 3]) -> [usize; 3] {
        [
            self.index(0, p[0]),
            self.index(1, p[1]),
            self.index(2, p[2]),
        ]
    }

    /// The cells of `p - d` and `p + d`, which bound the cells of every point within
    /// `d` of `p` (less rounding) along each axis.
    #[inline]
    fn cells_around(&self, p: [f64; 3], d: f64) -> ([usize; 3], [usize; 3]) {
        (
            self.cell_of([p[0] - d, p[1] - d, p[2] - d]),
            self.cell_of([p[0] + d, p[1] + d, p[2] + d]),
        )
    }

    /// The bucket of cell `c`.
    #[inline]
    fn bucket(&self, c: [usize; 3]) -> usize {
        let h = (c[0] as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
            ^ (c[1] as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f)
            ^ (c[2] as u64).wrapping_mul(0x1656_67b1_9e37_79f9);
        (h >> 32) as usize & self.mask
    }

    /// Adds point `index` (the next index: points are numbered in insertion order) at
    /// `p`.
    fn insert(&mut self, p: [f64; 3]) {
        let index = self.next.len() as u32;
        let bucket = self.bucket(self.cell_of(p));
        let head = &mut self.heads[bucket];
        if *head == NONE {
            self.touched.push(bucket as u32);
        }
        self.next.push(*head);
        *head = index;
    }

    /// Whether `test` holds for any point of the cells from `lo` to `hi` (inclusive,
    /// per axis) that `walk` accepts; stops at the first that does.
    #[inline]
    fn any_in(
        &self,
        lo: [usize; 3],
        hi: [usize; 3],
        walk: impl Fn([usize; 3]) -> bool,
        mut test: impl FnMut(u32) -> bool,
    ) -> bool {
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    if !walk([x, y, z]) {
                        continue;
                    }
                    let mut p = self.heads[self.bucket([x, y, z])];
                    while p != NONE {
                        if test(p) {
                            return true;
                        }
                        p = self.next[p as usize];
                    }
                }
            }
        }
        false
    }

    /// Hands every point of the cells at Chebyshev distance exactly `ring` from cell
    /// `c` to `visit`; returns whether rings `0..=ring` cover the whole grid.
    fn visit_ring(&self, c: [usize; 3], ring: usize, mut visit: impl FnMut(u32)) -> bool {
        let lo = c.map(|i| i.saturating_sub(ring));
        let hi = [0, 1, 2].map(|a| (c[a] + ring).min(self.dims[a] - 1));
        let on_ring = |cell: [usize; 3]| (0..3).any(|a| cell[a].abs_diff(c[a]) == ring);
        self.any_in(lo, hi, on_ring, |p| {
            visit(p);
            false
        });
        (0..3).all(|a| c[a] <= ring && c[a] + ring >= self.dims[a] - 1)
    }
}

/// Writes the distinct normals of `normals` into `reps`: each normal, in order, joins
/// the first representative already in `reps` within `tolerance_deg` of it
/// (`n . r >= cos(tolerance)`, computed in `f64`), or becomes a new representative.
///
/// A representative `r` that a normal `n` joins satisfies `|n - r|^2 = |n|^2 + |r|^2 -
/// 2 n . r <= 2 M - 2 cos`, `M` the largest squared norm of the normals, so only the
/// representatives in the cells within that distance of `n` are compared with it.
pub(super) fn cluster(
    normals: &[Vec3],
    tolerance_deg: f32,
    reps: &mut Vec<Vec3>,
    grid: &mut NormalGrid,
) {
    reps.clear();
    let cos = f64::from(tolerance_deg).to_radians().cos();
    // While there are few representatives, comparing with each is cheapest.
    let mut rest = normals;
    while let Some((&n, tail)) = rest.split_first() {
        if reps.len() == CLUSTER_LINEAR {
            break;
        }
        if !reps.iter().any(|&r| dot(n, r) >= cos) {
            reps.push(n);
        }
        rest = tail;
    }
    if rest.is_empty() {
        return;
    }
    // Then through the grid, which holds the representatives found so far.
    let (lo, hi, norm2) = bounds(normals);
    let reach = (2.0 * norm2 - 2.0 * cos + SLACK).max(0.0).sqrt() + SLACK;
    grid.shape(lo, hi, 2.0 * reach, normals.len());
    for &r in reps.iter() {
        grid.insert(coords(r));
    }
    for &n in rest {
        let p = coords(n);
        let (from, to) = grid.cells_around(p, reach);
        let own = grid.cell_of(p);
        // The normal's own cell first: where a representative it joins mostly is.
        let test = |r: u32| dot(n, reps[r as usize]) >= cos;
        let joins = grid.any_in(own, own, |_| true, test)
            || grid.any_in(
                from,
                to,
                |c| c[0] != own[0] || c[1] != own[1] || c[2] != own[2],
                test,
            );
        if !joins {
            grid.insert(p);
            reps.push(n);
        }
    }
}

/// Sum over `reps` of the angle (radians) from each to its nearest other (the largest
/// `f64` dot product, clamped to `[-1, 1]`), added in order; 0 with fewer than two.
///
/// The nearest other is searched in rings of cells around each representative: once
/// every representative within `g` of it has been compared, any other `b` has
/// `a . b < (|a|^2 + M - g^2) / 2`, `M` the largest squared norm, and the search stops
/// when the best dot product found reaches that bound.
pub(super) fn spread(reps: &[Vec3], grid: &mut NormalGrid) -> f64 {
    if reps.len() < 2 {
        return 0.0;
    }
    let nearest_of_all = |i: usize, a: Vec3| {
        reps.iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &b)| dot(a, b))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    if reps.len() <= SPREAD_BRUTE_FORCE {
        return reps
            .iter()
            .enumerate()
            .map(|(i, &a)| nearest_of_all(i, a).clamp(-1.0, 1.0).acos())
            .sum();
    }
    let (lo, hi, norm2) = bounds(reps);
    // About two representatives per cell of the unit sphere's 4 pi.
    let side = (8.0 * std::f64::consts::PI / reps.len() as f64).sqrt();
    grid.shape(lo, hi, side, reps.len());
    for &r in reps {
        grid.insert(coords(r));
    }
    let side = grid.side;
    reps.iter()
        .enumerate()
        .map(|(i, &a)| {
            let p = coords(a);
            let c = grid.cell_of(p);
            let mut best = f64::NEG_INFINITY;
            let mut ring = 0;
            let nearest = loop {
                let whole = grid.visit_ring(c, ring, |j| {
                    if j as usize != i {
                        best = best.max(dot(a, reps[j as usize]));
                    }
                });
                if whole {
                    break best;
                }
                let gap = ring as f64 * side - SLACK;
                if gap > 0.0 && best >= (dot(a, a) + norm2 - gap * gap) / 2.0 + SLACK {
                    break best;
                }
                if ring == SPREAD_MAX_RING {
                    break nearest_of_all(i, a);
                }
                ring += 1;
            };
            nearest.clamp(-1.0, 1.0).acos()
        })
        .sum()
}

/// `a . b` in `f64`.
#[inline]
fn dot(a: Vec3, b: Vec3) -> f64 {
    f64::from(a.x) * f64::from(b.x)
        + f64::from(a.y) * f64::from(b.y)
        + f64::from(a.z) * f64::from(b.z)
}
