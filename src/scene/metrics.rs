//! A model measured against a scene's targets in the literature's measures, whatever the
//! scene's fitness: model size, voxel IoU, silhouette IoU per view, and Chamfer distance
//! and F-score against the volume targets' surfaces
//! ([`shapegen_runtime::score::metrics`] defines each).

use serde::{Deserialize, Serialize};
use shapegen_runtime::score::Scorer;
use shapegen_runtime::score::metrics::{
    Sampling, SurfaceDistance, Triangle, mesh_triangles, model_triangles, silhouette_iou, voxel_iou,
};
use shapegen_runtime::score::objective::Objective;
use shapegen_runtime::{BoundMeshes, Genome, Grammar, Instance, Mesh};

use super::loaded::Scene;
use super::scorer::SceneScorer;
use super::scorer::volume::{F_SCORE_THRESHOLD, f_score_threshold};

/// Points sampled on each surface for the Chamfer distance and the F-score.
pub const SURFACE_SAMPLES: usize = 4096;

/// One model's measures against a scene's targets, as `summary.json` reports them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Metrics {
    /// Genes of its genome.
    pub genes: usize,
    /// Instances it derives.
    pub instances: usize,
    /// Triangles of those instances.
    pub triangles: usize,
    /// Intersection over union of its voxels with the target voxels, on the grid
    /// (scenes with a `[volume]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voxel_iou: Option<f64>,
    /// Its surface against the surfaces of the volume targets that attract (inside
    /// weight above 0), sampled at [`SURFACE_SAMPLES`] points each; the F-score at
    /// [`F_SCORE_THRESHOLD`] of their bounding box's diagonal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<SurfaceDistance>,
    /// Its surface against the point cloud of each `chamfer` objective, in the scene's
    /// order: [`SURFACE_SAMPLES`] points of each side, the F-score at
    /// [`F_SCORE_THRESHOLD`] of the cloud's bounding box's diagonal.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub point_clouds: Vec<CloudDistance>,
    /// Intersection over union of its silhouette with each target image, in the scene's
    /// order (scenes with a `[silhouette]`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub silhouette_iou: Vec<ViewIou>,
}

/// The surface distance to one point cloud.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CloudDistance {
    /// The objective whose cloud it is, by its name.
    pub objective: String,
    /// Chamfer distance and F-score.
    #[serde(flatten)]
    pub distance: SurfaceDistance,
}

/// The silhouette IoU through one target's camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ViewIou {
    /// The target, by its image.
    pub target: String,
    /// `on / (T + off)`.
    pub iou: f64,
}

/// The names of [`Metrics::columns`], for the tables of `compare` and `sweep`.
pub const METRIC_COLUMNS: [&str; 7] = [
    "genes",
    "instances",
    "triangles",
    "voxel_iou",
    "silhouette_iou",
    "chamfer",
    "f_score",
];

impl Metrics {
    /// The measures of `genome`'s model, derived here; see [`of`](Self::of).
    pub fn of_genome<G: Grammar>(
        scene: &Scene,
        scorer: Option<&SceneScorer>,
        meshes: &BoundMeshes,
        genome: &Genome<G>,
    ) -> Metrics {
        let mut instances = Vec::new();
        genome.derive_on(&scene.site, &mut instances);
        Metrics::of(scene, scorer, meshes, genome.len(), &instances)
    }

