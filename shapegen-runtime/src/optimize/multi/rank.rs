//! Ranking a population on several objectives: dominance, non-dominated fronts,
//! crowding distance, summed rank, weighted sum, the diversity penalty, and the scalar
//! selection fitness built from them.
//!
//! Objective values are a row-major matrix `values` of `n` rows of `k` raw values (one
//! row per individual) with one [`Sense`] per column. NaN is worse than every number in
//! every objective, and NaNs equal each other; `+inf` and `-inf` are ordinary extremes.
//! Every function here panics if `k` is 0 or `values` does not hold whole rows; none
//! allocates once its buffers have grown to the population's size.

use std::cmp::Ordering;

use super::settings::{Ranking, Selection};
use crate::evaluate::Sense;
use crate::optimize::fitness::compare;

/// Orders two raw values of an objective, better first (`Less` means `a` is better).
fn better_first(sense: Sense, a: f64, b: f64) -> Ordering {
    compare(sense.oriented(b), sense.oriented(a))
}

/// Number of rows of a `k`-column matrix.
fn rows(values: &[f64], k: usize) -> usize {
    assert!(k > 0, "at least one objective");
    assert_eq!(values.len() % k, 0, "values must hold whole rows of {k}");
    values.len() / k
}

/// Whether objective vector `a` dominates `b`: no worse in any objective and better in
/// at least one.
///
/// ```
/// use shapegen_runtime::optimize::{Sense, multi::dominates};
///
/// let senses = [Sense::Maximize, Sense::Minimize];
/// assert!(dominates(&[2.0, 1.0], &[1.0, 1.0], &senses));
/// assert!(!dominates(&[2.0, 2.0], &[1.0, 1.0], &senses));
/// assert!(dominates(&[0.0, 0.0], &[f64::NAN, 0.0], &senses));
/// ```
pub fn dominates(a: &[f64], b: &[f64], senses: &[Sense]) -> bool {
    let mut strictly = false;
    for ((&x, &y), &s) in a.iter().zip(b).zip(senses) {
        match better_first(s, x, y) {
            Ordering::Greater => return false,
            Ordering::Less => strictly = true,
            Ordering::Equal => {}
        }
    }
    strictly
}

/// Which of `a` and `b` dominates the other, in one pass: `Less` if `a` dominates,
/// `Greater` if `b` does, `Equal` if neither.
fn dominance(a: &[f64], b: &[f64], senses: &[Sense]) -> Ordering {
    let (mut a_better, mut b_better) = (false, false);
    for ((&x, &y), &s) in a.iter().zip(b).zip(senses) {
        match better_first(s, x, y) {
            Ordering::Less => a_better = true,
            Ordering::Greater => b_better = true,
            Ordering::Equal => {}
        }
        if a_better && b_better {
            return Ordering::Equal;
        }
    }
    match (a_better, b_better) {
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        _ => Ordering::Equal,
    }
}

/// The non-dominated fronts of a population, with reusable buffers.
///
/// Front 1 holds the individuals no one dominates; front `r + 1` those dominated only by
/// members of fronts 1 to `r`. Fast non-dominated sorting, `O(k n^2)` time and `O(n)`
/// memory: dominance counts first, then each front releases the individuals it
/// dominates.
///
/// ```
/// use shapegen_runtime::optimize::{Sense, multi::Fronts};
///
/// // Two objectives to maximize.
/// let values = [1.0, 3.0, /**/ 2.0, 2.0, /**/ 1.0, 1.0, /**/ 3.0, 0.0];
/// let mut fronts = Fronts::default();
/// fronts.sort(&values, 2, &[Sense::Maximize; 2]);
/// assert_eq!(fronts.ranks(), [1, 1, 2, 1]);
/// assert_eq!(fronts.front(0), [0, 1, 3]);
/// assert_eq!(fronts.front(1), [2]);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Fronts {
    rank: Vec<u32>,
    count: Vec<u32>,
    order: Vec<u32>,
    starts: Vec<u32>,
}

