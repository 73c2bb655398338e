//! The GPU context itself: buffers read back, bad shaders are errors.

use shapegen_runtime::gpu::{GpuContext, GpuError, MAX_BINDING, wgpu};

use crate::GpuTest;

/// The tests of this module.
pub const TESTS: &[GpuTest] = &[
    ("context::a_buffer_reads_back", a_buffer_reads_back),
    (
        "context::a_bad_shader_is_an_error_not_a_panic",
        a_bad_shader_is_an_error_not_a_panic,
    ),
];

fn a_buffer_reads_back(gpu: &GpuContext) {
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: 8,
        usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    gpu.queue
        .write_buffer(&buffer, 0, &[1, 2, 3, 4, 5, 6, 7, 8]);
    assert_eq!(gpu.read_back(&buffer, 6).unwrap(), [1, 2, 3, 4, 5, 6]);
    assert!(gpu.max_binding() <= MAX_BINDING);
    assert!(!gpu.describe().is_empty());
}

fn a_bad_shader_is_an_error_not_a_panic(gpu: &GpuContext) {
    let err = gpu.shader("bad", "fn main( {").unwrap_err();
    assert!(matches!(err, GpuError::Device(_)), "{err}");
}
