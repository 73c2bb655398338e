//! Standard measures of how close a model is to its target, whatever the fitness: the
//! intersection over union of voxels and of silhouette pixels, and the Chamfer distance
//! and F-score between surfaces. Searches do not use them; runs report them, so that a
//! result can be compared with other systems' in the measures the literature uses.
//!
//! ```
//! use glam::Vec3;
//! use shapegen_runtime::score::metrics::{Sampling, SurfaceDistance, Triangle};
//!
//! // Two unit squares, one 0.01 above the other: every sample has one of the other
//! // square's samples within 0.1, so the F-score at 0.1 is 1.
//! let square = |z: f32| -> Vec<Triangle> {
//!     let p = |x: f32, y: f32| Vec3::new(x, y, z);
//!     vec![[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)], [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]]
//! };
//! let sampling = Sampling { threshold: 0.1, samples: 500, seed: 7 };
//! let d = SurfaceDistance::between(&square(0.0), &square(0.01), sampling).unwrap();
//! assert_eq!(d.f_score, 1.0);
//! assert!(d.chamfer >= 0.01 && d.chamfer < 0.05);
//! ```

use glam::{DVec3, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::form::{f_score, share};
use super::silhouette::{ImageTarget, TargetCounts};
use super::volume::{VolumeCounts, VolumeScorer};
use crate::geometry::{BoundMeshes, Instance, Mesh};

/// One triangle's corners, in world space.
pub type Triangle = [Vec3; 3];

/// The intersection over union of a model's silhouette with a target's pixels:
/// `on / (T + off)`, where `on` are the covered target pixels, `off` the covered other
/// pixels and `T` the target pixels ([`ImageTarget::target_pixels`]); 0 when both are
/// empty.
pub fn silhouette_iou(target: &ImageTarget, counts: &TargetCounts) -> f64 {
    share(
        u64::from(counts.on_target),
        target.target_pixels() + u64::from(counts.off_target),
    )
}

/// The intersection over union of a model's voxels with the target voxels, on the
/// scorer's grid: `inside / (T + outside)`, where `inside` are the covered target voxels
/// (weight above 0), `outside` the covered other voxels of the grid and `T` the target
/// voxels; what a model covers beyond the grid is not counted. 0 when both are empty.
pub fn voxel_iou(scorer: &VolumeScorer, counts: &VolumeCounts) -> f64 {
    share(counts.inside, scorer.target_voxels() + counts.outside)
}

/// The triangles of a model's instances, in world space.
pub fn model_triangles(instances: &[Instance], meshes: &BoundMeshes) -> Vec<Triangle> {
    let mut out = Vec::new();
    for instance in instances {
        if let Some(mesh) = meshes.get(instance.mesh) {
            out.extend(
                mesh_triangles(mesh).map(|t| t.map(|p| instance.transform.transform_point3(p))),
            );
        }
    }
    out
}

/// A mesh's triangles.
pub fn mesh_triangles(mesh: &Mesh) -> impl Iterator<Item = Triangle> + '_ {
    mesh.triangles()
        .map(|t| t.map(|i| mesh.positions[i as usize]))
}

/// How [`SurfaceDistance`] samples two surfaces and matches their samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// The distance under which a sample counts as matched, for the F-score.
    pub threshold: f64,
    /// Points sampled on each surface, uniformly by area.
    pub samples: usize,
    /// The seed of the ChaCha8 stream the samples are drawn from, the model's before the
    /// other side's.
    pub seed: u64,
}

impl Sampling {
    /// The seeded stream, and the model's samples drawn from it; `None` when the model
    /// has no area or no samples are asked for.
    fn model_samples(self, model: &[Triangle]) -> Option<(ChaCha8Rng, Vec<DVec3>)> {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        let samples = sample(model, self.samples, &mut rng)?;
        Some((rng, samples))
    }
}

