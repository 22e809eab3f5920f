//! A scene's camera: its own when it names one, written back as it was read; otherwise one
//! that frames its moving bodies with the ground under them near the bottom of the view.

// Positions are `Real`, f32 or f64 by the core's feature; the zoom is f32 either way.
#![allow(clippy::unnecessary_cast)]

use carom_scene::{Camera, build, parse, to_text};

const GROUND_AND_TOWER: &str = r#"(
    name: "tower",
    bodies: [
        (kind: static, shape: Box(width: 200.0, height: 2.0), position: (0.0, -1.0)),
        (shape: Box(width: 1.0, height: 1.0), position: (30.0, 0.5)),
        (shape: Box(width: 1.0, height: 1.0), position: (30.0, 1.5)),
        (shape: Box(width: 1.0, height: 1.0), position: (30.0, 12.5)),
    ],
)"#;

/// The world box a camera shows in the reference view.
fn shown(camera: &Camera) -> ((f32, f32), (f32, f32)) {
    let (width, height) = Camera::REFERENCE_VIEW;
    let (half_w, half_h) = (0.5 * width / camera.zoom, 0.5 * height / camera.zoom);
    let (x, y) = (camera.center.0 as f32, camera.center.1 as f32);
    ((x - half_w, y - half_h), (x + half_w, y + half_h))
}

#[test]
fn a_scene_without_a_camera_frames_its_bodies_over_the_ground() {
    let scene = parse(GROUND_AND_TOWER, "tower.ron").unwrap();
    assert_eq!(scene.camera, None);
    let built = build(&scene, "tower.ron").unwrap();
    let ((left, bottom), (right, top)) = shown(&built.camera);
    // Every box in view, the 200 m ground not stretched across it.
    assert!(left < 29.5 && right > 30.5, "{:?}", built.camera);
    assert!(bottom < 0.0 && top > 13.0, "{:?}", built.camera);
    assert!(right - left < 40.0, "{:?}", built.camera);
    // The ground's top near the bottom: under a fifth of the view's height.
    let ground_up = (0.0 - bottom) / (top - bottom);
    assert!((0.0..0.2).contains(&ground_up), "{ground_up}");
    // The tower fills most of the height.
    assert!(13.0 / (top - bottom) > 0.7, "{:?}", built.camera);
}

#[test]
fn a_lone_small_body_is_not_blown_up_and_an_empty_scene_has_the_default() {
    let ball = r#"(name: "ball", bodies: [(shape: Circle(radius: 0.1), position: (5.0, 5.0))])"#;
    let built = build(&parse(ball, "ball.ron").unwrap(), "ball.ron").unwrap();
    let ((left, bottom), (right, top)) = shown(&built.camera);
    assert!(top - bottom >= 3.99 && left < 5.0 && right > 5.0 && bottom < 5.0 && top > 5.0);
    let empty = build(
        &parse(r#"(name: "empty")"#, "empty.ron").unwrap(),
        "empty.ron",
    )
    .unwrap();
    assert_eq!(empty.camera, Camera::default());
}

#[test]
fn a_scene_camera_is_the_override_and_is_written_back_as_read() {
    let text = GROUND_AND_TOWER.replace(
        r#"name: "tower","#,
        r#"name: "tower", camera: (center: (1.0, 2.0), zoom: 33.0),"#,
    );
    let scene = parse(&text, "tower.ron").unwrap();
    let camera = Camera {
        center: (1.0, 2.0),
        zoom: 33.0,
    };
    assert_eq!(scene.camera, Some(camera));
    assert_eq!(build(&scene, "tower.ron").unwrap().camera, camera);
    let written = to_text(&scene, "tower.ron").unwrap();
    assert!(!written.contains("camera: Some"), "{written}");
    assert_eq!(parse(&written, "tower.ron").unwrap().camera, Some(camera));
    // Without one, none is written, and the file frames its bodies again when read.
    let framed = parse(GROUND_AND_TOWER, "tower.ron").unwrap();
    assert!(!to_text(&framed, "tower.ron").unwrap().contains("camera"));
}
