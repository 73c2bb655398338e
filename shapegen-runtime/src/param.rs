//! Parameter values: how each supported type is packed into 32-bit gene words, how a
//! value is drawn from its [`Distribution`], and how a stored value is checked against it.

use glam::{Vec2, Vec3};
use rand::{Rng, RngExt};

use crate::graph::Distribution;

/// A type that a generator parameter may have, packed into whole 32-bit words.
///
/// Implemented for `f32`, [`Vec2`], [`Vec3`], `i32`, `u32` and `bool`: the types the
/// `generator!` macro accepts.
pub trait ParamValue: Copy {
    /// Number of words one value takes.
    const WORDS: usize;
    /// Reads a value from the first [`WORDS`](Self::WORDS) words of `words`.
    fn read(words: &[u32]) -> Self;
    /// Writes the value into the first [`WORDS`](Self::WORDS) words of `words`.
    fn write(self, words: &mut [u32]);
}

impl ParamValue for f32 {
    const WORDS: usize = 1;
    #[inline]
    fn read(words: &[u32]) -> Self {
        f32::from_bits(words[0])
    }
    #[inline]
    fn write(self, words: &mut [u32]) {
        words[0] = self.to_bits();
    }
}

/// Packs glam vectors of `$n` floats as their components' bits, in order.
macro_rules! float_vectors {
    ($($ty:ident: $n:literal),*) => {$(
        impl ParamValue for $ty {
            const WORDS: usize = $n;
            #[inline]
            fn read(words: &[u32]) -> Self {
                $ty::from_array(read_floats(words))
            }
            #[inline]
            fn write(self, words: &mut [u32]) {
                write_floats(self.to_array(), words);
            }
        }
    )*};
}

float_vectors!(Vec2: 2, Vec3: 3);

/// The `N` floats whose bits the first `N` words of `words` hold.
#[inline(always)]
fn read_floats<const N: usize>(words: &[u32]) -> [f32; N] {
    let words = &words[..N];
    std::array::from_fn(|i| f32::from_bits(words[i]))
}

/// Writes the bits of the `N` floats `values` into the first `N` words of `words`.
#[inline(always)]
fn write_floats<const N: usize>(values: [f32; N], words: &mut [u32]) {
    for (w, v) in words[..N].iter_mut().zip(values) {
        *w = v.to_bits();
    }
}

impl ParamValue for i32 {
    const WORDS: usize = 1;
    #[inline]
    fn read(words: &[u32]) -> Self {
        words[0] as i32
    }
    #[inline]
    fn write(self, words: &mut [u32]) {
        words[0] = self as u32;
    }
}

impl ParamValue for u32 {
    const WORDS: usize = 1;
    #[inline]
    fn read(words: &[u32]) -> Self {
        words[0]
    }
    #[inline]
    fn write(self, words: &mut [u32]) {
        words[0] = self;
    }
}

impl ParamValue for bool {
    const WORDS: usize = 1;
    #[inline]
    fn read(words: &[u32]) -> Self {
        words[0] != 0
    }
    #[inline]
    fn write(self, words: &mut [u32]) {
        words[0] = u32::from(self);
    }
}

/// Draws a value from `dist` and writes it into the first `dist.words()` words of `out`.
#[inline(always)]
pub fn sample(dist: &Distribution, rng: &mut impl Rng, out: &mut [u32]) {
    match *dist {
        Distribution::Uniform { lo, hi } | Distribution::Angle { lo, hi, .. } => {
            uniform_f32(rng, lo, hi).write(out)
        }
        Distribution::UniformVec2 { lo, hi } => Vec2::new(
            uniform_f32(rng, lo[0], hi[0]),
            uniform_f32(rng, lo[1], hi[1]),
        )
        .write(out),
        Distribution::UniformVec3 { lo, hi } => Vec3::new(
            uniform_f32(rng, lo[0], hi[0]),
            uniform_f32(rng, lo[1], hi[1]),
            uniform_f32(rng, lo[2], hi[2]),
        )
        .write(out),
        Distribution::Int { lo, hi } => rng.random_range(lo..=hi).write(out),
        Distribution::Index { lo, hi } => rng.random_range(lo..=hi).write(out),
        Distribution::Weighted { weights } => weighted_index(rng, weights).write(out),
        Distribution::Bernoulli { p } => (rng.random::<f32>() < p).write(out),
    }
}

/// Uniform `f32` over the closed interval `[lo, hi]`; `lo == hi` gives `lo`.
///
/// Exactly the value `rng.random_range(lo..=hi)` gives (rand's `UniformFloat`: the top 23
/// bits of one `u32` as a float in `[1, 2)`, less one, times `hi - lo`, plus `lo`), from
/// the same single draw, without the checks and the `Result` that a general range
/// needs: bounds come from a checked distribution. A test holds the two equal.
#[inline]
fn uniform_f32(rng: &mut impl Rng, lo: f32, hi: f32) -> f32 {
    let scale = hi - lo;
    if lo < hi && scale.is_finite() {
        uniform_in(rng, lo, scale)
    } else if lo < hi {
        rng.random_range(lo..=hi) // a span past f32's range, refused there
    } else {
        lo
    }
}

/// A uniform `f32` in `[lo, lo + scale]` for a finite `scale > 0`, from one `u32` of
/// `rng`, as rand's `UniformFloat` makes it (see [`uniform_f32`]).
#[inline]
pub(crate) fn uniform_in(rng: &mut impl Rng, lo: f32, scale: f32) -> f32 {
    let value1_2 = f32::from_bits((rng.next_u32() >> 9) | 0x3f80_0000);
    (value1_2 - 1.0) * scale + lo
}

