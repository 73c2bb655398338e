//! The GPU backend's plumbing: choosing an adapter, creating the device, compiling shaders
//! and reading results back. The scorers' GPU paths build on it; their WGSL is the
//! `shapegen-shaders` crate's.
//!
//! Every GPU path has a CPU path that gives the same counts; a caller that finds no adapter
//! ([`GpuContext::new`] fails) scores on the CPU and says so.
//!
//! ```
//! use shapegen_runtime::gpu::GpuContext;
//!
//! match GpuContext::new() {
//!     Ok(gpu) => println!("scoring on {}", gpu.describe()),
//!     Err(err) => println!("no GPU ({err}); scoring on the CPU"),
//! }
//! ```

pub use wgpu;

/// Why the GPU backend cannot be used, or failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GpuError {
    /// No adapter was found, or it could not give a device.
    #[error("no usable GPU adapter: {0}")]
    NoAdapter(String),
    /// This scorer or scene cannot run on the GPU; the CPU path can.
    #[error("not supported on the GPU: {0}")]
    Unsupported(String),
    /// The device reported an error (validation, out of memory, lost device, mapping).
    #[error("GPU error: {0}")]
    Device(String),
}

/// Storage bindings are kept at or below this size, whatever the device allows, so that
/// batches fit every adapter that meets WebGPU's default limits.
pub const MAX_BINDING: u64 = 128 << 20;

/// An adapter's device and queue, with what the adapter is.
#[derive(Debug)]
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter the device was created on.
    pub info: wgpu::AdapterInfo,
}

impl GpuContext {
    /// Opens the high-performance adapter (the environment variables `WGPU_BACKEND` and
    /// `WGPU_ADAPTER_NAME` narrow the choice) with the adapter's own limits.
    ///
    /// # Errors
    /// [`GpuError::NoAdapter`] when there is no adapter or it gives no device.
    pub fn new() -> Result<GpuContext, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        };
        let adapter = pollster::block_on(instance.request_adapter(&options))
            .map_err(|err| GpuError::NoAdapter(err.to_string()))?;
        let info = adapter.get_info();
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("shapegen"),
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
            .map_err(|err| GpuError::NoAdapter(format!("{} gave no device: {err}", info.name)))?;
        device.on_uncaptured_error(std::sync::Arc::new(|err: wgpu::Error| {
            eprintln!("shapegen: uncaptured GPU error: {err}");
        }));
        Ok(GpuContext {
            device,
            queue,
            info,
        })
    }

    /// The adapter in words, e.g. `NVIDIA H200 (Vulkan, discrete GPU)` or
    /// `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, CPU)`.
    pub fn describe(&self) -> String {
        let kind = match self.info.device_type {
            wgpu::DeviceType::DiscreteGpu => "discrete GPU",
            wgpu::DeviceType::IntegratedGpu => "integrated GPU",
            wgpu::DeviceType::VirtualGpu => "virtual GPU",
            wgpu::DeviceType::Cpu => "CPU",
            wgpu::DeviceType::Other => "other",
        };
        format!("{} ({}, {kind})", self.info.name, self.info.backend)
    }

    /// The largest storage binding to use: the device's limit, at most [`MAX_BINDING`].
    pub fn max_binding(&self) -> u64 {
        let limits = self.device.limits();
        limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size)
            .min(MAX_BINDING)
    }

    /// Compiles WGSL `source` into a shader module.
    ///
    /// # Errors
    /// [`GpuError::Device`] with the compiler's message when the device rejects it.
    pub fn shader(&self, label: &str, source: &str) -> Result<wgpu::ShaderModule, GpuError> {
        self.checked(|| {
            self.device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                })
        })
    }

    /// Runs `work` (resource creation, encoding, submission) and turns any validation or
    /// out-of-memory error it caused into [`GpuError::Device`].
    ///
    /// # Errors
    /// The first error the device reported during `work`.
    pub fn checked<T>(&self, work: impl FnOnce() -> T) -> Result<T, GpuError> {
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = work();
        let validation = pollster::block_on(validation.pop());
        let oom = pollster::block_on(oom.pop());
        match validation.or(oom) {
            Some(err) => Err(GpuError::Device(err.to_string())),
            None => Ok(value),
        }
    }

    /// Copies the first `bytes` bytes of `buffer` (which needs `COPY_SRC` usage) into a
    /// staging buffer, waits for the queue, and returns them.
    ///
    /// # Errors
    /// [`GpuError::Device`] when the copy, the wait or the mapping fails.
    pub fn read_back(&self, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, GpuError> {
        if bytes == 0 {
            return Ok(Vec::new());
        }
        let size = bytes.next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
        let staging = self.checked(|| {
            let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("shapegen read-back"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
            encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
            self.queue.submit([encoder.finish()]);
            staging
        })?;
        let (sender, receiver) = std::sync::mpsc::channel();
        staging.map_async(wgpu::MapMode::Read, .., move |result| {
            // The receiver waits below; a send can only fail once it is gone.
            let _ = sender.send(result);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|err| GpuError::Device(format!("waiting for the GPU: {err}")))?;
        receiver
            .recv()
            .map_err(|_| GpuError::Device("the read-back was dropped".into()))?
            .map_err(|err| GpuError::Device(format!("mapping the read-back: {err}")))?;
        let bytes =
            usize::try_from(bytes).map_err(|_| GpuError::Device("read-back too large".into()))?;
        let view = staging
            .get_mapped_range(..)
            .map_err(|err| GpuError::Device(format!("reading the read-back: {err}")))?;
        let out = view[..bytes].to_vec();
        drop(view);
        staging.unmap();
        Ok(out)
    }
}
