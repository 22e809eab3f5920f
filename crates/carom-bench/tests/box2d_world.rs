//! The Box2D copy of a carom world has the same bodies, masses and friction, and settles alike.

use carom::{BodyDef, BodyKind, Effect, Shape, World, vec2};
use carom_bench::Box2dWorld;

const DT: f32 = 1.0 / 60.0;

/// A 40 m static ground box with its top at y = 0 (friction 0.4) and a 1 m box (density 2,
/// friction 0.9) with its bottom face 2 m above it.
fn box_over_ground() -> World {
    let mut world = World::new();
    world
        .add_body(
            BodyDef::static_body(Shape::rect(20.0, 0.5))
                .position(vec2(0.0, -0.5))
                .friction(0.4),
        )
        .unwrap();
    world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(0.0, 2.5))
                .density(2.0)
                .friction(0.9),
        )
        .unwrap();
    world
}

#[test]
fn dropped_box_lands_at_the_same_height_in_both_engines() {
    let mut world = box_over_ground();
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
        box2d.step(DT).unwrap();
    }
    let carom_y = world.bodies().nth(1).unwrap().position().y;
    let box2d_y = box2d.position(1).unwrap()[1];
    // Resting on soft contacts, both sink by less than the slop.
    assert!((carom_y - 0.5).abs() < 0.005, "carom box at {carom_y}");
    assert!(
        (carom_y - box2d_y).abs() < 0.003,
        "carom box at {carom_y}, Box2D box at {box2d_y}"
    );
    assert!(box2d.linear_velocity(1).unwrap()[1].abs() < 0.01);
}

#[test]
fn mapping_keeps_bodies_masses_and_friction() {
    let world = box_over_ground();
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    assert_eq!(box2d.body_count(), 2);
    assert_eq!(box2d.native_body_count().unwrap(), 2);
    for (i, body) in world.bodies().enumerate() {
        assert_eq!(box2d.kind(i), body.kind());
        assert_eq!(box2d.index_of(body.handle()), Some(i));
        let friction = box2d.friction(i).unwrap();
        let carom = world.collider(body.colliders()[0]).unwrap().friction();
        assert!(
            (friction - carom).abs() < 1e-6,
            "body {i}: Box2D friction {friction}, carom {carom}"
        );
        let p = box2d.position(i).unwrap();
        assert!((p[0] - body.position().x).abs() < 1e-6);
        assert!((p[1] - body.position().y).abs() < 1e-6);
    }
    let dynamic = world.bodies().nth(1).unwrap();
    assert_eq!(dynamic.kind(), BodyKind::Dynamic);
    assert!((dynamic.mass() - 2.0).abs() < 1e-4);
    assert!(
        (box2d.mass(1) - dynamic.mass()).abs() < 1e-4,
        "Box2D {} kg, carom {} kg",
        box2d.mass(1),
        dynamic.mass()
    );
    assert!(
        (box2d.rotational_inertia(1) - dynamic.inertia()).abs() < 1e-4 * dynamic.inertia(),
        "Box2D {} kg m², carom {} kg m²",
        box2d.rotational_inertia(1),
        dynamic.inertia()
    );
    assert_eq!(box2d.mass(0), 0.0);
}

#[test]
fn friction_off_gives_frictionless_shapes_and_triangles_keep_their_vertices() {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Friction, false))
        .unwrap();
    let triangle = Shape::polygon(&[vec2(-0.5, -0.5), vec2(0.5, -0.5), vec2(0.0, 0.5)]).unwrap();
    world
        .add_body(
            BodyDef::dynamic(triangle)
                .position(vec2(1.0, 2.0))
                .angle(0.3)
                .friction(0.8),
        )
        .unwrap();
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    assert_eq!(box2d.friction(0).unwrap(), 0.0);
    let body = world.bodies().next().unwrap();
    assert_same_bounds(&mut box2d, 0, body);
    assert!((box2d.mass(0) - body.mass()).abs() < 1e-4 * body.mass());
}

/// Each collider of a compound body becomes a Box2D shape in its place, with its own density
/// and friction: the same mass, centre of mass, inertia and bounding box.
#[test]
fn a_compound_body_keeps_each_collider_s_place_density_and_friction() {
    let world = carom_bench::cases::compound_body();
    let body = world.bodies().next().unwrap();
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    assert!((box2d.mass(0) - body.mass()).abs() < 1e-5 * body.mass());
    assert!(
        (box2d.rotational_inertia(0) - body.inertia()).abs() < 1e-4 * body.inertia(),
        "Box2D {} kg m², carom {} kg m²",
        box2d.rotational_inertia(0),
        body.inertia()
    );
    let id = box2d.body_id(body.handle()).unwrap();
    let native = box2d.native().body(id).unwrap();
    let center = native.local_center_of_mass().unwrap();
    assert!(
        (center.x - body.local_center().x).abs() < 1e-5
            && (center.y - body.local_center().y).abs() < 1e-5,
        "Box2D centre {center:?}, carom {:?}",
        body.local_center()
    );
    let shapes = native.shapes().unwrap();
    assert_eq!(shapes.len(), 3);
    // Box2D lists a body's shapes newest first.
    for (shape, &collider) in shapes.into_iter().rev().zip(body.colliders()) {
        let carom = world.collider(collider).unwrap();
        let shape = box2d.native().shape(shape).unwrap();
        assert!((shape.friction().unwrap() - carom.friction()).abs() < 1e-6);
        assert!((shape.density().unwrap() - carom.density()).abs() < 1e-6);
    }
    assert_same_bounds(&mut box2d, 0, body);
}

