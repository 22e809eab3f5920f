//! The demo without its window: synthetic mouse events grab, drag and throw a body.

use carom::{Vec2, vec2};
use carom_demo::demo::{Button, Demo, Key};
use std::path::PathBuf;

const VIEWPORT: [u32; 2] = [980, 720];
const FRAME: f64 = 1.0 / 60.0;

fn demos() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos")
}

fn open(scene: &str) -> Demo {
    Demo::open(&demos(), &demos().join(scene), VIEWPORT).unwrap()
}

fn frames(demo: &mut Demo, count: usize) {
    for _ in 0..count {
        demo.frame(FRAME).unwrap();
    }
}

/// The box of the grabbing scene: its handle and where it is on screen.
fn the_box(demo: &Demo) -> (carom::BodyHandle, Vec2) {
    let body = demo
        .scene
        .world
        .bodies()
        .find(|b| b.is_dynamic() && (b.mass() - 1.44).abs() < 1e-3)
        .expect("the grabbing scene has a 1.2 m box");
    let screen = demo.camera.world_to_screen(body.position(), VIEWPORT);
    (body.handle(), screen)
}

#[test]
fn a_body_is_grabbed_dragged_against_a_wall_and_thrown() {
    let mut demo = open("grabbing.ron");
    frames(&mut demo, 60);
    let (handle, screen) = the_box(&demo);

    // Press on the box: it is grabbed at the point clicked.
    demo.press(Button::Left, screen);
    assert_eq!(demo.grabbed(), Some(handle));
    // The grab is a mouse joint on the box, a soft constraint the solver holds with the
    // contacts.
    let joints: Vec<_> = demo.scene.world.joints().collect();
    assert_eq!(joints.len(), 1);
    assert!(matches!(joints[0].kind(), carom::JointKind::Mouse(_)));
    assert_eq!(joints[0].bodies(), [handle, handle]);

    // Drag far past the right wall (0.5 m thick, its inner face at x = 7): the box follows the
    // cursor but stops at the wall. Contacts are soft, as Box2D's: the box hits the wall at
    // about 10 m/s and is pressed into it by the spring, so its corner may sink a little into
    // the wall, never far and never through (up to 0.12 m with soft step's graph-coloured
    // order, under 0.1 m in contact order).
    let target = demo.camera.world_to_screen(vec2(12.0, 3.0), VIEWPORT);
    for i in 1..=90 {
        let t = (i as carom::Real / 60.0).min(1.0);
        demo.move_to(screen + (target - screen) * t);
        frames(&mut demo, 1);
        let right = demo.scene.world.body(handle).unwrap().aabb().max.x;
        assert!(
            right < 7.0 + 0.15,
            "frame {i}: the box's right side went {} m into the wall",
            right - 7.0
        );
    }
    let pressed = demo.scene.world.body(handle).unwrap().position();
    assert!(
        pressed.x > 6.0,
        "the box did not follow the cursor: {pressed:?}"
    );
    // Pressed into the wall, friction holds it a little below the cursor's height.
    assert!(
        pressed.y > 1.5,
        "the box did not follow the cursor up: {pressed:?}"
    );

    // Swing it up and to the left, then let go mid-swing: it flies on that way.
    let start = demo.camera.world_to_screen(pressed, VIEWPORT);
    for i in 1..=8 {
        demo.move_to(start + vec2(-40.0, -20.0) * i as carom::Real);
        frames(&mut demo, 1);
    }
    demo.release(Button::Left);
    assert_eq!(demo.grabbed(), None);
    assert_eq!(
        demo.scene.world.joint_count(),
        0,
        "letting go removes the joint"
    );
    let velocity = demo.scene.world.body(handle).unwrap().linear_velocity();
    assert!(
        velocity.x < -2.0 && velocity.y > 0.5,
        "thrown at {velocity:?}"
    );
    let released_at = demo.scene.world.body(handle).unwrap().position();
    frames(&mut demo, 10);
    let later = demo.scene.world.body(handle).unwrap().position();
    assert!(
        later.x < released_at.x - 0.3,
        "{released_at:?} -> {later:?}"
    );
}