impl Fronts {
    /// Sorts the `n` rows of `values` (`k` per row) into fronts.
    pub fn sort(&mut self, values: &[f64], k: usize, senses: &[Sense]) {
        let n = rows(values, k);
        let row = |i: usize| &values[i * k..(i + 1) * k];
        self.rank.clear();
        self.rank.resize(n, 0);
        self.count.clear();
        self.count.resize(n, 0);
        for p in 0..n {
            for q in p + 1..n {
                match dominance(row(p), row(q), senses) {
                    Ordering::Less => self.count[q] += 1,
                    Ordering::Greater => self.count[p] += 1,
                    Ordering::Equal => {}
                }
            }
        }
        self.order.clear();
        self.starts.clear();
        self.order
            .extend((0..n as u32).filter(|&i| self.count[i as usize] == 0));
        let mut start = 0;
        let mut rank = 1;
        while start < self.order.len() {
            let end = self.order.len();
            self.starts.push(start as u32);
            for f in start..end {
                let p = self.order[f] as usize;
                self.rank[p] = rank;
                for q in 0..n {
                    if self.count[q] > 0 && dominates(row(p), row(q), senses) {
                        self.count[q] -= 1;
                        if self.count[q] == 0 {
                            self.order.push(q as u32);
                        }
                    }
                }
            }
            self.order[end..].sort_unstable();
            start = end;
            rank += 1;
        }
    }

    /// Front rank of each individual, 1 for the non-dominated.
    pub fn ranks(&self) -> &[u32] {
        &self.rank
    }

    /// Number of fronts.
    pub fn len(&self) -> usize {
        self.starts.len()
    }

    /// Whether there are no fronts (an empty population).
    pub fn is_empty(&self) -> bool {
        self.starts.is_empty()
    }

    /// The individuals of front `i` (0 for rank 1), in increasing index order.
    pub fn front(&self, i: usize) -> &[u32] {
        let start = self.starts[i] as usize;
        let end = self
            .starts
            .get(i + 1)
            .map_or(self.order.len(), |&e| e as usize);
        &self.order[start..end]
    }
}

/// NSGA-II crowding distance of the members of `front` (indices into the rows of
/// `values`), written to `out[j]` for `front[j]`.
///
/// Per objective, the front is sorted (better first, ties by index); its first and last
/// members get an infinite distance, and every other member adds the gap between its two
/// neighbours' values divided by the objective's range in the front. An objective whose
/// range is zero, infinite or NaN adds nothing to interior members, nor does a gap that
/// is not finite. Fronts of one or two members are all infinite.
///
/// ```
/// use shapegen_runtime::optimize::{Sense, multi::crowding};
///
/// let values = [0.0, 4.0, /**/ 1.0, 2.0, /**/ 4.0, 0.0];
/// let mut out = [0.0; 3];
/// crowding(&values, 2, &[Sense::Maximize; 2], &[0, 1, 2], &mut Vec::new(), &mut out);
/// // Interior point: (4 - 0) / 4 + (4 - 0) / 4.
/// assert_eq!(out, [f64::INFINITY, 2.0, f64::INFINITY]);
/// ```
pub fn crowding(
    values: &[f64],
    k: usize,
    senses: &[Sense],
    front: &[u32],
    order: &mut Vec<u32>,
    out: &mut [f64],
) {
    rows(values, k);
    assert_eq!(out.len(), front.len(), "one distance per member");
    out.fill(0.0);
    let m = front.len();
    if m == 0 {
        return;
    }
    for (j, &sense) in senses.iter().enumerate().take(k) {
        let v = |slot: u32| values[front[slot as usize] as usize * k + j];
        order.clear();
        order.extend(0..m as u32);
        order.sort_unstable_by(|&a, &b| better_first(sense, v(a), v(b)).then(a.cmp(&b)));
        out[order[0] as usize] = f64::INFINITY;
        out[order[m - 1] as usize] = f64::INFINITY;
        let range = (v(order[0]) - v(order[m - 1])).abs();
        if !(range.is_finite() && range > 0.0) {
            continue;
        }
        for w in order.windows(3) {
            let gap = (v(w[0]) - v(w[2])).abs() / range;
            if gap.is_finite() {
                out[w[1] as usize] += gap;
            }
        }
    }
}

