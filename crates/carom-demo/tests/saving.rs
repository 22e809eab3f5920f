//! The demo saves the running scene to a file that opens as it was, and reloads the open
//! scene when its file changes.

use carom::vec2;
use carom_demo::demo::{Button, Demo};
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

const VIEWPORT: [u32; 2] = [980, 720];
const FRAME: f64 = 1.0 / 60.0;

/// A folder of its own holding a copy of the demo scene `name`.
fn scratch_copy(name: &str, test: &str) -> (PathBuf, PathBuf) {
    let folder = std::env::temp_dir().join(format!("carom-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let demos = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos");
    let path = folder.join(name);
    std::fs::copy(demos.join(name), &path).unwrap();
    (folder, path)
}

fn frames(demo: &mut Demo, count: usize) {
    for _ in 0..count {
        demo.frame(FRAME).unwrap();
    }
}

/// Writes `text` to `path` and moves its change time on, as an editor's save does.
fn edit(path: &Path, text: &str, seconds_later: u64) {
    std::fs::write(path, text).unwrap();
    let file = std::fs::File::options().write(true).open(path).unwrap();
    file.set_modified(SystemTime::now() + Duration::from_secs(seconds_later))
        .unwrap();
}

#[test]
fn a_saved_scene_opens_as_it_was_and_goes_on_the_same() {
    let (folder, path) = scratch_copy("grabbing.ron", "save");
    let mut demo = Demo::open(&folder, &path, VIEWPORT).unwrap();
    frames(&mut demo, 30);
    // Hold a body while saving: the cursor's spring is not part of the scene.
    let held = demo.camera.world_to_screen(vec2(0.0, 2.0), VIEWPORT);
    demo.press(Button::Left, held);
    frames(&mut demo, 10);
    demo.camera.center += vec2(1.5, -0.5);
    demo.save().unwrap();
    let saved = folder.join("grabbing-saved.ron");
    assert!(
        demo.notice
            .as_deref()
            .is_some_and(|n| n.contains("grabbing-saved.ron"))
    );
    assert!(demo.grabbed().is_none());
    assert!(
        demo.scenes
            .iter()
            .any(|s| s.path == saved && s.name == "grabbing (saved)")
    );

    let mut reopened = Demo::open(&folder, &saved, VIEWPORT).unwrap();
    assert_eq!(
        reopened.scene.world.state_hash(),
        demo.scene.world.state_hash()
    );
    assert_eq!(reopened.scene.world.time(), demo.scene.world.time());
    assert_eq!(
        reopened.scene.world.joint_count(),
        demo.scene.world.joint_count()
    );
    assert!((reopened.camera.center - demo.camera.center).norm() < 1e-5);
    assert!((reopened.camera.zoom - demo.camera.zoom).abs() < 1e-3);
    for _ in 0..60 {
        demo.step().unwrap();
        reopened.step().unwrap();
    }
    assert_eq!(
        reopened.scene.world.state_hash(),
        demo.scene.world.state_hash()
    );

    // A saved scene saves over itself rather than stacking "-saved" names.
    reopened.save().unwrap();
    assert!(
        reopened
            .notice
            .as_deref()
            .is_some_and(|n| n.contains("grabbing-saved.ron"))
    );
    assert!(!folder.join("grabbing-saved-saved.ron").exists());
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn editing_the_open_scene_reloads_it_and_a_bad_edit_says_where() {
    let (folder, path) = scratch_copy("grabbing.ron", "reload");
    let mut demo = Demo::open(&folder, &path, VIEWPORT).unwrap();
    frames(&mut demo, 10);
    assert!(!demo.reload_if_changed().unwrap(), "nothing changed yet");
    let bodies = demo.scene.world.body_count();
    let camera = demo.camera;

    let original = std::fs::read_to_string(&path).unwrap();
    let one_more = original.replacen(
        "bodies: [",
        "bodies: [\n        (shape: Circle(radius: 0.3), position: (4.0, 8.0)),",
        1,
    );
    edit(&path, &one_more, 5);
    assert!(demo.reload_if_changed().unwrap());
    assert_eq!(demo.scene.world.body_count(), bodies + 1);
    assert_eq!(
        demo.camera.center, camera.center,
        "the view stays where it was"
    );
    assert!(
        demo.notice
            .as_deref()
            .is_some_and(|n| n.starts_with("reloaded"))
    );
    assert!(
        !demo.reload_if_changed().unwrap(),
        "reloaded once per change"
    );

    // Saved half-edited: the error names the line and column, the scene runs on.
    let half_edited = one_more.replacen("position: (4.0, 8.0)", "position: (4.0 8.0)", 1);
    edit(&path, &half_edited, 10);
    let line = 1 + half_edited
        .lines()
        .position(|l| l.contains("(4.0 8.0)"))
        .unwrap();
    let error = demo.reload_if_changed().unwrap_err();
    assert!(error.contains(&format!("grabbing.ron:{line}:")), "{error}");
    assert_eq!(demo.scene.world.body_count(), bodies + 1);
    frames(&mut demo, 5);
    assert!(
        !demo.reload_if_changed().unwrap(),
        "a bad edit is reported once"
    );

    edit(&path, &original, 15);
    assert!(demo.reload_if_changed().unwrap());
    assert_eq!(demo.scene.world.body_count(), bodies);
    std::fs::remove_dir_all(&folder).unwrap();
}
