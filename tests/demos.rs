//! Every scene shipped in `demos/` loads and runs without NaN.

use carom_scene::load;
use std::path::PathBuf;

fn demos() -> Vec<PathBuf> {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    files
}

/// Every dynamic body's centre in half metres, sorted: exact for boxes laid on a 0.5 m grid.
fn dynamic_centres(scene: &carom_scene::SceneWorld) -> Vec<(i32, i32)> {
    let mut centres: Vec<(i32, i32)> = scene
        .world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| {
            (
                (b.position().x * 2.0).round() as i32,
                (b.position().y * 2.0).round() as i32,
            )
        })
        .collect();
    centres.sort_unstable();
    centres
}

#[test]
fn every_demo_loads_and_runs_finite() {
    let files = demos();
    assert!(files.len() >= 7, "found {files:?}");
    for file in files {
        let mut scene = load(&file).unwrap_or_else(|e| panic!("{e}"));
        // Big scenes get fewer steps here; `carom run` runs them at length.
        let steps = if scene.world.body_count() > 1000 {
            10
        } else {
            240
        };
        for _ in 0..steps {
            scene.step().unwrap();
        }
        for body in scene.world.bodies() {
            let finite = body
                .position()
                .iter()
                .chain(body.linear_velocity().iter())
                .all(|x| x.is_finite());
            assert!(finite, "{}: a body went non-finite", file.display());
        }
    }
}

#[test]
fn the_tunneling_demo_tunnels_until_continuous_collision_is_on() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/tunneling.ron");
    let run = |continuous: bool| {
        let mut scene = load(&file).unwrap();
        scene
            .world
            .set_effect(carom::Effect::Continuous, continuous);
        for _ in 0..30 {
            scene.step().unwrap();
        }
        scene.world.body(scene.names["ball"]).unwrap().position().x
    };
    assert!(run(false) > 1.0, "the ball should pass the wall");
    assert!(run(true) < -0.25, "the wall should hold");
}

#[test]
fn the_large_pyramid_is_box2d_s_recipe() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/large_pyramid.ron");
    let scene = load(&file).unwrap();
    assert_eq!(scene.world.body_count(), 5051);
    // Row i, box j (j from i to 99): x = (i + 1) 0.5 + (j - i) - 50, y = (2 i + 1) 0.5.
    let mut expected: Vec<(i32, i32)> = Vec::new();
    for i in 0..100 {
        for j in i..100 {
            let x = (i + 1) as f32 * 0.5 + (j - i) as f32 - 50.0;
            let y = (2 * i + 1) as f32 * 0.5;
            expected.push(((x * 2.0).round() as i32, (y * 2.0).round() as i32));
        }
    }
    expected.sort_unstable();
    assert_eq!(dynamic_centres(&scene), expected);
    assert!(!scene.world.effects().contains(carom::Effect::Sleeping));
}

#[test]
fn the_normals_demo_reproduces_the_worked_example() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/normals.ron");
    let mut scene = load(&file).unwrap();
    scene.step().unwrap();
    let (rectangle, quad) = (scene.names["rectangle"], scene.names["quad"]);
    let contact = scene
        .world
        .contacts()
        .find(|c| [c.body_a(), c.body_b()] == [rectangle, quad])
        .expect("the worked example's pair touches");
    let manifold = contact.manifold();
    // The MTV of the worked example (see tests/collision.rs): 1.109 along (0.5546, 0.8321).
    assert!((manifold.normal - carom::vec2(0.554_611, 0.832_116)).norm() < 1e-4);
    let deepest = manifold.min_separation().unwrap();
    assert!((deepest + 1.109).abs() < 1e-3, "{deepest}");
}

