//! One timed run of a scene in one engine, measured the way Box2D's benchmark harness does.

use stats_alloc::{INSTRUMENTED_SYSTEM, Region};
use std::time::Instant;

use carom::{BodyKind, World};
use carom_scene::{Made, SceneWorld, SpawnChange, SpawnSchedule};

use crate::box2d_world::Box2dWorld;
use crate::rapier_world::RapierWorld;

/// What one run of a scene in one engine measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunResult {
    /// Wall time of the timed steps (every step but the first), ms.
    pub total_ms: f64,
    /// Timed steps.
    pub timed_steps: u32,
    /// How far the highest dynamic body at the start fell by the end, m (NaN if none).
    pub top_drop: f32,
    /// True when any body's position became NaN or infinite.
    pub nan: bool,
    /// Heap allocations in the timed steps proper (a block grown or moved counts as one), not
    /// in a scene's spawns before them
    /// (counted only where the program's global allocator is
    /// [`stats_alloc::INSTRUMENTED_SYSTEM`], as in the `carom-bench` binary).
    pub allocations: usize,
    /// What the stages took and did, per timed step (carom's and Box2D's; none for Rapier).
    pub stages: Option<StageProfile>,
    /// The deepest overlap the narrowphase found at the start of a timed step, m, over the
    /// run and on average over the steps (carom's, which reports it at no cost; NaN for the
    /// peers: see [`box2d_deepest_overlap`]).
    pub deepest_overlap: Overlap,
}

/// The deepest overlap found at the start of each step: the most over the steps, and their
/// mean, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// The deepest of all the steps'.
    pub most: f32,
    /// The mean over the steps of each step's deepest.
    pub mean: f32,
}

impl Overlap {
    /// Not measured.
    pub const NAN: Overlap = Overlap {
        most: f32::NAN,
        mean: f32::NAN,
    };

    /// Of the steps' deepest overlaps `deepest`.
    fn of(deepest: &[f32]) -> Overlap {
        let sum: f64 = deepest.iter().map(|&d| f64::from(d)).sum();
        Overlap {
            most: deepest.iter().copied().fold(0.0, f32::max),
            mean: (sum / deepest.len().max(1) as f64) as f32,
        }
    }
}

/// The mean per timed step of each stage's time and of the work behind it, in carom's
/// stages. Box2D's profile maps onto them: broadphase = pairs + refit, narrowphase =
/// collide, continuous = bullets, sleep = sleep islands + split islands, solve = the rest of
/// its solve.
/// A count an engine does not report is NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StageProfile {
    /// The whole step, ms.
    pub step_ms: f64,
    /// Finding new pairs and keeping the trees, ms.
    pub broadphase_ms: f64,
    /// Building manifolds and the bookkeeping after, ms.
    pub narrowphase_ms: f64,
    /// Integrating and solving (with placing the moved shapes), ms.
    pub solve_ms: f64,
    /// Sweeping fast bodies, ms.
    pub continuous_ms: f64,
    /// Sleep timers and islands, ms.
    pub sleep_ms: f64,
    /// Contacts held (touching or not).
    pub contacts: f64,
    /// Contacts whose manifolds the narrowphase updated (the awake ones).
    pub awake_contacts: f64,
    /// Of those, manifolds carried along instead of built.
    pub recycled: f64,
    /// Contacts with points.
    pub touching: f64,
    /// Contacts created and destroyed.
    pub created: f64,
    /// Contacts destroyed.
    pub destroyed: f64,
    /// Colliders moved in the broadphase.
    pub proxies_moved: f64,
    /// Candidate pairs the broadphase's queries met.
    pub candidates: f64,
    /// Islands split.
    pub island_splits: f64,
}

