//! carom's joints and collision filters rebuilt in Box2D and Rapier behave as carom's do:
//! pendulums swing with carom's period, springs oscillate at their frequency, limits, motors
//! and welds hold, filtered bodies make no contacts, and what a peer cannot express is noted.

use std::collections::HashMap;
use std::path::PathBuf;

use carom::{
    BodyDef, BodyHandle, CollisionFilter, Effect, JointDef, Real, Shape, Vec2, World, vec2,
};
use carom_bench::{Box2dWorld, RapierWorld};

const DT: f32 = 1.0 / 60.0;

/// One body's pose after every step: position and angle.
type Track = Vec<([f32; 2], f32)>;

/// Steps the world and its copies `steps` times, tracking body `index` (carom's order) in
/// each: carom, Box2D, Rapier.
fn tracks(world: &mut World, index: usize, steps: usize) -> [Track; 3] {
    let mut box2d = Box2dWorld::from_carom(world).unwrap();
    let mut rapier = RapierWorld::from_carom(world, DT).unwrap();
    let (mut c, mut b, mut r) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..steps {
        world.step(DT).unwrap();
        box2d.step(DT).unwrap();
        rapier.step();
        let body = world.bodies().nth(index).unwrap();
        c.push(([body.position().x, body.position().y], body.angle()));
        b.push((box2d.position(index).unwrap(), box2d.angle(index).unwrap()));
        r.push((rapier.positions()[index], rapier.angle(index).unwrap()));
    }
    [c, b, r]
}

/// The mean period of a signal, s, from the times it crosses `level` upward (interpolated
/// between steps).
fn period(signal: impl Iterator<Item = f32>, level: f32) -> f32 {
    let values: Vec<f32> = signal.collect();
    let mut ups = Vec::new();
    for (i, w) in values.windows(2).enumerate() {
        if w[0] < level && w[1] >= level {
            let t = (level - w[0]) / (w[1] - w[0]);
            ups.push((i as f32 + 1.0 + t) * DT);
        }
    }
    assert!(ups.len() >= 3, "only {} upward crossings", ups.len());
    (ups[ups.len() - 1] - ups[0]) / (ups.len() - 1) as f32
}

/// Periods in the three engines agree with carom's within `tolerance` (a fraction).
fn same_periods(periods: [f32; 3], tolerance: f32, what: &str) {
    let [c, b, r] = periods;
    for (engine, p) in [("Box2D", b), ("Rapier", r)] {
        assert!(
            (p - c).abs() < tolerance * c,
            "{what}: carom's period {c} s, {engine}'s {p} s"
        );
    }
}

/// A static pivot at the origin and a 0.1 m ball hung 1 m from it at 10° from the vertical.
fn pendulum() -> (World, BodyHandle, BodyHandle, Vec2) {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let pivot = world
        .add_body(BodyDef::static_body(Shape::rect(0.1, 0.1)))
        .unwrap();
    let angle = 10.0_f32.to_radians();
    let at = vec2(angle.sin(), -angle.cos());
    let bob = world
        .add_body(BodyDef::dynamic(Shape::circle(0.1)).position(at))
        .unwrap();
    (world, pivot, bob, at)
}

#[test]
fn a_hinged_pendulum_swings_with_carom_s_period_in_both_peers() {
    let (mut world, pivot, bob, _) = pendulum();
    world
        .add_joint(JointDef::revolute(pivot, bob, Vec2::zeros()))
        .unwrap();
    let tracks = tracks(&mut world, 1, 600);
    let periods = tracks.map(|t| period(t.iter().map(|(p, _)| p[0]), 0.0));
    // A point mass on 1 m: 2π √(L/g) (1 + θ²/16) = 1.9914 s; the ball's own inertia adds a
    // little.
    assert!(
        (periods[0] - 1.99).abs() < 0.02,
        "carom's period {}",
        periods[0]
    );
    same_periods(periods, 0.01, "hinged pendulum");
}

#[test]
fn a_pendulum_on_a_rod_swings_with_carom_s_period_in_both_peers() {
    let (mut world, pivot, bob, at) = pendulum();
    world
        .add_joint(JointDef::distance(pivot, bob, Vec2::zeros(), at))
        .unwrap();
    let tracks = tracks(&mut world, 1, 600);
    let periods = tracks.map(|t| period(t.iter().map(|(p, _)| p[0]), 0.0));
    same_periods(periods, 0.01, "pendulum on a rod");
    let box2d = Box2dWorld::from_carom(&world).unwrap();
    assert!(box2d.notes().is_empty(), "{:?}", box2d.notes().lines());
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    assert!(rapier.notes().mentions("rigid distance joint"));
}

