//! `[silhouette]`: target images seen through cameras, counted on the CPU or the GPU,
//! where bred children are counted from what the device kept of their parents
//! ([`SilhouetteScorer`], [`GpuSilhouetteScorer`], [`GpuRetention`]).
//!
//! ```toml
//! [silhouette]
//! good = 1.0
//! bad = 1.0
//! [[silhouette.target]]
//! image = "skyline.png"
//! camera = { phi = -3.05, theta = 0.05, radius = 12.4, lookat = [1.8, 4.7, -0.6],
//!            fov = 60, near = 0.1, far = 100, width = 800, height = 600 }
//! ```

use glam::{Mat4, Vec3};
use serde::Deserialize;
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::gpu::{GpuContext, GpuError};
use shapegen_runtime::score::silhouette::{
    Camera, GpuRetention, GpuSilhouetteScorer, ImageTarget, Weighting, MaskRule, OrbitCamera,
    SilhouetteCounts, SilhouetteScorer,
};
use shapegen_runtime::score::{Form, InstanceBatch};
use shapegen_runtime::Grammar;
use shapegen_runtime::optimize::Bred;

use crate::scene::error::{SceneError, ValueError};
use crate::scene::image::read_image;
use crate::scene::resolver::Resolver;
use crate::scene::scorer_kind::{FormName, GpuCount, SceneScorerKind, ScorerMemory, resolve_form};

/// The RGB distance from a mask's `background` colour within which a pixel is backdrop,
/// when the scene gives no `tolerance`.
const DEFAULT_BACKGROUND_TOLERANCE: u16 = 32;

/// The `[silhouette]` kind of scorer.
pub struct Silhouette;

/// `[silhouette]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SilhouetteFile {
    #[serde(default = "one")]
    good: f64,
    #[serde(default = "one")]
    bad: f64,
    /// Opt-in distance shaping of every mask target: the distance in pixels over which
    /// an off-target pixel's cost rises to its full weight.
    shaping_radius: Option<f32>,
    #[serde(default)]
    target: Vec<ImageTargetFile>,
}

fn one() -> f64 {
    1.0
}

/// `[[silhouette.target]]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ImageTargetFile {
    image: String,
    #[serde(default)]
    kind: ImageKind,
    /// Mask images: pixels darker than this grey level are the target, instead of the
    /// original's rule (red channel 0).
    threshold: Option<u16>,
    /// Mask images: pixels at least this opaque (alpha 1 to 255) are the target.
    alpha: Option<u16>,
    /// Mask images: pixels farther than `tolerance` from this RGB colour are the target.
    background: Option<[u16; 3]>,
    /// Mask images with a `background`: the largest RGB distance of a backdrop pixel.
    tolerance: Option<u16>,
    /// Mask images: weight of dark pixels. Weight maps: weight of black.
    on: Option<f32>,
    /// Mask images: weight of light pixels. Weight maps: weight of white.
    off: Option<f32>,
    camera: CameraFile,
}

/// `silhouette.target.kind`
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
enum ImageKind {
    /// Black and white: black pixels (red channel 0) are the target, or those darker
    /// than a threshold.
    #[default]
    Mask,
    /// Grey levels mapped linearly from `on` (black) to `off` (white).
    Weights,
}

/// `silhouette.target.camera`: an orbit camera or explicit matrices.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraFile {
    width: u32,
    height: u32,
    phi: Option<f32>,
    theta: Option<f32>,
    radius: Option<f32>,
    lookat: Option<[f32; 3]>,
    fov: Option<f32>,
    near: Option<f32>,
    far: Option<f32>,
    /// Row-major 4 x 4 view matrix.
    view: Option<[[f32; 4]; 4]>,
    /// Row-major 4 x 4 projection matrix.
    projection: Option<[[f32; 4]; 4]>,
}

/// The `[silhouette]` table, resolved: the target images with their cameras, and the
/// fitness form.
#[derive(Clone, Debug)]
pub struct SilhouetteGoal {
    /// The target images.
    pub targets: Vec<ImageTarget>,
    /// How counts become fitness.
    pub form: Form,
}

impl SceneScorerKind for Silhouette {
    type File = SilhouetteFile;
    type Goal = SilhouetteGoal;
    type Scorer = SilhouetteScorer;
    type Counts = SilhouetteCounts;
    type Gpu<'a> = GpuSilhouetteScorer<'a>;

    fn resolve(
        r: &Resolver<'_>,
        file: &SilhouetteFile,
        form: FormName,
    ) -> Result<SilhouetteGoal, SceneError> {
        resolve(r, file, form)
    }

