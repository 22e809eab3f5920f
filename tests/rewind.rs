//! Snapshots restore exactly: every scene in `demos/`, rewound to a snapshot, steps on to the
//! very state it reached the first time, its timed events included.

use carom::World;
use carom_scene::load;

/// The whole state as a saved world writes it: bodies, contacts and their impulses, islands,
/// sleep, the broadphase's trees.
fn saved(world: &World) -> String {
    ron::ser::to_string(world).expect("a world serializes")
}

/// Worlds above this many bodies are stepped less and compared by their hash alone (writing
/// out their whole state takes longer than stepping them).
const LARGE: usize = 1500;

#[test]
fn every_demo_rewound_to_a_snapshot_steps_to_the_same_bits() {
    let files = carom_tests::demo_files();
    assert!(files.len() >= 30, "found {files:?}");
    for file in files {
        let name = file.display();
        let mut scene = load(&file).unwrap_or_else(|e| panic!("{name}: {e}"));
        let at = if scene.world.body_count() > LARGE {
            10
        } else {
            100
        };
        for _ in 0..at {
            scene.step().unwrap();
        }
        let large = scene.world.body_count() > LARGE;
        let end = if large { at + 20 } else { at + 200 };
        let snapshot = scene.snapshot();
        assert_eq!(snapshot.world().step_count(), at);
        for _ in at..end {
            scene.step().unwrap();
        }
        let hash = scene.world.state_hash();
        let state = (!large).then(|| saved(&scene.world));

        scene.restore(&snapshot);
        assert_eq!(scene.world.step_count(), at, "{name}: the step count");
        for _ in at..end {
            scene.step().unwrap();
        }
        assert_eq!(
            scene.world.state_hash(),
            hash,
            "{name}: the rewound scene went elsewhere"
        );
        if let Some(state) = state {
            assert!(
                saved(&scene.world) == state,
                "{name}: the rewound scene's state differs beyond its bodies"
            );
        }
    }
}

/// A pyramid of 10 on the ground, every effect on, stepped for a second, with its boxes.
fn pyramid() -> (World, Vec<carom::BodyHandle>) {
    use carom::{BodyDef, Shape, vec2};
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    carom_bench::cases::worlds::add_pyramid(&mut world, 10, 1.0);
    for _ in 0..60 {
        world.step(1.0 / 60.0).unwrap();
    }
    let boxes = world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| b.handle())
        .collect();
    (world, boxes)
}

#[test]
fn edits_made_after_a_snapshot_are_undone_by_restoring_it() {
    use carom::{BodyDef, Shape, vec2};
    let (mut world, boxes) = pyramid();
    let snapshot = world.snapshot();
    let mut reference = world.clone();
    for _ in 0..120 {
        reference.step(1.0 / 60.0).unwrap();
    }

    // Knock a box out, add a ball, change gravity, and step on.
    world.remove_body(boxes[3]).unwrap();
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.3)).position(vec2(0.0, 14.0)))
        .unwrap();
    world
        .update_settings(|settings| settings.gravity = vec2(3.0, -20.0))
        .unwrap();
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert_ne!(world.state_hash(), reference.state_hash());

    world.restore(&snapshot);
    assert!(world.body(boxes[3]).is_some(), "the removed box is back");
    assert_eq!(world.body_count(), reference.body_count());
    assert_eq!(world.settings().gravity, vec2(0.0, -10.0));
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(world.state_hash(), reference.state_hash());
    assert!(saved(&world) == saved(&reference));
    // The ball's handle was made after the snapshot: it names nothing now.
    assert!(world.body(ball).is_none());
}

#[test]
fn a_snapshot_restores_into_another_world() {
    let (mut world, _) = pyramid();
    let snapshot = world.snapshot();
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    let mut other = World::new();
    other.restore(&snapshot);
    assert_eq!(other.step_count(), snapshot.step_count());
    for _ in 0..30 {
        other.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(other.state_hash(), world.state_hash());
}
