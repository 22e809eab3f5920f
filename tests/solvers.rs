//! The contact solvers against numbers: resting contact, elastic collision, friction on an
//! incline, a tall stack, what warm starting buys, and the tutorial's bias.

use carom::{
    BodyDef, BodyHandle, Real, Shape, SolverKind, SolverParams, Vec2, World, WorldSettings, vec2,
};

const DT: Real = 1.0 / 60.0;

fn world(params: SolverParams, gravity: Vec2) -> World {
    World::with_settings(WorldSettings {
        gravity,
        solver: params,
        ..WorldSettings::default()
    })
    .unwrap()
}

/// A ground whose top surface is y = 0.
fn add_ground(world: &mut World) -> BodyHandle {
    world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap()
}

/// How far a box of half-height `half` centred at `y` dips below y = 0.
fn penetration(world: &World, body: BodyHandle) -> Real {
    let aabb = world.body(body).unwrap().aabb();
    (-aabb.min.y).max(0.0)
}

#[test]
fn a_box_rests_on_the_ground() {
    for kind in [SolverKind::SequentialImpulse, SolverKind::SoftStep] {
        let mut world = world(SolverParams::for_kind(kind), vec2(0.0, -10.0));
        add_ground(&mut world);
        let crate_box = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5)))
            .unwrap();
        for _ in 0..120 {
            world.step(DT).unwrap();
        }
        let body = world.body(crate_box).unwrap();
        let depth = penetration(&world, crate_box);
        let speed = body.linear_velocity().norm();
        assert!(depth <= 0.005 + 1e-3, "{kind:?}: penetration {depth}");
        assert!(speed < 1e-3, "{kind:?}: speed {speed}");
        assert!(
            body.angle().abs() < 1e-3,
            "{kind:?}: angle {}",
            body.angle()
        );
    }
}

#[test]
fn equal_circles_swap_velocities_in_an_elastic_head_on_collision() {
    for kind in [SolverKind::SequentialImpulse, SolverKind::SoftStep] {
        let mut world = world(SolverParams::for_kind(kind), Vec2::zeros());
        let ball = |x: Real, vx: Real| {
            BodyDef::dynamic(Shape::circle(0.5))
                .position(vec2(x, 0.0))
                .linear_velocity(vec2(vx, 0.0))
                .restitution(1.0)
                .friction(0.0)
        };
        let a = world.add_body(ball(-2.0, 4.0)).unwrap();
        let b = world.add_body(ball(2.0, -4.0)).unwrap();
        let mass = world.body(a).unwrap().mass() as f64;
        let energy = |w: &World| {
            [a, b]
                .iter()
                .map(|h| w.body(*h).unwrap().kinetic_energy() as f64)
                .sum::<f64>()
        };
        let momentum = |w: &World| {
            [a, b]
                .iter()
                .map(|h| w.body(*h).unwrap().linear_velocity().x as f64 * mass)
                .sum::<f64>()
        };
        let (energy_before, scale) = (energy(&world), 4.0 * mass);
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let (va, vb) = (
            world.body(a).unwrap().linear_velocity(),
            world.body(b).unwrap().linear_velocity(),
        );
        assert!(
            (va.x + 4.0).abs() < 0.05 && (vb.x - 4.0).abs() < 0.05,
            "{kind:?}: {va:?} {vb:?}"
        );
        let momentum_error = momentum(&world).abs() / scale;
        assert!(
            momentum_error < 1e-9,
            "{kind:?}: momentum error {momentum_error}"
        );
        let energy_error = (energy(&world) - energy_before).abs() / energy_before;
        assert!(energy_error < 0.01, "{kind:?}: energy error {energy_error}");
    }
}

/// Puts a box at rest on a static slope of `angle` with friction `mu` for both and reports how
/// far it slid along the slope in two seconds.
fn slide_on_incline(kind: SolverKind, mu: Real, angle: Real) -> Real {
    let mut world = world(SolverParams::for_kind(kind), vec2(0.0, -10.0));
    let (down_slope, up_normal) = (
        vec2(-angle.cos(), -angle.sin()),
        vec2(-angle.sin(), angle.cos()),
    );
    world
        .add_body(
            BodyDef::static_body(Shape::rect(20.0, 0.5))
                .position(-up_normal * 0.5)
                .angle(angle)
                .friction(mu),
        )
        .unwrap();
    let start = up_normal * 0.25;
    let crate_box = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.25, 0.25))
                .position(start)
                .angle(angle)
                .friction(mu),
        )
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    (world.body(crate_box).unwrap().position() - start).dot(&down_slope)
}

