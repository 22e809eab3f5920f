//! The accuracy sweep behind `carom-bench sweep` and the demo's `carom bench` (both read their
//! command line with [`cli::SweepArgs`]; the demo's accuracy panel runs it on the scene open): what accuracy costs in time. Every solver
//! setting (solver × iterations × substeps, and joint stiffness on scenes with joints) runs
//! each scene a few times, sleeping off; each point of the sweep is its median ms/step and its
//! error against the scene's exact answer ([`carom_scene::Accuracy`]). With peers, Box2D v3
//! and Rapier run the same scenes, rebuilt from carom's world, over their own settings. The
//! results go to a CSV, a markdown report (which engine is best at each time budget) and a
//! chart of each engine's Pareto front of error against time.

// The PNG chart is the command line's; plotters' text has no fonts on wasm32.
#[cfg(feature = "native")]
pub mod chart;
#[cfg(feature = "native")]
pub mod cli;
pub mod engine;
pub mod front;
pub mod measure;
pub mod peer;
pub mod report;

pub use engine::Engine;
pub use front::pareto_front;
pub use measure::{ErrorKind, Measurement, Setting, measure, solves_joints};

use carom::{Effect, Real, SolverKind, SolverParams, Vec2};
use carom_scene::{Accuracy, SceneWorld};
use std::path::PathBuf;

/// What to sweep.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// The scene files.
    pub scenes: Vec<PathBuf>,
    /// Runs per point; the point's time is the median of the runs' medians. One by default:
    /// back to back, more runs of a point meet the same moment of the machine, so they do not
    /// steady its time (two sweeps of one run and of three each move a point's time as much).
    pub runs: usize,
    /// The solvers.
    pub solvers: Vec<SolverKind>,
    /// Iteration counts.
    pub iterations: Vec<u32>,
    /// Substep counts (for the solvers that have substeps; the others run 1).
    pub substeps: Vec<u32>,
    /// carom's settings of more passes per step than this (iterations times substeps) are
    /// left out: a step costs in proportion to them, and past 64 the error of every scene
    /// swept is as flat as its cost is steep.
    pub max_passes: u32,
    /// Joint stiffnesses for soft step on scenes with joints, Hz. Each is capped at a quarter
    /// of the substep rate, as the solver caps it, and stiffnesses the cap makes equal run
    /// once.
    pub joint_hertz: Vec<Real>,
    /// Soft step's direct joint trees on scenes with joints: off, on, or both.
    pub direct_joints: Vec<bool>,
    /// Soft step's shock propagation on scenes of bodies resting on bodies under gravity
    /// (those measured by how far they drift from rest, or by how far the light ones sink):
    /// off, on, or both.
    pub shock_propagation: Vec<bool>,
    /// How long a scene without an accuracy measure runs, s.
    pub seconds: Real,
    /// The engines: carom runs the settings above, each peer its own below.
    pub engines: Vec<Engine>,
    /// Contact stiffnesses for soft step and Box2D, Hz (the other solvers' contacts are not
    /// soft).
    pub contact_hertz: Vec<Real>,
    /// Box2D's substep counts.
    pub box2d_substeps: Vec<u32>,
    /// Rapier's solver iterations (`num_solver_iterations`, which are its substeps).
    pub rapier_substeps: Vec<u32>,
    /// Rapier's stabilization iterations per substep.
    pub rapier_stabilization: Vec<u32>,
    /// Points measured at once, each on a thread of its own. One by default: on two cores two
    /// points at once slow each other unevenly, which the times would show. More for a sweep
    /// whose errors alone are wanted (the errors do not depend on it).
    pub jobs: usize,
}

impl Default for SweepOptions {
    /// The sweep over the ten accuracy scenes in `demos/`: contacts at 30 Hz (Box2D's
    /// default) and 60 Hz, joints at Box2D's 60 Hz and at 240 Hz, which is as stiff as the
    /// substeps allow at 16 substeps (120 Hz at 8), and soft step with direct joints and with
    /// shock propagation off and on.
    fn default() -> Self {
        SweepOptions {
            scenes: [
                "vertical_stack",
                "pyramid",
                "high_mass_ratio",
                "newtons_cradle",
                "incline_friction",
                "pendulum",
                "chain",
                "bridge",
                "ragdolls",
                "heavy_on_light",
            ]
            .iter()
            .map(|name| PathBuf::from(format!("demos/{name}.ron")))
            .collect(),
            runs: 1,
            solvers: SolverKind::ALL.to_vec(),
            iterations: vec![1, 2, 4, 8, 16, 32, 64],
            substeps: vec![1, 2, 4, 8, 16],
            max_passes: 64,
            joint_hertz: vec![60.0, 240.0],
            direct_joints: vec![false, true],
            shock_propagation: vec![false, true],
            seconds: 10.0,
            engines: vec![Engine::Carom],
            contact_hertz: vec![30.0, 60.0],
            box2d_substeps: vec![1, 2, 4, 8, 16],
            rapier_substeps: vec![1, 2, 4, 8, 16],
            rapier_stabilization: vec![1, 2, 4, 8, 16],
            jobs: 1,
        }
    }
}

