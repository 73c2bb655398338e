//! The `[[objective]]` tables of a multi-objective scene: what each objective measures,
//! resolved into an [`ObjectiveSet`], and the evaluator that measures whole populations.

use glam::Vec2;
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::geometry::PointCloud;
use shapegen_runtime::optimize::multi::MultiEvaluator;
use shapegen_runtime::optimize::{EvaluateError, Sense};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{
    BredObjectives, ChamferMatch, Objective, ObjectiveError, ObjectiveSet, Parts, ProjectionMatch,
    View,
};
use shapegen_runtime::score::retained::RetentionStats;
use shapegen_runtime::{Genome, Grammar};

use super::error::{SceneError, ValueError};
use super::file::{ObjectiveFile, ProjectionFile};
use super::image::read_image;
use super::loaded::Scene;
use super::resolve::Resolver;

impl Resolver<'_> {
    /// The objectives of `[[objective]]` tables, in order, for a generator whose meshes
    /// are named `meshes` (in id order): the parts objectives name are resolved
    /// against those.
    pub(super) fn objectives(
        &self,
        tables: Vec<toml::Table>,
        meshes: &[&str],
    ) -> Result<ObjectiveSet, SceneError> {
        let mut entries = Vec::with_capacity(tables.len());
        for (i, table) in tables.into_iter().enumerate() {
            let (name, file) = self.objective_file(i, table)?;
            let image = format!("objective[{i}].image");
            // The meshes of `field`, an error naming the table, its objective and the
            // field.
            let parts = |field: &str, wanted: &[String], kind: &str| {
                Parts::named(wanted, meshes).map_err(|err| {
                    self.refused(
                        format!("objective[{i}].{field}"),
                        ObjectiveError::Entry {
                            name: name.clone().unwrap_or_else(|| kind.to_owned()),
                            source: Box::new(err),
                        },
                    )
                })
            };
            // One arm per kind.
            let objective = match file {
                ObjectiveFile::Height { target } => Objective::Height { target },
                ObjectiveFile::UniqueNormals { tolerance_deg } => {
                    Objective::UniqueNormals { tolerance_deg }
                }
                ObjectiveFile::NormalSpread { tolerance_deg } => {
                    Objective::NormalSpread { tolerance_deg }
                }
                ObjectiveFile::FootprintExcess { min, max } => Objective::FootprintExcess {
                    min: Vec2::from(min),
                    max: Vec2::from(max),
                },
                ObjectiveFile::TopMatch(p) => self.projection(&image, View::Top, &p)?,
                ObjectiveFile::FrontMatch(p) => self.projection(&image, View::Front, &p)?,
                ObjectiveFile::Chamfer { points, samples } => {
                    self.chamfer(&format!("objective[{i}]"), &points, samples)?
                }
                ObjectiveFile::AreaShare {
                    parts: p,
                    of,
                    target,
                } => Objective::AreaShare {
                    parts: parts("parts", &p, "area_share")?,
                    of: of.map(|of| parts("of", &of, "area_share")).transpose()?,
                    target,
                },
                ObjectiveFile::RoofPitch {
                    parts: p,
                    target_deg,
                } => Objective::RoofPitch {
                    parts: parts("parts", &p, "roof_pitch")?,
                    target_deg,
                },
            };
            entries.push((
                name.unwrap_or_else(|| objective.name().to_owned()),
                objective,
            ));
        }
        ObjectiveSet::new(entries).map_err(|err| self.refused("objective", err))
    }

    /// The `name` of the `i`th `[[objective]]` table, and the rest read as its kind's.
    fn objective_file(
        &self,
        i: usize,
        mut table: toml::Table,
    ) -> Result<(Option<String>, ObjectiveFile), SceneError> {
        let name = table
            .remove("name")
            .map(toml::Value::try_into::<String>)
            .transpose()
            .map_err(|err| self.refused(format!("objective[{i}].name"), ValueError::Toml(err)))?;
        let kind = table
            .get("kind")
            .and_then(toml::Value::as_str)
            .map(str::to_owned);
        let file = toml::Value::Table(table)
            .try_into()
            .map_err(|err: toml::de::Error| {
                // serde's message names the key and what is valid; this adds the table, and
                // the kind whose keys they are.
                match kind {
                    _ if err.message().starts_with("unknown variant") => {
                        self.refused(format!("objective[{i}].kind"), ValueError::Toml(err))
                    }
                    Some(kind) => self.refused(
                        format!("objective[{i}]"),
                        ValueError::ObjectiveKey { kind, error: err },
                    ),
                    None => self.refused(format!("objective[{i}]"), ValueError::Toml(err)),
                }
            })?;
        Ok((name, file))
    }

    /// A Chamfer objective toward the point cloud `points` of the table `key`.
    fn chamfer(&self, key: &str, points: &str, samples: usize) -> Result<Objective, SceneError> {
        let points_key = format!("{key}.points");
        let path = self.file(&points_key, points)?;
        let cloud = PointCloud::load(&path).map_err(|err| self.refused(&points_key, err))?;
        let chamfer = ChamferMatch::new(&cloud, samples)
            .map_err(|err| self.refused(format!("{key}.samples"), err))?;
        Ok(Objective::Chamfer(chamfer))
    }

    /// A projection objective through `view`, its image read as `key`.
    fn projection(
        &self,
        key: &str,
        view: View,
        p: &ProjectionFile,
    ) -> Result<Objective, SceneError> {
        let path = self.file(key, &p.image)?;
        let image = read_image(&path)
            .map_err(|err| self.refused(key, err))?
            .into_luma8();
        let (min, max) = (Vec2::from(p.min), Vec2::from(p.max));
        let projection = ProjectionMatch::from_image(view, min, max, &image)
            .map_err(|err| self.refused(key, err))?;
        Ok(Objective::Projection(projection))
    }
}

