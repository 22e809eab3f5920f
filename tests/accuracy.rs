//! Accuracy against analytic answers: what the integrator and the force model must get right.

use carom::{BodyDef, DragModel, Real, Shape, Vec2, World, WorldSettings, vec2};

const DT: Real = 1.0 / 60.0;

fn world_with(gravity: Vec2, drag: DragModel) -> World {
    World::with_settings(WorldSettings {
        gravity,
        drag,
        ..WorldSettings::default()
    })
    .unwrap()
}

#[test]
fn free_fall_matches_semi_implicit_euler_exactly_and_physics_closely() {
    let mut world = World::new();
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 100.0)))
        .unwrap();
    let steps = 180;
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    let body = world.body(ball).unwrap();
    // The default solver integrates in substeps of h = dt / substeps.
    let substeps = world.solver().substeps as f64;
    let (g, t) = (10.0_f64, steps as f64 * DT as f64);
    let (n, h) = (steps as f64 * substeps, DT as f64 / substeps);
    // Semi-implicit Euler over n substeps: v_n = -g n h, y_n = y0 - g h² n (n + 1) / 2.
    let expected_y = 100.0 - g * h * h * n * (n + 1.0) / 2.0;
    assert!((body.position().y as f64 - expected_y).abs() < 1e-3);
    assert!((body.linear_velocity().y as f64 + g * t).abs() < 1e-3);
    // And within one substep's worth of the exact parabola y0 - g t² / 2.
    let exact_y = 100.0 - 0.5 * g * t * t;
    assert!((body.position().y as f64 - exact_y).abs() <= g * t * h / 2.0 + 1e-3);
    assert_eq!(body.position().x, 0.0);
}

#[test]
fn projectile_range_converges_to_the_analytic_range() {
    // Launch at 45 degrees, 20 m/s, g = 10: range v² / g = 40 m, flight time 2 v sin / g.
    let range_with = |dt: Real| {
        let mut world = World::new();
        let speed = 20.0 / std::f32::consts::SQRT_2;
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.1)).linear_velocity(vec2(speed, speed)))
            .unwrap();
        let mut last = Vec2::zeros();
        loop {
            world.step(dt).unwrap();
            let p = world.body(ball).unwrap().position();
            if p.y < 0.0 {
                // Interpolate the crossing of y = 0 between the last two positions.
                let s = last.y / (last.y - p.y);
                return last.x + s * (p.x - last.x);
            }
            last = p;
        }
    };
    let coarse = (range_with(1.0 / 30.0) - 40.0).abs();
    let fine = (range_with(1.0 / 240.0) - 40.0).abs();
    assert!(coarse < 0.5, "coarse error {coarse}");
    assert!(fine < 0.1, "fine error {fine}");
    // First order: 8x smaller step, roughly 8x smaller error.
    assert!(fine < coarse / 4.0, "{fine} vs {coarse}");
}

#[test]
fn exponential_damping_follows_its_closed_form() {
    let mut world = world_with(Vec2::zeros(), DragModel::Exponential);
    let c = 0.8;
    let ball = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.5))
                .linear_velocity(vec2(6.0, -3.0))
                .angular_velocity(4.0)
                .damping(c, 2.0 * c),
        )
        .unwrap();
    let steps = 120;
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    let body = world.body(ball).unwrap();
    // Damping acts once per substep of h = dt / substeps.
    let substeps = world.solver().substeps as i32;
    let h = DT as f64 / substeps as f64;
    let linear_factor = (1.0 / (1.0 + h * c as f64)).powi(steps * substeps);
    let angular_factor = (1.0 / (1.0 + h * 2.0 * c as f64)).powi(steps * substeps);
    let v = body.linear_velocity();
    assert!((v.x as f64 - 6.0 * linear_factor).abs() < 1e-4);
    assert!((v.y as f64 + 3.0 * linear_factor).abs() < 1e-4);
    assert!((body.angular_velocity() as f64 - 4.0 * angular_factor).abs() < 1e-4);
    // Close to the continuous e^(-c t) too.
    let continuous = 6.0 * (-(c as f64) * 2.0).exp();
    assert!((v.x as f64 - continuous).abs() < 0.05);
}

