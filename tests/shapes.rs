//! Capsules, rounded polygons, segments and chains in a world: bodies rest, roll and slide on
//! them as they should.

use carom::{BodyDef, BodyHandle, ChainDef, Real, Shape, Vec2, World, vec2};

const DT: Real = 1.0 / 60.0;

/// Flat ground from x = -5 to x = 105 as a chain with a point every `step` metres, solid
/// below (walking right to left, the colliding side is up), frictionless.
fn flat_chain(step: Real) -> ChainDef {
    let count = (110.0 / step).round() as usize;
    let points: Vec<Vec2> = (0..=count)
        .map(|i| vec2(105.0 - i as Real * step, 0.0))
        .collect();
    ChainDef::open(points).friction(0.0)
}

/// The highest a body's lowest point rises above where it settled, while it is pushed along
/// at `speed` over 100 m of `ground`: a bump at a join lifts it.
fn worst_bump(ground: BodyDef, body: Shape, speed: Real) -> (Real, Real) {
    let mut world = World::new();
    world.add_body(ground).unwrap();
    let mover = world
        .add_body(
            BodyDef::dynamic(body)
                .position(vec2(0.0, 0.5))
                .friction(0.0),
        )
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let settled = world.body(mover).unwrap().position().y;
    slide(&mut world, mover, speed, settled)
}

/// Slides `mover` to the right at `speed` until it passes x = 100 m, returning how far it rose
/// above `settled` at worst and the slowest it went (0 if it stopped for good).
fn slide(world: &mut World, mover: BodyHandle, speed: Real, settled: Real) -> (Real, Real) {
    world
        .body_mut(mover)
        .unwrap()
        .set_linear_velocity(vec2(speed, 0.0))
        .unwrap();
    let (mut rise, mut slowest) = (0.0 as Real, speed);
    while world.body(mover).unwrap().position().x < 100.0 {
        world.step(DT).unwrap();
        let body = world.body(mover).unwrap();
        rise = rise.max(body.position().y - settled);
        slowest = slowest.min(body.linear_velocity().x);
        if world.time() > 60.0 {
            return (rise, 0.0);
        }
    }
    (rise, slowest)
}

#[test]
fn a_box_slides_across_a_fine_chain_without_a_bump() {
    let chain = BodyDef::static_chain(&flat_chain(0.01)).unwrap();
    let (rise, slowest) = worst_bump(chain, Shape::rect(0.5, 0.5), 5.0);
    println!("box on a 1 cm chain: rose {rise} m at worst, slowest {slowest} m/s");
    assert!(rise <= 0.001, "the box rose {rise} m at a join");
    assert!(slowest >= 4.99, "the box slowed to {slowest} m/s at a join");
}

#[test]
fn loose_segments_catch_where_a_chain_does_not() {
    // The same ground as separate two-sided segments, which know nothing of their
    // neighbours: the box's leading corner meets the next segment's end.
    let step = 0.01;
    let count = (110.0 / step) as usize;
    let mut ground = BodyDef::static_chain(&flat_chain(step)).unwrap();
    ground.colliders = (0..count)
        .map(|i| {
            let x = -5.0 + i as Real * step;
            carom::ColliderDef::new(Shape::segment(vec2(x, 0.0), vec2(x + step, 0.0)))
                .density(0.0)
                .friction(0.0)
        })
        .collect();
    let (rise, slowest) = worst_bump(ground, Shape::rect(0.5, 0.5), 5.0);
    println!("box on loose 1 cm segments: rose {rise} m at worst, slowest {slowest} m/s");
    assert!(
        rise > 0.001 || slowest < 4.9,
        "loose segments should catch: rose {rise} m, slowest {slowest} m/s"
    );
}

#[test]
fn chains_are_one_sided_and_stop_fast_bodies_from_above() {
    // A flat chain 2 m up, solid side up: a ball thrown up from below passes through it and
    // lands on it; a fast ball dropped on it from above stops on it (continuous collision).
    let mut world = World::new();
    let chain = ChainDef::open(vec![vec2(10.0, 2.0), vec2(-10.0, 2.0)]);
    world
        .add_body(BodyDef::static_chain(&chain).unwrap())
        .unwrap();
    let thrown = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(vec2(-3.0, 0.0))
                .linear_velocity(vec2(0.0, 12.0)),
        )
        .unwrap();
    let dropped = world
        .add_body(
            BodyDef::dynamic(Shape::capsule(vec2(-0.3, 0.0), vec2(0.3, 0.0), 0.1))
                .position(vec2(3.0, 60.0))
                .linear_velocity(vec2(0.0, -120.0)),
        )
        .unwrap();
    let mut highest: Real = 0.0;
    for _ in 0..240 {
        world.step(DT).unwrap();
        highest = highest.max(world.body(thrown).unwrap().position().y);
    }
    assert!(highest > 4.0, "the thrown ball only reached {highest} m");
    let thrown_y = world.body(thrown).unwrap().position().y;
    assert!(
        (thrown_y - 2.25).abs() < 0.02,
        "the ball ended at {thrown_y} m"
    );
    let dropped_y = world.body(dropped).unwrap().position().y;
    assert!(
        (dropped_y - 2.1).abs() < 0.02,
        "the capsule ended at {dropped_y} m"
    );
}

#[test]
fn capsules_and_rounded_boxes_rest_on_their_surfaces() {
    // On a box floor: a capsule lying down rests on its radius, a rounded box on its rounding,
    // and both stay put (no rolling off on their own).
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let capsule = world
        .add_body(
            BodyDef::dynamic(Shape::capsule(vec2(-0.5, 0.0), vec2(0.5, 0.0), 0.25))
                .position(vec2(-3.0, 1.0)),
        )
        .unwrap();
    let rounded = world
        .add_body(BodyDef::dynamic(Shape::rounded_rect(0.4, 0.2, 0.1)).position(vec2(3.0, 1.0)))
        .unwrap();
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.3)).position(vec2(0.0, 3.0)))
        .unwrap();
    for _ in 0..300 {
        world.step(DT).unwrap();
    }
    let c = world.body(capsule).unwrap();
    assert!((c.position().y - 0.25).abs() < 0.01, "{:?}", c.position());
    assert!((c.position().x + 3.0).abs() < 0.01 && c.angle().abs() < 0.01);
    let r = world.body(rounded).unwrap();
    assert!((r.position().y - 0.3).abs() < 0.01, "{:?}", r.position());
    assert!((r.position().x - 3.0).abs() < 0.01 && r.angle().abs() < 0.01);
    assert!((world.body(ball).unwrap().position().y - 0.3).abs() < 0.01);
}