/// Measures a multi-objective scene's objectives on whole populations of grammar `G`:
/// derives the genomes into one batch and measures it on the rayon pool. Its buffers are
/// kept between populations.
///
/// Children bred from a measured population
/// ([`evaluate_bred`](MultiEvaluator::evaluate_bred)) have their projection objectives
/// counted from what was kept of their parents ([`BredObjectives`]), with exactly the
/// values of measuring them in full; [`with_incremental(false)`](Self::with_incremental)
/// measures every child in full.
#[derive(Debug)]
pub struct ObjectiveEvaluator<'a> {
    set: &'a ObjectiveSet,
    meshes: BoundMeshes,
    batch: InstanceBatch,
    bred: Option<BredObjectives>,
}

impl<'a> ObjectiveEvaluator<'a> {
    /// The evaluator of `scene`'s objectives for grammar `G`, the scene's generator,
    /// counting bred children incrementally where it can.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] when the scene has no objectives, [`SceneError::Value`]
    /// when its meshes lack one the grammar uses.
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
            .map_err(|err| scene.refused("meshes", err))?;
        Ok(ObjectiveEvaluator {
            set: &goal.set,
            bred: BredObjectives::new(&goal.set, &meshes),
            meshes,
            batch: InstanceBatch::new().on_site(scene.site.clone()),
        })
    }

    /// Whether bred children's projection objectives are counted from their parents'
    /// kept state (the default).
    pub fn with_incremental(mut self, incremental: bool) -> Self {
        self.bred = incremental
            .then(|| BredObjectives::new(self.set, &self.meshes))
            .flatten();
        self
    }

    /// Whether some objective of bred children is counted incrementally: incremental
    /// counting is on and the scene has a projection objective.
    pub fn incremental(&self) -> bool {
        self.bred.is_some()
    }

    /// How the bred children's projection objectives were counted so far, and the bytes
    /// of state kept now; `None` when nothing is counted incrementally.
    pub fn retention(&self) -> Option<(RetentionStats, usize)> {
        let bred = self.bred.as_ref()?;
        Some((bred.stats(), bred.memory()))
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
        self.batch.set_genomes(genomes);
        self.set.measure_batch(&self.batch, &self.meshes, out);
        Ok(())
    }

    fn evaluate_bred(
        &mut self,
        genomes: &[Genome<G>],
        parents: &[Genome<G>],
        from: &[u32],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        self.batch.set_genomes(genomes);
        match &mut self.bred {
            Some(bred) => bred.measure_bred(genomes, &self.batch, parents, from, out),
            None => self.set.measure_batch(&self.batch, &self.meshes, out),
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kinds a table may name, as serde lists them when refusing an unknown one.
    fn kinds() -> Vec<String> {
        let table: toml::Table = toml::from_str("kind = \"?\"").unwrap();
        let err = toml::Value::Table(table)
            .try_into::<ObjectiveFile>()
            .unwrap_err();
        let message = err.message();
        let (_, listed) = message.split_once("expected one of ").expect(message);
        listed
            .split(", ")
            .map(|k| k.trim_matches('`').to_owned())
            .collect()
    }

    /// A table of `kind` with the keys it needs; `image.png` is a 4 x 4 image and
    /// `scan.xyz` a cloud of two points.
    fn table(kind: &str) -> toml::Table {
        let keys = match kind {
            "height" => "target = 2",
            "unique_normals" | "normal_spread" => "",
            "footprint_excess" => "min = [-1, -1]\nmax = [1, 1]",
            "top_match" | "front_match" => "image = \"image.png\"\nmin = [-1, -1]\nmax = [1, 1]",
            "chamfer" => "points = \"scan.xyz\"",
            "area_share" => "parts = [\"window\"]\nof = [\"wall\", \"window\"]\ntarget = 0.4",
            "roof_pitch" => "target_deg = 35",
            _ => panic!("give a table of the new kind `{kind}` here"),
        };
        toml::from_str(&format!("kind = \"{kind}\"\n{keys}")).unwrap()
    }

    #[test]
    fn the_kinds_are_named_as_the_runtime_names_them() {
        let dir = tempfile::tempdir().unwrap();
        image::GrayImage::from_fn(4, 4, |x, _| image::Luma([if x < 2 { 0 } else { 255 }]))
            .save(dir.path().join("image.png"))
            .unwrap();
        std::fs::write(dir.path().join("scan.xyz"), "0 0 0\n1 1 1\n").unwrap();
        let path = dir.path().join("scene.toml");
        let kinds = kinds();
        assert!(kinds.len() > 1, "{kinds:?}");
        let set = Resolver::new(&path, &crate::scene::sources::Sources::new())
            .objectives(
                kinds.iter().map(|k| table(k)).collect(),
                &["cube", "wall", "roof", "window"],
            )
            .unwrap();
        for (kind, (name, objective)) in kinds.iter().zip(set.entries()) {
            assert_eq!(objective.name(), kind);
            assert_eq!(name, kind, "unnamed objectives take their kind's name");
        }
    }
}
