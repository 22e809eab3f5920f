//! A long soak: `demos/mixed_1000.ron` stepped for a set time under random abuse, everything a
//! user does to a running world at once: bodies removed and added, grabbed and thrown, turned
//! kinematic and back, made bullets, blown apart, tied together by joints that break, a
//! character walking and jumping through the pile, snapshots taken and restored, the whole world
//! saved and read back in its place. Every body and the character are checked finite after
//! every step.
//!
//! Everything the soak does is written to a recording as it does it, with the world's state
//! hash after every step. At the end the recording is played back from the scene file on one
//! thread: every step must end in the hash recorded. A failing run leaves its recording to play
//! back (`--replay <file>`); `--follow` plays one back while another process is still writing
//! it, on the second core, so that an hour's run is checked in about an hour.
//!
//! Every ten simulated seconds the running scene is also saved as a scene file and opened again
//! beside it: the reopened world must be in the same state and step on to the same states as the
//! running one, which carries on. One world lives the whole run (reading a saved world back puts
//! the same arrays' contents in new ones), so whatever it fails to free piles up.
//!
//! It fails (exit code 1) on a body or character that is not finite, a reopened save or a saved
//! world that does not carry on from the same state, a replayed step that ends in another hash, a
//! panic, or a leak, which it looks for two ways, both on the live heap (bytes allocated and not
//! yet freed, counted by an instrumented allocator):
//! - **Nothing outlives its owner.** Once the run's world is dropped, the heap must be back
//!   where it was before the world was built, to the byte.
//! - **A world does not grow without bound.** At each save the running world's heap (less the
//!   snapshot it holds) is set beside the heap the same state takes when opened fresh from its
//!   save. Arrays keep the capacity of the busiest moment they have seen, and capacities double,
//!   so a world that has run a while holds a few times its fresh size; one that keeps growing
//!   passes [`GROWN_AT_MOST`].
//!
//! The heap is not held to "no growth over the run": a pile that only shifts grows its arrays
//! whenever a throw or an explosion makes a busier moment than any before, in steps of tens of
//! kilobytes to a megabyte, at steps no one can place in advance. Resident memory is printed
//! beside the heap, not held to a bar: the system allocator keeps it at its high-water mark.
//!
//! ```sh
//! cargo run --release -p carom-tests --example soak -- --seconds 3600   # the hour, then its replay
//! cargo run -p carom-tests --example soak -- --seconds 75               # CI's run
//! # the hour with its replay beside it, on the other core:
//! soak --seconds 3600 --record run.soak --no-replay & soak --replay run.soak --follow
//! ```

use carom::{
    BodyDef, BodyHandle, BodyKind, CaromError, Character, CharacterDef, CharacterState,
    ExplosionDef, JointDef, JointHandle, Real, Shape, World, vec2,
};
use carom_bench::cases::Rng;
use carom_scene::{SceneSnapshot, SceneWorld};
use serde::{Deserialize, Serialize};
use stats_alloc::{INSTRUMENTED_SYSTEM, StatsAlloc};
use std::alloc::System;
use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

#[global_allocator]
static HEAP: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// How many times its fresh size a running world's heap may be at a save. A world that has run
/// two minutes of the release build holds 2.4-3x; an array that grows without bound goes past
/// this.
const GROWN_AT_MOST: f64 = 4.0;
/// Steps between saves: ten simulated seconds.
const SAVE_EVERY: u64 = 600;
/// Steps the reopened world takes beside a copy of the running one.
const REOPENED_STEPS: u32 = 10;
/// Joints the soak keeps at most between bodies (they break, and go with their bodies).
const MOST_LINKS: usize = 40;
/// Bodies drawn to find one near a body to tie it to, and how near it must be, m.
const LINK_CANDIDATES: usize = 32;
const LINK_REACH: Real = 3.0;
/// The character's walking speed, m/s, and the speed a jump leaves the ground at.
const WALK_SPEED: Real = 4.0;
const JUMP_SPEED: Real = 7.0;
/// How fast the character's fall gathers speed, m/s².
const FALL_ACCELERATION: Real = 9.81;
/// The fastest the character falls, m/s.
const FASTEST_FALL: Real = 30.0;
/// Below this height the character has left the room, and is put back at the top.
const OUT_OF_THE_ROOM: Real = -5.0;
/// Where the character starts, and is put back.
const CHARACTER_START: (Real, Real) = (0.0, 28.0);

