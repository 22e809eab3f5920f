//! `carom-bench`: times carom and Rapier on the same scenes, in turn, in one process.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use carom_bench::{RapierWorld, RunResult, run_carom, run_rapier};
use clap::Parser;

/// Time step of every run, s (Box2D's benchmark).
const DT: f32 = 1.0 / 60.0;

/// Box2D's benchmark scenes and step counts, run when no scene is named.
const DEFAULT_SCENES: [(&str, u32); 2] = [
    ("demos/large_pyramid.ron", 500),
    ("demos/many_pyramids.ron", 200),
];

/// Steps for a scene not in [`DEFAULT_SCENES`] when `--steps` is not given.
const FALLBACK_STEPS: u32 = 500;

/// Times carom and Rapier on the same scenes: dt 1/60, first step untimed, minimum over runs.
#[derive(Parser, Debug)]
#[command(name = "carom-bench")]
struct Args {
    /// Scene files (default: demos/large_pyramid.ron, 500 steps; demos/many_pyramids.ron, 200).
    scenes: Vec<PathBuf>,
    /// Steps per run, overriding each scene's default.
    #[arg(long)]
    steps: Option<u32>,
    /// Runs per engine, each from a fresh copy of the scene; the fastest is kept.
    #[arg(long, default_value_t = 3)]
    runs: u32,
    /// Also write the table as CSV to this file.
    #[arg(long)]
    csv: Option<PathBuf>,
}

/// One table row.
struct Row {
    scene: String,
    bodies: usize,
    carom: RunResult,
    rapier: RunResult,
}

fn default_steps(path: &Path) -> u32 {
    DEFAULT_SCENES
        .iter()
        .find(|(p, _)| path.ends_with(p) || Path::new(p).file_name() == path.file_name())
        .map_or(FALLBACK_STEPS, |(_, s)| *s)
}

/// Keeps the faster run's time; accuracy figures are those of the first run.
fn keep_min(best: Option<RunResult>, run: RunResult) -> RunResult {
    match best {
        Some(b) if b.total_ms <= run.total_ms => b,
        Some(b) => RunResult {
            total_ms: run.total_ms,
            ..b
        },
        None => run,
    }
}

/// The scene file: as given, or for a relative path not found, under the workspace root (so
/// the default scenes load from any directory).
fn resolve(path: &Path) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    if path.exists() || path.is_absolute() || !root.join(path).exists() {
        path.to_path_buf()
    } else {
        root.join(path)
    }
}

fn bench_scene(path: &Path, steps: u32, runs: u32) -> Result<Row, String> {
    let path = &resolve(path);
    let load = || carom_scene::load(path).map_err(|e| format!("{}: {e}", path.display()));
    let mut carom_best = None;
    let mut rapier_best = None;
    let mut bodies = 0;
    for run in 1..=runs {
        let mut scene = load()?;
        bodies = scene.world.body_count();
        let c = run_carom(&mut scene.world, DT, steps)?;
        eprintln!(
            "{} run {run}: carom {:.3} ms/step",
            path.display(),
            c.ms_per_step()
        );
        carom_best = Some(keep_min(carom_best, c));
        drop(scene);

        let scene = load()?;
        let mut rapier = RapierWorld::from_carom(&scene.world, DT)?;
        drop(scene);
        let r = run_rapier(&mut rapier, steps);
        eprintln!(
            "{} run {run}: Rapier {:.3} ms/step",
            path.display(),
            r.ms_per_step()
        );
        rapier_best = Some(keep_min(rapier_best, r));
    }
    let name = path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into(),
    );
    Ok(Row {
        scene: name,
        bodies,
        carom: carom_best.ok_or("no runs")?,
        rapier: rapier_best.ok_or("no runs")?,
    })
}

fn drop_cell(r: &RunResult) -> String {
    if r.nan {
        format!("{:.3} (NaN!)", r.top_drop)
    } else {
        format!("{:.3}", r.top_drop)
    }
}

fn markdown(rows: &[Row]) -> String {
    let mut s = String::from(
        "| scene | bodies | carom ms/step | Rapier ms/step | carom/Rapier ratio | carom top drop m | Rapier top drop m |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let (c, p) = (r.carom.ms_per_step(), r.rapier.ms_per_step());
        let _ = writeln!(
            s,
            "| {} | {} | {:.3} | {:.3} | {:.2} | {} | {} |",
            r.scene,
            r.bodies,
            c,
            p,
            c / p,
            drop_cell(&r.carom),
            drop_cell(&r.rapier)
        );
    }
    s
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "scene,bodies,carom_ms_per_step,rapier_ms_per_step,carom_rapier_ratio,carom_top_drop_m,rapier_top_drop_m,carom_nan,rapier_nan\n",
    );
    for r in rows {
        let (c, p) = (r.carom.ms_per_step(), r.rapier.ms_per_step());
        let _ = writeln!(
            s,
            "{},{},{:.4},{:.4},{:.4},{:.4},{:.4},{},{}",
            r.scene,
            r.bodies,
            c,
            p,
            c / p,
            r.carom.top_drop,
            r.rapier.top_drop,
            r.carom.nan,
            r.rapier.nan
        );
    }
    s
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    if args.runs == 0 {
        return Err("--runs must be at least 1".into());
    }
    let scenes: Vec<(PathBuf, u32)> = if args.scenes.is_empty() {
        DEFAULT_SCENES
            .iter()
            .map(|(p, s)| (PathBuf::from(p), args.steps.unwrap_or(*s)))
            .collect()
    } else {
        args.scenes
            .iter()
            .map(|p| (p.clone(), args.steps.unwrap_or_else(|| default_steps(p))))
            .collect()
    };
    let mut rows = Vec::new();
    for (path, steps) in &scenes {
        rows.push(bench_scene(path, *steps, args.runs)?);
    }
    println!(
        "dt 1/60, steps {}, first step untimed, minimum of {} run(s)\n",
        scenes
            .iter()
            .map(|(p, s)| format!("{}: {s}", p.display()))
            .collect::<Vec<_>>()
            .join(", "),
        args.runs
    );
    print!("{}", markdown(&rows));
    if let Some(path) = &args.csv {
        std::fs::write(path, csv(&rows)).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}