/// Summed rank: per objective, each individual's rank (1 for the best; equal values
/// share the best rank of their group, "competition ranking", so `[5, 7, 7, 9]`
/// maximized ranks `[4, 2, 2, 1]`), summed over the objectives into `out`. With
/// `normalized`, each objective's ranks are first divided by that objective's largest
/// rank, so that objectives with many ties weigh as much as the others. Lower is better.
///
/// ```
/// use shapegen_runtime::optimize::{Sense, multi::summed_rank};
///
/// let values = [5.0, 7.0, 7.0, 9.0];
/// let mut out = [0.0; 4];
/// summed_rank(&values, 1, &[Sense::Maximize], false, &mut Vec::new(), &mut out);
/// assert_eq!(out, [4.0, 2.0, 2.0, 1.0]);
/// summed_rank(&values, 1, &[Sense::Maximize], true, &mut Vec::new(), &mut out);
/// assert_eq!(out, [1.0, 0.5, 0.5, 0.25]);
/// ```
pub fn summed_rank(
    values: &[f64],
    k: usize,
    senses: &[Sense],
    normalized: bool,
    order: &mut Vec<u32>,
    out: &mut [f64],
) {
    let n = rows(values, k);
    assert_eq!(out.len(), n, "one rank per individual");
    out.fill(0.0);
    if n == 0 {
        return;
    }
    for (j, &sense) in senses.iter().enumerate().take(k) {
        let v = |i: u32| values[i as usize * k + j];
        order.clear();
        order.extend(0..n as u32);
        order.sort_unstable_by(|&a, &b| better_first(sense, v(a), v(b)).then(a.cmp(&b)));
        let differs = |pos: usize| better_first(sense, v(order[pos - 1]), v(order[pos])).is_ne();
        let worst = (1..n)
            .rev()
            .find(|&pos| differs(pos))
            .map_or(1, |pos| pos + 1);
        let scale = if normalized { 1.0 / worst as f64 } else { 1.0 };
        let mut rank = 1;
        for pos in 0..n {
            if pos > 0 && differs(pos) {
                rank = pos + 1;
            }
            out[order[pos] as usize] += rank as f64 * scale;
        }
    }
}

/// Weighted sum of the oriented values (`Sense::oriented`, so higher is better):
/// `out[i] = sum_j weights[j] * oriented(values[i][j])`. Objectives of weight 0 are left
/// out entirely; a NaN value (or `+inf` plus `-inf`) among the others makes the sum NaN.
///
/// ```
/// use shapegen_runtime::optimize::{Sense, multi::weighted_sum};
///
/// let mut out = [0.0];
/// weighted_sum(&[2.0, 3.0], 2, &[Sense::Maximize, Sense::Minimize], &[1.0, 0.5], &mut out);
/// assert_eq!(out, [0.5]);
/// ```
pub fn weighted_sum(values: &[f64], k: usize, senses: &[Sense], weights: &[f64], out: &mut [f64]) {
    let n = rows(values, k);
    assert_eq!(out.len(), n, "one sum per individual");
    assert_eq!(weights.len(), k, "one weight per objective");
    for (o, row) in out.iter_mut().zip(values.chunks_exact(k)) {
        *o = row
            .iter()
            .zip(senses)
            .zip(weights)
            .filter(|&(_, &w)| w != 0.0)
            .map(|((&v, &s), &w)| w * s.oriented(v))
            .sum();
    }
}

/// Orders two rows lexicographically, NaNs equal each other and above nothing.
fn row_order(a: &[f64], b: &[f64]) -> Ordering {
    a.iter()
        .zip(b)
        .map(|(&x, &y)| compare(x, y))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}

/// Marks, in `first[i]`, whether row `i` of `values` is the first (lowest index) of its
/// group of equal rows (equal value for value, NaN equal to NaN, `-0.0` to `0.0`).
pub(crate) fn first_of_equals(values: &[f64], k: usize, order: &mut Vec<u32>, first: &mut [bool]) {
    let n = rows(values, k);
    let row = |i: u32| &values[i as usize * k..(i as usize + 1) * k];
    order.clear();
    order.extend(0..n as u32);
    order.sort_unstable_by(|&a, &b| row_order(row(a), row(b)).then(a.cmp(&b)));
    for (pos, &i) in order.iter().enumerate() {
        first[i as usize] = pos == 0 || row_order(row(order[pos - 1]), row(i)).is_ne();
    }
}

