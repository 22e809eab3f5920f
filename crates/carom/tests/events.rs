//! What a step reports besides motion, through the public interface: the impulses each contact
//! point applied, when contacts begin and end touching, hard hits, and what overlaps sensors.

use carom::{
    BodyDef, BodyHandle, ContactEvent, Effect, HitEvent, Real, SensorEvent, SensorOverlap, Shape,
    SolverKind, SolverParams, World, WorldSettings, vec2,
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
        .flat_map(|c| c.point_impulses());
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

/// Every sensor event of `steps` steps, with the step it came in.
fn sensor_events(world: &mut World, steps: usize) -> Vec<(usize, SensorEvent)> {
    let mut seen = Vec::new();
    for step in 0..steps {
        world.step(DT).unwrap();
        seen.extend(world.sensor_events().iter().map(|&e| (step, e)));
    }
    seen
}

#[test]
fn a_static_sensor_sees_a_ball_fall_through_and_never_touches_it() {
    let mut world = world_with(SolverKind::SoftStep);
    // A 4 x 1 m zone from y = 2.5 to 3.5.
    let zone = world
        .add_body(
            BodyDef::static_body(Shape::rect(2.0, 0.5))
                .position(vec2(0.0, 3.0))
                .sensor(true),
        )
        .unwrap();
    let sensor = world.body(zone).unwrap().colliders()[0];
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(0.5, 5.0)))
        .unwrap();
    let visitor = world.body(ball).unwrap().colliders()[0];
    let mut seen = Vec::new();
    for step in 0..120 {
        world.step(DT).unwrap();
        seen.extend(world.sensor_events().iter().map(|&e| (step, e)));
        assert!(
            world
                .contacts()
                .all(|c| c.collider_a() != sensor && c.collider_b() != sensor),
            "the sensor never pairs"
        );
        // While inside, the sensor lists the ball.
        let y = world.body(ball).unwrap().position().y;
        let inside = (2.25..=3.75).contains(&y);
        let listed = world.sensor_overlaps(sensor).unwrap();
        if (2.3..=3.7).contains(&y) {
            assert_eq!(listed.len(), 1, "at y = {y}");
            assert_eq!(listed[0].visitor, visitor);
        } else if !inside {
            assert!(listed.is_empty(), "at y = {y}");
        }
    }
    let expected = SensorOverlap {
        sensor,
        sensor_body: zone,
        visitor,
        visitor_body: ball,
    };
    let [
        (entered, SensorEvent::Begin(a)),
        (left, SensorEvent::End(b)),
    ] = seen[..]
    else {
        panic!("{seen:?}");
    };
    assert_eq!((a, b), (expected, expected));
    // Free fall from 5 m: the ball's bottom reaches 3.5 m after sqrt(2 × 1.25 / 10) = 0.5 s
    // and its top leaves 2.5 m after sqrt(2 × 2.75 / 10) = 0.74 s, undisturbed.
    assert!((29..=31).contains(&entered), "entered at step {entered}");
    assert!((43..=45).contains(&left), "left at step {left}");
    // It came to rest on the floor, not on the sensor.
    assert!((world.body(ball).unwrap().position().y - 0.25).abs() < 0.01);
}

#[test]
fn a_kinematic_sensor_sees_dynamic_bodies_and_not_static_ones() {
    let mut world = world_with(SolverKind::SoftStep);
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(0.0, 0.25)))
        .unwrap();
    let post = world
        .add_body(BodyDef::static_body(Shape::rect(0.1, 0.5)).position(vec2(2.0, 0.5)))
        .unwrap();
    // A sweeping 1 m blade from x = -3, at 4 m/s: over the ball at 0.5 s, the post at 1.25 s.
    let blade = world
        .add_body(
            BodyDef::kinematic(Shape::rect(0.5, 0.5))
                .position(vec2(-3.0, 0.5))
                .linear_velocity(vec2(4.0, 0.0))
                .sensor(true),
        )
        .unwrap();
    let seen = sensor_events(&mut world, 120);
    assert!(
        seen.iter()
            .all(|(_, e)| e.overlap().sensor_body == blade && e.overlap().visitor_body == ball),
        "{seen:?}"
    );
    assert!(matches!(
        seen[..],
        [(_, SensorEvent::Begin(_)), (_, SensorEvent::End(_))]
    ));
    // The ball did not move: the blade passed through it.
    assert!((world.body(ball).unwrap().position() - vec2(0.0, 0.25)).norm() < 1e-3);
    assert!(world.contains(post));
}

