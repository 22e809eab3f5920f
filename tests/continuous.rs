//! Continuous collision: the tutorial's tunnelling case, and Box2D's hardest sweeps.

use carom::{
    BodyDef, BodyHandle, CollisionFilter, Effect, Effects, JointDef, Real, Shape, SolverParams,
    Vec2, World, WorldSettings, vec2,
};
use carom_bench::cases::skinny_box;
use carom_tests::world_shape;

const DT: Real = 1.0 / 60.0;

fn world(continuous: bool, gravity: Vec2) -> World {
    World::with_settings(WorldSettings {
        gravity,
        effects: Effects::ALL.switched(Effect::Continuous, continuous),
        solver: SolverParams::default(),
        ..WorldSettings::default()
    })
    .unwrap()
}

/// A world with continuous collision and no friction, drag or sleeping, so a body keeps its
/// speed unless something stops it.
fn slick_world(gravity: Vec2) -> World {
    World::with_settings(WorldSettings {
        gravity,
        effects: Effects::ALL
            .switched(Effect::Friction, false)
            .switched(Effect::Drag, false)
            .switched(Effect::Sleeping, false),
        ..WorldSettings::default()
    })
    .unwrap()
}

/// Fires a 0.25 m circle at 300 m/s, from 10 m away along `direction`, at a 0.1 m thick static
/// wall through the origin facing it; returns how far past the wall's far face it ended
/// (negative: it stayed on its side).
fn fire_at_wall(continuous: bool, direction: Real) -> Real {
    fire_at_wall_in(world(continuous, Vec2::zeros()), direction)
}

/// [`fire_at_wall`] in `world`.
fn fire_at_wall_in(mut world: World, direction: Real) -> Real {
    let along = vec2(direction.cos(), direction.sin());
    world
        .add_body(BodyDef::static_body(Shape::rect(0.05, 4.0)).angle(direction))
        .unwrap();
    let bullet = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(-along * 10.0)
                .linear_velocity(along * 300.0)
                .density(4.0),
        )
        .unwrap();
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    world.body(bullet).unwrap().position().dot(&along) - 0.05
}

/// What keeps the fired circle and the wall from colliding, if anything.
#[derive(Debug, Clone, Copy, PartialEq)]
enum KeptApart {
    No,
    /// The wall's category is not in the circle's mask.
    ByFilter,
    /// A filter joint joins the two bodies.
    ByJoint,
}

/// [`fire_at_wall`] straight on, with continuous collision, where `kept` may keep the circle
/// and the wall from ever colliding.
fn fire_at_wall_kept_apart(kept: KeptApart) -> Real {
    let mut world = world(true, Vec2::zeros());
    let wall_filter = CollisionFilter {
        category: 0b10,
        ..CollisionFilter::DEFAULT
    };
    let wall = world
        .add_body(BodyDef::static_body(Shape::rect(0.05, 4.0)).filter(wall_filter))
        .unwrap();
    let mask = if kept == KeptApart::ByFilter {
        !0b10
    } else {
        u64::MAX
    };
    let bullet = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(vec2(-10.0, 0.0))
                .linear_velocity(vec2(300.0, 0.0))
                .density(4.0)
                .filter(CollisionFilter {
                    mask,
                    ..CollisionFilter::DEFAULT
                }),
        )
        .unwrap();
    if kept == KeptApart::ByJoint {
        world.add_joint(JointDef::filter(wall, bullet)).unwrap();
    }
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    world.body(bullet).unwrap().position().x - 0.05
}

#[test]
fn continuous_collision_stops_nothing_at_a_body_it_may_not_collide_with() {
    assert!(fire_at_wall_kept_apart(KeptApart::No) < 0.0);
    for kept in [KeptApart::ByFilter, KeptApart::ByJoint] {
        let past = fire_at_wall_kept_apart(kept);
        // 30 steps at 300 m/s from 10 m before the wall: 140 m beyond it, unslowed.
        assert!(
            (past - 140.0).abs() < 1.0,
            "{kept:?}: ended {past} m past the wall"
        );
    }
}