impl StageProfile {
    fn zero() -> Self {
        StageProfile {
            step_ms: 0.0,
            broadphase_ms: 0.0,
            narrowphase_ms: 0.0,
            solve_ms: 0.0,
            continuous_ms: 0.0,
            sleep_ms: 0.0,
            contacts: 0.0,
            awake_contacts: 0.0,
            recycled: 0.0,
            touching: 0.0,
            created: 0.0,
            destroyed: 0.0,
            proxies_moved: 0.0,
            candidates: 0.0,
            island_splits: 0.0,
        }
    }

    /// Every field divided by `steps` (the sums over steps become means).
    fn mean(self, steps: u32) -> Self {
        let n = f64::from(steps.max(1));
        StageProfile {
            step_ms: self.step_ms / n,
            broadphase_ms: self.broadphase_ms / n,
            narrowphase_ms: self.narrowphase_ms / n,
            solve_ms: self.solve_ms / n,
            continuous_ms: self.continuous_ms / n,
            sleep_ms: self.sleep_ms / n,
            contacts: self.contacts / n,
            awake_contacts: self.awake_contacts / n,
            recycled: self.recycled / n,
            touching: self.touching / n,
            created: self.created / n,
            destroyed: self.destroyed / n,
            proxies_moved: self.proxies_moved / n,
            candidates: self.candidates / n,
            island_splits: self.island_splits / n,
        }
    }

    /// `[step, broadphase, narrowphase, solve, continuous, sleep]`, ms per step.
    pub fn ms(&self) -> [f64; 6] {
        [
            self.step_ms,
            self.broadphase_ms,
            self.narrowphase_ms,
            self.solve_ms,
            self.continuous_ms,
            self.sleep_ms,
        ]
    }

    /// Two lines for a terminal: each stage's ms per step, then the work behind them.
    pub fn describe(&self) -> String {
        format!(
            "step {:.3} ms: broadphase {:.3}, narrowphase {:.3}, solve {:.3}, continuous {:.3}, \
             sleep {:.3}\ncontacts {:.0} (awake {:.0}, recycled {:.0}, touching {:.0}), \
             created {:.1}, destroyed {:.1}, proxies moved {:.0}, pair candidates {:.0}, \
             island splits {:.2}",
            self.step_ms,
            self.broadphase_ms,
            self.narrowphase_ms,
            self.solve_ms,
            self.continuous_ms,
            self.sleep_ms,
            self.contacts,
            self.awake_contacts,
            self.recycled,
            self.touching,
            self.created,
            self.destroyed,
            self.proxies_moved,
            self.candidates,
            self.island_splits,
        )
    }

    /// Adds carom's statistics of one step.
    fn add_carom(&mut self, stats: &carom::StepStats) {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let (t, w) = (&stats.times, &stats.collision);
        self.step_ms += ms(t.total);
        self.broadphase_ms += ms(t.broadphase);
        self.narrowphase_ms += ms(t.narrowphase);
        self.solve_ms += ms(t.solve);
        self.continuous_ms += ms(t.continuous);
        self.sleep_ms += ms(t.sleep);
        self.contacts += stats.contacts as f64;
        self.awake_contacts += (w.manifolds_built + w.manifolds_recycled) as f64;
        self.recycled += w.manifolds_recycled as f64;
        self.touching += stats.touching_contacts as f64;
        self.created += w.contacts_created as f64;
        self.destroyed += w.contacts_destroyed as f64;
        self.proxies_moved += w.proxies_moved as f64;
        self.candidates += w.pair_candidates as f64;
        self.island_splits += w.island_splits as f64;
    }

