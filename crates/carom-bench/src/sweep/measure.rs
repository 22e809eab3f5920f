//! One measurement: a scene run with one solver setting, its step times and its error against
//! the scene's exact answer (see [`carom_scene::Accuracy`]).

use super::engine::Engine;
use super::peer::Peer;
use crate::cases::joint_measures::period;
use carom::{BodyHandle, BodyKind, Effect, Real, SolverKind, SolverParams, Vec2, World};
use carom_scene::{Accuracy, Scene, SceneWorld};
use web_time::Instant;

/// The engine and solver setting a point of the sweep runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting {
    /// The engine: carom, or a peer rebuilt from the carom scene.
    pub engine: Engine,
    /// carom's solver (soft step for Box2D and Rapier, whose solvers are of its kind).
    pub solver: SolverKind,
    /// Velocity iterations (per substep for soft step; Rapier's PGS iterations; 1 for
    /// Box2D, which has none to set).
    pub iterations: u32,
    /// Substeps (1 for the solvers without them; Rapier's solver iterations, which are its
    /// substeps).
    pub substeps: u32,
    /// Soft step's joint stiffness, Hz, where it is not the default: `None` runs the
    /// solver's 60 Hz (Box2D's), which the solver caps at a quarter of the substep rate.
    /// A scene's own stiffness is replaced either way, as its iterations and substeps are.
    pub joint_hertz: Option<Real>,
    /// Contact stiffness, Hz, where the sweep sets it (Box2D's); `None` keeps the scene's.
    pub contact_hertz: Option<Real>,
    /// Rapier's stabilization iterations per substep, where set.
    pub stabilization: Option<u32>,
    /// Soft step's direct joint trees ([`SolverParams::direct_joints`]).
    pub direct_joints: bool,
    /// Soft step's shock propagation ([`SolverParams::shock_propagation`]).
    pub shock_propagation: bool,
}

impl Setting {
    /// carom with `solver`, `iterations` and `substeps`, everything else at its default.
    pub fn carom(solver: SolverKind, iterations: u32, substeps: u32) -> Self {
        Setting {
            engine: Engine::Carom,
            solver,
            iterations,
            substeps,
            joint_hertz: None,
            contact_hertz: None,
            stabilization: None,
            direct_joints: false,
            shock_propagation: false,
        }
    }

    /// Solver passes over the constraints a step makes: iterations times substeps in carom,
    /// a solve and a relaxation per substep in Box2D, and the velocity and stabilization
    /// iterations of each substep in Rapier. What a step costs grows with it.
    pub fn passes_per_step(&self) -> u32 {
        match self.engine {
            Engine::Carom => self.iterations * self.substeps,
            Engine::Box2d => 2 * self.substeps,
            Engine::Rapier => self.substeps * (1 + self.stabilization.unwrap_or(1)),
        }
    }

    /// The joint stiffness the solver runs with `hertz` asked for, at `time_step` seconds per
    /// step: at most a quarter of the substep rate, as the solver caps it (Box2D's rule).
    pub fn capped_joint_hertz(&self, hertz: Real, time_step: Real) -> Real {
        let cap = 0.25 * self.substeps as f64 / time_step as f64;
        // To a thousandth of a hertz: 1/60 s in f32 makes 8 substeps' cap 119.99999 Hz, which
        // is 120 Hz as far as the solver goes and should read so.
        ((hertz as f64).min(cap) * 1000.0).round() as Real / 1000.0
    }
}

/// Whether a solver solves joints. Push-out and the tutorial's impulse solver leave joints
/// out, so on a scene with joints their error measures only the bodies falling apart.
pub fn solves_joints(solver: SolverKind) -> bool {
    matches!(solver, SolverKind::SequentialImpulse | SolverKind::SoftStep)
}

/// What one run of a setting gave.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// Wall time of every step taken, ms.
    pub step_ms: Vec<f64>,
    /// The errors, one per kind the scene's measure gives (two for [`Accuracy::Hinges`],
    /// one for the others), each in its [`ErrorKind::unit`]s; infinite if the world went NaN.
    pub errors: Vec<(ErrorKind, f64)>,
    /// The deepest overlap seen in any step, m.
    pub max_penetration: f64,
}