/// The diversity penalty: every individual whose objective vector equals (exactly, as
/// numbers, NaN equal to NaN) that of an individual of lower index loses `penalty` from
/// its selection fitness `fitness[i]`; the first of each group keeps its value, so
/// clones lose selection.
///
/// ```
/// use shapegen_runtime::optimize::multi::penalize_clones;
///
/// let values = [1.0, 2.0, /**/ 3.0, 4.0, /**/ 1.0, 2.0];
/// let mut fitness = [10.0, 9.0, 10.0];
/// penalize_clones(&values, 2, 20.0, &mut Vec::new(), &mut Vec::new(), &mut fitness);
/// assert_eq!(fitness, [10.0, 9.0, -10.0]);
/// ```
pub fn penalize_clones(
    values: &[f64],
    k: usize,
    penalty: f64,
    order: &mut Vec<u32>,
    first: &mut Vec<bool>,
    fitness: &mut [f64],
) {
    let n = rows(values, k);
    assert_eq!(fitness.len(), n, "one fitness per individual");
    first.clear();
    first.resize(n, true);
    first_of_equals(values, k, order, first);
    for (f, &keep) in fitness.iter_mut().zip(first.iter()) {
        if !keep {
            *f -= penalty;
        }
    }
}

/// Reusable buffers of [`selection_fitness`].
#[derive(Clone, Debug, Default)]
pub struct RankScratch {
    fronts: Fronts,
    order: Vec<u32>,
    crowd: Vec<f64>,
    first: Vec<bool>,
}

/// The Pareto selection fitness of an individual of front `rank` with crowding distance
/// `d`: `-rank + c`, where `c = d / (2 (1 + d))` for a finite `d` and `c = 1/2` for an
/// infinite one. Since `c` lies in `[0, 1/2]`, every member of a front ranks above every
/// member of the next; within a front a larger distance ranks higher (finite distances
/// from [`crowding`] are at most `k`, so they stay strictly below the infinite ones).
pub fn pareto_fitness(rank: u32, d: f64) -> f64 {
    let c = if d.is_finite() {
        d / (2.0 * (1.0 + d))
    } else {
        0.5
    };
    c - f64::from(rank)
}