#[test]
fn a_rope_and_a_spring_hold_as_carom_s_do() {
    // A ball on a slack rope of 1.5 m drops and hangs at the rope's length; a ball on a 2 Hz
    // undamped spring of 1 m bounces at 2 Hz (no gravity for this one: `gravity_scale` 0).
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let hook = world
        .add_body(BodyDef::static_body(Shape::rect(0.1, 0.1)))
        .unwrap();
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.1)).position(vec2(0.0, -1.0)))
        .unwrap();
    world
        .add_joint(JointDef::rope(
            hook,
            ball,
            Vec2::zeros(),
            vec2(0.0, -1.0),
            1.5,
        ))
        .unwrap();
    let bouncer = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.1))
                .position(vec2(5.0, -1.2))
                .gravity_scale(0.0),
        )
        .unwrap();
    world
        .add_joint(
            JointDef::distance(hook, bouncer, vec2(5.0, 0.0), vec2(5.0, -1.2))
                .spring(2.0, 0.0)
                .limits(0.1, 10.0),
        )
        .unwrap();
    // The spring's rest length is 1 m: it starts stretched by 0.2 m.
    let spring = world.joints().nth(1).unwrap().handle();
    let mut kind = *world.joint(spring).unwrap().kind();
    if let carom::JointKind::Distance(d) = &mut kind {
        d.length = 1.0;
    }
    world.joint_mut(spring).unwrap().set_kind(kind).unwrap();
    let hung = tracks(&mut world.clone(), 1, 180);
    for (engine, t) in ["carom", "Box2D", "Rapier"].iter().zip(&hung) {
        let y = t.last().unwrap().0[1];
        assert!((y + 1.5).abs() < 0.01, "{engine}: the ball hangs at {y}");
    }
    let bounce = tracks(&mut world, 2, 300);
    let periods = bounce.map(|t| period(t.iter().map(|(p, _)| p[1]), -1.0));
    assert!(
        (periods[0] - 0.5).abs() < 0.01,
        "carom's period {}",
        periods[0]
    );
    same_periods(periods, 0.01, "distance spring");
}

#[test]
fn hinge_limits_and_reference_angles_map_to_the_peers_frames() {
    // Body A (static) at 0.3 rad, body B at 1.0 rad, hinged at B's left end: gravity turns B
    // down until its limit, 0.1 rad below where it started relative to A.
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let a = world
        .add_body(BodyDef::static_body(Shape::rect(0.5, 0.1)).angle(0.3))
        .unwrap();
    let (angle, half) = (1.0_f32, 0.5);
    let b = world
        .add_body(
            BodyDef::dynamic(Shape::rect(half, 0.05))
                .position(vec2(3.0 + half * angle.cos(), half * angle.sin()))
                .angle(angle),
        )
        .unwrap();
    world
        .add_joint(JointDef::revolute(a, b, vec2(3.0, 0.0)).limits(-0.1, 0.4))
        .unwrap();
    let tracks = tracks(&mut world, 1, 120);
    for (engine, t) in ["carom", "Box2D", "Rapier"].iter().zip(&tracks) {
        let turned = t.last().unwrap().1 - angle;
        assert!(
            (turned + 0.1).abs() < 0.02,
            "{engine}: B turned {turned} rad from its start, its limit -0.1"
        );
        // Still on its hinge: B's left end at (3, 0).
        let ([x, y], th) = *t.last().unwrap();
        let end = [x - half * th.cos(), y - half * th.sin()];
        assert!(end[0].hypot(end[1]) > 0.0 && (end[0] - 3.0).abs() < 0.01 && end[1].abs() < 0.01);
    }
}

