//! Drawing into a window: the surface, the device behind it and the renderer, set up in one
//! call so a program only has to open the window and hand it over.

use crate::camera::Camera;
use crate::error::RenderError;
use crate::gpu::{Gpu, backends};
use crate::renderer::{Renderer, clear_color};
use carom::draw::{Color, DrawList};
use std::sync::Arc;

/// How a [`Screen`] is set up, beyond its window. The default suits a program that only draws
/// carom's [`DrawList`].
#[derive(Debug, Clone, Default)]
pub struct ScreenOptions {
    /// The backends to try; by default those `WGPU_BACKEND` names (`vulkan`, `gl`, ...), else
    /// every one, software rasterisers too.
    pub backends: Option<wgpu::Backends>,
    /// Prefer a surface format that is not sRGB, when the surface offers one: what a user
    /// interface that blends in gamma space (egui) needs. By default the surface's preferred
    /// format; the renderer and [`clear_color`] handle either.
    pub gamma_format: bool,
    /// Make each frame readable (copied from), when the surface allows it, for screenshots;
    /// [`Screen::readable`] says whether it does.
    pub readable: bool,
}

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

/// A frame of a [`Screen`] to draw into: its texture, until [`Screen::present`] shows it.
pub struct ScreenFrame {
    frame: wgpu::SurfaceTexture,
    /// The window changed under the surface: the frame is drawn, then the surface set up again.
    suboptimal: bool,
}

impl ScreenFrame {
    /// The texture to draw the frame into.
    pub fn texture(&self) -> &wgpu::Texture {
        &self.frame.texture
    }
}

impl Screen {
    /// Opens a device that can draw into `window`, whose drawable area is `size` pixels wide
    /// and high (a zero side counts as 1), with the default [`ScreenOptions`], blocking until
    /// it is ready (use [`Screen::request`] on the web).
    ///
    /// `display` is the handle of the display the window is on (winit's
    /// `ActiveEventLoop::owned_display_handle()`); wgpu's GL backend needs it. Frames are paced
    /// to the display (vsync).
    pub fn new<W, D>(window: Arc<W>, display: D, size: [u32; 2]) -> Result<Screen, RenderError>
    where
        W: wgpu::WindowHandle + 'static,
        D: wgpu::rwh::HasDisplayHandle + std::fmt::Debug + Send + Sync + 'static,
    {
        pollster::block_on(Screen::request(
            window,
            display,
            size,
            &ScreenOptions::default(),
        ))
    }

