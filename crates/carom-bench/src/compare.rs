//! One timed run of a scene in one engine, measured the way Box2D's benchmark harness does.

use stats_alloc::{INSTRUMENTED_SYSTEM, Region};
use std::time::Instant;

use carom::{BodyKind, World};

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
    /// Heap allocations during the timed steps (counted only where the program's global
    /// allocator is [`stats_alloc::INSTRUMENTED_SYSTEM`], as in the `carom-bench` binary).
    pub allocations: usize,
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

/// Steps a carom world `steps` times by `dt`, timing all steps but the first.
///
/// # Errors
/// A failed carom step.
pub fn run_carom(world: &mut World, dt: f32, steps: u32) -> Result<RunResult, String> {
    let start = carom_positions(world);
    let top = top_body(&start, &carom_dynamic_flags(world));
    let (mut total_ms, mut allocations) = (0.0, 0);
    if steps > 0 {
        world.step(dt).map_err(|e| e.to_string())?;
        let region = Region::new(&INSTRUMENTED_SYSTEM);
        let t0 = Instant::now();
        for _ in 1..steps {
            world.step(dt).map_err(|e| e.to_string())?;
        }
        total_ms = t0.elapsed().as_secs_f64() * 1e3;
        allocations = region.change().allocations;
    }
    let end = carom_positions(world);
    Ok(RunResult {
        total_ms,
        timed_steps: steps.saturating_sub(1),
        top_drop: drop_of(top, &start, &end),
        nan: any_nan(&end),
        allocations,
    })
}

/// Steps a Box2D world `steps` times by `dt` (in its substeps, on one worker), timing all
/// but the first. Box2D allocates through C's allocator, which is not counted.
///
/// # Errors
/// A failed Box2D step or body query.
pub fn run_box2d(world: &mut Box2dWorld, dt: f32, steps: u32) -> Result<RunResult, String> {
    let positions = |world: &mut Box2dWorld| -> Result<Vec<[f32; 2]>, String> {
        (0..world.body_count()).map(|i| world.position(i)).collect()
    };
    let start = positions(world)?;
    let dynamic: Vec<bool> = (0..world.body_count())
        .map(|i| world.kind(i) == BodyKind::Dynamic)
        .collect();
    let top = top_body(&start, &dynamic);
    let mut total_ms = 0.0;
    if steps > 0 {
        world.step(dt)?;
        let t0 = Instant::now();
        for _ in 1..steps {
            world.step(dt)?;
        }
        total_ms = t0.elapsed().as_secs_f64() * 1e3;
    }
    let end = positions(world)?;
    Ok(RunResult {
        total_ms,
        timed_steps: steps.saturating_sub(1),
        top_drop: drop_of(top, &start, &end),
        nan: any_nan(&end),
        allocations: 0,
    })
}

/// Steps a Rapier world `steps` times (by the dt it was built with), timing all but the first.
pub fn run_rapier(world: &mut RapierWorld, steps: u32) -> RunResult {
    let start = world.positions();
    let top = top_body(&start, &world.dynamic_flags());
    let (mut total_ms, mut allocations) = (0.0, 0);
    if steps > 0 {
        world.step();
        let region = Region::new(&INSTRUMENTED_SYSTEM);
        let t0 = Instant::now();
        for _ in 1..steps {
            world.step();
        }
        total_ms = t0.elapsed().as_secs_f64() * 1e3;
        allocations = region.change().allocations;
    }
    let end = world.positions();
    RunResult {
        total_ms,
        timed_steps: steps.saturating_sub(1),
        top_drop: drop_of(top, &start, &end),
        nan: any_nan(&end),
        allocations,
    }
}
