//! The `[[objective]]` tables of a multi-objective scene: what each objective measures,
//! resolved into an [`ObjectiveSet`], and the evaluator that measures whole populations.

use image::GrayImage;
use shapegen_runtime::geometry::BoundMeshes;
use shapegen_runtime::geometry::PointCloud;
use shapegen_runtime::optimize::multi::MultiEvaluator;
use shapegen_runtime::optimize::{Bred, EvaluateError, Sense};
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::objective::{
    BredObjectives, ObjectiveError, ObjectiveFile, ObjectiveSet, ObjectiveSource,
};
use shapegen_runtime::score::retained::RetentionStats;
use shapegen_runtime::{Genome, Grammar};

use super::error::{SceneError, ValueError};
use super::image::read_image;
use super::loaded::Scene;
use super::resolve::Resolver;

impl Resolver<'_> {
    /// The objectives of `[[objective]]` tables, in order, for a generator whose meshes
    /// are named `meshes` (in id order): the parts objectives name are resolved
    /// against those. Each table is read as its kind's, by the runtime's table of kinds
    /// ([`ObjectiveFile`]); errors name the table and its key (`objective[i].key`).
    pub(super) fn objectives(
        &self,
        tables: Vec<toml::Table>,
        meshes: &[&str],
    ) -> Result<ObjectiveSet, SceneError> {
        let mut entries = Vec::with_capacity(tables.len());
        for (index, table) in tables.into_iter().enumerate() {
            let (name, file) = self.objective_file(index, table)?;
            let table = ObjectiveTable {
                resolver: self,
                index,
                name: name.unwrap_or_else(|| file.name().to_owned()),
                meshes,
            };
            let objective = file.resolve(&table)?;
            entries.push((table.name, objective));
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
}

/// The `index`th `[[objective]]` table of a scene, as the runtime's kinds read it: its
/// files resolved against the scene's folder, its errors naming `objective[index].key`.
struct ObjectiveTable<'r, 'a> {
    resolver: &'r Resolver<'a>,
    index: usize,
    /// The table's `name`, else its kind's.
    name: String,
    /// The names of the generator's meshes, in id order.
    meshes: &'r [&'r str],
}

impl ObjectiveTable<'_, '_> {
    /// The key `field` of the table, as errors name it.
    fn key(&self, field: &str) -> String {
        format!("objective[{}].{field}", self.index)
    }
}

impl ObjectiveSource for ObjectiveTable<'_, '_> {
    type Error = SceneError;

    fn name(&self) -> &str {
        &self.name
    }

    fn meshes(&self) -> &[&str] {
        self.meshes
    }

    fn image(&self, field: &str, path: &str) -> Result<GrayImage, SceneError> {
        let key = self.key(field);
        let path = self.resolver.file(&key, path)?;
        let image = read_image(&path).map_err(|err| self.resolver.refused(&key, err))?;
        Ok(image.into_luma8())
    }

    fn point_cloud(&self, field: &str, path: &str) -> Result<PointCloud, SceneError> {
        let key = self.key(field);
        let path = self.resolver.file(&key, path)?;
        PointCloud::load(&path).map_err(|err| self.resolver.refused(&key, err))
    }

    fn refused(&self, field: &str, error: ObjectiveError) -> SceneError {
        self.resolver.refused(self.key(field), error)
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

    fn evaluate_bred(&mut self, bred: Bred<'_, G>, out: &mut [f64]) -> Result<(), EvaluateError> {
        self.batch.set_genomes(bred.children);
        match &mut self.bred {
            Some(kept) => kept.measure_bred(bred, &self.batch, out),
            None => self.set.measure_batch(&self.batch, &self.meshes, out),
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use shapegen_runtime::score::objective::Objective;

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

    #[test]
    fn the_kinds_a_table_may_name_are_the_runtimes_in_its_order() {
        assert_eq!(kinds(), Objective::NAMES);
    }

    #[test]
    fn unnamed_objectives_take_their_kinds_name() {
        let tables = [
            "kind = \"height\"\ntarget = 2",
            "kind = \"roof_pitch\"\ntarget_deg = 35",
        ]
        .map(|t| toml::from_str(t).unwrap());
        let path = std::path::Path::new("scene.toml");
        let set = Resolver::new(path, &crate::scene::sources::Sources::new())
            .objectives(tables.into(), &["cube", "roof"])
            .unwrap();
        let names: Vec<&str> = set.names().collect();
        assert_eq!(names, ["height", "roof_pitch"]);
    }
}
