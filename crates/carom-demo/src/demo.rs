//! The demo's state, apart from any window: the scene and its camera, the grab, the settings,
//! the fixed-step clock and the live metrics. The window feeds it input events and frame
//! times and draws what it describes; tests feed it synthetic events the same way.

use crate::accuracy_panel::AccuracyPanel;
use crate::files;
use crate::metrics::Metrics;
use crate::recording;
use carom::draw::{Color, DrawList, DrawOptions};
use carom::{Effect, Real, Vec2};
use carom_render::Camera;
use carom_scene::{Course, Input, PlayerInput, Recording, SceneWorld, Timeline};
use std::path::{Path, PathBuf};
use std::time::SystemTime;
use web_time::Instant;

/// A scene file found in the scenes folder.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneEntry {
    /// The file.
    pub path: PathBuf,
    /// Its `name`.
    pub name: String,
    /// Its `description`.
    pub description: String,
}

/// Every `*.ron` scene in `folder` that parses, sorted by file name, and the files that do not
/// parse with the reason (shown, not fatal: one broken scene must not hide the others).
pub fn find_scenes(folder: &Path) -> (Vec<SceneEntry>, Vec<String>) {
    let (mut found, mut broken) = (Vec::new(), Vec::new());
    for path in files::scene_files(folder) {
        match files::read_scene(&path) {
            Ok(scene) => found.push(SceneEntry {
                path,
                name: scene.name,
                description: scene.description,
            }),
            Err(e) => broken.push(e.to_string()),
        }
    }
    (found, broken)
}

/// A mouse button, as the demo cares about them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Button {
    /// Grabs.
    Left,
    /// Pans.
    Right,
    /// Pans too.
    Middle,
}

/// The keys the demo answers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    /// Pause or play (a scene with a player jumps with it instead; see [`Control`]).
    Space,
    /// Pause or play, in every scene.
    Pause,
    /// One step (pauses).
    Step,
    /// Reload the scene.
    Reset,
    /// One step back (pauses).
    StepBack,
    /// Scene by number: 1 is the first, 0 the tenth.
    Digit(u8),
}

/// What the keys held tell a scene's player.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Walk left (A or ←).
    Left,
    /// Walk right (D or →).
    Right,
    /// Jump (Space or ↑).
    Jump,
}

/// The key hints the sidebar shows.
pub const HINTS: &str = "Left drag: grab and throw · Right/middle drag: pan · Wheel: zoom\n\
                         Space or P: pause · S or .: step · ,: step back · R: reset\n\
                         W: save state · 1-9, 0: scenes\n\
                         A/D or ←/→: walk, Space or ↑: jump (scenes with a player)\n\
                         Editing the open scene's file reloads it.";

/// The demo, minus the window.
pub struct Demo {
    /// Scenes to choose from.
    pub scenes: Vec<SceneEntry>,
    /// Index into `scenes` of the one running (if it came from the list).
    pub current: Option<usize>,
    /// The file of the scene running.
    pub scene_path: PathBuf,
    /// The running scene.
    pub scene: SceneWorld,
    /// The view.
    pub camera: Camera,
    /// Size of the view, pixels.
    pub viewport: [u32; 2],
    /// What is drawn.
    pub draw: DrawOptions,
    /// Stopped between steps.
    pub paused: bool,
    /// Simulated seconds per real second.
    pub time_scale: f32,
    /// Most steps one frame may take, so a slow machine slows down instead of spiralling.
    pub max_steps_per_frame: u32,
    /// Wall time one frame may spend stepping; past it the frame takes no more steps (it always
    /// takes one), so a scene slower than real time runs slowed down at a usable frame rate
    /// instead of a few frames a second.
    pub step_budget: std::time::Duration,
    /// Step costs and errors.
    pub metrics: Metrics,
    /// The measured cost of accuracy of the scene's solver settings, and where the demo's
    /// setting sits among them; the sidebar keeps it up to date with the scene shown.
    pub accuracy: AccuracyPanel,
    /// What the demo last did that the user should know of ("saved to …", "reloaded").
    pub notice: Option<String>,
    /// When the open scene's file was last changed, as last seen: a later change reloads it.
    file_changed: Option<SystemTime>,
    accumulator: f64,
    /// The run since the scene was opened or reset, its keyframes, and the hand that
    /// applies inputs (the body the cursor holds).
    timeline: Timeline,
    /// The step the timeline is being played to, a frame's step budget at a time.
    seeking: Option<u64>,
    pan_from: Option<Vec2>,
}

