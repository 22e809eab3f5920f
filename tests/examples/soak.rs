//! A long soak: `demos/mixed_1000.ron` stepped for a set time under random abuse (bodies
//! removed and added, grabbed and thrown, turned kinematic and back, made bullets, blown
//! apart), with every body checked finite after every step. Every ten simulated seconds the
//! running scene is saved as a scene file and opened again beside it: the reopened world must be
//! in the same state and step on to the same states as the running one, which carries on. One
//! world lives the whole run, so whatever it fails to free piles up.
//!
//! It fails (exit code 1) on a body that is not finite, a reopened save that does not carry on
//! from the same state, a panic, or a leak, which it looks for two ways, both on the live heap
//! (bytes allocated and not yet freed, counted by an instrumented allocator):
//! - **Nothing outlives its owner.** Once the run's world is dropped, the heap must be back
//!   where it was before the world was built, to the byte.
//! - **A world does not grow without bound.** At each save the running world's heap is set
//!   beside the heap the same state takes when opened fresh from its save. Arrays keep the
//!   capacity of the busiest moment they have seen, and capacities double, so a world that has
//!   run a while holds a few times its fresh size; one that keeps growing passes
//!   [`GROWN_AT_MOST`].
//!
//! The heap is not held to "no growth over the run": a pile that only shifts grows its arrays
//! whenever a throw or an explosion makes a busier moment than any before, in steps of tens of
//! kilobytes to a megabyte, at steps no one can place in advance. Resident memory is printed
//! beside the heap, not held to a bar: the system allocator keeps it at its high-water mark.
//!
//! ```sh
//! cargo run --release -p carom-tests --example soak -- --seconds 3600   # the hour
//! cargo run -p carom-tests --example soak -- --seconds 120              # CI's two minutes
//! ```

use carom::{BodyDef, BodyHandle, BodyKind, ExplosionDef, JointDef, JointHandle, Shape, vec2};
use carom_bench::cases::Rng;
use carom_scene::SceneWorld;
use stats_alloc::{INSTRUMENTED_SYSTEM, StatsAlloc};
use std::alloc::System;
use std::path::PathBuf;
use std::time::{Duration, Instant};

#[global_allocator]
static HEAP: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// How many times its fresh size a running world's heap may be at a save. A world that has run
/// two minutes of the release build (54,000 steps) holds 2.4-3x; an array that grows without
/// bound goes past this.
const GROWN_AT_MOST: f64 = 4.0;
/// Steps between saves: ten simulated seconds.
const SAVE_EVERY: u64 = 600;
/// Steps the reopened world takes beside a copy of the running one.
const REOPENED_STEPS: u32 = 10;

/// A body held by a mouse joint, and where its target goes.
struct Grab {
    joint: JointHandle,
    body: BodyHandle,
    steps_left: u32,
    velocity: carom::Vec2,
}

/// What the soak did, for its report.
#[derive(Debug, Default)]
struct Tally {
    steps: u64,
    replaced: u64,
    grabs: u64,
    explosions: u64,
    kind_changes: u64,
    bullets: u64,
    reopened: u64,
}

fn main() {
    let seconds: u64 = std::env::args()
        .skip_while(|a| a != "--seconds")
        .nth(1)
        .map(|s| s.parse().expect("--seconds takes a whole number"))
        .unwrap_or(120);
    let length = Duration::from_secs(seconds);
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/mixed_1000.ron");
    let scene = carom_scene::read(&file).unwrap_or_else(|e| panic!("{e}"));
    let name = file.display().to_string();
    // The records are allocated whole (and never grown) and the output started before the
    // baseline, so the heap the run must come back to holds those, the scene and what the first
    // step starts once for the process (the thread pool), and nothing a world owns.
    let mut samples: Vec<Sample> = Vec::with_capacity(seconds as usize + 2);
    let mut saves: Vec<SavePoint> = Vec::with_capacity((seconds as usize + 1) * 4);
    start_once(&scene, &name);
    println!("the soak: {name} for {seconds} s");
    let baseline = heap_bytes();
    {
        let mut built = carom_scene::build(&scene, &name).unwrap_or_else(|e| panic!("{e}"));
        let mut rng = Rng::new(0x50a6);
        let mut tally = Tally::default();
        let mut grab: Option<Grab> = None;
        let started = Instant::now();
        let mut next_sample = Duration::ZERO;
        while started.elapsed() < length {
            abuse(&mut built, &mut rng, &mut grab, &mut tally);
            built.step().expect("a valid world steps");
            tally.steps += 1;
            check_finite(&built, tally.steps);
            if tally.steps % SAVE_EVERY == 0 {
                // A grab's joint is the user's hand, not part of the scene: let go first.
                if let Some(held) = grab.take() {
                    let _ = built.world.remove_joint(held.joint);
                }
                let live = heap_bytes().saturating_sub(baseline);
                let fresh = reopen(&built, &scene, &name);
                if saves.len() < saves.capacity() {
                    saves.push(SavePoint {
                        at: started.elapsed(),
                        step: tally.steps,
                        live,
                        fresh,
                    });
                }
                tally.reopened += 1;
            }
            let now = started.elapsed();
            if now >= next_sample && samples.len() < samples.capacity() {
                samples.push(Sample {
                    at: now,
                    heap: heap_bytes(),
                    resident: resident_bytes(),
                });
                next_sample += Duration::from_secs(1);
            }
        }
        println!("{tally:?}");
        println!("bodies at the end: {}", built.world.body_count());
    }
    let left = heap_bytes() as i64 - baseline as i64;
    report_memory(&samples, &saves, left);
}