#[test]
fn friction_holds_below_the_critical_angle_and_lets_go_above() {
    let mu: Real = 0.5;
    for kind in [SolverKind::SequentialImpulse, SolverKind::SoftStep] {
        let holds = slide_on_incline(kind, mu, (0.9 * mu).atan());
        let slides = slide_on_incline(kind, mu, (1.1 * mu).atan());
        assert!(
            holds.abs() < 0.01,
            "{kind:?}: crept {holds} m at tan = 0.9 mu"
        );
        // Sliding: a = g (sin - mu cos) = 0.41 m/s² at 1.1 mu, so about 0.8 m in 2 s.
        assert!(
            slides > 0.5,
            "{kind:?}: slid only {slides} m at tan = 1.1 mu"
        );
    }
}

/// A column of `count` 1 m boxes (friction 0.6) on the ground; returns the world and the top box.
fn stack(params: SolverParams, count: usize) -> (World, BodyHandle) {
    let mut world = world(params, vec2(0.0, -10.0));
    add_ground(&mut world);
    let mut top = None;
    for i in 0..count {
        top = Some(
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(0.0, 0.5 + i as Real))
                        .friction(0.6),
                )
                .unwrap(),
        );
    }
    (world, top.unwrap())
}

/// How far the top box of a stack moved from where it started over `seconds`.
fn stack_drift(params: SolverParams, count: usize, seconds: Real) -> Real {
    let (mut world, top) = stack(params, count);
    let start = world.body(top).unwrap().position();
    for _ in 0..(seconds / DT) as usize {
        world.step(DT).unwrap();
    }
    let end = world.body(top).unwrap().position();
    assert!(end.iter().all(|x| x.is_finite()));
    (end - start).norm()
}

#[test]
fn a_stack_of_ten_stands_for_ten_seconds() {
    let drift = stack_drift(SolverParams::default(), 10, 10.0);
    assert!(drift < 0.05, "top box moved {drift} m");
}

#[test]
fn a_stack_of_twenty_stands_at_the_default_and_at_stiffer_contacts() {
    // The contacts give a little under the column's weight (13 cm over 20 boxes at 30 Hz),
    // and the column stands on them, as long as contacts keep their lever arms while a pair
    // barely moves (recycled manifolds keep their anchors, as Box2D's do).
    for hertz in [30.0, 60.0] {
        let params = SolverParams {
            contact_hertz: hertz,
            ..SolverParams::default()
        };
        // Drift is measured once the column has settled on its contacts (the first second).
        let (mut world, top) = stack(params, 20);
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let settled = world.body(top).unwrap().position();
        for _ in 0..540 {
            world.step(DT).unwrap();
        }
        let drift = (world.body(top).unwrap().position() - settled).norm();
        assert!(
            drift < 0.05,
            "{hertz} Hz: top box moved {drift} m after settling"
        );
    }
}

#[test]
fn warm_starting_cuts_the_iterations_a_stack_needs() {
    // The fewest sequential-impulse iterations that keep a 10-box stack's top within 5 cm for
    // 5 s, with and without warm starting.
    let needed = |warm_starting: bool| {
        (1..=64).find(|&iterations| {
            let params = SolverParams {
                iterations: Some(iterations),
                warm_starting,
                ..SolverParams::for_kind(SolverKind::SequentialImpulse)
            };
            stack_drift(params, 10, 5.0) < 0.05
        })
    };
    let (warm, cold) = (needed(true), needed(false));
    println!("iterations a 10-box stack needs: warm {warm:?}, cold {cold:?} (None: more than 64)");
    let warm = warm.expect("warm starting never held the stack");
    assert!(
        cold.is_none_or(|cold| warm * 2 <= cold),
        "warm {warm} vs cold {cold:?}"
    );
}