/// How long a replay that follows a recording waits for a line before it takes the run to have
/// stopped.
const FOLLOW_PATIENCE: Duration = Duration::from_secs(120);

/// A new body's shape.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
enum NewShape {
    Circle { radius: Real },
    Rect { half_width: Real, half_height: Real },
    Capsule { radius: Real },
}

/// One thing the soak does to the scene before a step, with all it needs to do it again.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
enum Act {
    /// Removes a body and drops a new one from the top.
    Replace {
        gone: BodyHandle,
        shape: NewShape,
        at: (Real, Real),
    },
    /// Grabs a body with a mouse joint and drags it for some steps, then lets go: a throw.
    Grab {
        body: BodyHandle,
        steps: u32,
        velocity: (Real, Real),
    },
    /// Lets go of the body held, if any.
    LetGo,
    Explode {
        center: (Real, Real),
        radius: Real,
        impulse: Real,
    },
    /// Turns a body kinematic, or back to dynamic.
    ToggleKind {
        body: BodyHandle,
    },
    ToggleBullet {
        body: BodyHandle,
    },
    /// Ties two bodies together, halfway between them, with a joint that breaks.
    Link {
        a: BodyHandle,
        b: BodyHandle,
        weld: bool,
        break_force: Real,
    },
    /// The character's keys from now on.
    Walk {
        direction: i8,
        jump: bool,
    },
    /// Takes a snapshot of the scene and the character (letting go first).
    Snapshot,
    /// Puts the scene and the character back as the last snapshot holds them.
    Restore,
    /// Saves the world (serde) and puts the world read back from it in its place.
    Reload,
}

/// A line of a recording: an act, a step and the state after it, or the end.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
enum Line {
    Act(Act),
    /// A step taken: the world's state hash after it and the character's place, as bits.
    Step {
        hash: u64,
        character: (u64, u64),
    },
    End,
}

/// A body held by a mouse joint, and where its target goes.
struct Grab {
    joint: JointHandle,
    body: BodyHandle,
    steps_left: u32,
    velocity: carom::Vec2,
}

/// The character, its keys and its fall.
struct Walker {
    character: Character,
    direction: i8,
    jump: bool,
    /// Its vertical speed, m/s.
    rise: Real,
}

/// A snapshot of the scene and of the character.
struct Saved {
    scene: SceneSnapshot,
    character: CharacterState,
    rise: Real,
}

/// The scene and what the soak holds beside it.
struct Soak {
    built: SceneWorld,
    grab: Option<Grab>,
    walker: Walker,
    saved: Option<Saved>,
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
    links: u64,
    walks: u64,
    snapshots: u64,
    restores: u64,
    reloads: u64,
    reopened: u64,
    /// Times the character left the room and was put back.
    character_out: u64,
}

/// The command line.
struct Options {
    seconds: u64,
    record: PathBuf,
    replay: bool,
    /// Plays back this recording instead of running.
    replay_only: Option<PathBuf>,
    follow: bool,
}

fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str| {
        args.iter().position(|a| a == name).map(|i| {
            args.get(i + 1)
                .unwrap_or_else(|| panic!("{name} takes a value"))
        })
    };
    Options {
        seconds: value("--seconds")
            .map_or(120, |s| s.parse().expect("--seconds takes a whole number")),
        record: value("--record").map_or_else(
            || std::env::temp_dir().join(format!("carom-soak-{}.soak", std::process::id())),
            PathBuf::from,
        ),
        replay: !args.iter().any(|a| a == "--no-replay"),
        replay_only: value("--replay").map(PathBuf::from),
        follow: args.iter().any(|a| a == "--follow"),
    }
}

fn scene_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../demos/mixed_1000.ron")
}