#[test]
fn a_hinge_motor_and_a_hinge_spring_act_alike() {
    // A wheel on a static hub driven at 3 rad/s; beside it a disc on a 1 Hz undamped
    // torsion spring, started turning.
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let hub = world
        .add_body(BodyDef::static_body(Shape::circle(0.05)))
        .unwrap();
    let wheel = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)))
        .unwrap();
    world
        .add_joint(JointDef::revolute(hub, wheel, Vec2::zeros()).motor_drive(3.0, 1000.0))
        .unwrap();
    let disc = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.5))
                .position(vec2(3.0, 0.0))
                .angular_velocity(2.0),
        )
        .unwrap();
    world
        .add_joint(JointDef::revolute(hub, disc, vec2(3.0, 0.0)).spring(1.0, 0.0))
        .unwrap();
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    let mut rapier = RapierWorld::from_carom(&world, DT).unwrap();
    let mut angles = [Vec::new(), Vec::new(), Vec::new()];
    for _ in 0..300 {
        world.step(DT).unwrap();
        box2d.step(DT).unwrap();
        rapier.step();
        angles[0].push(world.body(disc).unwrap().angle());
        angles[1].push(box2d.angle(2).unwrap());
        angles[2].push(rapier.angle(2).unwrap());
    }
    let spins = [
        world.body(wheel).unwrap().angular_velocity(),
        box2d.angular_velocity(1).unwrap(),
        rapier.velocity(1).unwrap().1,
    ];
    for (engine, w) in ["carom", "Box2D", "Rapier"].iter().zip(spins) {
        assert!(
            (w - 3.0).abs() < 0.01,
            "{engine}: the wheel turns at {w} rad/s"
        );
    }
    let periods = angles.map(|a| period(a.into_iter(), 0.0));
    assert!(
        (periods[0] - 1.0).abs() < 0.01,
        "carom's period {}",
        periods[0]
    );
    same_periods(periods, 0.01, "torsion spring");
}

/// Without gravity: a puck pulled by a motor joint's spring toward an offset and turned by
/// its angular spring, a puck braked by its velocity part, and a ball reeled out by a
/// distance joint's motor against a spring that only pulls, bounded. Box2D follows carom's
/// paths.
#[test]
fn motor_joints_and_distance_motors_move_as_box2d_s() {
    let mut world = World::new();
    world
        .update_settings(|s| {
            s.gravity = Vec2::zeros();
            s.effects.set(Effect::Sleeping, false);
        })
        .unwrap();
    let ground = world
        .add_body(BodyDef::static_body(Shape::rect(0.1, 0.1)))
        .unwrap();
    let pulled = world
        .add_body(BodyDef::dynamic(Shape::rect(0.3, 0.3)).position(vec2(1.0, 0.0)))
        .unwrap();
    world
        .add_joint(JointDef::new(
            ground,
            pulled,
            vec2(1.0, 0.0),
            vec2(1.0, 0.0),
            carom::JointKind::Motor(carom::MotorJoint {
                linear_offset: vec2(-1.0, 2.0),
                angular_offset: 1.0,
                linear_spring: carom::Spring::new(1.0, 0.7),
                max_spring_force: 2.0,
                angular_spring: carom::Spring::new(1.0, 0.7),
                max_spring_torque: 0.5,
                ..carom::MotorJoint::default()
            }),
        ))
        .unwrap();
    let braked = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(5.0, 0.0))
                .linear_velocity(vec2(2.0, 1.0))
                .angular_velocity(2.0),
        )
        .unwrap();
    world
        .add_joint(JointDef::new(
            ground,
            braked,
            vec2(5.0, 0.0),
            vec2(5.0, 0.0),
            carom::JointKind::Motor(carom::MotorJoint {
                max_velocity_force: 1.0,
                max_velocity_torque: 0.2,
                ..carom::MotorJoint::default()
            }),
        ))
        .unwrap();
    let reeled = world
        .add_body(BodyDef::dynamic(Shape::circle(0.2)).position(vec2(0.0, -1.0)))
        .unwrap();
    world
        .add_joint(
            JointDef::distance(ground, reeled, Vec2::zeros(), vec2(0.0, -1.0))
                .spring(2.0, 0.0)
                .spring_force(-0.5, 0.0)
                .motor_drive(1.0, 3.0),
        )
        .unwrap();
    let box2d = Box2dWorld::from_carom(&world).unwrap();
    assert_eq!(
        box2d.joint_count().unwrap(),
        3,
        "{:?}",
        box2d.notes().lines()
    );
    let mut worst = [0.0_f32; 3];
    let mut box2d = box2d;
    for _ in 0..180 {
        world.step(DT).unwrap();
        box2d.step(DT).unwrap();
        for (i, body) in [pulled, braked, reeled].into_iter().enumerate() {
            let b = world.body(body).unwrap();
            let [x, y] = box2d.position(i + 1).unwrap();
            let gap = (b.position() - vec2(x, y)).norm();
            let turn = (b.angle() - box2d.angle(i + 1).unwrap()).abs();
            worst[i] = worst[i].max(gap).max(turn);
        }
    }
    for (what, gap) in ["spring-pulled puck", "braked puck", "reeled ball"]
        .iter()
        .zip(worst)
    {
        assert!(gap < 0.01, "{what}: Box2D strays {gap} m or rad from carom");
    }
    // And they got somewhere: the pulled puck near its target, the braked one stopped.
    let p = world.body(pulled).unwrap();
    assert!(
        (p.position() - vec2(0.0, 2.0)).norm() < 0.05,
        "{}",
        p.position()
    );
    assert!(world.body(braked).unwrap().linear_velocity().norm() < 1e-4);
}