#[test]
fn tutorial_impulse_sinks_without_bias_and_holds_with_it() {
    // Depth of a resting box after 5 s and after 10 s.
    let sink = |baumgarte: Real| {
        let params = SolverParams {
            baumgarte,
            ..SolverParams::for_kind(SolverKind::TutorialImpulse)
        };
        let mut world = world(params, vec2(0.0, -10.0));
        add_ground(&mut world);
        let crate_box = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5)))
            .unwrap();
        let mut depths = [0.0; 2];
        for depth in &mut depths {
            for _ in 0..300 {
                world.step(DT).unwrap();
            }
            *depth = penetration(&world, crate_box);
        }
        depths
    };
    // Without bias nothing undoes the g dt² that gravity sinks it each step: it keeps going.
    let [five, ten] = sink(0.0);
    assert!(
        five > 0.05 && ten > five + 0.05,
        "without bias: {five} then {ten}"
    );
    // With bias it settles where the bias balances gravity, 0.01 + g dt² / 0.2 = 2.4 cm.
    let [five, ten] = sink(0.2);
    let settled = 0.01 + 10.0 * DT * DT / 0.2;
    assert!(
        (five - settled).abs() < 2e-3 && (ten - five).abs() < 1e-4,
        "with bias: {five} then {ten}"
    );
}

#[test]
fn push_out_separates_but_rests_worse_than_impulses() {
    let rest = |params: SolverParams| {
        let mut world = world(params, vec2(0.0, -10.0));
        add_ground(&mut world);
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 3.0)))
            .unwrap();
        for _ in 0..180 {
            world.step(DT).unwrap();
        }
        let body = world.body(ball).unwrap();
        (penetration(&world, ball), body.position().y)
    };
    let push = SolverParams {
        impulse_resolution: false,
        ..SolverParams::default()
    };
    assert_eq!(push.effective_kind(), SolverKind::PushOut);
    let (depth, height) = rest(push);
    // It lands and stays on the ground, never through it.
    assert!(
        depth < 0.02 && (height - 0.5).abs() < 0.02,
        "{depth} {height}"
    );
}

#[test]
fn every_solver_survives_a_falling_pile() {
    for kind in SolverKind::ALL {
        let mut world = world(SolverParams::for_kind(kind), vec2(0.0, -10.0));
        add_ground(&mut world);
        for i in 0..60 {
            let shape = if i % 2 == 0 {
                Shape::circle(0.3)
            } else {
                Shape::regular(3 + i % 5, 0.4).unwrap()
            };
            world
                .add_body(
                    BodyDef::dynamic(shape)
                        .position(vec2(
                            (i % 6) as Real * 0.9 - 2.25,
                            0.5 + (i / 6) as Real * 0.9,
                        ))
                        .density(if i % 7 == 0 { 50.0 } else { 1.0 }),
                )
                .unwrap();
        }
        for _ in 0..240 {
            world.step(DT).unwrap();
        }
        for body in world.bodies().filter(|b| b.is_dynamic()) {
            assert!(body.position().iter().all(|x| x.is_finite()), "{kind:?}");
            // Falling 5 m gives 10 m/s; anything much faster is energy from nowhere.
            assert!(body.linear_velocity().norm() < 15.0, "{kind:?} exploded");
            // Push-out splits each push by inverse mass, pair by pair, so a light body squeezed
            // under a heavy one is driven into the ground: the weakness it is there to show.
            if kind != SolverKind::PushOut {
                assert!(
                    body.position().y > 0.0,
                    "{kind:?}: a body fell through the ground"
                );
            }
        }
    }
}

#[test]
fn guard_rails_cap_speed_and_spin() {
    let mut world = world(SolverParams::default(), Vec2::zeros());
    let rocket = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.1))
                .linear_velocity(vec2(1.0e6, 0.0))
                .angular_velocity(1.0e6),
        )
        .unwrap();
    world.step(DT).unwrap();
    let body = world.body(rocket).unwrap();
    assert!(body.linear_velocity().norm() <= 400.0 + 1e-3);
    // At most an eighth of a turn per step.
    let max_spin = 0.25 * std::f32::consts::PI / DT;
    assert!(body.angular_velocity().abs() <= max_spin * 1.0001);
}

#[test]
fn the_spin_cap_holds_per_step_whatever_the_substeps() {
    // Capped per substep, 8 substeps would let a body turn a whole turn in a step, and a turn
    // rebuilt from the step's start and end rotations would come out as none at all.
    for substeps in [1, 4, 8, 16] {
        let params = SolverParams {
            substeps,
            ..SolverParams::default()
        };
        let mut world = world(params, Vec2::zeros());
        let spinner = world
            .add_body(BodyDef::dynamic(Shape::rect(1.0, 0.1)).angular_velocity(1.0e3))
            .unwrap();
        world.step(DT).unwrap();
        let turned = world.body(spinner).unwrap().angle();
        let quarter = 0.25 * std::f32::consts::PI;
        assert!(
            (turned - quarter).abs() < 1e-4,
            "{substeps} substeps: turned {turned} rad in a step"
        );
    }
}