fn main() {
    let options = options();
    let file = scene_file();
    let scene = carom_scene::read(&file).unwrap_or_else(|e| panic!("{e}"));
    let name = file.display().to_string();
    if let Some(recording) = &options.replay_only {
        std::process::exit(i32::from(!replay(recording, &scene, &name, options.follow)));
    }
    let seconds = options.seconds;
    let length = Duration::from_secs(seconds);
    // The records and the recording's writer are made whole (and never grown) and the output
    // started before the baseline, so the heap the run must come back to holds those, the scene
    // and what the first step starts once for the process (the thread pool), and nothing a world
    // owns.
    let mut samples: Vec<Sample> = Vec::with_capacity(seconds as usize + 2);
    let mut saves: Vec<SavePoint> = Vec::with_capacity((seconds as usize + 1) * 4);
    let mut recording = BufWriter::new(
        File::create(&options.record)
            .unwrap_or_else(|e| panic!("{}: {e}", options.record.display())),
    );
    start_once(&scene, &name);
    println!(
        "the soak: {name} for {seconds} s, recorded in {}",
        options.record.display()
    );
    let baseline = heap_bytes();
    {
        let mut soak =
            Soak::new(carom_scene::build(&scene, &name).unwrap_or_else(|e| panic!("{e}")));
        let mut rng = Rng::new(0x50a6);
        let mut tally = Tally::default();
        let started = Instant::now();
        let mut next_sample = Duration::ZERO;
        let mut record = |line: Line| {
            let text = ron::to_string(&line).expect("a line serializes");
            writeln!(recording, "{text}").expect("the recording is written");
        };
        while started.elapsed() < length {
            if let Some(act) = plan(&soak, &mut rng) {
                record(Line::Act(act));
                soak.apply(act, &mut tally).expect("a planned act applies");
            }
            if (tally.steps + 1) % SAVE_EVERY == 0 {
                // A grab's joint is the user's hand, not part of the scene: let go first.
                record(Line::Act(Act::LetGo));
                soak.apply(Act::LetGo, &mut tally)
                    .expect("letting go applies");
            }
            let line = soak.step(&mut tally);
            record(line);
            check_finite(&soak, tally.steps);
            if tally.steps % SAVE_EVERY == 0 {
                let live = heap_bytes().saturating_sub(baseline).saturating_sub(
                    soak.saved
                        .as_ref()
                        .map_or(0, |s| s.scene.heap_bytes() as u64),
                );
                let fresh = reopen(&soak.built, &scene, &name);
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
        record(Line::End);
        println!("{tally:?}");
        println!(
            "bodies at the end: {}, joints: {}",
            soak.built.world.body_count(),
            soak.built.world.joint_count()
        );
    }
    let left = heap_bytes() as i64 - baseline as i64;
    recording.flush().expect("the recording is written");
    drop(recording);
    let mut failed = !report_memory(&samples, &saves, left);
    if options.replay {
        // On one thread, whatever the run used: the same bits on any thread count.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a thread pool");
        failed |= !pool.install(|| replay(&options.record, &scene, &name, false));
    }
    if failed {
        std::process::exit(1);
    }
}

/// Builds the scene and steps it once, then drops it: what the first step starts once for the
/// whole process (the thread pool) is then part of the baseline, not of a world.
fn start_once(scene: &carom_scene::Scene, name: &str) {
    let mut built = carom_scene::build(scene, name).unwrap_or_else(|e| panic!("{e}"));
    built.step().expect("a valid world steps");
}

/// One step's worth of random abuse, chosen from the scene as it is: none on most steps.
fn plan(soak: &Soak, rng: &mut Rng) -> Option<Act> {
    let world = &soak.built.world;
    let dynamic: Vec<BodyHandle> = world
        .bodies()
        .filter(|b| b.kind() != BodyKind::Static)
        .map(|b| b.handle())
        .collect();
    if dynamic.is_empty() {
        return None;
    }
    let pick = |rng: &mut Rng| dynamic[rng.below(dynamic.len())];
    let held = soak.grab.as_ref().map(|g| g.body);
    let act = match rng.below(240) {
        0..=7 => {
            let gone = pick(rng);
            let shape = match rng.below(3) {
                0 => NewShape::Circle {
                    radius: rng.range(0.1, 0.5),
                },
                1 => NewShape::Rect {
                    half_width: rng.range(0.1, 0.5),
                    half_height: rng.range(0.1, 0.5),
                },
                _ => NewShape::Capsule {
                    radius: rng.range(0.05, 0.3),
                },
            };
            let at = (rng.range(-18.0, 18.0), rng.range(20.0, 28.0));
            (Some(gone) != held).then_some(Act::Replace { gone, shape, at })?
        }
        8 if soak.grab.is_none() => Act::Grab {
            body: pick(rng),
            steps: 30 + rng.below(90) as u32,
            velocity: (rng.range(-30.0, 30.0), rng.range(-10.0, 30.0)),
        },
        9 => Act::Explode {
            center: (rng.range(-18.0, 18.0), rng.range(1.0, 25.0)),
            radius: rng.range(1.0, 5.0),
            impulse: rng.range(1.0, 50.0),
        },
        10 => {
            let body = pick(rng);
            (Some(body) != held).then_some(Act::ToggleKind { body })?
        }
        11 => Act::ToggleBullet { body: pick(rng) },
        12 | 13 if world.joint_count() < MOST_LINKS => {
            // Two bodies near each other, as a user ties them: the nearest of a few to one.
            let a = pick(rng);
            let place = |h| world.body(h).map_or(vec2(0.0, 0.0), |b| b.position());
            let from = place(a);
            let (b, distance) = (0..LINK_CANDIDATES)
                .map(|_| pick(rng))
                .filter(|&b| b != a)
                .map(|b| (b, (place(b) - from).norm()))
                .min_by(|p, q| p.1.total_cmp(&q.1))?;
            let weld = rng.below(2) == 0;
            let break_force = rng.range(10.0, 2000.0);
            (distance < LINK_REACH).then_some(Act::Link {
                a,
                b,
                weld,
                break_force,
            })?
        }
        14 | 15 => Act::Walk {
            direction: rng.below(3) as i8 - 1,
            jump: rng.below(3) == 0,
        },
        16 => Act::Snapshot,
        17 if soak.saved.is_some() => Act::Restore,
        18 if rng.below(4) == 0 => Act::Reload,
        _ => return None,
    };
    Some(act)
}

impl Soak {
    fn new(built: SceneWorld) -> Soak {
        let at = vec2(CHARACTER_START.0, CHARACTER_START.1);
        let character = Character::new(CharacterDef::capsule(0.4, 0.3).position(at))
            .expect("a valid character");
        Soak {
            built,
            grab: None,
            walker: Walker {
                character,
                direction: 1,
                jump: false,
                rise: 0.0,
            },
            saved: None,
        }
    }

    /// Does `act` to the scene.
    fn apply(&mut self, act: Act, tally: &mut Tally) -> Result<(), CaromError> {
        let world = &mut self.built.world;
        match act {
            Act::Replace { gone, shape, at } => {
                world.remove_body(gone)?;
                self.built.colors.remove(&gone);
                self.built.names.retain(|_, &mut h| h != gone);
                let shape = match shape {
                    NewShape::Circle { radius } => Shape::circle(radius),
                    NewShape::Rect {
                        half_width,
                        half_height,
                    } => Shape::rect(half_width, half_height),
                    NewShape::Capsule { radius } => {
                        Shape::capsule(vec2(-0.3, 0.0), vec2(0.3, 0.0), radius)
                    }
                };
                self.built
                    .world
                    .add_body(BodyDef::dynamic(shape).position(vec2(at.0, at.1)))?;
                tally.replaced += 1;
            }
            Act::Grab {
                body,
                steps,
                velocity,
            } => {
                let b = world.body(body).ok_or_else(|| stale(body))?;
                let (point, mass) = (b.position(), b.mass());
                if mass > 0.0 {
                    let joint = world.add_joint(JointDef::mouse(body, point, 1000.0 * mass))?;
                    self.grab = Some(Grab {
                        joint,
                        body,
                        steps_left: steps,
                        velocity: vec2(velocity.0, velocity.1),
                    });
                    tally.grabs += 1;
                }
            }
            Act::LetGo => self.let_go(),
            Act::Explode {
                center,
                radius,
                impulse,
            } => {
                let explosion = ExplosionDef {
                    falloff: 2.0,
                    ..ExplosionDef::new(vec2(center.0, center.1), radius, impulse)
                };
                world.explode(&explosion)?;
                tally.explosions += 1;
            }
            Act::ToggleKind { body } => {
                let mut b = world.body_mut(body).ok_or_else(|| stale(body))?;
                let kind = if b.kind() == BodyKind::Kinematic {
                    BodyKind::Dynamic
                } else {
                    BodyKind::Kinematic
                };
                b.set_kind(kind)?;
                tally.kind_changes += 1;
            }
            Act::ToggleBullet { body } => {
                let mut b = world.body_mut(body).ok_or_else(|| stale(body))?;
                let bullet = !b.is_bullet();
                b.set_bullet(bullet);
                tally.bullets += 1;
            }
            Act::Link {
                a,
                b,
                weld,
                break_force,
            } => {
                let place = |h| world.body(h).map(|b| b.position());
                let (pa, pb) = (
                    place(a).ok_or_else(|| stale(a))?,
                    place(b).ok_or_else(|| stale(b))?,
                );
                let anchor = (pa + pb) * 0.5;
                let def = if weld {
                    JointDef::weld(a, b, anchor)
                } else {
                    JointDef::revolute(a, b, anchor)
                };
                world.add_joint(def.break_force(break_force))?;
                tally.links += 1;
            }
            Act::Walk { direction, jump } => {
                self.walker.direction = direction;
                self.walker.jump = jump;
                tally.walks += 1;
            }
            Act::Snapshot => {
                self.let_go();
                let character = self.walker.character.state();
                let rise = self.walker.rise;
                match &mut self.saved {
                    Some(saved) => {
                        self.built.snapshot_into(&mut saved.scene);
                        saved.character = character;
                        saved.rise = rise;
                    }
                    None => {
                        self.saved = Some(Saved {
                            scene: self.built.snapshot(),
                            character,
                            rise,
                        });
                    }
                }
                tally.snapshots += 1;
            }
            Act::Restore => {
                if let Some(saved) = &self.saved {
                    // The snapshot holds no grab: the world it restores has no hand's joint.
                    self.grab = None;
                    self.built.restore(&saved.scene);
                    self.walker.character.restore(saved.character)?;
                    self.walker.rise = saved.rise;
                    tally.restores += 1;
                }
            }
            Act::Reload => {
                self.let_go();
                let text = ron::to_string(&self.built.world).expect("a world serializes");
                let reloaded: World = ron::from_str(&text).expect("a saved world reads back");
                assert_eq!(
                    reloaded.state_hash(),
                    self.built.world.state_hash(),
                    "a saved world read back is not where the running one was"
                );
                self.built.world = reloaded;
                tally.reloads += 1;
            }
        }
        Ok(())
    }

    fn let_go(&mut self) {
        if let Some(held) = self.grab.take() {
            // Gone already if the body was removed.
            let _ = self.built.world.remove_joint(held.joint);
        }
    }

    /// Moves the held body's target and the character, steps the scene, and returns the
    /// recording's line for the step.
    fn step(&mut self, tally: &mut Tally) -> Line {
        let dt = self.built.time_step;
        let world = &mut self.built.world;
        // Move the held body's target, and throw it when the time is up.
        if let Some(held) = &mut self.grab {
            held.steps_left -= 1;
            let target = world
                .body(held.body)
                .map(|b| b.position() + held.velocity * dt);
            match (held.steps_left, target) {
                (1.., Some(target)) => world
                    .joint_mut(held.joint)
                    .expect("the grab's joint is live")
                    .set_mouse_target(target)
                    .expect("a target within reach is taken"),
                _ => self.let_go(),
            }
        }
        self.walk(tally);
        self.built.step().expect("a valid world steps");
        tally.steps += 1;
        let at = self.walker.character.position();
        Line::Step {
            hash: self.built.world.state_hash(),
            character: (f64::from(at.x).to_bits(), f64::from(at.y).to_bits()),
        }
    }

    /// Walks the character by its keys, falling when nothing holds it up.
    fn walk(&mut self, tally: &mut Tally) {
        let dt = self.built.time_step;
        let walker = &mut self.walker;
        if walker.character.position().y < OUT_OF_THE_ROOM {
            let start = vec2(CHARACTER_START.0, CHARACTER_START.1);
            walker
                .character
                .set_position(start)
                .expect("the start is in range");
            walker.rise = 0.0;
            tally.character_out += 1;
        }
        if walker.character.is_grounded() {
            walker.rise = if walker.jump { JUMP_SPEED } else { 0.0 };
        } else {
            walker.rise = (walker.rise - FALL_ACCELERATION * dt).max(-FASTEST_FALL);
        }
        let translation = vec2(Real::from(walker.direction) * WALK_SPEED, walker.rise) * dt;
        self.built
            .world
            .move_character(&mut walker.character, translation, dt)
            .expect("a walk within reach is taken");
    }
}

/// The error for a body that is gone.
fn stale(body: BodyHandle) -> CaromError {
    CaromError::StaleHandle {
        what: "body",
        index: body.index(),
        generation: body.generation(),
    }
}

/// Plays `path` back from the scene: every act again before the step it came before, and every
/// step to the hash recorded. With `follow`, waits for lines still being written until the
/// recording's end. Returns whether every step matched.
fn replay(path: &Path, scene: &carom_scene::Scene, name: &str, follow: bool) -> bool {
    let started = Instant::now();
    let file = File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = BufReader::new(file);
    let mut soak = Soak::new(carom_scene::build(scene, name).unwrap_or_else(|e| panic!("{e}")));
    let mut tally = Tally::default();
    let mut text = String::new();
    let mut acts = 0u64;
    let mut waited = Instant::now();
    loop {
        let read = reader.read_line(&mut text).expect("the recording reads");
        if !text.ends_with('\n') {
            // The end of what is written so far, in a line or between two.
            if read == 0 && !follow {
                eprintln!(
                    "the recording {} ends after step {} with no end line: the run stopped there",
                    path.display(),
                    tally.steps
                );
                return false;
            }
            if waited.elapsed() > FOLLOW_PATIENCE {
                eprintln!(
                    "the recording {} has grown by nothing for {} s after step {}: the run stopped",
                    path.display(),
                    FOLLOW_PATIENCE.as_secs(),
                    tally.steps
                );
                return false;
            }
            std::thread::sleep(Duration::from_millis(20));
            continue;
        }
        waited = Instant::now();
        let line: Line = ron::from_str(text.trim_end())
            .unwrap_or_else(|e| panic!("{}: a line that is not the soak's: {e}", path.display()));
        text.clear();
        match line {
            Line::Act(act) => {
                acts += 1;
                soak.apply(act, &mut tally).unwrap_or_else(|e| {
                    panic!("the act before step {} did not apply: {e}", tally.steps + 1)
                });
            }
            Line::Step { .. } => {
                let replayed = soak.step(&mut tally);
                if replayed != line {
                    eprintln!(
                        "step {}: the replay ended in {replayed:?}, the recording in {line:?}",
                        tally.steps
                    );
                    return false;
                }
            }
            Line::End => break,
        }
    }
    println!(
        "replayed {} steps and {acts} acts from {} in {:.0} s, on {} thread(s): every hash as recorded",
        tally.steps,
        path.display(),
        started.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    true
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

/// Ends the run, naming the step, if any body or the character is not finite.
fn check_finite(soak: &Soak, step: u64) {
    if let Some(figures) = carom_tests::first_non_finite_body(&soak.built.world) {
        eprintln!("step {step}: a body went non-finite: {figures:?}");
        std::process::exit(1);
    }
    let at = soak.walker.character.position();
    if !(at.x.is_finite() && at.y.is_finite()) {
        eprintln!("step {step}: the character went non-finite: {at:?}");
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

/// Prints the heap and resident memory over the run; false on a leak.
fn report_memory(samples: &[Sample], saves: &[SavePoint], left: i64) -> bool {
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
    !failed
}
