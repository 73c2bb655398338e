//! From the scene file as written to a checked [`Scene`]: paths resolved against the
//! scene's folder, files loaded, values checked, every error naming its key.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};
use shapegen_runtime::Site;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::{Mesh, MeshLibrary};
use shapegen_runtime::optimize::multi::Selection;
use shapegen_runtime::score::silhouette::{Camera, ImageTarget, MaskRule, OrbitCamera};
use shapegen_runtime::score::volume::{Grid, MAX_HALF_WIDTH, VolumeTarget, fscore_half_width};
use shapegen_runtime::score::{Form, LengthPenalty};

use super::error::{SceneError, ValueError};
use super::file::{
    CameraFile, FitnessFile, FormName, ImageKind, ImageTargetFile, LengthFrom, LimitsFile,
    MeshFile, SceneFile, SilhouetteFile, VolumeFile,
};
use super::goal::{ObjectiveGoal, SilhouetteGoal, VolumeGoal};
use super::image::read_image;
use super::loaded::Scene;
use super::method::{Method, SettingsKeyError};
use super::metrics::f_score_threshold;
use super::optimizer::{self, OptimizerGoal, Overrides};
use super::scorer::ScorerGoal;
use super::sources::Sources;
use crate::registry::Registry;

/// The RGB distance from a mask's `background` colour within which a pixel is backdrop,
/// when the scene gives no `tolerance`.
const DEFAULT_BACKGROUND_TOLERANCE: u16 = 32;

impl Scene {
    /// Loads and checks the scene file at `path`, which names a published generator.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        Scene::open(path, &Registry::published(), &Overrides::default())
    }

    /// Loads the scene file at `path`, naming one of `registry`'s generators, with
    /// `overrides` applied.
    pub fn open(
        path: impl AsRef<Path>,
        registry: &Registry,
        overrides: &Overrides,
    ) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_owned(),
            source,
        })?;
        Scene::parse_in(&text, path, registry, overrides)
    }

    /// Checks the scene written in `text`, as if read from `path` (paths in it are
    /// relative to `path`'s folder), naming a published generator.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        Scene::parse_in(text, path, &Registry::published(), &Overrides::default())
    }

    /// Checks the scene written in `text`, as if read from `path`, naming one of
    /// `registry`'s generators, with `overrides` applied.
    pub fn parse_in(
        text: &str,
        path: &Path,
        registry: &Registry,
        overrides: &Overrides,
    ) -> Result<Scene, SceneError> {
        Scene::parse_with(text, path, registry, overrides, &Sources::new())
    }

    /// Checks the scene written in `text`, as if read from `path`, naming one of
    /// `registry`'s generators, with `overrides` applied, its targets taken from
    /// `sources` where it names one they hold (see [`Sources`]).
    pub fn parse_with(
        text: &str,
        path: &Path,
        registry: &Registry,
        overrides: &Overrides,
        sources: &Sources,
    ) -> Result<Scene, SceneError> {
        let syntax = |message: String| SceneError::Syntax {
            path: path.to_owned(),
            message: message.trim_end().to_owned(),
        };
        let file: SceneFile = if overrides.sets.is_empty() {
            toml::from_str(text).map_err(|err| syntax(err.to_string()))?
        } else {
            let mut table: toml::Table =
                toml::from_str(text).map_err(|err| syntax(err.to_string()))?;
            optimizer::apply_overrides(&mut table, &overrides.sets).map_err(|error| {
                SceneError::Set {
                    path: path.to_owned(),
                    error,
                }
            })?;
            toml::Value::Table(table)
                .try_into()
                .map_err(|err: toml::de::Error| syntax(format!("after --set: {}", err.message())))?
        };
        Resolver::new(path, sources).scene(file, registry, overrides)
    }
}

pub(super) struct Resolver<'a> {
    path: &'a Path,
    dir: PathBuf,
    /// Targets given in memory, looked up before files.
    sources: &'a Sources,
}

impl<'a> Resolver<'a> {
    /// A resolver of the scene at `path` that takes the targets `sources` holds from
    /// there.
    pub fn new(path: &'a Path, sources: &'a Sources) -> Self {
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Resolver { path, dir, sources }
    }

