//! Drawing into a window: the surface, the device behind it and the renderer, set up in one
//! call so a program only has to open the window and hand it over.

use crate::camera::Camera;
use crate::error::RenderError;
use crate::gpu::{Gpu, backends};
use crate::renderer::{Renderer, clear_color};
use carom::draw::{Color, DrawList};
use std::sync::Arc;

/// A window's surface with a device that can draw into it and a [`Renderer`] for its format.
///
/// carom-render does not depend on a windowing library: anything with a window handle will
/// do. With winit, pass the `Arc<Window>` and the event loop's `owned_display_handle()`.
pub struct Screen {
    gpu: Gpu,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    renderer: Renderer,
}

impl Screen {
    /// Opens a device that can draw into `window`, whose drawable area is `size` pixels wide
    /// and high (a zero side counts as 1).
    ///
    /// `display` is the handle of the display the window is on (winit's
    /// `ActiveEventLoop::owned_display_handle()`); wgpu's GL backend needs it. Every backend is
    /// tried, software rasterisers too, unless `WGPU_BACKEND` names one (`vulkan`, `gl`, ...).
    /// Frames are paced to the display (vsync).
    pub fn new<W, D>(window: Arc<W>, display: D, size: [u32; 2]) -> Result<Screen, RenderError>
    where
        W: wgpu::WindowHandle + 'static,
        D: wgpu::rwh::HasDisplayHandle + std::fmt::Debug + Send + Sync + 'static,
    {
        let mut descriptor = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(display));
        descriptor.backends = backends();
        let instance = wgpu::Instance::new(descriptor);
        // Owning an Arc of the window makes the surface 'static, so it can live in `Screen`.
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Window(Box::new(window)))
            .map_err(|e| RenderError::Surface(e.to_string()))?;
        let gpu = Gpu::open(&instance, Some(&surface), "carom window")?;
        // The surface's preferred format: the renderer and `clear_color` handle sRGB or not.
        let [width, height] = size.map(|side| side.max(1));
        let mut config = (surface.get_default_config(&gpu.adapter, width, height))
            .ok_or_else(|| RenderError::Incompatible(gpu.adapter.get_info().name))?;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        surface.configure(&gpu.device, &config);
        let renderer = Renderer::new(&gpu.device, config.format);
        Ok(Screen {
            gpu,
            surface,
            config,
            renderer,
        })
    }

    /// Follows the window to its new size, in pixels. A zero side (a minimised window) counts
    /// as 1, since an empty surface is invalid.
    pub fn resize(&mut self, width: u32, height: u32) {
        self.config.width = width.max(1);
        self.config.height = height.max(1);
        self.surface.configure(&self.gpu.device, &self.config);
    }

    /// The surface's width and height, pixels: the viewport to frame a [`Camera`] for.
    pub fn size(&self) -> [u32; 2] {
        [self.config.width, self.config.height]
    }

    /// Clears the window to `clear`, draws `list` as `camera` sees it, and presents the frame.
    ///
    /// Returns false when the surface had no frame to give (resized under us, hidden, timed
    /// out): nothing was drawn, the surface was set up again, and the next call should succeed.
    pub fn draw(&mut self, list: &DrawList, camera: &Camera, clear: Color) -> bool {
        self.draw_with(list, camera, clear, || {})
    }

    /// [`Screen::draw`], calling `before_present` once the frame is drawn, just before it is
    /// presented. With winit, pass `|| window.pre_present_notify()`, which paces frames
    /// properly on Wayland.
    pub fn draw_with(
        &mut self,
        list: &DrawList,
        camera: &Camera,
        clear: Color,
        before_present: impl FnOnce(),
    ) -> bool {
        let (frame, suboptimal) = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => (frame, false),
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => (frame, true),
            _ => {
                self.surface.configure(&self.gpu.device, &self.config);
                return false;
            }
        };
        let Gpu { device, queue, .. } = &self.gpu;
        (self.renderer).prepare(device, queue, list, camera, self.size());
        let view = frame.texture.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        let clear = clear_color(clear, self.config.format);
        (self.renderer).render_cleared(&mut encoder, &view, clear, "carom window");
        queue.submit([encoder.finish()]);
        before_present();
        queue.present(frame);
        if suboptimal {
            // Drawn, but the window has changed under the surface: match it for the next frame.
            self.surface.configure(device, &self.config);
        }
        true
    }

    /// The adapter, device and queue, to draw more (a user interface, say) with.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The surface's texture format, for pipelines that draw into it.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The window's surface, for programs that render their frames themselves.
    pub fn surface(&self) -> &wgpu::Surface<'static> {
        &self.surface
    }

    /// The renderer that draws the [`DrawList`], to use in a render pass of your own.
    pub fn renderer_mut(&mut self) -> &mut Renderer {
        &mut self.renderer
    }
}