#[test]
fn without_continuous_collision_the_bullet_tunnels() {
    let past = fire_at_wall(false, 0.0);
    assert!(
        past > 1.0,
        "expected a tunnel, ended {past} m past the wall"
    );
}

#[test]
fn with_continuous_collision_the_bullet_never_passes_the_wall() {
    for run in 0..100 {
        let direction = run as Real * 0.0631;
        let past = fire_at_wall(true, direction);
        // Its centre stays at least a radius in front of the near face.
        assert!(
            past < -0.1 - 0.25 + 0.01,
            "run {run}: ended {past} m past the wall"
        );
    }
}

/// Drops a 4 x 0.1 m plank at 100 m/s spinning at 50 rad/s onto a thin static floor next to
/// a thin static post; returns the lowest point the plank reached and whether its centre passed
/// through the post.
fn drop_plank(continuous: bool, angle: Real, spin: Real, offset: Real) -> (Real, bool) {
    let mut world = world(continuous, vec2(0.0, -10.0));
    skinny_box::add_course(&mut world);
    let plank = world
        .add_body(
            skinny_box::plank()
                .position(vec2(offset, 8.0))
                .angle(angle)
                .linear_velocity(vec2(0.0, -100.0))
                .angular_velocity(spin),
        )
        .unwrap();
    let mut lowest = Real::INFINITY;
    let mut crossed = false;
    let mut before = world.body(plank).unwrap().position();
    for _ in 0..60 {
        world.step(DT).unwrap();
        let body = world.body(plank).unwrap();
        lowest = lowest.min(body.aabb().min.y);
        let after = body.position();
        crossed |= skinny_box::through_post(before, after);
        before = after;
    }
    (lowest, crossed)
}

/// The drop of run `run` of 100: angles, spins and offsets from the post vary.
fn plank_run(continuous: bool, run: usize) -> (Real, bool) {
    let angle = run as Real * 0.377;
    let spin = if run.is_multiple_of(2) { 50.0 } else { -50.0 };
    let offset = [-1.5, -0.5, 0.3][run % 3];
    drop_plank(continuous, angle, spin, offset)
}

#[test]
fn without_continuous_collision_the_plank_passes_the_floor() {
    let tunnels = (0..100)
        .filter(|&run| plank_run(false, run).0 < -0.5)
        .count();
    assert!(
        tunnels > 50,
        "only {tunnels} of 100 drops went through the floor"
    );
}

#[test]
fn a_fast_spinning_plank_never_passes_the_floor_or_the_post() {
    for run in 0..100 {
        let (lowest, crossed) = plank_run(true, run);
        // Below the floor's top by no more than the slop it is allowed to sink.
        assert!(lowest > -0.02, "run {run}: reached y = {lowest}");
        assert!(!crossed, "run {run}: passed through the post");
    }
}

/// A free-floating 4 m x 0.1 m dynamic plank (density 50) at the origin and a 0.25 m circle
/// 10 m before it at `height`, flying at it at 300 m/s; returns the world, the plank and the
/// circle.
fn shot_at_free_plank(bullet: bool, height: Real) -> (World, BodyHandle, BodyHandle) {
    let mut world = world(true, Vec2::zeros());
    let plank = world
        .add_body(BodyDef::dynamic(Shape::rect(0.05, 2.0)).density(50.0))
        .unwrap();
    let shot = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(vec2(-10.0, height))
                .linear_velocity(vec2(300.0, 0.0))
                .bullet(bullet),
        )
        .unwrap();
    (world, plank, shot)
}

/// Fires a 0.25 m circle at 300 m/s at a free-floating 0.1 m thick dynamic plank; returns how
/// far past the plank's starting plane the circle got in 5 steps.
fn fire_at_dynamic_plank(bullet: bool) -> Real {
    let (mut world, _, shot) = shot_at_free_plank(bullet, 0.0);
    for _ in 0..5 {
        world.step(DT).unwrap();
    }
    world.body(shot).unwrap().position().x
}

