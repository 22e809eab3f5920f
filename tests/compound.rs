//! Bodies made of several colliders: mass from all of them, collision by each, and the
//! world's collider API (add, remove, density, kind).

use carom::{
    BodyDef, BodyKind, CaromError, ColliderDef, Effect, QueryFilter, Ray, Real, Shape, Vec2, World,
    vec2,
};
use std::f32::consts::PI;

/// Mass and inertia about its own centre of a `width` x `height` box of `density`.
fn box_mass(width: Real, height: Real, density: Real) -> (Real, Real) {
    let mass = density * width * height;
    (mass, mass * (width * width + height * height) / 12.0)
}

/// Total mass, centre of mass and inertia about it of parts `(mass, inertia about own centre,
/// centre)`, by the parallel-axis theorem.
fn combine(parts: &[(Real, Real, Vec2)]) -> (Real, Vec2, Real) {
    let mass: Real = parts.iter().map(|p| p.0).sum();
    let center = parts.iter().map(|p| p.2 * p.0).sum::<Vec2>() / mass;
    let inertia = parts
        .iter()
        .map(|(m, i, c)| i + m * (c - center).norm_squared())
        .sum();
    (mass, center, inertia)
}

fn assert_close(what: &str, got: Real, want: Real) {
    assert!(
        (got - want).abs() <= 1e-5 * want.abs().max(1.0),
        "{what}: got {got}, want {want}"
    );
}

#[test]
fn an_l_of_two_boxes_has_the_analytic_mass_centre_and_inertia() {
    // A 2 m x 0.5 m foot and a 0.5 m x 1.5 m upright standing on its left end.
    let mut world = World::new();
    let position = vec2(3.0, 2.0);
    let l = world
        .add_body(
            BodyDef::dynamic(Shape::rect(1.0, 0.25))
                .position(position)
                .collider(ColliderDef::new(Shape::rect(0.25, 0.75)).offset(vec2(-0.75, 1.0))),
        )
        .unwrap();
    let (foot, upright) = (box_mass(2.0, 0.5, 1.0), box_mass(0.5, 1.5, 1.0));
    let (mass, center, inertia) = combine(&[
        (foot.0, foot.1, Vec2::zeros()),
        (upright.0, upright.1, vec2(-0.75, 1.0)),
    ]);
    let body = world.body(l).unwrap();
    assert_close("mass", body.mass(), mass);
    assert_close("centre x", body.local_center().x, center.x);
    assert_close("centre y", body.local_center().y, center.y);
    assert_close("inertia", body.inertia(), inertia);
    // The origin stays where it was put; the centre of mass is found from it.
    assert_eq!(body.position(), position);
    assert!((body.center_of_mass() - (position + center)).norm() < 1e-6);
}

#[test]
fn a_box_with_a_circle_on_top_has_the_analytic_mass_centre_and_inertia() {
    // A 1 m box of density 1 and a 0.5 m circle of density 2 resting on it, turned a quarter.
    let mut world = World::new();
    let body = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .angle(0.5 * PI)
                .collider(
                    ColliderDef::new(Shape::circle(0.5))
                        .offset(vec2(0.0, 1.0))
                        .density(2.0),
                ),
        )
        .unwrap();
    let square = box_mass(1.0, 1.0, 1.0);
    let disc_mass = 2.0 * PI * 0.25;
    let (mass, center, inertia) = combine(&[
        (square.0, square.1, Vec2::zeros()),
        (disc_mass, 0.5 * disc_mass * 0.25, vec2(0.0, 1.0)),
    ]);
    let body = world.body(body).unwrap();
    assert_close("mass", body.mass(), mass);
    assert_close("centre y", body.local_center().y, center.y);
    assert_close("inertia", body.inertia(), inertia);
    // Turned a quarter, the circle is to the left of the box, and so is the centre of mass.
    assert!((body.center_of_mass() - vec2(-center.y, 0.0)).norm() < 1e-5);
    let circle = world.collider(body.colliders()[1]).unwrap();
    let carom::WorldShape::Circle { center: placed, .. } = circle.world_shape() else {
        unreachable!("a circle collider")
    };
    assert!((placed - vec2(-1.0, 0.0)).norm() < 1e-5);
}