    /// The measures as table cells, named by [`METRIC_COLUMNS`]: the model's size; the
    /// voxel IoU; the silhouette IoU, the mean over the views; the Chamfer distance and
    /// F-score against the volume targets' surfaces, or else against the first point
    /// cloud. A cell is empty where the scene has no such target; numbers are written
    /// as they round-trip.
    ///
    /// ```
    /// use shapegen::scene::{METRIC_COLUMNS, Metrics, ViewIou};
    ///
    /// let view = |iou| ViewIou { target: "front.png".into(), iou };
    /// let m = Metrics {
    ///     genes: 12, instances: 30, triangles: 360, voxel_iou: None, surface: None,
    ///     point_clouds: Vec::new(), silhouette_iou: vec![view(0.5), view(0.75)],
    /// };
    /// assert_eq!(m.columns(), ["12", "30", "360", "", "0.625", "", ""]);
    /// assert_eq!(METRIC_COLUMNS[4], "silhouette_iou");
    /// ```
    pub fn columns(&self) -> [String; METRIC_COLUMNS.len()] {
        let number = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
        let views = &self.silhouette_iou;
        let silhouette = (!views.is_empty())
            .then(|| views.iter().map(|v| v.iou).sum::<f64>() / views.len() as f64);
        let surface = self
            .surface
            .or_else(|| self.point_clouds.first().map(|c| c.distance));
        [
            self.genes.to_string(),
            self.instances.to_string(),
            self.triangles.to_string(),
            number(self.voxel_iou),
            number(silhouette),
            number(surface.map(|s| s.chamfer)),
            number(surface.map(|s| s.f_score)),
        ]
    }

    /// The measures of a model of `genes` genes deriving `instances` (of `meshes`,
    /// bound to its grammar) against `scene`'s targets, counted on the CPU by `scorer`
    /// (none for a multi-objective scene, which has no scorers: no IoU then).
    /// Deterministic: the surface samples come from a fixed seed.
    pub fn of(
        scene: &Scene,
        scorer: Option<&SceneScorer>,
        meshes: &BoundMeshes,
        genes: usize,
        instances: &[Instance],
    ) -> Metrics {
        let model = model_triangles(instances, meshes);
        let voxel_iou = scorer
            .and_then(SceneScorer::volume)
            .map(|v| voxel_iou(v, &v.count(instances, &mut v.scratch())));
        let silhouette_iou = scorer
            .and_then(SceneScorer::silhouette)
            .map(|s| {
                let counts = s.count(instances, &mut s.scratch());
                s.targets()
                    .iter()
                    .zip(counts.targets())
                    .map(|(t, c)| ViewIou {
                        target: t.name().to_owned(),
                        iou: silhouette_iou(t, c),
                    })
                    .collect()
            })
            .unwrap_or_default();
        Metrics {
            genes,
            instances: instances.len(),
            triangles: model.len(),
            voxel_iou,
            surface: surface(scene, &model),
            point_clouds: point_clouds(scene, &model),
            silhouette_iou,
        }
    }
}

/// The model's surface against the attracting volume targets'.
fn surface(scene: &Scene, model: &[Triangle]) -> Option<SurfaceDistance> {
    let meshes: Vec<&Mesh> = scene
        .scorers()
        .iter()
        .filter_map(|goal| goal.volume())
        .flat_map(|volume| volume.targets.iter().filter(|t| t.inside > 0.0))
        .map(|t| &t.mesh)
        .collect();
    let threshold = f_score_threshold(meshes.iter().copied())?;
    let target: Vec<Triangle> = meshes.iter().flat_map(|m| mesh_triangles(m)).collect();
    SurfaceDistance::between(model, &target, sampling(threshold))
}

/// [`SURFACE_SAMPLES`] points a side from the stream of seed 0, matched within
/// `threshold`.
fn sampling(threshold: f64) -> Sampling {
    Sampling {
        threshold,
        samples: SURFACE_SAMPLES,
        seed: 0,
    }
}

/// The model's surface against each `chamfer` objective's whole cloud.
fn point_clouds(scene: &Scene, model: &[Triangle]) -> Vec<CloudDistance> {
    let Some(goal) = scene.objectives.as_ref() else {
        return Vec::new();
    };
    goal.set
        .entries()
        .iter()
        .filter_map(|(name, objective)| match objective {
            Objective::Chamfer(chamfer) => Some((name, chamfer.cloud())),
            _ => None,
        })
        .filter_map(|(name, cloud)| {
            let (lo, hi) = cloud.bounds();
            let threshold = F_SCORE_THRESHOLD * f64::from((hi - lo).length());
            let distance = SurfaceDistance::to_points(model, &cloud.points, sampling(threshold))?;
            Some(CloudDistance {
                objective: name.clone(),
                distance,
            })
        })
        .collect()
}
