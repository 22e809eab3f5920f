//! The window: winit events in, a wgpu surface out, the scene drawn by `carom-render` and the
//! sidebar by egui on top. Everything else lives in [`Demo`], which knows nothing of windows.
//!
//! The same window runs natively ([`run`]) and in a web page's canvas (`start_in_canvas`, in
//! the wasm build), where the graphics device arrives asynchronously and a [`Host`] (the
//! page) hears of each frame, of failures and of saves.

use crate::capture::copy_to_buffer;
use crate::demo::{Button, Control, Demo, Key};
use crate::ui::{Ask, SIDEBAR_WIDTH, sidebar};
use carom::draw::{Color, DrawList};
use carom::{Real, vec2};
use carom_render::{Screen, ScreenOptions, clear_color};
use std::path::PathBuf;
use std::sync::Arc;
use web_time::Instant;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, Touch, TouchPhase, WindowEvent};
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
    /// Inner size, logical pixels (the web page sizes its canvas itself).
    pub size: (u32, u32),
    /// Close after this many frames (for screenshots and tests).
    pub frames: Option<u64>,
    /// Save the window's contents to this PNG after the last frame.
    pub screenshot: Option<PathBuf>,
    /// Play the opening scene's recorded play, if it has a player.
    pub replay: bool,
    /// Take this many steps every frame, whatever the time (a scripted run that must reach
    /// a given step whatever the machine's speed), instead of keeping to the clock.
    pub steps_per_frame: Option<u32>,
    /// What to do at given frames, as a user would (for tests and demonstrations).
    pub script: Vec<Scripted>,
    /// The graphics backends to choose from; `None` takes the environment's `WGPU_BACKEND`,
    /// or else any (on the web: WebGPU where the browser has it, WebGL2 otherwise).
    pub backends: Option<wgpu::Backends>,
}

/// An action at a frame: done at the frame's start, before its steps, in the order given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scripted {
    /// The frame, counted from 1.
    pub frame: u64,
    /// What to do.
    pub action: Action,
}

/// What a script does, as the keys, the sidebar and the mouse would.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    /// Pause.
    Pause,
    /// Play.
    Play,
    /// One step back (the `,` key).
    StepBack,
    /// Go to a step of the run (the sidebar's scrubber).
    GoTo(u64),
    /// Press the left button over this world point (m), grabbing what is there.
    Grab(Real, Real),
    /// Release the left button.
    LetGo,
    /// Print the frame, the step, the run's end, the state hash and the notice shown.
    Print,
}

/// Reads a scripted action, `FRAME:ACTION`, where the action is `pause`, `play`, `step-back`,
/// `go-to=STEP`, `grab=X,Y` (a world point, m), `let-go` or `print`.
pub fn parse_scripted(text: &str) -> Result<Scripted, String> {
    let (frame, action) = text
        .split_once(':')
        .ok_or("expected FRAME:ACTION, for example 30:pause")?;
    let frame: u64 = frame
        .parse()
        .map_err(|_| format!("{frame:?} is not a frame number"))?;
    let (name, value) = action.split_once('=').unwrap_or((action, ""));
    let number = |text: &str| -> Result<Real, String> {
        text.trim()
            .parse::<Real>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or(format!("{text:?} is not a finite number"))
    };
    let action = match name {
        "pause" => Action::Pause,
        "play" => Action::Play,
        "step-back" => Action::StepBack,
        "go-to" => Action::GoTo(
            value
                .parse()
                .map_err(|_| format!("go-to takes a step number, not {value:?}"))?,
        ),
        "grab" => {
            let (x, y) = value
                .split_once(',')
                .ok_or("grab takes a world point, grab=X,Y")?;
            Action::Grab(number(x)?, number(y)?)
        }
        "let-go" => Action::LetGo,
        "print" => Action::Print,
        _ => {
            return Err(format!(
                "no action {name:?}: pause, play, step-back, go-to=STEP, grab=X,Y, let-go or \
                 print"
            ));
        }
    };
    Ok(Scripted { frame, action })
}

