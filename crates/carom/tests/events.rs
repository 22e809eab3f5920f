//! What a step reports besides motion, through the public interface: the impulses each contact
//! point applied.

use carom::{
    BodyDef, BodyHandle, ContactEvent, Effect, HitEvent, Real, Shape, SolverKind, SolverParams,
    World, WorldSettings, vec2,
};

const DT: Real = 1.0 / 60.0;

/// A world with gravity (0, -10), sleeping off so resting bodies stay solved, the given solver
/// at its defaults, and a static floor whose top is y = 0.
fn world_with(kind: SolverKind) -> World {
    let mut settings = WorldSettings {
        solver: SolverParams::for_kind(kind),
        ..WorldSettings::default()
    };
    settings.effects.set(Effect::Sleeping, false);
    let mut world = World::with_settings(settings).unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    world
}

/// The sum over `body`'s contact points of what the last step applied there, total and most
/// in one substep.
fn impulses_on(world: &World, body: BodyHandle) -> (Real, Real) {
    let points = world
        .contacts()
        .filter(|c| c.body_a() == body || c.body_b() == body)
        .flat_map(|c| c.manifold().points());
    points.fold((0.0, 0.0), |(total, max), p| {
        (total + p.total_normal_impulse, max + p.max_normal_impulse)
    })
}

#[test]
fn a_resting_box_reports_its_weight_as_the_step_impulse_in_both_solvers() {
    for (kind, substeps) in [
        (SolverKind::SoftStep, 4.0),
        (SolverKind::SequentialImpulse, 1.0),
    ] {
        let mut world = world_with(kind);
        // 1 m x 1 m at density 2: 2 kg.
        let crate_box = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .position(vec2(0.0, 0.5))
                    .density(2.0),
            )
            .unwrap();
        let weight_impulse = 2.0 * 10.0 * DT;
        for step in 0..180 {
            world.step(DT).unwrap();
            if step < 60 {
                continue;
            }
            let (total, max) = impulses_on(&world, crate_box);
            assert!(
                (total - weight_impulse).abs() < 0.01 * weight_impulse,
                "{kind:?} step {step}: {total} N·s for a weight of {weight_impulse}"
            );
            // Soft step starts each substep over from the accumulated impulse, so a substep
            // holds a quarter of the step's; the classic solvers' step is its one substep.
            let per_substep = weight_impulse / substeps;
            assert!(
                (max - per_substep).abs() < 0.05 * per_substep,
                "{kind:?} step {step}: {max} N·s at most in a substep, expected {per_substep}"
            );
        }
        // Force is impulse over time: the box's weight.
        let floor_contact = world.contacts().find(|c| c.body_b() == crate_box).unwrap();
        let force = floor_contact.total_normal_impulse() / DT;
        assert!((force - 20.0).abs() < 0.2, "{kind:?}: {force} N");
    }
}

#[test]
fn a_dropped_ball_begins_touching_on_impact_not_within_the_margin_and_ends_when_lifted() {
    for kind in [SolverKind::SoftStep, SolverKind::SequentialImpulse] {
        let mut world = world_with(kind);
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 3.0)))
            .unwrap();
        let closest = |world: &World| {
            world
                .contacts()
                .find(|c| c.body_b() == ball)
                .and_then(|c| c.manifold().min_separation())
        };
        let (mut speculative_steps, mut begin_step) = (0, None);
        for step in 0..240 {
            world.step(DT).unwrap();
            let events = world.contact_events();
            match begin_step {
                None => {
                    assert!(
                        events.iter().all(|e| matches!(e, ContactEvent::Begin(_))),
                        "{kind:?}: {events:?} before the impact"
                    );
                    if events.is_empty() {
                        // Points within the speculative margin, apart: no event yet.
                        if closest(&world).is_some_and(|s| s > 0.0) {
                            speculative_steps += 1;
                        }
                    } else {
                        assert_eq!(events.len(), 1, "{kind:?}");
                        let s = closest(&world).unwrap();
                        assert!(s <= 0.0005, "{kind:?}: began {s} m apart");
                        begin_step = Some(step);
                    }
                }
                // Resting for the rest of the 4 s: no flicker.
                Some(_) => assert!(events.is_empty(), "{kind:?} step {step}: {events:?}"),
            }
        }
        let begin_step = begin_step.expect("the ball lands");
        assert!(speculative_steps >= 1, "{kind:?}: never speculative");
        assert!(begin_step < 60, "{kind:?}: landed at step {begin_step}");
        let contact = world.contacts().find(|c| c.body_b() == ball).unwrap();
        assert!(contact.is_touching());
        // Thrown up gently (5 cm high, 0.2 s there and back): the contact ends while the pair is
        // still within the fat margin, and begins again as the ball lands.
        world
            .body_mut(ball)
            .unwrap()
            .set_linear_velocity(vec2(0.0, 1.0))
            .unwrap();
        let mut seen = Vec::new();
        for step in 0..60 {
            world.step(DT).unwrap();
            seen.extend(world.contact_events().iter().map(|&e| (step, e)));
        }
        let [
            (ended, ContactEvent::End(a)),
            (landed, ContactEvent::Begin(b)),
        ] = seen[..]
        else {
            panic!("{kind:?}: {seen:?}");
        };
        assert!(a.body_b == ball && b.body_b == ball);
        // Over the slop (5 mm) at 1 m/s: within the first steps.
        assert!(ended <= 2, "{kind:?}: ended at step {ended}");
        assert!(
            (10..=16).contains(&landed),
            "{kind:?}: landed at step {landed}"
        );
    }
}

