//! The real window, driven to a screenshot. It needs a display, so it is ignored by a plain
//! `cargo test`; `.ci/run` runs it under Xvfb with `cargo test -p carom-demo --test window --
//! --ignored`.

use std::path::PathBuf;
use std::process::Command;

/// The project's root, and where under `target/window` the screenshot `name` goes (any earlier
/// one removed, so a run that writes none is caught).
fn fresh_screenshot(name: &str) -> (PathBuf, PathBuf) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = root.join("target/window");
    std::fs::create_dir_all(&out).unwrap();
    let screenshot = out.join(name);
    let _ = std::fs::remove_file(&screenshot);
    (root, screenshot)
}

#[test]
#[ignore = "needs a display: .ci/run runs it under Xvfb"]
fn the_window_shows_the_scene_and_the_sidebar() {
    let (root, screenshot) = fresh_screenshot("collision.png");
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
    let (root, screenshot) = fresh_screenshot("platformer.png");
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

/// The timeline, driven through the window as the keys and the scrubber drive it: 300 steps
/// of the pyramid, back to step 100, played on to 300 (the same state as the first time), back
/// again, and a grab there, which branches the run and says so.
#[test]
#[ignore = "needs a display: .ci/run runs it under Xvfb"]
fn the_window_goes_back_in_time_and_branches() {
    let (root, screenshot) = fresh_screenshot("timeline.png");
    // Ten steps a frame: frame F begins at step 10 (F - 1) while playing.
    let script = [
        "11:print",
        "31:pause",
        "31:print",
        "31:go-to=100",
        "32:print",
        "32:play",
        "52:pause",
        "52:print",
        "52:go-to=100",
        "53:grab=0,19.5",
        "53:print",
        "53:play",
        "73:pause",
        "73:print",
        "74:go-to=150",
    ];
    let mut command = Command::new(env!("CARGO_BIN_EXE_carom"));
    command.current_dir(&root).args([
        "--scene",
        "demos/pyramid.ron",
        "--steps-per-frame",
        "10",
        "--frames",
        "76",
        "--screenshot",
    ]);
    command.arg(&screenshot);
    for action in script {
        command.args(["--at", action]);
    }
    let output = command.output().unwrap();
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "carom failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    // "frame F: step S of E, hash H, notice: N", one line per print.
    let prints: Vec<(u64, u64, String, String)> = report
        .lines()
        .filter_map(|line| {
            let (_, rest) = line.split_once(": step ")?;
            let (step, rest) = rest.split_once(" of ")?;
            let (end, rest) = rest.split_once(", hash ")?;
            let (hash, notice) = rest.split_once(", notice: ")?;
            Some((
                step.parse().ok()?,
                end.parse().ok()?,
                hash.into(),
                notice.into(),
            ))
        })
        .collect();
    let steps: Vec<(u64, u64)> = prints.iter().map(|p| (p.0, p.1)).collect();
    assert_eq!(
        steps,
        [
            (100, 100),
            (300, 300),
            (100, 300),
            (300, 300),
            (100, 100),
            (300, 300)
        ],
        "{report}"
    );
    let hash = |i: usize| prints[i].2.as_str();
    assert_eq!(hash(2), hash(0), "step 100 gone back to: {report}");
    assert_eq!(hash(3), hash(1), "step 300 replayed: {report}");
    assert!(prints[3].3 == "none", "{report}");
    assert!(
        prints[4].3.contains("a new branch from step 100"),
        "the grab did not say it branched: {report}"
    );
    assert_ne!(hash(5), hash(1), "the grab changed nothing: {report}");
    assert!(image::open(&screenshot).is_ok());
}