impl SweepOptions {
    /// The whole sweep, every engine: what `carom-bench sweep` runs and `docs/accuracy/`
    /// holds.
    pub fn full() -> Self {
        SweepOptions {
            engines: Engine::ALL.to_vec(),
            ..SweepOptions::default()
        }
    }

    /// A part of [`SweepOptions::full`], one run each, in under a minute: each engine at 1
    /// substep and at Box2D's 4, carom's solvers at 1 and 8 iterations (soft step's default
    /// and the others'), both contact stiffnesses, Rapier at 1 stabilization iteration, with
    /// every option. Every point of it is a point of the whole sweep, measured the same way,
    /// so its errors must equal those the whole sweep wrote (CI checks that they do).
    pub fn quick() -> Self {
        SweepOptions::full().quickened()
    }

    /// The part of these options that [`SweepOptions::quick`] takes of the whole sweep: the
    /// same scenes, engines and options, at fewer iterations and substeps, one run each.
    pub fn quickened(self) -> Self {
        SweepOptions {
            runs: 1,
            iterations: vec![1, 8],
            substeps: vec![1, 4],
            box2d_substeps: vec![1, 4],
            rapier_substeps: vec![1, 4],
            rapier_stabilization: vec![1],
            ..self
        }
    }

    /// Every setting the sweep runs on `scene`, engine by engine, carom's solver by solver.
    /// On a scene with joints the solvers that leave joints out do not run
    /// ([`solves_joints`]), and soft step runs once per joint stiffness the cap leaves
    /// distinct and once per choice of direct joints; on a pile at rest under gravity, once
    /// per choice of shock propagation.
    pub fn settings(&self, scene: &SceneWorld) -> Vec<Setting> {
        let mut settings = Vec::new();
        for &engine in &self.engines {
            match engine {
                Engine::Carom => settings.extend(self.carom_settings(scene)),
                Engine::Box2d => {
                    for &hertz in &self.contact_hertz {
                        for &substeps in &self.box2d_substeps {
                            settings.push(Setting {
                                engine,
                                contact_hertz: Some(hertz),
                                ..Setting::carom(SolverKind::SoftStep, 1, substeps)
                            });
                        }
                    }
                }
                Engine::Rapier => {
                    for &stabilization in &self.rapier_stabilization {
                        for &substeps in &self.rapier_substeps {
                            settings.push(Setting {
                                engine,
                                stabilization: Some(stabilization),
                                ..Setting::carom(SolverKind::SoftStep, 1, substeps)
                            });
                        }
                    }
                }
            }
        }
        settings
    }

    /// carom's settings of the sweep on `scene`.
    fn carom_settings(&self, scene: &SceneWorld) -> Vec<Setting> {
        let joints = scene.world.joint_count() > 0;
        // Bodies resting on bodies under gravity: a pile at rest, or light bodies under a
        // heavy one. (A heap of ragdolls is measured by its hinges, which direct joints
        // hold.)
        let piled = matches!(
            scene.accuracy,
            Some(Accuracy::Rest { .. } | Accuracy::Sink { .. })
        ) && scene.world.settings().effects.contains(Effect::Gravity)
            && scene.world.settings().gravity != Vec2::zeros();
        let default_hertz = SolverParams::default().joint_hertz;
        let mut settings = Vec::new();
        for &solver in &self.solvers {
            if joints && !solves_joints(solver) {
                continue;
            }
            let substeps: &[u32] = if solver.has_substeps() {
                &self.substeps
            } else {
                &[1]
            };
            for &substeps in substeps {
                let base = Setting::carom(solver, 1, substeps);
                // The stiffnesses this substep count makes distinct, the default first; the
                // solver caps the default too, so a stiffness capped to it is the default.
                let mut joint_hertz = vec![None];
                if joints && solver.has_substeps() {
                    let default = base.capped_joint_hertz(default_hertz, scene.time_step);
                    for &hertz in &self.joint_hertz {
                        let capped = base.capped_joint_hertz(hertz, scene.time_step);
                        if capped != default && !joint_hertz.contains(&Some(capped)) {
                            joint_hertz.push(Some(capped));
                        }
                    }
                }
                // Soft contacts only in soft step.
                let contact_hertz: Vec<Option<Real>> = if solver == SolverKind::SoftStep {
                    self.contact_hertz.iter().map(|&h| Some(h)).collect()
                } else {
                    vec![None]
                };
                // Soft step's options only where they have something to act on: direct
                // joints on joints, shock propagation on a pile at rest under gravity.
                let soft = solver == SolverKind::SoftStep;
                let direct_joints: &[bool] = if joints && soft {
                    &self.direct_joints
                } else {
                    &[false]
                };
                let shock_propagation: &[bool] = if piled && soft {
                    &self.shock_propagation
                } else {
                    &[false]
                };
                let options = product(direct_joints, shock_propagation);
                let stiffness = product(&contact_hertz, &joint_hertz);
                for (direct_joints, shock_propagation) in options {
                    for &(contact_hertz, joint_hertz) in &stiffness {
                        for &iterations in &self.iterations {
                            if iterations * substeps > self.max_passes {
                                continue;
                            }
                            settings.push(Setting {
                                iterations,
                                joint_hertz,
                                contact_hertz,
                                direct_joints,
                                shock_propagation,
                                ..base
                            });
                        }
                    }
                }
            }
        }
        settings
    }
}