    /// Adds Box2D's profile and counters of one step.
    fn add_box2d(&mut self, profile: &boxdd::Profile, counters: &boxdd::Counters) {
        let p = |x: f32| f64::from(x);
        self.step_ms += p(profile.step);
        self.broadphase_ms += p(profile.pairs) + p(profile.refit);
        self.narrowphase_ms += p(profile.collide);
        // Box2D splits an island during its solve (on a worker of its own when it has one);
        // carom's sleep stage holds its split, so Box2D's is counted there too.
        let sleep = p(profile.sleep_islands) + p(profile.split_islands);
        self.solve_ms += p(profile.solve) - p(profile.refit) - p(profile.bullets) - sleep;
        self.continuous_ms += p(profile.bullets);
        self.sleep_ms += sleep;
        self.contacts += f64::from(counters.contact_count);
        self.awake_contacts += f64::from(counters.awake_contact_count);
        self.recycled += f64::from(counters.recycled_contact_count);
        for unknown in [
            &mut self.touching,
            &mut self.created,
            &mut self.destroyed,
            &mut self.proxies_moved,
            &mut self.candidates,
            &mut self.island_splits,
        ] {
            *unknown = f64::NAN;
        }
    }
}

impl RunResult {
    /// Heap allocations per timed step.
    pub fn allocations_per_step(&self) -> f64 {
        if self.timed_steps == 0 {
            0.0
        } else {
            self.allocations as f64 / f64::from(self.timed_steps)
        }
    }

    /// Milliseconds per timed step.
    pub fn ms_per_step(&self) -> f64 {
        if self.timed_steps == 0 {
            0.0
        } else {
            self.total_ms / f64::from(self.timed_steps)
        }
    }
}

/// Index of the highest dynamic body, given positions and dynamic flags in the same order.
pub fn top_body(positions: &[[f32; 2]], dynamic: &[bool]) -> Option<usize> {
    positions
        .iter()
        .zip(dynamic)
        .enumerate()
        .filter(|(_, (_, d))| **d)
        .max_by(|(_, (a, _)), (_, (b, _))| a[1].total_cmp(&b[1]))
        .map(|(i, _)| i)
}

/// Positions of a carom world's bodies in `bodies()` order.
pub fn carom_positions(world: &World) -> Vec<[f32; 2]> {
    world
        .bodies()
        .map(|b| [b.position().x, b.position().y])
        .collect()
}

/// Whether each carom body is dynamic, in `bodies()` order.
pub fn carom_dynamic_flags(world: &World) -> Vec<bool> {
    world
        .bodies()
        .map(|b| b.kind() == BodyKind::Dynamic)
        .collect()
}

fn any_nan(positions: &[[f32; 2]]) -> bool {
    positions
        .iter()
        .any(|p| !(p[0].is_finite() && p[1].is_finite()))
}

fn drop_of(top: Option<usize>, start: &[[f32; 2]], end: &[[f32; 2]]) -> f32 {
    top.map_or(f32::NAN, |i| start[i][1] - end[i][1])
}

/// Steps a scene `steps` times by its time step, its events firing before each step as they
/// do in the demo (spawned bodies are made and removed inside the timed steps, as Box2D's
/// benchmark does in its step function), timing all steps but the first.
///
/// # Errors
/// A failed carom step.
pub fn run_carom(scene: &mut SceneWorld, steps: u32) -> Result<RunResult, String> {
    let start = carom_positions(&scene.world);
    let top = top_body(&start, &carom_dynamic_flags(&scene.world))
        .and_then(|i| scene.world.bodies().nth(i))
        .map(|b| (b.handle(), b.position().y));
    let (mut total_ms, mut allocations) = (0.0, 0);
    let mut stages = StageProfile::zero();
    let mut deepest = Vec::with_capacity(steps as usize);
    if steps > 0 {
        scene.step().map_err(|e| e.to_string())?;
        let t0 = Instant::now();
        for _ in 1..steps {
            // Allocations are counted in the step proper, not in the spawns before it.
            scene.fire_events();
            let region = Region::new(&INSTRUMENTED_SYSTEM);
            scene
                .world
                .step(scene.time_step)
                .map_err(|e| e.to_string())?;
            allocations += heap_calls(region.change());
            stages.add_carom(scene.world.stats());
            deepest.push(scene.world.stats().max_penetration);
        }
        total_ms = t0.elapsed().as_secs_f64() * 1e3;
    }
    // The top body by its handle: events may have added and removed bodies since.
    let top_drop = top.map_or(f32::NAN, |(handle, y)| {
        scene
            .world
            .body(handle)
            .map_or(f32::NAN, |b| y - b.position().y)
    });
    Ok(RunResult {
        total_ms,
        timed_steps: steps.saturating_sub(1),
        top_drop,
        nan: any_nan(&carom_positions(&scene.world)),
        allocations,
        stages: Some(stages.mean(steps.saturating_sub(1))),
        deepest_overlap: Overlap::of(&deepest),
    })
}