impl Demo {
    /// Opens `scene` (a file), listing the scenes of `folder` for the menu.
    pub fn open(folder: &Path, scene: &Path, viewport: [u32; 2]) -> Result<Demo, String> {
        let (scenes, _) = find_scenes(folder);
        let (loaded, recording) = recording::open(scene)?;
        let current = scenes.iter().position(|s| same_file(&s.path, scene));
        let timeline = Timeline::new(recording, &loaded);
        let mut demo = Demo {
            scenes,
            current,
            scene_path: scene.to_path_buf(),
            camera: scene_camera(&loaded, viewport),
            draw: DrawOptions {
                flags: loaded.draw,
                ..DrawOptions::default()
            },
            scene: loaded,
            viewport,
            paused: false,
            time_scale: 1.0,
            max_steps_per_frame: 4,
            step_budget: std::time::Duration::from_millis(10),
            metrics: Metrics::default(),
            accuracy: AccuracyPanel::default(),
            notice: None,
            file_changed: modified(scene),
            accumulator: 0.0,
            timeline,
            seeking: None,
            pan_from: None,
        };
        demo.metrics.clear();
        Ok(demo)
    }

    /// Switches to scene `index` of the list, with its own settings.
    pub fn select(&mut self, index: usize) -> Result<(), String> {
        let entry = self.scenes.get(index).ok_or("no such scene")?.clone();
        self.load(&entry.path)?;
        self.current = Some(index);
        Ok(())
    }

    /// Reloads the scene from its file, keeping the user's solver, effect and drawing
    /// choices; the view starts again where the scene's camera starts (its own, or one that
    /// frames its bodies).
    pub fn reset(&mut self) -> Result<(), String> {
        let (solver, effects) = (*self.scene.world.solver(), self.scene.world.effects());
        let path = self.scene_path.clone();
        let draw = self.draw;
        self.load(&path)?;
        self.input(Input::Solver(solver))?;
        for effect in Effect::ALL {
            let on = effects.contains(effect);
            if self.scene.world.effects().contains(effect) != on {
                self.input(Input::Effect { effect, on })?;
            }
        }
        self.draw = draw;
        Ok(())
    }

    fn load(&mut self, path: &Path) -> Result<(), String> {
        let changed = modified(path);
        let (loaded, recording) = recording::open(path)?;
        self.timeline = Timeline::new(recording, &loaded);
        self.seeking = None;
        self.file_changed = changed;
        self.notice = None;
        self.camera = scene_camera(&loaded, self.viewport);
        self.draw.flags = loaded.draw;
        self.scene = loaded;
        self.scene_path = path.to_path_buf();
        self.metrics.clear();
        self.accumulator = 0.0;
        self.pan_from = None;
        Ok(())
    }

    /// The running scene as it is now, camera included, as a scene file, and the file it
    /// saves to: `NAME-saved.ron` beside its own (a saved scene saves over itself). Opened
    /// again, it goes on exactly as this one would have.
    pub fn saved(&mut self) -> Result<(PathBuf, carom_scene::Scene), String> {
        let mut scene = files::read_scene(&self.scene_path).map_err(|e| e.to_string())?;
        let stem = self
            .scene_path
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy();
        let stem = stem.strip_suffix("-saved").unwrap_or(&stem);
        let path = self.scene_path.with_file_name(format!("{stem}-saved.ron"));
        let scale = carom_scene::Camera::view_scale(self.viewport[0], self.viewport[1]);
        scene.camera = Some(carom_scene::Camera {
            center: (self.camera.center.x, self.camera.center.y),
            zoom: self.camera.zoom / scale,
        });
        scene.draw = self.draw.flags;
        if !scene.name.ends_with("(saved)") {
            scene.name = format!("{} (saved)", scene.name);
        }
        // The grab's spring is the cursor's, not the scene's: let go before saving.
        self.let_go()?;
        Ok((path, self.scene.save(&scene)))
    }