#[test]
fn fast_bodies_meet_moving_bodies_face_on_and_bullets_too() {
    // An ordinary fast body is swept only against static bodies, but its contact with the
    // plank's face is made a step ahead (the face margin reaches as far as the pair closes in
    // a step), so it hits the plank and pushes it along; a bullet, swept against every body,
    // does too.
    for bullet in [false, true] {
        let x = fire_at_dynamic_plank(bullet);
        assert!(x < 2.0, "bullet {bullet}: ended at x = {x}");
    }
}

/// A small bullet stopped at a free wall's face, above its centre, pushes the wall and turns
/// it; the face then moves at the bullet's speed where it was hit and turns away. Seen from
/// the wall (its own frame: the wall turns, so world positions alone mislead), the bullet
/// stays at the face and never sinks in, as in Box2D on the same case.
#[test]
fn a_bullet_that_hits_a_free_wall_off_centre_stays_at_its_face() {
    let mut world = world(true, Vec2::zeros());
    let wall = |x: Real| {
        BodyDef::dynamic(Shape::rect(0.1, 2.0))
            .position(vec2(x, 0.0))
            .density(5.0)
    };
    world.add_body(wall(-3.0)).unwrap();
    let target = world.add_body(wall(3.0)).unwrap();
    let shot = BodyDef::dynamic(Shape::circle(0.05))
        .position(vec2(0.0, 1.0))
        .linear_velocity(vec2(500.0, 0.0))
        .bullet(true);
    let bullet = world.add_body(shot).unwrap();
    // How far the bullet's surface is past the wall's near face (local x = -0.1), m.
    let mut deepest = Real::NEG_INFINITY;
    for _ in 0..60 {
        world.step(DT).unwrap();
        let (b, w) = (world.body(bullet).unwrap(), world.body(target).unwrap());
        let d = b.position() - w.position();
        let (sin, cos) = (-w.angle()).sin_cos();
        let local = vec2(cos * d.x - sin * d.y, sin * d.x + cos * d.y);
        assert!(
            local.y.abs() < 2.0,
            "the bullet stays beside the face: {local:?}"
        );
        deepest = deepest.max(local.x + 0.05 + 0.1);
    }
    assert!(deepest < 0.005, "the bullet sank {deepest} m into the wall");
    let w = world.body(target).unwrap();
    assert!(
        w.linear_velocity().x > 0.5,
        "the wall took the bullet's push"
    );
    assert!(
        w.angular_velocity() < -0.3,
        "and turned: {}",
        w.angular_velocity()
    );
    assert!(
        w.angle() < -0.3,
        "by over 0.3 rad in a second: {}",
        w.angle()
    );
}

#[test]
fn a_fast_body_sliding_on_the_ground_is_not_held_back() {
    // A box resting on a floor and sliding fast enough to be swept touches the floor at the
    // start of every sweep. Touching at the start is the solver's business, not a tunnel: the
    // box must slide on, not be put back where it started each step.
    let mut world = slick_world(WorldSettings::default().gravity);
    world
        .add_body(BodyDef::static_body(Shape::rect(100.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let slider = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.25))
                .position(vec2(-20.0, 0.25))
                .linear_velocity(vec2(20.0, 0.0)),
        )
        .unwrap();
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let body = world.body(slider).unwrap();
    let travelled = body.position().x + 20.0;
    assert!(
        (travelled - 10.0).abs() < 0.5,
        "in 0.5 s at 20 m/s the box should slide 10 m, it slid {travelled} m"
    );
    assert!(
        (body.position().y - 0.25).abs() < 0.02,
        "and stay on the floor, at y = {}",
        body.position().y
    );
}