impl Measurement {
    /// The first error: the only one, for every measure but [`Accuracy::Hinges`].
    pub fn error(&self) -> f64 {
        self.errors.first().map_or(f64::INFINITY, |e| e.1)
    }
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
    /// Relative error of a swing's period.
    Period,
    /// Worst relative stretch of what a body hangs by.
    Stretch,
    /// Worst sum of joint separations along a span.
    Gaps,
    /// Worst separation of a hinge's anchors.
    HingeGap,
    /// Worst turn of a hinge past its limits.
    PastLimit,
    /// Deepest a body gets below the ground.
    Sink,
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
            Some(Accuracy::Period { .. }) => ErrorKind::Period,
            Some(Accuracy::Stretch { .. }) => ErrorKind::Stretch,
            Some(Accuracy::Gaps { .. }) => ErrorKind::Gaps,
            Some(Accuracy::Hinges { .. }) => ErrorKind::HingeGap,
            Some(Accuracy::Sink { .. }) => ErrorKind::Sink,
            None => ErrorKind::Overlap,
        }
    }

    /// A short name, to tell apart the errors of one scene.
    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::Rest => "drift",
            ErrorKind::Conservation => "conservation",
            ErrorKind::SlideAngle => "slide angle",
            ErrorKind::Period => "period",
            ErrorKind::Stretch => "stretch",
            ErrorKind::Gaps => "span stretch",
            ErrorKind::HingeGap => "hinge gap",
            ErrorKind::PastLimit => "past limits",
            ErrorKind::Sink => "sink",
            ErrorKind::Overlap => "overlap",
        }
    }

    /// What the error measures, for tables and charts.
    pub fn description(self) -> &'static str {
        match self {
            ErrorKind::Rest => "distance from the resting pose after the run",
            ErrorKind::Conservation => "relative change of momentum or kinetic energy",
            ErrorKind::SlideAngle => "error of the angle at which the box starts to slide",
            ErrorKind::Period => "error of the swing's period",
            ErrorKind::Stretch => "worst stretch of the joints holding the body",
            ErrorKind::Gaps => "worst stretch of the joints over their span",
            ErrorKind::HingeGap => "worst gap between a hinge's anchors",
            ErrorKind::PastLimit => "worst turn of a hinge past its limits",
            ErrorKind::Sink => "deepest a body gets below the ground",
            ErrorKind::Overlap => "deepest overlap (no exact answer)",
        }
    }

    /// The error's unit.
    pub fn unit(self) -> &'static str {
        match self {
            ErrorKind::Rest | ErrorKind::Overlap | ErrorKind::HingeGap | ErrorKind::Sink => "m",
            ErrorKind::Conservation => "ratio",
            ErrorKind::SlideAngle | ErrorKind::PastLimit => "deg",
            ErrorKind::Period | ErrorKind::Stretch | ErrorKind::Gaps => "%",
        }
    }
}

