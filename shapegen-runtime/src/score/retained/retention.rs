//! The states kept for one search's current models, and counting bred children from
//! them.

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use rayon::prelude::*;

use super::cells::TILE_BYTES;
use super::diff::InstanceDiff;
use super::scorer::RetainedScorer;
use crate::derive::{Grammar, Site};
use crate::evaluate::Bred;
use crate::genome::Genome;
use crate::geometry::Instance;
use crate::score::batch::InstanceBatch;

/// What is kept of one model: its instances and each scorer's state.
struct Kept<S: RetainedScorer> {
    instances: Vec<Instance>,
    states: Vec<S::State>,
    /// The bytes it holds, counting what it shares with other models as its own.
    bound: usize,
}

impl<S: RetainedScorer> Kept<S> {
    fn new(scorers: &[S], instances: &[Instance], states: Vec<S::State>) -> Self {
        let mut bound = size_of_val(instances);
        for (scorer, state) in scorers.iter().zip(&states) {
            scorer.visit_cells(state, &mut |cells| bound += cells.bytes());
            scorer.visit_blocks(state, &mut |_, size| bound += size);
        }
        Kept {
            instances: instances.to_vec(),
            states,
            bound,
        }
    }
}

/// The default of [`Retention::with_max_bytes`]: 1 GiB.
pub const DEFAULT_MAX_BYTES: usize = 1 << 30;

/// How the children of the calls so far were counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RetentionStats {
    /// Children counted from their parent's state.
    pub incremental: u64,
    /// Children counted from nothing: no parent state, as many instances removed and
    /// added as the child has, or a count that overflowed.
    pub full: u64,
    /// Parents whose state was computed because none was kept.
    pub parents_counted: u64,
    /// Instances rasterized or voxelized for incremental children (removed and added).
    pub changed_instances: u64,
    /// Instances of the children counted incrementally.
    pub child_instances: u64,
}

impl RetentionStats {
    /// Counts one child of `instances` instances: from its parent with `changed`
    /// instances removed and added, or from nothing (`None`).
    pub(crate) fn count_child(&mut self, changed: Option<usize>, instances: usize) {
        match changed {
            Some(changed) => {
                self.incremental += 1;
                self.changed_instances += changed as u64;
                self.child_instances += instances as u64;
            }
            None => self.full += 1,
        }
    }
}

/// The states of the models a search currently holds, keyed by genome, for a list of
/// [`RetainedScorer`]s (one per scorer of a scene), and the counting of bred children
/// from them. See the [module documentation](super).
///
/// ```
/// use shapegen_runtime::evaluate::Bred;
/// use shapegen_runtime::score::retained::Retention;
/// use shapegen_runtime::score::volume::{Fill, Grid, VolumeScorer, VolumeTarget};
/// use shapegen_runtime::score::{Form, InstanceBatch, Scorer, count_batch};
/// use shapegen_runtime::prelude::*;
/// use shapegen_runtime::{Mesh, MeshLibrary};
/// use glam::Vec3;
/// use rand::SeedableRng;
///
/// generator! {
///     /// A chain of blocks.
///     pub Chain {
///         axiom Seg;
///         node Seg {
///             params { size: Vec3 ~ uniform([0.5, 0.5, 0.5], [1.5, 1.5, 1.5]) }
///             children { next: Seg = 0.8 }
///             derive(s) {
///                 let s = s.with_size(size);
///                 s.emit(CUBE);
///                 if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
///             }
///         }
///     }
/// }
///
/// let grid = Grid::new(Vec3::splat(-4.0), Vec3::splat(4.0), [32, 32, 32])?;
/// let target = VolumeTarget { name: "t".into(), mesh: Mesh::unit_cube(), inside: 1.0, outside: -1.0, fill: Fill::Parity };
/// let meshes = MeshLibrary::new().bind_names("Chain", &["cube"])?;
/// let scorer = VolumeScorer::new(grid, &[target], &meshes, Form::Smooth { good: 1.0, bad: 1.0 })?;
///
/// let mut ops = shapegen_runtime::ops::Operators::<Chain>::new(Limits::new(1, 20, 20)?)?;
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
/// let parents = vec![ops.random(6, &mut rng)];
/// let mut child = parents[0].clone();
/// ops.alter(&mut child, &mut rng);
/// let children = vec![child];
///
/// let mut batch = InstanceBatch::new();
/// batch.push_genome(&children[0]);
/// let mut retention = Retention::new();
/// let mut counts = [Default::default()];
/// let bred = Bred { children: &children, parents: &parents, from: &[0] };
/// retention.count_bred(&[scorer.clone()], bred, &batch, &mut counts);
/// let mut full = [Default::default()];
/// count_batch(&scorer, &batch, &mut full);
/// assert_eq!(counts, full);
/// assert_eq!(retention.stats().incremental + retention.stats().full, 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Retention<S: RetainedScorer> {
    kept: HashMap<u64, Arc<Kept<S>>>,
    max_bytes: usize,
    stats: RetentionStats,
}

