//! The accuracy sweep's command line, one definition for `carom-bench sweep` and the demo's
//! `carom bench`: which scenes and settings, where the report goes, and whether to measure it
//! again against the committed one.

use super::engine::Engine;
use super::{SweepOptions, report, sweep, sweep_to_folder};
use carom::{Real, SolverKind};
use std::path::{Path, PathBuf};

/// What a sweep is asked on the command line; every setting left out keeps the caller's
/// default (see [`SweepArgs::run`]).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct SweepArgs {
    /// Scene files (default: the accuracy scenes in demos/).
    pub scenes: Vec<PathBuf>,
    /// Folder for the CSV, the report and the chart (with --check: where the committed
    /// sweep is read from).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// A part of the settings, one run each: a minute or two instead of ten.
    #[arg(long)]
    pub quick: bool,
    /// Write nothing; measure the points and compare their errors and overlaps (not their
    /// times) with --out's accuracy.csv, failing where they differ.
    #[arg(long)]
    pub check: bool,
    /// Runs per point; its time is the median of the runs' medians (default 1).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub runs: Option<u32>,
    /// Points measured at once (default: one, so that no point slows another; every core
    /// with --check, which compares no times).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub jobs: Option<u32>,
    /// Engines, comma separated: carom, box2d, rapier. Box2D is swept over its substeps and
    /// contact stiffness (30 and 60 Hz), Rapier over its solver and stabilization
    /// iterations, on the same scenes.
    #[arg(long, value_delimiter = ',', value_parser = engine)]
    pub engines: Option<Vec<Engine>>,
    /// carom's solvers, comma separated (default: all).
    #[arg(long, value_delimiter = ',', value_parser = solver_kind)]
    pub solvers: Option<Vec<SolverKind>>,
    /// Iteration counts, comma separated (default: 1,2,4,8,16,32,64).
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=64))]
    pub iterations: Option<Vec<u32>>,
    /// Substep counts for soft step, comma separated (default: 1,2,4,8,16).
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=16))]
    pub substeps: Option<Vec<u32>>,
    /// Joint stiffnesses for soft step on scenes with joints, Hz, comma separated (default:
    /// 60,240). Each is capped at a quarter of the substep rate; those the cap makes equal
    /// run once.
    #[arg(long, value_delimiter = ',', value_parser = joint_hertz)]
    pub joint_hertz: Option<Vec<Real>>,
    /// Direct joints for soft step on scenes with joints, comma separated: off, on or both
    /// (default: off,on).
    #[arg(long, value_delimiter = ',', value_parser = on_or_off)]
    pub direct_joints: Option<Vec<bool>>,
    /// Shock propagation for soft step on scenes of bodies at rest under gravity, comma
    /// separated: off, on or both (default: off,on).
    #[arg(long, value_delimiter = ',', value_parser = on_or_off)]
    pub shock_propagation: Option<Vec<bool>>,
    /// How long scenes without an accuracy measure run, s (default 10).
    #[arg(long, value_parser = seconds)]
    pub seconds: Option<Real>,
}

impl SweepArgs {
    /// The sweep's options: `base` (or its quick part, with `--quick`), with every setting
    /// given on the command line in place of `base`'s, its scenes found from the repository's
    /// root when they are not where the program runs.
    pub fn options(&self, base: SweepOptions) -> SweepOptions {
        let mut options = if self.quick { base.quickened() } else { base };
        if !self.scenes.is_empty() {
            options.scenes = self.scenes.clone();
        }
        options.scenes = options.scenes.iter().map(|p| resolve(p)).collect();
        pick(&self.engines, &mut options.engines);
        pick(&self.solvers, &mut options.solvers);
        pick(&self.iterations, &mut options.iterations);
        pick(&self.substeps, &mut options.substeps);
        pick(&self.joint_hertz, &mut options.joint_hertz);
        pick(&self.direct_joints, &mut options.direct_joints);
        pick(&self.shock_propagation, &mut options.shock_propagation);
        if let Some(seconds) = self.seconds {
            options.seconds = seconds;
        }
        options.runs = self.runs.map_or(1, |n| n as usize);
        options.jobs = match self.jobs {
            Some(jobs) => jobs as usize,
            None if self.check => std::thread::available_parallelism().map_or(1, |n| n.get()),
            None => 1,
        };
        options
    }

    /// Measures the sweep of [`SweepArgs::options`] over `base` and writes its report to
    /// `--out` (else `default_out`), saying how it was made (`command`); with `--check`,
    /// writes nothing and fails where an error or overlap differs from the committed
    /// `accuracy.csv` there. Progress and the outcome go to standard error.
    pub fn run(&self, base: SweepOptions, default_out: &Path, command: &str) -> Result<(), String> {
        let options = self.options(base);
        let out = self.out.as_deref().unwrap_or(default_out);
        let started = std::time::Instant::now();
        if !self.check {
            let points = sweep_to_folder(&options, out, command)?;
            eprintln!(
                "{} points in {:.0} s -> {}",
                points.len(),
                started.elapsed().as_secs_f64(),
                out.join("README.md").display()
            );
            return Ok(());
        }
        let committed_path = out.join("accuracy.csv");
        let committed = std::fs::read_to_string(&committed_path)
            .map_err(|e| format!("{}: {e}", committed_path.display()))
            .and_then(|text| {
                report::parse_csv(&text).map_err(|e| format!("{}: {e}", committed_path.display()))
            })?;
        let measured = sweep(&options, |_, _, _| {})?;
        let differences = report::differences(&measured, &committed);
        if differences.is_empty() {
            eprintln!(
                "{} points in {:.0} s: every error and overlap as in {}",
                measured.len(),
                started.elapsed().as_secs_f64(),
                committed_path.display()
            );
            return Ok(());
        }
        for line in &differences {
            eprintln!("{line}");
        }
        Err(format!(
            "{} of {} points differ from {}: run `carom-bench sweep` and commit what it writes",
            differences.len(),
            measured.len(),
            committed_path.display()
        ))
    }
}