/// Runs `scene` once with `setting` and measures it. `default_seconds` is how long a scene
/// without an accuracy measure runs.
pub fn measure(
    scene: &Scene,
    file: &str,
    setting: Setting,
    default_seconds: Real,
) -> Result<Measurement, String> {
    let mut run = Run::new(scene, file, setting)?;
    let time_step = run.scene.time_step;
    let seconds_to_steps = |seconds: Real| (seconds / time_step).ceil().max(1.0) as usize;
    let kind = ErrorKind::of(scene.accuracy.as_ref());
    let errors = match &scene.accuracy {
        Some(Accuracy::Gaps { length, seconds }) => {
            let joints = JointFrame::all(&run.scene.world);
            let mut worst: f64 = 0.0;
            for _ in 0..seconds_to_steps(*seconds) {
                run.steps(1)?;
                let mut gaps = 0.0;
                for joint in &joints {
                    gaps += run.gap(joint);
                }
                worst = worse(worst, 100.0 * gaps / *length as f64);
            }
            vec![(kind, worst)]
        }
        Some(Accuracy::Hinges { seconds }) => {
            let hinges: Vec<JointFrame> = JointFrame::all(&run.scene.world)
                .into_iter()
                .filter(|j| j.hinge)
                .collect();
            let (mut gap, mut past): (f64, f64) = (0.0, 0.0);
            for _ in 0..seconds_to_steps(*seconds) {
                run.steps(1)?;
                for hinge in &hinges {
                    gap = worse(gap, run.gap(hinge));
                    past = worse(past, run.past_limit(hinge).to_degrees());
                }
            }
            vec![(ErrorKind::HingeGap, gap), (ErrorKind::PastLimit, past)]
        }
        Some(Accuracy::Sink { ground, seconds }) => {
            let bodies = dynamic_shapes(&run.scene.world);
            let mut worst: f64 = 0.0;
            for _ in 0..seconds_to_steps(*seconds) {
                run.steps(1)?;
                for (body, shapes) in &bodies {
                    let (origin, angle) = run.pose(*body);
                    let placed = carom::Isometry::new(origin, angle);
                    for (shape, local) in shapes {
                        let low = carom::WorldShape::new(shape, &(placed * local))
                            .aabb()
                            .min
                            .y;
                        worst = worse(worst, (*ground - low) as f64);
                    }
                }
            }
            vec![(kind, worst)]
        }
        Some(Accuracy::Rest { bodies, seconds }) => vec![(kind, {
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
        })],
        Some(Accuracy::Conservation { seconds }) => vec![(kind, {
            run.scene.fire_events();
            let (momentum, energy) = run.momentum_and_energy();
            run.steps(seconds_to_steps(*seconds))?;
            let (momentum_end, energy_end) = run.momentum_and_energy();
            let change = (momentum_end[0] - momentum[0]).hypot(momentum_end[1] - momentum[1]);
            let momentum_error = change / momentum[0].hypot(momentum[1]).max(1e-12);
            let energy_error = (energy_end - energy).abs() / energy.max(1e-12);
            momentum_error.max(energy_error)
        })],
        Some(Accuracy::SlideAngle {
            body,
            friction,
            seconds,
        }) => vec![(kind, {
            let steps = seconds_to_steps(*seconds);
            let critical = (*friction as f64).atan();
            let angle = slide_angle(scene, file, setting, body, critical, steps, &mut run)?;
            (angle - critical).abs().to_degrees()
        })],
        Some(Accuracy::Period {
            body,
            expected,
            seconds,
        }) => vec![(kind, {
            let handle = run.scene.names[body];
            let steps = seconds_to_steps(*seconds);
            let mut samples = Vec::with_capacity(steps);
            for step in 1..=steps {
                run.steps(1)?;
                // The body's centre, not its anchor: a hinge's anchor stays at the pivot.
                let [_, pivot] = run.joint_anchors(handle);
                let x = run.position(handle).x as f64 - pivot.x as f64;
                // Time counted in steps, not summed, and in double precision: a minute of
                // swings measured to a millionth of a period.
                samples.push((step as f64 * time_step as f64, x));
            }
            // Too few swings to time (the body stopped, or fell off its joint) is no period.
            period(&samples).map_or(f64::INFINITY, |measured| {
                100.0 * (measured - *expected as f64).abs() / *expected as f64
            })
        })],
        Some(Accuracy::Stretch {
            body,
            anchor,
            length,
            seconds,
        }) => vec![(kind, {
            let handle = run.scene.names[body];
            let anchor = carom::vec2(anchor.0, anchor.1);
            let length = *length as f64;
            let mut worst: f64 = 0.0;
            for _ in 0..seconds_to_steps(*seconds) {
                run.steps(1)?;
                let [on_body, _] = run.joint_anchors(handle);
                let stretch = 100.0 * ((on_body - anchor).norm() as f64 - length).abs() / length;
                // A NaN anchor is a world gone wrong, not a small stretch (max would drop it).
                worst = if stretch.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(stretch)
                };
            }
            worst
        })],
        None => vec![(kind, {
            run.steps(seconds_to_steps(default_seconds))?;
            run.max_penetration
        })],
    };
    let errors = errors
        .into_iter()
        .map(|(kind, error)| (kind, if run.nan { f64::INFINITY } else { error }))
        .collect();
    Ok(Measurement {
        errors,
        max_penetration: run.max_penetration,
        step_ms: run.step_ms,
    })
}

/// The larger of a worst-so-far and a new figure; a NaN is a world gone wrong, the worst of
/// all (`max` would drop it).
fn worse(worst: f64, figure: f64) -> f64 {
    if figure.is_nan() {
        f64::INFINITY
    } else {
        worst.max(figure)
    }
}

/// A joint as the joint measures read it: its bodies, its anchors in their frames, and a
/// hinge's reference angle and limits.
struct JointFrame {
    bodies: [BodyHandle; 2],
    anchors: [Vec2; 2],
    reference_angle: Real,
    limits: Option<(Real, Real)>,
    hinge: bool,
}

