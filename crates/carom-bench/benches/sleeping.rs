//! What sleeping bodies cost per step, in two worlds:
//! - 2000 boxes resting side by side on a floor, asleep and (with sleeping off) awake;
//! - 20,000 boxes asleep in 1000 columns of 20 beside one box that never stops moving, and
//!   that one box alone, so the difference is what the sleepers cost.
//!
//! Run with `cargo bench -p carom-bench --features criterion --bench sleeping`.

use carom::{BodyDef, Effect, Effects, Real, Shape, World, WorldSettings, vec2};
use criterion::{Criterion, criterion_group, criterion_main};

const DT: Real = 1.0 / 60.0;

fn world(sleeping: bool) -> World {
    World::with_settings(WorldSettings {
        effects: Effects::ALL.switched(Effect::Sleeping, sleeping),
        ..WorldSettings::default()
    })
    .unwrap()
}

fn resting_boxes(sleeping: bool) -> World {
    let mut world = world(sleeping);
    world
        .add_body(BodyDef::static_body(Shape::rect(2100.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    for i in 0..2000 {
        let x = i as Real * 2.0 - 2000.0;
        world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, 0.5)))
            .unwrap();
    }
    // Settle (and, with sleeping on, fall asleep).
    for _ in 0..90 {
        world.step(DT).unwrap();
    }
    assert_eq!(
        world.stats().sleeping_bodies,
        if sleeping { 2000 } else { 0 }
    );
    world
}

/// A box gliding through empty space far above everything: it never rests, so the world
/// always has a step to take.
fn add_mover(world: &mut World) {
    world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(0.0, 500.0))
                .linear_velocity(vec2(1.0, 0.0))
                .gravity_scale(0.0),
        )
        .unwrap();
}

/// `columns` columns of 20 unit boxes on a floor, settled until every box sleeps, and the mover.
fn sleeping_columns(columns: usize) -> World {
    let mut world = world(true);
    let width = columns as Real * 2.0 + 10.0;
    world
        .add_body(BodyDef::static_body(Shape::rect(width, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    for column in 0..columns {
        let x = column as Real * 2.0 - columns as Real;
        for row in 0..20 {
            let y = 0.5 + row as Real;
            world
                .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, y)))
                .unwrap();
        }
    }
    add_mover(&mut world);
    let boxes = columns * 20;
    for _ in 0..600 {
        world.step(DT).unwrap();
        if world.stats().sleeping_bodies == boxes {
            return world;
        }
    }
    panic!(
        "only {} of {boxes} boxes fell asleep",
        world.stats().sleeping_bodies
    );
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("2000 resting boxes");
    for (name, sleeping) in [("asleep", true), ("awake", false)] {
        let mut world = resting_boxes(sleeping);
        group.bench_function(name, |b| b.iter(|| world.step(DT).unwrap()));
    }
    group.finish();

    let mut group = c.benchmark_group("one moving box");
    let mut alone = world(true);
    add_mover(&mut alone);
    group.bench_function("alone", |b| b.iter(|| alone.step(DT).unwrap()));
    let mut beside = sleeping_columns(1000);
    group.bench_function("beside 20,000 sleeping boxes", |b| {
        b.iter(|| beside.step(DT).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
