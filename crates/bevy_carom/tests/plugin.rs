//! The plugin in headless apps (Bevy's `MinimalPlugins`): spawning, changing and despawning
//! bodies, colliders and joints, messages, queries, scenes, and the same bits as plain carom.

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_carom::carom;
use bevy_carom::prelude::*;
use bevy_carom::{CaromBody, CaromCollider, LoadScene, QueryHit, SceneLoaded};

/// The time step, s. Bevy keeps its fixed timestep in whole nanoseconds: from the `f32` step
/// it rounds back to the same `f32`, where `Time::<Fixed>::from_hz(60.0)` would be an ulp off.
const DT: f32 = 1.0 / 60.0;

/// An app with the plugin whose every update is one fixed step of `DT`.
fn app() -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin, CaromPlugin))
        .insert_resource(Time::<Fixed>::from_seconds(DT as f64))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    app.finish();
    app.cleanup();
    app
}

/// Runs updates until the world has taken `n` more steps.
fn steps(app: &mut App, n: u64) {
    let end = app.world().resource::<CaromWorld>().step_count() + n;
    for _ in 0..n + 10 {
        if app.world().resource::<CaromWorld>().step_count() >= end {
            return;
        }
        app.update();
    }
    panic!("the world did not take {n} steps");
}

fn ground(app: &mut App) -> Entity {
    app.world_mut()
        .spawn((
            Collider::rectangle(40.0, 1.0),
            Transform::from_xyz(0.0, -0.5, 0.0),
        ))
        .id()
}

fn ball(app: &mut App, x: f32, y: f32) -> Entity {
    app.world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.5),
            Transform::from_xyz(x, y, 0.0),
        ))
        .id()
}

/// Steps `n` times, collecting the messages `M` written (Bevy drops them after two frames).
fn steps_collecting<M: Message + Clone>(app: &mut App, n: u64) -> Vec<M> {
    let mut all = Vec::new();
    for _ in 0..n {
        steps(app, 1);
        all.extend(messages::<M>(app));
    }
    all
}

fn messages<M: Message + Clone>(app: &mut App) -> Vec<M> {
    app.world_mut()
        .resource_mut::<Messages<M>>()
        .drain()
        .collect()
}

#[test]
fn a_ball_falls_onto_a_lone_collider_and_rests_there() {
    let mut app = app();
    let ground = ground(&mut app);
    let ball = ball(&mut app, 0.0, 4.0);
    steps(&mut app, 1);
    assert_eq!(
        app.world().get::<RigidBody>(ground),
        Some(&RigidBody::Static)
    );
    let y0 = app.world().get::<Transform>(ball).unwrap().translation.y;
    assert!(y0 < 4.0, "it fell in the first step: {y0}");
    assert!(app.world().get::<Velocity>(ball).unwrap().linear.y < 0.0);
    steps(&mut app, 180);
    let t = app.world().get::<Transform>(ball).unwrap();
    assert!(
        (t.translation.y - 0.5).abs() < 0.02,
        "rests on the ground: {}",
        t.translation.y
    );
    assert_eq!(app.world().resource::<CaromWorld>().world().body_count(), 2);
}

#[test]
fn despawning_removes_bodies_colliders_and_joints() {
    let mut app = app();
    ground(&mut app);
    let a = ball(&mut app, 0.0, 2.0);
    let b = ball(&mut app, 2.0, 2.0);
    let joint = app
        .world_mut()
        .spawn(Joint::distance(
            a,
            b,
            Vec2::new(0.0, 2.0),
            Vec2::new(2.0, 2.0),
        ))
        .id();
    steps(&mut app, 2);
    let world = app.world().resource::<CaromWorld>();
    assert_eq!(
        (world.world().body_count(), world.world().joint_count()),
        (3, 1)
    );
    let handle = app.world().get::<CaromBody>(a).unwrap().handle();

    app.world_mut().despawn(a);
    steps(&mut app, 1);
    let world = app.world().resource::<CaromWorld>();
    assert_eq!(
        (world.world().body_count(), world.world().joint_count()),
        (2, 0)
    );
    assert_eq!(world.body_entity(handle), None);
    assert_eq!(world.world().colliders().len(), 2);
    // The joint's entity keeps its Joint, waiting for its body; despawning it is clean too.
    assert!(app.world().get::<Joint>(joint).is_some());
    app.world_mut().despawn(joint);
    app.world_mut().entity_mut(b).remove::<Collider>();
    steps(&mut app, 1);
    let world = app.world().resource::<CaromWorld>();
    assert_eq!(world.world().colliders().len(), 1);
    assert!(app.world().get::<CaromCollider>(b).is_none());
}