/// Builds the scene and steps it once, then drops it: what the first step starts once for the
/// whole process (the thread pool) is then part of the baseline, not of a world.
fn start_once(scene: &carom_scene::Scene, name: &str) {
    let mut built = carom_scene::build(scene, name).unwrap_or_else(|e| panic!("{e}"));
    built.step().expect("a valid world steps");
}

/// One step's worth of random abuse.
fn abuse(built: &mut SceneWorld, rng: &mut Rng, grab: &mut Option<Grab>, tally: &mut Tally) {
    let world = &mut built.world;
    // Move the held body's target, and throw it when the time is up.
    if let Some(held) = grab {
        held.steps_left -= 1;
        let target = world
            .body(held.body)
            .map(|b| b.position() + held.velocity / 60.0);
        match (held.steps_left, target) {
            (1.., Some(target)) => {
                let mut joint = world
                    .joint_mut(held.joint)
                    .expect("the grab's joint is live");
                joint
                    .set_mouse_target(target)
                    .expect("a finite target is taken");
            }
            _ => {
                let _ = world.remove_joint(held.joint);
                *grab = None;
            }
        }
    }
    let dynamic: Vec<BodyHandle> = world
        .bodies()
        .filter(|b| b.kind() != BodyKind::Static)
        .map(|b| b.handle())
        .collect();
    if dynamic.is_empty() {
        return;
    }
    let pick = |rng: &mut Rng| dynamic[rng.below(dynamic.len())];
    let held = grab.as_ref().map(|g| g.body);
    match rng.below(240) {
        // Replace a body with a new one of another shape, dropped from the top.
        0..=7 => {
            let gone = pick(rng);
            if Some(gone) != held {
                world.remove_body(gone).expect("a live body is removed");
                built.colors.remove(&gone);
                built.names.retain(|_, &mut h| h != gone);
                let shape = match rng.below(3) {
                    0 => Shape::circle(rng.range(0.1, 0.5)),
                    1 => Shape::rect(rng.range(0.1, 0.5), rng.range(0.1, 0.5)),
                    _ => Shape::capsule(vec2(-0.3, 0.0), vec2(0.3, 0.0), rng.range(0.05, 0.3)),
                };
                let at = vec2(rng.range(-18.0, 18.0), rng.range(20.0, 28.0));
                let world = &mut built.world;
                world
                    .add_body(BodyDef::dynamic(shape).position(at))
                    .expect("a valid body is added");
                tally.replaced += 1;
            }
        }
        // Grab a body and throw it.
        8 if grab.is_none() => {
            let body = pick(rng);
            let (point, mass) = {
                let b = world.body(body).expect("a live body");
                (b.position(), b.mass())
            };
            if mass > 0.0 {
                let joint = world
                    .add_joint(JointDef::mouse(body, point, 1000.0 * mass))
                    .expect("a mouse joint on a live body");
                *grab = Some(Grab {
                    joint,
                    body,
                    steps_left: 30 + rng.below(90) as u32,
                    velocity: vec2(rng.range(-30.0, 30.0), rng.range(-10.0, 30.0)),
                });
                tally.grabs += 1;
            }
        }
        9 => {
            let center = vec2(rng.range(-18.0, 18.0), rng.range(1.0, 25.0));
            let explosion = ExplosionDef {
                falloff: 2.0,
                ..ExplosionDef::new(center, rng.range(1.0, 5.0), rng.range(1.0, 50.0))
            };
            world.explode(&explosion).expect("a valid explosion");
            tally.explosions += 1;
        }
        // Turn a body kinematic for a while, or back.
        10 => {
            let body = pick(rng);
            if Some(body) != held {
                let mut b = world.body_mut(body).expect("a live body");
                let kind = if b.kind() == BodyKind::Kinematic {
                    BodyKind::Dynamic
                } else {
                    BodyKind::Kinematic
                };
                b.set_kind(kind).expect("a valid kind");
                tally.kind_changes += 1;
            }
        }
        11 => {
            let body = pick(rng);
            let mut b = world.body_mut(body).expect("a live body");
            let bullet = !b.is_bullet();
            b.set_bullet(bullet);
            tally.bullets += 1;
        }
        _ => {}
    }
}

