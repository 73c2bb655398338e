//! A population's models, back to back, and counting them all in parallel.

use rayon::prelude::*;

use super::scorer::Scorer;
use crate::derive::{Grammar, Site};
use crate::genome::Genome;
use crate::geometry::Instance;

/// The instances of many models in one buffer: model `i` is
/// `instances[starts[i]..starts[i + 1]]`. Reused from generation to generation, it
/// allocates only when a population outgrows it. Genomes are derived on the batch's
/// [`site`](Self::site), [`Site::NONE`] unless [set](Self::on_site).
///
/// ```
/// use shapegen_runtime::score::InstanceBatch;
/// use shapegen_runtime::{CUBE, Instance};
/// use glam::Affine3A;
///
/// let cube = Instance { transform: Affine3A::IDENTITY, mesh: CUBE };
/// let mut batch = InstanceBatch::new();
/// batch.push_with(|out| out.push(cube));
/// batch.push_with(|out| out.extend([cube, cube]));
/// assert_eq!(batch.len(), 2);
/// assert_eq!(batch.model(1).len(), 2);
/// assert_eq!(batch.instances().len(), 3);
/// ```
#[derive(Clone, Debug, Default)]
pub struct InstanceBatch {
    instances: Vec<Instance>,
    starts: Vec<u32>,
    site: Site,
    /// Scratch of [`set_genomes`](Self::set_genomes): each chunk's instances and model
    /// lengths, derived in parallel.
    chunks: Vec<(Vec<Instance>, Vec<u32>)>,
}

impl InstanceBatch {
    /// An empty batch.
    pub fn new() -> Self {
        InstanceBatch {
            instances: Vec::new(),
            starts: vec![0],
            site: Site::NONE,
            chunks: Vec::new(),
        }
    }

    /// The batch, empty, deriving its genomes on `site` from now on.
    pub fn on_site(self, site: Site) -> Self {
        let mut batch = self;
        batch.clear();
        InstanceBatch { site, ..batch }
    }

    /// The site the batch derives genomes on.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// Empties the batch, keeping its memory.
    pub fn clear(&mut self) {
        self.instances.clear();
        self.starts.clear();
        self.starts.push(0);
    }

    /// Appends one model, whose instances `write` appends to the buffer it is given
    /// (for example `|out| genome.derive_append(out)`, which is what
    /// [`push_genome`](Self::push_genome) does).
    pub fn push_with(&mut self, write: impl FnOnce(&mut Vec<Instance>)) {
        self.open_model();
        write(&mut self.instances);
        self.close_model();
    }

    /// Appends the model `genome` derives into on the batch's site.
    pub fn push_genome<G: Grammar>(&mut self, genome: &Genome<G>) {
        self.open_model();
        genome.derive_append_on(&self.site, &mut self.instances);
        self.close_model();
    }

    /// Starts a model: makes sure the first start is recorded.
    fn open_model(&mut self) {
        if self.starts.is_empty() {
            self.starts.push(0);
        }
    }

    /// Ends the model whose instances were appended since [`open_model`](Self::open_model).
    fn close_model(&mut self) {
        let end =
            u32::try_from(self.instances.len()).expect("a batch holds fewer than 2^32 instances");
        self.starts.push(end);
    }

    /// Empties the batch, keeping its memory, and appends the model each of `genomes`
    /// derives into, in order: a population's batch for an evaluator. The genomes are
    /// derived in parallel, a few chunks per worker thread, on the current rayon pool.
    pub fn set_genomes<G: Grammar>(&mut self, genomes: &[Genome<G>]) {
        self.clear();
        let chunk = genomes
            .len()
            .div_ceil(4 * rayon::current_num_threads())
            .max(1);
        self.chunks
            .resize_with(genomes.len().div_ceil(chunk), Default::default);
        let site = &self.site;
        self.chunks
            .par_iter_mut()
            .zip(genomes.par_chunks(chunk))
            .for_each(|((instances, lengths), genomes)| {
                instances.clear();
                lengths.clear();
                for genome in genomes {
                    let start = instances.len();
                    genome.derive_append_on(site, instances);
                    lengths.push((instances.len() - start) as u32);
                }
            });
        for (instances, lengths) in &self.chunks {
            let mut start = self.instances.len();
            self.instances.extend_from_slice(instances);
            for &n in lengths {
                start += n as usize;
                self.starts
                    .push(u32::try_from(start).expect("a batch holds fewer than 2^32 instances"));
            }
        }
    }

    /// Number of models.
    pub fn len(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// Whether the batch holds no model.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The instances of model `index`.
    ///
    /// # Panics
    /// If `index >= self.len()`.
    pub fn model(&self, index: usize) -> &[Instance] {
        let (start, end) = (self.starts[index], self.starts[index + 1]);
        &self.instances[start as usize..end as usize]
    }

    /// Every model's instances, back to back.
    pub fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// Where each model starts in [`instances`](Self::instances), followed by the total.
    pub fn starts(&self) -> &[u32] {
        &self.starts
    }
}

/// Counts every model of `batch` with `scorer` on the current rayon pool, writing model
/// `i`'s counts to `out[i]`. The result does not depend on the number of threads.
///
/// The models are dealt out in a few chunks per worker thread, each counted with one
/// scratch buffer, so a batch allocates a handful of scratch buffers however many models
/// it holds.
///
/// # Panics
/// If `out.len() != batch.len()`.
pub fn count_batch<S: Scorer>(scorer: &S, batch: &InstanceBatch, out: &mut [S::Counts]) {
    assert_eq!(out.len(), batch.len(), "one counts slot per model");
    let chunks = 4 * rayon::current_num_threads();
    let chunk = out.len().div_ceil(chunks).max(1);
    out.par_chunks_mut(chunk)
        .enumerate()
        .for_each(|(c, slots)| {
            let mut scratch = scorer.scratch();
            for (i, slot) in slots.iter_mut().enumerate() {
                *slot = scorer.count(batch.model(c * chunk + i), &mut scratch);
            }
        });
}
