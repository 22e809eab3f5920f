//! The window: winit events in, a wgpu surface out, the scene drawn by `carom-render` and the
//! sidebar by egui on top. Everything else lives in [`Demo`], which knows nothing of windows.

use crate::capture::copy_to_buffer;
use crate::demo::{Button, Demo, Key};
use crate::ui::{SIDEBAR_WIDTH, sidebar};
use carom::{Color, DrawList, vec2};
use carom_render::{Renderer, clear_color};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// How the window starts and when it stops by itself.
#[derive(Debug, Clone)]
pub struct WindowOptions {
    /// The scene to open.
    pub scene: PathBuf,
    /// The folder whose scenes the menu lists.
    pub scenes_folder: PathBuf,
    /// Inner size, logical pixels.
    pub size: (u32, u32),
    /// Close after this many frames (for screenshots and tests).
    pub frames: Option<u64>,
    /// Save the window's contents to this PNG after the last frame.
    pub screenshot: Option<PathBuf>,
}

/// Opens the window and runs until it is closed (or `frames` have been shown).
pub fn run(options: WindowOptions) -> Result<(), String> {
    let event_loop = EventLoop::new().map_err(|e| format!("cannot open a window: {e}"))?;
    let mut app = App {
        options,
        running: None,
        failure: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| format!("the event loop failed: {e}"))?;
    if let Some(message) = app.failure {
        return Err(message);
    }
    if let (Some(_), Some(running)) = (app.options.frames, &app.running) {
        println!("{}", running.report());
    }
    Ok(())
}

struct App {
    options: WindowOptions,
    running: Option<Running>,
    failure: Option<String>,
}

