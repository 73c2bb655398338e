//! Named objectives measured together, over whole populations.

use rayon::prelude::*;

use super::ObjectiveError;
use super::bred::BredObjectives;
use super::kind::{Objective, ObjectiveScratch};
use super::surface::Surface;
use crate::evaluate::{EvaluateError, Evaluator, Sense};
use crate::geometry::{BoundMeshes, Instance};
use crate::score::InstanceBatch;
use crate::{Genome, Grammar};

/// The objectives of a search, each under the user's name for it: every model gets one
/// raw value per objective, in order.
///
/// ```
/// use glam::Affine3A;
/// use shapegen_runtime::evaluate::Sense;
/// use shapegen_runtime::score::objective::{Objective, ObjectiveSet};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let set = ObjectiveSet::new(vec![
///     ("tall".into(), Objective::Height { target: 3.0 }),
///     ("facets".into(), Objective::UniqueNormals { tolerance_deg: 1.0 }),
/// ])?;
/// assert_eq!(set.senses(), [Sense::Minimize, Sense::Maximize]);
/// assert_eq!(set.names().collect::<Vec<_>>(), ["tall", "facets"]);
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let mut values = [0.0; 2];
/// set.measure(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes, &mut values);
/// assert_eq!(values, [2.5, 6.0]);
/// // One fitness from both: -1 * 2.5 + 0.5 * 6.
/// assert_eq!(set.weighted(&values, &[1.0, 0.5])?, 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectiveSet {
    entries: Vec<(String, Objective)>,
    senses: Vec<Sense>,
}

impl ObjectiveSet {
    /// A set of `entries` (name, objective), measured in this order.
    ///
    /// Fails when there is no entry, when a name is empty or given twice, or when an
    /// objective's parameters are invalid ([`Objective::validate`]; the error names the
    /// entry).
    pub fn new(entries: Vec<(String, Objective)>) -> Result<ObjectiveSet, ObjectiveError> {
        if entries.is_empty() {
            return Err(ObjectiveError::NoObjectives);
        }
        for (index, (name, objective)) in entries.iter().enumerate() {
            if name.is_empty() {
                return Err(ObjectiveError::EmptyName { index });
            }
            if entries[..index].iter().any(|(other, _)| other == name) {
                return Err(ObjectiveError::DuplicateName(name.clone()));
            }
            objective
                .validate()
                .map_err(|source| ObjectiveError::Entry {
                    name: name.clone(),
                    source: Box::new(source),
                })?;
        }
        let senses = entries.iter().map(|(_, o)| o.sense()).collect();
        Ok(ObjectiveSet { entries, senses })
    }

    /// The entries, in order.
    pub fn entries(&self) -> &[(String, Objective)] {
        &self.entries
    }

    /// Number of objectives (at least 1).
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the set has no objective (never: [`new`](Self::new) refuses that).
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Each objective's direction, in order.
    pub fn senses(&self) -> &[Sense] {
        &self.senses
    }

    /// Each objective's name, in order.
    pub fn names(&self) -> impl ExactSizeIterator<Item = &str> {
        self.entries.iter().map(|(n, _)| n.as_str())
    }

    /// Writes every objective's value for `surface` to `out` (one per objective).
    ///
    /// # Panics
    /// If `out.len() != self.len()`.
    pub fn measure_surface(
        &self,
        surface: &Surface,
        scratch: &mut ObjectiveScratch,
        out: &mut [f64],
    ) {
        assert_eq!(out.len(), self.len(), "one value slot per objective");
        self.measure_which(surface, scratch, out, |_| true);
    }

    /// Writes the values for `surface` of the objectives `which` accepts to their
    /// slots of `out`.
    fn measure_which(
        &self,
        surface: &Surface,
        scratch: &mut ObjectiveScratch,
        out: &mut [f64],
        which: impl Fn(&Objective) -> bool,
    ) {
        scratch.forget();
        for ((_, objective), slot) in self.entries.iter().zip(out) {
            if which(objective) {
                *slot = objective.measure_same(surface, scratch);
            }
        }
    }

    /// Writes every objective's value for the model made of `instances` to `out` (one
    /// per objective). Allocates its working memory; for many models use
    /// [`measure_batch`](Self::measure_batch) or [`measure_surface`](Self::measure_surface).
    ///
    /// # Panics
    /// If `out.len() != self.len()`.
    pub fn measure(&self, instances: &[Instance], meshes: &BoundMeshes, out: &mut [f64]) {
        let surface = Surface::from_instances(instances, meshes);
        self.measure_surface(&surface, &mut ObjectiveScratch::default(), out);
    }