#[test]
fn changed_components_reach_the_body() {
    let mut app = app();
    let body = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Collider::circle(0.5), GravityScale(0.0)))
        .id();
    steps(&mut app, 1);
    assert_eq!(
        app.world().get::<Transform>(body).unwrap().translation,
        Vec3::ZERO
    );

    app.world_mut().get_mut::<Velocity>(body).unwrap().linear = Vec2::new(6.0, 0.0);
    steps(&mut app, 10);
    let x = app.world().get::<Transform>(body).unwrap().translation.x;
    assert!((x - 1.0).abs() < 1e-3, "10 steps at 6 m/s: {x}");

    // A teleport, turned a quarter.
    *app.world_mut().get_mut::<Transform>(body).unwrap() =
        Transform::from_xyz(-5.0, 3.0, 0.0).with_rotation(Quat::from_rotation_z(1.0));
    steps(&mut app, 1);
    let world = app.world().resource::<CaromWorld>();
    let state = world
        .world()
        .body(world.entity_body(body).unwrap())
        .unwrap();
    assert!(
        (state.position().x + 5.0 - 0.1).abs() < 1e-3,
        "{}",
        state.position().x
    );
    assert!((state.angle() - 1.0).abs() < 1e-4);

    // Gravity back, heavier damping, and a new kind.
    app.world_mut().get_mut::<GravityScale>(body).unwrap().0 = 1.0;
    app.world_mut().get_mut::<Damping>(body).unwrap().linear = 2.0;
    steps(&mut app, 1);
    let world = app.world().resource::<CaromWorld>();
    let state = world
        .world()
        .body(world.entity_body(body).unwrap())
        .unwrap();
    assert_eq!((state.gravity_scale(), state.linear_damping()), (1.0, 2.0));
    assert!(app.world().get::<Velocity>(body).unwrap().linear.y < 0.0);
    app.world_mut().entity_mut(body).insert(RigidBody::Static);
    steps(&mut app, 1);
    let y = app.world().get::<Transform>(body).unwrap().translation.y;
    steps(&mut app, 5);
    assert_eq!(app.world().get::<Transform>(body).unwrap().translation.y, y);
}

/// How deep a ball thrown at 60 m/s sinks into a free block in a world without look-ahead:
/// the deepest overlap over the steps around the impact, m.
fn sinks_into_a_block(look_ahead: bool) -> f32 {
    let mut app = app();
    app.world_mut()
        .resource_mut::<CaromWorld>()
        .update_settings(|s| {
            s.look_ahead = false;
            s.gravity = carom::Vec2::zeros();
        })
        .unwrap();
    let block = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Collider::rectangle(1.0, 1.0)))
        .id();
    let ball = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.25),
            Transform::from_xyz(-3.1, 0.0, 0.0),
            Velocity {
                linear: Vec2::new(60.0, 0.0),
                angular: 0.0,
            },
        ))
        .id();
    if look_ahead {
        app.world_mut().entity_mut(ball).insert(LookAhead);
    }
    let mut deepest = 0.0f32;
    for _ in 0..5 {
        steps(&mut app, 1);
        let x = |e| app.world().get::<Transform>(e).unwrap().translation.x;
        deepest = deepest.max(0.75 - (x(block) - x(ball)));
    }
    let world = app.world().resource::<CaromWorld>();
    let handle = world.entity_body(ball).unwrap();
    assert_eq!(
        world.world().body(handle).unwrap().looks_ahead(),
        look_ahead
    );
    deepest
}