#[test]
fn the_incline_boxes_hold_below_the_critical_angle_and_slide_above() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/incline_friction.ron");
    let mut scene = load(&file).unwrap();
    let start: Vec<_> = scene
        .world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| b.position())
        .collect();
    for _ in 0..120 {
        scene.step().unwrap();
    }
    let moved: Vec<f32> = scene
        .world
        .bodies()
        .filter(|b| b.is_dynamic())
        .zip(&start)
        .map(|(b, s)| (b.position() - s).norm())
        .collect();
    // Slopes at 0.8, 0.9, 1.0, 1.1 and 1.2 times the critical angle.
    assert!(moved[0] < 0.01 && moved[1] < 0.01, "{moved:?}");
    assert!(moved[3] > 0.3 && moved[4] > 0.3, "{moved:?}");
}

#[test]
fn the_cradle_passes_the_momentum_down_the_row() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/newtons_cradle.ron");
    let mut scene = load(&file).unwrap();
    for _ in 0..120 {
        scene.step().unwrap();
    }
    let velocities: Vec<f32> = scene
        .world
        .bodies()
        .map(|b| b.linear_velocity().x)
        .collect();
    let striker = velocities[0];
    let last = *velocities.last().unwrap();
    assert!(striker.abs() < 0.3, "striker still moving: {velocities:?}");
    assert!((last - 4.0).abs() < 0.3, "last ball: {velocities:?}");
    let momentum: f32 = velocities.iter().sum();
    assert!((momentum - 4.0).abs() < 1e-3, "{velocities:?}");
}

#[test]
fn the_overlapped_pyramid_recovers_without_exploding() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/overlap_recovery.ron");
    let mut scene = load(&file).unwrap();
    let mut fastest: f32 = 0.0;
    for _ in 0..180 {
        scene.step().unwrap();
        fastest = scene
            .world
            .bodies()
            .map(|b| b.linear_velocity().norm())
            .fold(fastest, f32::max);
    }
    // Soft step pushes each overlap out at no more than 3 m/s; a box pushed by several
    // neighbours moves a little faster (3.55 m/s in the graph-coloured order; the stability
    // suite lists it as a known miss of its 1.1 x cap bar).
    assert!(fastest < 4.0, "fastest {fastest} m/s");
    assert!(scene.world.stats().max_penetration < 0.01);
}

#[test]
fn many_pyramids_is_box2d_s_recipe() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/many_pyramids.ron");
    let scene = load(&file).unwrap();
    assert_eq!(scene.world.body_count(), 20 + 22_000);
    // Box2D: x = (i + 1) 0.5 + (j - i) + centreX - 0.5, y = (2 i + 1) 0.5 + baseY, with
    // centreX = -110 + 11 column + 1 and baseY = 11 row, i the row in the pyramid, j from i to 9.
    let mut expected: Vec<(i32, i32)> = Vec::new();
    for row in 0..20 {
        for column in 0..20 {
            let (center_x, base_y) = (-110.0 + 11.0 * column as f32 + 1.0, 11.0 * row as f32);
            for i in 0..10 {
                for j in i..10 {
                    let x = (i + 1) as f32 * 0.5 + (j - i) as f32 + center_x - 0.5;
                    let y = (2 * i + 1) as f32 * 0.5 + base_y;
                    expected.push(((x * 2.0).round() as i32, (y * 2.0).round() as i32));
                }
            }
        }
    }
    expected.sort_unstable();
    assert_eq!(dynamic_centres(&scene), expected);
}

#[test]
fn rain_is_the_same_every_time() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/rain.ron");
    let (a, b) = (load(&file).unwrap(), load(&file).unwrap());
    assert_eq!(a.world.state_hash(), b.world.state_hash());
    assert_eq!(a.world.body_count(), 4 + 300);
}

#[test]
fn the_card_house_stands() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/card_house.ron");
    let mut scene = load(&file).unwrap();
    let start: Vec<_> = scene.world.bodies().map(|b| b.position()).collect();
    for _ in 0..300 {
        scene.step().unwrap();
    }
    // The leaning pairs close their millimetre gaps and settle; a collapse drops cards by metres.
    let dropped = scene
        .world
        .bodies()
        .zip(&start)
        .map(|(b, s)| s.y - b.position().y)
        .fold(0.0, f32::max);
    assert!(dropped < 0.05, "a card fell {dropped} m");
}
