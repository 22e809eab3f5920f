//! carom in a window: the smallest game loop to start your own program from. winit opens the
//! window, the world steps at a fixed 60 Hz whatever the frame rate, and carom-render draws it.
//!
//! `cargo run -p carom-render --example window` (`-- --frames 120` closes it after 120 frames).

use carom::{BodyDef, Real, Shape, World, vec2};

use carom::draw::{Color, DrawList, DrawOptions};
use carom_render::{Camera, Screen};
use std::error::Error;
use std::sync::Arc;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

/// The physics time step, s. A fixed step keeps the simulation the same at any frame rate.
const STEP: Real = 1.0 / 60.0;

fn main() -> Result<(), Box<dyn Error>> {
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
        let at = vec2(0.7 * (i % 3) as Real - 0.7, 1.0 + 1.2 * i as Real);
        world.add_body(BodyDef::dynamic(shape).position(at).angle(0.3 * i as Real))?;
    }
    let mut app = App {
        world,
        frames,
        gfx: None,
        error: None,
    };
    EventLoop::new()?.run_app(&mut app)?;
    if let Some(error) = app.error {
        return Err(error);
    }
    println!("{:.2} s simulated", app.world.time());
    Ok(())
}

struct App {
    world: World,
    /// Frames left to show before closing, if counted.
    frames: Option<u64>,
    /// None until winit says the app may open its window (`resumed`).
    gfx: Option<Gfx>,
    /// Why the window could not be opened or drawn into; `main` returns it.
    error: Option<Box<dyn Error>>,
}

/// The window, what draws into it, and the clock that paces the physics.
struct Gfx {
    window: Arc<Window>,
    /// The surface, device and renderer: everything wgpu needs to draw the world.
    screen: Screen,
    /// Filled by the world each frame; kept so its memory is reused.
    list: DrawList,
    last_frame: Instant,
    /// Real time not simulated yet, s.
    behind: Real,
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        // Some platforms resume more than once; the window is made the first time.
        if self.gfx.is_none() {
            match Gfx::open(event_loop) {
                Ok(gfx) => self.gfx = Some(gfx),
                Err(error) => {
                    self.error = Some(error);
                    event_loop.exit();
                }
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gfx) = &mut self.gfx else { return };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => gfx.screen.resize(size.width, size.height),
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
    /// Opens the window and a device that can draw into it.
    fn open(event_loop: &ActiveEventLoop) -> Result<Gfx, Box<dyn Error>> {
        let attributes = Window::default_attributes().with_title("carom");
        let window = Arc::new(event_loop.create_window(attributes)?);
        // The display handle lets wgpu's GL backend reach the window's display. Every backend
        // is tried (software rasterisers too) unless WGPU_BACKEND=vulkan|gl names one.
        let display = event_loop.owned_display_handle();
        let size = window.inner_size();
        let screen = Screen::new(window.clone(), display, [size.width, size.height])?;
        println!("drawing on {}", screen.gpu().describe());
        Ok(Gfx {
            window,
            screen,
            list: DrawList::new(),
            last_frame: Instant::now(),
            behind: 0.0,
        })
    }

    /// Steps the world up to now, then draws it.
    fn frame(&mut self, world: &mut World) {
        // Whole steps for the real time that passed. After a stall (a dragged window, a
        // debugger) at most five are owed, so the loop does not fall behind catching up.
        let now = Instant::now();
        self.behind = (self.behind + (now - self.last_frame).as_secs_f64() as Real).min(5.0 * STEP);
        self.last_frame = now;
        while self.behind >= STEP {
            world.step(STEP).expect("the world's settings are valid");
            self.behind -= STEP;
        }
        self.list.clear(); // `debug_draw` appends
        world.debug_draw(&DrawOptions::default(), |_| None, &mut self.list);
        // Frame a 24 m x 12 m region above the ground, whatever the window's shape.
        let [width, height] = self.screen.size().map(|side| side as f32);
        let camera = Camera {
            center: vec2(0.0, 5.0),
            zoom: (width / 24.0).min(height / 12.0),
        };
        let window = &self.window;
        let notify = || window.pre_present_notify(); // tells winit a frame is coming
        // Ask for the next frame at once: with vsync, presenting paces the loop to the display.
        // No frame (hidden, resized under us): the screen is set up again, and winit asks
        // for a redraw when the window shows.
        if (self.screen).draw_with(&self.list, &camera, Color::BACKGROUND, notify) {
            window.request_redraw();
        }
    }
}