/// A dumbbell: two balls 2 m apart on a thin bar, dropped flat onto a floor.
fn dumbbell(world: &mut World, height: Real) -> carom::BodyHandle {
    world
        .add_body(
            BodyDef::dynamic(Shape::rect(1.0, 0.05))
                .position(vec2(0.0, height))
                .collider(ColliderDef::new(Shape::circle(0.3)).offset(vec2(-1.0, 0.0)))
                .collider(ColliderDef::new(Shape::circle(0.3)).offset(vec2(1.0, 0.0))),
        )
        .unwrap()
}

#[test]
fn a_compound_body_lands_and_rests_on_its_colliders() {
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let bell = dumbbell(&mut world, 2.0);
    for _ in 0..180 {
        world.step(1.0 / 60.0).unwrap();
    }
    let body = world.body(bell).unwrap();
    // Resting on both balls: level, at the balls' radius, still.
    assert!(
        (body.position().y - 0.3).abs() < 0.01,
        "{}",
        body.position().y
    );
    assert!(body.angle().abs() < 1e-3, "{}", body.angle());
    assert!(body.linear_velocity().norm() < 0.01);
    // Two contacts, one per ball; the bar never reaches the floor.
    let touching: Vec<_> = world.contacts().filter(|c| c.is_touching()).collect();
    assert_eq!(touching.len(), 2);
    let balls = &body.colliders()[1..];
    assert!(touching.iter().all(|c| balls.contains(&c.collider_b())));
}

#[test]
fn colliders_of_one_body_never_collide_with_each_other() {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Gravity, false))
        .unwrap();
    let body = world
        .add_body(
            BodyDef::dynamic(Shape::rect(1.0, 1.0))
                .collider(ColliderDef::new(Shape::circle(0.8)).offset(vec2(0.5, 0.0))),
        )
        .unwrap();
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(world.contacts().len(), 0);
    let body = world.body(body).unwrap();
    assert_eq!(body.position(), Vec2::zeros());
    assert_eq!(body.angular_velocity(), 0.0);
}

#[test]
fn queries_find_a_body_by_any_of_its_colliders() {
    let mut world = World::new();
    let bell = dumbbell(&mut world, 0.0);
    assert_eq!(world.body_at(vec2(1.1, 0.1)), Some(bell));
    assert_eq!(world.body_at(vec2(0.0, 0.2)), None, "between bar and balls");
    let right_ball = world.body(bell).unwrap().colliders()[2];
    let hit = world
        .cast_ray(
            &Ray::new(vec2(5.0, 0.0), vec2(-10.0, 0.0)),
            QueryFilter::ALL,
        )
        .unwrap();
    assert_eq!((hit.body, hit.collider), (bell, right_ball));
    assert!((hit.point - vec2(1.3, 0.0)).norm() < 1e-5);
    assert!((hit.normal - vec2(1.0, 0.0)).norm() < 1e-5);
    // Moved, it is found where it went, at once.
    world
        .body_mut(bell)
        .unwrap()
        .set_position(vec2(0.0, 10.0))
        .unwrap();
    assert_eq!(world.body_at(vec2(1.1, 10.1)), Some(bell));
    assert_eq!(world.body_at(vec2(1.1, 0.1)), None);
}

#[test]
fn adding_and_removing_colliders_keeps_the_mass_right() {
    let mut world = World::new();
    let body = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)))
        .unwrap();
    let extra = world
        .add_collider(
            body,
            ColliderDef::new(Shape::rect(0.5, 0.5)).offset(vec2(1.0, 0.0)),
        )
        .unwrap();
    let two = world.body(body).unwrap();
    assert_close("mass of two", two.mass(), 2.0);
    assert_close("centre of two", two.local_center().x, 0.5);
    assert_close("inertia of two", two.inertia(), 2.0 / 6.0 + 2.0 * 0.25);
    world.collider_mut(extra).unwrap().set_density(3.0).unwrap();
    assert_close("heavier", world.body(body).unwrap().mass(), 4.0);
    // A dynamic body may not lose all its mass.
    let first = world.body(body).unwrap().colliders()[0];
    world.collider_mut(first).unwrap().set_density(0.0).unwrap();
    assert!(world.collider_mut(extra).unwrap().set_density(0.0).is_err());
    assert_close("unchanged", world.body(body).unwrap().mass(), 3.0);
    world.collider_mut(first).unwrap().set_density(1.0).unwrap();
    let removed = world.remove_collider(extra).unwrap();
    assert_eq!(removed.body(), body);
    let one = world.body(body).unwrap();
    assert_close("mass of one", one.mass(), 1.0);
    assert_eq!(one.local_center(), Vec2::zeros());
    assert!(world.collider(extra).is_none());
    assert!(matches!(
        world.remove_collider(first),
        Err(CaromError::NoCollider)
    ));
}