#[test]
fn a_look_ahead_body_stops_at_the_surface_in_a_world_without_look_ahead() {
    let (with, without) = (sinks_into_a_block(true), sinks_into_a_block(false));
    assert!(
        with < 0.01,
        "with look-ahead it stops at the face: {with} m in"
    );
    assert!(
        without > 0.3,
        "without, it sinks in for a step: {without} m in"
    );

    // Taken off, the body no longer looks ahead.
    let mut app = app();
    let ball = ball(&mut app, 0.0, 2.0);
    app.world_mut().entity_mut(ball).insert(LookAhead);
    steps(&mut app, 1);
    app.world_mut().entity_mut(ball).remove::<LookAhead>();
    steps(&mut app, 1);
    let world = app.world().resource::<CaromWorld>();
    let handle = world.entity_body(ball).unwrap();
    assert!(!world.world().body(handle).unwrap().looks_ahead());
}

#[test]
fn impulses_forces_and_child_colliders() {
    let mut app = app();
    let body = app
        .world_mut()
        .spawn((RigidBody::Dynamic, GravityScale(0.0)))
        .with_children(|children| {
            children.spawn((
                Collider::rectangle(1.0, 1.0),
                Transform::from_xyz(-1.0, 0.0, 0.0),
            ));
            children.spawn((
                Collider::rectangle(1.0, 1.0),
                Transform::from_xyz(1.0, 0.0, 0.0),
            ));
        })
        .id();
    steps(&mut app, 1);
    let world = app.world().resource::<CaromWorld>();
    let state = world
        .world()
        .body(world.entity_body(body).unwrap())
        .unwrap();
    assert_eq!(state.colliders().len(), 2);
    assert!(
        (state.mass() - 2.0).abs() < 1e-5,
        "two unit boxes: {}",
        state.mass()
    );

    app.world_mut().entity_mut(body).insert(ExternalImpulse {
        impulse: Vec2::new(4.0, 0.0),
        angular: 0.0,
    });
    steps(&mut app, 2);
    let v = app.world().get::<Velocity>(body).unwrap().linear;
    assert!((v.x - 2.0).abs() < 1e-4, "4 N·s on 2 kg, once: {v}");
    assert_eq!(
        app.world().get::<ExternalImpulse>(body).unwrap().impulse,
        Vec2::ZERO
    );

    app.world_mut().entity_mut(body).insert(ExternalForce {
        force: Vec2::new(0.0, 12.0),
        torque: 0.0,
    });
    steps(&mut app, 10);
    let v = app.world().get::<Velocity>(body).unwrap().linear;
    assert!((v.y - 1.0).abs() < 1e-3, "12 N on 2 kg for 1/6 s: {v}");
}

#[test]
fn contacts_sensors_hits_and_broken_joints_are_messages() {
    let mut app = app();
    let ground = ground(&mut app);
    app.world_mut().entity_mut(ground).insert(HitEvents);
    let sensor = app
        .world_mut()
        .spawn((
            Collider::rectangle(4.0, 1.0),
            Sensor,
            Transform::from_xyz(0.0, 3.0, 0.0),
        ))
        .id();
    let ball = ball(&mut app, 0.0, 6.0);
    let mut started = Vec::new();
    let (mut entered, mut exited, mut hits) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..120 {
        steps(&mut app, 1);
        started.extend(messages::<ContactStarted>(&mut app));
        entered.extend(messages::<SensorEntered>(&mut app));
        exited.extend(messages::<SensorExited>(&mut app));
        hits.extend(messages::<Hit>(&mut app));
    }
    assert_eq!(started.len(), 1, "{started:?}");
    let pair = [started[0].collider_a, started[0].collider_b];
    assert!(pair.contains(&ground) && pair.contains(&ball), "{pair:?}");
    assert_eq!(entered.len(), 1);
    assert_eq!((entered[0].sensor, entered[0].visitor), (sensor, ball));
    assert_eq!(exited.len(), 1);
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(
        hits[0].approach_speed > 5.0,
        "fell 5.5 m: {}",
        hits[0].approach_speed
    );

    // A rod between the ball and a static anchor that cannot hold 1 N.
    let anchor = app
        .world_mut()
        .spawn((Collider::circle(0.1), Transform::from_xyz(0.0, 1.5, 0.0)))
        .id();
    let joint = app
        .world_mut()
        .spawn(
            Joint::distance(anchor, ball, Vec2::new(0.0, 1.5), Vec2::new(0.0, 0.5))
                .with_break_limits(1.0, f32::INFINITY),
        )
        .id();
    app.world_mut().get_mut::<Velocity>(ball).unwrap().linear = Vec2::new(20.0, 0.0);
    let broken = steps_collecting::<JointBroken>(&mut app, 5);
    assert_eq!(broken.len(), 1);
    assert_eq!(broken[0].joint, joint);
    assert!(app.world().get::<Joint>(joint).is_none());
    assert_eq!(
        app.world().resource::<CaromWorld>().world().joint_count(),
        0
    );
}

