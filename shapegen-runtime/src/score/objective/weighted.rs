//! [`WeightedObjectives`]: an evaluator whose fitness is a weighted sum of objectives.

use super::bred::BredObjectives;
use super::error::ObjectiveError;
use super::set::ObjectiveSet;
use crate::derive::Grammar;
use crate::evaluate::{Bred, EvaluateError, Evaluator};
use crate::genome::Genome;
use crate::geometry::BoundMeshes;
use crate::score::batch::InstanceBatch;

/// An [`Evaluator`] whose fitness is an [`ObjectiveSet`]'s [weighted](ObjectiveSet::weighted)
/// sum: drives a single-objective search (the GA, SMC, MCMC) with one objective or a
/// weighted combination. Its buffers are kept between populations, and children bred
/// from a scored population ([`evaluate_bred`](Evaluator::evaluate_bred)) have their
/// projection objectives counted from their parents' kept state ([`BredObjectives`]),
/// unless [`with_incremental(false)`](Self::with_incremental).
///
/// ```
/// use shapegen_runtime::evaluate::Evaluator;
/// use shapegen_runtime::prelude::*;
/// use shapegen_runtime::score::objective::{Height, Objective, ObjectiveSet, WeightedObjectives};
/// use shapegen_runtime::MeshLibrary;
///
/// generator! {
///     /// A single block.
///     pub Block { axiom B; node B { derive(s) { s.emit(CUBE); } } }
/// }
///
/// let set = ObjectiveSet::new(vec![("tall".into(), Objective::Height(Height { target: 1.5 }))])?;
/// let meshes = MeshLibrary::new().bind(&Block::GRAPH)?;
/// let mut evaluator = WeightedObjectives::new(set, vec![1.0], meshes)?;
/// let genomes = [Genome::<Block>::axiom(&mut rand::rng())];
/// let mut fitness = [0.0];
/// evaluator.evaluate(&genomes, &mut fitness)?;
/// assert_eq!(fitness, [-1.0]); // the block's top is at 0.5, 1 below the target
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct WeightedObjectives {
    set: ObjectiveSet,
    weights: Vec<f64>,
    meshes: BoundMeshes,
    batch: InstanceBatch,
    values: Vec<f64>,
    bred: Option<BredObjectives>,
}

impl WeightedObjectives {
    /// Scores models made of `meshes` by `set`'s weighted sum with `weights` (one
    /// finite weight per objective).
    pub fn new(
        set: ObjectiveSet,
        weights: Vec<f64>,
        meshes: BoundMeshes,
    ) -> Result<WeightedObjectives, ObjectiveError> {
        set.check_weights(&weights)?;
        Ok(WeightedObjectives {
            bred: BredObjectives::new(&set, &meshes),
            set,
            weights,
            meshes,
            batch: InstanceBatch::new(),
            values: Vec::new(),
        })
    }

    /// The objectives.
    pub fn set(&self) -> &ObjectiveSet {
        &self.set
    }

    /// Whether bred children's projection objectives are counted from their parents'
    /// kept state (the default).
    pub fn with_incremental(mut self, incremental: bool) -> Self {
        self.bred = incremental
            .then(|| BredObjectives::new(&self.set, &self.meshes))
            .flatten();
        self
    }

    /// What counts bred children incrementally: `None` when that is off or the set has
    /// no projection objective.
    pub fn bred(&self) -> Option<&BredObjectives> {
        self.bred.as_ref()
    }

    /// The raw values of the last population evaluated, row by row (one row of
    /// [`len`](ObjectiveSet::len) values per genome).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Writes the fitness of `genomes` to `out`, counting their projections from their
    /// parents' kept state when `lineage` (of which `genomes` are the children) is given
    /// and incremental counting is on.
    fn score<G: Grammar>(
        &mut self,
        genomes: &[Genome<G>],
        lineage: Option<Bred<'_, G>>,
        out: &mut [f64],
    ) {
        self.batch.set_genomes(genomes);
        let k = self.set.len();
        self.values.resize(genomes.len() * k, 0.0);
        match (&mut self.bred, lineage) {
            (Some(kept), Some(bred)) => kept.measure_bred(bred, &self.batch, &mut self.values),
            _ => self
                .set
                .measure_batch(&self.batch, &self.meshes, &mut self.values),
        }
        for (slot, row) in out.iter_mut().zip(self.values.chunks_exact(k)) {
            *slot = self.set.weighted_unchecked(row, &self.weights);
        }
    }
}

impl<G: Grammar> Evaluator<G> for WeightedObjectives {
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.score(genomes, None, out);
        Ok(())
    }

    fn evaluate_bred(&mut self, bred: Bred<'_, G>, out: &mut [f64]) -> Result<(), EvaluateError> {
        self.score(bred.children, Some(bred), out);
        Ok(())
    }
}
