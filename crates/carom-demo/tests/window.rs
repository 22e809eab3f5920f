//! The real window, driven to a screenshot. It needs a display, so it is ignored by a plain
//! `cargo test`; `.ci/run` runs it under Xvfb with `cargo test -p carom-demo --test window --
//! --ignored`.

use std::path::PathBuf;
use std::process::Command;

#[test]
#[ignore = "needs a display: .ci/run runs it under Xvfb"]
fn the_window_shows_the_scene_and_the_sidebar() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = root.join("target/window");
    std::fs::create_dir_all(&out).unwrap();
    let screenshot = out.join("collision.png");
    let _ = std::fs::remove_file(&screenshot);
    let output = Command::new(env!("CARGO_BIN_EXE_carom"))
        .current_dir(&root)
        .args([
            "--scene",
            "demos/collision.ron",
            "--frames",
            "120",
            "--screenshot",
        ])
        .arg(&screenshot)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "carom failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let image = image::open(&screenshot).unwrap().to_rgba8();
    let (width, height) = image.dimensions();
    assert!(width >= 640 && height >= 360, "{width}x{height}");

    // Not blank: many distinct colours overall.
    let mut colours: Vec<[u8; 3]> = image.pixels().map(|p| [p[0], p[1], p[2]]).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 50, "only {} colours", colours.len());

    // The sidebar: egui's panel on the left is a flat grey unlike the scene's background,
    // with text on it (light pixels on dark).
    let background = [23u8, 26, 31]; // Color::BACKGROUND, sRGB bytes
    let panel = image.get_pixel(5, height - 5);
    let scene = image.get_pixel(width - 5, 5);
    assert_ne!(
        [panel[0], panel[1], panel[2]],
        [scene[0], scene[1], scene[2]]
    );
    assert!(
        scene.0[..3]
            .iter()
            .zip(background)
            .all(|(a, b)| a.abs_diff(b) <= 2),
        "the scene's corner should be the background, got {scene:?}"
    );
    let text_pixels = (0..300.min(width))
        .flat_map(|x| (0..height / 2).map(move |y| (x, y)))
        .filter(|&(x, y)| image.get_pixel(x, y)[0] > 150)
        .count();
    assert!(
        text_pixels > 500,
        "no text in the sidebar ({text_pixels} light pixels)"
    );
}

/// The platformer, played through the window by its recorded play: 8 steps a frame for 130
/// frames (1040 steps, the play needs about 950), whatever the machine's speed. The window
/// reports the player finished, and the picture shows it at the goal.
#[test]
#[ignore = "needs a display: .ci/run runs it under Xvfb"]
fn the_window_plays_the_platformer_to_its_goal() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = root.join("target/window");
    std::fs::create_dir_all(&out).unwrap();
    let screenshot = out.join("platformer.png");
    let _ = std::fs::remove_file(&screenshot);
    let output = Command::new(env!("CARGO_BIN_EXE_carom"))
        .current_dir(&root)
        .args([
            "--scene",
            "demos/platformer.ron",
            "--replay",
            "--steps-per-frame",
            "8",
            "--frames",
            "130",
            "--screenshot",
        ])
        .arg(&screenshot)
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "carom failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(report.contains("1040 steps"), "{report}");
    assert!(
        report.contains(", finished"),
        "the player did not finish: {report}"
    );
    assert!(image::open(&screenshot).is_ok());
}
