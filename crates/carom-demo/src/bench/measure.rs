//! One measurement: a scene run with one solver setting, its step times and its error against
//! the scene's exact answer (see [`carom_scene::Accuracy`]).

use carom::{BodyKind, Effect, Real, SolverKind, Vec2, World};
use carom_scene::{Accuracy, Scene, SceneWorld};
use std::time::Instant;

/// The solver setting a point of the sweep runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Setting {
    /// The solver.
    pub solver: SolverKind,
    /// Velocity iterations (per substep for soft step).
    pub iterations: u32,
    /// Substeps (1 for the solvers without them).
    pub substeps: u32,
}

/// What one run of a setting gave.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// Wall time of every step taken, ms.
    pub step_ms: Vec<f64>,
    /// The error, in [`ErrorKind::unit`]s; infinite if the world went NaN.
    pub error: f64,
    /// The deepest overlap seen in any step, m.
    pub max_penetration: f64,
}

/// How a scene's error is defined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// Distance from the exact resting pose.
    Rest,
    /// Relative change of momentum or energy.
    Conservation,
    /// Error of the angle at which sliding starts.
    SlideAngle,
    /// No exact answer: the deepest overlap.
    Overlap,
}

impl ErrorKind {
    /// The error's kind for a scene.
    pub fn of(accuracy: Option<&Accuracy>) -> Self {
        match accuracy {
            Some(Accuracy::Rest { .. }) => ErrorKind::Rest,
            Some(Accuracy::Conservation { .. }) => ErrorKind::Conservation,
            Some(Accuracy::SlideAngle { .. }) => ErrorKind::SlideAngle,
            None => ErrorKind::Overlap,
        }
    }

    /// What the error measures, for tables and charts.
    pub fn description(self) -> &'static str {
        match self {
            ErrorKind::Rest => "distance from the resting pose after the run",
            ErrorKind::Conservation => "relative change of momentum or kinetic energy",
            ErrorKind::SlideAngle => "error of the angle at which the box starts to slide",
            ErrorKind::Overlap => "deepest overlap (no exact answer)",
        }
    }

    /// The error's unit.
    pub fn unit(self) -> &'static str {
        match self {
            ErrorKind::Rest | ErrorKind::Overlap => "m",
            ErrorKind::Conservation => "ratio",
            ErrorKind::SlideAngle => "deg",
        }
    }
}

/// Runs `scene` once with `setting` and measures it. `default_seconds` is how long a scene
/// without an accuracy measure runs.
pub fn measure(
    scene: &Scene,
    file: &str,
    setting: Setting,
    default_seconds: f32,
) -> Result<Measurement, String> {
    let mut run = Run::new(scene, file, setting)?;
    let time_step = run.scene.time_step;
    let seconds_to_steps = |seconds: f32| (seconds / time_step).ceil().max(1.0) as usize;
    let error = match &scene.accuracy {
        Some(Accuracy::Rest { bodies, seconds }) => {
            let bodies: Vec<carom::BodyHandle> = if bodies.is_empty() {
                highest_dynamic_body(&run.scene.world).into_iter().collect()
            } else {
                bodies.iter().map(|name| run.scene.names[name]).collect()
            };
            let starts: Vec<Vec2> = bodies.iter().map(|&h| run.position(h)).collect();
            run.steps(seconds_to_steps(*seconds))?;
            bodies
                .iter()
                .zip(&starts)
                .map(|(&h, start)| (run.position(h) - start).norm() as f64)
                .fold(0.0, f64::max)
        }
        Some(Accuracy::Conservation { seconds }) => {
            run.scene.fire_events();
            let (momentum, energy) = momentum_and_energy(&run.scene.world);
            run.steps(seconds_to_steps(*seconds))?;
            let (momentum_end, energy_end) = momentum_and_energy(&run.scene.world);
            let change = (momentum_end[0] - momentum[0]).hypot(momentum_end[1] - momentum[1]);
            let momentum_error = change / momentum[0].hypot(momentum[1]).max(1e-12);
            let energy_error = (energy_end - energy).abs() / energy.max(1e-12);
            momentum_error.max(energy_error)
        }
        Some(Accuracy::SlideAngle {
            body,
            friction,
            seconds,
        }) => {
            let steps = seconds_to_steps(*seconds);
            let critical = (*friction as f64).atan();
            let angle = slide_angle(scene, file, setting, body, critical, steps, &mut run)?;
            (angle - critical).abs().to_degrees()
        }
        None => {
            run.steps(seconds_to_steps(default_seconds))?;
            run.max_penetration
        }
    };
    Ok(Measurement {
        error: if run.nan { f64::INFINITY } else { error },
        max_penetration: run.max_penetration,
        step_ms: run.step_ms,
    })
}

