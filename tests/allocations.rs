//! A world in steady state steps without touching the heap: every stage keeps its memory from
//! step to step, on Box2D's eight benchmark recipes too; and a snapshot's count of the heap it
//! holds is what taking it allocated. A growing buffer's reallocation counts as one.
//! Counted by an instrumented global allocator, so this file holds one test (the count is
//! process-wide) and runs it from its own `main`, without libtest, whose timing thread
//! allocates to warn of a test that runs past a minute.

use carom::{BodyDef, Capacity, Effect, Effects, Shape, Snapshot, World, WorldSettings, vec2};
use carom_scene::SceneWorld;
use rayon::{ThreadPool, ThreadPoolBuilder};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, Stats, StatsAlloc};
use std::alloc::System;

#[global_allocator]
static ALLOCATOR: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// A pyramid of `base` boxes with circles resting beside it, every effect in `effects`.
fn pyramid(base: usize, effects: Effects) -> World {
    let settings = WorldSettings {
        effects,
        ..WorldSettings::default()
    };
    let mut world = World::with_settings(settings).unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(200.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    for row in 0..base {
        for column in 0..base - row {
            let x = column as f32 - (base - row - 1) as f32 * 0.5;
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(x, row as f32 + 0.5))
                        .friction(0.6)
                        .damping(0.1, 0.1),
                )
                .unwrap();
        }
    }
    for i in 0..20 {
        let x = base as f32 * 0.5 + 2.0 + i as f32;
        world
            .add_body(
                BodyDef::dynamic(Shape::circle(0.4))
                    .position(vec2(x, 0.4))
                    .restitution(0.5),
            )
            .unwrap();
    }
    world
}

/// A 30 x 30 grid of circles joined to their neighbours by hinges and hung from its two top
/// corners, swinging (1740 joints: soft step shares its joint colours among threads), beside
/// the same pyramid of 20.
fn hanging_grid(effects: Effects) -> World {
    let mut world = pyramid(20, effects);
    carom_tests::hanging_grid(&mut world, vec2(40.0, 40.0), 30);
    world
}

/// Circles, capsules and boxes in turn, flying fast enough for continuous collision to sweep
/// every one of them each step (gravity off, nothing in their way).
fn fast_mixed_shapes() -> World {
    let settings = WorldSettings {
        effects: Effects::ALL
            .without(Effect::Sleeping)
            .without(Effect::Gravity),
        ..WorldSettings::default()
    };
    let mut world = World::with_settings(settings).unwrap();
    let shapes = [
        Shape::circle(0.25),
        Shape::capsule(vec2(-0.25, 0.0), vec2(0.25, 0.0), 0.2),
        Shape::rect(0.25, 0.25),
    ];
    for i in 0..30 {
        world
            .add_body(
                BodyDef::dynamic(shapes[i % 3].clone())
                    .position(vec2(0.0, 2.0 * i as f32))
                    .linear_velocity(vec2(60.0, 0.0)),
            )
            .unwrap();
    }
    world
}

/// `world` with soft step's shock propagation on.
fn with_shock_propagation(mut world: World) -> World {
    world
        .update_settings(|s| s.solver.shock_propagation = true)
        .unwrap();
    world
}

/// The ragdolls scene with direct joints: twenty ragdolls in a pile, their hinge trees
/// solved with the limits that hold.
fn ragdolls_with_direct_joints() -> World {
    let path = carom_bench::cases::worlds::workspace().join("demos/ragdolls.ron");
    let mut world = carom_scene::load(&path).unwrap().world;
    world
        .update_settings(|s| s.solver.direct_joints = true)
        .unwrap();
    world
}

/// Allocations over `steps` steps of `world` after `warm_up` steps, on `pool`'s threads.
fn allocations(mut world: World, pool: &ThreadPool, warm_up: usize, steps: usize) -> usize {
    pool.install(|| {
        for _ in 0..warm_up {
            world.step(1.0 / 60.0).unwrap();
        }
        let region = Region::new(&INSTRUMENTED_SYSTEM);
        for _ in 0..steps {
            world.step(1.0 / 60.0).unwrap();
        }
        heap_calls(region.change())
    })
}

/// Calls that took memory from the heap: new blocks, and blocks grown or moved.
fn heap_calls(change: Stats) -> usize {
    change.allocations + change.reallocations
}

/// Box2D's benchmark recipes, as the speed comparison runs them.
const RECIPES: [&str; 8] = [
    "joint_grid",
    "large_pyramid",
    "many_pyramids",
    "tumbler",
    "smash",
    "compounds",
    "ragdoll_rain",
    "spinner",
];

/// The recipes whose every buffer has grown to its high by step 100: nothing they hold grows
/// after (the pyramids settled, the tumbler and the spinner stirring a set of bodies that
/// neither grows nor comes to rest, which makes new pairs every step), so even their first
/// pass from step 100 takes nothing from the heap. The others still gain contacts, woken
/// bodies or fast bodies then, and grow a buffer to a new high now and again.
const STEADY_BY_STEP_100: [&str; 4] = ["large_pyramid", "many_pyramids", "tumbler", "spinner"];

