//! `carom run`: a scene headless, and what it measured.

use carom::{Effect, Real, SolverKind};
use carom_scene::SceneWorld;
use std::path::Path;
use web_time::Instant;

/// How to run a scene, beyond what the scene file says.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Steps to take.
    pub steps: usize,
    /// Replace the scene's solver.
    pub solver: Option<SolverKind>,
    /// Replace the iteration count.
    pub iterations: Option<u32>,
    /// Replace the substep count.
    pub substeps: Option<u32>,
    /// Effects to add (`true`) or remove (`false`).
    pub effects: Vec<(Effect, bool)>,
    /// Threads the world steps on (default: rayon's, one per core).
    pub threads: Option<usize>,
}

/// What a run measured.
#[derive(Debug, Clone, PartialEq)]
pub struct RunReport {
    /// Mean wall time of a step, the first left out (as Box2D's benchmark does), ms.
    pub ms_per_step: f64,
    /// Median wall time of a step, ms.
    pub ms_per_step_median: f64,
    /// Steps taken.
    pub steps: usize,
    /// Bodies in the world.
    pub bodies: usize,
    /// Contacts at the end.
    pub contacts: usize,
    /// The deepest overlap seen in any step, m.
    pub max_penetration: Real,
    /// Kinetic energy at the end, J.
    pub kinetic_energy: Real,
    /// The fastest body seen in any step, m/s.
    pub max_speed: Real,
    /// True if any position or velocity ever went NaN or infinite.
    pub nan: bool,
    /// Bodies asleep at the end.
    pub asleep: usize,
    /// Fingerprint of the final positions and velocities.
    pub hash: u64,
    /// Mean ms per step in each stage (broadphase, narrowphase, solve, continuous, sleep),
    /// then in the parts of solve that prepare and store, the first step left out.
    pub stage_ms: [f64; 7],
}

impl RunReport {
    /// One JSON object with the keys in a fixed order.
    pub fn to_json(&self) -> String {
        format!(
            "{{\"ms_per_step\": {}, \"ms_per_step_median\": {}, \"steps\": {}, \"bodies\": {}, \
             \"contacts\": {}, \"max_penetration\": {}, \"kinetic_energy\": {}, \
             \"max_speed\": {}, \"nan\": {}, \"asleep\": {}, \"hash\": \"{:016x}\"}}",
            json_number(self.ms_per_step),
            json_number(self.ms_per_step_median),
            self.steps,
            self.bodies,
            self.contacts,
            json_number(self.max_penetration as f64),
            json_number(self.kinetic_energy as f64),
            json_number(self.max_speed as f64),
            self.nan,
            self.asleep,
            self.hash
        )
    }

    /// A few lines for people.
    pub fn summary(&self, name: &str) -> String {
        format!(
            "{name}: {} steps, {} bodies, {} contacts\n\
             time      {:.4} ms/step (mean after the first), {:.4} ms/step (median)\n\
             accuracy  max penetration {:.5} m, max speed {:.3} m/s, kinetic energy {:.4} J\n\
             state     {} asleep, nan: {}, hash {:016x}\n\
             stages    broadphase {:.3}, narrowphase {:.3}, solve {:.3} (prepare {:.3}, store \
             {:.3}), continuous {:.3}, sleep {:.3} ms/step",
            self.steps,
            self.bodies,
            self.contacts,
            self.ms_per_step,
            self.ms_per_step_median,
            self.max_penetration,
            self.max_speed,
            self.kinetic_energy,
            self.asleep,
            self.nan,
            self.hash,
            self.stage_ms[0],
            self.stage_ms[1],
            self.stage_ms[2],
            self.stage_ms[5],
            self.stage_ms[6],
            self.stage_ms[3],
            self.stage_ms[4],
        )
    }
}

/// JSON has no NaN or infinity: they become null.
fn json_number(value: f64) -> String {
    if value.is_finite() {
        format!("{value}")
    } else {
        "null".into()
    }
}

/// Loads a scene, applies the options, and runs it, on `options.threads` threads.
pub fn run(file: &Path, options: &RunOptions) -> Result<RunReport, String> {
    match options.threads {
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| e.to_string())?
            .install(|| run_here(file, options)),
        None => run_here(file, options),
    }
}

/// [`run`] on the calling thread's pool.
fn run_here(file: &Path, options: &RunOptions) -> Result<RunReport, String> {
    let mut scene = crate::files::load_scene(file).map_err(|e| e.to_string())?;
    apply(&mut scene, options)?;
    let mut times = Vec::with_capacity(options.steps);
    let (mut max_penetration, mut max_speed, mut nan) = (0.0 as Real, 0.0 as Real, false);
    let mut stage_ms = [0.0; 7];
    for step in 0..options.steps {
        let clock = Instant::now();
        scene.step().map_err(|e| e.to_string())?;
        times.push(clock.elapsed().as_secs_f64() * 1e3);
        if step > 0 {
            let t = scene.world.stats().times;
            let stages = [
                t.broadphase,
                t.narrowphase,
                t.solve,
                t.continuous,
                t.sleep,
                t.prepare,
                t.store,
            ];
            for (sum, stage) in stage_ms.iter_mut().zip(stages) {
                *sum += stage.as_secs_f64() * 1e3 / (options.steps - 1) as f64;
            }
        }
        max_penetration = max_penetration.max(scene.world.stats().max_penetration);
        for body in scene.world.bodies() {
            let (p, v) = (body.position(), body.linear_velocity());
            nan |= !(p.iter().chain(v.iter()).all(|x| x.is_finite())
                && body.angular_velocity().is_finite());
            max_speed = max_speed.max(v.norm());
        }
    }
    let timed = &times[times.len().min(1)..];
    let ms_per_step = if timed.is_empty() {
        0.0
    } else {
        timed.iter().sum::<f64>() / timed.len() as f64
    };
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let stats = scene.world.stats();
    Ok(RunReport {
        ms_per_step,
        ms_per_step_median: sorted.get(sorted.len() / 2).copied().unwrap_or(0.0),
        steps: options.steps,
        bodies: scene.world.body_count(),
        contacts: scene.world.contacts().len(),
        max_penetration,
        kinetic_energy: stats.kinetic_energy,
        max_speed,
        nan,
        asleep: stats.sleeping_bodies,
        hash: scene.world.state_hash(),
        stage_ms,
    })
}

/// Overrides the scene's solver settings and effects.
fn apply(scene: &mut SceneWorld, options: &RunOptions) -> Result<(), String> {
    let mut solver = *scene.world.solver();
    if let Some(kind) = options.solver {
        // Another solver starts from its own iteration count.
        solver.kind = kind;
        solver.iterations = None;
    }
    solver.iterations = options.iterations.or(solver.iterations);
    solver.substeps = options.substeps.unwrap_or(solver.substeps);
    scene
        .world
        .update_settings(|s| {
            s.solver = solver;
            for &(effect, on) in &options.effects {
                s.effects.set(effect, on);
            }
        })
        .map_err(|e| e.to_string())
}
