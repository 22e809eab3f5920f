//! The adapter, device and queue, found without a window.

use crate::error::RenderError;
use crate::renderer::Renderer;

/// The backends to try: the one `WGPU_BACKEND` names (`vulkan`, `gl`, ...), else every one,
/// software rasterisers included.
pub(crate) fn backends() -> wgpu::Backends {
    wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all())
}

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
        descriptor.backends = backends();
        let instance = wgpu::Instance::new(descriptor);
        Gpu::open(&instance, None, "carom offscreen")
    }

    /// Finds an adapter of `instance` that the renderer can use (and that can draw into
    /// `surface`, when one is given) and opens a device named `label` on it.
    pub(crate) fn open(
        instance: &wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
        label: &str,
    ) -> Result<Gpu, RenderError> {
        pollster::block_on(Gpu::request(instance, surface, label))
    }

    /// Finds an adapter of `instance` that the renderer can use (and that can draw into
    /// `surface`, when one is given) and opens a device named `label` on it. Asynchronous as
    /// the web needs it, where both are promises; elsewhere block on it with any executor.
    /// The limits asked for are downlevel ones, so GL and software adapters qualify as well
    /// as GPUs, and on the web WebGL2's.
    pub async fn request(
        instance: &wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
        label: &str,
    ) -> Result<Gpu, RenderError> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                compatible_surface: surface,
                ..Default::default()
            })
            .await
            .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        Renderer::check(&adapter)?;
        let limits = if cfg!(target_arch = "wasm32") {
            wgpu::Limits::downlevel_webgl2_defaults()
        } else {
            wgpu::Limits::downlevel_defaults()
        };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some(label),
                required_limits: limits.using_resolution(adapter.limits()),
                ..Default::default()
            })
            .await
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
