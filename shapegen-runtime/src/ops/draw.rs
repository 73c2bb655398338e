//! The original implementation's random draws (`RandomValues.cpp`), for the rules that
//! reproduce it: a uniform `f32` in `[0, 1)`, a float range, and an integer range that is
//! a float draw truncated, so that its upper bound is never drawn unless it is also the
//! lower one. The original draws from its own generator; these draw from the caller's
//! stream, so they reproduce its distributions, not its numbers.

use rand::{Rng, RngExt};

/// `getRandomValue01()`: uniform over `[0, 1)`.
#[inline]
pub(crate) fn value01(rng: &mut impl Rng) -> f32 {
    rng.random::<f32>()
}

/// `getRandomValue(float min, float max)`: `min + (max - min) U`, and `min` without a
/// draw when the range is a single value.
#[inline]
pub(crate) fn value(rng: &mut impl Rng, min: f32, max: f32) -> f32 {
    if max == min {
        min
    } else {
        min + (max - min) * value01(rng)
    }
}

/// `getRandomValue(int min, int max)`: the float draw over `[min, max)` truncated toward
/// zero, so `max` itself only when `min == max`.
#[inline]
pub(crate) fn int_value(rng: &mut impl Rng, min: i32, max: i32) -> i32 {
    if max == min {
        min
    } else {
        value(rng, min as f32, max as f32) as i32
    }
}

/// The original's pick among `n >= 1` candidates, `getRandomValue(0, n - 1)`: uniform
/// over the first `n - 1` when `n >= 2`, so the last one only when it is alone.
#[inline]
pub(crate) fn pick(rng: &mut impl Rng, n: usize) -> usize {
    debug_assert!(n > 0);
    int_value(rng, 0, n as i32 - 1) as usize
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;

    #[test]
    fn integer_draws_never_reach_their_upper_bound() {
        let mut r = ChaCha8Rng::seed_from_u64(3);
        let mut counts = [0u32; 4];
        for _ in 0..30_000 {
            counts[int_value(&mut r, 0, 3) as usize] += 1;
        }
        assert_eq!(counts[3], 0);
        for &c in &counts[..3] {
            assert!((9_500..10_500).contains(&c), "{counts:?}");
        }
        assert_eq!(int_value(&mut r, 4, 4), 4);
        assert_eq!(pick(&mut r, 1), 0);
        assert!((0..1000).all(|_| pick(&mut r, 2) == 0));
        assert!((0..1000).all(|_| pick(&mut r, 3) < 2));
    }
}
