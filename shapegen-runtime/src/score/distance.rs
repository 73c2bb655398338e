//! Exact Euclidean distance transforms on pixel and voxel grids, for shaping a target's
//! weights by the distance to it.
//!
//! The transform is the separable algorithm of Felzenszwalb and Huttenlocher
//! ("Distance Transforms of Sampled Functions", Theory of Computing 8, 2012): the lower
//! envelope of parabolas along each axis in turn, linear in the number of cells. It
//! works on grids of any dimension, which the volume targets need (image-processing
//! crates offer it for 2-D images only).

/// The squared Euclidean distance, in cells, from every cell of a row-major grid of size
/// `dims` (the last axis varies fastest) to the nearest cell for which `seed` is true;
/// `f64::INFINITY` everywhere when no cell is a seed.
///
/// ```
/// use shapegen_runtime::score::squared_distances;
///
/// // A 3 x 4 image (3 rows of 4) whose only seed is the top-left pixel.
/// let d = squared_distances(&[3, 4], |i| i == 0);
/// assert_eq!(d[0], 0.0);
/// assert_eq!(d[3], 9.0); // (0, 3)
/// assert_eq!(d[2 * 4 + 3], 13.0); // (2, 3): 2^2 + 3^2
/// assert!(squared_distances(&[2, 2], |_| false).iter().all(|d| d.is_infinite()));
/// ```
pub fn squared_distances(dims: &[usize], seed: impl Fn(usize) -> bool) -> Vec<f64> {
    let len: usize = dims.iter().product();
    let mut grid: Vec<f64> = (0..len)
        .map(|i| if seed(i) { 0.0 } else { f64::INFINITY })
        .collect();
    let longest = dims.iter().copied().max().unwrap_or(0);
    let mut line = Envelope::new(longest);
    let mut values = vec![0.0; longest];
    for (axis, &n) in dims.iter().enumerate() {
        if n == 0 {
            return grid;
        }
        let stride: usize = dims[axis + 1..].iter().product();
        let outer = len / (n * stride);
        for o in 0..outer {
            for inner in 0..stride {
                let start = o * n * stride + inner;
                for (k, v) in values[..n].iter_mut().enumerate() {
                    *v = grid[start + k * stride];
                }
                line.transform(&values[..n]);
                for (k, d) in line.out[..n].iter().enumerate() {
                    grid[start + k * stride] = *d;
                }
            }
        }
    }
    grid
}

/// Working memory of the one-dimensional transform: the parabolas of the lower
/// envelope, where each takes over, and the result.
struct Envelope {
    vertices: Vec<usize>,
    bounds: Vec<f64>,
    out: Vec<f64>,
}

impl Envelope {
    fn new(n: usize) -> Self {
        Envelope {
            vertices: vec![0; n],
            bounds: vec![0.0; n + 1],
            out: vec![0.0; n],
        }
    }

    /// `out[q] = min_p (f[p] + (q - p)^2)` over the finite `f[p]`; infinite when none is.
    fn transform(&mut self, f: &[f64]) {
        let n = f.len();
        let mut k = 0usize;
        let mut any = false;
        for q in 0..n {
            if !f[q].is_finite() {
                continue;
            }
            if !any {
                any = true;
                self.vertices[0] = q;
                self.bounds[0] = f64::NEG_INFINITY;
                self.bounds[1] = f64::INFINITY;
                continue;
            }
            let qf = q as f64;
            // The first bound is minus infinity, so this stops at the first parabola.
            let s = loop {
                let p = self.vertices[k];
                let pf = p as f64;
                let s = ((f[q] + qf * qf) - (f[p] + pf * pf)) / (2.0 * (qf - pf));
                if s <= self.bounds[k] {
                    k -= 1;
                } else {
                    break s;
                }
            };
            k += 1;
            self.vertices[k] = q;
            self.bounds[k] = s;
            self.bounds[k + 1] = f64::INFINITY;
        }
        if !any {
            self.out[..n].fill(f64::INFINITY);
            return;
        }
        let mut k = 0;
        for q in 0..n {
            let qf = q as f64;
            while self.bounds[k + 1] < qf {
                k += 1;
            }
            let p = self.vertices[k];
            let d = qf - p as f64;
            self.out[q] = d * d + f[p];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The squared distance to the nearest seed by trying every seed.
    fn brute_force(dims: &[usize], seeds: &[bool]) -> Vec<f64> {
        let coords = |mut i: usize| {
            let mut c = vec![0usize; dims.len()];
            for a in (0..dims.len()).rev() {
                c[a] = i % dims[a];
                i /= dims[a];
            }
            c
        };
        (0..seeds.len())
            .map(|i| {
                let ci = coords(i);
                (0..seeds.len())
                    .filter(|&j| seeds[j])
                    .map(|j| {
                        coords(j)
                            .iter()
                            .zip(&ci)
                            .map(|(&a, &b)| (a as f64 - b as f64).powi(2))
                            .sum::<f64>()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    proptest! {
        #[test]
        fn equals_the_brute_force_distance_in_one_to_three_dimensions(
            dims in prop::collection::vec(1usize..7, 1..=3),
            density in 0.0f64..0.5,
            bits in prop::collection::vec(0.0f64..1.0, 216),
        ) {
            let len: usize = dims.iter().product();
            let seeds: Vec<bool> = bits[..len].iter().map(|&b| b < density).collect();
            let fast = squared_distances(&dims, |i| seeds[i]);
            prop_assert_eq!(fast, brute_force(&dims, &seeds));
        }
    }

    #[test]
    fn a_line_measures_to_its_nearest_seed_on_either_side() {
        let d = squared_distances(&[8], |i| i == 1 || i == 6);
        assert_eq!(d, [1.0, 0.0, 1.0, 4.0, 4.0, 1.0, 0.0, 1.0]);
    }
}
