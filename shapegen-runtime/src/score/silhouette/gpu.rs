//! The silhouette scorer on the GPU: a whole population per submission, counted by the
//! fragment shader of [`shapegen_shaders::SILHOUETTE`].

use std::ops::Range;

use bytemuck::{Pod, Zeroable};

use super::counts::{SilhouetteCounts, TargetCounts};
use super::gpu_draw::{
    Counters, GpuMeshes, GpuTarget, Passes, Program, TargetIndex, View, counter_bytes, rows,
};
use super::scorer::SilhouetteScorer;
use crate::gpu::{GpuContext, GpuError};
use crate::score::batch::InstanceBatch;

/// Mirrors the WGSL struct `Params` of [`shapegen_shaders::SILHOUETTE`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Params {
    view: View,
    /// 32-bit words per bitset row, and per model's bitset.
    row_words: u32,
    image_words: u32,
    /// Index of the first model whose bitset is at the start of the coverage buffer.
    first_model: u32,
    index: TargetIndex,
}
const _: () = assert!(size_of::<Params>() == 96);

/// One instance as the vertex shader's instance attributes read it (locations 1 to 4):
/// the rows of its affine transform and the index of its model in the batch.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GpuInstance {
    rows: [[f32; 4]; 3],
    model: u32,
    _pad: [u32; 3],
}
const _: () = assert!(size_of::<GpuInstance>() == 64);

/// Most models whose bitsets share one coverage buffer, whatever the binding limit.
const MAX_CHUNK: u64 = 256;

/// The [`SilhouetteScorer`] on the GPU: the same counts, up to pixels whose centres lie
/// within rounding of a triangle edge (the hardware transforms and rasterizes in its own
/// floating point, with the same pixel-centre sampling and top-left rule).
///
/// [`count_batch`](Self::count_batch) scores a whole [`InstanceBatch`] in one
/// submission: every instance (its transform and its model's index) in one instance
/// buffer, sorted by mesh; per target and mesh one instanced draw; the fragment shader
/// sets the pixel's bit in the model's coverage bitset with `atomicOr`, and the one
/// invocation that set it adds the pixel to the model's counts with `atomicAdd`. Models
/// are taken in chunks so that no binding exceeds [`GpuContext::max_binding`]; one small
/// read-back returns the counts.
///
/// ```no_run
/// # fn demo(scorer: &shapegen_runtime::score::silhouette::SilhouetteScorer,
/// #         batch: &shapegen_runtime::score::InstanceBatch) -> Result<(), Box<dyn std::error::Error>> {
/// use shapegen_runtime::gpu::GpuContext;
/// use shapegen_runtime::score::silhouette::{GpuSilhouetteScorer, SilhouetteCounts};
///
/// let gpu = GpuContext::new()?;
/// let on_gpu = GpuSilhouetteScorer::new(&gpu, scorer)?;
/// let mut counts = vec![SilhouetteCounts::default(); batch.len()];
/// on_gpu.count_batch(batch, &mut counts)?;
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct GpuSilhouetteScorer<'a> {
    pub(super) gpu: &'a GpuContext,
    program: Program,
    pub(super) meshes: GpuMeshes,
    pub(super) targets: Vec<GpuTarget>,
    coverage: wgpu::Buffer,
    /// Models per chunk.
    chunk: usize,
    /// Largest bitset of one model, in 32-bit words.
    image_words: u64,
}

fn row_words32(width: u32) -> u32 {
    width.div_ceil(32)
}

impl<'a> GpuSilhouetteScorer<'a> {
    /// Uploads `scorer`'s meshes and targets to `gpu` and builds the pipeline.
    ///
    /// # Errors
    /// [`GpuError::Unsupported`] when a target is larger than the device's textures or
    /// one model's bitset exceeds the largest binding; [`GpuError::Device`] when the
    /// device rejects the shader or a resource.
    pub fn new(gpu: &'a GpuContext, scorer: &SilhouetteScorer) -> Result<Self, GpuError> {
        let limits = gpu.device.limits();
        let mut image_words = 0u64;
        for t in scorer.targets() {
            let side = limits.max_texture_dimension_2d;
            if t.width() > side || t.height() > side {
                return Err(GpuError::Unsupported(format!(
                    "target `{}` is {} x {} pixels; this device's images are at most {side} x {side}",
                    t.name(),
                    t.width(),
                    t.height()
                )));
            }
            image_words =
                image_words.max(u64::from(row_words32(t.width())) * u64::from(t.height()));
        }
        let per_model = image_words * 4;
        let chunk = (gpu.max_binding() / per_model).min(MAX_CHUNK);
        if chunk == 0 {
            return Err(GpuError::Unsupported(format!(
                "one model's coverage takes {per_model} bytes; this device binds at most {}",
                gpu.max_binding()
            )));
        }
        gpu.checked(|| Self::build(gpu, scorer, image_words, chunk as usize))
    }

    fn build(
        gpu: &'a GpuContext,
        scorer: &SilhouetteScorer,
        image_words: u64,
        chunk: usize,
    ) -> Self {
        let device = &gpu.device;
        let meshes = GpuMeshes::upload(device, &scorer.meshes);
        let targets = GpuTarget::upload(device, scorer.targets());
        let coverage = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("silhouette coverage"),
            size: image_words * 4 * chunk as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let program = Program::new::<GpuInstance>(
            gpu,
            "silhouette",
            shapegen_shaders::SILHOUETTE,
            &wgpu::vertex_attr_array![4 => Uint32],
        );
        GpuSilhouetteScorer {
            gpu,
            program,
            meshes,
            targets,
            coverage,
            chunk,
            image_words,
        }
    }