impl<S: RetainedScorer> Default for Retention<S> {
    fn default() -> Self {
        Retention::new()
    }
}

impl<S: RetainedScorer> std::fmt::Debug for Retention<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Retention")
            .field("kept", &self.kept.len())
            .field("max_bytes", &self.max_bytes)
            .field("stats", &self.stats)
            .finish()
    }
}

/// One worker's memory: a scratch per scorer, a diff, a buffer of instances.
struct Worker<S: RetainedScorer> {
    scratch: Vec<S::Scratch>,
    diff: InstanceDiff,
    instances: Vec<Instance>,
}

impl<S: RetainedScorer> Worker<S> {
    fn new(scorers: &[S]) -> Self {
        Worker {
            scratch: scorers.iter().map(|s| s.scratch()).collect(),
            diff: InstanceDiff::default(),
            instances: Vec::new(),
        }
    }
}

/// What counting one child gave: its counts (one per scorer, written to the output)
/// and, when it could be kept, its state.
struct Counted<S: RetainedScorer> {
    kept: Option<Arc<Kept<S>>>,
    /// The instances removed and added when counted from the parent; `None` when
    /// counted from nothing.
    changed: Option<usize>,
}

impl<S: RetainedScorer> Retention<S> {
    /// No state kept yet, at most 1 GiB of states.
    pub fn new() -> Self {
        Retention {
            kept: HashMap::new(),
            max_bytes: DEFAULT_MAX_BYTES,
            stats: RetentionStats::default(),
        }
    }

    /// At most `bytes` of states kept (as [`memory`](Self::memory) measures them): once
    /// the kept states pass it, children are counted from their parents still, but not
    /// kept themselves.
    pub fn with_max_bytes(mut self, bytes: usize) -> Self {
        self.max_bytes = bytes;
        self
    }

    /// How the children of the calls so far were counted.
    pub fn stats(&self) -> RetentionStats {
        self.stats
    }

    /// Number of models whose state is kept.
    pub fn len(&self) -> usize {
        self.kept.len()
    }

    /// Whether no state is kept.
    pub fn is_empty(&self) -> bool {
        self.kept.is_empty()
    }

    /// Forgets every state.
    pub fn clear(&mut self) {
        self.kept.clear();
    }

    /// Bytes the kept states hold: instance lists, tile directories, and every tile and
    /// other block once, however many states share it.
    pub fn memory(&self, scorers: &[S]) -> usize {
        let mut tiles = HashSet::new();
        let mut blocks = HashMap::new();
        let mut bytes = 0;
        for kept in self.kept.values() {
            bytes += size_of_val(kept.instances.as_slice());
            for (scorer, state) in scorers.iter().zip(&kept.states) {
                scorer.visit_cells(state, &mut |cells| {
                    bytes += cells.directory_bytes();
                    tiles.extend(cells.tile_addresses());
                });
                scorer.visit_blocks(state, &mut |address, size| {
                    blocks.insert(address, size);
                });
            }
        }
        bytes + tiles.len() * TILE_BYTES + blocks.values().sum::<usize>()
    }