/// A ray down, an overlap, a point, a shape cast and a ray that skips a body.
type Answers = (
    Option<QueryHit>,
    Vec<Entity>,
    Option<Entity>,
    Option<QueryHit>,
    Option<QueryHit>,
);

#[test]
fn queries_answer_in_entities() {
    let mut app = app();
    let ground = ground(&mut app);
    let ball = ball(&mut app, 3.0, 0.5);
    steps(&mut app, 1);
    let mut system = IntoSystem::into_system(move |query: CaromQuery| -> Answers {
        let down = query.cast_ray(
            Vec2::new(0.0, 5.0),
            Vec2::new(0.0, -10.0),
            QueryFilter::default(),
        );
        let near = query.overlap_aabb(
            Vec2::new(2.0, 0.0),
            Vec2::new(4.0, 2.0),
            QueryFilter::default(),
        );
        let at = query.body_at(Vec2::new(3.0, 0.5));
        let cast = query.cast_shape(
            &Collider::circle(0.25),
            Vec2::new(-3.0, 0.5),
            0.0,
            Vec2::new(10.0, 0.0),
            QueryFilter::default(),
        );
        let past = query.cast_ray(
            Vec2::new(3.0, 5.0),
            Vec2::new(0.0, -10.0),
            QueryFilter::excluding(ball),
        );
        (down, near, at, cast, past)
    });
    system.initialize(app.world_mut());
    let (down, near, at, cast, past) = system.run((), app.world_mut()).unwrap();
    let down = down.unwrap();
    assert_eq!((down.collider, down.body), (ground, ground));
    assert!(down.point.y.abs() < 1e-4 && down.normal.y > 0.99);
    assert!(near.contains(&ball) && near.contains(&ground), "{near:?}");
    assert_eq!(at, Some(ball));
    let cast = cast.unwrap();
    assert_eq!(cast.body, ball);
    assert!((cast.point.x - 2.5).abs() < 0.01, "{:?}", cast.point);
    assert_eq!(past.unwrap().body, ground, "the ball is excluded");
}

#[test]
fn bad_components_are_errors_and_are_tried_again_when_changed() {
    let mut app = app();
    let bad = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(-1.0),
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    let nan = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.5),
            Transform::from_xyz(f32::NAN, 0.0, 0.0),
        ))
        .id();
    let errors = steps_collecting::<PhysicsError>(&mut app, 3);
    assert_eq!(errors.len(), 2, "once each, not every step: {errors:?}");
    assert!(errors.iter().any(|e| e.entity == Some(bad)));
    assert!(errors.iter().any(|e| e.entity == Some(nan)));
    assert!(app.world().get::<CaromCollider>(bad).is_none());
    assert!(app.world().get::<CaromBody>(nan).is_none());

    *app.world_mut().get_mut::<Collider>(bad).unwrap() = Collider::circle(0.5);
    app.world_mut()
        .get_mut::<Transform>(nan)
        .unwrap()
        .translation
        .x = 3.0;
    assert!(steps_collecting::<PhysicsError>(&mut app, 2).is_empty());
    assert!(app.world().get::<CaromCollider>(bad).is_some());
    assert!(app.world().get::<CaromBody>(nan).is_some());
    assert_eq!(
        app.world()
            .resource::<CaromWorld>()
            .world()
            .colliders()
            .len(),
        2
    );
    assert!(
        app.world()
            .get::<Transform>(bad)
            .unwrap()
            .translation
            .is_finite()
    );
}

