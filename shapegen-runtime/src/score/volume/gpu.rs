//! Counting whole populations on the GPU, with counts identical to the CPU's.
//!
//! Every model's box instances are quantised on the CPU ([`QuantBox`]) into one buffer
//! per pass, and their spans' out-of-grid voxels are counted there too (a closed form
//! per instance); the shader [`shapegen_shaders::VOLUME`] runs one invocation per
//! (instance, row) pair, found from a prefix sum of rows per instance, marks the row's
//! voxels in the model's bitset with `atomicOr`, marks those that were already set in a
//! second bitset (voxels covered more than once) and adds what it counted to the model's
//! counters. A pass holds as many models as their bitsets fit in one storage binding; all
//! passes go in one submission, followed by one small read-back of the counters.
//!
//! Instances of other meshes, and a model's facets (voxelized together, by winding
//! number), are rasterised on the CPU threads by the CPU's own code, model by model;
//! their covered in-grid runs of each row go to the GPU as boxes of one row (a
//! [`QuantBox`] without planes, consecutive rows of the same run merged), counted there
//! with the model's box instances, and what they cover outside the grid is counted on
//! the CPU. So every grammar counts on the GPU, exactly as on the CPU.

use std::sync::Mutex;

use rayon::prelude::*;
use wgpu::util::DeviceExt;

use super::count::Lattice;
use super::counts::VolumeCounts;
use super::parity::Voxelizer;
use super::parts::PartKind;
use super::quant::{Placement, QuantBox, quantize};
use super::scorer::VolumeScorer;
use super::span::span_out_of_grid;
use super::target::MAX_CLASSES;
use crate::gpu::{GpuContext, GpuError};
use crate::score::batch::InstanceBatch;
use crate::score::form::Form;

/// Invocations per workgroup (`@workgroup_size` in the shader).
const WORKGROUP: u64 = 64;
/// Most workgroups along one dispatch dimension.
const MAX_GROUPS: u64 = 65_535;
/// Counter words per model: low and high halves of 16 class counts, overlap hits,
/// out-of-grid hits and overlap voxels.
const COUNTERS: usize = 2 * (MAX_CLASSES + 3);
const OVERLAP_HITS: usize = 2 * MAX_CLASSES;
const OUT_OF_GRID_HITS: usize = OVERLAP_HITS + 2;
const OVERLAP_VOXELS: usize = OUT_OF_GRID_HITS + 2;

/// One pass's uniforms. Mirrors `struct Params` in [`shapegen_shaders::VOLUME`] (48
/// bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct PassParams {
    res: [i32; 4],
    rows: u32,
    boxes: u32,
    groups_x: u32,
    first_model: u32,
    words_per_model: u32,
    pad: [u32; 3],
}

const _: () = assert!(size_of::<PassParams>() == 48);

/// What a model's instances count on the CPU: out-of-grid hits (of box instances too
/// large to rasterise, and of what is rasterised on the CPU), and their spans'
/// out-of-grid voxels.
#[derive(Clone, Copy, Default)]
struct Beyond {
    outside: u64,
    span: u64,
}

/// What the CPU rasterises of one model (its instances of meshes other than boxes, and
/// its facets): in-grid runs as boxes of one row, and what lies beyond the grid.
struct Rows {
    /// Grid resolution along x and y, to split flat voxel indices.
    nx: usize,
    ny: usize,
    boxes: Vec<QuantBox>,
    beyond: Beyond,
}

impl Rows {
    fn new(res: [u32; 3]) -> Rows {
        Rows {
            nx: res[0] as usize,
            ny: res[1] as usize,
            boxes: Vec::new(),
            beyond: Beyond::default(),
        }
    }
}

impl Lattice for Rows {
    fn span(&mut self, n: u64) {
        self.beyond.span = self.beyond.span.saturating_add(n);
    }

    fn outside(&mut self, n: u64) {
        self.beyond.outside = self.beyond.outside.saturating_add(n);
    }

