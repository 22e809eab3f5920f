//! Sleeping: resting islands stop, and wake when disturbed.

use carom::{BodyDef, BodyHandle, Effect, Effects, Real, Shape, World, WorldSettings, vec2};

const DT: Real = 1.0 / 60.0;

fn world(sleeping: bool) -> World {
    World::with_settings(WorldSettings {
        effects: Effects::ALL.switched(Effect::Sleeping, sleeping),
        ..WorldSettings::default()
    })
    .unwrap()
}

/// A ground and a column of `count` boxes on it; returns the boxes bottom to top.
fn column(world: &mut World, x: Real, count: usize) -> Vec<BodyHandle> {
    (0..count)
        .map(|i| {
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, 0.5 + i as Real)),
                )
                .unwrap()
        })
        .collect()
}

fn add_ground(world: &mut World) {
    world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
}

fn steps(world: &mut World, count: usize) {
    for _ in 0..count {
        world.step(DT).unwrap();
    }
}

#[test]
fn a_resting_stack_falls_asleep_as_one_and_stays_put() {
    let mut world = world(true);
    add_ground(&mut world);
    let boxes = column(&mut world, 0.0, 5);
    steps(&mut world, 20);
    assert!(
        boxes.iter().all(|b| !world.body(*b).unwrap().is_sleeping()),
        "too early"
    );
    steps(&mut world, 100);
    assert!(boxes.iter().all(|b| world.body(*b).unwrap().is_sleeping()));
    assert_eq!(world.stats().sleeping_bodies, 5);
    assert_eq!(
        world.stats().contact_points,
        0,
        "sleeping contacts are not solved"
    );
    let before: Vec<_> = boxes
        .iter()
        .map(|b| world.body(*b).unwrap().position())
        .collect();
    steps(&mut world, 120);
    let after: Vec<_> = boxes
        .iter()
        .map(|b| world.body(*b).unwrap().position())
        .collect();
    assert_eq!(before, after, "asleep means not moving at all");
}

#[test]
fn sleeping_off_means_never_asleep() {
    let mut world = world(false);
    add_ground(&mut world);
    let boxes = column(&mut world, 0.0, 3);
    steps(&mut world, 240);
    assert!(boxes.iter().all(|b| !world.body(*b).unwrap().is_sleeping()));
    assert_eq!(world.stats().sleeping_bodies, 0);
}

#[test]
fn an_impact_wakes_the_whole_island() {
    let mut world = world(true);
    add_ground(&mut world);
    let boxes = column(&mut world, 0.0, 4);
    let far_away = column(&mut world, 20.0, 2);
    steps(&mut world, 120);
    assert!(world.stats().sleeping_bodies == 6);
    // A ball dropped on top of the first column.
    world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.3))
                .position(vec2(0.1, 6.0))
                .density(5.0),
        )
        .unwrap();
    let mut woke = false;
    for _ in 0..120 {
        world.step(DT).unwrap();
        woke |= boxes.iter().all(|b| !world.body(*b).unwrap().is_sleeping());
    }
    assert!(woke, "the column never woke");
    // The other column was never touched: it slept throughout.
    assert!(
        far_away
            .iter()
            .all(|b| world.body(*b).unwrap().is_sleeping())
    );
}

#[test]
fn pushing_or_moving_a_sleeping_body_wakes_it_and_its_island() {
    let mut world = world(true);
    add_ground(&mut world);
    let boxes = column(&mut world, 0.0, 3);
    steps(&mut world, 120);
    assert!(world.body(boxes[0]).unwrap().is_sleeping());
    world
        .body_mut(boxes[0])
        .unwrap()
        .apply_impulse_at_center(vec2(3.0, 0.0))
        .unwrap();
    assert!(!world.body(boxes[0]).unwrap().is_sleeping());
    world.step(DT).unwrap();
    assert!(
        boxes.iter().all(|b| !world.body(*b).unwrap().is_sleeping()),
        "island woke"
    );
    steps(&mut world, 240);
    assert!(
        boxes.iter().all(|b| world.body(*b).unwrap().is_sleeping()),
        "and slept again"
    );
    world
        .body_mut(boxes[2])
        .unwrap()
        .set_position(vec2(5.0, 3.0))
        .unwrap();
    steps(&mut world, 30);
    let lifted = world.body(boxes[2]).unwrap();
    assert!(
        lifted.position().y < 2.0,
        "the teleported box fell: {:?}",
        lifted.position()
    );
}

#[test]
fn step_stats_count_what_happened() {
    let mut world = world(false);
    add_ground(&mut world);
    column(&mut world, 0.0, 3);
    steps(&mut world, 60);
    let stats = *world.stats();
    assert_eq!(stats.bodies, 4);
    assert_eq!(stats.touching_contacts, 3);
    assert_eq!(stats.contact_points, 6);
    assert!(stats.max_penetration > 0.0 && stats.max_penetration < 0.01);
    assert!(stats.kinetic_energy < 1e-3);
    assert!(stats.times.total >= stats.times.solve);
    assert!(stats.times.solve > std::time::Duration::ZERO);
}

#[test]
fn a_stack_on_a_still_kinematic_platform_sleeps_and_wakes_when_it_moves() {
    let mut world = world(true);
    let platform = world
        .add_body(BodyDef::kinematic(Shape::rect(3.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let stack = column(&mut world, 0.0, 3);
    let asleep = |world: &World| stack.iter().all(|&b| world.body(b).unwrap().is_sleeping());
    steps(&mut world, 90);
    assert!(
        asleep(&world),
        "a still platform lets what rests on it sleep"
    );
    for step in 0..60 {
        world.step(DT).unwrap();
        assert!(asleep(&world), "and it stays asleep ({step} steps on)");
    }
    world
        .body_mut(platform)
        .unwrap()
        .set_linear_velocity(vec2(0.0, 1.0))
        .unwrap();
    steps(&mut world, 30);
    assert!(
        stack.iter().all(|&b| !world.body(b).unwrap().is_sleeping()),
        "a moving platform wakes it"
    );
    let rose = world.body(stack[0]).unwrap().position().y - 0.5;
    assert!(rose > 0.3, "the stack rides the platform up ({rose} m)");
}
