//! carom in a window: the smallest game loop to start your own program from. winit opens the
//! window, the world steps at a fixed 60 Hz whatever the frame rate, and carom-render draws it.
//!
//! `cargo run -p carom-render --example window` (`-- --frames 120` closes it after 120 frames).

use carom::{BodyDef, Color, DrawList, DrawOptions, Shape, World, vec2};
use carom_render::{Camera, Renderer, clear_color};
use std::sync::Arc;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

/// The physics time step, s. A fixed step keeps the simulation the same at any frame rate.
const STEP: f32 = 1.0 / 60.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let frames = match (args.next().as_deref(), args.next()) {
        (None, _) => None,
        (Some("--frames"), Some(n)) => Some(n.parse()?),
        _ => return Err("usage: window [--frames N]".into()),
    };
    // A ground, and boxes and circles dropped onto it in a staggered column, to tumble and pile.
    let mut world = World::new(); // gravity (0, -10) m/s²
    world.add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))?;
    for i in 0..12 {
        let shape = [Shape::rect(0.5, 0.4), Shape::circle(0.5)][i % 2].clone();
        let at = vec2(0.7 * (i % 3) as f32 - 0.7, 1.0 + 1.2 * i as f32);
        world.add_body(BodyDef::dynamic(shape).position(at).angle(0.3 * i as f32))?;
    }
    let mut app = App {
        world,
        frames,
        gfx: None,
    };
    EventLoop::new()?.run_app(&mut app)?;
    println!("{:.2} s simulated", app.world.time());
    Ok(())
}

struct App {
    world: World,
    /// Frames left to show before closing, if counted.
    frames: Option<u64>,
    /// None until winit says the app may open its window (`resumed`).
    gfx: Option<Gfx>,
}

/// The window, what draws into it, and the clock that paces the physics.
struct Gfx {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    renderer: Renderer,
    /// Filled by the world each frame; kept so its memory is reused.
    list: DrawList,
    last_frame: Instant,
    /// Real time not simulated yet, s.
    behind: f32,
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        // Some platforms resume more than once; the window is made the first time.
        if self.gfx.is_none() {
            self.gfx = Some(Gfx::open(event_loop));
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gfx) = &mut self.gfx else { return };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                // A zero-sized surface is invalid (a minimised window): keep at least 1 x 1.
                gfx.config.width = size.width.max(1);
                gfx.config.height = size.height.max(1);
                gfx.surface.configure(&gfx.device, &gfx.config);
            }
            WindowEvent::RedrawRequested => {
                gfx.frame(&mut self.world);
                self.frames = self.frames.map(|left| left.saturating_sub(1));
                if self.frames == Some(0) {
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }
}

impl Gfx {
    /// Opens the window and a wgpu device that can draw into it.
    fn open(event_loop: &ActiveEventLoop) -> Gfx {
        let attributes = Window::default_attributes().with_title("carom");
        let window = Arc::new(event_loop.create_window(attributes).expect("no window"));
        // The display handle lets wgpu's GL backend reach the window's display. Every backend
        // is tried (software rasterisers too) unless WGPU_BACKEND=vulkan|gl names one.
        let display = Box::new(event_loop.owned_display_handle());
        let mut descriptor = wgpu::InstanceDescriptor::new_with_display_handle(display);
        descriptor.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
        let instance = wgpu::Instance::new(descriptor);
        // Owning an Arc of the window makes the surface 'static, so it can live in `Gfx`.
        let surface = instance.create_surface(window.clone()).expect("no surface");
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .expect("no graphics adapter can draw into the window");
        Renderer::check(&adapter).unwrap_or_else(|e| panic!("{e}"));
        println!("drawing on {}", adapter.get_info().name);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            // Downlevel limits, so GL and software adapters qualify as well as GPUs.
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .expect("cannot open the graphics device");
        let size = window.inner_size();
        // The surface's preferred format: the renderer and `clear_color` handle sRGB or not.
        let (width, height) = (size.width.max(1), size.height.max(1)); // 0 is invalid
        let mut config = (surface.get_default_config(&adapter, width, height))
            .expect("the adapter cannot draw into this window");
        config.present_mode = wgpu::PresentMode::AutoVsync;
        surface.configure(&device, &config);
        let renderer = Renderer::new(&device, config.format);
        let (list, last_frame, behind) = (DrawList::new(), Instant::now(), 0.0);
        Gfx {
            window,
            surface,
            device,
            queue,
            config,
            renderer,
            list,
            last_frame,
            behind,
        }
    }

    /// Steps the world up to now, then draws it.
    fn frame(&mut self, world: &mut World) {
        // Whole steps for the real time that passed. After a stall (a dragged window, a
        // debugger) at most five are owed, so the loop does not fall behind catching up.
        let now = Instant::now();
        self.behind = (self.behind + (now - self.last_frame).as_secs_f32()).min(5.0 * STEP);
        self.last_frame = now;
        while self.behind >= STEP {
            world.step(STEP).expect("the world's settings are valid");
            self.behind -= STEP;
        }
        // No frame (resized under us, hidden, timed out): set the surface up, try next time.
        let wgpu::CurrentSurfaceTexture::Success(frame) = self.surface.get_current_texture() else {
            return self.surface.configure(&self.device, &self.config);
        };
        self.list.clear(); // `debug_draw` appends
        world.debug_draw(&DrawOptions::default(), |_| None, &mut self.list);
        // Frame a 24 m x 12 m region above the ground, whatever the window's shape.
        let viewport = [self.config.width, self.config.height];
        let zoom = (viewport[0] as f32 / 24.0).min(viewport[1] as f32 / 12.0);
        let camera = Camera {
            center: vec2(0.0, 5.0),
            zoom,
        };
        let (device, queue) = (&self.device, &self.queue);
        self.renderer
            .prepare(device, queue, &self.list, &camera, viewport);

        let view = frame.texture.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        let clear = clear_color(Color::BACKGROUND, self.config.format);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        self.renderer.render(&mut pass);
        drop(pass); // the pass borrows the encoder until it ends
        queue.submit([encoder.finish()]);
        self.window.pre_present_notify();
        queue.present(frame);
        // Ask for the next frame at once: with vsync, presenting paces the loop to the display.
        self.window.request_redraw();
    }
}
