//! The silhouette scorer on the GPU: a whole population per submission, counted by the
//! fragment shader of [`shapegen_shaders::SILHOUETTE`].

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use super::counts::{SilhouetteCounts, TargetCounts};
use super::scorer::SilhouetteScorer;
use crate::gpu::{GpuContext, GpuError};
use crate::score::InstanceBatch;

/// Mirrors the WGSL struct `Params` of [`shapegen_shaders::SILHOUETTE`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Params {
    view_projection: [[f32; 4]; 4],
    width: u32,
    height: u32,
    row_words: u32,
    image_words: u32,
    first_model: u32,
    targets: u32,
    target_index: u32,
    _pad: u32,
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

/// Counts of one (model, target) as the shader accumulates them: covered, on target,
/// grey-level sum, unused.
const COUNT_WORDS: usize = 4;

/// The attachment's format; nothing is ever written to it.
const ATTACHMENT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// Most models whose bitsets share one coverage buffer, whatever the binding limit.
const MAX_CHUNK: u64 = 256;

/// One target as the GPU sees it.
#[derive(Debug)]
pub(super) struct GpuTarget {
    params: Params,
    pub(super) pixels: wgpu::Buffer,
    pub(super) attachment: wgpu::TextureView,
}

impl GpuTarget {
    /// The camera's view-projection matrix, by columns.
    pub(super) fn view_projection(&self) -> [[f32; 4]; 4] {
        self.params.view_projection
    }

    /// Width and height in pixels.
    pub(super) fn size(&self) -> (u32, u32) {
        (self.params.width, self.params.height)
    }
}

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
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    pub(super) vertices: wgpu::Buffer,
    /// Vertex range of each mesh in `vertices`, indexed by mesh id.
    pub(super) mesh_vertices: Vec<Range<u32>>,
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
        let mut positions: Vec<[f32; 3]> = Vec::new();
        let mut mesh_vertices = Vec::new();
        for mesh in &scorer.meshes {
            let first = positions.len() as u32;
            for tri in &mesh.triangles {
                positions.extend(tri.map(|i| mesh.positions[i as usize].to_array()));
            }
            mesh_vertices.push(first..positions.len() as u32);
        }
        if positions.is_empty() {
            positions.push([0.0; 3]);
        }
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("silhouette vertices"),
            contents: bytemuck::cast_slice(&positions),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let count = scorer.targets().len() as u32;
        let targets = scorer
            .targets()
            .iter()
            .enumerate()
            .map(|(k, t)| {
                let pixels: Vec<u32> = (0..t.height())
                    .flat_map(|y| (0..t.width()).map(move |x| (x, y)))
                    .map(|(x, y)| u32::from(t.level(x, y)) | u32::from(t.is_target(x, y)) << 8)
                    .collect();
                let pixels = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("silhouette target pixels"),
                    contents: bytemuck::cast_slice(&pixels),
                    usage: wgpu::BufferUsages::STORAGE,
                });
                let texture = device.create_texture(&wgpu::TextureDescriptor {
                    label: Some("silhouette attachment"),
                    size: wgpu::Extent3d {
                        width: t.width(),
                        height: t.height(),
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: ATTACHMENT,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[],
                });
                let row_words = row_words32(t.width());
                GpuTarget {
                    params: Params {
                        view_projection: t.view_projection().to_cols_array_2d(),
                        width: t.width(),
                        height: t.height(),
                        row_words,
                        image_words: row_words * t.height(),
                        first_model: 0,
                        targets: count,
                        target_index: k as u32,
                        _pad: 0,
                    },
                    pixels,
                    attachment: texture.create_view(&wgpu::TextureViewDescriptor::default()),
                }
            })
            .collect();
        let coverage = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("silhouette coverage"),
            size: image_words * 4 * chunk as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (pipeline, layout) = pipeline(
            gpu,
            "silhouette",
            shapegen_shaders::SILHOUETTE,
            size_of::<GpuInstance>() as u64,
            &wgpu::vertex_attr_array![4 => Uint32],
        );
        GpuSilhouetteScorer {
            gpu,
            pipeline,
            layout,
            vertices,
            mesh_vertices,
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
        let count_bytes = (batch.len() * targets * COUNT_WORDS * 4) as u64;
        let (instances, mesh_ranges) = self.sort_instances(batch);
        let counts = self
            .gpu
            .checked(|| self.encode(batch.len(), &instances, &mesh_ranges, count_bytes))?;
        let bytes = self.gpu.read_back(&counts, count_bytes)?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        for (i, slot) in out.iter_mut().enumerate() {
            let mut counts = SilhouetteCounts::zeroed(targets);
            for (k, c) in counts.targets_mut().iter_mut().enumerate() {
                let w = &words[(i * targets + k) * COUNT_WORDS..][..COUNT_WORDS];
                *c = TargetCounts {
                    covered: w[0],
                    on_target: w[1],
                    off_target: w[0] - w[1],
                    level_sum: u64::from(w[2]),
                };
            }
            *slot = counts;
        }
        Ok(())
    }

    /// Every instance of `batch` whose mesh the scorer has, sorted by mesh and then by
    /// model, with each mesh's range of them.
    fn sort_instances(&self, batch: &InstanceBatch) -> (Vec<GpuInstance>, Vec<Range<u32>>) {
        let meshes = self.mesh_vertices.len();
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
        count_bytes: u64,
    ) -> wgpu::Buffer {
        let device = &self.gpu.device;
        let instance_buffer = instance_buffer(device, "silhouette instances", instances);
        let counts = result_buffer(device, "silhouette counts", count_bytes);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("silhouette"),
        });
        for first in (0..models).step_by(self.chunk) {
            let chunk = first..(first + self.chunk).min(models);
            for target in &self.targets {
                let params = Params {
                    first_model: first as u32,
                    ..target.params
                };
                let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("silhouette params"),
                    contents: bytemuck::bytes_of(&params),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("silhouette"),
                    layout: &self.layout,
                    entries: &[
                        entry(0, &uniform),
                        entry(1, &target.pixels),
                        entry(2, &self.coverage),
                        entry(3, &counts),
                    ],
                });
                let used = u64::from(params.image_words) * 4 * chunk.len() as u64;
                encoder.clear_buffer(&self.coverage, 0, Some(used));
                let draws = self
                    .mesh_vertices
                    .iter()
                    .zip(mesh_ranges)
                    .map(|(vertices, range)| {
                        (vertices.clone(), self.chunk_range(instances, range, &chunk))
                    });
                draw_pass(
                    &mut encoder,
                    &target.attachment,
                    &self.pipeline,
                    &bind_group,
                    &self.vertices,
                    &instance_buffer,
                    draws,
                );
            }
        }
        self.gpu.queue.submit([encoder.finish()]);
        counts
    }

    /// The part of one mesh's instance range (sorted by model) whose models lie in
    /// `chunk`.
    fn chunk_range(
        &self,
        instances: &[GpuInstance],
        range: &Range<u32>,
        chunk: &Range<usize>,
    ) -> Range<u32> {
        let of_mesh = &instances[range.start as usize..range.end as usize];
        let lo = of_mesh.partition_point(|i| (i.model as usize) < chunk.start);
        let hi = of_mesh.partition_point(|i| (i.model as usize) < chunk.end);
        range.start + lo as u32..range.start + hi as u32
    }

    /// The most models one batch may hold: as many as the largest storage binding holds
    /// counts of, for every target.
    pub fn max_batch(&self) -> usize {
        let per_model = (self.targets.len().max(1) * COUNT_WORDS * 4) as u64;
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

/// A vertex buffer of per-instance records (one zeroed record when there are none, as
/// a buffer may not be empty).
pub(super) fn instance_buffer<T: Pod>(
    device: &wgpu::Device,
    label: &str,
    instances: &[T],
) -> wgpu::Buffer {
    let empty = vec![0u8; size_of::<T>()];
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if instances.is_empty() {
            &empty
        } else {
            bytemuck::cast_slice(instances)
        },
        usage: wgpu::BufferUsages::VERTEX,
    })
}