    fn memory(goal: &SilhouetteGoal, _threads: usize) -> ScorerMemory {
        let n = goal
            .targets
            .iter()
            .map(|t| u64::from(t.width()) * u64::from(t.height()))
            .sum();
        let setting = "silhouette.target sizes".to_owned();
        ScorerMemory {
            cells: Some(("target pixels", setting, n)),
            other: Vec::new(),
        }
    }

    fn make(goal: &SilhouetteGoal, meshes: &BoundMeshes) -> Result<SilhouetteScorer, ValueError> {
        SilhouetteScorer::new(goal.targets.clone(), meshes, goal.form)
            .map_err(|err| ValueError::Scorer(Box::new(err)))
    }

    fn gpu<'a>(
        scorer: &'a SilhouetteScorer,
        context: &'a GpuContext,
    ) -> Option<Result<GpuSilhouetteScorer<'a>, GpuError>> {
        Some(GpuSilhouetteScorer::new(context, scorer))
    }

    fn gpu_retention(gpu: &GpuSilhouetteScorer<'_>) -> Option<GpuRetention> {
        GpuRetention::new(gpu).ok()
    }

    fn count_bred<G: Grammar>(
        gpu: &GpuSilhouetteScorer<'_>,
        retention: &mut GpuRetention,
        bred: Bred<'_, G>,
        batch: &InstanceBatch,
        out: &mut [SilhouetteCounts],
    ) -> Result<(), GpuError> {
        retention.count_bred(gpu, bred, batch, out)
    }
}

impl GpuCount<SilhouetteCounts> for GpuSilhouetteScorer<'_> {
    fn count_batch(
        &self,
        batch: &InstanceBatch,
        out: &mut [SilhouetteCounts],
    ) -> Result<(), GpuError> {
        GpuSilhouetteScorer::count_batch(self, batch, out)
    }

    fn max_batch(&self) -> usize {
        GpuSilhouetteScorer::max_batch(self)
    }
}