/// One higher-is-better selection fitness per individual, relative to this population,
/// written to `out`:
/// - [`Ranking::WeightedSum`]: the [`weighted_sum`];
/// - [`Ranking::Pareto`]: [`pareto_fitness`] of the individual's front rank
///   ([`Fronts`]) and its [`crowding`] distance within its front;
/// - [`Ranking::SummedRank`] and [`Ranking::NormalizedSummedRank`]: minus the
///   [`summed_rank`];
///
/// then the [diversity penalty](penalize_clones) of
/// [`Selection::diversity_penalty`] (none when it is 0).
///
/// Panics if the weights of a weighted sum are not one per objective (checked by
/// [`MultiGa`](super::MultiGa) before it starts).
///
/// ```
/// use shapegen_runtime::optimize::Sense;
/// use shapegen_runtime::optimize::multi::{RankScratch, Ranking, Selection, selection_fitness};
///
/// let values = [1.0, 3.0, /**/ 2.0, 2.0, /**/ 1.0, 1.0, /**/ 1.0, 3.0];
/// let selection = Selection { ranking: Ranking::Pareto, diversity_penalty: 20.0 };
/// let mut out = [0.0; 4];
/// selection_fitness(&selection, &values, 2, &[Sense::Maximize; 2], &mut out, &mut RankScratch::default());
/// // Front 1 is {0, 1, 3}, all at the ends of the front; 3 is a clone of 0.
/// assert_eq!(out, [-0.5, -0.5, -1.5, -20.5]);
/// ```
pub fn selection_fitness(
    selection: &Selection,
    values: &[f64],
    k: usize,
    senses: &[Sense],
    out: &mut [f64],
    scratch: &mut RankScratch,
) {
    let n = rows(values, k);
    assert_eq!(out.len(), n, "one fitness per individual");
    assert_eq!(senses.len(), k, "one sense per objective");
    match &selection.ranking {
        Ranking::WeightedSum { weights } => weighted_sum(values, k, senses, weights, out),
        Ranking::Pareto => {
            let s = &mut *scratch;
            s.fronts.sort(values, k, senses);
            for f in 0..s.fronts.len() {
                let front = s.fronts.front(f);
                s.crowd.clear();
                s.crowd.resize(front.len(), 0.0);
                crowding(values, k, senses, front, &mut s.order, &mut s.crowd);
                for (&i, &d) in front.iter().zip(&s.crowd) {
                    out[i as usize] = pareto_fitness(f as u32 + 1, d);
                }
            }
        }
        Ranking::SummedRank | Ranking::NormalizedSummedRank => {
            let normalized = matches!(selection.ranking, Ranking::NormalizedSummedRank);
            summed_rank(values, k, senses, normalized, &mut scratch.order, out);
            out.iter_mut().for_each(|o| *o = -*o);
        }
    }
    if selection.diversity_penalty != 0.0 {
        penalize_clones(
            values,
            k,
            selection.diversity_penalty,
            &mut scratch.order,
            &mut scratch.first,
            out,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Populations of `n` rows of `k` small integers (many ties), some NaN.
    fn population(rng: &mut ChaCha8Rng, n: usize, k: usize) -> Vec<f64> {
        (0..n * k)
            .map(|_| match rng.random_range(0..12) {
                0 => f64::NAN,
                v => f64::from(v % 5),
            })
            .collect()
    }

    fn senses(k: usize) -> Vec<Sense> {
        (0..k)
            .map(|j| [Sense::Maximize, Sense::Minimize][j % 2])
            .collect()
    }

    #[test]
    fn fronts_match_peeling_the_non_dominated() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut fronts = Fronts::default();
        for (n, k) in [(1, 1), (7, 1), (30, 2), (40, 3), (25, 4)] {
            let values = population(&mut rng, n, k);
            let s = senses(k);
            fronts.sort(&values, k, &s);
            let row = |i: usize| &values[i * k..(i + 1) * k];
            let mut left: Vec<usize> = (0..n).collect();
            let mut rank = 1;
            while !left.is_empty() {
                let (front, rest): (Vec<usize>, Vec<usize>) = left
                    .iter()
                    .partition(|&&i| !left.iter().any(|&j| dominates(row(j), row(i), &s)));
                let expect: Vec<u32> = front.iter().map(|&i| i as u32).collect();
                assert_eq!(fronts.front(rank - 1), expect, "n {n} k {k}");
                assert!(front.iter().all(|&i| fronts.ranks()[i] == rank as u32));
                left = rest;
                rank += 1;
            }
            assert_eq!(fronts.len(), rank - 1);
        }
    }

    #[test]
    fn summed_rank_counts_the_strictly_better() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let (mut order, mut out) = (Vec::new(), Vec::new());
        for (n, k) in [(1, 1), (9, 2), (33, 3)] {
            let values = population(&mut rng, n, k);
            let s = senses(k);
            // Competition rank: one plus the number of strictly better individuals.
            let r = |i: usize, j: usize| {
                1 + (0..n)
                    .filter(|&q| s[j].better(values[q * k + j], values[i * k + j]))
                    .count()
            };
            for normalized in [false, true] {
                out.clear();
                out.resize(n, 0.0);
                summed_rank(&values, k, &s, normalized, &mut order, &mut out);
                for (i, &o) in out.iter().enumerate() {
                    let expect: f64 = (0..k)
                        .map(|j| {
                            let worst = (0..n).map(|q| r(q, j)).max().unwrap();
                            let scale = if normalized { 1.0 / worst as f64 } else { 1.0 };
                            r(i, j) as f64 * scale
                        })
                        .sum();
                    assert!((o - expect).abs() < 1e-12, "{o} vs {expect}");
                }
            }
        }
    }

    #[test]
    fn first_of_equals_marks_the_lowest_index_of_each_group() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let values = population(&mut rng, 50, 2);
        let mut first = vec![false; 50];
        first_of_equals(&values, 2, &mut Vec::new(), &mut first);
        let same = |a: usize, b: usize| {
            (0..2).all(|j| compare(values[a * 2 + j], values[b * 2 + j]).is_eq())
        };
        for (i, &f) in first.iter().enumerate() {
            assert_eq!(f, !(0..i).any(|e| same(e, i)), "row {i}");
        }
    }
}
