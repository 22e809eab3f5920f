//! The carom demo in a web page: the demo app's window (`carom_demo::window`) in the page's
//! `<canvas id="carom-canvas">`, on WebGPU where the browser has it and WebGL2 otherwise,
//! with every scene of `demos/` and the accuracy report built in.
//! `crates/carom-web/build-site.sh` builds the site (see `docs/web.md`).
//!
//! The page's script can ask the running demo what it shows (`probe`), run a scene headless as
//! `carom run` does (`run_scene`), take the run so far as a recording (`request_recording`,
//! then `recording`) and play a recording back as `carom replay` does (`replay_run`); the
//! browser test uses them all.
//!
//! Built for the machine (not wasm32) the crate is empty, so the workspace builds as before.

#![cfg(target_arch = "wasm32")]

use carom_demo::demo::Demo;
use carom_demo::run::{RunOptions, run};
use carom_demo::window::{FrameInfo, Host, WindowOptions, start_in_canvas};
use std::cell::{Cell, RefCell};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use wasm_bindgen::prelude::*;

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/embedded.rs"));
}

/// The folder the scenes are listed from, as built in.
const SCENES: &str = "demos";
/// The scene the page opens unless its address names another (`?scene=pyramid`).
const FIRST_SCENE: &str = "grabbing";
/// At most this many bodies are listed by [`probe`].
const PROBED_BODIES: usize = 64;

thread_local! {
    /// What the last frame showed, as [`probe`] returns it.
    static LAST_FRAME: RefCell<String> = const { RefCell::new(String::new()) };
    /// Whether the page asked for the run as a recording, and the recording written by the
    /// first frame after it asked ([`request_recording`], [`recording`]).
    static RECORDING_ASKED: Cell<bool> = const { Cell::new(false) };
    static RECORDING: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Starts the demo in the page's `<canvas id="carom-canvas">` (run by the module's `init`).
#[wasm_bindgen(start)]
pub fn start() -> Result<(), JsValue> {
    std::panic::set_hook(Box::new(|info| fail(&format!("carom panicked: {info}"))));
    carom_demo::files::embed(embedded::FILES);
    let canvas = document()?
        .get_element_by_id("carom-canvas")
        .ok_or("the page has no <canvas id=\"carom-canvas\">")?
        .dyn_into::<web_sys::HtmlCanvasElement>()?;
    let name = scene_asked().unwrap_or_else(|| FIRST_SCENE.into());
    let scene = Path::new(SCENES).join(format!("{name}.ron"));
    if carom_demo::files::embedded(&scene).is_none() {
        let message = format!("there is no scene {name} in {SCENES}/");
        fail(&message);
        return Err(message.into());
    }
    let options = WindowOptions {
        scene,
        scenes_folder: PathBuf::from(SCENES),
        size: (0, 0),
        frames: None,
        screenshot: None,
        replay: false,
        steps_per_frame: None,
        script: Vec::new(),
        backends: query("backend").map(|names| wgpu::Backends::from_comma_list(&names)),
    };
    start_in_canvas(options, canvas, Box::new(Page)).map_err(|e| {
        fail(&e);
        JsValue::from(e)
    })
}

/// What the last frame showed, as JSON: frames shown, frames a second, the scene, the camera,
/// the sidebar's width, and where (in CSS pixels from the canvas's top left) the held body
/// and up to 64 dynamic bodies in view are. Empty before the first frame.
#[wasm_bindgen]
pub fn probe() -> String {
    LAST_FRAME.with(|last| last.borrow().clone())
}

/// Runs the built-in scene `file` (`demos/pyramid.ron`) headless for `steps` steps, as
/// `carom run --json` does, and returns its report as JSON (the state hash included).
#[wasm_bindgen]
pub fn run_scene(file: &str, steps: usize) -> Result<String, JsValue> {
    let options = RunOptions {
        steps,
        ..RunOptions::default()
    };
    run(Path::new(file), &options)
        .map(|report| report.to_json())
        .map_err(JsValue::from)
}

/// Asks for the running scene's run so far as a recording: the next frame writes it, and
/// [`recording`] returns it from then on.
#[wasm_bindgen]
pub fn request_recording() {
    RECORDING.with(|text| text.borrow_mut().clear());
    RECORDING_ASKED.with(|asked| asked.set(true));
}

/// The recording the first frame after [`request_recording`] wrote (RON text, as `carom
/// replay` reads it); empty until then.
#[wasm_bindgen]
pub fn recording() -> String {
    RECORDING.with(|text| text.borrow().clone())
}

/// Plays back the recording `text` (one from `carom record`, or saved from a demo) as `carom
/// replay --json` does, and returns its report as JSON: `parted_at` is the first step whose
/// hash differs, or null.
#[wasm_bindgen]
pub fn replay_run(text: &str) -> Result<String, JsValue> {
    carom_demo::recording::replay(text, "the recording")
        .map(|replayed| replayed.to_json())
        .map_err(JsValue::from)
}

