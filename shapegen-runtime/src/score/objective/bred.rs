//! Measuring bred children: projections counted from their parents' kept per-pixel
//! counts, the other objectives in full.

use super::kinds::Objective;
use super::retained::{ProjectionCounts, ProjectionScorer};
use super::set::ObjectiveSet;
use crate::derive::Grammar;
use crate::evaluate::Bred;
use crate::geometry::BoundMeshes;
use crate::score::batch::InstanceBatch;
use crate::score::retained::{Retention, RetentionStats};
use crate::score::scorer::Scorer;

/// Measures an [`ObjectiveSet`] on children bred from a population it measured: each
/// projection objective ([`ProjectionScorer`]) is counted from the kept state of the
/// child's parent through a [`Retention`], the other objectives on the child's whole
/// surface, as [`ObjectiveSet::measure_batch`] does. The values are exactly those of
/// `measure_batch`; memory is bounded as the retention's.
///
/// ```
/// use glam::Vec2;
/// use rand::SeedableRng;
/// use shapegen_runtime::evaluate::Bred;
/// use shapegen_runtime::prelude::*;
/// use shapegen_runtime::score::InstanceBatch;
/// use shapegen_runtime::score::objective::{BredObjectives, Objective, ObjectiveSet, ProjectionMatch, UniqueNormals, View};
/// use shapegen_runtime::MeshLibrary;
///
/// generator! {
///     /// A row of blocks.
///     pub Row {
///         axiom Block;
///         node Block {
///             params { width: f32 ~ uniform(0.5, 2.0) }
///             children { next: Block = 0.8 }
///             derive(s) {
///                 s.with_size(vec3(width, 1.0, 1.0)).emit(CUBE);
///                 if let Some(next) = next { s.translate(vec3(1.0, 0.0, 0.0)).derive(next); }
///             }
///         }
///     }
/// }
///
/// let mask: Vec<bool> = (0..256).map(|i| i % 16 < 8).collect();
/// let top = ProjectionMatch::new(View::Top, Vec2::splat(-4.0), Vec2::splat(4.0), 16, 16, &mask)?;
/// let set = ObjectiveSet::new(vec![
///     ("top".into(), Objective::from(top)),
///     ("facets".into(), Objective::UniqueNormals(UniqueNormals { tolerance_deg: 1.0 })),
/// ])?;
/// let meshes = MeshLibrary::new().bind(&Row::GRAPH)?;
/// let mut bred = BredObjectives::new(&set, &meshes).expect("the set has a projection");
///
/// let mut ops = shapegen_runtime::ops::Operators::<Row>::new(Limits::new(1, 10, 10)?)?;
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
/// let parents = vec![ops.random(4, &mut rng)];
/// let mut child = parents[0].clone();
/// ops.alter(&mut child, &mut rng);
/// let mut batch = InstanceBatch::new();
/// batch.push_genome(&child);
///
/// let mut values = [0.0; 2];
/// let children = [child];
/// let lineage = Bred { children: &children, parents: &parents, from: &[0] };
/// bred.measure_bred(lineage, &batch, &mut values);
/// let mut full = [0.0; 2];
/// set.measure_batch(&batch, &meshes, &mut full);
/// assert_eq!(values, full);
/// assert_eq!(bred.stats().incremental + bred.stats().full, 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct BredObjectives {
    set: ObjectiveSet,
    meshes: BoundMeshes,
    /// The set's projection objectives, in order.
    projections: Vec<ProjectionScorer>,
    retention: Retention<ProjectionScorer>,
    /// The last children's projection counts, one row per child.
    counts: Vec<ProjectionCounts>,
}

impl BredObjectives {
    /// Measures `set` on models made of `meshes`; `None` when `set` has no projection
    /// objective, the only kind counted from parents.
    pub fn new(set: &ObjectiveSet, meshes: &BoundMeshes) -> Option<BredObjectives> {
        let projections: Vec<ProjectionScorer> = set
            .entries()
            .iter()
            .filter_map(|(_, objective)| {
                let p = objective.projection()?;
                Some(ProjectionScorer::new(p.clone(), meshes.clone()))
            })
            .collect();
        (!projections.is_empty()).then(|| BredObjectives {
            set: set.clone(),
            meshes: meshes.clone(),
            projections,
            retention: Retention::new(),
            counts: Vec::new(),
        })
    }

    /// The objectives measured.
    pub fn set(&self) -> &ObjectiveSet {
        &self.set
    }

    /// Writes the values of the `children` of `bred` (whose instances are the models of
    /// `batch`, in order), child `i` bred from `parents[from[i]]`, to `out` as
    /// [`ObjectiveSet::measure_batch`] does (one row of [`len`](ObjectiveSet::len)
    /// values per child), with exactly its values. Afterwards only the states of
    /// `parents` and `children` are kept. The result does not depend on the number of
    /// threads, nor on what was kept.
    ///
    /// # Panics
    /// If the lengths disagree (`batch` and `from` one model per child, `out` one row
    /// per child) or an entry of `from` is out of range.
    pub fn measure_bred<G: Grammar>(
        &mut self,
        bred: Bred<'_, G>,
        batch: &InstanceBatch,
        out: &mut [f64],
    ) {
        let children = bred.children.len();
        let k = self.set.len();
        assert_eq!(out.len(), children * k, "one row of values per child");
        let p = self.projections.len();
        self.counts.clear();
        self.counts
            .resize(children * p, ProjectionCounts::default());
        self.retention
            .count_bred(&self.projections, bred, batch, &mut self.counts);
        let is_projection = |o: &Objective| o.projection().is_some();
        self.set
            .measure_rows(batch, &self.meshes, out, |o| !is_projection(o));
        for (row, counts) in out.chunks_exact_mut(k).zip(self.counts.chunks_exact(p)) {
            let slots = row
                .iter_mut()
                .zip(self.set.entries())
                .filter(|(_, (_, o))| is_projection(o));
            for ((slot, _), (scorer, counts)) in slots.zip(self.projections.iter().zip(counts)) {
                *slot = scorer.fitness(counts);
            }
        }
    }

    /// How the children of the calls so far were counted.
    pub fn stats(&self) -> RetentionStats {
        self.retention.stats()
    }

    /// Bytes of the states kept ([`Retention::memory`]).
    pub fn memory(&self) -> usize {
        self.retention.memory(&self.projections)
    }
}