/// A 20 m box (400 kg) dropped from `drop` m onto two 1 m boxes standing 10 m apart, under
/// `gravity`, with shock propagation on or off; returns the world and the big box.
fn heavy_on_light(shock_propagation: bool, gravity: Vec2, drop: Real) -> (World, BodyHandle) {
    let params = SolverParams {
        shock_propagation,
        ..SolverParams::for_kind(SolverKind::SoftStep)
    };
    let mut world = world(params, gravity);
    add_ground(&mut world);
    for x in [-5.0, 5.0] {
        world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, 0.5)))
            .unwrap();
    }
    let big = world
        .add_body(BodyDef::dynamic(Shape::rect(10.0, 10.0)).position(vec2(0.0, 11.0 + drop)))
        .unwrap();
    (world, big)
}

/// The deepest overlap between the big box and what it stands on.
fn deepest_under(world: &World, big: BodyHandle) -> Real {
    world
        .contacts()
        .filter(|c| c.body_a() == big || c.body_b() == big)
        .flat_map(|c| c.manifold().points().iter().map(|p| -p.separation))
        .fold(0.0, Real::max)
}

#[test]
fn shock_propagation_stops_a_heavy_box_on_light_ones_and_reports_its_weight() {
    let gravity = vec2(0.0, -10.0);
    let (mut plain, plain_big) = heavy_on_light(false, gravity, 1.0);
    let (mut shocked, big) = heavy_on_light(true, gravity, 1.0);
    for _ in 0..180 {
        plain.step(DT).unwrap();
        shocked.step(DT).unwrap();
    }
    // Gauss-Seidel moves the light boxes' share of the load per pass: the big box sinks into them.
    let sunk = deepest_under(&plain, plain_big);
    assert!(
        sunk > 0.05,
        "without shock propagation the big box sinks only {sunk} m"
    );
    let held = deepest_under(&shocked, big);
    assert!(
        held < 0.01,
        "with shock propagation the big box still sinks {held} m"
    );
    // What the contacts under the big box report pushing over a step is its weight times the
    // step, though most of it came from the extra pass.
    let mass = shocked.body(big).unwrap().mass();
    let pushed: Real = shocked
        .contacts()
        .filter(|c| c.body_a() == big || c.body_b() == big)
        .map(|c| c.total_normal_impulse())
        .sum();
    let weight = mass * 10.0 * DT;
    assert!(
        (pushed / weight - 1.0).abs() < 0.02,
        "the contacts report {pushed} N s against a weight of {weight} N s"
    );
}

#[test]
fn shock_propagation_holds_a_heavy_box_by_friction_on_a_slope() {
    // Gravity 20° off the vertical: a 20° slope, with friction 0.6 holding (tan 20° ≈ 0.36).
    // The big box starts at rest on the small ones.
    let angle = (20.0 as Real).to_radians();
    let gravity = vec2(angle.sin(), -angle.cos()) * 10.0;
    let moved = |shock_propagation: bool| {
        let (mut world, big) = heavy_on_light(shock_propagation, gravity, 0.0);
        let start = world.body(big).unwrap().position();
        for _ in 0..240 {
            world.step(DT).unwrap();
        }
        (world.body(big).unwrap().position() - start).norm()
    };
    // The light boxes' share of friction lets it slide; held by them as by the ground, by the
    // friction its weight gives, it stays.
    let plain = moved(false);
    assert!(
        plain > 0.05,
        "without shock propagation the big box moves only {plain} m"
    );
    let held = moved(true);
    assert!(
        held < 0.01,
        "with shock propagation the big box moves {held} m in 4 s"
    );
}

#[test]
fn without_gravity_shock_propagation_changes_nothing() {
    let run = |shock_propagation: bool| {
        let params = SolverParams {
            shock_propagation,
            ..SolverParams::for_kind(SolverKind::SoftStep)
        };
        let mut world = world(params, Vec2::zeros());
        add_ground(&mut world);
        for i in 0..30 {
            let at = vec2((i % 6) as Real * 0.9 - 2.5, (i / 6) as Real * 0.9 + 0.45);
            let body = BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(at)
                .linear_velocity(vec2(0.0, -2.0));
            world.add_body(body).unwrap();
        }
        for _ in 0..120 {
            world.step(DT).unwrap();
        }
        world.state_hash()
    };
    assert_eq!(run(true), run(false));
}