/// A timed Box2D run steps the world (the box falls 2 m onto the ground), times all steps but
/// the first, and reports the drop of the highest dynamic body.
#[test]
fn a_timed_box2d_run_measures_the_drop() {
    let world = box_over_ground();
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    let run = carom_bench::run_box2d(&mut box2d, DT, 120, None).unwrap();
    assert_eq!(run.timed_steps, 119);
    assert!(run.total_ms > 0.0 && !run.nan);
    assert!((run.top_drop - 2.0).abs() < 0.01, "drop {}", run.top_drop);
}

/// Box2D on two workers (its own scheduler) steps the same world to the same place: its
/// solver gives the same bits on any number of workers.
#[test]
fn two_box2d_workers_give_one_workers_result() {
    let world = box_over_ground();
    let mut one = Box2dWorld::from_carom(&world).unwrap();
    let mut two = Box2dWorld::with_workers(&world, 2).unwrap();
    for _ in 0..90 {
        one.step(DT).unwrap();
        two.step(DT).unwrap();
    }
    assert_eq!(one.position(1).unwrap(), two.position(1).unwrap());
    assert!(one.position(1).unwrap()[1] < 0.6, "the box has landed");
    assert!(Box2dWorld::with_workers(&world, 0).is_err());
}

/// An explosion among a circle, a capsule, a box and a rounded hexagon, some within the
/// radius, some in the falloff, one off the line to its centre, gives each body the same
/// impulse and angular impulse in carom and in Box2D.
#[test]
fn an_explosion_pushes_bodies_alike_in_both_engines() {
    use carom::ExplosionDef;
    let mut world = World::with_settings(carom::WorldSettings {
        gravity: vec2(0.0, 0.0),
        ..carom::WorldSettings::default()
    })
    .unwrap();
    let shapes = [
        (Shape::circle(0.4), vec2(1.5, 0.5), 0.0),
        (
            Shape::capsule(vec2(-0.5, 0.0), vec2(0.5, 0.0), 0.25),
            vec2(-2.0, 1.0),
            0.7,
        ),
        (Shape::rect(0.5, 1.5), vec2(0.5, -3.5), 0.3),
        (
            Shape::Polygon(carom::Polygon::regular(6, 0.6).unwrap().rounded(0.1)),
            vec2(-3.0, -2.5),
            0.2,
        ),
    ];
    for (shape, at, angle) in shapes {
        world
            .add_body(BodyDef::dynamic(shape).position(at).angle(angle))
            .unwrap();
    }
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    let explosion = ExplosionDef::new(vec2(0.2, 0.1), 2.0, 3.0).falloff(3.0);
    assert_eq!(world.explode(&explosion).unwrap(), 4);
    box2d.explode(&explosion).unwrap();
    let mut moving = 0;
    for (i, body) in world.bodies().enumerate() {
        // Compared as impulses: Box2D weighs a rounded polygon by pushing its corners out
        // (the hexagon comes out 7.6 % heavier than its exact mass, which carom uses).
        let (linear, angular) = (
            body.linear_velocity() * body.mass(),
            body.angular_velocity() * body.inertia(),
        );
        let [bx, by] = box2d.linear_velocity(i).unwrap().map(|v| v * box2d.mass(i));
        let b_angular = box2d.angular_velocity(i).unwrap() * box2d.rotational_inertia(i);
        let tolerance = 1e-4 * (1.0 + linear.norm());
        assert!(
            (linear.x - bx).abs() < tolerance && (linear.y - by).abs() < tolerance,
            "body {i}: carom {linear:?}, Box2D ({bx}, {by})"
        );
        assert!(
            (angular - b_angular).abs() < 1e-4 * (1.0 + angular.abs()),
            "body {i}: {angular} against {b_angular}"
        );
        moving += usize::from(linear.norm() > 0.1);
    }
    assert_eq!(moving, 4, "every body was pushed");
}

/// Box2D's tight box of its `i`-th body is carom's `body`'s, within 10 µm.
fn assert_same_bounds(box2d: &mut Box2dWorld, i: usize, body: &carom::Body) {
    let (lo, hi) = box2d.aabb(i).unwrap();
    let aabb = body.aabb();
    for (a, b) in [lo, hi]
        .iter()
        .flatten()
        .zip([aabb.min.x, aabb.min.y, aabb.max.x, aabb.max.y])
    {
        assert!(
            (a - b).abs() < 1e-5,
            "Box2D box {lo:?} {hi:?}, carom {aabb:?}"
        );
    }
}
