//! Named objectives measured together, over whole populations.

use rayon::prelude::*;

use super::error::ObjectiveError;
use super::kinds::Objective;
use super::scratch::ObjectiveScratch;
use super::surface::Surface;
use crate::evaluate::Sense;
use crate::geometry::{BoundMeshes, Instance};
use crate::score::batch::InstanceBatch;

/// The objectives of a search, each under the user's name for it: every model gets one
/// raw value per objective, in order.
///
/// ```
/// use glam::Affine3A;
/// use shapegen_runtime::evaluate::Sense;
/// use shapegen_runtime::score::objective::{Height, Objective, ObjectiveSet, UniqueNormals};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let set = ObjectiveSet::new(vec![
///     ("tall".into(), Objective::Height(Height { target: 3.0 })),
///     ("facets".into(), Objective::UniqueNormals(UniqueNormals { tolerance_deg: 1.0 })),
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

    pub(super) fn weighted_unchecked(&self, values: &[f64], weights: &[f64]) -> f64 {
        values
            .iter()
            .zip(weights)
            .zip(&self.senses)
            .map(|((&v, &w), s)| w * s.oriented(v))
            .sum()
    }
}