#[test]
fn a_rolling_hexagon_touches_once_though_it_hops_from_corner_to_corner() {
    let mut world = world_with(SolverKind::SoftStep);
    let hexagon = Shape::regular(6, 0.5).unwrap();
    world
        .add_body(
            BodyDef::dynamic(hexagon)
                .position(vec2(-8.0, 0.5))
                .angular_velocity(-6.0),
        )
        .unwrap();
    let mut events = Vec::new();
    for _ in 0..240 {
        world.step(DT).unwrap();
        events.extend_from_slice(world.contact_events());
    }
    // Rolling over a corner lifts it up to about a millimetre off the floor now and then:
    // within the slop, so the contact goes on (with the begin tolerance alone it ends and
    // begins again three times).
    assert!(matches!(events[..], [ContactEvent::Begin(_)]), "{events:?}");
}

/// The hits a ball of radius 0.5 dropped from `height` (its bottom above the floor) reports in
/// 2 s, asking for them or not; and the world.
fn drop_ball(height: Real, asks: bool, restitution: Real) -> (Vec<HitEvent>, World) {
    let mut world = world_with(SolverKind::SoftStep);
    world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.5))
                .position(vec2(0.3, 0.5 + height))
                .restitution(restitution)
                .hit_events(asks),
        )
        .unwrap();
    let mut hits = Vec::new();
    for _ in 0..120 {
        world.step(DT).unwrap();
        hits.extend_from_slice(world.hit_events());
    }
    (hits, world)
}

#[test]
fn a_ball_dropped_from_5_m_reports_one_hit_at_the_impact_speed() {
    let (hits, world) = drop_ball(5.0, true, 0.0);
    let [hit] = hits[..] else {
        panic!("{hits:?}");
    };
    // v = sqrt(2 g h), less what gravity adds in the step it is stopped (g dt, 1.7 %).
    let expected = (2.0 * 10.0 * 5.0 as Real).sqrt();
    assert!(
        (hit.approach_speed - expected).abs() < 0.03 * expected,
        "{} m/s, expected {expected}",
        hit.approach_speed
    );
    // The floor was added first: the normal points from it to the ball, up.
    assert!(
        (hit.normal - vec2(0.0, 1.0)).norm() < 1e-5,
        "{:?}",
        hit.normal
    );
    assert!(
        (hit.point - vec2(0.3, 0.0)).norm() < 1e-3,
        "{:?}",
        hit.point
    );
    let ball = world.bodies().last().unwrap().handle();
    assert_eq!(hit.pair.body_b, ball);
    // Dropped from 2 cm (0.63 m/s, below the 1 m/s threshold): nothing.
    assert!(drop_ball(0.02, true, 0.0).0.is_empty());
    // Not asked for: nothing.
    assert!(drop_ball(5.0, false, 0.0).0.is_empty());
    // A bouncing ball reports each bounce faster than the threshold, each slower than the last.
    let (bounces, _) = drop_ball(1.0, true, 0.8);
    assert!(bounces.len() >= 3, "{bounces:?}");
    assert!(
        bounces
            .windows(2)
            .all(|w| w[1].approach_speed < w[0].approach_speed && w[1].approach_speed > 1.0)
    );
}