/// How far apart two surfaces are, measured on points sampled uniformly by area on each.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SurfaceDistance {
    /// The symmetric Chamfer distance: the mean distance from a sample of one surface to
    /// the nearest sample of the other, averaged over both directions, in world units.
    pub chamfer: f64,
    /// The F-score at `threshold`: the harmonic mean of precision (the share of the
    /// model's samples within `threshold` of a target sample) and recall (the share of
    /// the target's samples within `threshold` of a model sample); 0 when both are 0.
    pub f_score: f64,
    /// The distance under which a sample counts as matched.
    pub threshold: f64,
    /// Samples taken on each surface.
    pub samples: usize,
}

impl SurfaceDistance {
    /// The distance between `model` and `target`, each sampled as `sampling` says.
    /// Nearest samples are found exactly, by comparing every pair. `None` when either
    /// surface has no area or no samples are asked for.
    pub fn between(model: &[Triangle], target: &[Triangle], sampling: Sampling) -> Option<Self> {
        let (mut rng, a) = sampling.model_samples(model)?;
        let b = sample(target, sampling.samples, &mut rng)?;
        Some(Self::of_samples(&a, &b, sampling.threshold))
    }

    /// The distance between `model` and the point cloud `points`: the model sampled as
    /// in [`between`](Self::between), the cloud taken whole when it has at most
    /// `sampling.samples` points and otherwise that many of them drawn without
    /// replacement from the same seeded stream. `None` when the model has no area or
    /// either side is empty.
    ///
    /// ```
    /// use glam::Vec3;
    /// use shapegen_runtime::score::metrics::{Sampling, SurfaceDistance};
    ///
    /// let square = [
    ///     [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)],
    ///     [Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
    /// ];
    /// // A scan of the square 0.2 above it.
    /// let scan: Vec<Vec3> = (0..100)
    ///     .map(|i| Vec3::new((i % 10) as f32 / 9.0, (i / 10) as f32 / 9.0, 0.2))
    ///     .collect();
    /// let sampling = Sampling { threshold: 0.25, samples: 1000, seed: 0 };
    /// let d = SurfaceDistance::to_points(&square, &scan, sampling).unwrap();
    /// assert_eq!(d.f_score, 1.0);
    /// assert!(d.chamfer >= 0.2 && d.chamfer < 0.25);
    /// ```
    pub fn to_points(model: &[Triangle], points: &[Vec3], sampling: Sampling) -> Option<Self> {
        let (mut rng, a) = sampling.model_samples(model)?;
        let b = subsample(points, sampling.samples, &mut rng);
        if b.is_empty() {
            return None;
        }
        Some(Self::of_samples(&a, &b, sampling.threshold))
    }

    /// The measures of two sets of samples.
    fn of_samples(a: &[DVec3], b: &[DVec3], threshold: f64) -> SurfaceDistance {
        let (a_to_b, precision) = nearest(a, b, threshold);
        let (b_to_a, recall) = nearest(b, a, threshold);
        SurfaceDistance {
            chamfer: (a_to_b + b_to_a) / 2.0,
            f_score: f_score(precision, recall),
            threshold,
            samples: a.len(),
        }
    }
}

/// `points` whole when there are at most `n`, else `n` of them drawn without
/// replacement (a partial Fisher-Yates shuffle) from `rng`.
pub(crate) fn subsample(points: &[Vec3], n: usize, rng: &mut ChaCha8Rng) -> Vec<DVec3> {
    let mut all: Vec<DVec3> = points.iter().map(|p| p.as_dvec3()).collect();
    if all.len() > n {
        for i in 0..n {
            let j = rng.random_range(i..all.len());
            all.swap(i, j);
        }
        all.truncate(n);
    }
    all
}

/// `n` points uniformly by area on `triangles`; `None` when they have no area or `n` is 0.
pub(crate) fn sample(triangles: &[Triangle], n: usize, rng: &mut ChaCha8Rng) -> Option<Vec<DVec3>> {
    let mut cumulative = Vec::with_capacity(triangles.len());
    let mut total = 0.0;
    for t in triangles {
        let [a, b, c] = t.map(|p| p.as_dvec3());
        let area = (b - a).cross(c - a).length() / 2.0;
        total += if area.is_finite() { area } else { 0.0 };
        cumulative.push(total);
    }
    if total <= 0.0 || n == 0 {
        return None;
    }
    Some(
        (0..n)
            .map(|_| {
                let at = rng.random::<f64>() * total;
                let i = cumulative
                    .partition_point(|&c| c <= at)
                    .min(triangles.len() - 1);
                let [a, b, c] = triangles[i].map(|p| p.as_dvec3());
                let (mut u, mut v) = (rng.random::<f64>(), rng.random::<f64>());
                if u + v > 1.0 {
                    (u, v) = (1.0 - u, 1.0 - v);
                }
                a + (b - a) * u + (c - a) * v
            })
            .collect(),
    )
}

