//! The state behind the sidebar's "cost of accuracy" front: the measured settings of the scene
//! running (from the last `carom bench` report, or from a sweep run in the background on
//! request), and where the demo's own solver setting sits among them, "you are here".
//!
//! Nothing here draws: [`crate::ui`] draws what [`AccuracyPanel`] holds, so tests can drive
//! the panel and read what the sidebar showed.

use carom::{Real, SolverKind, SolverParams};
use carom_bench::sweep::{self, Engine, Point, Setting, SweepOptions, pareto_front, report};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

/// The points of the scene named `name` with its first error: a scene measured by two (a
/// pile of ragdolls: its hinges' gap and their turn past their limits) shows the first.
fn front_of(points: Vec<Point>, name: &str) -> Vec<Point> {
    let kind = points
        .iter()
        .find(|p| p.scene == name)
        .map(|p| p.error_kind);
    points
        .into_iter()
        .filter(|p| p.scene == name && Some(p.error_kind) == kind)
        .collect()
}

/// Where a report is, relative to the working directory or to the scene folder's parent.
pub const REPORT_CSV: &str = "docs/accuracy/accuracy.csv";

/// Whether this build can measure a scene from the panel. A sweep runs on a thread of its
/// own so the app keeps running, and the web build has no threads: it shows the report it was
/// built with.
pub const CAN_MEASURE: bool = cfg!(not(target_arch = "wasm32"));

/// Whether this build can measure Box2D and Rapier beside carom (the web build cannot).
pub const CAN_MEASURE_PEERS: bool = CAN_MEASURE && cfg!(feature = "peers");

/// The scene the panel shows, as read from its file.
#[derive(Debug, Clone)]
pub struct SceneInfo {
    /// The file.
    pub path: PathBuf,
    /// Its `name`, which keys its points in a report.
    pub name: String,
    /// Whether it has an accuracy measure (without one the error is the deepest overlap).
    pub has_accuracy: bool,
    /// The solver settings the file asks for: what the sweep runs, apart from the swept
    /// solver, iterations, substeps and joint stiffness.
    pub params: SolverParams,
    /// Seconds per step (joint stiffness is capped by the substep rate).
    pub time_step: Real,
    /// Whether it has joints (so soft step's joint stiffness matters).
    pub joints: bool,
}

impl SceneInfo {
    /// Reads and builds the scene file at `path` (building gives its solver settings as the
    /// sweep starts from them).
    pub fn read(path: &Path) -> Result<SceneInfo, String> {
        let file = path.display().to_string();
        let scene = crate::files::read_scene(path).map_err(|e| e.to_string())?;
        let built = carom_scene::build(&scene, &file).map_err(|e| e.to_string())?;
        Ok(SceneInfo {
            path: path.to_path_buf(),
            name: scene.name,
            has_accuracy: scene.accuracy.is_some(),
            params: *built.world.solver(),
            time_step: built.time_step,
            joints: built.world.joint_count() > 0,
        })
    }
}

/// Where the panel's points came from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// A `carom bench` CSV.
    Report(PathBuf),
    /// A sweep run from the panel.
    Sweep,
    /// Given by the program ([`AccuracyPanel::set_points`]).
    Given,
}

/// How far a background sweep has got.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Progress {
    /// Points measured.
    pub done: usize,
    /// Points in all (0 until the sweep has counted them).
    pub total: usize,
    /// The point measured last.
    pub what: String,
}

impl Progress {
    /// Done as a fraction in `[0, 1]`.
    pub fn fraction(&self) -> f32 {
        if self.total == 0 {
            0.0
        } else {
            self.done as f32 / self.total as f32
        }
    }
}

/// A sweep running on its own thread.
struct BackgroundSweep {
    scene: PathBuf,
    progress: Arc<Mutex<Progress>>,
    thread: JoinHandle<Result<Vec<Point>, String>>,
}

/// Where the demo's setting sits among the measured ones.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// The demo's setting, as the sweep would name it.
    pub wanted: Setting,
    /// The measured point shown: the demo's setting, or the nearest measured one.
    pub point: Point,
    /// Whether `point` is the demo's setting itself.
    pub exact: bool,
}