#[test]
fn pressing_on_empty_space_grabs_nothing_and_right_drag_pans() {
    let mut demo = open("grabbing.ron");
    let empty = demo.camera.world_to_screen(vec2(0.0, 9.0), VIEWPORT);
    demo.press(Button::Left, empty);
    assert_eq!(demo.grabbed(), None);
    demo.release(Button::Left);

    let before = demo.camera.screen_to_world(vec2(490.0, 360.0), VIEWPORT);
    demo.press(Button::Right, vec2(490.0, 360.0));
    demo.move_to(vec2(590.0, 360.0));
    demo.release(Button::Right);
    // Dragging the view right by 100 px shows what was 100 px to the left.
    let after = demo.camera.screen_to_world(vec2(590.0, 360.0), VIEWPORT);
    assert!((after - before).norm() < 1e-3, "{before:?} vs {after:?}");

    // The wheel zooms about the cursor: the point under it stays put.
    let cursor = vec2(200.0, 150.0);
    let under = demo.camera.screen_to_world(cursor, VIEWPORT);
    let zoom = demo.camera.zoom;
    demo.wheel(3.0, cursor);
    assert!((demo.camera.screen_to_world(cursor, VIEWPORT) - under).norm() < 1e-3);
    assert!(
        demo.camera.zoom > 1.3 * zoom,
        "three notches zoom in by 1.1³"
    );

    // Over the sidebar (left of the view) the wheel scrolls the sidebar only.
    let camera = demo.camera;
    demo.wheel(3.0, vec2(-120.0, 150.0));
    assert_eq!(demo.camera, camera);
}

#[test]
fn keys_pause_step_reset_and_pick_scenes() {
    let mut demo = open("grabbing.ron");
    demo.key(Key::Space).unwrap();
    assert!(demo.paused);
    assert_eq!(demo.frame(1.0).unwrap(), 0, "paused: no steps");
    demo.key(Key::Step).unwrap();
    assert_eq!(demo.scene.world.step_count(), 1);
    demo.key(Key::Reset).unwrap();
    assert_eq!(demo.scene.world.step_count(), 0);
    demo.key(Key::Digit(1)).unwrap();
    assert_eq!(demo.current, Some(0));
    assert_eq!(demo.scene_path, demo.scenes[0].path);
    assert!(demo.scenes.len() >= 17, "found {}", demo.scenes.len());
}

#[test]
fn a_slow_machine_takes_at_most_the_cap_of_steps_per_frame() {
    let mut demo = open("grabbing.ron");
    // No time budget: on a loaded machine it could end the frame first.
    demo.step_budget = std::time::Duration::MAX;
    // A frame that took a whole second catches up by at most the cap, not 60 steps.
    let steps = demo.frame(1.0).unwrap();
    assert_eq!(steps, demo.max_steps_per_frame);
    let steps = demo.frame(FRAME).unwrap();
    assert!(steps <= 2, "the backlog was dropped, not chased: {steps}");
}

#[test]
fn every_step_is_measured() {
    let mut demo = open("pyramid.ron");
    frames(&mut demo, 30);
    let steps = demo.scene.world.step_count() as usize;
    assert!(steps >= 29, "{steps} steps in half a second");
    assert_eq!(demo.metrics.samples().len(), steps);
    let latest = *demo.metrics.latest().unwrap();
    assert!(latest.step_ms > 0.0 && latest.max_penetration >= 0.0);
    assert!(latest.energy_change.is_finite());
}

#[test]
fn a_slow_scene_takes_one_step_per_frame_when_the_budget_is_spent() {
    let mut demo = open("pyramid.ron");
    // A budget every step overruns: each frame still takes one step, never more.
    demo.step_budget = std::time::Duration::ZERO;
    for _ in 0..5 {
        assert_eq!(demo.frame(0.5).unwrap(), 1);
    }
    assert_eq!(demo.scene.world.step_count(), 5);
}

/// A grab, a drag and a throw in the grabbing scene, with a solver change between them.
fn recorded_throw() -> carom_scene::Recording {
    let mut demo = open("grabbing.ron");
    frames(&mut demo, 30);
    let (_, screen) = the_box(&demo);
    demo.press(Button::Left, screen);
    // A step after each drag, so each drag has a step of its own.
    for i in 1..=20 {
        demo.move_to(screen + vec2(-8.0 * i as carom::Real, -6.0 * i as carom::Real));
        demo.step().unwrap();
    }
    let mut solver = *demo.scene.world.solver();
    solver.substeps = 6;
    demo.input(carom_scene::Input::Solver(solver)).unwrap();
    demo.release(Button::Left);
    for _ in 0..60 {
        demo.step().unwrap();
    }
    demo.recording().clone()
}