/// The pyramid recipe (demos/pyramid.ron): 20 boxes in the base on an 80 m floor.
fn pyramid_defs() -> Vec<carom::BodyDef> {
    let mut defs = vec![
        carom::BodyDef::static_body(carom::Shape::rect(40.0, 1.0)).position(carom::vec2(0.0, -1.0)),
    ];
    for row in 0..20 {
        for i in 0..20 - row {
            let x = (i as f32 - (19 - row) as f32 * 0.5) * 1.0;
            let y = 0.5 + row as f32;
            defs.push(
                carom::BodyDef::dynamic(carom::Shape::rect(0.5, 0.5)).position(carom::vec2(x, y)),
            );
        }
    }
    defs
}

#[test]
fn spawned_bodies_step_bit_for_bit_as_in_plain_carom() {
    let mut plain = carom::World::new();
    for def in pyramid_defs() {
        plain.add_body(def).unwrap();
    }
    let mut app = app();
    for def in pyramid_defs() {
        let kind = match def.kind {
            carom::BodyKind::Static => RigidBody::Static,
            _ => RigidBody::Dynamic,
        };
        let p = def.position;
        let (w, h) = if kind == RigidBody::Static {
            (80.0, 2.0)
        } else {
            (1.0, 1.0)
        };
        app.world_mut().spawn((
            kind,
            Collider::rectangle(w, h),
            Transform::from_xyz(p.x, p.y, 0.0),
        ));
    }
    for _ in 0..90 {
        plain.step(DT).unwrap();
    }
    steps(&mut app, 90);
    let hash = app.world().resource::<CaromWorld>().state_hash();
    assert_eq!(hash, plain.state_hash());
}

#[test]
fn a_scene_loads_as_entities_and_steps_as_the_scene_does() {
    let text = include_str!("../../../demos/pyramid.ron");
    let mut plain = carom_scene::build(
        &carom_scene::parse(text, "pyramid.ron").unwrap(),
        "pyramid.ron",
    )
    .unwrap();
    let mut app = app();
    let stale = ball(&mut app, 0.0, 50.0);
    steps(&mut app, 1);
    app.world_mut()
        .commands()
        .queue(LoadScene::new(text, "pyramid.ron"));
    app.world_mut().flush();
    let loaded = messages::<SceneLoaded>(&mut app);
    let entities = loaded[0].result.clone().unwrap();
    assert_eq!(entities.bodies.len(), 211);
    assert!(
        app.world().get_entity(stale).is_err(),
        "the old world's entities are gone"
    );
    assert_eq!(
        app.world().get::<RigidBody>(entities.bodies[0]),
        Some(&RigidBody::Static)
    );
    assert!(app.world().get::<Collider>(entities.bodies[1]).is_some());

    let before = app.world().resource::<CaromWorld>().step_count();
    steps(&mut app, 60);
    for _ in 0..60 {
        plain.step().unwrap();
    }
    assert_eq!(
        app.world().resource::<CaromWorld>().step_count(),
        before + 60
    );
    assert_eq!(
        app.world().resource::<CaromWorld>().state_hash(),
        plain.world.state_hash()
    );
    let top = *entities.bodies.last().unwrap();
    let y = app.world().get::<Transform>(top).unwrap().translation.y;
    assert!((y - 19.5).abs() < 0.05, "the top box stands: {y}");

    app.world_mut()
        .commands()
        .queue(LoadScene::new("(format: 2", "broken.ron"));
    app.world_mut().flush();
    let loaded = messages::<SceneLoaded>(&mut app);
    assert!(
        loaded[0]
            .result
            .as_ref()
            .is_err_and(|e| e.contains("broken.ron")),
        "{:?}",
        loaded[0].result
    );
    assert_eq!(
        app.world().resource::<CaromWorld>().world().body_count(),
        211
    );
}