    /// An upper bound of [`memory`](Self::memory), counting shared tiles once per
    /// state, cheap enough to check every call.
    fn memory_bound(&self) -> usize {
        self.kept.values().map(|kept| kept.bound).sum()
    }

    /// Counts the `children` of `bred` (whose instances are the models of `batch`, in
    /// order) with each of `scorers`, child `i` bred from `parents[from[i]]`:
    /// `out[i * k + j]` gets child `i`'s counts of scorer `j`, `k = scorers.len()`,
    /// exactly as counting it from nothing would. Parents not kept are derived on the
    /// batch's [site](InstanceBatch::site). Afterwards only the states of `parents` and
    /// `children` are kept. The result does not depend on the number of threads, nor on
    /// what was kept.
    ///
    /// # Panics
    /// If the lengths disagree (`batch` and `from` one model per child, `out` `k` per
    /// child) or an entry of `from` is out of range.
    pub fn count_bred<G: Grammar>(
        &mut self,
        scorers: &[S],
        bred: Bred<'_, G>,
        batch: &InstanceBatch,
        out: &mut [S::Counts],
    ) {
        let Bred {
            children,
            parents,
            from,
        } = bred;
        let k = scorers.len();
        assert_eq!(batch.len(), children.len(), "one model per child");
        assert_eq!(from.len(), children.len(), "one parent per child");
        assert_eq!(out.len(), children.len() * k, "k counts per child");
        if k == 0 {
            self.kept.clear();
            return;
        }
        let parent_keys: Vec<u64> = parents.par_iter().map(genome_key).collect();
        let mut bases: Vec<Option<Arc<Kept<S>>>> = parent_keys
            .iter()
            .map(|key| self.kept.get(key).cloned())
            .collect();
        self.count_missing_parents(scorers, parents, batch.site(), from, &mut bases);
        let keep = self.memory_bound() <= self.max_bytes || self.memory(scorers) <= self.max_bytes;
        // One child at a time: a child counted from nothing costs far more than one
        // counted from its parent, so fixed chunks would leave threads idle.
        let counted: Vec<Counted<S>> = out
            .par_chunks_mut(k)
            .enumerate()
            .map_init(
                || Worker::new(scorers),
                |worker, (child, counts)| {
                    let base = &bases[from[child] as usize];
                    count_child(
                        scorers,
                        base.as_deref(),
                        batch.model(child),
                        keep,
                        worker,
                        counts,
                    )
                },
            )
            .collect();
        let child_keys: Vec<u64> = children.par_iter().map(genome_key).collect();
        let mut kept = HashMap::with_capacity(parents.len() + children.len());
        for (key, base) in parent_keys.into_iter().zip(bases) {
            if let Some(base) = base {
                kept.insert(key, base);
            }
        }
        for ((key, counted), model) in child_keys.into_iter().zip(counted).zip(0..) {
            self.stats
                .count_child(counted.changed, batch.model(model).len());
            if let Some(state) = counted.kept {
                kept.insert(key, state);
            }
        }
        // The states no longer kept are freed in parallel.
        let old = std::mem::replace(&mut self.kept, kept);
        old.into_par_iter().for_each(drop);
    }

    /// Computes the state of every parent that `from` names and `bases` lacks.
    fn count_missing_parents<G: Grammar>(
        &mut self,
        scorers: &[S],
        parents: &[Genome<G>],
        site: &Site,
        from: &[u32],
        bases: &mut [Option<Arc<Kept<S>>>],
    ) {
        let mut missing: Vec<u32> = from
            .iter()
            .copied()
            .filter(|&p| bases[p as usize].is_none())
            .collect();
        missing.sort_unstable();
        missing.dedup();
        let states: Vec<Option<Arc<Kept<S>>>> = missing
            .par_iter()
            .map_init(
                || Worker::new(scorers),
                |worker, &p| {
                    parents[p as usize].derive_on(site, &mut worker.instances);
                    full_state(scorers, &worker.instances, &mut worker.scratch).map(Arc::new)
                },
            )
            .collect();
        self.stats.parents_counted += missing.len() as u64;
        for (p, state) in missing.into_iter().zip(states) {
            bases[p as usize] = state;
        }
    }
}

