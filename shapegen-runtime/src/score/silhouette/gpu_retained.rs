//! Counting bred children on the GPU from what the GPU kept of their parents.
//!
//! [`GpuRetention`] keeps, in the GPU's memory, a *slot* for each model of a search's
//! current population: how many triangle fragments of the model's instances hit each
//! pixel of each target ([`shapegen_shaders::SILHOUETTE_RETAINED`]). A child bred from a
//! parent is counted by copying the parent's slot and drawing only the instances the child
//! lost (subtracting) and gained (adding); the fragment that takes a pixel from 0 to 1, or
//! from 1 to 0, changes the child's counts. Only the changed instances are uploaded and
//! drawn, and the counts are exactly those of drawing the child from nothing, since the
//! same instances give the same fragments (the vertex stage is [`GpuSilhouetteScorer`]'s,
//! with an invariant position).

use std::collections::{HashMap, HashSet};
use std::ops::Range;
use std::sync::Arc;

use bytemuck::{Pod, Zeroable};

use super::counts::{SilhouetteCounts, TargetCounts};
use super::gpu::GpuSilhouetteScorer;
use super::gpu_draw::{Counters, Passes, Program, TargetIndex, View, counter_bytes, rows};
use crate::derive::{Grammar, Site};
use crate::evaluate::Bred;
use crate::genome::Genome;
use crate::geometry::Instance;
use crate::gpu::GpuError;
use crate::score::batch::InstanceBatch;
use crate::score::retained::{InstanceDiff, RetentionStats, genome_key};

/// Mirrors the WGSL struct `Params` of [`shapegen_shaders::SILHOUETTE_RETAINED`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Params {
    view: View,
    /// Words from the start of a slot to this target's image, and words per slot.
    image_offset: u32,
    slot_words: u32,
    /// The first slot of the bound page.
    first_slot: u32,
    index: TargetIndex,
}
const _: () = assert!(size_of::<Params>() == 96);

/// One instance to draw into a slot: the rows of its transform, the entry whose counts
/// it changes, its slot, and whether it is taken away (1) or added (0).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GpuInstance {
    rows: [[f32; 4]; 3],
    entry: u32,
    slot: u32,
    removed: u32,
    _pad: u32,
}
const _: () = assert!(size_of::<GpuInstance>() == 64);

/// Most slots of one page (one buffer), whatever the binding limit: pages are allocated
/// as slots are needed, so that a small search holds little more than it uses.
const MAX_PAGE_SLOTS: u64 = 64;

/// The default of [`GpuRetention::with_max_bytes`]: 1 GiB of slots.
const DEFAULT_MAX_BYTES: u64 = 1 << 30;

/// What is kept of one model: its instances, its slot and its counts.
struct Kept {
    instances: Vec<Instance>,
    slot: u32,
    counts: SilhouetteCounts,
}

/// One model to count in a submission: into `slot`, which starts as a copy of the slot
/// `from` (or empty), with the instances `removed` taken away and `added` drawn.
struct Draw<'a> {
    slot: u32,
    from: Option<u32>,
    removed: &'a [Instance],
    added: &'a [Instance],
}

impl<'a> Draw<'a> {
    /// The draw of a child into `slot`: the changes `diff` from the kept parent `base`,
    /// or the whole `model` when it is counted from nothing.
    fn of(slot: u32, base: Option<&Kept>, diff: &'a InstanceDiff, model: &'a [Instance]) -> Self {
        match base {
            Some(base) => Draw {
                slot,
                from: Some(base.slot),
                removed: diff.removed(),
                added: diff.added(),
            },
            None => Draw {
                slot,
                from: None,
                removed: &[],
                added: model,
            },
        }
    }
}