/// Saves the running scene as a scene file's text and opens it again: the reopened world must
/// be in the same state and step on beside the running one to the same states. Returns the heap
/// the reopened world took when built, the size of the running world's state with nothing grown.
fn reopen(built: &SceneWorld, scene: &carom_scene::Scene, name: &str) -> u64 {
    let text = carom_scene::to_text(&built.save(scene), name).expect("a running scene saves");
    let parsed = carom_scene::parse(&text, name).expect("a saved scene parses");
    let before = heap_bytes();
    let mut reopened = carom_scene::build(&parsed, name).expect("a saved scene opens");
    let fresh = heap_bytes().saturating_sub(before);
    assert_eq!(
        reopened.world.state_hash(),
        built.world.state_hash(),
        "the reopened scene is not where the saved one was"
    );
    let mut original = built.world.clone();
    for step in 1..=REOPENED_STEPS {
        original.step(built.time_step).expect("a valid step");
        reopened.step().expect("a valid step");
        assert_eq!(
            reopened.world.state_hash(),
            original.state_hash(),
            "the reopened scene stepped to another state {step} steps on"
        );
    }
    fresh
}

/// Ends the run, naming the step, if any body is not finite.
fn check_finite(built: &SceneWorld, step: u64) {
    if let Some(figures) = carom_tests::first_non_finite_body(&built.world) {
        eprintln!("step {step}: a body went non-finite: {figures:?}");
        std::process::exit(1);
    }
}

/// Memory at one moment of the run.
struct Sample {
    at: Duration,
    /// Bytes allocated and not yet freed.
    heap: u64,
    /// The process's resident memory, where the system says.
    resident: Option<u64>,
}

/// Bytes allocated and not yet freed, by every thread.
fn heap_bytes() -> u64 {
    // A reallocation counts its growth as allocated and its shrinking as freed.
    let stats = HEAP.stats();
    stats
        .bytes_allocated
        .saturating_sub(stats.bytes_deallocated) as u64
}

/// The process's resident memory, bytes, where the system says (Linux's `/proc`).
fn resident_bytes() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096)
}

/// The running world's heap at a save.
struct SavePoint {
    at: Duration,
    step: u64,
    /// Bytes allocated since the baseline and not yet freed: the running world, grown.
    live: u64,
    /// Bytes the same state took when opened from its save: the world, not grown.
    fresh: u64,
}

/// Prints the heap and resident memory over the run and fails on a leak.
fn report_memory(samples: &[Sample], saves: &[SavePoint], left: i64) {
    let mb = |bytes: u64| bytes as f64 / (1024.0 * 1024.0);
    let every = if samples.len() > 600 { 300 } else { 10 };
    println!("| s | heap MB | resident MB |\n|---|---|---|");
    for sample in samples.iter().filter(|s| s.at.as_secs() % every == 0) {
        let resident = sample
            .resident
            .map_or("-".to_string(), |r| format!("{:.1}", mb(r)));
        println!(
            "| {} | {:.1} | {resident} |",
            sample.at.as_secs(),
            mb(sample.heap)
        );
    }
    if let Some(resident) = samples.iter().filter_map(|s| s.resident).max() {
        println!("resident memory: peak {:.1} MB", mb(resident));
    }
    let grown = |save: &SavePoint| save.live as f64 / save.fresh.max(1) as f64;
    let every = (saves.len() / 12).max(1);
    println!("\n| s | step | running world MB | opened fresh MB | grown |\n|---|---|---|---|---|");
    for (i, save) in saves.iter().enumerate() {
        if i % every == 0 || i + 1 == saves.len() {
            println!(
                "| {} | {} | {:.2} | {:.2} | {:.2}x |",
                save.at.as_secs(),
                save.step,
                mb(save.live),
                mb(save.fresh),
                grown(save)
            );
        }
    }
    let mut failed = false;
    if let Some(worst) = saves.iter().max_by(|a, b| grown(a).total_cmp(&grown(b))) {
        println!(
            "the running world at most {:.2}x its fresh size (step {}; bar: {GROWN_AT_MOST}x)",
            grown(worst),
            worst.step
        );
        if grown(worst) > GROWN_AT_MOST {
            eprintln!(
                "the running world grew to {:.2}x the heap of the same state opened fresh (bar: {GROWN_AT_MOST}x)",
                grown(worst)
            );
            failed = true;
        }
    }
    println!("heap left once the world was dropped: {left} bytes (bar: 0)");
    if left != 0 {
        eprintln!("{left} bytes were still allocated after the world was dropped: a leak");
        failed = true;
    }
    if failed {
        std::process::exit(1);
    }
}