    fn voxels(&mut self, first: usize, last: usize) {
        let (i, row) = (first % self.nx, first / self.nx);
        let (j, k) = (row % self.ny, row / self.ny);
        let [i, j, k, len] = [i, j, k, last - first + 1].map(|n| n as i32);
        // The run of the row before it, along y, grows by one row.
        if let Some(q) = self.boxes.last_mut()
            && q.corner[..3] == [i, j - q.extent[1], k]
            && q.extent[0] == len
        {
            q.extent[1] += 1;
            return;
        }
        // No planes: every row of the box covers its whole extent.
        self.boxes.push(QuantBox {
            corner: [i, j, k, 0],
            extent: [len, 1, 1, 0],
            ..QuantBox::default()
        });
    }
}

/// The models of one pass and their quantised boxes.
#[derive(Default)]
struct Pass {
    first_model: usize,
    models: usize,
    boxes: Vec<QuantBox>,
    rows: u64,
}

/// A [`VolumeScorer`]'s counting on the GPU: the class grid uploaded once, populations
/// counted in one submission each.
///
/// ```no_run
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::gpu::GpuContext;
/// use shapegen_runtime::score::volume::{GpuVolumeScorer, Grid, VolumeCounts, VolumeScorer};
/// use shapegen_runtime::score::{Form, InstanceBatch, Scorer};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let grid = Grid::new(Vec3::splat(-2.0), Vec3::splat(2.0), [8, 8, 8])?;
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let scorer = VolumeScorer::new(grid, &[], &meshes, Form::Weighted { overlap: 1.0 })?;
/// let mut batch = InstanceBatch::new();
/// batch.push_with(|out| out.push(Instance { transform: Affine3A::from_scale(Vec3::splat(3.0)), mesh: CUBE }));
/// let gpu = GpuContext::new()?;
/// let mut counts = [VolumeCounts::default()];
/// GpuVolumeScorer::new(&gpu, &scorer)?.count_batch(&batch, &mut counts)?;
/// assert_eq!(counts[0], scorer.count(batch.model(0), &mut scorer.scratch()));
/// assert_eq!(counts[0].outside, 6 * 6 * 6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct GpuVolumeScorer<'a> {
    ctx: &'a GpuContext,
    scorer: &'a VolumeScorer,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    classes: wgpu::Buffer,
    words_per_model: u64,
    models_per_pass: usize,
    /// The bitsets of the largest pass so far, covered and covered again, reused.
    bitsets: Mutex<Option<[wgpu::Buffer; 2]>>,
    /// Every instance of the last batch, quantised, with its span's out-of-grid
    /// voxels; reused.
    placements: Mutex<Vec<(Placement, u64)>>,
    /// Whether every mesh of the grammar is a box, so nothing is rasterised on the CPU.
    boxes_only: bool,
}

impl std::fmt::Debug for GpuVolumeScorer<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuVolumeScorer")
            .field("gpu", &self.ctx.describe())
            .field("models_per_pass", &self.models_per_pass)
            .finish_non_exhaustive()
    }
}