impl JointFrame {
    fn all(world: &World) -> Vec<JointFrame> {
        world
            .joints()
            .map(|joint| {
                let (hinge, limits) = match joint.kind() {
                    carom::JointKind::Revolute(r) => (true, r.limits.map(|l| (l.lower, l.upper))),
                    _ => (false, None),
                };
                JointFrame {
                    bodies: joint.bodies(),
                    anchors: joint.local_anchors(),
                    reference_angle: joint.reference_angle(),
                    limits,
                    hinge,
                }
            })
            .collect()
    }
}

/// Every dynamic body with its colliders' shapes, each with where it sits in its body.
fn dynamic_shapes(world: &World) -> Vec<(BodyHandle, Vec<(carom::Shape, carom::Isometry)>)> {
    world
        .bodies()
        .filter(|b| b.kind() == BodyKind::Dynamic)
        .map(|b| {
            let shapes = b
                .colliders()
                .iter()
                .filter_map(|&c| world.collider(c))
                .map(|c| (c.shape().clone(), c.local_transform()))
                .collect();
            (b.handle(), shapes)
        })
        .collect()
}

/// A scene being run with a setting, timing every step.
struct Run {
    scene: SceneWorld,
    setting: Setting,
    /// A peer's copy of the world, made at the first step from the carom world as it then is
    /// (so a tilted gravity and the scene's events at time 0 reach it); `None` before, and
    /// always for carom itself.
    peer: Option<Peer>,
    step_ms: Vec<f64>,
    max_penetration: f64,
    nan: bool,
}

impl Run {
    fn new(scene: &Scene, file: &str, setting: Setting) -> Result<Self, String> {
        let mut built = carom_scene::build(scene, file).map_err(|e| e.to_string())?;
        let defaults = SolverParams::default();
        let mut params = *built.world.solver();
        params.kind = setting.solver;
        params.impulse_resolution = true;
        params.iterations = Some(setting.iterations);
        params.substeps = setting.substeps;
        params.joint_hertz = setting.joint_hertz.unwrap_or(defaults.joint_hertz);
        params.direct_joints = setting.direct_joints;
        params.shock_propagation = setting.shock_propagation;
        if let Some(hertz) = setting.contact_hertz {
            params.contact_hertz = hertz;
        }
        built
            .world
            .update_settings(|s| s.solver = params)
            .map_err(|e| e.to_string())?;
        // Every step is solved: a setting that settles sooner would otherwise look cheaper
        // only because its bodies sleep.
        built
            .world
            .update_settings(|s| s.effects.set(Effect::Sleeping, false))
            .expect("switching an effect keeps the settings valid");
        Ok(Run {
            scene: built,
            setting,
            peer: None,
            step_ms: Vec::new(),
            // The peers' overlap is not measured.
            max_penetration: if setting.engine == Engine::Carom {
                0.0
            } else {
                f64::NAN
            },
            nan: false,
        })
    }

    fn steps(&mut self, count: usize) -> Result<(), String> {
        let time_step = self.scene.time_step;
        if self.setting.engine != Engine::Carom && self.peer.is_none() {
            // The peers replay no scene events: those due now go into the copy.
            self.scene.fire_events();
            self.peer = Peer::of(
                self.setting.engine,
                &self.scene.world,
                time_step,
                self.setting.stabilization,
            )?;
        }
        for _ in 0..count {
            // A world gone NaN has its error: stepping it further would only take time.
            if self.nan {
                break;
            }
            let clock = Instant::now();
            match &mut self.peer {
                Some(peer) => peer.step(time_step)?,
                None => self.scene.step().map_err(|e| e.to_string())?,
            }
            self.step_ms.push(clock.elapsed().as_secs_f64() * 1e3);
            if self.peer.is_none() {
                let stats = self.scene.world.stats();
                self.max_penetration = self.max_penetration.max(stats.max_penetration as f64);
                self.nan |= !stats.kinetic_energy.is_finite();
            }
        }
        Ok(())
    }

    /// Where the body's origin is and how it is turned, in whichever engine runs.
    fn pose(&mut self, handle: BodyHandle) -> (Vec2, Real) {
        let carom = |world: &World| {
            world
                .body(handle)
                .map_or((Vec2::zeros(), 0.0), |b| (b.position(), b.angle()))
        };
        let pose = match &mut self.peer {
            Some(peer) => peer.pose(handle),
            None => Some(carom(&self.scene.world)),
        };
        let pose = pose.unwrap_or((Vec2::repeat(Real::NAN), Real::NAN));
        self.nan |= !(pose.0.x.is_finite() && pose.0.y.is_finite());
        pose
    }