/// Index `i` with probability `weights[i] / sum(weights)`.
fn weighted_index(rng: &mut impl Rng, weights: &[f32]) -> u32 {
    let total: f32 = weights.iter().sum();
    let mut x = rng.random::<f32>() * total;
    for (i, &w) in weights.iter().enumerate() {
        if x < w {
            return i as u32;
        }
        x -= w;
    }
    // Rounding can leave `x` just past the last positive weight.
    weights.iter().rposition(|&w| w > 0.0).unwrap_or(0) as u32
}

/// Why a stored parameter value does not fit its distribution.
pub fn check(dist: &Distribution, words: &[u32]) -> Result<(), String> {
    let in_range = |v: f32, lo: f32, hi: f32| v.is_finite() && v >= lo && v <= hi;
    match *dist {
        Distribution::Uniform { lo, hi } | Distribution::Angle { lo, hi, .. } => {
            let v = f32::read(words);
            if !in_range(v, lo, hi) {
                return Err(format!("{v} is outside [{lo}, {hi}]"));
            }
        }
        Distribution::UniformVec2 { lo, hi } => {
            let v = Vec2::read(words).to_array();
            if (0..2).any(|i| !in_range(v[i], lo[i], hi[i])) {
                return Err(format!("{v:?} is outside [{lo:?}, {hi:?}]"));
            }
        }
        Distribution::UniformVec3 { lo, hi } => {
            let v = Vec3::read(words).to_array();
            if (0..3).any(|i| !in_range(v[i], lo[i], hi[i])) {
                return Err(format!("{v:?} is outside [{lo:?}, {hi:?}]"));
            }
        }
        Distribution::Int { lo, hi } => {
            let v = i32::read(words);
            if !(lo..=hi).contains(&v) {
                return Err(format!("{v} is outside {lo}..={hi}"));
            }
        }
        Distribution::Index { lo, hi } => {
            let v = u32::read(words);
            if !(lo..=hi).contains(&v) {
                return Err(format!("{v} is outside {lo}..={hi}"));
            }
        }
        Distribution::Weighted { weights } => {
            let v = u32::read(words);
            if weights.get(v as usize).is_none_or(|&w| w <= 0.0) {
                return Err(format!(
                    "{v} is not a choice with positive weight among {} choices",
                    weights.len()
                ));
            }
        }
        Distribution::Bernoulli { .. } => {
            if words[0] > 1 {
                return Err(format!("{} is not a boolean (0 or 1)", words[0]));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn uniform_draws_are_rands_from_the_same_stream() {
        let bounds = [
            (0.0, 1.0),
            (-0.5, 0.5),
            (0.6, 1.5),
            (35f32.to_radians(), 85f32.to_radians()),
            (-1e30, 1e30),
            (1.0, 1.0 + f32::EPSILON),
        ];
        let (mut ours, mut rands) = (ChaCha8Rng::seed_from_u64(9), ChaCha8Rng::seed_from_u64(9));
        for _ in 0..20_000 {
            for &(lo, hi) in &bounds {
                let want: f32 = rands.random_range(lo..=hi);
                assert_eq!(uniform_f32(&mut ours, lo, hi).to_bits(), want.to_bits());
            }
        }
        assert_eq!(uniform_f32(&mut ours, 2.0, 2.0), 2.0);
        assert_eq!(
            ours.next_u32(),
            rands.next_u32(),
            "an empty span draws nothing"
        );
    }

    #[test]
    fn values_round_trip_through_words() {
        let mut w = [0u32; 3];
        Vec3::new(1.0, -2.5, 3.25).write(&mut w);
        assert_eq!(Vec3::read(&w), Vec3::new(1.0, -2.5, 3.25));
        (-7i32).write(&mut w);
        assert_eq!(i32::read(&w), -7);
        true.write(&mut w);
        assert!(bool::read(&w));
    }

    #[test]
    fn samples_pass_their_own_check() {
        static W: [f32; 3] = [0.0, 2.0, 1.0];
        let dists = [
            Distribution::Uniform { lo: -1.0, hi: 1.0 },
            Distribution::Uniform { lo: 0.8, hi: 0.8 },
            Distribution::UniformVec3 {
                lo: [0.3, 0.1, 0.3],
                hi: [0.8, 0.2, 0.8],
            },
            Distribution::Int { lo: -3, hi: 3 },
            Distribution::Weighted { weights: &W },
            Distribution::Bernoulli { p: 0.5 },
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut w = [0u32; 3];
        for d in &dists {
            for _ in 0..1000 {
                sample(d, &mut rng, &mut w);
                check(d, &w).unwrap();
            }
        }
    }

    #[test]
    fn weighted_index_follows_weights_and_never_picks_zero_weight() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut counts = [0u32; 3];
        for _ in 0..30_000 {
            counts[weighted_index(&mut rng, &[0.0, 2.0, 1.0]) as usize] += 1;
        }
        assert_eq!(counts[0], 0);
        let ratio = f64::from(counts[1]) / f64::from(counts[2]);
        assert!((ratio - 2.0).abs() < 0.15, "ratio {ratio}");
    }

    #[test]
    fn check_rejects_out_of_range_and_non_finite() {
        let d = Distribution::Uniform { lo: 0.0, hi: 1.0 };
        assert!(check(&d, &[2.0f32.to_bits()]).is_err());
        assert!(check(&d, &[f32::NAN.to_bits()]).is_err());
        assert!(check(&Distribution::Bernoulli { p: 0.5 }, &[2]).is_err());
    }
}