fn resolve(
    r: &Resolver<'_>,
    s: &SilhouetteFile,
    form: FormName,
) -> Result<SilhouetteGoal, SceneError> {
    if s.target.is_empty() {
        return Err(r.invalid(
            "silhouette.target",
            "no target: add at least one [[silhouette.target]] with an `image` and a `camera`",
        ));
    }
    let targets = s
        .target
        .iter()
        .enumerate()
        .map(|(i, t)| image_target(r, &format!("silhouette.target[{i}]"), t))
        .map(|target| match s.shaping_radius {
            None => target,
            Some(radius) => target?
                .shaped(radius)
                .map_err(|err| r.refused("silhouette.shaping_radius", err)),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let form = resolve_form(r, "silhouette", form, (s.good, s.bad, 0.0), None)?;
    Ok(SilhouetteGoal { targets, form })
}

fn image_target(
    r: &Resolver<'_>,
    key: &str,
    t: &ImageTargetFile,
) -> Result<ImageTarget, SceneError> {
    let camera = camera(r, &format!("{key}.camera"), &t.camera)?;
    let image_key = format!("{key}.image");
    let image = match r.sources().get_image(&t.image) {
        Some(image) => image.clone(),
        None => {
            let path = r.file(&image_key, &t.image)?;
            read_image(&path).map_err(|err| r.refused(&image_key, err))?
        }
    };
    let (width, height) = (image.width(), image.height());
    if (width, height) != (t.camera.width, t.camera.height) {
        return Err(r.invalid(
            &image_key,
            format!(
                "the image is {width} x {height} pixels but its camera renders {} x {}; \
                 make them equal",
                t.camera.width, t.camera.height
            ),
        ));
    }
    let on = f64::from(t.on.unwrap_or(1.0));
    let off = f64::from(t.off.unwrap_or(-1.0));
    let on = r.finite(&format!("{key}.on"), on)? as f32;
    let off = r.finite(&format!("{key}.off"), off)? as f32;
    let rule = mask_rule(r, key, t)?;
    let weighting = match t.kind {
        ImageKind::Mask => Weighting::mask_by(rule, on, off),
        ImageKind::Weights => Weighting::weight_map(on, off),
    };
    ImageTarget::new(t.image.clone(), &image, camera, weighting)
        .map_err(|err| r.refused(image_key, err))
}

/// The rule that picks a mask's target pixels: at most one of `threshold`,
/// `alpha` and `background` (with its `tolerance`), for masks only.
fn mask_rule(r: &Resolver<'_>, key: &str, t: &ImageTargetFile) -> Result<MaskRule, SceneError> {
    let given: Vec<&str> = [
        ("threshold", t.threshold.is_some()),
        ("alpha", t.alpha.is_some()),
        ("background", t.background.is_some()),
    ]
    .into_iter()
    .filter_map(|(field, set)| set.then_some(field))
    .collect();
    if t.tolerance.is_some() && t.background.is_none() {
        return Err(r.invalid(
            format!("{key}.tolerance"),
            "a tolerance is the distance from a `background` colour; give the background",
        ));
    }
    match given[..] {
        [] => return Ok(MaskRule::RedZero),
        [field] if t.kind == ImageKind::Weights => {
            return Err(r.invalid(
                format!("{key}.{field}"),
                "only a mask picks target pixels; a weight map weighs every grey level",
            ));
        }
        [_] => {}
        _ => {
            return Err(r.invalid(
                format!("{key}.{}", given[1]),
                format!(
                    "a mask has one rule, but {} are given; keep one",
                    given.join(" and ")
                ),
            ));
        }
    }
    let level = |field: &str, value: u16| match value {
        1..=255 => Ok(value as u8),
        _ => Err(r.invalid(
            format!("{key}.{field}"),
            format!("{value} is not a level from 1 to 255"),
        )),
    };
    if let Some(threshold) = t.threshold {
        return Ok(MaskRule::DarkerThan(level("threshold", threshold)?));
    }
    if let Some(alpha) = t.alpha {
        return Ok(MaskRule::OpaqueFrom(level("alpha", alpha)?));
    }
    let colour = t.background.unwrap_or_default();
    let Ok(background) = colour
        .map(u8::try_from)
        .into_iter()
        .collect::<Result<Vec<u8>, _>>()
    else {
        return Err(r.invalid(
            format!("{key}.background"),
            format!("{colour:?} is not an RGB colour of three values from 0 to 255"),
        ));
    };
    let tolerance = t.tolerance.unwrap_or(DEFAULT_BACKGROUND_TOLERANCE);
    if tolerance > 441 {
        return Err(r.invalid(
            format!("{key}.tolerance"),
            format!("{tolerance} is beyond the largest RGB distance, 441"),
        ));
    }
    Ok(MaskRule::FarFrom {
        background: [background[0], background[1], background[2]],
        tolerance,
    })
}

fn camera(r: &Resolver<'_>, key: &str, c: &CameraFile) -> Result<Camera, SceneError> {
    if c.width == 0 || c.height == 0 {
        return Err(r.invalid(
            key,
            format!(
                "the image size {} x {} must be at least 1 x 1",
                c.width, c.height
            ),
        ));
    }
    let orbit = [
        c.phi.is_some(),
        c.theta.is_some(),
        c.radius.is_some(),
        c.lookat.is_some(),
        c.fov.is_some(),
        c.near.is_some(),
        c.far.is_some(),
    ];
    let matrices = [c.view.is_some(), c.projection.is_some()];
    let camera = match (orbit.iter().any(|&b| b), matrices.iter().any(|&b| b)) {
        (true, false) => {
            let missing: Vec<&str> = ["phi", "theta", "radius", "lookat", "fov", "near", "far"]
                .into_iter()
                .zip(orbit)
                .filter(|&(_, present)| !present)
                .map(|(name, _)| name)
                .collect();
            if !missing.is_empty() {
                return Err(r.invalid(
                    key,
                    format!("an orbit camera also needs {}", missing.join(", ")),
                ));
            }
            Camera::Orbit(OrbitCamera {
                phi: c.phi.unwrap_or_default(),
                theta: c.theta.unwrap_or_default(),
                radius: c.radius.unwrap_or_default(),
                lookat: Vec3::from(c.lookat.unwrap_or_default()),
                fov_degrees: c.fov.unwrap_or_default(),
                near: c.near.unwrap_or_default(),
                far: c.far.unwrap_or_default(),
            })
        }
        (false, true) => match (c.view, c.projection) {
            (Some(view), Some(projection)) => Camera::Matrices {
                view: Mat4::from_cols_array_2d(&view).transpose(),
                projection: Mat4::from_cols_array_2d(&projection).transpose(),
            },
            _ => {
                return Err(r.invalid(
                    key,
                    "a matrix camera needs both `view` and `projection` (4 rows of 4 numbers each)",
                ));
            }
        },
        (true, true) => {
            return Err(r.invalid(
                key,
                "give either an orbit camera (phi, theta, radius, lookat, fov, near, far) \
                 or matrices (view, projection), not both",
            ));
        }
        (false, false) => {
            return Err(r.invalid(
                key,
                "no camera: give phi, theta, radius, lookat, fov, near and far, \
                 or view and projection matrices",
            ));
        }
    };
    camera.validate().map_err(|err| r.refused(key, err))?;
    Ok(camera)
}