/// `kept` replaced by `given`, if given.
fn pick<T: Clone>(given: &Option<Vec<T>>, kept: &mut Vec<T>) {
    if let Some(given) = given {
        kept.clone_from(given);
    }
}

/// `path` as given when it exists there (or is absolute, or is not in the repository either),
/// else the same path from the repository's root, so that the sweep runs from any folder.
pub fn resolve(path: &Path) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    if path.exists() || path.is_absolute() || !root.join(path).exists() {
        path.to_path_buf()
    } else {
        root.join(path)
    }
}

/// A solver from its name on the command line (`soft-step` or `soft_step`).
pub fn solver_kind(text: &str) -> Result<SolverKind, String> {
    SolverKind::from_id(&text.replace('-', "_")).ok_or_else(|| {
        let names: Vec<String> = SolverKind::ALL
            .iter()
            .map(|kind| kind.id().replace('_', "-"))
            .collect();
        format!("unknown solver {text:?}; one of {}", names.join(", "))
    })
}

/// An engine from the command line.
fn engine(text: &str) -> Result<Engine, String> {
    Engine::from_name(text)
        .ok_or_else(|| format!("unknown engine {text:?}; one of carom, box2d, rapier"))
}

/// A joint stiffness from the command line: finite and positive, as the solver requires.
fn joint_hertz(text: &str) -> Result<Real, String> {
    match text.parse::<Real>() {
        Ok(hertz) if hertz.is_finite() && hertz > 0.0 => Ok(hertz),
        _ => Err(format!("{text:?} is not a positive number of hertz")),
    }
}

/// A duration from the command line: finite and positive.
fn seconds(text: &str) -> Result<Real, String> {
    match text.parse::<Real>() {
        Ok(seconds) if seconds.is_finite() && seconds > 0.0 => Ok(seconds),
        _ => Err(format!("{text:?} is not a positive number of seconds")),
    }
}

/// `on` or `off` from the command line.
fn on_or_off(text: &str) -> Result<bool, String> {
    match text {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("{text:?} is neither on nor off")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        sweep: SweepArgs,
    }

    fn parse(args: &[&str]) -> Result<SweepArgs, clap::Error> {
        Cli::try_parse_from(std::iter::once("sweep").chain(args.iter().copied())).map(|c| c.sweep)
    }

    #[test]
    fn settings_given_replace_the_base_s_and_the_rest_are_kept() {
        let args = parse(&[
            "--engines=carom,box2d",
            "--solvers=soft-step",
            "--iterations=2,4",
            "--direct-joints=on",
            "--seconds=2.5",
            "--runs=3",
        ])
        .expect("valid arguments");
        let options = args.options(SweepOptions::default());
        assert_eq!(options.engines, vec![Engine::Carom, Engine::Box2d]);
        assert_eq!(options.solvers, vec![SolverKind::SoftStep]);
        assert_eq!(options.iterations, vec![2, 4]);
        assert_eq!(options.direct_joints, vec![true]);
        assert_eq!(options.seconds, 2.5);
        assert_eq!(options.runs, 3);
        assert_eq!(options.jobs, 1);
        let base = SweepOptions::default();
        assert_eq!(options.substeps, base.substeps);
        assert_eq!(options.shock_propagation, base.shock_propagation);
        assert_eq!(options.scenes.len(), base.scenes.len());
    }

    #[test]
    fn quick_takes_the_base_s_quick_part_and_check_every_core() {
        let args = parse(&["--quick", "--check"]).expect("valid arguments");
        let options = args.options(SweepOptions::full());
        let quick = SweepOptions::quick();
        assert_eq!(options.iterations, quick.iterations);
        assert_eq!(options.substeps, quick.substeps);
        assert_eq!(options.engines, quick.engines);
        assert!(options.jobs >= 1);
    }

    #[test]
    fn bad_values_are_refused_with_their_reason() {
        for (args, says) in [
            (&["--solvers=fast"][..], "unknown solver"),
            (&["--engines=havok"][..], "unknown engine"),
            (&["--joint-hertz=-5"][..], "positive number of hertz"),
            (&["--seconds=nan"][..], "positive number of seconds"),
            (&["--direct-joints=maybe"][..], "neither on nor off"),
            (&["--runs=0"][..], "0 is not in 1..=100"),
            (&["--jobs=0"][..], "0 is not in 1..=1024"),
        ] {
            let error = parse(args).expect_err("refused").to_string();
            assert!(error.contains(says), "{args:?}: {error}");
        }
    }
}