/// Every pair of an `a` and a `b`, `a` by `a`.
fn product<A: Copy, B: Copy>(a: &[A], b: &[B]) -> Vec<(A, B)> {
    a.iter()
        .flat_map(|&a| b.iter().map(move |&b| (a, b)))
        .collect()
}

/// One point of the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// The scene's name.
    pub scene: String,
    /// How its error is defined.
    pub error_kind: ErrorKind,
    /// The setting.
    pub setting: Setting,
    /// Median ms/step (median over the runs of each run's median).
    pub ms_per_step: f64,
    /// The error (infinite if the world went NaN).
    pub error: f64,
    /// The deepest overlap seen, m.
    pub max_penetration: f64,
    /// Whether the scene has joints (so the solvers that leave them out did not run).
    pub joints: bool,
}

/// Runs the sweep; `progress(done, total, what)` is told as each point ends (`what` names
/// it), on the calling thread.
///
/// Every point runs with carom on one thread (as Box2D, on one worker, and Rapier run). One at
/// a time, the points run in sweep order, so the engines' points on a scene are measured
/// within moments of each other. The points are independent, so with [`SweepOptions::jobs`]
/// above one that many run at once, each on a thread of its own, the costliest first so the
/// last to finish are short. The points come back in sweep order, whatever order they ran in:
/// scene by scene, setting by setting.
pub fn sweep(
    options: &SweepOptions,
    mut progress: impl FnMut(usize, usize, &str),
) -> Result<Vec<Point>, String> {
    let scenes = options
        .scenes
        .iter()
        .map(|path| {
            let file = path.display().to_string();
            let scene = carom_scene::read(path).map_err(|e| e.to_string())?;
            // Built once here to see what settings it takes (its joints, its time step).
            let built = carom_scene::build(&scene, &file).map_err(|e| e.to_string())?;
            let settings = options.settings(&built);
            let joints = built.world.joint_count() > 0;
            Ok((scene, file, settings, joints))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let cells: Vec<(usize, Setting)> = scenes
        .iter()
        .enumerate()
        .flat_map(|(i, (_, _, settings, _))| settings.iter().map(move |&s| (i, s)))
        .collect();
    let total = cells.len();
    let runs = options.runs.max(1);
    let jobs = options.jobs.clamp(1, total.max(1));
    let mut order: Vec<usize> = (0..total).collect();
    if jobs > 1 {
        // Longest first: a cell's work grows with its passes per step.
        order.sort_by_key(|&c| std::cmp::Reverse(cells[c].1.passes_per_step()));
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (send, receive) = std::sync::mpsc::channel();
    let mut results: Vec<Option<Measured>> = vec![None; total];
    std::thread::scope(|scope| -> Result<(), String> {
        for _ in 0..jobs {
            let (send, next, order, cells, scenes) = (send.clone(), &next, &order, &cells, &scenes);
            scope.spawn(move || {
                let one_thread = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
                    Ok(pool) => pool,
                    Err(e) => {
                        let _ = send.send(Err(e.to_string()));
                        return;
                    }
                };
                loop {
                    let taken = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&cell) = order.get(taken) else {
                        return;
                    };
                    let (scene, setting) = cells[cell];
                    let (scene, file, _, _) = &scenes[scene];
                    let measured = one_thread
                        .install(|| measure_runs(scene, file, setting, options.seconds, runs));
                    if send.send(measured.map(|m| (cell, m))).is_err() {
                        return;
                    }
                }
            });
        }
        drop(send);
        for (done, received) in receive.iter().enumerate() {
            let (cell, measured) = match received {
                Ok(received) => received,
                Err(e) => {
                    // The workers stop at the next cell they take.
                    next.store(total, std::sync::atomic::Ordering::Relaxed);
                    return Err(e);
                }
            };
            let (scene, setting) = cells[cell];
            let what = format!(
                "{}: {}",
                scenes[scene].0.name,
                report::setting_name(&setting)
            );
            results[cell] = Some(measured);
            progress(done + 1, total, &what);
        }
        Ok(())
    })?;
    // A point per error: a measure of two (a hinge's gap and its turn past its limits) makes
    // two points of one run.
    let points = cells
        .iter()
        .zip(results)
        .flat_map(|(&(scene, setting), measured)| {
            let (scene, _, _, joints) = &scenes[scene];
            let measured = measured.expect("every cell was measured");
            measured
                .errors
                .into_iter()
                .map(move |(error_kind, error)| Point {
                    scene: scene.name.clone(),
                    error_kind,
                    setting,
                    ms_per_step: measured.ms_per_step,
                    error,
                    max_penetration: measured.max_penetration,
                    joints: *joints,
                })
        })
        .collect();
    progress(total, total, "done");
    Ok(points)
}

/// What the runs of one cell gave: the median over the runs of each run's median ms/step, and
/// the first run's errors and overlap (every run gives the same: the physics is
/// deterministic).
#[derive(Debug, Clone)]
struct Measured {
    ms_per_step: f64,
    errors: Vec<(ErrorKind, f64)>,
    max_penetration: f64,
}

/// Runs one cell `runs` times.
fn measure_runs(
    scene: &carom_scene::Scene,
    file: &str,
    setting: Setting,
    seconds: Real,
    runs: usize,
) -> Result<Measured, String> {
    let mut medians = Vec::with_capacity(runs);
    let mut first: Option<Measurement> = None;
    for _ in 0..runs {
        let measurement = measure(scene, file, setting, seconds)?;
        medians.push(median(&measurement.step_ms));
        first.get_or_insert(measurement);
    }
    let first = first.expect("at least one run");
    Ok(Measured {
        ms_per_step: median(&medians),
        errors: first.errors,
        max_penetration: first.max_penetration,
    })
}

/// The median of some times (0 for none).
pub fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let middle = sorted.len() / 2;
    if sorted.len().is_multiple_of(2) {
        0.5 * (sorted[middle - 1] + sorted[middle])
    } else {
        sorted[middle]
    }
}