/// Everything that exists while the window is open.
struct Running {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    renderer: Renderer,
    egui: egui::Context,
    egui_input: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    demo: Demo,
    list: DrawList,
    error: Option<String>,
    cursor: egui::Pos2,
    last_frame: Instant,
    frames: u64,
    /// Seconds of wall time per frame, smoothed, for the sidebar's frame rate.
    frame_seconds: f64,
    /// Wall time of every frame after the first, ms, for the report `--frames` prints.
    frame_ms: Vec<f64>,
    /// The adapter drawing, for that report.
    adapter: String,
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match Running::new(event_loop, &self.options) {
            Ok(running) => self.running = Some(running),
            Err(message) => {
                self.failure = Some(message);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(running) = &mut self.running else {
            return;
        };
        let response = running.egui_input.on_window_event(&running.window, &event);
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => running.resize(size.width, size.height),
            WindowEvent::RedrawRequested => match running.redraw(&self.options) {
                Ok(true) => {}
                Ok(false) => event_loop.exit(),
                Err(message) => {
                    self.failure = Some(message);
                    event_loop.exit();
                }
            },
            // The cursor's position and a button's release always reach the demo, so a grab
            // or a pan ends even when the button comes up over the sidebar.
            WindowEvent::CursorMoved { .. }
            | WindowEvent::MouseInput {
                state: ElementState::Released,
                ..
            } => running.input(&event),
            other if !response.consumed => running.input(&other),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(running) = &self.running {
            running.window.request_redraw();
        }
    }
}

impl Running {
    fn new(event_loop: &ActiveEventLoop, options: &WindowOptions) -> Result<Running, String> {
        let attributes = Window::default_attributes()
            .with_title("carom")
            .with_inner_size(winit::dpi::LogicalSize::new(options.size.0, options.size.1));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| format!("cannot create the window: {e}"))?,
        );
        let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
        let mut descriptor = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(
            event_loop.owned_display_handle(),
        ));
        descriptor.backends = backends;
        let instance = wgpu::Instance::new(descriptor);
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| format!("cannot draw into the window: {e}"))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .map_err(|e| {
            format!(
                "no graphics adapter can draw into the window ({e}); on Debian install \
                 mesa-vulkan-drivers (Vulkan) or libegl1 libegl-mesa0 libgl1-mesa-dri (GL)"
            )
        })?;
        Renderer::check(&adapter).map_err(|e| e.to_string())?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("carom"),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| format!("cannot open the graphics device: {e}"))?;
        let size = window.inner_size();
        let capabilities = surface.get_capabilities(&adapter);
        // A non-sRGB format when there is one: egui blends in gamma space and expects it.
        let format = capabilities
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .unwrap_or(capabilities.formats[0]);
        let copy_src = capabilities.usages.contains(wgpu::TextureUsages::COPY_SRC);
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | if copy_src {
                    wgpu::TextureUsages::COPY_SRC
                } else {
                    wgpu::TextureUsages::empty()
                },
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: capabilities.alpha_modes[0],
            view_formats: Vec::new(),
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&device, &config);
        let renderer = Renderer::new(&device, format);
        let egui = egui::Context::default();
        let egui_input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&device, format, egui_wgpu::RendererOptions::default());
        let scale = window.scale_factor() as f32;
        let viewport = scene_viewport(size.width, size.height, scale);
        let demo = Demo::open(&options.scenes_folder, &options.scene, viewport)?;
        window.set_title(&format!("carom: {}", demo.scene_path.display()));
        Ok(Running {
            window,
            surface,
            device,
            queue,
            config,
            renderer,
            egui,
            egui_input,
            egui_renderer,
            demo,
            list: DrawList::new(),
            error: None,
            cursor: egui::Pos2::ZERO,
            last_frame: Instant::now(),
            frames: 0,
            frame_seconds: 1.0 / 60.0,
            frame_ms: Vec::new(),
            adapter: format!(
                "{} on {:?}",
                adapter.get_info().name,
                adapter.get_info().backend
            ),
        })
    }

    fn resize(&mut self, width: u32, height: u32) {
        self.config.width = width.max(1);
        self.config.height = height.max(1);
        self.surface.configure(&self.device, &self.config);
        let scale = self.window.scale_factor() as f32;
        self.demo
            .resize(scene_viewport(self.config.width, self.config.height, scale));
    }

    /// Where the scene's view starts, in physical pixels: right of the sidebar.
    fn scene_left(&self) -> f32 {
        SIDEBAR_WIDTH * self.window.scale_factor() as f32
    }

    /// Mouse and keys that egui did not take.
    fn input(&mut self, event: &WindowEvent) {
        let result = match event {
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = egui::pos2(position.x as f32, position.y as f32);
                let local = vec2(self.cursor.x - self.scene_left(), self.cursor.y);
                self.demo.move_to(local);
                Ok(())
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let button = match button {
                    MouseButton::Left => Button::Left,
                    MouseButton::Right => Button::Right,
                    MouseButton::Middle => Button::Middle,
                    _ => return,
                };
                let local = vec2(self.cursor.x - self.scene_left(), self.cursor.y);
                match state {
                    ElementState::Pressed if local.x >= 0.0 => self.demo.press(button, local),
                    ElementState::Pressed => {}
                    ElementState::Released => self.demo.release(button),
                }
                Ok(())
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                let local = vec2(self.cursor.x - self.scene_left(), self.cursor.y);
                self.demo.wheel(lines, local);
                Ok(())
            }
            WindowEvent::KeyboardInput { event, .. } if event.state.is_pressed() => {
                let key = match event.physical_key {
                    PhysicalKey::Code(KeyCode::Space) => Some(Key::Space),
                    PhysicalKey::Code(KeyCode::KeyS) => Some(Key::Step),
                    PhysicalKey::Code(KeyCode::KeyR) => Some(Key::Reset),
                    PhysicalKey::Code(KeyCode::KeyW) => Some(Key::Save),
                    PhysicalKey::Code(code) => digit(code).map(Key::Digit),
                    _ => None,
                };
                key.map_or(Ok(()), |key| self.demo.key(key))
            }
            _ => Ok(()),
        };
        if let Err(message) = result {
            self.error = Some(message);
        }
    }

    /// One frame: steps due, sidebar, scene, present. False when it is time to close.
    fn redraw(&mut self, options: &WindowOptions) -> Result<bool, String> {
        let now = Instant::now();
        let elapsed = (now - self.last_frame).as_secs_f64();
        self.last_frame = now;
        self.frame_seconds += (elapsed - self.frame_seconds) * 0.05;
        if self.frames > 0 {
            self.frame_ms.push(elapsed * 1e3);
        }
        // Editing the open scene's file shows the edit at once (a bad edit says where).
        match self.demo.reload_if_changed() {
            Ok(true) => self.error = None,
            Ok(false) => {}
            Err(message) => self.error = Some(message),
        }
        if let Err(message) = self.demo.frame(elapsed) {
            self.error = Some(message);
        }

        let raw_input = self.egui_input.take_egui_input(&self.window);
        let (demo, error) = (&mut self.demo, &mut self.error);
        let fps = 1.0 / self.frame_seconds.max(1e-6);
        let output = self.egui.run_ui(raw_input, |ui| {
            egui::Panel::left("sidebar")
                .exact_size(SIDEBAR_WIDTH)
                .resizable(false)
                .show(ui, |ui| {
                    ui.label(format!("{fps:.0} frames/s"));
                    sidebar(ui, demo, error);
                });
        });
        self.egui_input
            .handle_platform_output(&self.window, output.platform_output);
        let pixels_per_point = output.pixels_per_point;
        let paint_jobs = self.egui.tessellate(output.shapes, pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point,
        };
        // Drain the texture changes: egui checks in debug builds that none is dropped unseen.
        let mut textures = output.textures_delta;
        for (id, deltas) in textures.set.drain() {
            for delta in &deltas {
                self.egui_renderer
                    .update_texture(&self.device, &self.queue, id, delta);
            }
        }

        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                return Ok(true);
            }
            _ => return Ok(true),
        };
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        self.demo.describe(&mut self.list);
        self.renderer.prepare(
            &self.device,
            &self.queue,
            &self.list,
            &self.demo.camera,
            self.demo.viewport,
        );
        let mut command_buffers = self.egui_renderer.update_buffers(
            &self.device,
            &self.queue,
            &mut encoder,
            &paint_jobs,
            &screen,
        );
        self.encode(&mut encoder, &frame.texture, &paint_jobs, &screen);
        let last = options.frames.is_some_and(|n| self.frames + 1 >= n);
        let capture = match (&options.screenshot, last) {
            (Some(_), true) if self.config.usage.contains(wgpu::TextureUsages::COPY_SRC) => {
                Some(copy_to_buffer(&self.device, &mut encoder, &frame.texture))
            }
            (Some(_), true) => {
                // The surface cannot be read: draw the same frame into a texture that can.
                let texture = self.device.create_texture(&wgpu::TextureDescriptor {
                    label: Some("screenshot"),
                    size: frame.texture.size(),
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: self.config.format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                });
                self.encode(&mut encoder, &texture, &paint_jobs, &screen);
                Some(copy_to_buffer(&self.device, &mut encoder, &texture))
            }
            _ => None,
        };
        command_buffers.push(encoder.finish());
        self.queue.submit(command_buffers);
        if let (Some(capture), Some(path)) = (capture, &options.screenshot) {
            let image = capture.read(&self.device, self.config.format)?;
            image
                .save(path)
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        }
        self.window.pre_present_notify();
        self.queue.present(frame);
        for id in textures.free.drain() {
            self.egui_renderer.free_texture(&id);
        }
        self.frames += 1;
        Ok(!last)
    }
}