/// Sends a 0.25 m ball at `speed` round the inside of a 10 m loop of 90 links facing inward,
/// gravity, friction and drag off, for a second; returns how far it went along the loop and
/// how deep it sank into it at worst.
fn ride_round_a_loop(speed: Real) -> (Real, Real) {
    let mut world = slick_world(Vec2::zeros());
    let (radius, ball_radius, links) = (10.0, 0.25, 90);
    let points: Vec<Vec2> = (0..links)
        .map(|i| {
            let angle = -std::f32::consts::TAU * i as Real / links as Real;
            vec2(angle.cos(), angle.sin()) * radius
        })
        .collect();
    world
        .add_body(BodyDef::static_chain(&carom::ChainDef::closed(points)).unwrap())
        .unwrap();
    let start = vec2(0.0, ball_radius - radius + 0.05);
    let ball = world
        .add_body(
            BodyDef::dynamic(Shape::circle(ball_radius))
                .position(start)
                .linear_velocity(vec2(speed, 0.0)),
        )
        .unwrap();
    let (mut turned, mut deepest): (Real, Real) = (0.0, 0.0);
    let mut last = start;
    for _ in 0..60 {
        world.step(DT).unwrap();
        let at = world.body(ball).unwrap().position();
        turned += last.perp(&at).atan2(last.dot(&at));
        deepest = deepest.max(at.norm() + ball_radius - radius);
        last = at;
    }
    (turned * (radius - ball_radius), deepest)
}

#[test]
fn a_fast_ball_riding_round_a_chain_loop_is_not_held_back() {
    // Each step's straight path cuts outside the circle the ball follows, toward the next link.
    // Sweeping it against that link would stop it there every step, and it would fall far
    // behind; its contact with the loop is what keeps it in.
    for speed in [10.0, 20.0, 40.0] {
        let (went, deepest) = ride_round_a_loop(speed);
        assert!(
            went > 0.9 * speed,
            "at {speed} m/s the ball went {went} m in a second"
        );
        assert!(
            deepest < 0.12,
            "at {speed} m/s it sank {deepest} m into the loop"
        );
    }
}

/// Throws a 1 m box, tilted 0.6 rad and spinning at `spin`, at `speed` from `start_x` into the
/// side of a 2 m box resting on the ground (static, or dynamic and ten times denser), gravity
/// off; returns the deepest overlap of the two after any step.
fn impact(speed: Real, spin: Real, target_moves: bool, start_x: Real, predicted: bool) -> Real {
    let world = world(predicted, Vec2::zeros());
    impact_in(world, (speed, spin), target_moves, start_x, false)
}

/// [`impact`] in `world`, the thrown box looking ahead whatever the world does if
/// `looks_ahead`.
fn impact_in(
    mut world: World,
    (speed, spin): (Real, Real),
    target_moves: bool,
    start_x: Real,
    looks_ahead: bool,
) -> Real {
    world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let target = if target_moves {
        BodyDef::dynamic(Shape::rect(1.0, 1.0)).density(10.0)
    } else {
        BodyDef::static_body(Shape::rect(1.0, 1.0))
    };
    let target = world.add_body(target.position(vec2(0.0, 1.0))).unwrap();
    let thrown = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(start_x, 1.2))
                .angle(0.6)
                .linear_velocity(vec2(speed, 0.0))
                .angular_velocity(spin)
                .look_ahead(looks_ahead),
        )
        .unwrap();
    deepest_overlap(&mut world, target, thrown, 40)
}

/// Steps `world` `steps` times; returns the deepest `a` and `b` overlapped after any step.
fn deepest_overlap(world: &mut World, a: BodyHandle, b: BodyHandle, steps: usize) -> Real {
    let mut deepest: Real = 0.0;
    for _ in 0..steps {
        world.step(DT).unwrap();
        let (a, b) = (world_shape(world, a), world_shape(world, b));
        let gap = carom::query::separation(a, b).separation;
        deepest = deepest.max(-gap);
    }
    deepest
}

#[test]
fn impacts_up_to_30_m_s_overlap_at_most_a_centimetre() {
    // Every speed and start (so the impact falls at every point of a step), into a static and
    // into a free heavy body, spinning or not. With continuous collision, a face's contact is
    // made a step ahead at whatever speed the pair closes, so the solver stops the approach at
    // the surface; without it, a box at 10 m/s sinks 14 cm before it is pushed back out.
    let mut worst_without: Real = 0.0;
    for target_moves in [false, true] {
        for (speed, spin) in [
            (2.0, 0.0),
            (5.0, 0.0),
            (10.0, 0.0),
            (15.0, 8.0),
            (20.0, 0.0),
            (30.0, 0.0),
            (30.0, 8.0),
        ] {
            for k in 0..12 {
                let start = -3.0 - 0.041 * k as Real;
                let deepest = impact(speed, spin, target_moves, start, true);
                assert!(
                    deepest < 0.01,
                    "{speed} m/s, spin {spin}, target moves {target_moves}, start {start}: {deepest} m deep"
                );
                worst_without = worst_without.max(impact(speed, spin, target_moves, start, false));
            }
        }
    }
    assert!(
        worst_without > 0.1,
        "without continuous collision: {worst_without} m"
    );
}

