//! `[volume]`: weighted target volumes to fill or avoid on a voxel grid, counted on the
//! CPU or the GPU ([`VolumeScorer`], [`GpuVolumeScorer`]).
//!
//! ```toml
//! [volume]
//! grid = { min = [-5, -5, -2], max = [5, 5, 18], resolution = [100, 200, 100] }
//! good = 2.0
//! bad = 15.0
//! [[volume.target]]
//! mesh = "target.obj"
//! ```

use glam::Vec3;
use serde::Deserialize;
use shapegen_runtime::geometry::{BoundMeshes, Mesh};
use shapegen_runtime::gpu::{GpuContext, GpuError};
use shapegen_runtime::score::Form;
use shapegen_runtime::score::volume::{
    Fill, GpuVolumeScorer, Grid, MAX_HALF_WIDTH, VolumeCounts, VolumeScorer, VolumeTarget,
    fscore_half_width,
};

use crate::scene::error::{SceneError, ValueError};
use crate::scene::resolver::Resolver;
use crate::scene::scorer_kind::{FormName, GpuCount, SceneScorerKind, ScorerMemory, resolve_form};

/// The F-score's threshold, as a share of the diagonal of the volume targets' bounding
/// box.
pub const F_SCORE_THRESHOLD: f64 = 0.01;

/// The `[volume]` kind of scorer.
pub struct Volume;

/// `[volume]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeFile {
    grid: GridFile,
    #[serde(default = "one")]
    good: f64,
    #[serde(default = "one")]
    bad: f64,
    #[serde(default)]
    overlap: f64,
    /// Opt-in distance shaping: the distance in voxels over which an off-target voxel's
    /// cost rises to its full weight.
    shaping_radius: Option<f64>,
    /// The `fscore` form's threshold, in world units.
    fscore_threshold: Option<f64>,
    #[serde(default)]
    target: Vec<VolumeTargetFile>,
}

/// `volume.grid`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct GridFile {
    min: [f32; 3],
    max: [f32; 3],
    resolution: [u32; 3],
}

/// `[[volume.target]]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct VolumeTargetFile {
    mesh: String,
    #[serde(default = "one")]
    inside: f64,
    #[serde(default = "minus_one")]
    outside: f64,
    #[serde(default)]
    fill: Fill,
}

fn one() -> f64 {
    1.0
}

fn minus_one() -> f64 {
    -1.0
}

/// The `[volume]` table, resolved: the grid, the targets loaded, and the fitness form.
#[derive(Clone, Debug)]
pub struct VolumeGoal {
    /// The voxel grid.
    pub grid: Grid,
    /// The target meshes and their weights.
    pub targets: Vec<VolumeTarget>,
    /// How counts become fitness.
    pub form: Form,
    /// Opt-in distance shaping ([`VolumeScorer::shaped`]): the distance in voxels over
    /// which an off-target voxel's cost rises to its full weight; `None` scores as
    /// published.
    pub shaping_radius: Option<f64>,
}

impl SceneScorerKind for Volume {
    type File = VolumeFile;
    type Goal = VolumeGoal;
    type Scorer = VolumeScorer;
    type Counts = VolumeCounts;
    type Gpu<'a> = GpuVolumeScorer<'a>;

    fn resolve(
        r: &Resolver<'_>,
        file: &VolumeFile,
        form: FormName,
    ) -> Result<VolumeGoal, SceneError> {
        resolve(r, file, form)
    }

    fn memory(goal: &VolumeGoal, threads: usize) -> ScorerMemory {
        let r = goal.grid.resolution();
        let n = r.iter().map(|&x| u64::from(x)).product::<u64>();
        let cells = Some(("voxels", format!("volume.grid.resolution = {r:?}"), n));
        let mut other = Vec::new();
        if let Form::FScore { threshold, .. } = goal.form {
            // The target's surface, the voxels near it and four edge bitsets; per
            // thread, the model's surface dilated once per voxel of half-width.
            let n = goal.grid.voxel_count();
            let dilated = fscore_half_width(&goal.grid, threshold) as u64 + 1;
            let bitsets = 6 + dilated.saturating_mul(threads as u64);
            other.push((
                format!("for the fscore form's {bitsets} bitsets of {n} voxels"),
                format!(
                    "fitness.form = \"fscore\", volume.fscore_threshold = {threshold}, \
                     --threads {threads}"
                ),
                (n / 8).saturating_mul(bitsets),
            ));
        }
        ScorerMemory { cells, other }
    }

    fn make(goal: &VolumeGoal, meshes: &BoundMeshes) -> Result<VolumeScorer, ValueError> {
        let scorer = VolumeScorer::new(goal.grid, &goal.targets, meshes, goal.form);
        match goal.shaping_radius {
            None => scorer,
            Some(radius) => scorer.and_then(|s| s.shaped(radius)),
        }
        .map_err(|err| ValueError::Scorer(Box::new(err)))
    }