#[test]
fn a_dynamic_sensor_sees_the_static_floor_and_sensors_do_not_see_sensors() {
    let mut world = world_with(SolverKind::SoftStep);
    let floor = world.bodies().next().unwrap().handle();
    // A ball carrying a sensor ring around it, dropped through a static sensor zone onto the
    // floor.
    let zone = world
        .add_body(
            BodyDef::static_body(Shape::rect(2.0, 0.5))
                .position(vec2(0.0, 3.0))
                .sensor(true),
        )
        .unwrap();
    let ball = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .collider(carom::ColliderDef::new(Shape::circle(0.6)).sensor(true))
                .position(vec2(0.0, 5.0)),
        )
        .unwrap();
    let [solid, ring] = world.body(ball).unwrap().colliders()[..] else {
        panic!("two colliders");
    };
    let seen = sensor_events(&mut world, 120);
    let events: Vec<SensorEvent> = seen.iter().map(|&(_, e)| e).collect();
    let zone_sensor = world.body(zone).unwrap().colliders()[0];
    // The zone sees the solid ball pass, never the ring; the ring sees the floor (static) and
    // stays on it, never the zone nor its own body's ball.
    let of = |sensor, visitor| {
        events
            .iter()
            .filter(|e| e.overlap().sensor == sensor && e.overlap().visitor == visitor)
            .count()
    };
    assert_eq!(of(zone_sensor, solid), 2, "{events:?}");
    let floor_collider = world.body(floor).unwrap().colliders()[0];
    assert_eq!(of(ring, floor_collider), 1, "{events:?}");
    assert_eq!(events.len(), 3, "{events:?}");
    let listed = world.sensor_overlaps(ring).unwrap();
    assert_eq!(listed.len(), 1);
    assert_eq!(listed[0].visitor_body, floor);
}

#[test]
fn a_visitor_that_falls_asleep_inside_stays_seen() {
    let mut settings = WorldSettings::default();
    settings.effects.set(Effect::Sleeping, true);
    let mut world = World::with_settings(settings).unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let pad = world
        .add_body(
            BodyDef::static_body(Shape::rect(1.0, 0.1))
                .position(vec2(0.0, 0.1))
                .sensor(true),
        )
        .unwrap();
    let sensor = world.body(pad).unwrap().colliders()[0];
    let crate_box = world
        .add_body(BodyDef::dynamic(Shape::rect(0.25, 0.25)).position(vec2(0.0, 1.0)))
        .unwrap();
    let seen = sensor_events(&mut world, 240);
    assert!(world.body(crate_box).unwrap().is_sleeping(), "it sleeps");
    assert!(matches!(seen[..], [(_, SensorEvent::Begin(_))]), "{seen:?}");
    assert_eq!(world.sensor_overlaps(sensor).unwrap().len(), 1);
}

#[test]
fn removing_a_visitor_or_the_sensor_ends_the_overlap() {
    let mut world = world_with(SolverKind::SoftStep);
    let pad = world
        .add_body(
            BodyDef::static_body(Shape::rect(2.0, 0.5))
                .position(vec2(0.0, 0.5))
                .sensor(true),
        )
        .unwrap();
    let sensor = world.body(pad).unwrap().colliders()[0];
    let balls: Vec<BodyHandle> = [-1.0, 1.0]
        .iter()
        .map(|&x| {
            world
                .add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(x, 0.25)))
                .unwrap()
        })
        .collect();
    let seen = sensor_events(&mut world, 10);
    assert_eq!(seen.len(), 2, "{seen:?}");
    world.remove_body(balls[0]).unwrap();
    let seen = sensor_events(&mut world, 1);
    assert!(
        matches!(seen[..], [(_, SensorEvent::End(o))] if o.visitor_body == balls[0]),
        "{seen:?}"
    );
    world.remove_body(pad).unwrap();
    let seen = sensor_events(&mut world, 1);
    assert!(
        matches!(seen[..], [(_, SensorEvent::End(o))] if o.visitor_body == balls[1] && o.sensor == sensor),
        "{seen:?}"
    );
    assert!(world.sensor_events().len() == 1);
    assert!(matches!(
        world.sensor_overlaps(sensor),
        Err(carom::CaromError::StaleHandle { .. })
    ));
    let solid = world.body(balls[1]).unwrap().colliders()[0];
    assert!(matches!(
        world.sensor_overlaps(solid),
        Err(carom::CaromError::NotASensor { .. })
    ));
}

#[test]
fn the_collision_filter_applies_between_sensor_and_visitor() {
    let mut world = world_with(SolverKind::SoftStep);
    let ghosts = carom::CollisionFilter {
        category: 2,
        ..carom::CollisionFilter::DEFAULT
    };
    // The sensor ignores category 2.
    world
        .add_body(
            BodyDef::static_body(Shape::rect(2.0, 0.5))
                .position(vec2(0.0, 0.5))
                .sensor(true)
                .filter(carom::CollisionFilter {
                    mask: !2,
                    ..carom::CollisionFilter::DEFAULT
                }),
        )
        .unwrap();
    let ghost = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(vec2(-1.0, 0.25))
                .filter(ghosts),
        )
        .unwrap();
    let seen_ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(1.0, 0.25)))
        .unwrap();
    let seen = sensor_events(&mut world, 10);
    assert!(
        matches!(seen[..], [(_, SensorEvent::Begin(o))] if o.visitor_body == seen_ball),
        "{seen:?}"
    );
    assert!(world.contains(ghost));
}