    /// Counts every model of `batch`, writing model `i`'s counts to `out[i]`.
    ///
    /// # Errors
    /// [`GpuError::Unsupported`] when `out.len() != batch.len()` or the batch's counts
    /// exceed the largest binding; [`GpuError::Device`] when the device fails.
    pub fn count_batch(
        &self,
        batch: &InstanceBatch,
        out: &mut [SilhouetteCounts],
    ) -> Result<(), GpuError> {
        if out.len() != batch.len() {
            return Err(GpuError::Unsupported(format!(
                "{} count slots given for a batch of {} models; give one per model",
                out.len(),
                batch.len()
            )));
        }
        let targets = self.targets.len();
        if batch.len() > self.max_batch() {
            return Err(GpuError::Unsupported(format!(
                "the counts of {} models exceed the largest storage binding, which holds those \
                 of {}; count fewer at once",
                batch.len(),
                self.max_batch()
            )));
        }
        if batch.is_empty() {
            return Ok(());
        }
        let (instances, mesh_ranges) = self.sort_instances(batch);
        let counts = self
            .gpu
            .checked(|| self.encode(batch.len(), &instances, &mesh_ranges))?;
        let counters = Counters::read(self.gpu, &counts, batch.len(), targets)?;
        for (i, slot) in out.iter_mut().enumerate() {
            let mut counts = SilhouetteCounts::zeroed(targets);
            for (k, c) in counts.targets_mut().iter_mut().enumerate() {
                let [covered, on_target, level_sum] = counters.get::<u32>(i, k);
                *c = TargetCounts {
                    covered,
                    on_target,
                    off_target: covered - on_target,
                    level_sum: u64::from(level_sum),
                };
            }
            *slot = counts;
        }
        Ok(())
    }

    /// Every instance of `batch` whose mesh the scorer has, sorted by mesh and then by
    /// model, with each mesh's range of them.
    fn sort_instances(&self, batch: &InstanceBatch) -> (Vec<GpuInstance>, Vec<Range<u32>>) {
        let meshes = self.meshes.len();
        let mut starts = vec![0u32; meshes + 1];
        for instance in batch.instances() {
            let m = instance.mesh.0 as usize;
            if m < meshes {
                starts[m + 1] += 1;
            }
        }
        for m in 0..meshes {
            starts[m + 1] += starts[m];
        }
        let mut next = starts.clone();
        let mut sorted = vec![GpuInstance::zeroed(); starts[meshes] as usize];
        for model in 0..batch.len() {
            for instance in batch.model(model) {
                let m = instance.mesh.0 as usize;
                if m >= meshes {
                    continue;
                }
                sorted[next[m] as usize] = GpuInstance {
                    rows: rows(&instance.transform),
                    model: model as u32,
                    _pad: [0; 3],
                };
                next[m] += 1;
            }
        }
        let ranges = (0..meshes).map(|m| starts[m]..starts[m + 1]).collect();
        (sorted, ranges)
    }

    /// Encodes and submits every pass, returning the buffer the counts land in.
    fn encode(
        &self,
        models: usize,
        instances: &[GpuInstance],
        mesh_ranges: &[Range<u32>],
    ) -> wgpu::Buffer {
        let count_bytes = counter_bytes(models, self.targets.len());
        let mut passes = Passes::new(
            self.gpu,
            &self.program,
            &self.meshes,
            instances,
            count_bytes,
        );
        for first in (0..models).step_by(self.chunk) {
            let chunk = first..(first + self.chunk).min(models);
            for target in &self.targets {
                let row_words = row_words32(target.view.width);
                let params = Params {
                    view: target.view,
                    row_words,
                    image_words: row_words * target.view.height,
                    first_model: first as u32,
                    index: target.index,
                };
                let used = u64::from(params.image_words) * 4 * chunk.len() as u64;
                passes.encoder.clear_buffer(&self.coverage, 0, Some(used));
                let draws = mesh_ranges
                    .iter()
                    .map(|range| chunk_range(instances, range, &chunk));
                passes.draw(target, &params, &self.coverage, draws);
            }
        }
        passes.submit()
    }

    /// The most models one batch may hold: as many as the largest storage binding holds
    /// counts of, for every target.
    pub fn max_batch(&self) -> usize {
        let per_model = counter_bytes(1, self.targets.len().max(1));
        (self.gpu.max_binding() / per_model) as usize
    }

    /// Models per chunk: how many share one coverage buffer.
    pub fn chunk_size(&self) -> usize {
        self.chunk
    }

    /// Bytes of one model's coverage bitset (the largest target's).
    pub fn bitset_bytes(&self) -> u64 {
        self.image_words * 4
    }
}

/// The part of one mesh's instance range (sorted by model) whose models lie in `chunk`.
fn chunk_range(instances: &[GpuInstance], range: &Range<u32>, chunk: &Range<usize>) -> Range<u32> {
    let of_mesh = &instances[range.start as usize..range.end as usize];
    let lo = of_mesh.partition_point(|i| (i.model as usize) < chunk.start);
    let hi = of_mesh.partition_point(|i| (i.model as usize) < chunk.end);
    range.start + lo as u32..range.start + hi as u32
}
