//! What both GPU silhouette programs draw with: the meshes and targets uploaded once, a
//! program's render pipeline, and the passes of one submission with the counters they
//! add to.
//!
//! Both programs ([`shapegen_shaders::SILHOUETTE`] and
//! [`shapegen_shaders::SILHOUETTE_RETAINED`]) bind a uniform `Params` (0), the target's
//! pixels (1), a buffer of per-pixel state (2) and per (model, target) counters (3); their
//! vertex stage reads the mesh's positions at location 0 and the instance's transform rows
//! at locations 1 to 3, followed by the program's own instance words. Each `Params`
//! starts with the target's [`View`] and ends with its [`TargetIndex`].

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use super::meshes::RasterMesh;
use super::target::ImageTarget;
use crate::gpu::{GpuContext, GpuError};

/// The attachment's format; nothing is ever written to it.
const ATTACHMENT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// Words of one (model, target)'s counters: covered, on target, grey-level sum, unused.
const COUNTER_WORDS: usize = 4;

/// The head of both programs' `Params`: a target's camera and size.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(super) struct View {
    /// The camera's view-projection matrix, by columns.
    view_projection: [[f32; 4]; 4],
    /// Width in pixels.
    pub(super) width: u32,
    /// Height in pixels.
    pub(super) height: u32,
}

/// The tail of both programs' `Params`: how many targets there are, and which one a pass
/// draws through.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(super) struct TargetIndex {
    targets: u32,
    target_index: u32,
    _pad: u32,
}

/// One target as the GPU sees it.
#[derive(Debug)]
pub(super) struct GpuTarget {
    /// Its camera and size.
    pub(super) view: View,
    /// Its place among the targets.
    pub(super) index: TargetIndex,
    /// Per pixel, row by row from the top: grey level in bits 0-7, target pixel in bit 8.
    pixels: wgpu::Buffer,
    /// What its passes draw into (cleared, never stored).
    attachment: wgpu::TextureView,
}

impl GpuTarget {
    /// Uploads every one of `targets`.
    pub(super) fn upload(device: &wgpu::Device, targets: &[ImageTarget]) -> Vec<GpuTarget> {
        let count = targets.len() as u32;
        targets
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
                GpuTarget {
                    view: View {
                        view_projection: t.view_projection().to_cols_array_2d(),
                        width: t.width(),
                        height: t.height(),
                    },
                    index: TargetIndex {
                        targets: count,
                        target_index: k as u32,
                        _pad: 0,
                    },
                    pixels,
                    attachment: texture.create_view(&wgpu::TextureViewDescriptor::default()),
                }
            })
            .collect()
    }
}

/// The scorer's meshes as the vertex stage reads them: the corners of every triangle,
/// mesh after mesh.
#[derive(Debug)]
pub(super) struct GpuMeshes {
    vertices: wgpu::Buffer,
    /// Vertex range of each mesh in `vertices`, indexed by mesh id.
    ranges: Vec<Range<u32>>,
}

impl GpuMeshes {
    /// Uploads `meshes`, indexed by mesh id.
    pub(super) fn upload(device: &wgpu::Device, meshes: &[RasterMesh]) -> GpuMeshes {
        let mut positions: Vec<[f32; 3]> = Vec::new();
        let mut ranges = Vec::new();
        for mesh in meshes {
            let first = positions.len() as u32;
            for tri in &mesh.triangles {
                positions.extend(tri.map(|i| mesh.positions[i as usize].to_array()));
            }
            ranges.push(first..positions.len() as u32);
        }
        if positions.is_empty() {
            positions.push([0.0; 3]);
        }
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("silhouette vertices"),
            contents: bytemuck::cast_slice(&positions),
            usage: wgpu::BufferUsages::VERTEX,
        });
        GpuMeshes { vertices, ranges }
    }

    /// The number of meshes.
    pub(super) fn len(&self) -> usize {
        self.ranges.len()
    }
}

/// A silhouette program's render pipeline, with the layout of its bind group.
#[derive(Debug)]
pub(super) struct Program {
    label: &'static str,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

impl Program {
    /// Compiles `source` for instances of type `I`: the rows of a transform
    /// ([`rows`]) followed by the words `instance_tail` reads (locations from 4, offsets
    /// from the end of the rows, as `wgpu::vertex_attr_array!` gives them).
    pub(super) fn new<I: Pod>(
        gpu: &GpuContext,
        label: &'static str,
        source: &str,
        instance_tail: &[wgpu::VertexAttribute],
    ) -> Program {
        let device = &gpu.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = bind_group_layout(device, label);
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
        let instance_attributes: Vec<wgpu::VertexAttribute> =
            rows.into_iter().chain(tail).collect();
        let buffers = [
            Some(wgpu::VertexBufferLayout {
                array_stride: 12,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3],
            }),
            Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<I>() as u64,
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
        Program {
            label,
            pipeline,
            layout,
        }
    }
}

/// The bindings of a [`Program`]: the uniforms (0) and three storage buffers, the first
/// read-only.
fn bind_group_layout(device: &wgpu::Device, label: &'static str) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
    })
}

