//! Stepping on several threads changes nothing but the time: a world stepped on one, two or
//! three threads ends in exactly the same state, bit for bit, also while islands fall asleep
//! and wake, and while a pre-solve hook, called from the narrowphase's threads, disables
//! contacts.

use carom::{
    BodyDef, Effect, Effects, JointDef, Shape, SolverKind, SolverParams, World, WorldSettings, vec2,
};

/// A pyramid of 92 in the base (4278 boxes, about 12,700 contacts: enough that the
/// narrowphase, the solver's per-body work and its graph colours are all shared among threads)
/// and circles and triangles tumbling beside it; every collider shows its contacts to the
/// pre-solve hook if `pre_solve`.
fn busy_world(solver: SolverKind, pre_solve: bool) -> World {
    let settings = WorldSettings {
        solver: SolverParams::for_kind(solver),
        effects: Effects::ALL.without(Effect::Sleeping),
        ..WorldSettings::default()
    };
    let mut world = World::with_settings(settings).unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(120.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    for row in 0..92 {
        for column in 0..92 - row {
            let x = column as f32 - (91 - row) as f32 * 0.5;
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(x, row as f32 + 0.5))
                        .friction(0.6)
                        .pre_solve(pre_solve),
                )
                .unwrap();
        }
    }
    let mut rng = carom_bench::cases::Rng::new(7);
    for i in 0..200 {
        let shape = if i % 2 == 0 {
            Shape::circle(rng.range(0.1, 0.4))
        } else {
            Shape::regular(3, rng.range(0.2, 0.5)).unwrap()
        };
        // Beside the pyramid, either side, tumbling onto the ground and each other.
        let side = if i % 4 < 2 { -1.0 } else { 1.0 };
        let position = vec2(side * rng.range(48.0, 58.0), rng.range(0.5, 8.0));
        world
            .add_body(
                BodyDef::dynamic(shape)
                    .position(position)
                    .restitution(0.3)
                    .pre_solve(pre_solve),
            )
            .unwrap();
    }
    world
}

fn final_hash(solver: SolverKind, threads: usize) -> u64 {
    carom_tests::on_threads(threads, || {
        let mut world = busy_world(solver, false);
        for _ in 0..60 {
            world.step(1.0 / 60.0).unwrap();
        }
        world.state_hash()
    })
}

/// With sleeping on, 60 small pyramids (2160 boxes) fall asleep island by island (out of the
/// awake set, their contacts out of the colours); then a ball dropped on one wakes it.
fn final_hash_with_sleep(threads: usize) -> (u64, usize, usize) {
    carom_tests::on_threads(threads, || {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(400.0, 1.0)).position(vec2(0.0, -1.0)))
            .unwrap();
        for pyramid in 0..60 {
            let left = pyramid as f32 * 12.0 - 360.0;
            for row in 0..8 {
                for column in 0..8 - row {
                    let x = left + column as f32 + 0.5 * row as f32;
                    world
                        .add_body(
                            BodyDef::dynamic(Shape::rect(0.5, 0.5))
                                .position(vec2(x, row as f32 + 0.5)),
                        )
                        .unwrap();
                }
            }
        }
        let (mut slept, mut after_drop) = (0, usize::MAX);
        for step in 0..300 {
            if step == 180 {
                let ball = BodyDef::dynamic(Shape::circle(0.5))
                    .position(vec2(3.5, 12.0))
                    .linear_velocity(vec2(0.0, -10.0));
                world.add_body(ball).unwrap();
            }
            world.step(1.0 / 60.0).unwrap();
            slept = slept.max(world.stats().sleeping_bodies);
            if step > 180 {
                after_drop = after_drop.min(world.stats().sleeping_bodies);
            }
        }
        (world.state_hash(), slept, after_drop)
    })
}

#[test]
fn every_thread_count_gives_the_same_world() {
    for solver in [SolverKind::SoftStep, SolverKind::SequentialImpulse] {
        let one = final_hash(solver, 1);
        for threads in [2, 3] {
            assert_eq!(
                final_hash(solver, threads),
                one,
                "{} on {threads} threads differs from one thread",
                solver.name()
            );
        }
    }
}

/// The busy world with a pre-solve hook that disables one contact in five, by a rule of the
/// pair alone, so the pyramid crumbles: the same world on every thread count.
#[test]
fn a_pre_solve_hook_gives_the_same_world_on_every_thread_count() {
    let run = |threads: usize| {
        carom_tests::on_threads(threads, || {
            let mut world = busy_world(SolverKind::SoftStep, true);
            world.set_pre_solve(|contact| {
                let pair = contact.pair;
                (pair.collider_a.index() ^ pair.collider_b.index()) % 5 != 0
            });
            for _ in 0..60 {
                world.step(1.0 / 60.0).unwrap();
            }
            world.state_hash()
        })
    };
    let one = run(1);
    assert_ne!(
        one,
        final_hash(SolverKind::SoftStep, 1),
        "the hook disables contacts"
    );
    for threads in [2, 3] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}

#[test]
fn sleeping_and_waking_give_the_same_world_on_every_thread_count() {
    let (one, slept, after_drop) = final_hash_with_sleep(1);
    assert!(slept >= 2160, "every pyramid fell asleep ({slept} bodies)");
    assert!(
        after_drop < 2160,
        "the ball woke a pyramid ({after_drop} still asleep)"
    );
    for threads in [2, 3] {
        assert_eq!(final_hash_with_sleep(threads).0, one, "{threads} threads");
    }
}