    fn gpu<'a>(
        scorer: &'a VolumeScorer,
        context: &'a GpuContext,
    ) -> Option<Result<GpuVolumeScorer<'a>, GpuError>> {
        Some(GpuVolumeScorer::new(context, scorer))
    }
}

impl GpuCount<VolumeCounts> for GpuVolumeScorer<'_> {
    fn count_batch(
        &self,
        batch: &shapegen_runtime::score::InstanceBatch,
        out: &mut [VolumeCounts],
    ) -> Result<(), GpuError> {
        GpuVolumeScorer::count_batch(self, batch, out)
    }

    fn max_batch(&self) -> usize {
        GpuVolumeScorer::max_batch(self)
    }
}

/// [`F_SCORE_THRESHOLD`] of the diagonal of the bounding box of `meshes`; `None` when
/// none has a bounding box.
pub fn f_score_threshold<'a>(meshes: impl Iterator<Item = &'a Mesh>) -> Option<f64> {
    let (lo, hi) = meshes
        .filter_map(|m| m.bounds())
        .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))?;
    Some(F_SCORE_THRESHOLD * f64::from((hi - lo).length()))
}

/// The `fscore` form's threshold: `volume.fscore_threshold`, or
/// [`F_SCORE_THRESHOLD`] of the diagonal of the attracting
/// targets' bounding box, as runs report the F-score.
fn fscore_threshold(
    r: &Resolver<'_>,
    v: &VolumeFile,
    grid: &Grid,
    targets: &[VolumeTarget],
) -> Result<f64, SceneError> {
    const KEY: &str = "volume.fscore_threshold";
    let t = match v.fscore_threshold {
        Some(t) if !(t.is_finite() && t > 0.0) => {
            return Err(r.invalid(KEY, format!("{t} is not a distance above 0")));
        }
        Some(t) => t,
        None => f_score_threshold(targets.iter().filter(|t| t.inside > 0.0).map(|t| &t.mesh))
            .filter(|&t| t > 0.0)
            .ok_or_else(|| {
                r.invalid(
                    KEY,
                    "no target attracts (inside above 0) with a bounding box to take \
                     the threshold from: give it, in world units",
                )
            })?,
    };
    let voxels = fscore_half_width(grid, t);
    if voxels > MAX_HALF_WIDTH as f64 {
        return Err(r.invalid(
            KEY,
            format!(
                "{t} spans {voxels} voxels along x, where at most {MAX_HALF_WIDTH} are \
                 supported: give a threshold below {} or a coarser grid",
                (MAX_HALF_WIDTH + 1) as f64 * grid.cell().x
            ),
        ));
    }
    Ok(t)
}

fn resolve(r: &Resolver<'_>, v: &VolumeFile, form: FormName) -> Result<VolumeGoal, SceneError> {
    let grid = Grid::new(
        Vec3::from(v.grid.min),
        Vec3::from(v.grid.max),
        v.grid.resolution,
    )
    .map_err(|err| r.refused("volume.grid", err))?;
    if v.target.is_empty() {
        return Err(r.invalid(
            "volume.target",
            "no target: add at least one [[volume.target]] with a `mesh`",
        ));
    }
    let mut targets = Vec::with_capacity(v.target.len());
    for (i, t) in v.target.iter().enumerate() {
        let key = format!("volume.target[{i}]");
        let mesh = match r.sources().get_mesh(&t.mesh) {
            Some(mesh) => mesh.clone(),
            None => {
                let path = r.file(&format!("{key}.mesh"), &t.mesh)?;
                Mesh::load(&path).map_err(|err| r.refused(format!("{key}.mesh"), err))?
            }
        };
        targets.push(VolumeTarget {
            name: t.mesh.clone(),
            mesh,
            inside: r.finite(&format!("{key}.inside"), t.inside)?,
            outside: r.finite(&format!("{key}.outside"), t.outside)?,
            fill: t.fill,
        });
    }
    let threshold = match form {
        FormName::FScore => Some(fscore_threshold(r, v, &grid, &targets)?),
        _ => None,
    };
    let form = resolve_form(r, "volume", form, (v.good, v.bad, v.overlap), threshold)?;
    let shaping_radius = match v.shaping_radius {
        Some(radius) if !(radius.is_finite() && radius > 0.0) => {
            return Err(r.invalid(
                "volume.shaping_radius",
                format!("{radius} is not a positive number of voxels"),
            ));
        }
        radius => radius,
    };
    Ok(VolumeGoal {
        grid,
        targets,
        form,
        shaping_radius,
    })
}