/// A scene being run with a setting, timing every step.
struct Run {
    scene: SceneWorld,
    step_ms: Vec<f64>,
    max_penetration: f64,
    nan: bool,
}

impl Run {
    fn new(scene: &Scene, file: &str, setting: Setting) -> Result<Self, String> {
        let mut built = carom_scene::build(scene, file).map_err(|e| e.to_string())?;
        let mut params = *built.world.solver();
        params.kind = setting.solver;
        params.impulse_resolution = true;
        params.iterations = setting.iterations;
        params.substeps = setting.substeps;
        built.world.set_solver(params).map_err(|e| e.to_string())?;
        // Every step is solved: a setting that settles sooner would otherwise look cheaper
        // only because its bodies sleep.
        built.world.set_effect(Effect::Sleeping, false);
        Ok(Run {
            scene: built,
            step_ms: Vec::new(),
            max_penetration: 0.0,
            nan: false,
        })
    }

    fn steps(&mut self, count: usize) -> Result<(), String> {
        for _ in 0..count {
            let clock = Instant::now();
            self.scene.step().map_err(|e| e.to_string())?;
            self.step_ms.push(clock.elapsed().as_secs_f64() * 1e3);
            let stats = self.scene.world.stats();
            self.max_penetration = self.max_penetration.max(stats.max_penetration as f64);
            self.nan |= !stats.kinetic_energy.is_finite();
        }
        Ok(())
    }

    fn position(&self, handle: carom::BodyHandle) -> Vec2 {
        self.scene
            .world
            .body(handle)
            .map(|b| b.position())
            .unwrap_or_else(Vec2::zeros)
    }
}

/// The dynamic body whose centre is highest (the top box of a stack or pyramid).
fn highest_dynamic_body(world: &World) -> Option<carom::BodyHandle> {
    world
        .bodies()
        .filter(|b| b.kind() == BodyKind::Dynamic)
        .max_by(|a, b| a.position().y.total_cmp(&b.position().y))
        .map(|b| b.handle())
}

/// Total linear momentum and kinetic energy of the dynamic bodies, summed in double precision.
fn momentum_and_energy(world: &World) -> ([f64; 2], f64) {
    let mut momentum = [0.0; 2];
    let mut energy = 0.0;
    for body in world.bodies().filter(|b| b.kind() == BodyKind::Dynamic) {
        let (v, mass) = (body.linear_velocity(), body.mass() as f64);
        momentum[0] += v.x as f64 * mass;
        momentum[1] += v.y as f64 * mass;
        energy += body.kinetic_energy() as f64;
    }
    (momentum, energy)
}

/// Finds by bisection the slope angle (rad) at which the named body starts to slide, tilting
/// gravity instead of the slope: a tilt of `φ` clockwise makes its slope `α + φ` steep, where
/// `α` is the body's starting angle. Every trial is timed into `run`.
fn slide_angle(
    scene: &Scene,
    file: &str,
    setting: Setting,
    body: &str,
    critical: f64,
    steps: usize,
    run: &mut Run,
) -> Result<f64, String> {
    const TRIALS: usize = 14;
    // The body moved more than this: it slides.
    const SLID: Real = 0.005;
    let slides = |angle: f64, run: &mut Run| -> Result<bool, String> {
        let mut trial = Run::new(scene, file, setting)?;
        let handle = trial.scene.names[body];
        let slope = trial.scene.world.body(handle).map_or(0.0, |b| b.angle()) as f64;
        let g = trial.scene.world.gravity().norm() as f64;
        let tilt = angle - slope;
        let gravity = carom::vec2((-g * tilt.sin()) as Real, (-g * tilt.cos()) as Real);
        trial
            .scene
            .world
            .set_gravity(gravity)
            .map_err(|e| e.to_string())?;
        let start = trial.position(handle);
        trial.steps(steps)?;
        let moved = (trial.position(handle) - start).norm();
        run.step_ms.append(&mut trial.step_ms);
        run.max_penetration = run.max_penetration.max(trial.max_penetration);
        run.nan |= trial.nan;
        Ok(!moved.is_finite() || moved > SLID)
    };
    let (mut low, mut high) = (0.0, (2.0 * critical).min(80f64.to_radians()));
    if slides(low, run)? {
        return Ok(low);
    }
    if !slides(high, run)? {
        return Ok(high);
    }
    for _ in 0..TRIALS {
        let middle = 0.5 * (low + high);
        if slides(middle, run)? {
            high = middle;
        } else {
            low = middle;
        }
    }
    Ok(0.5 * (low + high))
}
