//! The Rapier copy of a carom world has the same bodies, masses and shapes, and settles alike.

use carom::{BodyDef, BodyKind, Effect, Shape, World, vec2};
use carom_bench::RapierWorld;

const DT: f32 = 1.0 / 60.0;

/// A 40 m static ground box with its top at y = 0.
fn ground(world: &mut World) {
    world
        .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
}

/// Ground plus a pyramid of `rows` rows of 1 m boxes, density 2, touching.
fn pyramid(rows: usize) -> World {
    let mut world = World::new();
    ground(&mut world);
    for i in 0..rows {
        for j in i..rows {
            let x = (i as f32 + 1.0) * 0.5 + (j - i) as f32 - 0.5 * rows as f32;
            let y = i as f32 + 0.5;
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(x, y))
                        .density(2.0)
                        .friction(0.6),
                )
                .unwrap();
        }
    }
    world
}

#[test]
fn pyramid_converts_with_same_bodies_and_mass() {
    let world = pyramid(4);
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    assert_eq!(world.body_count(), 11);
    assert_eq!(rapier.body_count(), world.body_count());
    assert_eq!(rapier.colliders().len(), world.body_count());

    let carom_mass: f32 = world
        .bodies()
        .filter(|b| b.kind() == BodyKind::Dynamic)
        .map(|b| b.mass())
        .sum();
    assert!((carom_mass - 20.0).abs() < 1e-3, "carom mass {carom_mass}");
    let rapier_mass = rapier.dynamic_mass();
    assert!(
        (rapier_mass - carom_mass).abs() <= 1e-3 * carom_mass,
        "Rapier {rapier_mass} kg vs carom {carom_mass} kg"
    );
    // Same places, same kinds, in the same order.
    let flags = rapier.dynamic_flags();
    for ((body, p), dynamic) in world.bodies().zip(rapier.positions()).zip(flags) {
        assert_eq!(body.kind() == BodyKind::Dynamic, dynamic);
        assert!((body.position().x - p[0]).abs() < 1e-6);
        assert!((body.position().y - p[1]).abs() < 1e-6);
    }
    // `World::new()` simulates every effect, Sleeping included, so Rapier bodies may sleep.
    let first = rapier.handle(1).unwrap();
    assert!(
        rapier.bodies()[first]
            .activation()
            .normalized_linear_threshold
            > 0.0
    );
}

#[test]
fn sleeping_off_means_no_rapier_body_can_sleep() {
    let mut world = pyramid(3);
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    for (_, body) in rapier.bodies().iter() {
        assert!(body.activation().normalized_linear_threshold < 0.0);
    }
    assert_eq!(rapier.integration_parameters().num_solver_iterations, 4);
}

#[test]
fn dropped_box_rests_at_the_same_height_in_both_engines() {
    let mut world = World::new();
    ground(&mut world);
    // Bottom face 2 m above the ground.
    world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 2.5)))
        .unwrap();
    let mut rapier = RapierWorld::from_carom(&world, DT).unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
        rapier.step();
    }
    let carom_y = world.bodies().nth(1).unwrap().position().y;
    let rapier_y = rapier.positions()[1][1];
    assert!((carom_y - 0.5).abs() < 0.02, "carom box at {carom_y}");
    assert!(
        (carom_y - rapier_y).abs() < 0.02,
        "carom box at {carom_y}, Rapier box at {rapier_y}"
    );
}

#[test]
fn circle_converts_to_a_ball_of_same_radius_and_mass() {
    let mut world = World::new();
    world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.75))
                .position(vec2(1.0, 3.0))
                .density(3.0),
        )
        .unwrap();
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    let body = &rapier.bodies()[rapier.handle(0).unwrap()];
    let collider = &rapier.colliders()[body.colliders()[0]];
    let ball = collider.shape().as_ball().expect("a ball");
    assert!((ball.radius - 0.75).abs() < 1e-6);
    let carom_mass = world.bodies().next().unwrap().mass();
    assert!((carom_mass - 3.0 * std::f32::consts::PI * 0.75 * 0.75).abs() < 1e-3);
    assert!(
        (body.mass() - carom_mass).abs() <= 1e-3 * carom_mass,
        "Rapier {} kg vs carom {carom_mass} kg",
        body.mass()
    );
}

#[test]
fn rotated_box_and_triangle_become_convex_polygons() {
    let mut world = World::new();
    let tri = Shape::polygon(&[vec2(0.0, 0.0), vec2(2.0, 0.0), vec2(0.0, 1.0)]).unwrap();
    world.add_body(BodyDef::dynamic(tri)).unwrap();
    world
        .add_body(BodyDef::dynamic(Shape::rect(1.0, 0.25)).angle(0.3))
        .unwrap();
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    let shape_of = |i: usize| {
        let body = &rapier.bodies()[rapier.handle(i).unwrap()];
        rapier.colliders()[body.colliders()[0]].shape()
    };
    let poly = shape_of(0).as_convex_polygon().expect("a convex polygon");
    assert_eq!(poly.points().len(), 3);
    // A rectangle stays a cuboid in body space; the body carries the angle.
    let cuboid = shape_of(1).as_cuboid().expect("a cuboid");
    assert!((cuboid.half_extents.x - 1.0).abs() < 1e-6);
    assert!((cuboid.half_extents.y - 0.25).abs() < 1e-6);
    let body = &rapier.bodies()[rapier.handle(1).unwrap()];
    assert!((body.rotation().angle() - 0.3).abs() < 1e-6);
    let masses: f32 = world.bodies().map(|b| b.mass()).sum();
    assert!((rapier.dynamic_mass() - masses).abs() <= 1e-3 * masses);
}

/// Each collider of a compound body (Box2D's compound triangles, each at its centroid, and a
/// box turned by 0.4 rad, denser and slipperier) becomes a Rapier collider in its place, with its
/// own density and friction: the same mass, centre of mass and inertia.
#[test]
fn a_compound_body_keeps_each_collider_s_place_density_and_friction() {
    let world = carom_bench::cases::compound_body();
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    let body = world.bodies().next().unwrap();
    let copy = &rapier.bodies()[rapier.handle(0).unwrap()];
    assert!((copy.mass() - body.mass()).abs() < 1e-5 * body.mass());
    let center = copy.local_center_of_mass();
    assert!(
        (center.x - body.local_center().x).abs() < 1e-5
            && (center.y - body.local_center().y).abs() < 1e-5,
        "Rapier centre {center:?}, carom {:?}",
        body.local_center()
    );
    let inertia = copy.mass_properties().local_mprops.principal_inertia();
    assert!(
        (inertia - body.inertia()).abs() < 1e-4 * body.inertia(),
        "Rapier {inertia} kg m², carom {} kg m²",
        body.inertia()
    );
    assert_eq!(copy.colliders().len(), 3);
    for (&handle, &collider) in copy.colliders().iter().zip(body.colliders()) {
        let (part, carom) = (
            &rapier.colliders()[handle],
            world.collider(collider).unwrap(),
        );
        assert!((part.friction() - carom.friction()).abs() < 1e-6);
        assert!((part.density() - carom.density()).abs() < 1e-6);
        let place = part.position_wrt_parent().unwrap();
        let local = carom.local_transform();
        assert!((place.translation.x - local.translation.x).abs() < 1e-6);
        assert!((place.translation.y - local.translation.y).abs() < 1e-6);
        assert!((place.rotation.angle() - local.rotation.angle()).abs() < 1e-6);
    }
}