    /// Measures every model of `batch` on the current rayon pool: model `i`'s values
    /// go to `out[i * k..(i + 1) * k]`, `k = self.len()`. The result does not depend on
    /// the number of threads.
    ///
    /// The models are dealt out in a few chunks per worker thread, each measured with
    /// one [`Surface`] and one scratch, as [`count_batch`](crate::score::count_batch)
    /// does.
    ///
    /// # Panics
    /// If `out.len() != batch.len() * self.len()`.
    pub fn measure_batch(&self, batch: &InstanceBatch, meshes: &BoundMeshes, out: &mut [f64]) {
        self.measure_rows(batch, meshes, out, |_| true);
    }

    /// [`measure_batch`](Self::measure_batch) for the objectives `which` accepts only:
    /// their slots of `out` are written, the others' left as they are, and nothing is
    /// done when it accepts none.
    ///
    /// # Panics
    /// If `out.len() != batch.len() * self.len()`.
    pub(super) fn measure_rows(
        &self,
        batch: &InstanceBatch,
        meshes: &BoundMeshes,
        out: &mut [f64],
        which: impl Fn(&Objective) -> bool + Sync,
    ) {
        let k = self.len();
        assert_eq!(out.len(), batch.len() * k, "one row of values per model");
        if !self.entries.iter().any(|(_, o)| which(o)) {
            return;
        }
        let chunks = 4 * rayon::current_num_threads();
        let chunk = batch.len().div_ceil(chunks).max(1);
        out.par_chunks_mut(chunk * k)
            .enumerate()
            .for_each(|(c, rows)| {
                let mut surface = Surface::new();
                let mut scratch = ObjectiveScratch::default();
                for (i, row) in rows.chunks_exact_mut(k).enumerate() {
                    surface.fill(batch.model(c * chunk + i), meshes);
                    self.measure_which(&surface, &mut scratch, row, &which);
                }
            });
    }

    /// One higher-is-better fitness from one model's `values`:
    /// `sum over i of weights[i] * senses[i].oriented(values[i])`, so that a single
    /// objective (one weight 1, the others 0) or a weighted combination can drive a
    /// single-objective search.
    ///
    /// Fails when `values` or `weights` do not have one entry per objective, or when a
    /// weight is not finite.
    pub fn weighted(&self, values: &[f64], weights: &[f64]) -> Result<f64, ObjectiveError> {
        self.check_weights(weights)?;
        if values.len() != self.len() {
            return Err(ObjectiveError::ValueCount {
                given: values.len(),
                expected: self.len(),
            });
        }
        Ok(self.weighted_unchecked(values, weights))
    }

    /// Checks that `weights` has one finite entry per objective.
    pub fn check_weights(&self, weights: &[f64]) -> Result<(), ObjectiveError> {
        if weights.len() != self.len() {
            return Err(ObjectiveError::WeightCount {
                given: weights.len(),
                expected: self.len(),
            });
        }
        if let Some((index, &value)) = weights.iter().enumerate().find(|(_, w)| !w.is_finite()) {
            return Err(ObjectiveError::Weight {
                name: self.entries[index].0.clone(),
                value,
            });
        }
        Ok(())
    }

    fn weighted_unchecked(&self, values: &[f64], weights: &[f64]) -> f64 {
        values
            .iter()
            .zip(weights)
            .zip(&self.senses)
            .map(|((&v, &w), s)| w * s.oriented(v))
            .sum()
    }
}

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
/// use shapegen_runtime::score::objective::{Objective, ObjectiveSet, WeightedObjectives};
/// use shapegen_runtime::MeshLibrary;
///
/// generator! {
///     /// A single block.
///     pub Block { axiom B; node B { derive(s) { s.emit(CUBE); } } }
/// }
///
/// let set = ObjectiveSet::new(vec![("tall".into(), Objective::Height { target: 1.5 })])?;
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
    /// parents' kept state when `lineage` (`parents`, `from`) is given and incremental
    /// counting is on.
    fn score<G: Grammar>(
        &mut self,
        genomes: &[Genome<G>],
        lineage: Option<(&[Genome<G>], &[u32])>,
        out: &mut [f64],
    ) {
        self.batch.set_genomes(genomes);
        let k = self.set.len();
        self.values.resize(genomes.len() * k, 0.0);
        match (&mut self.bred, lineage) {
            (Some(bred), Some((parents, from))) => {
                bred.measure_bred(genomes, &self.batch, parents, from, &mut self.values)
            }
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

    fn evaluate_bred(
        &mut self,
        genomes: &[Genome<G>],
        parents: &[Genome<G>],
        from: &[u32],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        self.score(genomes, Some((parents, from)), out);
        Ok(())
    }
}