#[test]
fn without_looking_ahead_an_impact_sinks_in_but_nothing_tunnels() {
    // Box2D's promise: a contact keeps points within the speculative distance only, so a box
    // that closes faster than that in a step sinks into what it hits before it is pushed
    // out; the sweeps still keep fast bodies out of static ones.
    let box2d_like = || {
        World::with_settings(WorldSettings {
            gravity: Vec2::zeros(),
            look_ahead: false,
            ..WorldSettings::default()
        })
        .unwrap()
    };
    let (mut worst, mut worst_asked): (Real, Real) = (0.0, 0.0);
    for target_moves in [false, true] {
        for k in 0..12 {
            let start = -3.0 - 0.041 * k as Real;
            let deepest = |asked| impact_in(box2d_like(), (10.0, 0.0), target_moves, start, asked);
            worst = worst.max(deepest(false));
            // A body that asks to look ahead is stopped at the surface all the same.
            worst_asked = worst_asked.max(deepest(true));
        }
    }
    assert!(worst > 0.02, "at 10 m/s it sank {worst} m at worst");
    assert!(worst_asked < 0.01, "looking ahead, it sank {worst_asked} m");
    for direction in [0.0, 0.7, 2.0] {
        let past = fire_at_wall_in(box2d_like(), direction);
        assert!(past < -0.2, "the ball ended {past} m past the wall");
    }
}

/// Two 1 m boxes, one behind the other with a 0.3 m gap, flying along x at 30 m/s, gravity
/// off.
fn convoy() -> (World, BodyHandle, BodyHandle) {
    let mut world = world(true, Vec2::zeros());
    let mut add = |x: Real| {
        world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .position(vec2(x, 0.0))
                    .linear_velocity(vec2(30.0, 0.0)),
            )
            .unwrap()
    };
    let (rear, front) = (add(0.0), add(1.3));
    (world, rear, front)
}

#[test]
fn bodies_flying_together_have_no_contact() {
    // Each box's broadphase box reaches half a metre ahead, over the other, but the two keep
    // their distance: a contact would be work for nothing.
    let (mut world, rear, front) = convoy();
    for step in 0..20 {
        world.step(DT).unwrap();
        assert_eq!(world.contacts().count(), 0, "step {step}");
    }
    let gap = world.body(front).unwrap().position().x - world.body(rear).unwrap().position().x;
    assert!((gap - 1.3).abs() < 1e-4, "they keep their distance: {gap}");
}

#[test]
fn a_body_turned_round_by_hand_still_meets_the_one_behind_it() {
    // The front box is sent back at 30 m/s: the pair now closes a metre a step across a 0.3 m
    // gap, and what the last step said of the front box's motion no longer holds.
    let (mut world, rear, front) = convoy();
    for _ in 0..5 {
        world.step(DT).unwrap();
    }
    world
        .body_mut(front)
        .unwrap()
        .set_linear_velocity(vec2(-30.0, 0.0))
        .unwrap();
    let deepest = deepest_overlap(&mut world, rear, front, 10);
    assert!(deepest < 0.01, "{deepest} m deep");
}