impl Marker {
    /// "you are here: soft step, 4 substeps, 2 iterations", or "nearest measured: …" with
    /// the demo's own setting after it.
    pub fn title(&self) -> String {
        if self.exact {
            format!(
                "you are here: {}",
                report::setting_name(&self.point.setting)
            )
        } else {
            format!(
                "nearest measured: {} (you: {})",
                report::setting_name(&self.point.setting),
                report::setting_name(&self.wanted)
            )
        }
    }

    /// "0.021 ms/step, error 1.23e-3 %".
    pub fn numbers(&self) -> String {
        format!(
            "{} ms/step, error {} {}",
            format_ms(self.point.ms_per_step),
            format_error(self.point.error),
            self.point.error_kind.unit()
        )
    }
}

/// The sidebar's accuracy front for the scene running.
#[derive(Default)]
pub struct AccuracyPanel {
    /// The scene shown; `None` before the first [`AccuracyPanel::update`].
    scene: Option<SceneInfo>,
    /// Why the scene could not be read, or a report not parsed, or a sweep failed.
    notice: Option<String>,
    /// The scene's points, and where they came from (empty: nothing measured).
    points: Vec<Point>,
    source: Option<Source>,
    /// Points measured from the panel, by scene file, so going back to a scene shows them.
    measured: HashMap<PathBuf, Vec<Point>>,
    sweep: Option<BackgroundSweep>,
    /// A sweep started from the panel runs Box2D and Rapier too.
    pub with_peers: bool,
    marker: Option<Marker>,
}

impl AccuracyPanel {
    /// Brings the panel up to date for a frame: the scene at `scene_path` (read, and its
    /// points looked up, when it changed), a finished background sweep collected, and the
    /// marker for `params`, the demo's solver settings.
    pub fn update(&mut self, scene_path: &Path, params: &SolverParams) {
        if self.scene.as_ref().is_none_or(|s| s.path != scene_path) {
            self.open(scene_path);
        }
        self.poll();
        self.marker = self
            .scene
            .as_ref()
            .and_then(|s| marker(&self.points, params, s.time_step, s.joints));
    }

    /// Shows `points` for the scene at `scene_path` instead of any report's (those of other
    /// scenes are left out).
    pub fn set_points(&mut self, scene_path: &Path, points: Vec<Point>) {
        if self.scene.as_ref().is_none_or(|s| s.path != scene_path) {
            self.open(scene_path);
        }
        let name = self.scene.as_ref().map_or("", |s| s.name.as_str());
        self.points = front_of(points, name);
        self.source = Some(Source::Given);
    }

    /// Reads the scene and finds its points: measured here before, else the first report
    /// (see [`report_paths`]) that has the scene.
    fn open(&mut self, scene_path: &Path) {
        self.points.clear();
        self.source = None;
        self.notice = None;
        self.marker = None;
        self.scene = match SceneInfo::read(scene_path) {
            Ok(info) => Some(info),
            Err(e) => {
                self.notice = Some(e);
                // Still the scene shown, so the file is not read again every frame.
                Some(SceneInfo {
                    path: scene_path.to_path_buf(),
                    name: String::new(),
                    has_accuracy: false,
                    params: SolverParams::default(),
                    time_step: 1.0 / 60.0,
                    joints: false,
                })
            }
        };
        if self.notice.is_some() {
            return;
        }
        if let Some(points) = self.measured.get(scene_path) {
            self.points = points.clone();
            self.source = Some(Source::Sweep);
            return;
        }
        let name = self.scene.as_ref().map_or("", |s| s.name.as_str());
        for path in report_paths(scene_path) {
            let Ok(text) = crate::files::read_to_string(&path) else {
                continue;
            };
            match report::parse_csv(&text) {
                Ok(points) => {
                    let of_scene = front_of(points, name);
                    if !of_scene.is_empty() {
                        self.points = of_scene;
                        self.source = Some(Source::Report(path));
                        self.notice = None;
                        return;
                    }
                }
                // Said, not fatal: another report may still have the scene.
                Err(e) => self.notice = Some(format!("{}: {e}", path.display())),
            }
        }
    }