impl Running {
    /// What the frames cost: the median frame time and rate, and the median physics step.
    fn report(&self) -> String {
        let mut frame_ms = self.frame_ms.clone();
        frame_ms.sort_by(f64::total_cmp);
        let median = frame_ms.get(frame_ms.len() / 2).copied().unwrap_or(0.0);
        format!(
            "{}: {} frames at {}x{} on {}: median frame {median:.1} ms ({:.1} frames/s), \
             median step {:.3} ms, {} bodies",
            self.demo.scene_path.display(),
            self.frames,
            self.config.width,
            self.config.height,
            self.adapter,
            1e3 / median.max(1e-6),
            self.demo.metrics.median(|s| s.step_ms),
            self.demo.scene.world.body_count(),
        )
    }

    /// Records one frame into `target`: the scene right of the sidebar, egui over everything.
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::Texture,
        paint_jobs: &[egui::ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
    ) {
        let view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("frame"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(clear_color(
                            Color::BACKGROUND,
                            self.config.format,
                        )),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            })
            .forget_lifetime();
        let (width, height) = (self.config.width as f32, self.config.height as f32);
        let left = self.scene_left().min(width - 1.0);
        let [scene_width, scene_height] = self.demo.viewport;
        pass.set_viewport(
            left,
            0.0,
            (scene_width as f32).min(width - left),
            (scene_height as f32).min(height),
            0.0,
            1.0,
        );
        self.renderer.render(&mut pass);
        pass.set_viewport(0.0, 0.0, width, height, 0.0, 1.0);
        self.egui_renderer.render(&mut pass, paint_jobs, screen);
    }
}

/// The scene's part of the window (right of the sidebar), physical pixels.
fn scene_viewport(width: u32, height: u32, scale: f32) -> [u32; 2] {
    let sidebar = (SIDEBAR_WIDTH * scale).ceil() as u32;
    [width.saturating_sub(sidebar).max(1), height.max(1)]
}

fn digit(code: KeyCode) -> Option<u8> {
    Some(match code {
        KeyCode::Digit0 => 0,
        KeyCode::Digit1 => 1,
        KeyCode::Digit2 => 2,
        KeyCode::Digit3 => 3,
        KeyCode::Digit4 => 4,
        KeyCode::Digit5 => 5,
        KeyCode::Digit6 => 6,
        KeyCode::Digit7 => 7,
        KeyCode::Digit8 => 8,
        KeyCode::Digit9 => 9,
        _ => return None,
    })
}