#[test]
fn sliders_follow_their_axis_to_their_limits_and_spring_at_their_rate() {
    // A box on a slider tilted 30° below the horizontal slides down it to its limit at 0.5 m;
    // beside it, one on a 1.5 Hz undamped spring along a 60° axis, no gravity, started off.
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let ground = world
        .add_body(BodyDef::static_body(Shape::rect(0.1, 0.1)).position(vec2(0.0, 5.0)))
        .unwrap();
    let tilt = (-30.0_f32).to_radians();
    let axis = vec2(tilt.cos(), tilt.sin());
    let slider = world
        .add_body(BodyDef::dynamic(Shape::rect(0.2, 0.1)).angle(tilt))
        .unwrap();
    world
        .add_joint(JointDef::prismatic(ground, slider, Vec2::zeros(), axis).limits(-1.0, 0.5))
        .unwrap();
    let up = 60.0_f32.to_radians();
    let axis = vec2(up.cos(), up.sin());
    let sprung = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.2, 0.1))
                .position(vec2(3.0, 0.0) + axis * 0.3)
                .gravity_scale(0.0),
        )
        .unwrap();
    world
        .add_joint(
            JointDef::prismatic(ground, sprung, vec2(3.0, 0.0) + axis * 0.3, axis).spring(1.5, 0.0),
        )
        .unwrap();
    // Its spring pulls toward translation -0.3: back to (3, 0).
    let handle = world.joints().nth(1).unwrap().handle();
    let mut kind = *world.joint(handle).unwrap().kind();
    if let carom::JointKind::Prismatic(p) = &mut kind {
        p.target_translation = -0.3;
    }
    world.joint_mut(handle).unwrap().set_kind(kind).unwrap();
    let slid = tracks(&mut world.clone(), 1, 120);
    for (engine, t) in ["carom", "Box2D", "Rapier"].iter().zip(&slid) {
        let ([x, y], th) = *t.last().unwrap();
        let along = x * tilt.cos() + y * tilt.sin();
        let across = -x * tilt.sin() + y * tilt.cos();
        assert!(
            (along - 0.5).abs() < 0.01,
            "{engine}: slid {along} m, its limit 0.5"
        );
        assert!(
            across.abs() < 0.01 && (th - tilt).abs() < 0.01,
            "{engine}: off its axis"
        );
    }
    let bounce = tracks(&mut world, 2, 300);
    let periods = bounce.map(|t| period(t.iter().map(|(p, _)| p[1]), 0.0));
    assert!(
        (periods[0] - 1.0 / 1.5).abs() < 0.01,
        "carom's period {}",
        periods[0]
    );
    same_periods(periods, 0.01, "slider spring");
}