    /// Starts measuring the scene shown on a thread of its own: one run per setting, carom's
    /// settings, and the peers' too if [`AccuracyPanel::with_peers`]. Does nothing while a
    /// sweep runs.
    pub fn start_sweep(&mut self) {
        let Some(scene) = &self.scene else { return };
        if self.sweep.is_some() {
            return;
        }
        let mut options = SweepOptions {
            scenes: vec![scene.path.clone()],
            runs: 1,
            // One point at a time, so the app keeps a core.
            jobs: 1,
            ..SweepOptions::default()
        };
        if self.with_peers && CAN_MEASURE_PEERS {
            options.engines = Engine::ALL.to_vec();
        }
        let progress = Arc::new(Mutex::new(Progress::default()));
        let shared = Arc::clone(&progress);
        let spawned = std::thread::Builder::new()
            .name("accuracy sweep".into())
            .spawn(move || {
                sweep::sweep(&options, |done, total, what| {
                    // A poisoned lock only means a reader panicked; the numbers are still good.
                    let mut progress = shared.lock().unwrap_or_else(|e| e.into_inner());
                    *progress = Progress {
                        done,
                        total,
                        what: what.to_string(),
                    };
                })
            });
        match spawned {
            Ok(thread) => {
                self.notice = None;
                self.sweep = Some(BackgroundSweep {
                    scene: scene.path.clone(),
                    progress,
                    thread,
                });
            }
            Err(e) => self.notice = Some(format!("could not start the sweep: {e}")),
        }
    }

    /// Collects a finished sweep: its points are kept for its scene, and shown if that is
    /// the scene shown.
    fn poll(&mut self) {
        if !self
            .sweep
            .as_ref()
            .is_some_and(|sweep| sweep.thread.is_finished())
        {
            return;
        }
        let Some(sweep) = self.sweep.take() else {
            return;
        };
        let result = sweep
            .thread
            .join()
            .unwrap_or_else(|_| Err("the sweep panicked".into()));
        let shown = self.scene.as_ref().is_some_and(|s| s.path == sweep.scene);
        match result {
            Ok(points) => {
                // The sweep ran the one scene: its first error's points.
                let name = points.first().map(|p| p.scene.clone()).unwrap_or_default();
                let points = front_of(points, &name);
                if shown {
                    self.points = points.clone();
                    self.source = Some(Source::Sweep);
                    self.notice = None;
                }
                self.measured.insert(sweep.scene, points);
            }
            Err(e) => {
                self.notice = Some(format!(
                    "the sweep of {} failed: {e}",
                    sweep.scene.display()
                ))
            }
        }
    }

    /// Waits for a running sweep to finish and collects it (tests; the app polls instead).
    pub fn wait_for_sweep(&mut self) {
        if let Some(sweep) = &self.sweep {
            while !sweep.thread.is_finished() {
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
        }
        self.poll();
    }

    /// The scene shown.
    pub fn scene(&self) -> Option<&SceneInfo> {
        self.scene.as_ref()
    }

    /// The scene's measured points (empty when nothing is measured).
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// Where the points came from.
    pub fn source(&self) -> Option<&Source> {
        self.source.as_ref()
    }

    /// What went wrong last, if anything: a scene that does not read, a report that does not
    /// parse, a sweep that failed.
    pub fn notice(&self) -> Option<&str> {
        self.notice.as_deref()
    }

    /// How far the running sweep has got, and which scene it measures; `None` when none runs.
    pub fn progress(&self) -> Option<(Progress, &Path)> {
        self.sweep.as_ref().map(|sweep| {
            let progress = sweep.progress.lock().unwrap_or_else(|e| e.into_inner());
            (progress.clone(), sweep.scene.as_path())
        })
    }

    /// "You are here", as of the last [`AccuracyPanel::update`].
    pub fn marker(&self) -> Option<&Marker> {
        self.marker.as_ref()
    }

    /// The solver settings the demo runs that the points were not measured with (the scene
    /// file's), by name: the marker's numbers do not hold for them.
    pub fn unmeasured_changes(&self, params: &SolverParams) -> Vec<&'static str> {
        self.scene
            .as_ref()
            .map(|s| unmeasured_changes(params, &s.params))
            .unwrap_or_default()
    }
}