/// The calls that took memory from the heap in `change`: new blocks, and blocks grown or moved.
fn heap_calls(change: stats_alloc::Stats) -> usize {
    change.allocations + change.reallocations
}

/// A spawn schedule's changes, done before the steps they name, in order.
struct Replay<'a> {
    schedule: Option<&'a SpawnSchedule>,
    next: usize,
}

impl<'a> Replay<'a> {
    fn new(schedule: Option<&'a SpawnSchedule>) -> Self {
        Replay { schedule, next: 0 }
    }

    /// Does every change due before step `step` in `world`.
    fn before(&mut self, step: u64, world: &mut impl Spawns) -> Result<(), String> {
        let Some(schedule) = self.schedule else {
            return Ok(());
        };
        while let Some(change) = schedule.changes.get(self.next) {
            if change.step() > step {
                break;
            }
            match *change {
                SpawnChange::Add { copy, .. } => {
                    world.add_spawned(copy, &schedule.world, &schedule.copies[copy])?
                }
                SpawnChange::Remove { copy, .. } => world.remove_spawned(copy)?,
            }
            self.next += 1;
        }
        Ok(())
    }
}

/// A peer that makes and removes the copies of a scene's spawn events.
trait Spawns {
    /// Makes copy `copy`: `made`'s bodies and joints of `world`.
    fn add_spawned(&mut self, copy: usize, world: &World, made: &Made) -> Result<(), String>;
    /// Removes copy `copy`.
    fn remove_spawned(&mut self, copy: usize) -> Result<(), String>;
}

impl Spawns for Box2dWorld {
    fn add_spawned(&mut self, copy: usize, world: &World, made: &Made) -> Result<(), String> {
        Box2dWorld::add_spawned(self, copy, world, made)
    }

    fn remove_spawned(&mut self, copy: usize) -> Result<(), String> {
        Box2dWorld::remove_spawned(self, copy)
    }
}

impl Spawns for RapierWorld {
    fn add_spawned(&mut self, copy: usize, world: &World, made: &Made) -> Result<(), String> {
        RapierWorld::add_spawned(self, copy, world, made)
    }

    fn remove_spawned(&mut self, copy: usize) -> Result<(), String> {
        RapierWorld::remove_spawned(self, copy)
    }
}