/// Counts one child from `base` (or from nothing), writing one count per scorer to
/// `out`.
fn count_child<S: RetainedScorer>(
    scorers: &[S],
    base: Option<&Kept<S>>,
    instances: &[Instance],
    keep: bool,
    worker: &mut Worker<S>,
    out: &mut [S::Counts],
) -> Counted<S> {
    if let Some(base) = base {
        worker.diff.between(&base.instances, instances);
        let changed = worker.diff.len();
        if changed < instances.len().max(1) {
            let mut states = base.states.clone();
            let updated = scorers
                .iter()
                .zip(&mut states)
                .zip(&mut worker.scratch)
                .try_for_each(|((scorer, state), scratch)| {
                    let diff = &worker.diff;
                    scorer.update(state, diff.removed(), diff.added(), scratch)
                });
            if updated.is_ok() {
                for ((slot, scorer), state) in out.iter_mut().zip(scorers).zip(&states) {
                    *slot = scorer.state_counts(state);
                }
                let kept = keep.then(|| Arc::new(Kept::new(scorers, instances, states)));
                return Counted {
                    kept,
                    changed: Some(changed),
                };
            }
        }
    }
    let kept = match full_state(scorers, instances, &mut worker.scratch) {
        Some(kept) => {
            for ((slot, scorer), state) in out.iter_mut().zip(scorers).zip(&kept.states) {
                *slot = scorer.state_counts(state);
            }
            keep.then(|| Arc::new(kept))
        }
        None => {
            for ((slot, scorer), scratch) in out.iter_mut().zip(scorers).zip(&mut worker.scratch) {
                *slot = scorer.count(instances, scratch);
            }
            None
        }
    };
    Counted {
        kept,
        changed: None,
    }
}

/// The state of the model made of `instances` for every scorer, counted from nothing;
/// `None` when a count overflows.
fn full_state<S: RetainedScorer>(
    scorers: &[S],
    instances: &[Instance],
    scratch: &mut [S::Scratch],
) -> Option<Kept<S>> {
    let states = scorers
        .iter()
        .zip(scratch)
        .map(|(scorer, scratch)| scorer.count_retained(instances, scratch).ok())
        .collect::<Option<Vec<_>>>()?;
    Some(Kept::new(scorers, instances, states))
}

/// A 64-bit key of a genome's words, to find a parent's state: equal genomes have equal
/// keys. Two genomes sharing a key only cost work, never a wrong count, since a state is
/// always updated from the instances it was counted from.
pub(crate) fn genome_key<G: Grammar>(genome: &Genome<G>) -> u64 {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    let mix = |h: u64, w: u64| (h.rotate_left(23) ^ w).wrapping_mul(K);
    let words = genome.words();
    // Four lanes of two words each, independent of one another, so that the processor
    // overlaps their multiplications.
    let mut lanes = [1, 2, 3, 4].map(|i: u64| (genome.len() as u64 + i).wrapping_mul(K));
    let mut chunks = words.chunks_exact(8);
    for chunk in &mut chunks {
        for (lane, pair) in lanes.iter_mut().zip(chunk.chunks_exact(2)) {
            *lane = mix(*lane, u64::from(pair[0]) | u64::from(pair[1]) << 32);
        }
    }
    for (i, &w) in chunks.remainder().iter().enumerate() {
        lanes[i % 4] = mix(lanes[i % 4], u64::from(w) ^ 1 << 63);
    }
    let h = lanes.iter().enumerate().fold(0u64, |h, (i, &lane)| {
        mix(h, lane.rotate_left(16 * i as u32))
    });
    h ^ h >> 29
}
