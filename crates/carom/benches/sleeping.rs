//! What sleeping bodies cost: one step of 2000 boxes resting on a floor, asleep and (with
//! sleeping off) awake. Run with `cargo bench -p carom --bench sleeping`.

use carom::{BodyDef, Effect, Effects, Real, Shape, World, WorldSettings, vec2};
use criterion::{Criterion, criterion_group, criterion_main};

fn resting_boxes(sleeping: bool) -> World {
    let mut world = World::with_settings(WorldSettings {
        effects: Effects::ALL.switched(Effect::Sleeping, sleeping),
        ..WorldSettings::default()
    })
    .unwrap();
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
        world.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(
        world.stats().sleeping_bodies,
        if sleeping { 2000 } else { 0 }
    );
    world
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("2000 resting boxes");
    for (name, sleeping) in [("asleep", true), ("awake", false)] {
        let mut world = resting_boxes(sleeping);
        group.bench_function(name, |b| b.iter(|| world.step(1.0 / 60.0).unwrap()));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
