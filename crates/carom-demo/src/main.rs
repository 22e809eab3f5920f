//! `carom`: the demo app.
//!
//! Plain `carom` opens the window: scenes from `demos/`, bodies grabbed and thrown with the
//! mouse, solver, effect and drawing controls, and the live cost of accuracy. `carom run` runs a
//! scene headless and reports what it measured; `carom snapshot` renders one to a PNG;
//! `carom bench` sweeps solver settings and shows what accuracy costs in time.

use carom::{Effect, SolverKind};
use carom_bench::sweep::SweepOptions;
use carom_bench::sweep::cli::{SweepArgs, solver_kind};
use carom_demo::recording;
use carom_demo::run::{RunOptions, run};
use carom_demo::snapshot::{self, SnapshotOptions, parse_size};
use carom_demo::window::{self, WindowOptions};
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The carom physics demo.
#[derive(Parser, Debug)]
#[command(name = "carom", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The scene the window opens (default: demos/grabbing.ron).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Window size in logical pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    size: (u32, u32),
    /// Close the window after this many frames.
    #[arg(long)]
    frames: Option<u64>,
    /// Save the window's contents (sidebar included) to this PNG after the last frame.
    #[arg(long, requires = "frames")]
    screenshot: Option<PathBuf>,
    /// Play the scene's recorded play (a scene with a player and a `replay`).
    #[arg(long)]
    replay: bool,
    /// Take this many steps every frame, whatever the clock says (for scripted runs).
    #[arg(long)]
    steps_per_frame: Option<u32>,
    /// At a frame, act as a user would: FRAME:ACTION, the action one of pause, play,
    /// step-back, go-to=STEP, grab=X,Y (a world point), let-go, print (the step and the state
    /// hash). Repeatable; a frame's actions run in the order given, before its steps.
    #[arg(long = "at", value_parser = window::parse_scripted)]
    script: Vec<window::Scripted>,
}

#[derive(Subcommand, Debug, Clone)]
enum Command {
    /// Run a scene headless and print what it measured.
    Run {
        /// The scene file, for example demos/pyramid.ron.
        scene: PathBuf,
        /// How many steps.
        #[arg(long, default_value_t = 600)]
        steps: usize,
        /// Replace the scene's solver: push-out, tutorial-impulse, sequential-impulse or
        /// soft-step.
        #[arg(long, value_parser = solver_kind)]
        solver: Option<SolverKind>,
        /// Velocity iterations (1 to 64).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=64))]
        iterations: Option<u32>,
        /// Substeps (1 to 16).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16))]
        substeps: Option<u32>,
        /// Add (+) or remove (-) effects, for example `--effects=+continuous,-drag`.
        #[arg(long, value_parser = parse_effects, allow_hyphen_values = true)]
        effects: Option<EffectChanges>,
        /// Print one JSON object instead of a summary.
        #[arg(long)]
        json: bool,
        /// Threads to step on (default: one per core).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=256))]
        threads: Option<u32>,
    },
    /// Sweep solvers, iterations and substeps (and joint stiffness and direct joints on scenes
    /// with joints, shock propagation on piles at rest) over scenes: ms/step against error,
    /// written as a CSV, a markdown report and a chart to --out (default target/bench). The
    /// same sweep as `carom-bench sweep`, carom alone unless --engines names the peers.
    Bench(SweepArgs),
    /// Run a scene headless and write the run as a recording: the scene and the state hash
    /// after every step, for `carom replay` (natively or in the web build) to check.
    Record {
        /// The scene file, for example demos/pyramid.ron.
        scene: PathBuf,
        /// How many steps.
        #[arg(long, default_value_t = 600)]
        steps: u64,
        /// Where to write the recording (a `.run` file is RON text).
        #[arg(long)]
        out: PathBuf,
    },
    /// Play a recording back (one from `carom record`, or saved from the app with its grabs,
    /// throws, keys and setting changes) and check every step's state hash; exits with an error
    /// at the first step that ends elsewhere, naming it.
    Replay {
        /// The recording.
        run: PathBuf,
        /// Print one JSON object instead of a summary.
        #[arg(long)]
        json: bool,
    },
    /// Render a scene after some steps to a PNG, offscreen (no window needed).
    Snapshot {
        /// The scene file, for example demos/collision.ron.
        scene: PathBuf,
        /// Steps to simulate first.
        #[arg(long, default_value_t = 0)]
        steps: usize,
        /// Where to write the PNG.
        #[arg(long)]
        out: PathBuf,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "1280x720", value_parser = parse_size)]
        size: (u32, u32),
        /// Add (+) or remove (-) draw layers, for example `--draw=+aabbs,+contact_points`.
        #[arg(long, value_parser = parse_draw_changes, allow_hyphen_values = true)]
        draw: Option<DrawChanges>,
        /// Also render this many more frames and print the median frame time.
        #[arg(long, default_value_t = 0)]
        time_frames: usize,
    },
}

/// Draw layers to switch on (`true`) and off.
#[derive(Debug, Clone)]
struct DrawChanges(Vec<(carom::draw::DrawFlags, bool)>);

