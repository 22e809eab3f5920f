//! `carom snapshot`: a scene after some steps, rendered offscreen to an image.

use crate::demo::scene_camera;
use carom::draw::{Color, DrawFlags, DrawList, DrawOptions};
use carom_render::Offscreen;
use carom_scene::SceneWorld;
use image::RgbaImage;
use std::path::Path;
use web_time::Instant;

/// What to render and how big.
#[derive(Debug, Clone)]
pub struct SnapshotOptions {
    /// Steps to simulate before the picture.
    pub steps: usize,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Draw layers to add (`true`) or remove (`false`) from what the scene names.
    pub draw: Vec<(DrawFlags, bool)>,
}

impl Default for SnapshotOptions {
    fn default() -> Self {
        SnapshotOptions {
            steps: 0,
            width: 1280,
            height: 720,
            draw: Vec::new(),
        }
    }
}

/// The draw options a scene asks for, changed as `changes` say.
pub fn draw_options(scene: &SceneWorld, changes: &[(DrawFlags, bool)]) -> DrawOptions {
    let mut flags = scene.draw;
    for &(flag, on) in changes {
        flags.set(flag, on);
    }
    DrawOptions {
        flags,
        ..DrawOptions::default()
    }
}

/// Loads a scene and takes `steps` steps.
pub fn load_and_step(file: &Path, steps: usize) -> Result<SceneWorld, String> {
    let mut scene = carom_scene::load(file).map_err(|e| e.to_string())?;
    for _ in 0..steps {
        scene
            .step()
            .map_err(|e| format!("{}: {e}", file.display()))?;
    }
    Ok(scene)
}

/// Renders a scene as it stands.
pub fn render_scene(
    scene: &SceneWorld,
    options: &SnapshotOptions,
    renderer: &mut Offscreen,
) -> Result<RgbaImage, String> {
    let mut list = DrawList::new();
    scene.debug_draw(&draw_options(scene, &options.draw), &mut list);
    renderer.resize(options.width, options.height);
    renderer
        .render(
            &list,
            &scene_camera(scene, [options.width, options.height]),
            Color::BACKGROUND,
        )
        .map_err(|e| e.to_string())
}

/// How long frames took, ms, medians over the frames rendered.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameTimes {
    /// Describing the world into a draw list.
    pub describe_ms: f64,
    /// Uploading, drawing and reading the image back.
    pub render_ms: f64,
    /// Frames measured.
    pub frames: usize,
}

/// Renders the scene `frames` times as it stands and returns the median times; the first
/// frame (shader compilation, buffer creation) is left out.
pub fn time_frames(
    scene: &SceneWorld,
    options: &SnapshotOptions,
    renderer: &mut Offscreen,
    frames: usize,
) -> Result<FrameTimes, String> {
    let draw = draw_options(scene, &options.draw);
    let camera = scene_camera(scene, [options.width, options.height]);
    let mut list = DrawList::new();
    renderer.resize(options.width, options.height);
    let (mut describe, mut render) = (Vec::new(), Vec::new());
    for frame in 0..=frames {
        let clock = Instant::now();
        list.clear();
        scene.debug_draw(&draw, &mut list);
        let described = clock.elapsed();
        renderer
            .render(&list, &camera, Color::BACKGROUND)
            .map_err(|e| e.to_string())?;
        if frame > 0 {
            describe.push(described.as_secs_f64() * 1e3);
            render.push((clock.elapsed() - described).as_secs_f64() * 1e3);
        }
    }
    Ok(FrameTimes {
        describe_ms: median(&mut describe),
        render_ms: median(&mut render),
        frames,
    })
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

/// Parses `+aabbs,-shapes` into draw layers to switch on and off.
pub fn parse_draw_changes(text: &str) -> Result<Vec<(DrawFlags, bool)>, String> {
    let known: Vec<&str> = DrawFlags::NAMED.iter().map(|(n, _)| *n).collect();
    parse_toggles(text, ("layer", "draw layer"), &known, DrawFlags::from_name)
}

/// Parses `+a,-b` into things to switch on (`true`) and off, in order: each a name that
/// `find` knows. `what` names one in the errors, short and in full (`layer`, `draw layer`);
/// `known` lists the names an unknown one is told.
pub fn parse_toggles<T>(
    text: &str,
    what: (&str, &str),
    known: &[&str],
    find: impl Fn(&str) -> Option<T>,
) -> Result<Vec<(T, bool)>, String> {
    let (short, full) = what;
    text.split(',')
        .filter(|part| !part.is_empty())
        .map(|part| {
            let (on, name) = match part.split_at(1) {
                ("+", name) => (true, name),
                ("-", name) => (false, name),
                _ => return Err(format!("`{part}`: start each {short} with + or -")),
            };
            let found = find(name)
                .ok_or_else(|| format!("unknown {full} `{name}`; known: {}", known.join(", ")))?;
            Ok((found, on))
        })
        .collect()
}

/// Parses `1280x720`.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}`: give the size as WIDTHxHEIGHT, for example 1280x720");
    let (width, height) = text.split_once('x').ok_or_else(bad)?;
    let width: u32 = width.trim().parse().map_err(|_| bad())?;
    let height: u32 = height.trim().parse().map_err(|_| bad())?;
    if !(1..=8192).contains(&width) || !(1..=8192).contains(&height) {
        return Err(format!("`{text}`: each side must be 1 to 8192 pixels"));
    }
    Ok((width, height))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_layers_parse_or_say_why_not() {
        assert_eq!(parse_size("1280x720"), Ok((1280, 720)));
        assert!(parse_size("1280").unwrap_err().contains("WIDTHxHEIGHT"));
        assert!(parse_size("0x10").unwrap_err().contains("1 to 8192"));
        assert_eq!(
            parse_draw_changes("+aabbs,-shapes"),
            Ok(vec![(DrawFlags::AABBS, true), (DrawFlags::SHAPES, false)])
        );
        assert!(
            parse_draw_changes("+glow")
                .unwrap_err()
                .contains("contact_points")
        );
        assert!(parse_draw_changes("aabbs").unwrap_err().contains("+ or -"));
    }
}
