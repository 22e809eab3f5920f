//! Only the named effects run: each effect's work counter is zero when it is off.

use carom::{BodyDef, Effect, Effects, Real, Shape, Work, World, WorldSettings, vec2};

const DT: Real = 1.0 / 60.0;

/// A world that calls on every effect: gravity, damped bodies, friction and bounces on a floor,
/// a fast ball, and boxes resting long enough to sleep.
fn busy_world(effects: Effects) -> World {
    let mut world = World::with_settings(WorldSettings {
        effects,
        ..WorldSettings::default()
    })
    .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    for i in 0..6 {
        world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .position(vec2(i as Real * 2.0 - 20.0, 0.5))
                    .damping(0.1, 0.1),
            )
            .unwrap();
    }
    // A bouncy ball dropping from high up, fast enough to be swept.
    world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.2))
                .position(vec2(5.0, 8.0))
                .linear_velocity(vec2(1.0, -30.0))
                .restitution(0.8),
        )
        .unwrap();
    // A box sliding along the floor (friction).
    world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(10.0, 0.5))
                .linear_velocity(vec2(4.0, 0.0)),
        )
        .unwrap();
    world
}

/// The work summed over two seconds.
fn total_work(world: &mut World) -> Work {
    let mut total = Work::default();
    for _ in 0..120 {
        world.step(DT).unwrap();
        total += world.stats().work;
    }
    total
}

fn counter(work: &Work, effect: Effect) -> usize {
    match effect {
        Effect::Gravity => work.gravity_terms,
        Effect::Drag => work.drag_terms,
        Effect::Friction => work.friction_impulses,
        Effect::Restitution => work.restitution_impulses,
        Effect::Continuous => work.sweeps,
        Effect::Sleeping => work.sleep_checks,
        other => panic!("{} has no work counter in this test", other.name()),
    }
}

#[test]
fn every_effect_works_when_on_and_does_nothing_when_off() {
    let all = total_work(&mut busy_world(Effects::ALL));
    for effect in Effect::ALL {
        assert!(
            counter(&all, effect) > 0,
            "{} did no work when on",
            effect.name()
        );
    }
    for effect in Effect::ALL {
        let without = total_work(&mut busy_world(Effects::ALL.without(effect)));
        assert_eq!(
            counter(&without, effect),
            0,
            "{} ran while off",
            effect.name()
        );
    }
    let none = total_work(&mut busy_world(Effects::NONE));
    assert_eq!(none, Work::default(), "no effects, no effect work");
}

#[test]
fn effects_switch_at_run_time() {
    let mut world = busy_world(Effects::ALL);
    world.step(DT).unwrap();
    assert!(world.stats().work.gravity_terms > 0);
    world
        .update_settings(|s| s.effects.set(Effect::Gravity, false))
        .unwrap();
    world.step(DT).unwrap();
    assert_eq!(world.stats().work.gravity_terms, 0);
    assert!(!world.effects().contains(Effect::Gravity));
    // Sleeping turned off wakes whoever slept.
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    assert!(world.stats().sleeping_bodies > 0);
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    assert!(world.bodies().all(|b| !b.is_sleeping()));
}