/// A storage buffer of `bytes` the shader accumulates counters in, to be read back.
pub(super) fn result_buffer(device: &wgpu::Device, label: &str, bytes: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// The rows of an affine transform, as the vertex shaders read them.
pub(super) fn rows(t: &glam::Affine3A) -> [[f32; 4]; 3] {
    let (x, y, z, p) = (
        t.matrix3.x_axis,
        t.matrix3.y_axis,
        t.matrix3.z_axis,
        t.translation,
    );
    [
        [x.x, y.x, z.x, p.x],
        [x.y, y.y, z.y, p.y],
        [x.z, y.z, z.z, p.z],
    ]
}

pub(super) fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A silhouette shader's render pipeline and bind group layout. Both shaders bind a
/// uniform (0), the target's pixels (1) and two read-write buffers (2, 3), read the
/// mesh's vertex positions at location 0 and the instance's transform rows at
/// locations 1 to 3, followed by `instance_tail` (locations from 4, offsets from the
/// end of the rows, as `wgpu::vertex_attr_array!` gives them).
pub(super) fn pipeline(
    gpu: &GpuContext,
    label: &str,
    source: &str,
    instance_stride: u64,
    instance_tail: &[wgpu::VertexAttribute],
) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
            storage(1, true),
            storage(2, false),
            storage(3, false),
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let rows = wgpu::vertex_attr_array![1 => Float32x4, 2 => Float32x4, 3 => Float32x4];
    let rows_bytes = size_of::<[[f32; 4]; 3]>() as u64;
    let tail = instance_tail.iter().map(|a| wgpu::VertexAttribute {
        offset: a.offset + rows_bytes,
        ..*a
    });
    let instance_attributes: Vec<wgpu::VertexAttribute> = rows.into_iter().chain(tail).collect();
    let buffers = [
        Some(wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![0 => Float32x3],
        }),
        Some(wgpu::VertexBufferLayout {
            array_stride: instance_stride,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &instance_attributes,
        }),
    ];
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: ATTACHMENT,
                blend: None,
                write_mask: wgpu::ColorWrites::empty(),
            })],
        }),
        multiview_mask: None,
        cache: None,
    });
    (pipeline, layout)
}

/// Records one render pass into `attachment` (cleared, never stored) with `pipeline`,
/// `bind_group`, the meshes' `vertices` and `instances`, drawing for each
/// `(vertex range, instance range)` of `draws`.
pub(super) fn draw_pass(
    encoder: &mut wgpu::CommandEncoder,
    attachment: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    bind_group: &wgpu::BindGroup,
    vertices: &wgpu::Buffer,
    instances: &wgpu::Buffer,
    draws: impl IntoIterator<Item = (Range<u32>, Range<u32>)>,
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("silhouette"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: attachment,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Discard,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    pass.set_vertex_buffer(0, vertices.slice(..));
    pass.set_vertex_buffer(1, instances.slice(..));
    for (vertices, instances) in draws {
        if !vertices.is_empty() && !instances.is_empty() {
            pass.draw(vertices, instances);
        }
    }
}
