//! Snapshot images: scenes rendered offscreen after fixed steps, compared with the golden PNGs
//! in `crates/carom-demo/tests/snapshots/`.
//!
//! Rendering needs a wgpu adapter: Mesa's GL (llvmpipe, through EGL) or Vulkan (lavapipe). The
//! adapter is requested across all backends, Vulkan first; `WGPU_BACKEND=gl|vulkan` picks one.
//! With none, the tests fail and say what to install: they never pass without rendering.
//!
//! On a mismatch the actual image and a diff (differing pixels red over a dimmed copy of the
//! golden) are written under `target/snapshots/`. `CAROM_UPDATE_SNAPSHOTS=1` rewrites the
//! goldens instead of comparing.

use carom_demo::snapshot::{SnapshotOptions, load_and_step, render_scene};
use carom_render::Offscreen;
use image::{Rgba, RgbaImage};
use std::path::PathBuf;

/// Size of every snapshot: small enough to keep the goldens light, large enough to read.
const WIDTH: u32 = 480;
const HEIGHT: u32 = 270;

/// A pixel differs when any channel differs by more than this (of 255). GL and Vulkan
/// rasterise polygon edges and round smoothed edges slightly differently; a wrong colour,
/// a missing body or a moved one differs by far more.
const CHANNEL_TOLERANCE: u8 = 40;

/// At most this fraction of pixels may differ: a shifted body of the smallest scene moves
/// several times more pixels than this.
const MAX_DIFFERING_FRACTION: f64 = 0.002;

/// Each case: scene, steps before the picture, and what it shows.
const CASES: [(&str, usize); 11] = [
    // Mixed shapes piled on the floor, contact points and normals drawn.
    ("collision", 150),
    // The worked example's reference and incident edges, and every edge normal.
    ("normals", 1),
    // The ball already past the wall it should have hit: continuous collision is off.
    ("tunneling", 3),
    // A column of 20 boxes after two seconds.
    ("vertical_stack", 120),
    // A pyramid of 210 boxes after a second.
    ("pyramid", 60),
    // A chain of 40 hinged links holding a ball, joints drawn.
    ("chain", 30),
    // Box2D's bridge with boxes dropped on it, after two seconds.
    ("bridge", 120),
    // Capsules, rounded boxes and circles on their way down a chain landscape, after 4 s.
    ("terrain", 240),
    // 20 ragdolls falling into a pile, after a second and a half.
    ("ragdolls", 90),
    // The platformer's level, its player (a capsule) standing at the start, the seesaw
    // level, the moving platform on its way.
    ("platformer", 30),
    // A pyramid and the player on a ramp 100 km from the origin on each axis, after a second:
    // the same picture in the double-precision build, whose positions it shows.
    ("far_away", 60),
];

fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// How two images differ.
struct Difference {
    differing: usize,
    total: usize,
    largest: u8,
    image: RgbaImage,
}

fn compare(golden: &RgbaImage, actual: &RgbaImage) -> Difference {
    let mut image = RgbaImage::new(golden.width(), golden.height());
    let (mut differing, mut largest) = (0, 0u8);
    for (x, y, expected) in golden.enumerate_pixels() {
        let got = actual.get_pixel(x, y);
        let delta = (0..4)
            .map(|c| expected[c].abs_diff(got[c]))
            .max()
            .unwrap_or(0);
        largest = largest.max(delta);
        let shown = if delta > CHANNEL_TOLERANCE {
            differing += 1;
            Rgba([255, 0, 0, 255])
        } else {
            Rgba([expected[0] / 3, expected[1] / 3, expected[2] / 3, 255])
        };
        image.put_pixel(x, y, shown);
    }
    Difference {
        differing,
        total: (golden.width() * golden.height()) as usize,
        largest,
        image,
    }
}