    /// Saves the running scene ([`Demo::saved`]) to its file and lists it among the scenes.
    pub fn save(&mut self) -> Result<PathBuf, String> {
        let (path, saved) = self.saved()?;
        carom_scene::write(&saved, &path).map_err(|e| e.to_string())?;
        if same_file(&path, &self.scene_path) {
            self.file_changed = modified(&path);
        }
        let folder = path.parent().unwrap_or(Path::new("."));
        let (scenes, _) = find_scenes(folder);
        if let Some(current) = self.current.and_then(|i| self.scenes.get(i)) {
            self.current = scenes
                .iter()
                .position(|s| same_file(&s.path, &current.path));
        }
        self.scenes = scenes;
        self.notice = Some(format!("saved to {}", path.display()));
        Ok(path)
    }

    /// The file the run's recording saves to: `NAME.run` beside the scene's file (a saved
    /// scene's run saves beside it too).
    pub fn recording_path(&self) -> PathBuf {
        self.scene_path.with_extension("run")
    }

    /// Saves the run so far ([`Demo::recording`]) to [`Demo::recording_path`], for `carom
    /// replay` to play back.
    pub fn save_recording(&mut self) -> Result<PathBuf, String> {
        let path = self.recording_path();
        std::fs::write(&path, self.recording().to_text())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        self.notice = Some(format!(
            "recording of {} steps saved to {}",
            self.recording().steps(),
            path.display()
        ));
        Ok(path)
    }

    /// Reloads the open scene if its file changed since it was loaded, keeping the camera
    /// and what is drawn; true if it did. A file that does not load (saved half-edited, say)
    /// is an error naming its line and column, and the scene runs on until the next change.
    pub fn reload_if_changed(&mut self) -> Result<bool, String> {
        let changed = modified(&self.scene_path);
        if changed.is_none() || changed == self.file_changed {
            return Ok(false);
        }
        self.file_changed = changed;
        let (camera, draw) = (self.camera, self.draw);
        let path = self.scene_path.clone();
        self.load(&path)?;
        self.camera = camera;
        self.draw = draw;
        self.notice = Some(format!("reloaded {}", path.display()));
        Ok(true)
    }

    /// The view changed size: the camera keeps its centre and scales its zoom as the scene's
    /// own camera would, so the same part of the world stays in view.
    pub fn resize(&mut self, viewport: [u32; 2]) {
        let scale = |[width, height]: [u32; 2]| carom_scene::Camera::view_scale(width, height);
        self.camera.zoom *= scale(viewport) / scale(self.viewport);
        self.viewport = viewport;
    }

    /// Advances by a frame of `seconds` of real time: as many fixed steps as are due (scaled
    /// by `time_scale`), at most `max_steps_per_frame` and no more once `step_budget` is spent.
    /// Returns the steps taken.
    /// A timeline being played to a step ([`Demo::go_to`]) goes on toward it first, paused or
    /// not, within the same budget.
    pub fn frame(&mut self, seconds: f64) -> Result<u32, String> {
        if let Some(target) = self.seeking {
            return self.seek(target);
        }
        if self.paused {
            return Ok(0);
        }
        let dt = self.scene.time_step as f64;
        self.accumulator += seconds.clamp(0.0, 0.25) * self.time_scale as f64;
        let started = Instant::now();
        let mut steps = 0;
        let mut behind = false;
        while self.accumulator >= dt {
            let over_budget = steps > 0 && started.elapsed() > self.step_budget;
            if steps == self.max_steps_per_frame || over_budget {
                behind = true;
                break;
            }
            self.step()?;
            self.accumulator -= dt;
            steps += 1;
        }
        if behind {
            // Drop the backlog rather than chase it.
            self.accumulator = self.accumulator.min(dt);
        }
        Ok(steps)
    }

    /// Steps toward `target` within the frame's budget; the seek ends there.
    fn seek(&mut self, target: u64) -> Result<u32, String> {
        let started = Instant::now();
        let mut steps = 0;
        while self.timeline.at() < target {
            if steps > 0 && started.elapsed() > self.step_budget {
                return Ok(steps);
            }
            self.step()?;
            steps += 1;
        }
        self.seeking = None;
        Ok(steps)
    }