#[test]
fn a_kind_change_rebuilds_the_mass() {
    let mut world = World::new();
    let body = world
        .add_body(
            BodyDef::static_body(Shape::rect(0.5, 0.5))
                .collider(ColliderDef::new(Shape::circle(0.5)).offset(vec2(2.0, 0.0))),
        )
        .unwrap();
    assert_eq!(world.body(body).unwrap().mass(), 0.0);
    assert_eq!(world.body(body).unwrap().local_center(), Vec2::zeros());
    world
        .body_mut(body)
        .unwrap()
        .set_kind(BodyKind::Dynamic)
        .unwrap();
    let moving = world.body(body).unwrap();
    let disc = PI * 0.25;
    assert_close("mass", moving.mass(), 1.0 + disc);
    assert_close("centre", moving.local_center().x, 2.0 * disc / (1.0 + disc));
    // Dynamic now, it falls.
    world.step(1.0 / 60.0).unwrap();
    assert!(world.body(body).unwrap().linear_velocity().y < 0.0);
}

#[test]
fn removing_a_body_keeps_the_others_colliders_with_them() {
    // The last body moves into the removed one's place; its colliders must follow it.
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Gravity, false))
        .unwrap();
    let first = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)))
        .unwrap();
    let last = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.5))
                .position(vec2(5.0, 0.0))
                .linear_velocity(vec2(1.0, 0.0)),
        )
        .unwrap();
    world.remove_body(first).unwrap();
    for _ in 0..60 {
        world.step(1.0 / 60.0).unwrap();
    }
    let moved = world.body(last).unwrap();
    assert!((moved.position().x - 6.0).abs() < 1e-3);
    let collider = world.collider(moved.colliders()[0]).unwrap();
    assert!((collider.aabb().center() - moved.position()).norm() < 1e-5);
}

#[test]
fn a_collider_added_to_a_spinning_body_keeps_every_point_moving_as_it_was() {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Gravity, false))
        .unwrap();
    let body = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).angular_velocity(2.0))
        .unwrap();
    let probe = vec2(0.3, -0.2);
    let before = world.body(body).unwrap().velocity_at(probe);
    world
        .add_collider(
            body,
            ColliderDef::new(Shape::rect(0.5, 0.5)).offset(vec2(1.0, 0.0)),
        )
        .unwrap();
    let spinning = world.body(body).unwrap();
    assert!((spinning.local_center().x - 0.5).abs() < 1e-6);
    // The origin, no longer the centre of mass, still stands still; the probe keeps its speed.
    assert!(spinning.velocity_at(Vec2::zeros()).norm() < 1e-6);
    assert!((spinning.velocity_at(probe) - before).norm() < 1e-6);
}

#[test]
fn a_friction_changed_on_a_collider_applies_to_its_contacts() {
    // A box sliding on a floor (friction 0.6 both): once the floor is made frictionless, the
    // box keeps its speed.
    let mut world = World::new();
    let floor = world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let slider = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(0.0, 0.5))
                .linear_velocity(vec2(3.0, 0.0)),
        )
        .unwrap();
    for _ in 0..5 {
        world.step(1.0 / 60.0).unwrap();
    }
    let floor_collider = world.body(floor).unwrap().colliders()[0];
    world
        .collider_mut(floor_collider)
        .unwrap()
        .set_friction(0.0)
        .unwrap();
    // Its contacts take it at once (an edit between steps is seen by the next one), and a
    // restitution change likewise.
    assert!(world.contacts().len() > 0);
    assert!(world.contacts().all(|c| c.friction() == 0.0));
    world
        .collider_mut(floor_collider)
        .unwrap()
        .set_restitution(0.25)
        .unwrap();
    assert!(world.contacts().all(|c| c.restitution() == 0.25));
    world
        .collider_mut(floor_collider)
        .unwrap()
        .set_restitution(0.0)
        .unwrap();
    let before = world.body(slider).unwrap().linear_velocity().x;
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    let after = world.body(slider).unwrap().linear_velocity().x;
    assert!((after - before).abs() < 1e-3, "{before} -> {after}");
    assert!(world.contacts().all(|c| c.friction() == 0.0));
}