/// A fragment-stage storage binding.
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

/// The rows of an affine transform, as the vertex stage reads them.
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

/// Bytes of the counters of `models` models on `targets` targets.
pub(super) fn counter_bytes(models: usize, targets: usize) -> u64 {
    (models * targets * COUNTER_WORDS * 4) as u64
}

/// The passes of one submission: a program's draws of one buffer of instances, adding to
/// one buffer of counters.
pub(super) struct Passes<'a> {
    gpu: &'a GpuContext,
    program: &'a Program,
    meshes: &'a GpuMeshes,
    instances: wgpu::Buffer,
    counters: wgpu::Buffer,
    /// Records the passes, and whatever the program clears or copies before them.
    pub(super) encoder: wgpu::CommandEncoder,
}

impl<'a> Passes<'a> {
    /// Uploads `instances` (one zeroed record when there are none, as a buffer may not be
    /// empty) and zeroed counters of `counter_bytes` bytes ([`counter_bytes`]).
    pub(super) fn new<I: Pod>(
        gpu: &'a GpuContext,
        program: &'a Program,
        meshes: &'a GpuMeshes,
        instances: &[I],
        counter_bytes: u64,
    ) -> Passes<'a> {
        let device = &gpu.device;
        let empty = vec![0u8; size_of::<I>()];
        let instances = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(program.label),
            contents: if instances.is_empty() {
                &empty
            } else {
                bytemuck::cast_slice(instances)
            },
            usage: wgpu::BufferUsages::VERTEX,
        });
        let counters = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(program.label),
            size: counter_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some(program.label),
        });
        Passes {
            gpu,
            program,
            meshes,
            instances,
            counters,
            encoder,
        }
    }

    /// Records one pass through `target` with `params` (the program's `Params`) as the
    /// uniform and `state` as its per-pixel state, drawing each mesh's range of
    /// `instances` (one range per mesh, by mesh id).
    pub(super) fn draw<P: Pod>(
        &mut self,
        target: &GpuTarget,
        params: &P,
        state: &wgpu::Buffer,
        instances: impl IntoIterator<Item = Range<u32>>,
    ) {
        let device = &self.gpu.device;
        let label = Some(self.program.label);
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label,
            contents: bytemuck::bytes_of(params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label,
            layout: &self.program.layout,
            entries: &[
                entry(0, &uniform),
                entry(1, &target.pixels),
                entry(2, state),
                entry(3, &self.counters),
            ],
        });
        let mut pass = self.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label,
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.attachment,
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
        pass.set_pipeline(&self.program.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.set_vertex_buffer(0, self.meshes.vertices.slice(..));
        pass.set_vertex_buffer(1, self.instances.slice(..));
        for (vertices, instances) in self.meshes.ranges.iter().cloned().zip(instances) {
            if !vertices.is_empty() && !instances.is_empty() {
                pass.draw(vertices, instances);
            }
        }
    }

    /// Submits the passes, returning the buffer the counters land in.
    pub(super) fn submit(self) -> wgpu::Buffer {
        self.gpu.queue.submit([self.encoder.finish()]);
        self.counters
    }
}

fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// The counters a submission's passes added to, read back.
pub(super) struct Counters {
    bytes: Vec<u8>,
    targets: usize,
}

impl Counters {
    /// Reads back the counters of `models` models on `targets` targets from `buffer` (as
    /// [`Passes::submit`] returns it).
    ///
    /// # Errors
    /// [`GpuError::Device`] when the copy, the wait or the mapping fails.
    pub(super) fn read(
        gpu: &GpuContext,
        buffer: &wgpu::Buffer,
        models: usize,
        targets: usize,
    ) -> Result<Counters, GpuError> {
        let bytes = gpu.read_back(buffer, counter_bytes(models, targets))?;
        Ok(Counters { bytes, targets })
    }

    /// The covered pixels, pixels on target and grey-level sum of `model` on `target`, as
    /// the program's 32-bit words `T` (`u32` totals or `i32` changes).
    pub(super) fn get<T: Pod>(&self, model: usize, target: usize) -> [T; 3] {
        let start = (model * self.targets + target) * COUNTER_WORDS * size_of::<T>();
        bytemuck::pod_read_unaligned(&self.bytes[start..start + size_of::<[T; 3]>()])
    }
}