    /// One fixed step, with its cost recorded: a new one at the end of the run, or the
    /// recorded run's next one after going back.
    pub fn step(&mut self) -> Result<(), String> {
        let clock = Instant::now();
        self.timeline
            .step(&mut self.scene)
            .map_err(|e| e.to_string())?;
        let ms = clock.elapsed().as_secs_f64() * 1e3;
        self.metrics.record(&self.scene.world, ms);
        Ok(())
    }

    /// Goes back (or forward) to step `step` of the run and pauses there. The scene is put
    /// back from the keyframe at or before it, and the recorded run is played on from there,
    /// a frame's step budget at a time ([`Demo::frame`]), so it is at exactly the state it
    /// had. Playing on replays the run; any new input starts a new branch.
    pub fn go_to(&mut self, step: u64) -> Result<(), String> {
        self.paused = true;
        self.accumulator = 0.0;
        let target = self
            .timeline
            .start_toward(&mut self.scene, step)
            .map_err(|e| e.to_string())?;
        self.seeking = (self.timeline.at() < target).then_some(target);
        Ok(())
    }

    /// Where the scene is on its run, and the run: see [`Timeline`].
    pub fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// Applies a user's input to the scene and records it with the step it comes before, so
    /// the run can be played back exactly ([`Demo::recording`]). After going back in time it
    /// starts a new branch of the run, and says so.
    ///
    /// # Errors
    /// A setting out of range; the scene is then left as it was, and nothing is recorded.
    pub fn input(&mut self, input: Input) -> Result<(), String> {
        self.seeking = None;
        let course = self
            .timeline
            .input(&mut self.scene, input)
            .map_err(|e| e.to_string())?;
        if let Course::Branched { at, forgotten } = course {
            self.notice = Some(format!(
                "a new branch from step {at}: the old run's {forgotten} steps after it are gone"
            ));
        }
        Ok(())
    }

    /// The run since the scene was opened, reloaded or reset: its file's text, every input,
    /// and the state hash after every step, to the end of its newest branch.
    pub fn recording(&self) -> &Recording {
        self.timeline.recording()
    }

    /// Whether the scene has a player for the keys to walk ([`Demo::hold`]).
    pub fn has_player(&self) -> bool {
        self.scene.player.is_some()
    }

    /// A player's control held down (`true`) or let go, if the scene has a player.
    pub fn hold(&mut self, control: Control, held: bool) {
        if let Some(player) = &self.scene.player {
            let mut keys = player.input;
            match control {
                Control::Left => keys.left = held,
                Control::Right => keys.right = held,
                Control::Jump => keys.jump = held,
            }
            if keys != player.input {
                // Keys always apply.
                let _ = self.input(Input::keys(keys));
            }
        }
    }

    /// Lets go of every control of the player (the window lost the keyboard), unless it plays
    /// its recorded play, which holds the keys itself, or the run is being replayed after
    /// going back, whose keys are the run's, not the keyboard's.
    pub fn let_go_of_controls(&mut self) {
        if !self.timeline.is_live() {
            return;
        }
        if let Some(player) = self.scene.player.as_ref().filter(|p| !p.is_replaying())
            && player.input != PlayerInput::default()
        {
            // Keys always apply.
            let _ = self.input(Input::keys(PlayerInput::default()));
        }
    }

    /// A key was pressed.
    pub fn key(&mut self, key: Key) -> Result<(), String> {
        match key {
            Key::Space | Key::Pause => self.paused = !self.paused,
            Key::Step => {
                self.paused = true;
                self.step()?;
            }
            Key::StepBack => {
                let back = self.timeline.at().saturating_sub(1);
                self.go_to(back)?;
                // One step back is at most a keyframe's interval away: done at once.
                while let Some(target) = self.seeking {
                    self.seek(target)?;
                }
            }
            Key::Reset => self.reset()?,
            Key::Digit(digit) => {
                let index = if digit == 0 { 9 } else { digit as usize - 1 };
                if index < self.scenes.len() {
                    self.select(index)?;
                }
            }
        }
        Ok(())
    }