impl<'a> GpuVolumeScorer<'a> {
    /// Prepares `scorer`'s scene on `ctx`: uploads the class grid and builds the
    /// pipeline.
    ///
    /// # Errors
    /// [`GpuError::Unsupported`] when one model's bitset or the class grid exceeds the
    /// largest storage binding; [`GpuError::Device`] when the device rejects the shader
    /// or a buffer.
    pub fn new(ctx: &'a GpuContext, scorer: &'a VolumeScorer) -> Result<Self, GpuError> {
        if let Form::FScore { .. } = scorer.form() {
            return Err(GpuError::Unsupported(
                "the fscore form's surface counts are made on the CPU only; count on the CPU"
                    .into(),
            ));
        }
        let boxes_only = scorer
            .meshes()
            .iter()
            .all(|(id, _, _)| scorer.is_box(id) == Some(true));
        let max = ctx.max_binding();
        let voxels = scorer.grid().voxel_count();
        let words_per_model = voxels.div_ceil(32);
        let models_per_pass = (max / (words_per_model * 4)) as usize;
        if models_per_pass == 0 {
            return Err(GpuError::Unsupported(format!(
                "a model's bitset of {} bytes exceeds the largest storage binding of {max} bytes",
                words_per_model * 4
            )));
        }
        let packed = pack_classes(scorer.classes().voxels());
        let class_bytes = (packed.len() * 4) as u64;
        if class_bytes > max {
            return Err(GpuError::Unsupported(format!(
                "the class grid of {class_bytes} bytes exceeds the largest storage binding of {max} bytes"
            )));
        }
        let module = ctx.shader("volume", shapegen_shaders::VOLUME)?;
        let (pipeline, classes) = ctx.checked(|| {
            let pipeline = ctx
                .device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("volume"),
                    layout: None,
                    module: &module,
                    entry_point: Some("count_rows"),
                    compilation_options: Default::default(),
                    cache: None,
                });
            let classes = ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("volume classes"),
                    contents: bytemuck::cast_slice(&packed),
                    usage: wgpu::BufferUsages::STORAGE,
                });
            (pipeline, classes)
        })?;
        let layout = pipeline.get_bind_group_layout(0);
        Ok(GpuVolumeScorer {
            ctx,
            scorer,
            pipeline,
            layout,
            classes,
            words_per_model,
            models_per_pass,
            bitsets: Mutex::new(None),
            placements: Mutex::new(Vec::new()),
            boxes_only,
        })
    }

    /// How many models share one pass: as many bitsets as fit one storage binding (each
    /// model has two, in two bindings).
    pub fn models_per_pass(&self) -> usize {
        self.models_per_pass
    }

    /// The most models one batch may hold: as many as the largest storage binding holds
    /// counters of.
    pub fn max_batch(&self) -> usize {
        (self.ctx.max_binding() / (COUNTERS * 4) as u64) as usize
    }

    /// Puts at most `models` (at least 1) models in one pass, for smaller bitset
    /// buffers.
    pub fn limit_models_per_pass(&mut self, models: usize) {
        self.models_per_pass = self.models_per_pass.min(models.max(1));
    }

    /// Counts every model of `batch`, writing model `i`'s counts to `out[i]`: exactly
    /// what [`VolumeScorer`] counts on the CPU.
    ///
    /// # Errors
    /// [`GpuError::Unsupported`] when the batch has more than [`max_batch`](Self::max_batch)
    /// models, or one model's boxes or rows exceed what one pass holds;
    /// [`GpuError::Device`] when the device fails.
    ///
    /// # Panics
    /// If `out.len() != batch.len()`.
    pub fn count_batch(
        &self,
        batch: &InstanceBatch,
        out: &mut [VolumeCounts],
    ) -> Result<(), GpuError> {
        assert_eq!(out.len(), batch.len(), "one counts slot per model");
        if batch.is_empty() {
            return Ok(());
        }
        if batch.len() > self.max_batch() {
            return Err(GpuError::Unsupported(format!(
                "{} models' counters exceed the largest storage binding, which holds {}; \
                 count fewer at once",
                batch.len(),
                self.max_batch()
            )));
        }
        let (passes, beyond) = self.plan(batch)?;
        let counter_bytes = (batch.len() * COUNTERS * 4) as u64;
        let bitset_bytes = self.words_per_model * 4;
        let widest = passes.iter().map(|p| p.models).max().unwrap_or(0) as u64;
        let device = &self.ctx.device;
        let mut bitsets = self.bitsets.lock().unwrap_or_else(|e| e.into_inner());
        let counters = self.ctx.checked(|| {
            if bitsets
                .as_ref()
                .is_none_or(|[b, _]| b.size() < widest * bitset_bytes)
            {
                *bitsets = Some(["volume covered", "volume covered again"].map(|label| {
                    device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(label),
                        size: widest.max(1) * bitset_bytes,
                        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    })
                }));
            }
            let bitsets = bitsets.as_ref().expect("made above");
            let counters = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("volume counters"),
                size: counter_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("volume"),
            });
            for pass in passes.iter().filter(|p| p.rows > 0) {
                self.encode(&mut encoder, pass, bitsets, &counters);
            }
            self.ctx.queue.submit([encoder.finish()]);
            counters
        })?;
        drop(bitsets);
        let bytes = self.ctx.read_back(&counters, counter_bytes)?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        for (m, slot) in out.iter_mut().enumerate() {
            let w = &words[m * COUNTERS..(m + 1) * COUNTERS];
            let wide = |at: usize| u64::from(w[at]) | u64::from(w[at + 1]) << 32;
            *slot = self.scorer.with_totals(VolumeCounts {
                overlap_hits: wide(OVERLAP_HITS),
                overlap_voxels: wide(OVERLAP_VOXELS),
                out_of_grid_hits: wide(OUT_OF_GRID_HITS).saturating_add(beyond[m].outside),
                span_out_of_grid: beyond[m].span,
                classes: std::array::from_fn(|c| wide(2 * c)),
                ..VolumeCounts::default()
            });
        }
        Ok(())
    }

    /// Quantises every model's boxes, rasterises the rest on the CPU, and splits the
    /// models into passes; also gives what each model counts on the CPU.
    fn plan(&self, batch: &InstanceBatch) -> Result<(Vec<Pass>, Vec<Beyond>), GpuError> {
        let max_boxes = (self.ctx.max_binding() / size_of::<QuantBox>() as u64) as usize;
        // Row numbers travel as i32 in QuantBox::extent[3].
        let max_rows = i32::MAX as u64 - WORKGROUP;
        let grid = self.scorer.grid();
        // Quantise every box instance on the CPU threads, in order.
        let mut placements = self.placements.lock().unwrap_or_else(|e| e.into_inner());
        batch
            .instances()
            .par_iter()
            .map(|instance| match self.scorer.part(instance.mesh) {
                Some(part @ PartKind::Box) => (
                    quantize(grid, &instance.transform),
                    span_out_of_grid(grid, part, &instance.transform),
                ),
                // Rasterised below; ids the grammar lacks cover nothing.
                _ => (Placement::Nothing, 0),
            })
            .collect_into_vec(&mut placements);
        let rasterised = self.rasterise_rest(batch);
        let starts = batch.starts();
        let mut beyond: Vec<Beyond> = rasterised.iter().map(|r| r.beyond).collect();
        beyond.resize(batch.len(), Beyond::default());
        let mut passes = vec![Pass::default()];
        let mut model_boxes = Vec::new();
        for (m, extra) in beyond.iter_mut().enumerate() {
            model_boxes.clear();
            let mut rows = 0u64;
            for (placement, span) in &placements[starts[m] as usize..starts[m + 1] as usize] {
                extra.span = extra.span.saturating_add(*span);
                match *placement {
                    Placement::Nothing => {}
                    Placement::Oversize(n) => extra.outside = extra.outside.saturating_add(n),
                    Placement::Box(q) => {
                        rows += (q.extent[1] as u64) * (q.extent[2] as u64);
                        model_boxes.push(q);
                    }
                }
            }
            if let Some(cpu) = rasterised.get(m) {
                rows += cpu.boxes.iter().map(|q| q.extent[1] as u64).sum::<u64>();
                model_boxes.extend_from_slice(&cpu.boxes);
            }
            if model_boxes.len() > max_boxes || rows > max_rows {
                return Err(GpuError::Unsupported(format!(
                    "model {m} has {} boxes over {rows} rows; one pass holds at most \
                     {max_boxes} boxes and {max_rows} rows",
                    model_boxes.len()
                )));
            }
            let pass = passes.last_mut().expect("one pass at least");
            if pass.models == self.models_per_pass
                || pass.boxes.len() + model_boxes.len() > max_boxes
                || pass.rows + rows > max_rows
            {
                passes.push(Pass {
                    first_model: m,
                    ..Pass::default()
                });
            }
            let pass = passes.last_mut().expect("one pass at least");
            for q in &mut model_boxes {
                q.corner[3] = m as i32;
                q.extent[3] = pass.rows as i32;
                pass.rows += (q.extent[1] as u64) * (q.extent[2] as u64);
                pass.boxes.push(*q);
            }
            pass.models += 1;
        }
        Ok((passes, beyond))
    }

    /// Rasterises every model's instances other than boxes, and its facets, on the CPU
    /// threads (nothing when the grammar has only boxes).
    fn rasterise_rest(&self, batch: &InstanceBatch) -> Vec<Rows> {
        if self.boxes_only {
            return Vec::new();
        }
        let grid = self.scorer.grid();
        (0..batch.len())
            .into_par_iter()
            .map_init(Voxelizer::default, |voxelizer, m| {
                let model = batch.model(m);
                let mut rows = Rows::new(grid.resolution());
                for instance in model {
                    if self.scorer.part(instance.mesh) != Some(&PartKind::Box) {
                        self.scorer.walk(instance, voxelizer, &mut rows);
                    }
                }
                self.scorer.walk_facets(model, voxelizer, &mut rows);
                rows
            })
            .collect()
    }

    /// Records one pass: clear its bitsets, dispatch its rows.
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pass: &Pass,
        [covered, again]: &[wgpu::Buffer; 2],
        counters: &wgpu::Buffer,
    ) {
        let device = &self.ctx.device;
        let groups = pass.rows.div_ceil(WORKGROUP);
        let groups_x = groups.min(MAX_GROUPS);
        let groups_y = groups.div_ceil(groups_x);
        let res = self.scorer.grid().resolution().map(|r| r as i32);
        let params = PassParams {
            res: [res[0], res[1], res[2], 0],
            rows: pass.rows as u32,
            boxes: pass.boxes.len() as u32,
            groups_x: groups_x as u32,
            first_model: pass.first_model as u32,
            words_per_model: self.words_per_model as u32,
            pad: [0; 3],
        };
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("volume params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let boxes = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("volume boxes"),
            contents: bytemuck::cast_slice(&pass.boxes),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let bitsets = pass.models as u64 * self.words_per_model * 4;
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("volume pass"),
            layout: &self.layout,
            entries: &[
                entry(0, &params, None),
                entry(1, &boxes, None),
                entry(2, &self.classes, None),
                entry(3, covered, Some(bitsets)),
                entry(4, counters, None),
                entry(5, again, Some(bitsets)),
            ],
        });
        encoder.clear_buffer(covered, 0, Some(bitsets));
        encoder.clear_buffer(again, 0, Some(bitsets));
        let mut compute = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("volume rows"),
            timestamp_writes: None,
        });
        compute.set_pipeline(&self.pipeline);
        compute.set_bind_group(0, &group, &[]);
        compute.dispatch_workgroups(groups_x as u32, groups_y as u32, 1);
    }
}

/// Binds `size` bytes (all when `None`) of `buffer` at `binding`.
fn entry(binding: u32, buffer: &wgpu::Buffer, size: Option<u64>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer,
            offset: 0,
            size: size.and_then(wgpu::BufferSize::new),
        }),
    }
}

/// Voxel classes packed 8 to a word, 4 bits each, voxel `v` at bits `4 (v % 8)` of word
/// `v / 8`.
fn pack_classes(voxels: &[u8]) -> Vec<u32> {
    voxels
        .chunks(8)
        .map(|chunk| {
            chunk
                .iter()
                .enumerate()
                .fold(0u32, |w, (i, &c)| w | u32::from(c) << (4 * i))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_pack_four_bits_each() {
        let voxels = [1, 2, 3, 15, 0, 0, 0, 9, 4];
        assert_eq!(pack_classes(&voxels), [0x9000_f321, 4]);
    }
}