/// A 40 x 40 grid of circles joined to their neighbours by hinges, hung from its top row
/// (3120 joints: enough that soft step shares its joint colours among threads), swinging and
/// falling: the same world on every thread count.
#[test]
fn joints_give_the_same_world_on_every_thread_count() {
    let run = |threads: usize| {
        carom_tests::on_threads(threads, || {
            let mut world = World::new();
            let n = 40;
            carom_tests::hanging_grid(&mut world, vec2(0.0, 0.0), n);
            for _ in 0..60 {
                world.step(1.0 / 60.0).unwrap();
            }
            assert_eq!(world.stats().joints, 2 * n * (n - 1));
            world.state_hash()
        })
    };
    let one = run(1);
    assert_eq!(run(2), one);
    assert_eq!(run(3), one);
}

/// Forty chains of forty links, each holding a ball and swinging, every other hinge limited
/// to ±0.4 rad, with direct joints (1640 hinges: their trees solved at once with the limits
/// that hold, beside the threads that share the other joints' colours): the same world on
/// every thread count.
#[test]
fn direct_joints_give_the_same_world_on_every_thread_count() {
    let run = |threads: usize| {
        carom_tests::on_threads(threads, || {
            let mut world = World::new();
            world
                .update_settings(|s| s.solver.direct_joints = true)
                .unwrap();
            for chain in 0..40 {
                let top = vec2(3.0 * chain as f32, 0.0);
                let hook = world
                    .add_body(BodyDef::static_body(Shape::rect(0.1, 0.1)).position(top))
                    .unwrap();
                let mut above = hook;
                for link in 0..41 {
                    // Each chain leans out by its own angle; the last link is a ball.
                    let lean = vec2(0.3 + 0.01 * chain as f32, -1.0).normalize();
                    let at = top + lean * (0.5 * link as f32 + 0.25);
                    let shape = if link == 40 {
                        Shape::circle(0.3)
                    } else {
                        Shape::rect(0.05, 0.25)
                    };
                    let body = world
                        .add_body(BodyDef::dynamic(shape).position(at))
                        .unwrap();
                    let mut hinge = JointDef::revolute(above, body, top + lean * 0.5 * link as f32);
                    if link % 2 == 1 {
                        hinge = hinge.limits(-0.4, 0.4);
                    }
                    world.add_joint(hinge).unwrap();
                    above = body;
                }
            }
            for _ in 0..60 {
                world.step(1.0 / 60.0).unwrap();
            }
            world.state_hash()
        })
    };
    let one = run(1);
    assert_eq!(run(2), one);
    assert_eq!(run(3), one);
}

/// The busy pyramid with shock propagation (every contact between two rows solved once more
/// from the ground up, on one thread, beside the colours shared among threads): the same world
/// on every thread count.
#[test]
fn shock_propagation_gives_the_same_world_on_every_thread_count() {
    let run = |threads: usize| {
        carom_tests::on_threads(threads, || {
            let mut world = busy_world(SolverKind::SoftStep, false);
            world
                .update_settings(|s| s.solver.shock_propagation = true)
                .unwrap();
            for _ in 0..60 {
                world.step(1.0 / 60.0).unwrap();
            }
            world.state_hash()
        })
    };
    let one = run(1);
    assert_eq!(run(2), one);
    assert_eq!(run(3), one);
}

/// 300 dynamic walkers, each walked by a mover joint and held up by a pogo leg (600 joints:
/// two colours of 300, each shared among threads), in two crowds walking into each other:
/// the same world on every thread count.
#[test]
fn walkers_give_the_same_world_on_every_thread_count() {
    let run = |threads: usize| {
        carom_tests::on_threads(threads, || {
            let mut world = World::new();
            let ground = world
                .add_body(BodyDef::static_body(Shape::rect(400.0, 0.5)).position(vec2(0.0, -0.5)))
                .unwrap();
            for i in 0..300 {
                let x = (i as f32 - 150.0) * 1.1;
                let body = world
                    .add_body(
                        BodyDef::dynamic(Shape::rect(0.5, 0.5))
                            .position(vec2(x, 1.5 + 0.01 * (i % 7) as f32))
                            .friction(0.0)
                            .fixed_rotation(true),
                    )
                    .unwrap();
                let speed = if x < 0.0 { 2.0 } else { -1.5 };
                world
                    .add_joint(JointDef::mover(
                        ground,
                        body,
                        vec2(speed, 0.0),
                        vec2(30.0, 0.0),
                    ))
                    .unwrap();
                world
                    .add_joint(JointDef::pogo(
                        ground,
                        body,
                        vec2(x, 0.0),
                        vec2(x, 1.0),
                        vec2(0.0, 1.0),
                        0.9,
                        (1000.0, 1000.0),
                    ))
                    .unwrap();
            }
            for _ in 0..120 {
                world.step(1.0 / 60.0).unwrap();
            }
            assert_eq!(world.stats().joints, 600);
            world.state_hash()
        })
    };
    let one = run(1);
    assert_eq!(run(2), one);
    assert_eq!(run(3), one);
}
