//! The Chamfer distance from a model's surface to a point cloud, as an objective.

use std::sync::Arc;

use glam::DVec3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use serde::Deserialize;

use crate::evaluate::Sense;
use crate::geometry::PointCloud;
use crate::score::objective::error::ObjectiveError;
use crate::score::objective::kind::{FromTable, ObjectiveKind, ObjectiveSource};
use crate::score::objective::scratch::ObjectiveScratch;
use crate::score::objective::surface::Surface;
use crate::score::metrics::{nearest, sample, subsample};

/// The most samples a [`ChamferMatch`] may take: the work per model grows with their
/// square.
pub const MAX_CHAMFER_SAMPLES: usize = 8192;

/// A point cloud (a scan) to approach: the symmetric Chamfer distance between `samples`
/// points sampled by area on a model's surface and as many points of the cloud, in world
/// units ([`Sense::Minimize`]). The cloud is
/// subsampled once, when the objective is made; the model's samples come from a fixed
/// seed, so a model always measures the same. A model without surface measures the
/// diagonal of the cloud's bounding box, as if it were that far from every point. Its
/// table: `kind = "chamfer"`, `points` (the cloud's file: `.xyz`, `.txt` or `.ply`) and
/// `samples` (512 when left out).
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::geometry::PointCloud;
/// use shapegen_runtime::score::objective::{ChamferMatch, Surface};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// // A scan of the unit cube's top face.
/// let scan = PointCloud {
///     points: (0..121)
///         .map(|i| Vec3::new((i % 11) as f32 / 10.0 - 0.5, 0.5, (i / 11) as f32 / 10.0 - 0.5))
///         .collect(),
/// };
/// let chamfer = ChamferMatch::new(&scan, 256)?;
/// let at = |y: f32| {
///     let model = [Instance { transform: Affine3A::from_translation(Vec3::Y * y), mesh: CUBE }];
///     chamfer.measure(&Surface::from_instances(&model, &meshes))
/// };
/// assert!(at(0.0) < at(2.0));
/// assert_eq!(chamfer.measure(&Surface::new()), f64::from(2f32.sqrt())); // the diagonal
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ChamferMatch {
    cloud: Arc<PointCloud>,
    points: Arc<[DVec3]>,
    samples: usize,
    empty: f64,
}

impl ChamferMatch {
    /// The objective of approaching `cloud`, measured on `samples` points a side (1 to
    /// [`MAX_CHAMFER_SAMPLES`]).
    pub fn new(cloud: &PointCloud, samples: usize) -> Result<ChamferMatch, ObjectiveError> {
        if !(1..=MAX_CHAMFER_SAMPLES).contains(&samples) {
            return Err(ObjectiveError::Samples {
                samples,
                max: MAX_CHAMFER_SAMPLES,
            });
        }
        let (lo, hi) = cloud.bounds();
        let points = subsample(&cloud.points, samples, &mut ChaCha8Rng::seed_from_u64(0));
        if points.is_empty() || !(lo.is_finite() && hi.is_finite()) {
            return Err(ObjectiveError::EmptyCloud);
        }
        Ok(ChamferMatch {
            cloud: Arc::new(cloud.clone()),
            points: points.into(),
            samples,
            empty: f64::from((hi - lo).length()),
        })
    }

    /// The samples taken on each side.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// The whole cloud, of which the objective measures against a subsample.
    pub fn cloud(&self) -> &PointCloud {
        &self.cloud
    }

    /// The Chamfer distance of `surface` to the cloud.
    pub fn measure(&self, surface: &Surface) -> f64 {
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        let Some(model) = sample(surface.triangles(), self.samples, &mut rng) else {
            return self.empty;
        };
        let (to_cloud, _) = nearest(&model, &self.points, 0.0);
        let (to_model, _) = nearest(&self.points, &model, 0.0);
        (to_cloud + to_model) / 2.0
    }
}

/// The keys of a `chamfer` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChamferFile {
    /// The cloud's file (`.xyz`, `.txt` or `.ply`).
    pub points: String,
    /// Points sampled a side.
    #[serde(default = "chamfer_samples")]
    pub samples: usize,
}

/// The samples of a table that leaves them out.
fn chamfer_samples() -> usize {
    512
}

impl FromTable for ChamferMatch {
    type File = ChamferFile;

    /// The cloud of `points`; a sample count out of range is an error of `samples`.
    fn resolve<S: ObjectiveSource>(file: ChamferFile, source: &S) -> Result<Self, S::Error> {
        let cloud = source.point_cloud("points", &file.points)?;
        ChamferMatch::new(&cloud, file.samples).map_err(|err| source.refused("samples", err))
    }
}

impl ObjectiveKind for ChamferMatch {
    const SENSE: Sense = Sense::Minimize;

    fn measure(&self, surface: &Surface, _: &mut ObjectiveScratch) -> f64 {
        ChamferMatch::measure(self, surface)
    }
}