/// The built-in scene files, one path a line.
#[wasm_bindgen]
pub fn scene_files() -> String {
    carom_demo::files::scene_files(Path::new(SCENES))
        .iter()
        .map(|path| path.display().to_string())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The page around the demo.
struct Page;

impl Host for Page {
    fn frame(&mut self, demo: &Demo, frame: &FrameInfo<'_>) {
        LAST_FRAME.with(|last| describe(demo, frame, &mut last.borrow_mut()));
        if RECORDING_ASKED.with(|asked| asked.replace(false)) {
            RECORDING.with(|text| *text.borrow_mut() = demo.recording().to_text());
        }
    }

    fn failed(&mut self, message: &str) {
        fail(message);
    }

    /// The page has no folder to write to: the saved scene is offered as a download.
    fn save(&mut self, demo: &mut Demo) -> Result<(), String> {
        let (path, scene) = demo.saved()?;
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let text = carom_scene::to_text(&scene, &name).map_err(|e| e.to_string())?;
        download(&name, &text).map_err(|e| format!("cannot offer {name} for download: {e:?}"))?;
        demo.notice = Some(format!("saved as the download {name}"));
        Ok(())
    }

    /// The run is offered as a download, as a saved scene is.
    fn save_recording(&mut self, demo: &mut Demo) -> Result<(), String> {
        let path = demo.recording_path();
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        download(&name, &demo.recording().to_text())
            .map_err(|e| format!("cannot offer {name} for download: {e:?}"))?;
        demo.notice = Some(format!("recording saved as the download {name}"));
        Ok(())
    }
}

/// Writes [`probe`]'s JSON for the frame just shown into `out`.
fn describe(demo: &Demo, frame: &FrameInfo<'_>, out: &mut String) {
    let css = |pixels: f32| pixels as f64 / frame.scale_factor;
    let on_canvas = |point: carom::Vec2| {
        let screen = demo.camera.world_to_screen(point, demo.viewport);
        let [width, height] = demo.viewport.map(|v| v as f32);
        let inside = (0.0..=width).contains(&screen.x) && (0.0..=height).contains(&screen.y);
        inside.then(|| (css(screen.x + frame.scene_left), css(screen.y)))
    };
    let world = &demo.scene.world;
    out.clear();
    let _ = write!(
        out,
        "{{\"frames\": {}, \"fps\": {:.2}, \"adapter\": {:?}, \"scene\": {:?}, \
         \"name\": {:?}, \"time\": {}, \"sidebar_css\": {}, \"camera\": [{}, {}, {}], \
         \"bodies\": [",
        frame.frames,
        frame.frames_per_second,
        frame.adapter,
        demo.scene_path.display().to_string(),
        demo.current
            .and_then(|i| demo.scenes.get(i))
            .map_or("", |entry| entry.name.as_str()),
        world.time(),
        css(frame.scene_left),
        demo.camera.center.x,
        demo.camera.center.y,
        demo.camera.zoom,
    );
    let listed = world
        .bodies()
        .filter(|b| b.is_dynamic())
        .filter_map(|b| Some((b, on_canvas(b.position())?)))
        .take(PROBED_BODIES);
    for (i, (body, (x, y))) in listed.enumerate() {
        let separator = if i == 0 { "" } else { ", " };
        let p = body.position();
        let _ = write!(
            out,
            "{separator}{{\"x\": {x:.1}, \"y\": {y:.1}, \"world\": [{}, {}]}}",
            p.x, p.y
        );
    }
    out.push_str("], \"held\": ");
    match demo.grabbed().and_then(|handle| world.body(handle)) {
        Some(body) => {
            let p = body.position();
            let (x, y) = on_canvas(p).unwrap_or((f64::NAN, f64::NAN));
            let _ = write!(
                out,
                "{{\"x\": {x:.1}, \"y\": {y:.1}, \"world\": [{}, {}]}}",
                p.x, p.y
            );
        }
        None => out.push_str("null"),
    }
    out.push('}');
}

/// The scene the page's address asks for (`?scene=NAME`), if any.
fn scene_asked() -> Option<String> {
    query("scene")
}

/// The page address's query parameter `name`, if it is there and not empty: `scene` (a
/// built-in scene's name) and `backend` (`webgpu` or `gl`, to draw with that one only).
fn query(name: &str) -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    let params = web_sys::UrlSearchParams::new_with_str(&search).ok()?;
    params.get(name).filter(|value| !value.is_empty())
}

/// Says `message` in the console (where the browser test sees it) and in the page's
/// `#status`, if it has one.
fn fail(message: &str) {
    web_sys::console::error_1(&message.into());
    if let Some(status) = document().ok().and_then(|d| d.get_element_by_id("status")) {
        status.set_text_content(Some(message));
        let _ = status.set_attribute("class", "failed");
    }
}

fn document() -> Result<web_sys::Document, JsValue> {
    web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| "no document".into())
}

/// Offers `text` to the user as a file named `name`.
fn download(name: &str, text: &str) -> Result<(), JsValue> {
    let parts = js_sys::Array::of1(&JsValue::from_str(text));
    let properties = web_sys::BlobPropertyBag::new();
    properties.set_type("text/plain");
    let blob = web_sys::Blob::new_with_str_sequence_and_options(&parts, &properties)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)?;
    let link = document()?
        .create_element("a")?
        .dyn_into::<web_sys::HtmlAnchorElement>()?;
    link.set_href(&url);
    link.set_download(name);
    link.click();
    web_sys::Url::revoke_object_url(&url)
}