    fn position(&mut self, handle: BodyHandle) -> Vec2 {
        self.pose(handle).0
    }

    /// Where the body's first joint holds it and where it holds the other body, in the world
    /// (NaN if the joint is gone: the scene's build checked that the body had one).
    fn joint_anchors(&mut self, handle: BodyHandle) -> [Vec2; 2] {
        let world = &self.scene.world;
        let Some(joint) = world
            .joints_of(handle)
            .first()
            .and_then(|&joint| world.joint(joint))
        else {
            return [Vec2::repeat(Real::NAN); 2];
        };
        let (bodies, locals) = (joint.bodies(), joint.local_anchors());
        let mut anchors = [Vec2::zeros(); 2];
        for ((anchor, body), local) in anchors.iter_mut().zip(bodies).zip(locals) {
            let (origin, angle) = self.pose(body);
            *anchor = origin + carom::Rot::new(angle) * local;
        }
        if bodies[0] == handle {
            anchors
        } else {
            [anchors[1], anchors[0]]
        }
    }

    /// How far apart a joint's two anchors are, m.
    fn gap(&mut self, joint: &JointFrame) -> f64 {
        let [a, b] = joint.bodies.map(|body| self.pose(body));
        let at =
            |(origin, angle): (Vec2, Real), local: Vec2| origin + carom::Rot::new(angle) * local;
        (at(a, joint.anchors[0]) - at(b, joint.anchors[1])).norm() as f64
    }

    /// How far a hinge has turned past its limits, rad (0 within them, or without limits).
    fn past_limit(&mut self, joint: &JointFrame) -> f64 {
        let Some((lower, upper)) = joint.limits else {
            return 0.0;
        };
        let [(_, a), (_, b)] = joint.bodies.map(|body| self.pose(body));
        let angle = carom::Rot::new(b - a - joint.reference_angle).angle();
        f64::from((lower - angle).max(angle - upper).max(0.0))
    }

    /// Total linear momentum and kinetic energy of the dynamic bodies, in whichever engine
    /// runs.
    fn momentum_and_energy(&mut self) -> ([f64; 2], f64) {
        match &mut self.peer {
            Some(peer) => peer.momentum_and_energy(&self.scene.world),
            None => momentum_and_energy(&self.scene.world),
        }
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
            .update_settings(|s| s.gravity = gravity)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_period_of_a_sampled_sine_is_its_own() {
        // 2.5 s sampled at 60 Hz for 20 s, starting off zero: crossings between samples.
        let samples: Vec<(f64, f64)> = (0..1200)
            .map(|i| {
                let t = i as f64 / 60.0;
                (t, (std::f64::consts::TAU * t / 2.5 + 0.3).sin())
            })
            .collect();
        let period = period(&samples).unwrap();
        assert!((period - 2.5).abs() < 1e-5, "{period}");
        // Two upward crossings are one period, too few to trust.
        assert_eq!(super::period(&samples[..200]), None);
    }

    #[test]
    fn joint_stiffness_is_capped_at_a_quarter_of_the_substep_rate() {
        let setting = |substeps| Setting::carom(SolverKind::SoftStep, 1, substeps);
        let step = 1.0 / 60.0;
        assert_eq!(setting(1).capped_joint_hertz(60.0, step), 15.0);
        assert_eq!(setting(4).capped_joint_hertz(240.0, step), 60.0);
        // f32's 1/60 would make this 119.99999.
        assert_eq!(setting(8).capped_joint_hertz(240.0, step), 120.0);
        assert_eq!(setting(16).capped_joint_hertz(180.0, step), 180.0);
    }

    #[test]
    fn the_joint_measures_are_percentages() {
        for accuracy in [
            Accuracy::Period {
                body: "bob".into(),
                expected: 2.0,
                seconds: 1.0,
            },
            Accuracy::Stretch {
                body: "ball".into(),
                anchor: (0.0, 0.0),
                length: 20.0,
                seconds: 1.0,
            },
        ] {
            assert_eq!(ErrorKind::of(Some(&accuracy)).unit(), "%");
        }
        assert!(
            solves_joints(SolverKind::SoftStep) && solves_joints(SolverKind::SequentialImpulse)
        );
        assert!(!solves_joints(SolverKind::PushOut) && !solves_joints(SolverKind::TutorialImpulse));
    }
}