/// The mean distance from each point of `from` to its nearest point of `to`, and the
/// share of `from` within `threshold` of `to`.
pub(crate) fn nearest(from: &[DVec3], to: &[DVec3], threshold: f64) -> (f64, f64) {
    let distances: Vec<f64> = from
        .par_iter()
        .map(|p| {
            to.iter()
                .map(|q| p.distance_squared(*q))
                .fold(f64::INFINITY, f64::min)
                .sqrt()
        })
        .collect();
    let n = from.len() as f64;
    let within = distances.iter().filter(|&&d| d <= threshold).count() as f64;
    (distances.iter().sum::<f64>() / n, within / n)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sampling(threshold: f64, samples: usize, seed: u64) -> Sampling {
        Sampling {
            threshold,
            samples,
            seed,
        }
    }

    fn unit_square(z: f32) -> Vec<Triangle> {
        let p = |x: f32, y: f32| Vec3::new(x, y, z);
        vec![
            [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)],
            [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
        ]
    }

    #[test]
    fn parallel_planes_are_their_distance_apart() {
        let d =
            SurfaceDistance::between(&unit_square(0.0), &unit_square(0.5), sampling(0.4, 400, 1))
                .unwrap();
        // Every nearest sample is at least 0.5 away, and near it: samples of the other
        // square lie about 1/20 apart.
        assert!(d.chamfer >= 0.5 && d.chamfer < 0.52, "{}", d.chamfer);
        assert_eq!(d.f_score, 0.0);
        let d =
            SurfaceDistance::between(&unit_square(0.0), &unit_square(0.5), sampling(0.6, 400, 1))
                .unwrap();
        assert_eq!(d.f_score, 1.0);
    }

    #[test]
    fn a_surface_is_near_itself_and_half_a_surface_recalls_half() {
        let same =
            SurfaceDistance::between(&unit_square(0.0), &unit_square(0.0), sampling(0.1, 500, 2))
                .unwrap();
        assert!(same.chamfer < 0.05);
        assert_eq!(same.f_score, 1.0);
        // The model is the square's lower-right triangle, far below the threshold from
        // it: precision 1, recall about 1/2 (target samples in the other half lie up to
        // 0.7 away), so the F-score is about 2/3.
        let half = SurfaceDistance::between(
            &unit_square(0.0)[..1],
            &unit_square(0.0),
            sampling(0.02, 2000, 3),
        )
        .unwrap();
        assert!((half.f_score - 2.0 / 3.0).abs() < 0.05, "{}", half.f_score);
    }

    #[test]
    fn sampling_is_by_area_and_seeded() {
        // A big and a tiny triangle: nearly all samples on the big one.
        let big = [
            Vec3::ZERO,
            Vec3::new(10.0, 0.0, 0.0),
            Vec3::new(0.0, 10.0, 0.0),
        ];
        let tiny = [
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::new(0.01, 0.0, 5.0),
            Vec3::new(0.0, 0.01, 5.0),
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let points = sample(&[big, tiny], 1000, &mut rng).unwrap();
        assert!(points.iter().filter(|p| p.z > 1.0).count() <= 1);
        let again = sample(&[big, tiny], 1000, &mut ChaCha8Rng::seed_from_u64(4)).unwrap();
        assert_eq!(points, again);
        assert!(sample(&[], 10, &mut rng).is_none());
        assert!(sample(&[[Vec3::ZERO; 3]], 10, &mut rng).is_none());
        assert!(SurfaceDistance::between(&[big], &[big], sampling(0.1, 0, 0)).is_none());
    }
}
