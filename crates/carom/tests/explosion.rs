//! Explosions through the public interface: who is pushed, which way, and by how much.

use carom::{
    BodyDef, BodyHandle, CaromError, CollisionFilter, ExplosionDef, Real, Shape, Vec2, World,
    WorldSettings, vec2,
};

/// A world without gravity, so velocities are the explosion's alone.
fn still_world() -> World {
    World::with_settings(WorldSettings {
        gravity: vec2(0.0, 0.0),
        ..WorldSettings::default()
    })
    .unwrap()
}

fn add(world: &mut World, def: BodyDef) -> BodyHandle {
    world.add_body(def).unwrap()
}

fn velocity(world: &World, body: BodyHandle) -> (Vec2, Real) {
    let b = world.body(body).unwrap();
    (b.linear_velocity(), b.angular_velocity())
}

#[test]
fn circles_on_a_ring_fly_straight_out_by_impulse_per_length_times_their_width() {
    let mut world = still_world();
    let (r, ring) = (0.5, 2.0);
    let balls: Vec<(BodyHandle, Vec2)> = (0..6)
        .map(|i| {
            let angle = i as Real * carom::consts::TAU / 6.0;
            let out = vec2(angle.cos(), angle.sin());
            let ball = add(
                &mut world,
                BodyDef::dynamic(Shape::circle(r)).position(out * ring),
            );
            (ball, out)
        })
        .collect();
    let pushed = world
        .explode(&ExplosionDef::new(vec2(0.0, 0.0), 3.0, 4.0))
        .unwrap();
    assert_eq!(pushed, 6);
    for (ball, out) in balls {
        let mass = world.body(ball).unwrap().mass();
        let (v, w) = velocity(&world, ball);
        // The width a circle shows is its diameter.
        let expected = out * (4.0 * 2.0 * r / mass);
        assert!((v - expected).norm() < 1e-5, "{v:?} against {expected:?}");
        assert!(
            w.abs() < 1e-5,
            "a push through the centre does not spin: {w}"
        );
    }
}

#[test]
fn a_box_is_pushed_by_the_width_it_shows_at_its_nearest_point() {
    let mut world = still_world();
    // Equal boxes, 1 x 2 m, nearest points 2.5 m away: one shows its 2 m side to the blast,
    // the other its 1 m end.
    let broadside = add(
        &mut world,
        BodyDef::dynamic(Shape::rect(0.5, 1.0)).position(vec2(3.0, 0.0)),
    );
    let end_on = add(
        &mut world,
        BodyDef::dynamic(Shape::rect(1.0, 0.5)).position(vec2(-3.5, 0.0)),
    );
    world
        .explode(&ExplosionDef::new(vec2(0.0, 0.0), 10.0, 1.0))
        .unwrap();
    let mass = world.body(broadside).unwrap().mass();
    assert!((velocity(&world, broadside).0 - vec2(2.0 / mass, 0.0)).norm() < 1e-5);
    assert!((velocity(&world, end_on).0 - vec2(-1.0 / mass, 0.0)).norm() < 1e-5);
    assert!(velocity(&world, broadside).1.abs() < 1e-6);

    // Off the line to its centre: a 1 x 4 box, nearest point (2.5, -4) below its centre
    // (3, -3), takes 4 m of push there, so it spins as well as moves.
    let mut world = still_world();
    let off_centre = add(
        &mut world,
        BodyDef::dynamic(Shape::rect(0.5, 2.0)).position(vec2(3.0, -3.0)),
    );
    world
        .explode(&ExplosionDef::new(vec2(0.0, -4.0), 10.0, 1.0))
        .unwrap();
    let body = world.body(off_centre).unwrap();
    let (v, w) = velocity(&world, off_centre);
    let impulse = vec2(4.0, 0.0);
    let r = vec2(2.5, -4.0) - vec2(3.0, -3.0);
    let expected_w = (r.x * impulse.y - r.y * impulse.x) / body.inertia();
    assert!((v - impulse / body.mass()).norm() < 1e-5, "{v:?}");
    assert!((w - expected_w).abs() < 1e-5, "{w} against {expected_w}");
}

