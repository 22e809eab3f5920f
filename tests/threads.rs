//! Stepping on several threads changes nothing but the time: a world stepped on one, two or
//! three threads ends in exactly the same state, bit for bit.

use carom::{
    BodyDef, Effect, Effects, Shape, SolverKind, SolverParams, World, WorldSettings, vec2,
};

/// A pyramid of 92 in the base (4278 boxes, about 12,700 contacts: enough that the
/// narrowphase, the solver's per-body work and its graph colours are all shared among threads)
/// and circles and triangles tumbling beside it.
fn busy_world(solver: SolverKind) -> World {
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
                        .friction(0.6),
                )
                .unwrap();
        }
    }
    let mut rng = carom_tests::Rng::new(7);
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
            .add_body(BodyDef::dynamic(shape).position(position).restitution(0.3))
            .unwrap();
    }
    world
}

fn final_hash(solver: SolverKind, threads: usize) -> u64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut world = busy_world(solver);
        for _ in 0..60 {
            world.step(1.0 / 60.0).unwrap();
        }
        world.state_hash()
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