/// The reports that may hold `scene`'s points, most likely first: under the working
/// directory, then beside the scene's folder (`demos/../docs/accuracy/accuracy.csv`), each
/// once.
pub fn report_paths(scene: &Path) -> Vec<PathBuf> {
    let mut paths = vec![PathBuf::from(REPORT_CSV)];
    if let Some(root) = scene.parent().and_then(Path::parent) {
        paths.push(root.join(REPORT_CSV));
    }
    let mut seen: Vec<PathBuf> = Vec::new();
    paths.retain(|path| {
        let key = path.canonicalize().unwrap_or_else(|_| path.clone());
        let new = !seen.contains(&key);
        seen.push(key);
        new
    });
    paths
}

/// The demo's solver settings as the sweep names a carom setting: the solver that runs (push-
/// out when impulse resolution is off), substeps only for the solvers that have them, the
/// joint stiffness only where it is not the default, and direct joints and shock propagation
/// only for soft step.
pub fn setting_of(params: &SolverParams) -> Setting {
    let solver = params.effective_kind();
    let substeps = if solver.has_substeps() {
        params.substeps
    } else {
        1
    };
    let default_hertz = SolverParams::default().joint_hertz;
    Setting {
        joint_hertz: (params.joint_hertz != default_hertz).then_some(params.joint_hertz),
        // Soft contacts are soft step's alone, and the sweep names their stiffness.
        contact_hertz: (solver == SolverKind::SoftStep).then_some(params.contact_hertz),
        direct_joints: solver == SolverKind::SoftStep && params.direct_joints,
        shock_propagation: solver == SolverKind::SoftStep && params.shock_propagation,
        ..Setting::carom(solver, params.effective_iterations(), substeps)
    }
}

/// Where `params` sit among carom's measured `points`: the point of that very setting, or
/// else the nearest measured setting of the same solver (fewest doublings of iterations,
/// substeps and joint stiffness apart). `None` when the solver was not measured (push-out
/// and tutorial impulse do not run on scenes with joints).
///
/// Joint stiffness is compared as the solver runs it, capped at a quarter of the substep rate
/// at `time_step` seconds per step, and only for soft step on a scene with `joints`: a
/// stiffness the cap makes the default's is the default's point. Direct joints count as one
/// doubling apart, and only on a scene with `joints` (without, they change nothing); shock
/// propagation counts as one doubling apart on every scene.
pub fn marker(
    points: &[Point],
    params: &SolverParams,
    time_step: Real,
    joints: bool,
) -> Option<Marker> {
    let wanted = setting_of(params);
    let default_hertz = SolverParams::default().joint_hertz;
    let hertz_of =
        |s: &Setting| s.capped_joint_hertz(s.joint_hertz.unwrap_or(default_hertz), time_step);
    let stiffness_matters = joints && wanted.solver.has_substeps();
    let distance = |p: &Point| {
        let doublings = |a: u32, b: u32| (a.max(1) as f64 / b.max(1) as f64).log2().abs();
        let stiffness = if stiffness_matters {
            (hertz_of(&p.setting) as f64 / hertz_of(&wanted) as f64)
                .log2()
                .abs()
        } else {
            0.0
        };
        // A point without a contact stiffness ran the scene's own (a report from before the
        // sweep named it).
        let contacts = match (p.setting.contact_hertz, wanted.contact_hertz) {
            (Some(measured), Some(wanted)) => (measured as f64 / wanted as f64).log2().abs(),
            _ => 0.0,
        };
        let direct = if joints && p.setting.direct_joints != wanted.direct_joints {
            1.0
        } else {
            0.0
        };
        // The sweep runs shock propagation only on piles at rest under gravity: elsewhere a
        // setting with it was not measured, and is shown as the nearest.
        let shock = if p.setting.shock_propagation != wanted.shock_propagation {
            1.0
        } else {
            0.0
        };
        doublings(p.setting.iterations, wanted.iterations)
            + doublings(p.setting.substeps, wanted.substeps)
            + stiffness
            + contacts
            + direct
            + shock
    };
    let nearest = points
        .iter()
        .filter(|p| p.setting.engine == Engine::Carom && p.setting.solver == wanted.solver)
        // The first of equally near ones, in sweep order.
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))?;
    Some(Marker {
        wanted,
        point: nearest.clone(),
        exact: distance(nearest) == 0.0,
    })
}