/// A frame just shown, as a [`Host`] hears of it.
#[derive(Debug, Clone, Copy)]
pub struct FrameInfo<'a> {
    /// Frames shown so far, this one included.
    pub frames: u64,
    /// Frames a second, smoothed over the last few dozen.
    pub frames_per_second: f64,
    /// Physical pixels per logical pixel.
    pub scale_factor: f64,
    /// Where the scene's view starts, physical pixels from the left (right of the sidebar).
    pub scene_left: f32,
    /// The adapter drawing and its backend (WebGPU or WebGL2 on the web).
    pub adapter: &'a str,
}

/// What the window's surroundings hear of it: the native app prints and writes files; a web
/// page shows errors in the page and offers saves as downloads.
pub trait Host {
    /// A frame was shown.
    fn frame(&mut self, _demo: &Demo, _frame: &FrameInfo<'_>) {}
    /// The window could not start, or stopped with an error.
    fn failed(&mut self, _message: &str) {}
    /// The user asked to save the running scene (W). Natively it is written beside its file.
    fn save(&mut self, demo: &mut Demo) -> Result<(), String> {
        demo.save().map(|_| ())
    }
    /// The user asked to save the run as a recording. Natively it is written beside the
    /// scene's file.
    fn save_recording(&mut self, demo: &mut Demo) -> Result<(), String> {
        demo.save_recording().map(|_| ())
    }
}

/// The native app's host: everything as [`Host`]'s defaults do it.
#[cfg(not(target_arch = "wasm32"))]
struct Native;

#[cfg(not(target_arch = "wasm32"))]
impl Host for Native {}

/// Opens the window and runs until it is closed (or `frames` have been shown).
#[cfg(not(target_arch = "wasm32"))]
pub fn run(options: WindowOptions) -> Result<(), String> {
    let event_loop = EventLoop::<Started>::with_user_event()
        .build()
        .map_err(|e| format!("cannot open a window: {e}"))?;
    let mut app = App::new(options, Box::new(Native));
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

/// Starts the demo in `canvas`, a canvas of the page, and returns at once: the browser runs
/// the frames from then on, and `host` hears of them.
#[cfg(target_arch = "wasm32")]
pub fn start_in_canvas(
    options: WindowOptions,
    canvas: web_sys::HtmlCanvasElement,
    host: Box<dyn Host>,
) -> Result<(), String> {
    use winit::platform::web::EventLoopExtWebSys;
    let event_loop = EventLoop::<Started>::with_user_event()
        .build()
        .map_err(|e| format!("cannot start the event loop: {e}"))?;
    let mut app = App::new(options, host);
    app.canvas = Some(canvas);
    app.proxy = Some(event_loop.create_proxy());
    event_loop.spawn_app(app);
    Ok(())
}

/// The window's graphics, ready or not: what starting sends back to the event loop.
struct Started(Result<Running, String>);

struct App {
    options: WindowOptions,
    running: Option<Running>,
    /// Asked for the graphics device and waiting for it (the web answers asynchronously).
    starting: bool,
    failure: Option<String>,
    host: Box<dyn Host>,
    /// The page's canvas to draw in, and the way back into the event loop for the device
    /// found asynchronously.
    #[cfg(target_arch = "wasm32")]
    canvas: Option<web_sys::HtmlCanvasElement>,
    #[cfg(target_arch = "wasm32")]
    proxy: Option<winit::event_loop::EventLoopProxy<Started>>,
}

impl App {
    fn new(options: WindowOptions, host: Box<dyn Host>) -> App {
        App {
            options,
            running: None,
            starting: false,
            failure: None,
            host,
            #[cfg(target_arch = "wasm32")]
            canvas: None,
            #[cfg(target_arch = "wasm32")]
            proxy: None,
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, message: String) {
        self.host.failed(&message);
        self.failure = Some(message);
        event_loop.exit();
    }

    fn window_attributes(&self) -> winit::window::WindowAttributes {
        let attributes = Window::default_attributes().with_title("carom");
        #[cfg(not(target_arch = "wasm32"))]
        let attributes = attributes.with_inner_size(winit::dpi::LogicalSize::new(
            self.options.size.0,
            self.options.size.1,
        ));
        #[cfg(target_arch = "wasm32")]
        let attributes = {
            use winit::platform::web::WindowAttributesExtWebSys;
            attributes.with_canvas(self.canvas.clone())
        };
        attributes
    }
}

impl ApplicationHandler<Started> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() || self.starting {
            return;
        }
        let window = match event_loop.create_window(self.window_attributes()) {
            Ok(window) => Arc::new(window),
            Err(e) => return self.fail(event_loop, format!("cannot create the window: {e}")),
        };
        let display = event_loop.owned_display_handle();
        let options = self.options.clone();
        let starting = Running::new(window, display, options);
        self.starting = true;
        #[cfg(not(target_arch = "wasm32"))]
        self.user_event(event_loop, Started(pollster::block_on(starting)));
        #[cfg(target_arch = "wasm32")]
        {
            let proxy = self.proxy.clone();
            wasm_bindgen_futures::spawn_local(async move {
                let started = Started(starting.await);
                // Fails only once the event loop is gone, and then nobody is left to tell.
                if let Some(proxy) = proxy {
                    let _ = proxy.send_event(started);
                }
            });
        }
    }

    fn user_event(&mut self, event_loop: &ActiveEventLoop, started: Started) {
        self.starting = false;
        match started.0 {
            Ok(running) => {
                running.window.request_redraw();
                self.running = Some(running);
            }
            Err(message) => self.fail(event_loop, message),
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
                Ok(true) => {
                    if let Some(Ask::SaveRecording) = running.asked.take() {
                        running.error = self.host.save_recording(&mut running.demo).err();
                    }
                    self.host.frame(&running.demo, &running.frame_info());
                }
                Ok(false) => event_loop.exit(),
                Err(message) => self.fail(event_loop, message),
            },
            // Saving is the host's: a file natively, a download on the web.
            WindowEvent::KeyboardInput { event: ref key, .. }
                if !response.consumed
                    && key.state.is_pressed()
                    && key.physical_key == PhysicalKey::Code(KeyCode::KeyW) =>
            {
                running.error = self.host.save(&mut running.demo).err();
            }
            // A window that loses the keyboard hears no more key releases: the player's keys
            // are let go, so it does not walk on by itself.
            WindowEvent::Focused(false) => running.demo.let_go_of_controls(),
            // The cursor's position and a button's release always reach the demo, so a grab
            // or a pan ends even when the button comes up over the sidebar; touches and key
            // releases likewise (a player's key let go over the sidebar still stops it).
            WindowEvent::KeyboardInput { event: ref key, .. } if !key.state.is_pressed() => {
                running.input(&event)
            }
            WindowEvent::CursorMoved { .. }
            | WindowEvent::MouseInput {
                state: ElementState::Released,
                ..
            }
            | WindowEvent::Touch(Touch {
                phase: TouchPhase::Moved | TouchPhase::Ended | TouchPhase::Cancelled,
                ..
            }) => running.input(&event),
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

/// Everything that exists while the window is open.
struct Running {
    window: Arc<Window>,
    /// The window's surface, the device drawing into it and the scene's renderer.
    screen: Screen,
    egui: egui::Context,
    egui_input: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    demo: Demo,
    list: DrawList,
    error: Option<String>,
    /// What the sidebar last asked of the host.
    asked: Option<Ask>,
    cursor: egui::Pos2,
    /// The touch that grabs, while a finger is down.
    touch: Option<u64>,
    last_frame: Instant,
    frames: u64,
    /// Seconds of wall time per frame, smoothed, for the sidebar's frame rate.
    frame_seconds: f64,
    /// Wall time of every frame after the first, ms, for the report `--frames` prints.
    frame_ms: Vec<f64>,
    /// Wall time of every step, ms, for that report (the sidebar's metrics keep the last
    /// seconds only).
    step_ms: Vec<f64>,
    /// The adapter drawing, for that report.
    adapter: String,
}

impl Running {
    /// The window's graphics and the demo in it. Asynchronous for the web, where the adapter
    /// and device are promises; natively it is blocked on.
    async fn new(
        window: Arc<Window>,
        display: winit::event_loop::OwnedDisplayHandle,
        options: WindowOptions,
    ) -> Result<Running, String> {
        let size = window.inner_size();
        let screen_options = ScreenOptions {
            backends: options.backends,
            // egui blends in gamma space and expects a format that is not sRGB.
            gamma_format: true,
            // For --screenshot; a surface that cannot be read is drawn again into a texture.
            readable: true,
        };
        let mut screen = Screen::request(
            window.clone(),
            display,
            [size.width, size.height],
            &screen_options,
        )
        .await
        .map_err(|e| e.to_string())?;
        // The window may have been laid out while the device was on its way (a canvas sized by
        // its page), its resize reaching no one: follow the size it has now.
        let size = window.inner_size();
        screen.resize(size.width, size.height);
        let (device, format) = (&screen.gpu().device, screen.format());
        let largest = device.limits().max_texture_dimension_2d;
        let egui = egui::Context::default();
        let egui_input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(largest as usize),
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(device, format, egui_wgpu::RendererOptions::default());
        let scale = window.scale_factor() as f32;
        let [width, height] = screen.size();
        let viewport = scene_viewport(width, height, scale);
        let mut demo = Demo::open(&options.scenes_folder, &options.scene, viewport)?;
        if options.replay && demo.has_player() {
            demo.input(carom_scene::Input::PlayRecordedKeys)?;
        }
        window.set_title(&format!("carom: {}", demo.scene_path.display()));
        let info = screen.gpu().adapter.get_info();
        Ok(Running {
            window,
            screen,
            egui,
            egui_input,
            egui_renderer,
            demo,
            list: DrawList::new(),
            error: None,
            asked: None,
            cursor: egui::Pos2::ZERO,
            touch: None,
            last_frame: Instant::now(),
            frames: 0,
            frame_seconds: 1.0 / 60.0,
            frame_ms: Vec::new(),
            step_ms: Vec::new(),
            adapter: format!("{} on {:?}", info.name, info.backend),
        })
    }

    /// The frame just shown, for the host.
    fn frame_info(&self) -> FrameInfo<'_> {
        FrameInfo {
            frames: self.frames,
            frames_per_second: 1.0 / self.frame_seconds.max(1e-6),
            scale_factor: self.window.scale_factor(),
            scene_left: self.scene_left(),
            adapter: &self.adapter,
        }
    }

    fn resize(&mut self, width: u32, height: u32) {
        self.screen.resize(width, height);
        let scale = self.window.scale_factor() as f32;
        let [width, height] = self.screen.size();
        self.demo.resize(scene_viewport(width, height, scale));
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
                let local = vec2(
                    (self.cursor.x - self.scene_left()) as Real,
                    self.cursor.y as Real,
                );
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
                let local = vec2(
                    (self.cursor.x - self.scene_left()) as Real,
                    self.cursor.y as Real,
                );
                match state {
                    ElementState::Pressed if local.x >= 0.0 => self.demo.press(button, local),
                    ElementState::Pressed => {}
                    ElementState::Released => self.demo.release(button),
                }
                Ok(())
            }
            // One finger grabs and throws as the left button does; further fingers are
            // ignored until it lifts.
            WindowEvent::Touch(Touch {
                phase,
                location,
                id,
                ..
            }) => {
                let at = egui::pos2(location.x as f32, location.y as f32);
                let local = vec2((at.x - self.scene_left()) as Real, at.y as Real);
                match phase {
                    TouchPhase::Started if self.touch.is_none() && local.x >= 0.0 => {
                        self.touch = Some(*id);
                        self.cursor = at;
                        self.demo.press(Button::Left, local);
                    }
                    TouchPhase::Moved if self.touch == Some(*id) => {
                        self.cursor = at;
                        self.demo.move_to(local);
                    }
                    TouchPhase::Ended | TouchPhase::Cancelled if self.touch == Some(*id) => {
                        self.touch = None;
                        self.demo.release(Button::Left);
                    }
                    _ => {}
                }
                Ok(())
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                let local = vec2(
                    (self.cursor.x - self.scene_left()) as Real,
                    self.cursor.y as Real,
                );
                self.demo.wheel(lines, local);
                Ok(())
            }
            // A scene's player: its keys held and let go.
            WindowEvent::KeyboardInput { event, .. }
                if self.demo.has_player() && control(event.physical_key).is_some() =>
            {
                if let Some(control) = control(event.physical_key) {
                    self.demo.hold(control, event.state.is_pressed());
                }
                Ok(())
            }
            WindowEvent::KeyboardInput { event, .. } if event.state.is_pressed() => {
                let key = match event.physical_key {
                    PhysicalKey::Code(KeyCode::Space) => Some(Key::Space),
                    PhysicalKey::Code(KeyCode::KeyP) => Some(Key::Pause),
                    PhysicalKey::Code(KeyCode::KeyS | KeyCode::Period) => Some(Key::Step),
                    PhysicalKey::Code(KeyCode::Comma) => Some(Key::StepBack),
                    PhysicalKey::Code(KeyCode::KeyR) => Some(Key::Reset),
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

    /// Does what a script says, the way the keys, the sidebar and the mouse do it.
    fn act(&mut self, action: Action) -> Result<(), String> {
        let demo = &mut self.demo;
        match action {
            Action::Pause => demo.paused = true,
            Action::Play => demo.paused = false,
            Action::StepBack => demo.key(Key::StepBack)?,
            Action::GoTo(step) => demo.go_to(step)?,
            Action::Grab(x, y) => {
                let screen = demo.camera.world_to_screen(vec2(x, y), demo.viewport);
                demo.press(Button::Left, screen);
            }
            Action::LetGo => demo.release(Button::Left),
            Action::Print => {
                let timeline = demo.timeline();
                println!(
                    "frame {}: step {} of {}, hash {:016x}, notice: {}",
                    self.frames + 1,
                    timeline.at(),
                    timeline.end(),
                    demo.scene.world.state_hash(),
                    demo.notice.as_deref().unwrap_or("none")
                );
            }
        }
        Ok(())
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
        let frame = self.frames + 1;
        for scripted in options.script.iter().filter(|s| s.frame == frame) {
            if let Err(message) = self.act(scripted.action) {
                self.error = Some(message);
            }
        }
        // A fixed number of steps a frame (a scripted run), or as many as the time passed.
        let stepped = match options.steps_per_frame {
            Some(steps) if !self.demo.paused => (0..steps)
                .try_for_each(|_| self.demo.step())
                .map(|()| steps),
            _ => self.demo.frame(elapsed),
        };
        match stepped {
            // The steps just taken are the newest samples.
            Ok(steps) => self.step_ms.extend(
                self.demo
                    .metrics
                    .samples()
                    .iter()
                    .rev()
                    .take(steps as usize)
                    .map(|s| s.step_ms),
            ),
            Err(message) => self.error = Some(message),
        }

        let raw_input = self.egui_input.take_egui_input(&self.window);
        let (demo, error, asked) = (&mut self.demo, &mut self.error, &mut self.asked);
        let fps = 1.0 / self.frame_seconds.max(1e-6);
        let output = self.egui.run_ui(raw_input, |ui| {
            egui::Panel::left("sidebar")
                .exact_size(SIDEBAR_WIDTH)
                .resizable(false)
                .show(ui, |ui| {
                    ui.label(format!("{fps:.0} frames/s"));
                    *asked = sidebar(ui, demo, error);
                });
        });
        self.egui_input
            .handle_platform_output(&self.window, output.platform_output);
        let pixels_per_point = output.pixels_per_point;
        let paint_jobs = self.egui.tessellate(output.shapes, pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: self.screen.size(),
            pixels_per_point,
        };
        // Drain the texture changes: egui checks in debug builds that none is dropped unseen.
        let mut textures = output.textures_delta;
        let (device, queue) = (&self.screen.gpu().device, &self.screen.gpu().queue);
        for (id, deltas) in textures.set.drain() {
            for delta in &deltas {
                (self.egui_renderer).update_texture(device, queue, id, delta);
            }
        }

        let Some(frame) = self.screen.next_frame() else {
            return Ok(true);
        };
        self.demo.describe(&mut self.list);
        let viewport = self.demo.viewport;
        (self.screen).prepare(&self.list, &self.demo.camera, viewport);
        let (device, queue) = (&self.screen.gpu().device, &self.screen.gpu().queue);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let mut command_buffers =
            (self.egui_renderer).update_buffers(device, queue, &mut encoder, &paint_jobs, &screen);
        self.encode(&mut encoder, frame.texture(), &paint_jobs, &screen);
        let last = options.frames.is_some_and(|n| self.frames + 1 >= n);
        let format = self.screen.format();
        let capture = match (&options.screenshot, last) {
            (Some(_), true) if self.screen.readable() => {
                Some(copy_to_buffer(device, &mut encoder, frame.texture()))
            }
            (Some(_), true) => {
                // The surface cannot be read: draw the same frame into a texture that can.
                let texture = device.create_texture(&wgpu::TextureDescriptor {
                    label: Some("screenshot"),
                    size: frame.texture().size(),
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                });
                self.encode(&mut encoder, &texture, &paint_jobs, &screen);
                Some(copy_to_buffer(device, &mut encoder, &texture))
            }
            _ => None,
        };
        command_buffers.push(encoder.finish());
        queue.submit(command_buffers);
        if let (Some(capture), Some(path)) = (capture, &options.screenshot) {
            let image = capture.read(device, format)?;
            image
                .save(path)
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        }
        self.window.pre_present_notify();
        self.screen.present(frame);
        for id in textures.free.drain() {
            self.egui_renderer.free_texture(&id);
        }
        self.frames += 1;
        Ok(!last)
    }
}

impl Running {
    /// What the frames cost: the median frame time and rate, and the median physics step,
    /// all over the whole run.
    #[cfg(not(target_arch = "wasm32"))]
    fn report(&self) -> String {
        let median = |values: &[f64]| {
            let mut values = values.to_vec();
            values.sort_by(f64::total_cmp);
            values.get(values.len() / 2).copied().unwrap_or(0.0)
        };
        let (frame, step) = (median(&self.frame_ms), median(&self.step_ms));
        let player = match &self.demo.scene.player {
            Some(player) => {
                let at = player.character().position();
                let done = if player.finished() { ", finished" } else { "" };
                format!(", player at ({:.2}, {:.2}){done}", at.x, at.y)
            }
            None => String::new(),
        };
        format!(
            "{}: {} frames at {}x{} on {}: median frame {frame:.1} ms ({:.1} frames/s), \
             median step {step:.3} ms, {} bodies, {} steps{player}",
            self.demo.scene_path.display(),
            self.frames,
            self.screen.size()[0],
            self.screen.size()[1],
            self.adapter,
            1e3 / frame.max(1e-6),
            self.demo.scene.world.body_count(),
            self.demo.scene.world.step_count(),
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
                            self.screen.format(),
                        )),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            })
            .forget_lifetime();
        let [width, height] = self.screen.size().map(|side| side as f32);
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
        self.screen.renderer().render(&mut pass);
        pass.set_viewport(0.0, 0.0, width, height, 0.0, 1.0);
        self.egui_renderer.render(&mut pass, paint_jobs, screen);
    }
}

/// The scene's part of the window (right of the sidebar), physical pixels.
fn scene_viewport(width: u32, height: u32, scale: f32) -> [u32; 2] {
    let sidebar = (SIDEBAR_WIDTH * scale).ceil() as u32;
    [width.saturating_sub(sidebar).max(1), height.max(1)]
}

/// The player control a key gives, if any.
fn control(key: PhysicalKey) -> Option<Control> {
    match key {
        PhysicalKey::Code(KeyCode::KeyA | KeyCode::ArrowLeft) => Some(Control::Left),
        PhysicalKey::Code(KeyCode::KeyD | KeyCode::ArrowRight) => Some(Control::Right),
        PhysicalKey::Code(KeyCode::Space | KeyCode::ArrowUp) => Some(Control::Jump),
        _ => None,
    }
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