#[test]
fn a_recorded_throw_replays_to_the_same_hash_at_every_step() {
    let recording = recorded_throw();
    assert!(recording.steps() >= 100, "{} steps", recording.steps());
    // The grab, twenty drags, the solver change and the throw.
    assert_eq!(recording.inputs.len(), 23, "{:?}", recording.inputs);
    assert!(matches!(
        recording.inputs[0].input,
        carom_scene::Input::Grab { .. }
    ));
    // Written out and read back, as `carom replay` reads it.
    let text = recording.to_text();
    let replayed = carom_demo::recording::replay(&text, "throw.run").unwrap();
    assert_eq!(replayed.parting, None, "{}", replayed.summary());
    assert_eq!(replayed.steps, recording.steps());
}

#[test]
fn a_tampered_recording_parts_at_the_step_after_the_changed_input() {
    let mut recording = recorded_throw();
    // Move the tenth drag's target by 1 cm: the replay must part at the step that follows it.
    let timed = &mut recording.inputs[10];
    let carom_scene::Input::Drag { point } = &mut timed.input else {
        panic!("input 10 is a drag: {timed:?}");
    };
    point.0 += 0.01;
    let expected = timed.step + 1;
    let replayed = carom_demo::recording::replay(&recording.to_text(), "tampered.run").unwrap();
    let parting = replayed.parting.expect("the tampered recording parts");
    assert_eq!(parting.step, expected, "{}", replayed.summary());
    assert!(replayed.summary().contains(&format!("step {expected} ")));
}

#[test]
fn a_recording_that_is_not_one_is_refused_with_its_line() {
    let error = carom_demo::recording::replay("(format: 1, name: \"x\",", "bad.run").unwrap_err();
    assert!(error.contains("bad.run:"), "{error}");
    let other = carom_scene::Recording {
        format: 99,
        ..carom_scene::Recording::new("x.ron", "()")
    };
    let error = carom_demo::recording::replay(&other.to_text(), "old.run").unwrap_err();
    assert!(error.contains("format 99"), "{error}");
}

/// Steps the demo, one at a time, until it is at `step` of its run.
fn step_to(demo: &mut Demo, step: u64) {
    while demo.timeline().at() < step {
        demo.step().unwrap();
    }
}

#[test]
fn going_back_replays_the_run_and_a_grab_after_it_branches() {
    let mut demo = open("grabbing.ron");
    let mut first = Vec::new();
    step_to(&mut demo, 300);
    first.extend_from_slice(&demo.recording().hashes);

    // Back to step 100 through the scrubber: a frame's budget at a time, paused there.
    demo.go_to(100).unwrap();
    assert!(demo.paused);
    for _ in 0..200 {
        demo.frame(FRAME).unwrap();
    }
    assert_eq!(demo.timeline().at(), 100);
    assert_eq!(demo.scene.world.state_hash(), first[99]);
    // Playing on replays the run: step 300 is as it was.
    demo.paused = false;
    while demo.timeline().at() < 300 {
        demo.frame(FRAME).unwrap();
    }
    assert_eq!(demo.scene.world.state_hash(), first[299]);
    assert_eq!(demo.notice, None);

    // One step back, with the key.
    demo.key(Key::StepBack).unwrap();
    assert_eq!(demo.timeline().at(), 299);
    assert_eq!(demo.scene.world.state_hash(), first[298]);

    // A click on empty space after going back is no input: the run stays whole.
    demo.go_to(100).unwrap();
    frames(&mut demo, 200);
    demo.press(Button::Left, Vec2::new(2.0, 2.0));
    demo.release(Button::Left);
    assert_eq!(demo.timeline().end(), 300);

    // A grab is: the run branches at step 100, and the demo says so.
    let (_, screen) = the_box(&demo);
    demo.press(Button::Left, screen);
    assert_eq!(demo.timeline().end(), 100);
    let notice = demo.notice.clone().unwrap_or_default();
    assert!(notice.contains("a new branch from step 100"), "{notice}");
    demo.move_to(screen + vec2(0.0, -200.0));
    step_to(&mut demo, 300);
    assert_ne!(demo.scene.world.state_hash(), first[299]);
    assert_eq!(demo.recording().replay().unwrap(), None);
}