/// Names of the settings in `params` that differ from `measured` (the scene file's) and
/// that the sweep does not vary, so a marker's numbers were measured without them.
pub fn unmeasured_changes(params: &SolverParams, measured: &SolverParams) -> Vec<&'static str> {
    let soft = params.effective_kind().has_substeps();
    let warm = matches!(
        params.effective_kind(),
        SolverKind::SoftStep | SolverKind::SequentialImpulse
    );
    [
        (
            warm,
            "warm starting",
            params.warm_starting != measured.warm_starting,
        ),
        (
            soft,
            "graph colouring",
            params.graph_coloring != measured.graph_coloring,
        ),
        (
            soft,
            "friction in biased pass",
            params.friction_in_bias_pass != measured.friction_in_bias_pass,
        ),
        (
            soft,
            "damping ratio",
            params.damping_ratio != measured.damping_ratio,
        ),
    ]
    .into_iter()
    .filter(|&(applies, _, differs)| applies && differs)
    .map(|(_, name, _)| name)
    .collect()
}

/// Each engine's points split into its Pareto front (fastest first) and the rest, engines
/// in [`Engine::ALL`] order, those without points left out. Worlds gone NaN are in neither.
pub fn fronts(points: &[Point]) -> Vec<(Engine, Vec<&Point>, Vec<&Point>)> {
    Engine::ALL
        .into_iter()
        .filter_map(|engine| {
            let of_engine: Vec<&Point> = points
                .iter()
                .filter(|p| p.setting.engine == engine)
                .collect();
            if of_engine.is_empty() {
                return None;
            }
            let front = pareto_front(&of_engine);
            let rest = of_engine
                .into_iter()
                .filter(|p| p.error.is_finite() && !front.iter().any(|f| std::ptr::eq(*f, *p)))
                .collect();
            Some((engine, front, rest))
        })
        .collect()
}

/// A time per step as the panel writes it: three significant digits.
pub fn format_ms(ms: f64) -> String {
    if ms >= 100.0 {
        format!("{ms:.0}")
    } else if ms >= 10.0 {
        format!("{ms:.1}")
    } else if ms >= 1.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.3}")
    }
}