#[test]
fn the_push_fades_over_the_falloff_and_stops_beyond_it() {
    let mut world = still_world();
    let r = 0.5;
    // Surfaces 1, 3, 4 and 6 m from the centre; radius 2, falloff 2.
    let balls: Vec<BodyHandle> = [1.5, 3.5, 4.5, 6.5]
        .into_iter()
        .map(|x| {
            add(
                &mut world,
                BodyDef::dynamic(Shape::circle(r)).position(vec2(x, 0.0)),
            )
        })
        .collect();
    let pushed = world
        .explode(&ExplosionDef::new(vec2(0.0, 0.0), 2.0, 1.0).falloff(2.0))
        .unwrap();
    assert_eq!(pushed, 3, "the farthest is out of reach");
    let full = 2.0 * r / world.body(balls[0]).unwrap().mass();
    let speeds: Vec<Real> = balls.iter().map(|&b| velocity(&world, b).0.x).collect();
    for (speed, scale) in speeds.iter().zip([1.0, 0.5, 0.0, 0.0]) {
        assert!((speed - full * scale).abs() < 1e-5, "{speeds:?}");
    }
}

#[test]
fn only_dynamic_bodies_of_the_masked_categories_are_pushed_and_sleepers_wake() {
    let mut world = World::new();
    let floor = add(
        &mut world,
        BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)),
    );
    let sleeper = add(
        &mut world,
        BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(1.0, 0.5)),
    );
    let debris = CollisionFilter {
        category: 4,
        ..CollisionFilter::DEFAULT
    };
    let other = add(
        &mut world,
        BodyDef::dynamic(Shape::rect(0.5, 0.5))
            .position(vec2(-1.0, 0.5))
            .filter(debris),
    );
    let platform = add(
        &mut world,
        BodyDef::kinematic(Shape::rect(1.0, 0.1)).position(vec2(0.0, 3.0)),
    );
    for _ in 0..200 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert!(world.body(sleeper).unwrap().is_sleeping());
    let pushed = world
        .explode(&ExplosionDef::new(vec2(0.0, 0.5), 2.0, 5.0).mask(1))
        .unwrap();
    assert_eq!(pushed, 1);
    let body = world.body(sleeper).unwrap();
    assert!(!body.is_sleeping() && body.linear_velocity().x > 1.0);
    for still in [floor, other, platform] {
        assert_eq!(velocity(&world, still), (vec2(0.0, 0.0), 0.0));
    }
    // With every category, the other box goes the other way; a body that collides with
    // nothing (mask 0) is still in the blast.
    let ghost = add(
        &mut world,
        BodyDef::dynamic(Shape::circle(0.25))
            .position(vec2(0.0, 2.0))
            .filter(CollisionFilter {
                mask: 0,
                ..CollisionFilter::DEFAULT
            }),
    );
    world
        .explode(&ExplosionDef::new(vec2(0.0, 0.5), 2.0, 5.0))
        .unwrap();
    assert!(velocity(&world, other).0.x < -1.0);
    assert!(velocity(&world, ghost).0.y > 1.0);
}

#[test]
fn a_centre_inside_a_body_pushes_it_without_a_nan_and_bad_explosions_are_errors() {
    let mut world = still_world();
    let crate_box = add(&mut world, BodyDef::dynamic(Shape::rect(0.5, 0.5)));
    // At its very centre: no direction to push in, so a fixed one.
    assert_eq!(
        world
            .explode(&ExplosionDef::new(vec2(0.0, 0.0), 1.0, 1.0))
            .unwrap(),
        1
    );
    let (v, w) = velocity(&world, crate_box);
    assert!(v.norm() > 0.0 && v.x.is_finite() && v.y.is_finite() && w.is_finite());
    let before = velocity(&world, crate_box);
    for bad in [
        ExplosionDef::new(vec2(Real::NAN, 0.0), 1.0, 1.0),
        ExplosionDef::new(vec2(2e6, 0.0), 3e6, 1.0),
        ExplosionDef::new(vec2(0.0, 0.0), -1.0, 1.0),
        ExplosionDef::new(vec2(0.0, 0.0), 1.0, Real::INFINITY),
        ExplosionDef::new(vec2(0.0, 0.0), 1.0, 1.0).falloff(Real::NAN),
    ] {
        let error = world.explode(&bad).unwrap_err();
        assert!(
            matches!(
                error,
                CaromError::NonFinite { .. } | CaromError::OutOfRange { .. }
            ),
            "{error}"
        );
    }
    assert_eq!(
        velocity(&world, crate_box),
        before,
        "a refused explosion pushes nothing"
    );
}