#[test]
fn scenes_render_as_their_golden_images() {
    let mut renderer = Offscreen::new(WIDTH, HEIGHT).unwrap_or_else(|e| {
        panic!("snapshot tests need a wgpu adapter and found none: {e}");
    });
    let update = std::env::var_os("CAROM_UPDATE_SNAPSHOTS").is_some_and(|v| v == "1");
    let out = workspace().join("target/snapshots");
    std::fs::create_dir_all(&out).unwrap();
    let mut failures = Vec::new();
    for (name, steps) in CASES {
        let file = workspace().join(format!("demos/{name}.ron"));
        let scene = load_and_step(&file, steps).unwrap_or_else(|e| panic!("{e}"));
        let options = SnapshotOptions {
            steps,
            width: WIDTH,
            height: HEIGHT,
            draw: Vec::new(),
        };
        let actual =
            render_scene(&scene, &options, &mut renderer).unwrap_or_else(|e| panic!("{e}"));
        let golden_path =
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("tests/snapshots/{name}.png"));
        if update {
            actual.save(&golden_path).unwrap();
            continue;
        }
        let golden = image::open(&golden_path)
            .unwrap_or_else(|e| {
                panic!(
                    "{}: {e}; run with CAROM_UPDATE_SNAPSHOTS=1 to create it",
                    golden_path.display()
                )
            })
            .to_rgba8();
        assert_eq!(golden.dimensions(), actual.dimensions(), "{name}");
        let difference = compare(&golden, &actual);
        let fraction = difference.differing as f64 / difference.total as f64;
        println!(
            "{name}: {} of {} pixels differ by more than {CHANNEL_TOLERANCE} (largest {}), on {}",
            difference.differing,
            difference.total,
            difference.largest,
            renderer.gpu().describe()
        );
        if fraction > MAX_DIFFERING_FRACTION {
            let actual_path = out.join(format!("{name}.actual.png"));
            let diff_path = out.join(format!("{name}.diff.png"));
            actual.save(&actual_path).unwrap();
            difference.image.save(&diff_path).unwrap();
            failures.push(format!(
                "{name}: {:.3} % of pixels differ (at most {:.3} % may); see {} and {}",
                fraction * 100.0,
                MAX_DIFFERING_FRACTION * 100.0,
                actual_path.display(),
                diff_path.display()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_moved_body_is_caught() {
    // The comparison must be able to fail: the same scene a few steps later differs.
    let mut renderer = Offscreen::new(WIDTH, HEIGHT).unwrap_or_else(|e| panic!("{e}"));
    let file = workspace().join("demos/collision.ron");
    let options = SnapshotOptions {
        width: WIDTH,
        height: HEIGHT,
        ..SnapshotOptions::default()
    };
    let early = render_scene(&load_and_step(&file, 20).unwrap(), &options, &mut renderer).unwrap();
    let later = render_scene(&load_and_step(&file, 24).unwrap(), &options, &mut renderer).unwrap();
    let difference = compare(&early, &later);
    assert!(
        difference.differing as f64 / difference.total as f64 > MAX_DIFFERING_FRACTION,
        "four steps of falling moved only {} pixels",
        difference.differing
    );
}

#[test]
fn every_shipped_scene_renders_something() {
    // What `carom snapshot` does, for every scene in demos/: each must draw visibly more than
    // its background.
    let mut renderer = Offscreen::new(WIDTH, HEIGHT).unwrap_or_else(|e| panic!("{e}"));
    let options = SnapshotOptions {
        width: WIDTH,
        height: HEIGHT,
        ..SnapshotOptions::default()
    };
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(workspace().join("demos"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 10, "only {} scenes found", scenes.len());
    let background = carom::draw::Color::BACKGROUND
        .to_array()
        .map(|c| (c * 255.0).round() as u8);
    for scene in scenes {
        let image = render_scene(&load_and_step(&scene, 1).unwrap(), &options, &mut renderer)
            .unwrap_or_else(|e| panic!("{}: {e}", scene.display()));
        let drawn = image
            .pixels()
            .filter(|p| (0..3).any(|c| p[c].abs_diff(background[c]) > 8))
            .count();
        let fraction = drawn as f64 / (WIDTH * HEIGHT) as f64;
        assert!(
            fraction > 0.001,
            "{}: only {drawn} pixels differ from the background",
            scene.display()
        );
    }
}