#[test]
fn tutorial_drag_decelerates_linearly_then_settles() {
    let mut world = world_with(Vec2::zeros(), DragModel::Tutorial);
    let drag = 3.0;
    let ball = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.5))
                .linear_velocity(vec2(0.0, 10.0))
                .damping(drag, 0.0),
        )
        .unwrap();
    // Above 1 m/s the loss is a constant drag * dt per step.
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let vy = world.body(ball).unwrap().linear_velocity().y;
    assert!((vy - (10.0 - drag)).abs() < 1e-4, "{vy}");
    // Below it, proportional: it decays but never reverses.
    for _ in 0..600 {
        world.step(DT).unwrap();
    }
    let v = world.body(ball).unwrap().linear_velocity();
    assert!(v.y >= 0.0 && v.y < 1e-3, "{v:?}");
}

#[test]
fn torque_spins_up_by_alpha_equals_tau_over_inertia() {
    let mut world = world_with(Vec2::zeros(), DragModel::Exponential);
    let wheel = world
        .add_body(BodyDef::dynamic(Shape::circle(2.0)).density(0.5))
        .unwrap();
    let inertia = world.body(wheel).unwrap().inertia();
    for _ in 0..60 {
        let mut body = world.body_mut(wheel).unwrap();
        body.apply_torque(3.0).unwrap();
        // A force couple adds torque but no net force.
        body.apply_force(vec2(0.0, 1.0), vec2(2.0, 0.0)).unwrap();
        body.apply_force(vec2(0.0, -1.0), vec2(-2.0, 0.0)).unwrap();
        world.step(DT).unwrap();
    }
    let body = world.body(wheel).unwrap();
    let expected = (3.0 + 4.0) / inertia * 60.0 * DT;
    assert!((body.angular_velocity() - expected).abs() < 1e-4 * expected);
    assert!(body.linear_velocity().norm() < 1e-6);
    assert!(body.position().norm() < 1e-6);
    // Forces were cleared after each step: a free step changes nothing.
    let spin = body.angular_velocity();
    world.step(DT).unwrap();
    assert_eq!(world.body(wheel).unwrap().angular_velocity(), spin);
}

#[test]
fn impulses_conserve_momentum_between_two_bodies() {
    let mut world = world_with(Vec2::zeros(), DragModel::Exponential);
    let a = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.25)).position(vec2(-1.0, 0.0)))
        .unwrap();
    let b = world
        .add_body(
            BodyDef::dynamic(Shape::regular(5, 0.7).unwrap())
                .position(vec2(1.0, 0.5))
                .density(3.0),
        )
        .unwrap();
    // Equal and opposite impulses at one contact point.
    let (point, impulse) = (vec2(0.1, 0.3), vec2(2.0, -1.5));
    world
        .body_mut(a)
        .unwrap()
        .apply_impulse(-impulse, point)
        .unwrap();
    world
        .body_mut(b)
        .unwrap()
        .apply_impulse(impulse, point)
        .unwrap();
    let (ba, bb) = (world.body(a).unwrap(), world.body(b).unwrap());
    let momentum = ba.linear_velocity() * ba.mass() + bb.linear_velocity() * bb.mass();
    assert!(momentum.norm() < 1e-5);
    // Angular momentum about the contact point is conserved too.
    let angular = |body: &carom::Body| {
        body.inertia() * body.angular_velocity()
            + carom::testing::cross(
                body.position() - point,
                body.linear_velocity() * body.mass(),
            )
    };
    assert!((angular(ba) + angular(bb)).abs() < 1e-5);
    // Then they fly apart with constant momentum (no gravity, no drag).
    for _ in 0..100 {
        world.step(DT).unwrap();
    }
    let (ba, bb) = (world.body(a).unwrap(), world.body(b).unwrap());
    let momentum = ba.linear_velocity() * ba.mass() + bb.linear_velocity() * bb.mass();
    assert!(momentum.norm() < 1e-5);
}

#[test]
fn rotation_integrates_without_drift_over_many_turns() {
    let mut world = world_with(Vec2::zeros(), DragModel::Exponential);
    let spinner = world
        .add_body(BodyDef::dynamic(Shape::rect(1.0, 0.2)).angular_velocity(10.0))
        .unwrap();
    let steps = 6000; // 100 s, about 159 turns
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    let body = world.body(spinner).unwrap();
    let total = 10.0_f64 * steps as f64 * DT as f64;
    let expected =
        (total + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
    assert!(
        (body.angle() as f64 - expected).abs() < 2e-3,
        "{}",
        body.angle()
    );
    // The rotation stays a rotation: the box keeps its shape.
    let carom::WorldShape::Polygon { vertices, .. } = carom_tests::world_shape(&world, spinner)
    else {
        unreachable!("a rectangle is a polygon")
    };
    assert!(((vertices[1] - vertices[0]).norm() - 2.0).abs() < 1e-4);
    assert!(((vertices[2] - vertices[1]).norm() - 0.4).abs() < 1e-4);
}