/// The states a search keeps on the GPU for its current models, keyed by genome, and
/// the counting of bred children from them: the GPU counterpart of
/// [`Retention`](crate::score::retained::Retention) for one silhouette scorer.
///
/// The counts equal [`GpuSilhouetteScorer::count_batch`]'s, and do not depend on what
/// was kept: a child whose parent has no slot, or for which no slot is left (see
/// [`with_max_bytes`](Self::with_max_bytes)), is counted from nothing.
///
/// ```no_run
/// # fn demo(scorer: &shapegen_runtime::score::silhouette::SilhouetteScorer) -> Result<(), Box<dyn std::error::Error>> {
/// use shapegen_runtime::gpu::GpuContext;
/// use shapegen_runtime::score::silhouette::{GpuRetention, GpuSilhouetteScorer};
///
/// let gpu = GpuContext::new()?;
/// let on_gpu = GpuSilhouetteScorer::new(&gpu, scorer)?;
/// let retention = GpuRetention::new(&on_gpu)?.with_max_bytes(256 << 20);
/// println!("one model's slot takes {} bytes", retention.slot_bytes());
/// // Each generation: retention.count_bred(&on_gpu, bred, &batch, &mut counts)?;
/// # Ok(()) }
/// ```
pub struct GpuRetention {
    program: Program,
    /// Words from a slot's start to each target's image.
    offsets: Vec<u32>,
    /// 32-bit words of one slot.
    slot_words: u32,
    slots_per_page: u32,
    /// Most slots one binding (and [`MAX_PAGE_SLOTS`]) allows in a page.
    page_limit: u32,
    /// Most slots allowed.
    max_slots: u32,
    pages: Vec<wgpu::Buffer>,
    /// One slot's worth of memory, to copy a slot to another of the same page through.
    bounce: Option<wgpu::Buffer>,
    /// Slots `0..issued` exist (their pages are allocated).
    issued: u32,
    kept: HashMap<u64, Arc<Kept>>,
    stats: RetentionStats,
}

impl std::fmt::Debug for GpuRetention {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuRetention")
            .field("kept", &self.kept.len())
            .field("slot_words", &self.slot_words)
            .field("pages", &self.pages.len())
            .field("stats", &self.stats)
            .finish()
    }
}

impl GpuRetention {
    /// Nothing kept yet, at most 1 GiB of slots, for the targets of `scorer` (every
    /// later call must pass the same scorer).
    ///
    /// # Errors
    /// [`GpuError::Unsupported`] when one model's slot exceeds the largest binding.
    pub fn new(scorer: &GpuSilhouetteScorer<'_>) -> Result<Self, GpuError> {
        let mut offsets = Vec::with_capacity(scorer.targets.len());
        let mut words = 0u64;
        for target in &scorer.targets {
            offsets.push(words as u32);
            words += u64::from(target.view.width) * u64::from(target.view.height);
        }
        let slot_bytes = words * 4;
        let slots_per_page = (scorer.gpu.max_binding() / slot_bytes.max(4)).min(MAX_PAGE_SLOTS);
        if slots_per_page == 0 || words > u64::from(u32::MAX) {
            return Err(GpuError::Unsupported(format!(
                "one model's fragment counts take {slot_bytes} bytes; this device binds at most {}",
                scorer.gpu.max_binding()
            )));
        }
        let program = scorer.gpu.checked(|| {
            Program::new::<GpuInstance>(
                scorer.gpu,
                "silhouette retained",
                shapegen_shaders::SILHOUETTE_RETAINED,
                &wgpu::vertex_attr_array![4 => Uint32, 5 => Uint32, 6 => Uint32],
            )
        })?;
        Ok(GpuRetention {
            program,
            offsets,
            slot_words: words as u32,
            slots_per_page: slots_per_page as u32,
            page_limit: slots_per_page as u32,
            max_slots: u32::MAX,
            pages: Vec::new(),
            bounce: None,
            issued: 0,
            kept: HashMap::new(),
            stats: RetentionStats::default(),
        }
        .with_max_bytes(DEFAULT_MAX_BYTES))
    }