#[test]
fn wheels_sag_on_their_suspension_and_turn_at_their_motor_s_speed() {
    // A 2 Hz, ζ 0.7 suspension holds a wheel under gravity: it sags g / ω² = 6.3 cm.
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let chassis = world
        .add_body(BodyDef::static_body(Shape::rect(1.0, 0.1)).position(vec2(0.0, 1.0)))
        .unwrap();
    let wheel = world
        .add_body(BodyDef::dynamic(Shape::circle(0.3)))
        .unwrap();
    world
        .add_joint(
            JointDef::wheel(chassis, wheel, Vec2::zeros(), vec2(0.0, 1.0))
                .spring(2.0, 0.7)
                .motor_drive(-4.0, 100.0),
        )
        .unwrap();
    let tracks = tracks(&mut world.clone(), 1, 180);
    let omega = std::f32::consts::TAU * 2.0;
    let sag = 10.0 / (omega * omega);
    for (engine, t) in ["carom", "Box2D", "Rapier"].iter().zip(&tracks) {
        let [x, y] = t.last().unwrap().0;
        assert!(
            (y + sag).abs() < 0.002,
            "{engine}: sags to {y}, {sag} expected"
        );
        assert!(x.abs() < 0.001, "{engine}: off its axle by {x}");
    }
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    let mut rapier = RapierWorld::from_carom(&world, DT).unwrap();
    for _ in 0..60 {
        box2d.step(DT).unwrap();
        rapier.step();
    }
    assert!((box2d.angular_velocity(1).unwrap() + 4.0).abs() < 0.01);
    assert!((rapier.velocity(1).unwrap().1 + 4.0).abs() < 0.01);
}

#[test]
fn a_weld_holds_a_beam_out_and_a_soft_one_bends_alike() {
    // Two 2 m beams welded at one end to a wall: one rigidly, one through a 2 Hz angular
    // spring (ζ 1), which lets it droop to about the same angle in every engine.
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let wall = world
        .add_body(BodyDef::static_body(Shape::rect(0.1, 2.0)))
        .unwrap();
    let rigid = world
        .add_body(BodyDef::dynamic(Shape::rect(1.0, 0.1)).position(vec2(1.0, 1.0)))
        .unwrap();
    world
        .add_joint(JointDef::weld(wall, rigid, vec2(0.0, 1.0)))
        .unwrap();
    let soft = world
        .add_body(BodyDef::dynamic(Shape::rect(1.0, 0.1)).position(vec2(1.0, -1.0)))
        .unwrap();
    let mut weld = JointDef::weld(wall, soft, vec2(0.0, -1.0));
    weld.kind = carom::JointKind::Weld(carom::WeldJoint {
        linear: None,
        angular: Some(carom::Spring::new(2.0, 1.0)),
    });
    world.add_joint(weld).unwrap();
    let held = tracks(&mut world.clone(), 1, 180);
    for (engine, t) in ["carom", "Box2D", "Rapier"].iter().zip(&held) {
        let ([x, y], th) = *t.last().unwrap();
        assert!(
            (x - 1.0).abs() < 0.01 && (y - 1.0).abs() < 0.01 && th.abs() < 0.01,
            "{engine}: the rigid beam moved to ({x}, {y}) at {th} rad"
        );
    }
    let bent = tracks(&mut world, 2, 180);
    let droop = bent.map(|t| t.last().unwrap().1);
    assert!(
        droop[0] < -0.05,
        "carom's soft beam droops {} rad",
        droop[0]
    );
    for (engine, d) in [("Box2D", droop[1]), ("Rapier", droop[2])] {
        assert!(
            (d - droop[0]).abs() < 0.05 * droop[0].abs(),
            "{engine}'s soft beam droops {d} rad, carom's {}",
            droop[0]
        );
    }
}

/// A static floor and a box resting on it, joined by a slack rope (colliding or not) or by
/// a filter joint: where the joint keeps them from colliding the box falls through.
fn box_on_floor(join: impl Fn(BodyHandle, BodyHandle) -> JointDef) -> [f32; 3] {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .unwrap();
    let floor = world
        .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let crate_ = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5)))
        .unwrap();
    world.add_joint(join(floor, crate_)).unwrap();
    tracks(&mut world, 1, 60).map(|t| t.last().unwrap().0[1])
}

#[test]
fn collide_connected_and_filter_joints_decide_contacts_in_the_peers() {
    // The rope from a point of the floor's frame 3 m up to the box's centre: it lengthens as
    // the box falls.
    let rope = |a, b| JointDef::rope(a, b, vec2(0.0, 3.0), vec2(0.0, 0.5), 10.0);
    for (engine, y) in ["carom", "Box2D", "Rapier"]
        .iter()
        .zip(box_on_floor(|a, b| rope(a, b).collide_connected(true)))
    {
        assert!((y - 0.5).abs() < 0.01, "{engine}: the box rests at {y}");
    }
    for join in [rope as fn(_, _) -> _, JointDef::filter] {
        for (engine, y) in ["carom", "Box2D", "Rapier"].iter().zip(box_on_floor(join)) {
            assert!(y < -2.0, "{engine}: the box should fall through, at {y}");
        }
    }
}