/// Slides a box (or ball) at 30 m/s past the top corner of a static block, `clearance` above
/// it, gravity off; returns how much its velocity changed.
fn graze(shape: Shape, half_height: Real, clearance: Real, start_x: Real) -> Real {
    let mut world = world(true, Vec2::zeros());
    world
        .add_body(BodyDef::static_body(Shape::rect(1.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    let slider = world
        .add_body(
            BodyDef::dynamic(shape)
                .position(vec2(start_x, half_height + clearance))
                .linear_velocity(vec2(30.0, 0.0)),
        )
        .unwrap();
    for _ in 0..20 {
        world.step(DT).unwrap();
    }
    let body = world.body(slider).unwrap();
    (body.linear_velocity() - vec2(30.0, 0.0)).norm() + body.angular_velocity().abs()
}

#[test]
fn a_body_grazing_past_a_corner_at_30_m_s_is_not_deflected() {
    // Only a face's contact looks a step ahead: two corners facing each other (or a face past
    // the end of another) keep the plain 2 cm speculative margin, as their normal turns while
    // the bodies pass and a contact made ahead would stop a body that was only grazing by. A
    // corner within the plain margin can still catch a grazing body, as in Box2D.
    for k in 0..50 {
        let start = -3.0 - 0.0123 * k as Real;
        for clearance in [0.025, 0.05, 0.2] {
            let boxed = graze(Shape::rect(0.5, 0.5), 0.5, clearance, start);
            let ball = graze(Shape::circle(0.5), 0.5, clearance, start);
            assert!(
                boxed < 1e-3 && ball < 1e-3,
                "start {start}, clearance {clearance}: box {boxed}, ball {ball}"
            );
        }
    }
}

#[test]
fn a_shot_stopped_at_a_free_plank_stays_on_its_side() {
    // A light 0.25 m ball at 300 m/s into a free 0.1 m plank (density 50), off its centre so
    // the plank turns away under it: stopped at the plank (swept as a bullet, or by the face's
    // contact made a step ahead), it must then stay on its side, pushing the plank along, not
    // drift through it over the next four seconds.
    for bullet in [true, false] {
        let (mut world, plank, shot) = shot_at_free_plank(bullet, 0.3);
        let deepest = deepest_overlap(&mut world, plank, shot, 240);
        let plank_speed = world.body(plank).unwrap().linear_velocity().x;
        assert!(
            deepest < 0.01,
            "bullet {bullet}: {deepest} m into the plank"
        );
        assert!(
            plank_speed > 2.0,
            "bullet {bullet}: the plank moves at {plank_speed} m/s"
        );
    }
}

#[test]
fn a_runners_fat_box_is_its_swept_box_without_the_margin() {
    // A body that outruns its fat box's margin looks for new pairs every step, so its tree box
    // is where its next step takes it and no wider; a slow body keeps the margin, so it need
    // not be looked at again while it creeps.
    let mut world = slick_world(Vec2::zeros());
    let fast = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).linear_velocity(vec2(30.0, 0.0)))
        .unwrap();
    let slow = world
        .add_body(
            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(0.0, 10.0))
                .linear_velocity(vec2(0.6, 0.0)),
        )
        .unwrap();
    for _ in 0..3 {
        world.step(DT).unwrap();
    }
    let boxes = |body: BodyHandle| {
        let collider = world.body(body).unwrap().colliders()[0];
        (
            world.broadphase().fat_aabb(collider).unwrap(),
            world.collider(collider).unwrap().aabb(),
        )
    };
    let (fat, tight) = boxes(fast);
    let ahead = 30.0 * DT;
    assert!(
        (fat.max.x - (tight.max.x + ahead)).abs() < 1e-3,
        "{fat:?} {tight:?}"
    );
    assert!((fat.min.x - tight.min.x).abs() < 1e-3, "{fat:?} {tight:?}");
    assert!((fat.max.y - tight.max.y).abs() < 1e-3, "{fat:?} {tight:?}");
    assert!((fat.min.y - tight.min.y).abs() < 1e-3, "{fat:?} {tight:?}");
    let (fat, tight) = boxes(slow);
    assert!(fat.max.y - tight.max.y > 0.04, "{fat:?} {tight:?}");
    assert!(tight.min.y - fat.min.y > 0.04, "{fat:?} {tight:?}");
}