    /// At most `bytes` of slots on the GPU (at least one slot): past it, children are
    /// counted from nothing and not kept. Forgets what was kept.
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        let slots = (bytes / self.slot_bytes().max(1)).clamp(1, u64::from(u32::MAX));
        self.max_slots = slots as u32;
        self.slots_per_page = self.page_limit.min(self.max_slots);
        self.pages.clear();
        self.issued = 0;
        self.kept.clear();
        self
    }

    /// Bytes of one model's slot: 4 per pixel of every target.
    pub fn slot_bytes(&self) -> u64 {
        u64::from(self.slot_words) * 4
    }

    /// Bytes of GPU memory the slots take now.
    pub fn memory(&self) -> u64 {
        self.pages.len() as u64 * self.page_bytes()
    }

    /// How the children of the calls so far were counted.
    pub fn stats(&self) -> RetentionStats {
        self.stats
    }

    /// Number of models whose slot is kept.
    pub fn len(&self) -> usize {
        self.kept.len()
    }

    /// Whether no slot is kept.
    pub fn is_empty(&self) -> bool {
        self.kept.is_empty()
    }

    fn page_bytes(&self) -> u64 {
        u64::from(self.slots_per_page) * self.slot_bytes()
    }

    /// Counts the `children` of `bred` (the models of `batch`, in order), child `i` bred
    /// from `parents[from[i]]`, writing child `i`'s counts to `out[i]`, exactly as
    /// [`GpuSilhouetteScorer::count_batch`] counts them. Parents not kept are derived on
    /// the batch's [site](InstanceBatch::site). Afterwards only the slots of `parents`
    /// and `children` are kept.
    ///
    /// # Errors
    /// [`GpuError::Device`] when the device fails; [`GpuError::Unsupported`] when a
    /// submission's counts exceed the largest binding.
    ///
    /// # Panics
    /// If the lengths disagree or an entry of `from` is out of range.
    pub fn count_bred<G: Grammar>(
        &mut self,
        scorer: &GpuSilhouetteScorer<'_>,
        bred: Bred<'_, G>,
        batch: &InstanceBatch,
        out: &mut [SilhouetteCounts],
    ) -> Result<(), GpuError> {
        let Bred {
            children,
            parents,
            from,
        } = bred;
        assert_eq!(batch.len(), children.len(), "one model per child");
        assert_eq!(from.len(), children.len(), "one parent per child");
        assert_eq!(out.len(), children.len(), "one count per child");
        let parent_keys: Vec<u64> = parents.iter().map(genome_key).collect();
        let mut bases: Vec<Option<Arc<Kept>>> = parent_keys
            .iter()
            .map(|key| self.kept.get(key).cloned())
            .collect();
        self.kept.clear();
        let mut free = self.free_slots(bases.iter().flatten().map(|kept| kept.slot));
        self.count_missing_parents(scorer, parents, batch.site(), from, &mut bases, &mut free)?;

        let mut diffs: Vec<InstanceDiff> = Vec::new();
        let mut slots: Vec<Option<u32>> = Vec::with_capacity(children.len());
        let mut uses_base = Vec::with_capacity(children.len());
        for (child, &parent) in from.iter().enumerate() {
            let instances = batch.model(child);
            let mut diff = InstanceDiff::default();
            let base = bases[parent as usize].as_deref();
            let incremental = base.is_some_and(|base| {
                diff.between(&base.instances, instances);
                diff.len() < instances.len().max(1)
            });
            uses_base.push(incremental);
            diffs.push(diff);
            slots.push(self.take_slot(&mut free));
        }
        let draws: Vec<(usize, Draw)> = slots
            .iter()
            .enumerate()
            .filter_map(|(child, slot)| {
                let base = bases[from[child] as usize].as_deref();
                let base = base.filter(|_| uses_base[child]);
                Some((
                    child,
                    Draw::of((*slot)?, base, &diffs[child], batch.model(child)),
                ))
            })
            .collect();
        let draw_list: Vec<&Draw> = draws.iter().map(|(_, draw)| draw).collect();
        let changes = self.submit(scorer, &draw_list)?;
        for ((child, _), change) in draws.iter().zip(changes) {
            let base = bases[from[*child] as usize]
                .as_deref()
                .filter(|_| uses_base[*child]);
            out[*child] = apply(base.map(|b| &b.counts), &change)?;
        }
        self.count_unslotted(scorer, batch, &slots, out)?;

        self.keep_children(children, batch, &slots, &uses_base, &diffs, out);
        for (key, base) in parent_keys.into_iter().zip(bases) {
            if let Some(base) = base {
                self.kept.entry(key).or_insert(base);
            }
        }
        Ok(())
    }

    /// Counts each child in the stats (from its parent where `uses_base` says so, with
    /// the changes of `diffs`) and keeps each child given a slot in `slots`, with its
    /// counts `out`.
    fn keep_children<G: Grammar>(
        &mut self,
        children: &[Genome<G>],
        batch: &InstanceBatch,
        slots: &[Option<u32>],
        uses_base: &[bool],
        diffs: &[InstanceDiff],
        out: &[SilhouetteCounts],
    ) {
        for (child, slot) in slots.iter().enumerate() {
            let changed = uses_base[child].then(|| diffs[child].len());
            self.stats.count_child(changed, batch.model(child).len());
            if let Some(slot) = *slot {
                let kept = Arc::new(Kept {
                    instances: batch.model(child).to_vec(),
                    slot,
                    counts: out[child],
                });
                self.kept.insert(genome_key(&children[child]), kept);
            }
        }
    }

    /// The slots `0..issued` not in `used`, lowest last (taken first).
    fn free_slots(&self, used: impl Iterator<Item = u32>) -> Vec<u32> {
        let used: HashSet<u32> = used.collect();
        (0..self.issued)
            .rev()
            .filter(|s| !used.contains(s))
            .collect()
    }

    /// A free slot, or a new one while the memory bound allows.
    fn take_slot(&mut self, free: &mut Vec<u32>) -> Option<u32> {
        if let Some(slot) = free.pop() {
            return Some(slot);
        }
        (self.issued < self.max_slots).then(|| {
            self.issued += 1;
            self.issued - 1
        })
    }

    /// Counts, into slots of their own, the parents that `from` names and `bases` lacks
    /// (while slots are left).
    fn count_missing_parents<G: Grammar>(
        &mut self,
        scorer: &GpuSilhouetteScorer<'_>,
        parents: &[Genome<G>],
        site: &Site,
        from: &[u32],
        bases: &mut [Option<Arc<Kept>>],
        free: &mut Vec<u32>,
    ) -> Result<(), GpuError> {
        let mut missing: Vec<u32> = from
            .iter()
            .copied()
            .filter(|&p| bases[p as usize].is_none())
            .collect();
        missing.sort_unstable();
        missing.dedup();
        let mut fresh = Vec::new();
        for p in missing {
            let Some(slot) = self.take_slot(free) else {
                break;
            };
            let mut instances = Vec::new();
            parents[p as usize].derive_on(site, &mut instances);
            fresh.push((p, slot, instances));
        }
        let draws: Vec<Draw> = fresh
            .iter()
            .map(|(_, slot, instances)| Draw {
                slot: *slot,
                from: None,
                removed: &[],
                added: instances,
            })
            .collect();
        let changes = self.submit(scorer, &draws.iter().collect::<Vec<_>>())?;
        self.stats.parents_counted += fresh.len() as u64;
        for ((p, slot, instances), change) in fresh.into_iter().zip(changes) {
            let counts = apply(None, &change)?;
            bases[p as usize] = Some(Arc::new(Kept {
                instances,
                slot,
                counts,
            }));
        }
        Ok(())
    }

    /// Counts from nothing, with the bitset path, the children that got no slot.
    fn count_unslotted(
        &self,
        scorer: &GpuSilhouetteScorer<'_>,
        batch: &InstanceBatch,
        slots: &[Option<u32>],
        out: &mut [SilhouetteCounts],
    ) -> Result<(), GpuError> {
        let unslotted: Vec<usize> = (0..slots.len()).filter(|&c| slots[c].is_none()).collect();
        if unslotted.is_empty() {
            return Ok(());
        }
        let mut rest = InstanceBatch::new();
        for &child in &unslotted {
            rest.push_with(|instances| instances.extend_from_slice(batch.model(child)));
        }
        let mut counts = vec![SilhouetteCounts::default(); unslotted.len()];
        scorer.count_batch(&rest, &mut counts)?;
        for (child, counts) in unslotted.into_iter().zip(counts) {
            out[child] = counts;
        }
        Ok(())
    }

    /// Makes sure the pages holding slots `0..issued` exist, and the bounce buffer.
    fn allocate(&mut self, scorer: &GpuSilhouetteScorer<'_>) {
        let device = &scorer.gpu.device;
        let pages = self.issued.div_ceil(self.slots_per_page) as usize;
        while self.pages.len() < pages {
            self.pages
                .push(device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("silhouette slots"),
                    size: self.page_bytes(),
                    usage: wgpu::BufferUsages::STORAGE
                        | wgpu::BufferUsages::COPY_SRC
                        | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
        }
        if self.bounce.is_none() {
            self.bounce = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("silhouette slot copy"),
                size: self.slot_bytes().max(4),
                usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
        }
    }

    /// The page of `slot` and the byte offset of the slot in it.
    fn place(&self, slot: u32) -> (usize, u64) {
        let page = slot / self.slots_per_page;
        let index = slot % self.slots_per_page;
        (page as usize, u64::from(index) * self.slot_bytes())
    }

    /// Draws every model of `draws` into its slot in one submission and returns, per
    /// draw and target, how its counts changed.
    fn submit(
        &mut self,
        scorer: &GpuSilhouetteScorer<'_>,
        draws: &[&Draw],
    ) -> Result<Vec<Vec<[i64; 3]>>, GpuError> {
        if draws.is_empty() {
            return Ok(Vec::new());
        }
        let targets = scorer.targets.len();
        let change_bytes = counter_bytes(draws.len(), targets);
        if change_bytes > scorer.gpu.max_binding() {
            return Err(GpuError::Unsupported(format!(
                "the counts of {} models take {change_bytes} bytes; this device binds at most {}",
                draws.len(),
                scorer.gpu.max_binding()
            )));
        }
        self.allocate(scorer);
        let (instances, ranges) = self.sort_instances(scorer, draws);
        let changes = scorer
            .gpu
            .checked(|| self.encode(scorer, draws, &instances, &ranges, change_bytes))?;
        let changes = Counters::read(scorer.gpu, &changes, draws.len(), targets)?;
        Ok((0..draws.len())
            .map(|e| {
                (0..targets)
                    .map(|k| changes.get::<i32>(e, k).map(i64::from))
                    .collect()
            })
            .collect())
    }

    /// Every instance of `draws` whose mesh the scorer has, sorted by page and then by
    /// mesh, with the range of each (page, mesh) pair: `ranges[page * meshes + mesh]`.
    fn sort_instances(
        &self,
        scorer: &GpuSilhouetteScorer<'_>,
        draws: &[&Draw],
    ) -> (Vec<GpuInstance>, Vec<Range<u32>>) {
        let meshes = scorer.meshes.len();
        let mut keyed: Vec<(usize, GpuInstance)> = Vec::new();
        for (e, draw) in draws.iter().enumerate() {
            let (page, _) = self.place(draw.slot);
            let lists = [(draw.removed, 1u32), (draw.added, 0)];
            for (list, removed) in lists {
                for instance in list {
                    let m = instance.mesh.0 as usize;
                    if m >= meshes {
                        continue;
                    }
                    let gpu = GpuInstance {
                        rows: rows(&instance.transform),
                        entry: e as u32,
                        slot: draw.slot,
                        removed,
                        _pad: 0,
                    };
                    keyed.push((page * meshes + m, gpu));
                }
            }
        }
        keyed.sort_by_key(|(key, _)| *key);
        let mut ranges = vec![0..0; self.pages.len() * meshes];
        let mut start = 0;
        while start < keyed.len() {
            let key = keyed[start].0;
            let end = start + keyed[start..].partition_point(|(k, _)| *k == key);
            ranges[key] = start as u32..end as u32;
            start = end;
        }
        (keyed.into_iter().map(|(_, i)| i).collect(), ranges)
    }

    /// Encodes and submits the slots' clears and copies and every pass, returning the
    /// buffer the changes land in.
    fn encode(
        &self,
        scorer: &GpuSilhouetteScorer<'_>,
        draws: &[&Draw],
        instances: &[GpuInstance],
        ranges: &[Range<u32>],
        change_bytes: u64,
    ) -> wgpu::Buffer {
        let mut passes = Passes::new(
            scorer.gpu,
            &self.program,
            &scorer.meshes,
            instances,
            change_bytes,
        );
        let bounce = self.bounce.as_ref().expect("allocated before encoding");
        let size = self.slot_bytes();
        let encoder = &mut passes.encoder;
        for draw in draws {
            let (page, offset) = self.place(draw.slot);
            match draw.from {
                Some(from) => {
                    let (from_page, from_offset) = self.place(from);
                    let source = &self.pages[from_page];
                    encoder.copy_buffer_to_buffer(source, from_offset, bounce, 0, size);
                    encoder.copy_buffer_to_buffer(bounce, 0, &self.pages[page], offset, size);
                }
                None => encoder.clear_buffer(&self.pages[page], offset, Some(size)),
            }
        }
        let meshes = scorer.meshes.len();
        for (p, page) in self.pages.iter().enumerate() {
            let of_page = &ranges[p * meshes..(p + 1) * meshes];
            if of_page.iter().all(Range::is_empty) {
                continue;
            }
            for (k, target) in scorer.targets.iter().enumerate() {
                let params = Params {
                    view: target.view,
                    image_offset: self.offsets[k],
                    slot_words: self.slot_words,
                    first_slot: p as u32 * self.slots_per_page,
                    index: target.index,
                };
                passes.draw(target, &params, page, of_page.iter().cloned());
            }
        }
        passes.submit()
    }
}

/// The counts of a model whose slot started as `base`'s (or empty) and changed by
/// `change` (per target: covered, on target, grey-level sum).
///
/// # Errors
/// [`GpuError::Device`] when a count would fall below 0, which a correct device never
/// gives.
fn apply(
    base: Option<&SilhouetteCounts>,
    change: &[[i64; 3]],
) -> Result<SilhouetteCounts, GpuError> {
    let broken = || GpuError::Device("the GPU's incremental counts fell below zero".into());
    let mut counts = SilhouetteCounts::zeroed(change.len());
    for (k, (slot, change)) in counts.targets_mut().iter_mut().zip(change).enumerate() {
        let before = base.map(|b| b.targets()[k]).unwrap_or_default();
        let covered = u32::try_from(i64::from(before.covered) + change[0]).map_err(|_| broken())?;
        let on_target =
            u32::try_from(i64::from(before.on_target) + change[1]).map_err(|_| broken())?;
        let level_sum = u64::try_from(before.level_sum as i64 + change[2]).map_err(|_| broken())?;
        *slot = TargetCounts {
            covered,
            on_target,
            off_target: covered.checked_sub(on_target).ok_or_else(broken)?,
            level_sum,
        };
    }
    Ok(counts)
}