#[test]
fn the_pre_solve_hook_drops_a_box_through_the_floor_and_brings_it_back() {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    let mut settings = WorldSettings::default();
    settings.effects.set(Effect::Sleeping, false);
    let mut world = World::with_settings(settings).unwrap();
    // A 2 m thick floor, top at y = 0, that opted in; beside it one that did not.
    world
        .add_body(
            BodyDef::static_body(Shape::rect(3.0, 1.0))
                .position(vec2(0.0, -1.0))
                .pre_solve(true),
        )
        .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(3.0, 1.0)).position(vec2(10.0, -1.0)))
        .unwrap();
    let crate_box = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5)))
        .unwrap();
    let bystander = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(10.0, 0.5)))
        .unwrap();
    let solid = Arc::new(AtomicBool::new(true));
    let strays = Arc::new(AtomicUsize::new(0));
    let (hook_solid, hook_strays) = (Arc::clone(&solid), Arc::clone(&strays));
    world.set_pre_solve(move |contact| {
        if contact.pair.body_b == bystander {
            hook_strays.fetch_add(1, Ordering::Relaxed);
        }
        contact.pair.body_b != crate_box || hook_solid.load(Ordering::Relaxed)
    });
    let floor_contact = |world: &World| {
        world
            .contacts()
            .find(|c| c.body_b() == crate_box)
            .map(|c| (*c.manifold(), c.is_touching()))
    };
    let mut events = Vec::new();
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    assert!((world.body(crate_box).unwrap().position().y - 0.5).abs() < 0.01);
    // Disabled for 15 steps: free fall into the floor, no points, no impulse.
    solid.store(false, Ordering::Relaxed);
    for _ in 0..15 {
        world.step(DT).unwrap();
        events.extend_from_slice(world.contact_events());
        let (manifold, touching) = floor_contact(&world).expect("the boxes still overlap");
        assert!(manifold.is_empty() && !touching);
    }
    let falling = world.body(crate_box).unwrap();
    assert!(
        (falling.linear_velocity().y + 10.0 * 15.0 * DT).abs() < 0.01,
        "free fall: {:?}",
        falling.linear_velocity()
    );
    assert!(
        falling.position().y < 0.25,
        "sunk in: {}",
        falling.position().y
    );
    // Solved again: pushed back out onto the top, where it rests.
    solid.store(true, Ordering::Relaxed);
    for _ in 0..120 {
        world.step(DT).unwrap();
        events.extend_from_slice(world.contact_events());
    }
    let back = world.body(crate_box).unwrap();
    assert!(
        (back.position().y - 0.5).abs() < 0.01,
        "{}",
        back.position().y
    );
    assert!(back.linear_velocity().norm() < 0.01);
    let floor_events: Vec<_> = events
        .iter()
        .filter(|e| e.pair().body_b == crate_box)
        .collect();
    assert!(
        matches!(
            floor_events[..],
            [ContactEvent::End(_), ContactEvent::Begin(_)]
        ),
        "{floor_events:?}"
    );
    // Only the contacts of colliders that opted in are shown to the hook.
    assert_eq!(strays.load(Ordering::Relaxed), 0);
    assert!(world.contacts().any(|c| c.body_b() == bystander));
}

#[test]
fn a_capsule_sensor_sweeping_past_a_rounded_box_a_segment_and_a_chain_sees_each_once() {
    use carom::{ChainDef, Polygon};
    let mut world = World::with_settings(WorldSettings {
        gravity: vec2(0.0, 0.0),
        ..WorldSettings::default()
    })
    .unwrap();
    let rounded = Shape::Polygon(Polygon::rect(0.3, 0.3).rounded(0.2));
    world
        .add_body(BodyDef::static_body(rounded).position(vec2(-4.0, 0.0)))
        .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::segment(
            vec2(0.0, -1.0),
            vec2(0.0, 1.0),
        )))
        .unwrap();
    // Two links meeting where the sensor passes; the sensor crosses them from behind as well,
    // which a sensor sees (overlap, not collision).
    let chain = ChainDef::open([vec2(4.0, -1.0), vec2(4.0, 0.0), vec2(4.0, 1.0)]);
    world
        .add_body(BodyDef::static_chain(&chain).unwrap())
        .unwrap();
    world
        .add_body(
            BodyDef::dynamic(Shape::capsule(vec2(-0.5, 0.0), vec2(0.5, 0.0), 0.3))
                .sensor(true)
                .position(vec2(-8.0, 0.0))
                .linear_velocity(vec2(10.0, 0.0)),
        )
        .unwrap();
    let seen = sensor_events(&mut world, 100);
    let begins: Vec<_> = seen
        .iter()
        .filter(|(_, e)| matches!(e, SensorEvent::Begin(_)))
        .collect();
    let ends = seen.len() - begins.len();
    assert_eq!((begins.len(), ends), (4, 4), "{seen:?}");
    // In the order it meets them: the rounded box, the segment, the chain's links together.
    let steps: Vec<usize> = begins.iter().map(|(step, _)| *step).collect();
    assert!(steps[0] < steps[1] && steps[1] < steps[2] && steps[2] == steps[3]);
    // The rounded box is met where its rounding begins: the capsule's front (x + 0.8) at
    // -4 - 0.5, about step 16 at 10 m/s from -8.
    assert!((15..=17).contains(&steps[0]), "{steps:?}");
}
