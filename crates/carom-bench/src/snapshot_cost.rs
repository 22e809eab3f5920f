//! What rewinding costs beside a step (`carom-bench snapshots`): a scene is stepped to where it
//! is in full motion, then each round takes a snapshot into the last round's, steps, and
//! restores it, so every round times the same step, snapshot and restore.

use carom_scene::SceneWorld;
use std::time::{Duration, Instant};

/// One scene's times, each the minimum and median over the rounds.
#[derive(Debug, Clone, Copy)]
pub struct SnapshotCost {
    /// One step of the scene.
    pub step: Spread,
    /// Taking a snapshot into one taken before (its memory reused).
    pub snapshot: Spread,
    /// Restoring the world from a snapshot.
    pub restore: Spread,
}

/// A time's minimum and median over rounds.
#[derive(Debug, Clone, Copy)]
pub struct Spread {
    /// The fastest round.
    pub min: Duration,
    /// The middle round.
    pub median: Duration,
}

impl Spread {
    fn of(mut times: Vec<Duration>) -> Spread {
        times.sort_unstable();
        Spread {
            min: times.first().copied().unwrap_or_default(),
            median: times.get(times.len() / 2).copied().unwrap_or_default(),
        }
    }
}

impl SnapshotCost {
    /// Snapshot plus restore over one step, from the medians.
    pub fn ratio(&self) -> f64 {
        (self.snapshot.median + self.restore.median).as_secs_f64()
            / self.step.median.as_secs_f64().max(1e-12)
    }
}

/// Times `rounds` rounds of snapshot, step and restore on `scene`, after `warm_up` steps,
/// on the calling thread's pool.
pub fn measure(scene: &mut SceneWorld, warm_up: u32, rounds: u32) -> Result<SnapshotCost, String> {
    let step =
        |scene: &mut SceneWorld| scene.world.step(scene.time_step).map_err(|e| e.to_string());
    for _ in 0..warm_up {
        step(scene)?;
    }
    let mut snapshot = scene.world.snapshot();
    let (mut steps, mut snapshots, mut restores) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..rounds {
        let start = Instant::now();
        scene.world.snapshot_into(&mut snapshot);
        snapshots.push(start.elapsed());
        let start = Instant::now();
        step(scene)?;
        steps.push(start.elapsed());
        let start = Instant::now();
        scene.world.restore(&snapshot);
        restores.push(start.elapsed());
    }
    Ok(SnapshotCost {
        step: Spread::of(steps),
        snapshot: Spread::of(snapshots),
        restore: Spread::of(restores),
    })
}