    /// A button went down at `screen` (pixels, origin top-left). The left button grabs the
    /// body under the cursor at the point clicked; on empty space it does nothing.
    pub fn press(&mut self, button: Button, screen: Vec2) {
        match button {
            Button::Left => {
                let point = self.camera.screen_to_world(screen, self.viewport);
                // Only a grab of something is an input: a click on empty space after going
                // back in time must not branch the run.
                let world = &self.scene.world;
                let grabbable = world
                    .body_at(point)
                    .and_then(|body| world.body(body))
                    .is_some_and(|body| body.is_dynamic());
                if grabbable {
                    // A grab only adds a joint at a finite point; it cannot fail.
                    let _ = self.input(Input::Grab {
                        point: (point.x, point.y),
                    });
                }
            }
            Button::Right | Button::Middle => self.pan_from = Some(screen),
        }
    }

    /// The cursor moved to `screen`.
    pub fn move_to(&mut self, screen: Vec2) {
        if self.timeline.hand().grabbed().is_some() {
            let point = self.camera.screen_to_world(screen, self.viewport);
            // Screen points map to finite world points; a failure would leave the old target.
            let _ = self.input(Input::Drag {
                point: (point.x, point.y),
            });
        }
        if let Some(from) = self.pan_from {
            self.camera.pan_by_pixels(screen - from);
            self.pan_from = Some(screen);
        }
    }

    /// A button went up: a held body is let go with the velocity it has (a throw).
    pub fn release(&mut self, button: Button) {
        match button {
            Button::Left => {
                // Letting go cannot fail.
                let _ = self.let_go();
            }
            Button::Right | Button::Middle => self.pan_from = None,
        }
    }

    /// Lets go of the held body, if any: it keeps the velocity it has.
    fn let_go(&mut self) -> Result<(), String> {
        match self.timeline.hand().grabbed() {
            Some(_) => self.input(Input::LetGo),
            None => Ok(()),
        }
    }

    /// The wheel turned by `lines` (positive zooms in) with the cursor at `screen`. Outside
    /// the view (over the sidebar, left of it) the wheel is the sidebar's: it scrolls that,
    /// and the scene stays as it is.
    pub fn wheel(&mut self, lines: f32, screen: Vec2) {
        let [width, height] = self.viewport.map(|v| v as Real);
        if !(0.0..=width).contains(&screen.x) || !(0.0..=height).contains(&screen.y) {
            return;
        }
        let factor = 1.1f32.powf(lines.clamp(-10.0, 10.0));
        self.camera.zoom_about(screen, factor, self.viewport);
    }

    /// The body held, if any.
    pub fn grabbed(&self) -> Option<carom::BodyHandle> {
        self.timeline.hand().grabbed().map(|(_, body)| body)
    }

    /// Describes the scene and the grab's spring to `out` (cleared first).
    pub fn describe(&self, out: &mut DrawList) {
        out.clear();
        self.scene.debug_draw(&self.draw, out);
        let world = &self.scene.world;
        if let Some((joint, body)) = self.timeline.hand().grabbed()
            && let Some(joint) = world.joint(joint)
            && let Some(body) = world.body(body)
            && let carom::JointKind::Mouse(mouse) = joint.kind()
        {
            let anchor = body.world_point(joint.local_anchors()[1]);
            let spring = Color::rgb(1.0, 1.0, 1.0);
            carom::draw::DebugDraw::segment(out, anchor, mouse.target, 1.5, spring);
            carom::draw::DebugDraw::point(out, anchor, 6.0, spring);
            carom::draw::DebugDraw::point(out, mouse.target, 4.0, spring);
        }
    }
}

/// When a file was last changed, if it can be told.
fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// The scene's camera for a view `viewport` pixels in size.
pub fn scene_camera(scene: &SceneWorld, viewport: [u32; 2]) -> Camera {
    let (x, y) = scene.camera.center;
    Camera {
        center: carom::vec2(x, y),
        zoom: scene.camera.zoom_for_view(viewport[0], viewport[1]),
    }
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}