    /// [`Screen::new`] with `options`, asynchronous as the web needs it (where the adapter
    /// and the device are promises, and WebGPU is used where the browser has it, WebGL2
    /// otherwise); elsewhere block on it with any executor.
    pub async fn request<W, D>(
        window: Arc<W>,
        display: D,
        size: [u32; 2],
        options: &ScreenOptions,
    ) -> Result<Screen, RenderError>
    where
        W: wgpu::WindowHandle + 'static,
        D: wgpu::rwh::HasDisplayHandle + std::fmt::Debug + Send + Sync + 'static,
    {
        let mut descriptor = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(display));
        descriptor.backends = options.backends.unwrap_or_else(backends);
        let instance = wgpu::util::new_instance_with_webgpu_detection(descriptor).await;
        // Owning an Arc of the window makes the surface 'static, so it can live in `Screen`.
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Window(Box::new(window)))
            .map_err(|e| RenderError::Surface(e.to_string()))?;
        let gpu = Gpu::request(&instance, Some(&surface), "carom window").await?;
        let capabilities = surface.get_capabilities(&gpu.adapter);
        let Some(&preferred) = capabilities.formats.first() else {
            return Err(RenderError::Incompatible(gpu.adapter.get_info().name));
        };
        let format = match options.gamma_format {
            true => (capabilities.formats.iter().copied())
                .find(|f| !f.is_srgb())
                .unwrap_or(preferred),
            false => preferred,
        };
        let readable =
            options.readable && capabilities.usages.contains(wgpu::TextureUsages::COPY_SRC);
        let mut config = wgpu::SurfaceConfiguration {
            usage: match readable {
                true => wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                false => wgpu::TextureUsages::RENDER_ATTACHMENT,
            },
            format,
            width: 1,
            height: 1,
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: capabilities.alpha_modes[0],
            view_formats: Vec::new(),
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let [width, height] = fit(&gpu, size);
        (config.width, config.height) = (width, height);
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
    /// as 1, since an empty surface is invalid, and a side past the device's largest texture
    /// as that largest.
    pub fn resize(&mut self, width: u32, height: u32) {
        [self.config.width, self.config.height] = fit(&self.gpu, [width, height]);
        self.surface.configure(&self.gpu.device, &self.config);
    }

    /// The next frame to draw into, or `None` when the surface has none to give (resized
    /// under us, hidden, timed out): a stale surface is set up again, and a later call
    /// succeeds. Draw into its [`ScreenFrame::texture`], submit, then [`Screen::present`] it.
    pub fn next_frame(&mut self) -> Option<ScreenFrame> {
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => Some(ScreenFrame {
                frame,
                suboptimal: false,
            }),
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => Some(ScreenFrame {
                frame,
                suboptimal: true,
            }),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                // The window changed under the surface, or the surface was lost: set it up again.
                self.surface.configure(&self.gpu.device, &self.config);
                None
            }
            // Timed out or hidden: the same surface gives a frame once the window can show one.
            _ => None,
        }
    }

    /// Shows a frame drawn into (its work submitted to the queue).
    pub fn present(&mut self, frame: ScreenFrame) {
        self.gpu.queue.present(frame.frame);
        if frame.suboptimal {
            // Drawn, but the window has changed under the surface: match it for the next frame.
            self.surface.configure(&self.gpu.device, &self.config);
        }
    }

    /// Whether frames can be copied from (asked for with [`ScreenOptions::readable`] and
    /// allowed by the surface).
    pub fn readable(&self) -> bool {
        self.config.usage.contains(wgpu::TextureUsages::COPY_SRC)
    }

    /// The surface's width and height, pixels: the viewport to frame a [`Camera`] for.
    pub fn size(&self) -> [u32; 2] {
        [self.config.width, self.config.height]
    }

    /// Clears the window to `clear`, draws `list` as `camera` sees it, and presents the frame.
    ///
    /// Returns false when the surface had no frame to give (resized under us, hidden, timed
    /// out): nothing was drawn, a stale surface was set up again, and a later call succeeds.
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
        let Some(frame) = self.next_frame() else {
            return false;
        };
        self.prepare(list, camera, self.size());
        let Gpu { device, queue, .. } = &self.gpu;
        let view = frame.texture().create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        let clear = clear_color(clear, self.config.format);
        (self.renderer).render_cleared(&mut encoder, &view, clear, "carom window");
        queue.submit([encoder.finish()]);
        before_present();
        self.present(frame);
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
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// The renderer, to prepare a frame's [`DrawList`] with.
    pub fn renderer_mut(&mut self) -> &mut Renderer {
        &mut self.renderer
    }

    /// Prepares the renderer to draw `list` as `camera` sees it into a viewport of
    /// `viewport` pixels (a part of the window, when something else shares it), for
    /// [`Renderer::render`] in a render pass of your own.
    pub fn prepare(&mut self, list: &DrawList, camera: &Camera, viewport: [u32; 2]) {
        let Gpu { device, queue, .. } = &self.gpu;
        self.renderer.prepare(device, queue, list, camera, viewport);
    }
}

/// `size` with each side at least 1 and at most the device's largest texture.
fn fit(gpu: &Gpu, size: [u32; 2]) -> [u32; 2] {
    let largest = gpu.device.limits().max_texture_dimension_2d;
    size.map(|side| side.clamp(1, largest))
}