/// Fires the circle of [`fire_at_wall`] straight at the wall with `threshold` as its sweep
/// threshold; returns how many times it was swept and how far past the wall it ended.
fn fire_with_threshold(threshold: Real) -> (usize, Real) {
    let mut world = world(true, Vec2::zeros());
    world
        .add_body(BodyDef::static_body(Shape::rect(0.05, 4.0)))
        .unwrap();
    let bullet = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(vec2(-10.0, 0.0))
                .linear_velocity(vec2(300.0, 0.0))
                .sweep_threshold(threshold),
        )
        .unwrap();
    let mut sweeps = 0;
    for _ in 0..30 {
        world.step(DT).unwrap();
        sweeps += world.stats().work.sweeps;
    }
    (sweeps, world.body(bullet).unwrap().position().x - 0.05)
}

#[test]
fn each_body_chooses_how_fast_it_must_be_to_be_swept() {
    // 5 m a step for a circle of radius 0.25 m (its smallest extent): swept at the default
    // threshold (half that), never at infinity, and still stopped then by its contact, which
    // looks a step ahead.
    let (swept, past) = fire_with_threshold(carom::SWEEP_THRESHOLD);
    assert!(swept > 0 && past < -0.3, "{swept} sweeps, {past} m past");
    let (swept, past) = fire_with_threshold(Real::INFINITY);
    assert_eq!(swept, 0);
    assert!(past < -0.3, "{past} m past");
    // A threshold above its motion in a step (20 × 0.25 m) leaves it unswept too.
    assert_eq!(fire_with_threshold(30.0).0, 0);
    // Bad thresholds are refused.
    let mut world = World::new();
    let bad = BodyDef::dynamic(Shape::circle(0.25)).sweep_threshold(-1.0);
    assert!(world.add_body(bad).is_err());
    let nan = BodyDef::dynamic(Shape::circle(0.25)).sweep_threshold(Real::NAN);
    assert!(world.add_body(nan).is_err());
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.25)))
        .unwrap();
    let mut body = world.body_mut(ball).unwrap();
    assert!(body.set_sweep_threshold(-0.5).is_err());
    body.set_sweep_threshold(2.0).unwrap();
    assert_eq!(world.body(ball).unwrap().sweep_threshold(), 2.0);
}

/// Five thin links hinged in a row, thrown flat at the ground at 30 m/s with direct joints:
/// continuous collision puts the links that would pass the ground back, and every link
/// hinged to them with them, so no hinge parts by more than 5 mm after any step (put back
/// alone, a link would part from the next by as far as the rest went on).
#[test]
fn continuous_collision_keeps_hinged_bodies_together() {
    let mut world = world(true, vec2(0.0, -10.0));
    world
        .update_settings(|s| s.solver.direct_joints = true)
        .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(20.0, 0.05)))
        .unwrap();
    let links: Vec<BodyHandle> = (0..5)
        .map(|i| {
            let def = BodyDef::dynamic(Shape::rect(0.25, 0.02))
                .position(vec2(i as Real * 0.5, 2.0))
                .angle(0.3)
                .linear_velocity(vec2(3.0, -30.0))
                .angular_velocity(if i % 2 == 0 { 4.0 } else { -4.0 });
            world.add_body(def).unwrap()
        })
        .collect();
    for pair in links.windows(2) {
        let at = world.body(pair[0]).unwrap().position() + vec2(0.25, 0.0);
        world
            .add_joint(JointDef::revolute(pair[0], pair[1], at))
            .unwrap();
    }
    let mut impacts = 0;
    for step in 0..60 {
        world.step(DT).unwrap();
        impacts += world.stats().continuous_impacts;
        for joint in world.joints() {
            let [a, b] = joint.bodies().map(|h| world.body(h).unwrap());
            let [at_a, at_b] = joint.world_anchors(a, b);
            let gap = (at_a - at_b).norm();
            assert!(gap < 0.005, "step {step}: a hinge parts by {gap} m");
        }
        for &link in &links {
            let y = world.body(link).unwrap().position().y;
            assert!(y > 0.0, "step {step}: a link passed the ground (y {y})");
        }
    }
    assert!(impacts > 0, "continuous collision never put a link back");
}
