//! The adapter, device and queue, found without a window.

use crate::error::RenderError;
use crate::renderer::Renderer;

/// A device ready to draw offscreen.
pub struct Gpu {
    /// The adapter the device came from.
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// Finds an adapter across all backends (Vulkan first, else GL), or those `WGPU_BACKEND`
    /// names, software rasterisers included, and opens a device on it.
    pub fn headless() -> Result<Gpu, RenderError> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle();
        descriptor.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
        let instance = wgpu::Instance::new(descriptor);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        }))
        .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        Renderer::check(&adapter)?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("carom offscreen"),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Gpu {
            adapter,
            device,
            queue,
        })
    }

    /// The adapter's name and backend, for reports.
    pub fn describe(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} on {:?}", info.name, info.backend)
    }
}