/// One of [`RECIPES`], as its scene file makes it.
fn recipe(name: &str) -> SceneWorld {
    let path = carom_bench::cases::worlds::workspace().join(format!("demos/{name}.ron"));
    let mut scene = carom_scene::load(&path).unwrap();
    scene.time_step = 1.0 / 60.0;
    scene
}

/// The heap calls of `scene`'s world steps `from..to`, its events having fired up to `from`
/// (so the second pass is the first again): the first pass, then a second from a snapshot
/// taken at `from`, every buffer already grown to what the first pass needed.
fn recipe_heap_calls(scene: &mut SceneWorld, from: usize, to: usize) -> [usize; 2] {
    for _ in 0..from {
        scene.step().unwrap();
    }
    let at_start = scene.world.snapshot();
    let pass = |scene: &mut SceneWorld| {
        let mut calls = 0;
        for _ in from..to {
            let region = Region::new(&INSTRUMENTED_SYSTEM);
            scene.world.step(scene.time_step).unwrap();
            calls += heap_calls(region.change());
        }
        calls
    };
    let first = pass(scene);
    scene.world.restore(&at_start);
    [first, pass(scene)]
}

/// The heap calls of steps 1 to `to` of a new copy of recipe `name` with `capacity` reserved
/// (its events firing before each of its first `from` steps, uncounted; the first step, which
/// makes the memory of the threads it runs on, uncounted too): the run [`recipe_heap_calls`]
/// makes, so `capacity` can be the high water of that one.
fn reserved_heap_calls(name: &str, capacity: Capacity, from: usize, to: usize) -> usize {
    let mut scene = recipe(name);
    scene.world.reserve(capacity).unwrap();
    scene.step().unwrap();
    let mut calls = 0;
    for step in 1..to {
        if step < from {
            scene.fire_events();
        }
        let region = Region::new(&INSTRUMENTED_SYSTEM);
        scene.world.step(scene.time_step).unwrap();
        calls += heap_calls(region.change());
    }
    calls
}

/// The mixed scene: a thousand circles, boxes, pentagons and triangles raining into a room.
fn mixed_1000() -> World {
    let path = carom_bench::cases::worlds::workspace().join("demos/mixed_1000.ron");
    carom_scene::load(&path).unwrap().world
}

/// What a snapshot of `world` after `steps` steps says it holds on the heap, and what taking
/// it allocated, less what it freed, as the allocator counted it.
fn snapshot_heap(mut world: World, steps: usize) -> (usize, usize) {
    for _ in 0..steps {
        world.step(1.0 / 60.0).unwrap();
    }
    let region = Region::new(&INSTRUMENTED_SYSTEM);
    let snapshot = world.snapshot();
    let change = region.change();
    let counted = change.bytes_allocated - change.bytes_deallocated;
    (snapshot.heap_bytes(), counted)
}

/// Allocations over `rounds` rounds of a rollback loop on `world` after `warm_up` steps and
/// eight rounds: each round takes a snapshot into the oldest of a ring of four, steps, and
/// every fourth round goes back to the oldest snapshot kept and steps again from there.
fn rollback_allocations(mut world: World, warm_up: usize, rounds: usize) -> usize {
    for _ in 0..warm_up {
        world.step(1.0 / 60.0).unwrap();
    }
    let mut ring: Vec<Snapshot> = (0..4).map(|_| world.snapshot()).collect();
    let mut round = |world: &mut World, index: usize| {
        world.snapshot_into(&mut ring[index % 4]);
        world.step(1.0 / 60.0).unwrap();
        if index % 4 == 3 {
            world.restore(&ring[(index + 1) % 4]);
            for _ in 0..4 {
                world.step(1.0 / 60.0).unwrap();
            }
        }
    };
    for index in 0..8 {
        round(&mut world, index);
    }
    let region = Region::new(&INSTRUMENTED_SYSTEM);
    for index in 8..8 + rounds {
        round(&mut world, index);
    }
    heap_calls(region.change())
}

/// Runs the one check, taking libtest's arguments: `--list` lists it; it is skipped by
/// `--ignored` (it is not ignored), by a name filter it does not match, or by `--skip`.
fn main() {
    const NAME: &str = "a_world_in_steady_state_allocates_nothing_per_step";
    let (mut filters, mut skips, mut ignored) = (Vec::new(), Vec::new(), false);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--list" => {
                println!("{NAME}: test");
                return;
            }
            "--ignored" => ignored = true,
            "--skip" => skips.extend(args.next()),
            "--test-threads" | "--format" | "--color" | "--logfile" | "--shuffle-seed" | "-Z" => {
                args.next();
            }
            _ if arg.starts_with('-') => {}
            _ => filters.push(arg),
        }
    }
    let chosen = filters.is_empty() || filters.iter().any(|f| NAME.contains(f.as_str()));
    if ignored || !chosen || skips.iter().any(|s| NAME.contains(s.as_str())) {
        println!("{NAME}: skipped");
        return;
    }
    a_world_in_steady_state_allocates_nothing_per_step();
    println!("{NAME}: ok");
}