    pub(super) fn invalid(&self, key: impl Into<String>, reason: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_owned(),
            key: key.into(),
            reason: reason.into(),
        }
    }

    /// An error about `key`, whose value cannot be used for `cause`.
    pub(super) fn refused(
        &self,
        key: impl Into<String>,
        cause: impl Into<ValueError>,
    ) -> SceneError {
        SceneError::Value {
            path: self.path.to_owned(),
            key: key.into(),
            cause: Box::new(cause.into()),
        }
    }

    /// An error about a key of the `[optimizer]` or `[islands]` table.
    fn optimizer(&self, error: SettingsKeyError) -> SceneError {
        SceneError::Optimizer {
            path: self.path.to_owned(),
            error: Box::new(error),
        }
    }

    /// A path written in the scene, relative to the scene's folder, which must name an
    /// existing file.
    pub(super) fn file(&self, key: &str, written: &str) -> Result<PathBuf, SceneError> {
        if written.is_empty() {
            return Err(self.invalid(key, "the path is empty"));
        }
        let path = self.dir.join(written);
        if !path.is_file() {
            return Err(self.invalid(
                key,
                format!(
                    "`{}` is not a file (paths are relative to the scene file's folder)",
                    path.display()
                ),
            ));
        }
        Ok(path)
    }

    fn finite(&self, key: &str, value: f64) -> Result<f64, SceneError> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.invalid(key, format!("{value} is not a finite number")))
        }
    }

    fn non_negative(&self, key: &str, value: f64) -> Result<f64, SceneError> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(self.invalid(key, format!("{value} must be a finite number >= 0")))
        }
    }

    pub fn scene(
        &self,
        file: SceneFile,
        registry: &Registry,
        overrides: &Overrides,
    ) -> Result<Scene, SceneError> {
        let entry = registry.get(&file.generator).ok_or_else(|| {
            self.invalid(
                "generator",
                format!(
                    "`{}` is not a registered generator; the generators are {}",
                    file.generator,
                    registry.names()
                ),
            )
        })?;
        let presets = entry.defaults.presets;
        let meshes = self.meshes(&entry.defaults.meshes, &file.meshes)?;
        let (limits, optimal_len) = self.limits(&file.limits)?;
        let site = match &file.lot {
            Some(lot) => self.lot(lot)?,
            None => Site::NONE,
        };
        let length = self.length_penalty(&file.fitness, &limits, optimal_len)?;
        let optimum = self.optimum(file.fitness.optimum)?;
        let scorers = self.scorers(&file)?;
        let mut table = file.optimizer;
        let objectives = self.objective_goal(
            file.objective,
            file.selection,
            &scorers,
            entry.mesh_names,
            &mut table,
        )?;
        let optimizer = optimizer::resolve(&presets, table.clone(), file.islands, overrides)
            .map_err(|err| self.optimizer(err))?;
        if objectives.is_some() {
            self.check_front_search(&optimizer)?;
        }

        Ok(Scene {
            optimizer,
            optimizer_table: table,
            islands: file.islands,
            presets,
            overrides: overrides.clone(),
            path: self.path.to_owned(),
            generator: entry.name.clone(),
            meshes,
            limits,
            site,
            optimal_len,
            length,
            optimum,
            scorers,
            objectives,
        })
    }

    /// The generator's meshes `base` with the scene's `[meshes]` registered over them.
    fn meshes(
        &self,
        base: &MeshLibrary,
        files: &BTreeMap<String, MeshFile>,
    ) -> Result<MeshLibrary, SceneError> {
        let mut meshes = base.clone();
        for (name, entry) in files {
            let key = format!("meshes.{name}");
            let (written, normalize) = match entry {
                MeshFile::Path(path) => (path, true),
                MeshFile::Table { path, normalize } => (path, *normalize),
            };
            let path = self.file(&key, written)?;
            let registered = if normalize {
                meshes.register_obj(name.clone(), &path)
            } else {
                meshes.register_obj_as_written(name.clone(), &path)
            };
            registered.map_err(|err| self.refused(key, err))?;
        }
        Ok(meshes)
    }

    /// The length penalty of `[fitness]`, from `min_len` or `optimal_len` to `max_len`.
    fn length_penalty(
        &self,
        fitness: &FitnessFile,
        limits: &Limits,
        optimal_len: Option<u32>,
    ) -> Result<LengthPenalty, SceneError> {
        let from = match (fitness.length_from, optimal_len) {
            (LengthFrom::MinLen, _) => limits.min_len,
            (LengthFrom::OptimalLen, Some(optimal)) => optimal,
            (LengthFrom::OptimalLen, None) => {
                return Err(self.invalid(
                    "fitness.length_from",
                    "\"optimal_len\" starts the length penalty at limits.optimal_len, \
                     which the scene does not give; add it to [limits]",
                ));
            }
        };
        Ok(LengthPenalty {
            weight: self.non_negative("fitness.length", fitness.length)?,
            from: f64::from(from),
            to: f64::from(limits.max_len),
        })
    }

    /// `fitness.optimum`, which must be a finite number above 0 when given.
    fn optimum(&self, optimum: Option<f64>) -> Result<Option<f64>, SceneError> {
        match optimum {
            Some(v) if !(v.is_finite() && v > 0.0) => Err(self.invalid(
                "fitness.optimum",
                format!(
                    "{v} must be a finite number > 0: the best fitness the scene can \
                     reach, whose fractions compare and sweep time"
                ),
            )),
            v => Ok(v),
        }
    }

    /// The scene's scorers: one arm per kind of scorer, in the order of
    /// `ScorerKind::ALL`.
    fn scorers(&self, file: &SceneFile) -> Result<Vec<ScorerGoal>, SceneError> {
        let form = file.fitness.form;
        let scorers: Vec<ScorerGoal> = [
            file.volume
                .as_ref()
                .map(|v| self.volume(v, form).map(ScorerGoal::Volume)),
            file.silhouette
                .as_ref()
                .map(|s| self.silhouette(s, form).map(ScorerGoal::Silhouette)),
        ]
        .into_iter()
        .flatten()
        .collect::<Result<_, _>>()?;
        debug_assert!(scorers.is_sorted_by_key(ScorerGoal::kind));
        Ok(scorers)
    }

    /// The `[[objective]]` tables' goal, if the scene has any: then its `[selection]`
    /// and the archive taken from the `[optimizer]` `table`, whose method defaults to the
    /// GA. A scene scores by `scorers` or by objectives, not both, and by something.
    fn objective_goal(
        &self,
        objective: Vec<toml::Table>,
        selection: Option<Selection>,
        scorers: &[ScorerGoal],
        mesh_names: &[&str],
        table: &mut toml::Table,
    ) -> Result<Option<ObjectiveGoal>, SceneError> {
        if objective.is_empty() {
            if scorers.is_empty() {
                return Err(self.invalid(
                    "volume",
                    "the scene has nothing to score: add a [volume] or [silhouette] table, \
                     or [[objective]] tables",
                ));
            }
            if selection.is_some() {
                return Err(self.invalid(
                    "selection",
                    "ranks the objectives of [[objective]] tables, and the scene has none",
                ));
            }
            return Ok(None);
        }
        if !scorers.is_empty() {
            return Err(self.invalid(
                "objective",
                "a scene scores either by [volume] / [silhouette] or by [[objective]] \
                 tables, not both",
            ));
        }
        let set = self.objectives(objective, mesh_names)?;
        let selection = selection.unwrap_or_default();
        selection
            .validate()
            .and_then(|()| selection.check_objectives(set.len()))
            .map_err(|err| self.refused(err.field, err))?;
        let archive = optimizer::take_archive(table).map_err(|err| self.optimizer(err))?;
        // The multi-objective GA searches it, whatever the default method.
        table
            .entry("method")
            .or_insert_with(|| toml::Value::String(Method::Ga.name().to_owned()));
        Ok(Some(ObjectiveGoal {
            set,
            selection,
            archive,
        }))
    }

    /// A scene with objectives is searched by the multi-objective GA: the method must be
    /// the GA, without islands.
    fn check_front_search(&self, optimizer: &OptimizerGoal) -> Result<(), SceneError> {
        if optimizer.islands.is_some() {
            return Err(self.invalid(
                "islands",
                "scenes with [[objective]] tables are searched by the multi-objective GA, \
                 which has no island model; leave out [islands] and --islands",
            ));
        }
        if optimizer.method() != Method::Ga {
            return Err(self.invalid(
                "optimizer.method",
                format!(
                    "\"{}\": scenes with [[objective]] tables are searched by the \
                     multi-objective GA; the method must be \"ga\"",
                    optimizer.method().name()
                ),
            ));
        }
        Ok(())
    }

    fn limits(&self, l: &LimitsFile) -> Result<(Limits, Option<u32>), SceneError> {
        if l.min_len == 0 {
            return Err(self.invalid("limits.min_len", "must be at least 1 (the root gene)"));
        }
        if l.max_len < l.min_len {
            return Err(self.invalid(
                "limits.max_len",
                format!("{} is below limits.min_len = {}", l.max_len, l.min_len),
            ));
        }
        if let Some(optimal) = l
            .optimal_len
            .filter(|o| !(l.min_len..=l.max_len).contains(o))
        {
            return Err(self.invalid(
                "limits.optimal_len",
                format!(
                    "{optimal} must lie between limits.min_len = {} and limits.max_len = {}",
                    l.min_len, l.max_len
                ),
            ));
        }
        if l.max_depth == 0 {
            return Err(self.invalid("limits.max_depth", "must be at least 1 (the root)"));
        }
        let limits = Limits {
            min_len: l.min_len,
            max_len: l.max_len,
            max_depth: l.max_depth,
        };
        Ok((limits, l.optimal_len))
    }

    /// The form `form` of table `table` (`volume` or `silhouette`); `threshold` is the
    /// F-score's, which only a volume has.
    fn form(
        &self,
        table: &str,
        form: FormName,
        (good, bad, overlap): (f64, f64, f64),
        threshold: Option<f64>,
    ) -> Result<Form, SceneError> {
        Ok(match form {
            FormName::Smooth => Form::Smooth {
                good: self.finite(&format!("{table}.good"), good)?,
                bad: self.finite(&format!("{table}.bad"), bad)?,
            },
            FormName::Weighted => Form::Weighted {
                overlap: self.finite(&format!("{table}.overlap"), overlap)?,
            },
            FormName::Iou => Form::Iou {
                good: self.finite(&format!("{table}.good"), good)?,
            },
            FormName::FScore => match threshold {
                Some(threshold) => Form::FScore {
                    good: self.finite(&format!("{table}.good"), good)?,
                    threshold,
                },
                None => {
                    return Err(self.invalid(
                        "fitness.form",
                        format!(
                            "`fscore` is for volume goals; a [{table}] takes \"smooth\", \
                             \"weighted\" or \"iou\""
                        ),
                    ));
                }
            },
        })
    }

    /// The `fscore` form's threshold: `volume.fscore_threshold`, or
    /// [`F_SCORE_THRESHOLD`](super::F_SCORE_THRESHOLD) of the diagonal of the attracting
    /// targets' bounding box, as runs report the F-score.
    fn fscore_threshold(
        &self,
        v: &VolumeFile,
        grid: &Grid,
        targets: &[VolumeTarget],
    ) -> Result<f64, SceneError> {
        const KEY: &str = "volume.fscore_threshold";
        let t = match v.fscore_threshold {
            Some(t) if !(t.is_finite() && t > 0.0) => {
                return Err(self.invalid(KEY, format!("{t} is not a distance above 0")));
            }
            Some(t) => t,
            None => f_score_threshold(targets.iter().filter(|t| t.inside > 0.0).map(|t| &t.mesh))
                .filter(|&t| t > 0.0)
                .ok_or_else(|| {
                    self.invalid(
                        KEY,
                        "no target attracts (inside above 0) with a bounding box to take \
                         the threshold from: give it, in world units",
                    )
                })?,
        };
        let voxels = fscore_half_width(grid, t);
        if voxels > MAX_HALF_WIDTH as f64 {
            return Err(self.invalid(
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

    fn volume(&self, v: &VolumeFile, form: FormName) -> Result<VolumeGoal, SceneError> {
        let grid = Grid::new(
            Vec3::from(v.grid.min),
            Vec3::from(v.grid.max),
            v.grid.resolution,
        )
        .map_err(|err| self.refused("volume.grid", err))?;
        if v.target.is_empty() {
            return Err(self.invalid(
                "volume.target",
                "no target: add at least one [[volume.target]] with a `mesh`",
            ));
        }
        let mut targets = Vec::with_capacity(v.target.len());
        for (i, t) in v.target.iter().enumerate() {
            let key = format!("volume.target[{i}]");
            let mesh = match self.sources.get_mesh(&t.mesh) {
                Some(mesh) => mesh.clone(),
                None => {
                    let path = self.file(&format!("{key}.mesh"), &t.mesh)?;
                    Mesh::load(&path).map_err(|err| self.refused(format!("{key}.mesh"), err))?
                }
            };
            targets.push(VolumeTarget {
                name: t.mesh.clone(),
                mesh,
                inside: self.finite(&format!("{key}.inside"), t.inside)?,
                outside: self.finite(&format!("{key}.outside"), t.outside)?,
                fill: t.fill,
            });
        }
        let threshold = match form {
            FormName::FScore => Some(self.fscore_threshold(v, &grid, &targets)?),
            _ => None,
        };
        let form = self.form("volume", form, (v.good, v.bad, v.overlap), threshold)?;
        let shaping_radius = match v.shaping_radius {
            Some(r) if !(r.is_finite() && r > 0.0) => {
                return Err(self.invalid(
                    "volume.shaping_radius",
                    format!("{r} is not a positive number of voxels"),
                ));
            }
            r => r,
        };
        Ok(VolumeGoal {
            grid,
            targets,
            form,
            shaping_radius,
        })
    }

    fn silhouette(&self, s: &SilhouetteFile, form: FormName) -> Result<SilhouetteGoal, SceneError> {
        if s.target.is_empty() {
            return Err(self.invalid(
                "silhouette.target",
                "no target: add at least one [[silhouette.target]] with an `image` and a `camera`",
            ));
        }
        let targets = s
            .target
            .iter()
            .enumerate()
            .map(|(i, t)| self.image_target(&format!("silhouette.target[{i}]"), t))
            .map(|target| match s.shaping_radius {
                None => target,
                Some(radius) => target?
                    .shaped(radius)
                    .map_err(|err| self.refused("silhouette.shaping_radius", err)),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let form = self.form("silhouette", form, (s.good, s.bad, 0.0), None)?;
        Ok(SilhouetteGoal { targets, form })
    }

    fn image_target(&self, key: &str, t: &ImageTargetFile) -> Result<ImageTarget, SceneError> {
        let camera = self.camera(&format!("{key}.camera"), &t.camera)?;
        let image_key = format!("{key}.image");
        let image = match self.sources.get_image(&t.image) {
            Some(image) => image.clone(),
            None => {
                let path = self.file(&image_key, &t.image)?;
                read_image(&path).map_err(|err| self.refused(&image_key, err))?
            }
        };
        let (width, height) = (image.width(), image.height());
        if (width, height) != (t.camera.width, t.camera.height) {
            return Err(self.invalid(
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
        let on = self.finite(&format!("{key}.on"), on)? as f32;
        let off = self.finite(&format!("{key}.off"), off)? as f32;
        let name = t.image.clone();
        let rule = self.mask_rule(key, t)?;
        let target = match t.kind {
            ImageKind::Mask => ImageTarget::from_mask_by(name, &image, camera, on, off, rule),
            ImageKind::Weights => ImageTarget::from_weight_map(name, &image, camera, on, off),
        };
        target.map_err(|err| self.refused(image_key, err))
    }

    /// The rule that picks a mask's target pixels: at most one of `threshold`,
    /// `alpha` and `background` (with its `tolerance`), for masks only.
    fn mask_rule(&self, key: &str, t: &ImageTargetFile) -> Result<MaskRule, SceneError> {
        let given: Vec<&str> = [
            ("threshold", t.threshold.is_some()),
            ("alpha", t.alpha.is_some()),
            ("background", t.background.is_some()),
        ]
        .into_iter()
        .filter_map(|(field, set)| set.then_some(field))
        .collect();
        if t.tolerance.is_some() && t.background.is_none() {
            return Err(self.invalid(
                format!("{key}.tolerance"),
                "a tolerance is the distance from a `background` colour; give the background",
            ));
        }
        match given[..] {
            [] => return Ok(MaskRule::RedZero),
            [field] if t.kind == ImageKind::Weights => {
                return Err(self.invalid(
                    format!("{key}.{field}"),
                    "only a mask picks target pixels; a weight map weighs every grey level",
                ));
            }
            [_] => {}
            _ => {
                return Err(self.invalid(
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
            _ => Err(self.invalid(
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
            return Err(self.invalid(
                format!("{key}.background"),
                format!("{colour:?} is not an RGB colour of three values from 0 to 255"),
            ));
        };
        let tolerance = t.tolerance.unwrap_or(DEFAULT_BACKGROUND_TOLERANCE);
        if tolerance > 441 {
            return Err(self.invalid(
                format!("{key}.tolerance"),
                format!("{tolerance} is beyond the largest RGB distance, 441"),
            ));
        }
        Ok(MaskRule::FarFrom {
            background: [background[0], background[1], background[2]],
            tolerance,
        })
    }

    fn camera(&self, key: &str, c: &CameraFile) -> Result<Camera, SceneError> {
        if c.width == 0 || c.height == 0 {
            return Err(self.invalid(
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
                    return Err(self.invalid(
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
                    return Err(self.invalid(
                        key,
                        "a matrix camera needs both `view` and `projection` (4 rows of 4 numbers each)",
                    ));
                }
            },
            (true, true) => {
                return Err(self.invalid(
                    key,
                    "give either an orbit camera (phi, theta, radius, lookat, fov, near, far) \
                     or matrices (view, projection), not both",
                ));
            }
            (false, false) => {
                return Err(self.invalid(
                    key,
                    "no camera: give phi, theta, radius, lookat, fov, near and far, \
                     or view and projection matrices",
                ));
            }
        };
        camera.validate().map_err(|err| self.refused(key, err))?;
        Ok(camera)
    }
}

#[cfg(test)]
mod tests {
    use std::error::Error;

    use super::Scene;

    /// A silhouette scene whose target image is `bytes`, in a folder of its own.
    fn with_image(bytes: &[u8]) -> (tempfile::TempDir, super::SceneError) {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("target.png"), bytes).unwrap();
        let text = r#"
generator = "city"
[limits]
min_len = 1
max_len = 201
max_depth = 8
[[silhouette.target]]
image = "target.png"
camera = { phi = 0, theta = 0, radius = 5, lookat = [0, 0, 0], fov = 60, near = 0.1, far = 100, width = 8, height = 6 }
"#;
        let err = Scene::parse(text, &dir.path().join("scene.toml")).unwrap_err();
        (dir, err)
    }

    #[test]
    fn a_cause_is_printed_once_and_not_chained() {
        let (dir, err) = with_image(b"\x89PNG\r\n\x1a\n");
        let super::SceneError::Value { key, cause, .. } = &err else {
            panic!("{err}");
        };
        assert_eq!(key, "silhouette.target[0].image");
        assert!(matches!(**cause, super::ValueError::Image(_)), "{cause:?}");
        let image = dir.path().join("target.png");
        let message = err.to_string();
        let want = format!(
            "scene `{}`: `silhouette.target[0].image`: `{}`: ",
            dir.path().join("scene.toml").display(),
            image.display()
        );
        assert!(message.starts_with(&want), "{message}");
        assert!(
            err.source().is_none(),
            "the cause is in the message: {message}"
        );
    }
}