/// Steps a Box2D world `steps` times by `dt` (in its substeps, on one worker), timing all
/// but the first. The changes of a scene's spawn `schedule` are made before the steps they
/// name, inside the timed steps as Box2D's benchmark makes them. Box2D allocates through C's
/// allocator, which is not counted.
///
/// # Errors
/// A failed Box2D step, body query, or spawned body Box2D refuses.
pub fn run_box2d(
    world: &mut Box2dWorld,
    dt: f32,
    steps: u32,
    schedule: Option<&SpawnSchedule>,
) -> Result<RunResult, String> {
    let positions = |world: &mut Box2dWorld| -> Result<Vec<[f32; 2]>, String> {
        (0..world.body_count()).map(|i| world.position(i)).collect()
    };
    let start = positions(world)?;
    let dynamic: Vec<bool> = (0..world.body_count())
        .map(|i| world.kind(i) == BodyKind::Dynamic)
        .collect();
    let top = top_body(&start, &dynamic);
    let mut replay = Replay::new(schedule);
    // Allocations are counted in the step proper, not in the spawns before it (seen only once
    // Box2D's are routed through Rust's allocator: `box2d_heap`).
    let mut step = |world: &mut Box2dWorld, i: u32| -> Result<usize, String> {
        replay.before(u64::from(i), world)?;
        let region = Region::new(&INSTRUMENTED_SYSTEM);
        world.step(dt)?;
        Ok(heap_calls(region.change()))
    };
    let (mut total_ms, mut allocations) = (0.0, 0);
    let mut stages = StageProfile::zero();
    if steps > 0 {
        step(world, 0)?;
        let t0 = Instant::now();
        for i in 1..steps {
            allocations += step(world, i)?;
            stages.add_box2d(&world.profile()?, &world.counters()?);
        }
        total_ms = t0.elapsed().as_secs_f64() * 1e3;
    }
    let end = positions(world)?;
    let spawned = world.spawned_positions()?;
    Ok(RunResult {
        total_ms,
        timed_steps: steps.saturating_sub(1),
        top_drop: drop_of(top, &start, &end),
        nan: any_nan(&end) || any_nan(&spawned),
        allocations,
        stages: Some(stages.mean(steps.saturating_sub(1))),
        deepest_overlap: Overlap::NAN,
    })
}

/// The deepest overlap Box2D's narrowphase finds at the start of a step, m, over steps
/// `1..steps` of `world` (the steps [`run_box2d`] times), a scene's spawn `schedule`
/// followed as there, and whether any body's contacts could not be read back (the figure is
/// then a lower bound: see [`Box2dWorld::max_penetration_read`]). Untimed: reading every
/// contact back after each step costs more than the step.
///
/// # Errors
/// A spawned body Box2D cannot build, or one it no longer holds.
pub fn box2d_deepest_overlap(
    world: &mut Box2dWorld,
    dt: f32,
    steps: u32,
    schedule: Option<&SpawnSchedule>,
) -> Result<(Overlap, bool), String> {
    let mut replay = Replay::new(schedule);
    let (mut deepest, mut unread) = (Vec::with_capacity(steps as usize), false);
    for i in 0..steps {
        replay.before(u64::from(i), world)?;
        world.step(dt)?;
        if i > 0 {
            let (step_deepest, refused) = world.max_penetration_read()?;
            deepest.push(step_deepest);
            unread |= refused > 0;
        }
    }
    Ok((Overlap::of(&deepest), unread))
}

/// Steps a Rapier world `steps` times (by the dt it was built with), timing all but the first;
/// a scene's spawn `schedule` is followed as in [`run_box2d`].
///
/// # Errors
/// A spawned body Rapier cannot build.
pub fn run_rapier(
    world: &mut RapierWorld,
    steps: u32,
    schedule: Option<&SpawnSchedule>,
) -> Result<RunResult, String> {
    let start = world.positions();
    let top = top_body(&start, &world.dynamic_flags());
    let mut replay = Replay::new(schedule);
    // Allocations are counted in the step proper, not in the spawns before it.
    let mut step = |world: &mut RapierWorld, i: u32| -> Result<usize, String> {
        replay.before(u64::from(i), world)?;
        let region = Region::new(&INSTRUMENTED_SYSTEM);
        world.step();
        Ok(heap_calls(region.change()))
    };
    let (mut total_ms, mut allocations) = (0.0, 0);
    if steps > 0 {
        step(world, 0)?;
        let t0 = Instant::now();
        for i in 1..steps {
            allocations += step(world, i)?;
        }
        total_ms = t0.elapsed().as_secs_f64() * 1e3;
    }
    let end = world.positions();
    let spawned = world.spawned_positions();
    Ok(RunResult {
        total_ms,
        timed_steps: steps.saturating_sub(1),
        top_drop: drop_of(top, &start, &end),
        nan: any_nan(&end) || any_nan(&spawned),
        allocations,
        stages: None,
        deepest_overlap: Overlap::NAN,
    })
}