fn a_world_in_steady_state_allocates_nothing_per_step() {
    let awake = Effects::ALL.without(Effect::Sleeping);
    // Small (everything on the calling thread) and large (the parallel paths), one thread and
    // two; then sleeping on, with the pyramid falling asleep during the counted steps.
    let cases = [
        ("pyramid of 20, awake, 1 thread", pyramid(20, awake), 1, 60),
        ("pyramid of 20, awake, 2 threads", pyramid(20, awake), 2, 60),
        (
            "pyramid of 100, awake, 2 threads",
            pyramid(100, awake),
            2,
            5,
        ),
        (
            "pyramid of 20, sleeping on",
            pyramid(20, Effects::ALL),
            1,
            30,
        ),
        (
            "pyramid of 20, awake, shock propagation, 2 threads",
            with_shock_propagation(pyramid(20, awake)),
            2,
            60,
        ),
        (
            "ragdolls in a pile, direct joints, 2 threads",
            ragdolls_with_direct_joints(),
            2,
            300,
        ),
        (
            "fast circles, capsules and boxes swept in turn",
            fast_mixed_shapes(),
            1,
            5,
        ),
        (
            "a hanging grid of joints, 1 thread",
            hanging_grid(awake),
            1,
            30,
        ),
        (
            "a hanging grid of joints, 2 threads",
            hanging_grid(awake),
            2,
            30,
        ),
    ];
    // The pools live through every case: a pool dropped ends its threads in the background,
    // and a thread ending frees and allocates (its thread-locals), which the process-wide
    // count would charge to whichever case is counting then.
    let pools: Vec<ThreadPool> = (1..=2)
        .map(|threads| {
            ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool")
        })
        .collect();
    let mut failures = Vec::new();
    for (name, world, threads, warm_up) in cases {
        let count = allocations(world, &pools[threads - 1], warm_up, 60);
        if count > 0 {
            failures.push(format!("{name}: {count} allocations in 60 steps"));
        }
    }
    // Box2D's recipes on two threads (the parallel paths), after 100 steps: a step may take
    // memory only to grow a buffer past the largest it has held (their piles still gain
    // contacts), so stepped again from a snapshot, every buffer grown, none does; nor does
    // any step after the first of a new copy with room reserved for what the first held at
    // most.
    for name in RECIPES {
        let mut scene = recipe(name);
        let [first, again] = pools[1].install(|| recipe_heap_calls(&mut scene, 100, 250));
        let most = scene.world.high_water();
        let reserved = pools[1].install(|| reserved_heap_calls(name, most, 100, 250));
        println!(
            "{name}: {first} heap calls in steps 100 to 250, {again} stepped again, \
             {reserved} in steps 1 to 250 with room reserved for {most:?}"
        );
        if reserved > 0 {
            failures.push(format!(
                "{name}: {reserved} heap calls in steps 1 to 250 with room reserved for {most:?}"
            ));
        }
        if again > 0 {
            failures.push(format!(
                "{name}: {again} heap calls in steps 100 to 250 stepped again from a snapshot"
            ));
        }
        if first > 0 && STEADY_BY_STEP_100.contains(&name) {
            failures.push(format!(
                "{name}: {first} heap calls in steps 100 to 250, where nothing grows"
            ));
        }
    }
    // Rolling back: taking snapshots into old ones and restoring them reuse their memory.
    for (name, world, warm_up) in [
        ("pyramid of 20, rolled back", pyramid(20, awake), 60),
        ("ragdolls, rolled back", ragdolls_with_direct_joints(), 300),
        (
            "ragdolls after 600 steps, rolled back",
            ragdolls_with_direct_joints(),
            600,
        ),
        ("tumbler, rolled back", recipe("tumbler").world, 150),
    ] {
        let count = pools[0].install(|| rollback_allocations(world, warm_up, 40));
        if count > 0 {
            failures.push(format!("{name}: {count} allocations in 40 rounds"));
        }
    }
    // A snapshot's own count of its heap is the allocator's, within 5 % (its maps' tables are
    // estimated a little under). On one thread, the copy all on the counting one.
    for (name, world, steps) in [
        ("mixed 1000, 120 steps", mixed_1000(), 120),
        ("pyramid of 100, 5 steps", pyramid(100, awake), 5),
    ] {
        let (reported, counted) = pools[0].install(|| snapshot_heap(world, steps));
        let off = reported.abs_diff(counted) as f64 / counted as f64;
        println!(
            "{name}: a snapshot says it holds {reported} B, the allocator counted {counted} B"
        );
        if off > 0.05 {
            failures.push(format!(
                "{name}: a snapshot says it holds {reported} B, the allocator counted \
                 {counted} B ({:.1} % off)",
                off * 100.0
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
