//! Exact integer weights: probabilities as 32-bit fixed point, unbiased draws below a
//! bound, and a Fenwick tree for drawing among a growing set of weighted items.

use rand::Rng;

/// Fixed-point 1.0: probabilities are weights in `0..=ONE`.
pub(crate) const ONE: u64 = 1 << 32;

/// The fixed-point weight of probability `p`, rounded to the nearest `2^-32`; values
/// outside `[0, 1]` (and NaN) are clamped.
#[inline]
pub(crate) fn weight(p: f32) -> u64 {
    let p = if p.is_nan() { 0.0 } else { p.clamp(0.0, 1.0) };
    (f64::from(p) * ONE as f64).round() as u64
}

/// A uniform integer in `0..n`, without bias (Lemire's multiply-and-reject). `n > 0`.
#[inline]
pub(crate) fn below(rng: &mut impl Rng, n: u64) -> u64 {
    debug_assert!(n > 0);
    let mut m = u128::from(rng.next_u64()) * u128::from(n);
    if (m as u64) < n {
        let threshold = n.wrapping_neg() % n;
        while (m as u64) < threshold {
            m = u128::from(rng.next_u64()) * u128::from(n);
        }
    }
    (m >> 64) as u64
}

/// `true` with probability `w / ONE`, for a fixed-point weight `w`; draws nothing when
/// the outcome is certain.
#[inline]
pub(crate) fn chance(rng: &mut impl Rng, w: u64) -> bool {
    if w == 0 {
        false
    } else if w >= ONE {
        true
    } else {
        u64::from(rng.next_u32()) < w
    }
}

/// A Fenwick (binary indexed) tree over non-negative `u64` weights that grows by
/// appending: O(log n) append, update and draw.
#[derive(Debug, Default)]
pub(crate) struct Fenwick {
    /// `tree[i - 1]` holds the sum of the weights `(i - lowbit(i), i]` (1-based).
    tree: Vec<u64>,
    total: u64,
}

impl Fenwick {
    /// Empties the tree, keeping its allocation.
    pub(crate) fn clear(&mut self) {
        self.tree.clear();
        self.total = 0;
    }

    /// Sum of all weights.
    #[inline]
    pub(crate) fn total(&self) -> u64 {
        self.total
    }

    /// Appends an item of weight `w`; its index is the number of items before it.
    pub(crate) fn push(&mut self, w: u64) {
        let i = self.tree.len() + 1; // 1-based index of the new node
        let low = i & i.wrapping_neg();
        let mut sum = w;
        let mut j = i - 1;
        while j > i - low {
            sum += self.tree[j - 1];
            j &= j - 1;
        }
        self.tree.push(sum);
        self.total += w;
    }

    /// Subtracts `w` from the weight of item `index`.
    pub(crate) fn sub(&mut self, index: usize, w: u64) {
        let mut i = index + 1;
        while i <= self.tree.len() {
            self.tree[i - 1] -= w;
            i += i & i.wrapping_neg();
        }
        self.total -= w;
    }

    /// The first item whose cumulative weight exceeds `r`, for `r < total()`: item `i`
    /// is found for `r` in `[sum of weights before i, that + weight of i)`.
    pub(crate) fn find(&self, mut r: u64) -> usize {
        debug_assert!(r < self.total);
        let n = self.tree.len();
        let mut pos = 0usize;
        let mut step = if n == 0 {
            0
        } else {
            1 << (usize::BITS - 1 - n.leading_zeros())
        };
        while step > 0 {
            let next = pos + step;
            if next <= n && self.tree[next - 1] <= r {
                pos = next;
                r -= self.tree[next - 1];
            }
            step >>= 1;
        }
        pos
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn weights_are_exact_at_the_ends() {
        assert_eq!(weight(0.0), 0);
        assert_eq!(weight(1.0), ONE);
        assert_eq!(weight(0.5), ONE / 2);
        assert_eq!(weight(2.0), ONE);
        assert_eq!(weight(f32::NAN), 0);
    }

    #[test]
    fn below_stays_in_range_and_is_even() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut counts = [0u32; 3];
        for _ in 0..30_000 {
            counts[below(&mut rng, 3) as usize] += 1;
        }
        for c in counts {
            assert!((9_500..10_500).contains(&c), "{counts:?}");
        }
        assert_eq!(below(&mut rng, 1), 0);
    }

    #[test]
    fn fenwick_finds_like_a_linear_scan() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let mut f = Fenwick::default();
        let mut plain: Vec<u64> = Vec::new();
        for round in 0..400 {
            let w = below(&mut rng, 5) * 1000;
            f.push(w);
            plain.push(w);
            if round % 3 == 0 {
                let i = below(&mut rng, plain.len() as u64) as usize;
                let d = plain[i] / 2;
                f.sub(i, d);
                plain[i] -= d;
            }
            let total: u64 = plain.iter().sum();
            assert_eq!(f.total(), total);
            if total == 0 {
                continue;
            }
            for _ in 0..5 {
                let r = below(&mut rng, total);
                let mut acc = 0;
                let expect = plain
                    .iter()
                    .position(|&w| {
                        acc += w;
                        acc > r
                    })
                    .unwrap();
                assert_eq!(f.find(r), expect);
            }
        }
    }
}