#[test]
fn interpolated_bodies_are_drawn_between_their_last_two_steps() {
    // Steps of 20 ms and frames of 30 ms, both whole in nanoseconds: the overstep goes
    // 0.5, 0, 0.5, ...
    const DT: f32 = 0.02;
    let mut app = app();
    app.insert_resource(Time::<Fixed>::from_duration(
        std::time::Duration::from_millis(20),
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(
        std::time::Duration::from_millis(30),
    ));
    let moving = (
        Collider::circle(0.5),
        GravityScale(0.0),
        Velocity::linear(Vec2::new(6.0, 0.0)),
    );
    let drawn = app
        .world_mut()
        .spawn((RigidBody::Dynamic, Interpolated, moving.clone()))
        .id();
    let plain = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            moving,
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    let mut between = 0;
    for _ in 0..12 {
        app.update();
        let n = app.world().resource::<CaromWorld>().step_count() as f32;
        let overstep = app.world().resource::<Time<Fixed>>().overstep_fraction();
        let x = app.world().get::<Transform>(drawn).unwrap().translation.x;
        let stepped = app.world().get::<Transform>(plain).unwrap().translation.x;
        assert!(
            (stepped - 6.0 * n * DT).abs() < 1e-4,
            "the step is not disturbed: {stepped}"
        );
        if n >= 2.0 {
            let expected = 6.0 * (n - 1.0 + overstep) * DT;
            assert!(
                (x - expected).abs() < 1e-4,
                "{x} against {expected} ({n} steps, {overstep})"
            );
            if overstep == 0.5 {
                between += 1;
                assert!(
                    x > stepped - 6.0 * DT && x < stepped,
                    "{x} {stepped} {n} {overstep}"
                );
            }
        }
    }
    assert!(between >= 4, "frames drawn between steps: {between}");
}

#[test]
fn a_kinematic_body_moves_to_a_set_transform_and_stops_there() {
    let mut app = app();
    let lift = app
        .world_mut()
        .spawn((RigidBody::Kinematic, Collider::rectangle(2.0, 0.5)))
        .id();
    let rider = ball(&mut app, 0.0, 0.75);
    steps(&mut app, 30);
    app.world_mut()
        .get_mut::<Transform>(lift)
        .unwrap()
        .translation
        .y = 0.5;
    steps(&mut app, 1);
    let y = |app: &App, e| app.world().get::<Transform>(e).unwrap().translation.y;
    assert!(
        (y(&app, lift) - 0.5).abs() < 1e-4,
        "moved there in one step: {}",
        y(&app, lift)
    );
    assert!(app.world().get::<Velocity>(lift).unwrap().linear.y > 20.0);
    steps(&mut app, 30);
    assert!(
        (y(&app, lift) - 0.5).abs() < 1e-4,
        "and stayed: {}",
        y(&app, lift)
    );
    assert_eq!(
        app.world().get::<Velocity>(lift).unwrap().linear,
        Vec2::ZERO
    );
    assert!(
        y(&app, rider) > 1.2,
        "the lift pushed the ball up: {}",
        y(&app, rider)
    );
}

#[test]
fn a_teleported_interpolated_body_is_drawn_where_it_was_sent() {
    let mut app = app();
    let body = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::circle(0.5),
            GravityScale(0.0),
            Interpolated,
        ))
        .id();
    steps(&mut app, 3);
    app.world_mut()
        .get_mut::<Transform>(body)
        .unwrap()
        .translation
        .x = 5.0;
    steps(&mut app, 1);
    // Every update is exactly one step, so it is drawn at its pose before the step: where it
    // was sent, not where it came from.
    let x = app.world().get::<Transform>(body).unwrap().translation.x;
    assert!((x - 5.0).abs() < 1e-5, "{x}");
}

/// Room made ahead of time is what the world then reports as its high water, and changes no
/// bit of the run.
#[test]
fn room_made_ahead_of_time_changes_nothing() {
    let run = |reserve: bool| {
        let mut app = app();
        if reserve {
            let capacity = carom::Capacity {
                bodies: 64,
                colliders: 64,
                contacts: 256,
                joints: 0,
            };
            let mut world = app.world_mut().resource_mut::<CaromWorld>();
            world.reserve(capacity).unwrap();
        }
        ground(&mut app);
        for i in 0..8 {
            ball(&mut app, 0.1 * i as f32, 1.0 + 1.1 * i as f32);
        }
        steps(&mut app, 60);
        let world = app.world().resource::<CaromWorld>();
        (world.state_hash(), world.world().high_water())
    };
    let (plain, plain_high) = run(false);
    let (reserved, reserved_high) = run(true);
    assert_eq!(reserved, plain, "the same bits with room made");
    assert!(
        plain_high.bodies >= 8 && plain_high.contacts >= 8,
        "{plain_high:?}"
    );
    let counts = |c: carom::Capacity| (c.bodies, c.colliders, c.contacts, c.joints);
    assert_eq!(counts(reserved_high), (64, 64, 256, 0));
}