fn parse_draw_changes(text: &str) -> Result<DrawChanges, String> {
    snapshot::parse_draw_changes(text).map(DrawChanges)
}

/// Effects to switch on (`true`) and off, in order.
#[derive(Debug, Clone)]
struct EffectChanges(Vec<(Effect, bool)>);

/// Parses `+continuous,-drag` into effects to switch on and off.
fn parse_effects(text: &str) -> Result<EffectChanges, String> {
    let known: Vec<&str> = Effect::ALL.iter().map(|e| e.name()).collect();
    snapshot::parse_toggles(text, ("effect", "effect"), &known, Effect::from_name)
        .map(EffectChanges)
}

fn main() -> ExitCode {
    match run_command(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Does what the command line asks. A replay that parts from its recording is a failure
/// without an error: its summary already says where.
fn run_command(cli: Cli) -> Result<ExitCode, String> {
    match cli.command.clone() {
        None => window::run(window_options(&cli)?).map_err(|e| e.to_string())?,
        Some(Command::Run {
            scene,
            steps,
            solver,
            iterations,
            substeps,
            effects,
            json,
            threads,
        }) => {
            let options = RunOptions {
                steps,
                solver,
                iterations,
                substeps,
                effects: effects.map(|changes| changes.0).unwrap_or_default(),
                threads: threads.map(|n| n as usize),
            };
            let report = run(&scene, &options)?;
            if json {
                println!("{}", report.to_json());
            } else {
                println!("{}", report.summary(&scene.display().to_string()));
            }
        }
        Some(Command::Bench(sweep)) => {
            let command: Vec<String> = std::env::args().collect();
            let out = Path::new("target/bench");
            sweep.run(SweepOptions::default(), out, &command.join(" "))?;
        }
        Some(Command::Record { scene, steps, out }) => {
            let recording = recording::record(&scene, steps)?;
            std::fs::write(&out, recording.to_text())
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            println!("{}: {steps} steps -> {}", scene.display(), out.display());
        }
        Some(Command::Replay { run, json }) => {
            let text = std::fs::read_to_string(&run)
                .map_err(|e| format!("cannot read {}: {e}", run.display()))?;
            let replayed = recording::replay(&text, &run.display().to_string())?;
            if json {
                println!("{}", replayed.to_json());
            } else {
                println!("{}", replayed.summary());
            }
            if replayed.parting.is_some() {
                return Ok(ExitCode::FAILURE);
            }
        }
        Some(Command::Snapshot {
            scene,
            steps,
            out,
            size,
            draw,
            time_frames,
        }) => {
            let options = SnapshotOptions {
                steps,
                width: size.0,
                height: size.1,
                draw: draw.map(|changes| changes.0).unwrap_or_default(),
            };
            snapshot_command(&scene, &options, &out, time_frames)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `carom snapshot`: steps, renders, writes the PNG, and optionally times more frames.
fn snapshot_command(
    scene: &std::path::Path,
    options: &SnapshotOptions,
    out: &std::path::Path,
    time_frames: usize,
) -> Result<(), String> {
    let mut renderer =
        carom_render::Offscreen::new(options.width, options.height).map_err(|e| e.to_string())?;
    let world = snapshot::load_and_step(scene, options.steps)?;
    let image = snapshot::render_scene(&world, options, &mut renderer)?;
    image
        .save(out)
        .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
    println!(
        "{}: {} steps, {} bodies, {}x{} on {} -> {}",
        scene.display(),
        options.steps,
        world.world.body_count(),
        options.width,
        options.height,
        renderer.gpu().describe(),
        out.display()
    );
    if time_frames > 0 {
        let times = snapshot::time_frames(&world, options, &mut renderer, time_frames)?;
        println!(
            "frame     {:.3} ms describe + {:.3} ms render and read back (medians of {} frames)",
            times.describe_ms, times.render_ms, times.frames
        );
    }
    Ok(())
}

/// The window's options: the scene given, else `demos/grabbing.ron` from the working directory
/// or, for `cargo run` from elsewhere, from the source tree.
fn window_options(cli: &Cli) -> Result<WindowOptions, String> {
    let scene = match &cli.scene {
        Some(scene) => scene.clone(),
        None => default_demos_folder()?.join(DEFAULT_SCENE),
    };
    let scenes_folder = match scene.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok(WindowOptions {
        scene,
        scenes_folder,
        size: cli.size,
        frames: cli.frames,
        screenshot: cli.screenshot.clone(),
        replay: cli.replay,
        steps_per_frame: cli.steps_per_frame,
        script: cli.script.clone(),
        backends: None,
    })
}

/// The scene a plain `carom` opens.
const DEFAULT_SCENE: &str = "grabbing.ron";

fn default_demos_folder() -> Result<PathBuf, String> {
    let candidates = [
        PathBuf::from("demos"),
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos"),
    ];
    candidates
        .iter()
        .find(|folder| folder.join(DEFAULT_SCENE).is_file())
        .cloned()
        .ok_or_else(|| {
            format!(
                "cannot find demos/{DEFAULT_SCENE}; run carom from the repository's root or pass \
                 --scene FILE"
            )
        })
}
