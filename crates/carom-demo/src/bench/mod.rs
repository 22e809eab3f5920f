//! `carom bench`: what accuracy costs in time. Every solver setting (solver × iterations ×
//! substeps) runs each scene a few times, sleeping off; each point of the sweep is its median
//! ms/step and its error against the scene's exact answer ([`carom_scene::Accuracy`]). The results go to a CSV,
//! a markdown report and a chart of error against time.

pub mod chart;
pub mod measure;
pub mod report;

pub use measure::{ErrorKind, Measurement, Setting, measure};

use carom::SolverKind;
use std::path::PathBuf;

/// What to sweep.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// The scene files.
    pub scenes: Vec<PathBuf>,
    /// Runs per point; the point's time is the median of the runs' medians.
    pub runs: usize,
    /// The solvers.
    pub solvers: Vec<SolverKind>,
    /// Iteration counts.
    pub iterations: Vec<u32>,
    /// Substep counts (for the solvers that have substeps; the others run 1).
    pub substeps: Vec<u32>,
    /// How long a scene without an accuracy measure runs, s.
    pub seconds: f32,
}

impl Default for SweepOptions {
    /// The sweep over the five accuracy scenes in `demos/`.
    fn default() -> Self {
        SweepOptions {
            scenes: [
                "vertical_stack",
                "pyramid",
                "high_mass_ratio",
                "newtons_cradle",
                "incline_friction",
            ]
            .iter()
            .map(|name| PathBuf::from(format!("demos/{name}.ron")))
            .collect(),
            runs: 3,
            solvers: SolverKind::ALL.to_vec(),
            iterations: vec![1, 2, 4, 8, 16, 32, 64],
            substeps: vec![1, 2, 4, 8],
            seconds: 10.0,
        }
    }
}

impl SweepOptions {
    /// Every setting the sweep runs, solver by solver.
    pub fn settings(&self) -> Vec<Setting> {
        let mut settings = Vec::new();
        for &solver in &self.solvers {
            let substeps: &[u32] = if solver.has_substeps() {
                &self.substeps
            } else {
                &[1]
            };
            for &substeps in substeps {
                for &iterations in &self.iterations {
                    settings.push(Setting {
                        solver,
                        iterations,
                        substeps,
                    });
                }
            }
        }
        settings
    }
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
}

/// Runs the sweep; `progress(done, total, what)` is told before each run.
pub fn sweep(
    options: &SweepOptions,
    mut progress: impl FnMut(usize, usize, &str),
) -> Result<Vec<Point>, String> {
    let scenes = options
        .scenes
        .iter()
        .map(|path| {
            let scene = carom_scene::read(path).map_err(|e| e.to_string())?;
            Ok((scene, path.display().to_string()))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let settings = options.settings();
    let runs = options.runs.max(1);
    let total = scenes.len() * settings.len() * runs;
    let mut done = 0;
    let mut points = Vec::with_capacity(scenes.len() * settings.len());
    for (scene, file) in &scenes {
        for &setting in &settings {
            let what = format!(
                "{}: {}, {} iterations, {} substeps",
                scene.name,
                setting.solver.name(),
                setting.iterations,
                setting.substeps
            );
            let mut medians = Vec::with_capacity(runs);
            let mut first: Option<Measurement> = None;
            for _ in 0..runs {
                progress(done, total, &what);
                let measurement = measure(scene, file, setting, options.seconds)?;
                medians.push(median(&measurement.step_ms));
                first.get_or_insert(measurement);
                done += 1;
            }
            let first = first.expect("at least one run");
            points.push(Point {
                scene: scene.name.clone(),
                error_kind: ErrorKind::of(scene.accuracy.as_ref()),
                setting,
                ms_per_step: median(&medians),
                error: first.error,
                max_penetration: first.max_penetration,
            });
        }
    }
    progress(done, total, "done");
    Ok(points)
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
pub fn sweep_to_folder(
    options: &SweepOptions,
    out: &std::path::Path,
    command: &str,
) -> Result<Vec<Point>, String> {
    use indicatif::{ProgressBar, ProgressStyle};
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} runs, {elapsed} (eta {eta})  {msg}")
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
    write("accuracy.csv", &report::csv(&points))?;
    let machine = report::Machine::here();
    write(
        "README.md",
        &report::markdown(&points, &machine, command, options.runs),
    )?;
    chart::write_chart(&points, &out.join("accuracy.png"))?;
    Ok(points)
}