/// Runs the sweep with a progress bar on the terminal and writes `accuracy.csv`,
/// `README.md` (the report; `command` is how it was made) and `accuracy.png` to `out`.
/// Returns the points.
#[cfg(feature = "native")]
pub fn sweep_to_folder(
    options: &SweepOptions,
    out: &std::path::Path,
    command: &str,
) -> Result<Vec<Point>, String> {
    use indicatif::{ProgressBar, ProgressStyle};
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} points, {elapsed} (eta {eta})  {msg}")
            .map_err(|e| e.to_string())?,
    );
    let points = sweep(options, |done, total, what| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        bar.set_message(what.to_string());
    })?;
    bar.finish_and_clear();
    let write = |name: &str, text: &str| {
        let path = out.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    let provenance = report::Provenance {
        machine: report::Machine::here(),
        command: command.into(),
        runs: options.runs,
    };
    let text = provenance.header() + &report::csv(&points);
    write("accuracy.csv", &text)?;
    // The report and the chart from the points as the CSV keeps them, so that drawing them
    // again from the CSV (`carom-bench docs`) gives the same text.
    let kept = report::parse_csv(&text)?;
    write("README.md", &report::markdown(&kept, &provenance))?;
    chart::write_chart(&kept, &out.join("accuracy.png"))?;
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene of a ball, hinged to a hook if `joined`.
    fn scene(joined: bool) -> SceneWorld {
        let joints = if joined {
            r#"joints: [(bodies: ("hook", "ball"), anchor: (0.0, 0.0), kind: Revolute())],"#
        } else {
            ""
        };
        let text = format!(
            r#"(
                name: "hinge",
                bodies: [
                    (name: "hook", kind: static, shape: Circle(radius: 0.1)),
                    (name: "ball", shape: Circle(radius: 0.1), position: (1.0, 0.0)),
                ],
                {joints}
            )"#
        );
        let scene = carom_scene::parse(&text, "hinge.ron").unwrap();
        carom_scene::build(&scene, "hinge.ron").unwrap()
    }

    fn options() -> SweepOptions {
        SweepOptions {
            iterations: vec![1],
            substeps: vec![1, 2, 4, 8],
            contact_hertz: vec![30.0],
            ..SweepOptions::default()
        }
    }

    #[test]
    fn a_scene_without_joints_runs_every_solver_at_the_default_joint_stiffness() {
        let settings = options().settings(&scene(false));
        // Push-out, tutorial and sequential impulse, soft step at 1, 2, 4 and 8 substeps.
        assert_eq!(settings.len(), 3 + 4);
        assert!(settings.iter().all(|s| s.joint_hertz.is_none()));
        // Direct joints would change nothing without joints.
        assert!(settings.iter().all(|s| !s.direct_joints));
        // Soft contacts are soft step's alone.
        assert!(
            settings
                .iter()
                .all(|s| { (s.solver == SolverKind::SoftStep) == (s.contact_hertz == Some(30.0)) })
        );
        // Both contact stiffnesses by default, and each peer over its own axes.
        let all = SweepOptions {
            engines: Engine::ALL.to_vec(),
            ..options()
        };
        let settings = SweepOptions {
            contact_hertz: vec![30.0, 60.0],
            ..all
        }
        .settings(&scene(false));
        let count = |engine| settings.iter().filter(|s| s.engine == engine).count();
        assert_eq!(count(Engine::Carom), 3 + 4 * 2);
        assert_eq!(count(Engine::Box2d), 5 * 2);
        assert_eq!(count(Engine::Rapier), 5 * 5);
    }

    #[test]
    fn a_pile_at_rest_under_gravity_sweeps_shock_propagation_with_soft_step_alone() {
        let pile = |gravity: &str| {
            let text = format!(
                r#"(
                    name: "pile",
                    world: (gravity: {gravity}),
                    bodies: [
                        (name: "ground", kind: static, shape: Box(width: 10.0, height: 1.0)),
                        (name: "box", shape: Box(width: 1.0, height: 1.0), position: (0.0, 1.0)),
                    ],
                    accuracy: Some(Rest(seconds: 1.0)),
                )"#
            );
            let scene = carom_scene::parse(&text, "pile.ron").unwrap();
            carom_scene::build(&scene, "pile.ron").unwrap()
        };
        let settings = options().settings(&pile("(0.0, -10.0)"));
        let shocked: Vec<&Setting> = settings.iter().filter(|s| s.shock_propagation).collect();
        // Soft step at 1, 2, 4 and 8 substeps, each with and without.
        assert_eq!(shocked.len(), 4);
        assert_eq!(settings.len(), 3 + 2 * 4);
        assert!(shocked.iter().all(|s| s.solver == SolverKind::SoftStep));
        // Without gravity nothing rests on anything, and a scene not at rest is not a pile.
        let weightless = options().settings(&pile("(0.0, 0.0)"));
        assert!(weightless.iter().all(|s| !s.shock_propagation));
        assert!(
            options()
                .settings(&scene(false))
                .iter()
                .all(|s| !s.shock_propagation)
        );
    }

    #[test]
    fn a_scene_with_joints_skips_the_solvers_without_them_and_sweeps_stiffness() {
        let settings = SweepOptions {
            direct_joints: vec![false],
            ..options()
        }
        .settings(&scene(true));
        assert!(settings.iter().all(|s| solves_joints(s.solver)));
        let soft: Vec<(u32, Option<Real>)> = settings
            .iter()
            .filter(|s| s.solver == SolverKind::SoftStep)
            .map(|s| (s.substeps, s.joint_hertz))
            .collect();
        // 240 Hz is capped to the default's 15, 30 and 60 Hz up to 4 substeps; at 8 the
        // default stays 60 Hz and 240 Hz becomes 120.
        assert_eq!(
            soft,
            [(1, None), (2, None), (4, None), (8, None), (8, Some(120.0))]
        );
        let classic = settings.len() - soft.len();
        assert_eq!(classic, 1, "sequential impulse alone: {settings:?}");
        // By default soft step runs each of those with direct joints too, and only soft step.
        let both = options().settings(&scene(true));
        assert_eq!(both.len(), 1 + 2 * soft.len());
        let direct: Vec<&Setting> = both.iter().filter(|s| s.direct_joints).collect();
        assert_eq!(direct.len(), soft.len());
        assert!(direct.iter().all(|s| s.solver == SolverKind::SoftStep));
    }
}
