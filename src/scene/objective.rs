//! The `[[objective]]` tables of a multi-objective scene: what each objective measures,
//! resolved into an [`ObjectiveSet`], and the evaluator that measures whole populations.

use glam::Vec2;
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::optimize::multi::MultiEvaluator;
use shapegen_runtime::optimize::{EvaluateError, Sense};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{Objective, ObjectiveSet, ProjectionMatch, View};
use shapegen_runtime::{Genome, Grammar};

use super::file::ObjectiveFile;
use super::resolve::Resolver;
use super::{Scene, SceneError};

/// The kinds of objective a table may name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Height,
    UniqueNormals,
    NormalSpread,
    FootprintExcess,
    TopMatch,
    FrontMatch,
}

impl Kind {
    const ALL: [Kind; 6] = [
        Kind::Height,
        Kind::UniqueNormals,
        Kind::NormalSpread,
        Kind::FootprintExcess,
        Kind::TopMatch,
        Kind::FrontMatch,
    ];

    /// Its name in scene files.
    fn name(self) -> &'static str {
        match self {
            Kind::Height => "height",
            Kind::UniqueNormals => "unique_normals",
            Kind::NormalSpread => "normal_spread",
            Kind::FootprintExcess => "footprint_excess",
            Kind::TopMatch => "top_match",
            Kind::FrontMatch => "front_match",
        }
    }

    /// The keys it takes besides `kind` and `name`.
    fn keys(self) -> &'static [&'static str] {
        match self {
            Kind::Height => &["target"],
            Kind::UniqueNormals | Kind::NormalSpread => &["tolerance_deg"],
            Kind::FootprintExcess => &["min", "max"],
            Kind::TopMatch | Kind::FrontMatch => &["image", "min", "max"],
        }
    }
}

/// Default tolerance between normals counted as one, in degrees.
const TOLERANCE_DEG: f32 = 1.0;

impl Resolver<'_> {
    /// The objectives of `[[objective]]` tables, in order.
    pub(super) fn objectives(&self, files: &[ObjectiveFile]) -> Result<ObjectiveSet, SceneError> {
        let mut entries = Vec::with_capacity(files.len());
        for (i, file) in files.iter().enumerate() {
            let key = |k: &str| format!("objective[{i}].{k}");
            let Some(kind) = Kind::ALL.into_iter().find(|k| k.name() == file.kind) else {
                let valid: Vec<&str> = Kind::ALL.iter().map(|k| k.name()).collect();
                return Err(self.invalid(
                    key("kind"),
                    format!(
                        "\"{}\" is not an objective; the kinds are {}",
                        file.kind,
                        valid.join(", ")
                    ),
                ));
            };
            let given = [
                ("target", file.target.is_some()),
                ("tolerance_deg", file.tolerance_deg.is_some()),
                ("min", file.min.is_some()),
                ("max", file.max.is_some()),
                ("image", file.image.is_some()),
            ];
            let keys = kind.keys();
            if let Some((extra, _)) = given.iter().find(|(k, set)| *set && !keys.contains(k)) {
                return Err(self.invalid(
                    key(extra),
                    format!(
                        "is not used by kind \"{}\", which takes {}",
                        kind.name(),
                        keys.join(", ")
                    ),
                ));
            }
            let needed =
                |k: &str| self.invalid(key(k), format!("is needed by kind \"{}\"", kind.name()));
            let rect = || -> Result<(Vec2, Vec2), SceneError> {
                let min = file.min.ok_or_else(|| needed("min"))?;
                let max = file.max.ok_or_else(|| needed("max"))?;
                Ok((Vec2::from(min), Vec2::from(max)))
            };
            let tolerance_deg = file.tolerance_deg.unwrap_or(TOLERANCE_DEG);
            let objective = match kind {
                Kind::Height => Objective::Height {
                    target: file.target.ok_or_else(|| needed("target"))?,
                },
                Kind::UniqueNormals => Objective::UniqueNormals { tolerance_deg },
                Kind::NormalSpread => Objective::NormalSpread { tolerance_deg },
                Kind::FootprintExcess => {
                    let (min, max) = rect()?;
                    Objective::FootprintExcess { min, max }
                }
                Kind::TopMatch | Kind::FrontMatch => {
                    let view = if kind == Kind::TopMatch {
                        View::Top
                    } else {
                        View::Front
                    };
                    let written = file.image.as_deref().ok_or_else(|| needed("image"))?;
                    let path = self.file(&key("image"), written)?;
                    let image = image::open(&path)
                        .map_err(|err| {
                            self.invalid(key("image"), format!("`{}`: {err}", path.display()))
                        })?
                        .into_luma8();
                    let (min, max) = rect()?;
                    Objective::Projection(
                        ProjectionMatch::from_image(view, min, max, &image).map_err(|err| {
                            self.invalid(key("image"), shapegen_runtime::error_chain(&err))
                        })?,
                    )
                }
            };
            entries.push((
                file.name.clone().unwrap_or_else(|| kind.name().to_owned()),
                objective,
            ));
        }
        ObjectiveSet::new(entries)
            .map_err(|err| self.invalid("objective", shapegen_runtime::error_chain(&err)))
    }
}

/// Measures a multi-objective scene's objectives on whole populations of grammar `G`:
/// derives the genomes into one batch and measures it on the rayon pool. Its buffers are
/// kept between populations.
#[derive(Debug)]
pub struct ObjectiveEvaluator<'a> {
    set: &'a ObjectiveSet,
    meshes: BoundMeshes,
    batch: InstanceBatch,
}

impl<'a> ObjectiveEvaluator<'a> {
    /// The evaluator of `scene`'s objectives for grammar `G`, the scene's generator.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] when the scene has no objectives or its meshes lack one
    /// the grammar uses.
    pub fn new<G: Grammar>(scene: &'a Scene) -> Result<ObjectiveEvaluator<'a>, SceneError> {
        let goal = scene.objectives.as_ref().ok_or_else(|| {
            scene.invalid(
                "objective",
                "the scene has no [[objective]] tables to measure".into(),
            )
        })?;
        let meshes = scene
            .meshes
            .bind(G::GRAPH)
            .map_err(|err| scene.invalid("meshes", shapegen_runtime::error_chain(&err)))?;
        Ok(ObjectiveEvaluator {
            set: &goal.set,
            meshes,
            batch: InstanceBatch::new(),
        })
    }

    /// The objectives measured.
    pub fn set(&self) -> &'a ObjectiveSet {
        self.set
    }

    /// The grammar's meshes, bound.
    pub fn meshes(&self) -> &BoundMeshes {
        &self.meshes
    }
}

impl<G: Grammar> MultiEvaluator<G> for ObjectiveEvaluator<'_> {
    fn senses(&self) -> &[Sense] {
        self.set.senses()
    }

    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.batch.clear();
        for genome in genomes {
            self.batch.push_genome(genome);
        }
        self.set.measure_batch(&self.batch, &self.meshes, out);
        Ok(())
    }
}