/// A 10 x 10 grid of touching circles under a floor-less sky (no gravity), every one with
/// `filter`: how many pairs Box2D and Rapier track after a few steps.
fn pairs_in_grid(filter: CollisionFilter) -> (usize, usize) {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(Effect::Gravity, false))
        .unwrap();
    for k in 0..10 {
        for i in 0..10 {
            world
                .add_body(
                    BodyDef::dynamic(Shape::circle(0.4))
                        .position(vec2(0.8 * k as Real, -0.8 * i as Real))
                        .filter(filter),
                )
                .unwrap();
        }
    }
    let mut box2d = Box2dWorld::from_carom(&world).unwrap();
    let mut rapier = RapierWorld::from_carom(&world, DT).unwrap();
    for _ in 0..5 {
        box2d.step(DT).unwrap();
        rapier.step();
    }
    (box2d.contact_count().unwrap(), rapier.contact_count())
}

#[test]
fn collision_filters_keep_categories_masks_and_groups() {
    let plain = pairs_in_grid(CollisionFilter::DEFAULT);
    assert!(
        plain.0 >= 180 && plain.1 >= 180,
        "touching circles: {plain:?}"
    );
    // Box2D's joint grid filter: category 2, every category but 2.
    let apart = CollisionFilter {
        category: 2,
        mask: !2,
        group: 0,
    };
    assert_eq!(pairs_in_grid(apart), (0, 0));
    // One negative group: never collide, whatever the masks say.
    let group = |group| CollisionFilter {
        group,
        ..CollisionFilter::DEFAULT
    };
    assert_eq!(pairs_in_grid(group(-3)), (0, 0));
    // One positive group: always collide, even with masks that would not.
    let forced = pairs_in_grid(CollisionFilter { group: 3, ..apart });
    assert_eq!(forced, plain);
    // Categories beyond Rapier's 32 bits go through the filter hook, exactly.
    let high = CollisionFilter {
        category: 1 << 40,
        mask: !(1 << 40),
        group: 0,
    };
    assert_eq!(pairs_in_grid(high), (0, 0));
}

#[test]
fn joints_a_peer_cannot_express_are_noted_not_dropped_silently() {
    let (mut world, pivot, bob, at) = pendulum();
    world.add_joint(JointDef::mouse(bob, at, 50.0)).unwrap();
    world
        .add_joint(JointDef::motor(pivot, bob, at, 10.0, 1.0))
        .unwrap();
    world
        .add_joint(JointDef::mover(pivot, bob, Vec2::zeros(), vec2(1.0, 0.0)))
        .unwrap();
    world
        .add_joint(JointDef::revolute(pivot, bob, Vec2::zeros()).break_force(100.0))
        .unwrap();
    let box2d = Box2dWorld::from_carom(&world).unwrap();
    let rapier = RapierWorld::from_carom(&world, DT).unwrap();
    for (notes, whats) in [
        (box2d.notes(), &["mouse joint", "mover", "break force"][..]),
        (
            rapier.notes(),
            &["mouse joint", "motor", "mover", "break force"][..],
        ),
    ] {
        for what in whats {
            assert!(
                notes.mentions(what),
                "{what} not noted: {:?}",
                notes.lines()
            );
        }
    }
    // Box2D has the hinge and the motor joint; Rapier the hinge.
    assert_eq!(box2d.joint_count().unwrap(), 2);
    assert_eq!(rapier.joint_count(), 1);
}