/// An error as the panel writes it: three significant digits, plain from 0.01 to 9999 and
/// in exponent form beyond; `0` or `inf`.
pub fn format_error(error: f64) -> String {
    if error == 0.0 {
        "0".into()
    } else if !error.is_finite() {
        "inf".into()
    } else if (0.01..10_000.0).contains(&error) {
        let decimals = (2 - error.log10().floor() as i32).max(0) as usize;
        format!("{error:.decimals$}")
    } else {
        format!("{error:.2e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom::SolverKind;
    use carom_bench::sweep::ErrorKind;

    fn point(setting: Setting, ms: f64, error: f64) -> Point {
        Point {
            scene: "s".into(),
            error_kind: ErrorKind::Period,
            setting,
            ms_per_step: ms,
            error,
            max_penetration: 0.0,
            joints: true,
        }
    }

    fn soft(iterations: u32, substeps: u32, joint_hertz: Option<Real>) -> Setting {
        Setting {
            joint_hertz,
            ..Setting::carom(SolverKind::SoftStep, iterations, substeps)
        }
    }

    fn params(kind: SolverKind, iterations: u32, substeps: u32) -> SolverParams {
        SolverParams {
            iterations: Some(iterations),
            substeps,
            ..SolverParams::for_kind(kind)
        }
    }

    fn sweep() -> Vec<Point> {
        vec![
            // The peer first: a marker must pass over it for carom's point of the same numbers.
            point(
                Setting {
                    engine: Engine::Box2d,
                    ..soft(1, 4, None)
                },
                0.02,
                0.4,
            ),
            point(
                Setting::carom(SolverKind::SequentialImpulse, 8, 1),
                0.01,
                0.5,
            ),
            point(soft(1, 4, None), 0.02, 0.4),
            point(soft(2, 4, None), 0.03, 0.3),
            point(soft(4, 4, None), 0.05, 0.2),
            point(soft(1, 8, None), 0.04, 0.1),
            point(soft(1, 8, Some(120.0)), 0.04, 0.05),
        ]
    }

    const STEP: Real = 1.0 / 60.0;

    #[test]
    fn the_marker_is_the_point_of_the_demos_setting() {
        let points = sweep();
        let at = |p: SolverParams| marker(&points, &p, STEP, true).unwrap();
        let here = at(params(SolverKind::SoftStep, 2, 4));
        assert!(here.exact);
        assert_eq!(here.point.setting, soft(2, 4, None));
        assert_eq!(here.point.error, 0.3);
        assert!(
            here.title()
                .starts_with("you are here: soft step, 4 substeps, 2 it")
        );
        // The classic solvers' substeps do not count: sequential impulse runs one.
        let classic = at(params(SolverKind::SequentialImpulse, 8, 4));
        assert!(classic.exact);
        assert_eq!(classic.point.setting.solver, SolverKind::SequentialImpulse);
        // Never the peer's point of the same numbers.
        assert_eq!(
            at(params(SolverKind::SoftStep, 1, 4)).point.setting.engine,
            Engine::Carom
        );
    }

    #[test]
    fn an_unmeasured_setting_marks_the_nearest_of_its_solver() {
        let points = sweep();
        let near = marker(&points, &params(SolverKind::SoftStep, 3, 4), STEP, true).unwrap();
        assert!(!near.exact);
        // 3 iterations are nearer 4 than 2 in doublings: log2(4/3) = 0.42, log2(3/2) = 0.58.
        assert_eq!(near.point.setting, soft(4, 4, None));
        assert!(near.title().starts_with("nearest measured: soft step, 4 substeps, 4 iterations (you: soft step, 4 substeps, 3 iterations, 30 Hz contacts)"), "{}", near.title());
        // Push-out did not run on this scene with joints: no marker.
        let off = SolverParams {
            impulse_resolution: false,
            ..SolverParams::default()
        };
        assert_eq!(marker(&points, &off, STEP, true), None);
    }

    #[test]
    fn joint_stiffness_counts_as_the_solver_runs_it() {
        let points = sweep();
        let stiff = |hertz: Real, substeps: u32| SolverParams {
            joint_hertz: hertz,
            ..params(SolverKind::SoftStep, 1, substeps)
        };
        // 120 Hz at 8 substeps is its own point.
        let here = marker(&points, &stiff(120.0, 8), STEP, true).unwrap();
        assert!(here.exact);
        assert_eq!(here.point.error, 0.05);
        // 240 Hz at 8 substeps is capped to 120.
        let capped = marker(&points, &stiff(240.0, 8), STEP, true).unwrap();
        assert!(capped.exact);
        assert_eq!(capped.point.setting.joint_hertz, Some(120.0));
        // At 4 substeps 240 Hz is capped to 60, the default's cap there.
        let default = marker(&points, &stiff(240.0, 4), STEP, true).unwrap();
        assert!(default.exact);
        assert_eq!(default.point.setting, soft(1, 4, None));
        // Without joints the stiffness is no part of the setting: the first point of the
        // numbers is it.
        let free = marker(&points, &stiff(120.0, 8), STEP, false).unwrap();
        assert!(free.exact);
        assert_eq!(free.point.setting, soft(1, 8, None));
    }

    #[test]
    fn direct_joints_are_part_of_the_setting_on_a_scene_with_joints() {
        let mut points = sweep();
        let direct = Setting {
            direct_joints: true,
            ..soft(1, 4, None)
        };
        points.push(point(direct, 0.03, 0.01));
        let with = |direct_joints: bool| SolverParams {
            direct_joints,
            ..params(SolverKind::SoftStep, 1, 4)
        };
        let here = marker(&points, &with(true), STEP, true).unwrap();
        assert!(here.exact);
        assert_eq!(here.point.error, 0.01);
        assert!(here.title().contains("direct joints"), "{}", here.title());
        let off = marker(&points, &with(false), STEP, true).unwrap();
        assert!(off.exact);
        assert_eq!(off.point.setting, soft(1, 4, None));
        // Without a direct point measured, the nearest is the same numbers without.
        let unmeasured = marker(&sweep(), &with(true), STEP, true).unwrap();
        assert!(!unmeasured.exact);
        assert_eq!(unmeasured.point.setting, soft(1, 4, None));
        // The classic solvers have no direct joints to mark.
        assert!(
            !setting_of(&SolverParams {
                direct_joints: true,
                ..params(SolverKind::SequentialImpulse, 8, 1)
            })
            .direct_joints
        );
    }

    #[test]
    fn shock_propagation_is_part_of_the_setting() {
        let mut points = sweep();
        let shocked = Setting {
            shock_propagation: true,
            ..soft(1, 4, None)
        };
        points.push(point(shocked, 0.04, 0.001));
        let with = |shock_propagation: bool| SolverParams {
            shock_propagation,
            ..params(SolverKind::SoftStep, 1, 4)
        };
        let here = marker(&points, &with(true), STEP, false).unwrap();
        assert!(here.exact);
        assert_eq!(here.point.error, 0.001);
        assert!(
            here.title().contains("shock propagation"),
            "{}",
            here.title()
        );
        let off = marker(&points, &with(false), STEP, false).unwrap();
        assert!(off.exact);
        assert_eq!(off.point.setting, soft(1, 4, None));
        // Not measured with it: the nearest, not the same.
        let unmeasured = marker(&sweep(), &with(true), STEP, false).unwrap();
        assert!(!unmeasured.exact);
        assert_eq!(unmeasured.point.setting, soft(1, 4, None));
    }

    #[test]
    fn fronts_are_per_engine_and_the_rest_is_apart() {
        let mut points = sweep();
        points.push(point(soft(8, 8, None), 1.0, f64::INFINITY));
        let fronts = fronts(&points);
        let engines: Vec<Engine> = fronts.iter().map(|f| f.0).collect();
        assert_eq!(engines, [Engine::Carom, Engine::Box2d]);
        let (_, front, rest) = &fronts[0];
        let errors = |ps: &[&Point]| ps.iter().map(|p| p.error).collect::<Vec<f64>>();
        assert_eq!(errors(front), [0.5, 0.4, 0.3, 0.05]);
        // The NaN world is on neither.
        assert_eq!(errors(rest), [0.2, 0.1]);
    }

    #[test]
    fn settings_the_sweep_keeps_at_the_scenes_are_named_when_changed() {
        let scene = SolverParams::default();
        let mine = SolverParams {
            contact_hertz: 60.0,
            warm_starting: false,
            iterations: Some(8),
            ..scene
        };
        // Contact stiffness is swept: the marker finds the nearest measured one.
        assert_eq!(unmeasured_changes(&mine, &scene), ["warm starting"]);
        assert!(unmeasured_changes(&scene, &scene).is_empty());
    }

    #[test]
    fn numbers_read_as_three_significant_digits() {
        let errors = [
            0.0,
            0.4,
            0.05,
            6.25,
            62.5,
            1234.0,
            2.59e-4,
            3.1e5,
            f64::INFINITY,
        ];
        let written: Vec<String> = errors.into_iter().map(format_error).collect();
        assert_eq!(
            written,
            [
                "0", "0.400", "0.0500", "6.25", "62.5", "1234", "2.59e-4", "3.10e5", "inf"
            ]
        );
        assert_eq!(format_ms(0.0213), "0.021");
        assert_eq!(format_ms(12.345), "12.3");
    }

    #[test]
    fn a_stiffness_not_swept_is_nearest_the_closest_swept_one() {
        let points = sweep();
        // 180 Hz joints at 12 substeps: 8 substeps at 120 Hz is nearer than at the default's
        // 60 Hz.
        let chain = SolverParams {
            joint_hertz: 180.0,
            ..params(SolverKind::SoftStep, 1, 12)
        };
        let near = marker(&points, &chain, STEP, true).unwrap();
        assert!(!near.exact);
        assert_eq!(near.point.setting, soft(1, 8, Some(120.0)));
    }

    #[test]
    fn reports_are_looked_for_here_and_beside_the_scene_folder() {
        let paths = report_paths(Path::new("/somewhere/demos/pendulum.ron"));
        assert_eq!(
            paths,
            [
                PathBuf::from(REPORT_CSV),
                PathBuf::from("/somewhere").join(REPORT_CSV)
            ]
        );
    }
}