/// Largest distance between a joint's two anchors in each engine, m.
fn widest_gaps(world: &World, box2d: &mut Box2dWorld, rapier: &RapierWorld) -> [f32; 3] {
    let index: HashMap<BodyHandle, usize> = world
        .bodies()
        .enumerate()
        .map(|(i, b)| (b.handle(), i))
        .collect();
    let place = |([x, y], th): ([f32; 2], f32), p: Vec2| {
        vec2(
            x + th.cos() * p.x - th.sin() * p.y,
            y + th.sin() * p.x + th.cos() * p.y,
        )
    };
    let mut widest = [0.0_f32; 3];
    let positions = rapier.positions();
    for joint in world.joints() {
        let [a, b] = joint.bodies();
        let [la, lb] = joint.local_anchors();
        let [pa, pb] = joint.world_anchors(world.body(a).unwrap(), world.body(b).unwrap());
        widest[0] = widest[0].max((pb - pa).norm());
        let (ia, ib) = (index[&a], index[&b]);
        let mut pose = |i| (box2d.position(i).unwrap(), box2d.angle(i).unwrap());
        let gap = (place(pose(ib), lb) - place(pose(ia), la)).norm();
        widest[1] = widest[1].max(gap);
        let pose = |i: usize| (positions[i], rapier.angle(i).unwrap());
        let gap = (place(pose(ib), lb) - place(pose(ia), la)).norm();
        widest[2] = widest[2].max(gap);
    }
    widest
}

#[test]
fn box2d_s_joint_grid_is_copied_joint_for_joint() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos/joint_grid.ron");
    let mut scene = carom_scene::load(&file).unwrap();
    let world = &mut scene.world;
    assert_eq!(world.body_count(), 10_000);
    assert_eq!(world.joint_count(), 19_800);
    // Column by column from the top, as Box2D makes them: body k * 100 + i at (k, -i), the
    // seven in the middle of the top row static.
    let bodies: Vec<_> = world.bodies().collect();
    for (n, body) in bodies.iter().enumerate() {
        let (k, i) = (n / 100, n % 100);
        assert_eq!(body.position(), vec2(k as f32, -(i as f32)));
        assert_eq!(
            body.is_dynamic(),
            !((47..=53).contains(&k) && i == 0),
            "{k}, {i}"
        );
        let collider = world.collider(body.colliders()[0]).unwrap();
        let filter = collider.filter();
        assert_eq!(
            (filter.category, filter.mask, filter.group),
            (2, !2 & 0xFFFF_FFFF, 0)
        );
    }
    // Box2D's joints, in its order: for body (k, i), first the one to (k, i - 1) above, then
    // the one to (k - 1, i) on its left; the earlier body is A.
    let mut expected = Vec::new();
    for n in 0..10_000 {
        let (k, i) = (n / 100, n % 100);
        if i > 0 {
            expected.push((n - 1, n, [vec2(0.0, -0.5), vec2(0.0, 0.5)]));
        }
        if k > 0 {
            expected.push((n - 100, n, [vec2(0.5, 0.0), vec2(-0.5, 0.0)]));
        }
    }
    for (joint, (a, b, anchors)) in world.joints().zip(&expected) {
        assert_eq!(
            joint.kind(),
            &carom::JointKind::Revolute(Default::default())
        );
        assert_eq!(joint.bodies(), [bodies[*a].handle(), bodies[*b].handle()]);
        assert_eq!(joint.local_anchors(), *anchors);
        assert_eq!(joint.reference_angle(), 0.0);
        assert!(!joint.collide_connected());
    }
    let mut box2d = Box2dWorld::from_carom(world).unwrap();
    let mut rapier = RapierWorld::from_carom(world, DT).unwrap();
    assert!(box2d.notes().is_empty() && rapier.notes().is_empty());
    assert_eq!(box2d.joint_count().unwrap(), 19_800);
    assert_eq!(rapier.joint_count(), 19_800);
    for _ in 0..60 {
        world.step(DT).unwrap();
        box2d.step(DT).unwrap();
        rapier.step();
    }
    // The circles never touch one another; joined ones are not even paired.
    assert_eq!(box2d.contact_count().unwrap(), 0);
    assert_eq!(rapier.contact_count(), 0);
    // The net holds together in every engine: 5 t hang from seven circles on soft joints,
    // whose anchors open by about 0.36 m at the top in carom and Box2D alike (Rapier's, whose
    // solver converges less over the 100-joint chains, about twice as far).
    let [c, b, r] = widest_gaps(world, &mut box2d, &rapier);
    eprintln!("widest joint gaps after 1 s: carom {c}, Box2D {b}, Rapier {r} m");
    assert!(
        (c - b).abs() < 0.1 * b,
        "carom's widest gap {c} m, Box2D's {b} m"
    );
    assert!(r < 1.0, "Rapier's net came apart: a gap of {r} m");
}
