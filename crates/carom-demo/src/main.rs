//! `carom`: the demo app.
//!
//! Plain `carom` opens the window: scenes from `demos/`, bodies grabbed and thrown with the
//! mouse, solver, effect and drawing controls, and the live cost of accuracy. `carom run` runs a
//! scene headless and reports what it measured; `carom snapshot` renders one to a PNG;
//! `carom bench` sweeps solver settings and shows what accuracy costs in time.

use carom::{Effect, Real, SolverKind};
use carom_bench::sweep::{Engine, SweepOptions, sweep_to_folder};
use carom_demo::recording;
use carom_demo::run::{RunOptions, run};
use carom_demo::snapshot::{self, SnapshotOptions, parse_size};
use carom_demo::window::{self, WindowOptions};
use clap::{Parser, Subcommand};
use std::path::PathBuf;
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
    /// written as a CSV, a markdown report and a chart.
    Bench {
        /// Scene files (default: the seven accuracy scenes in demos/).
        scenes: Vec<PathBuf>,
        /// The folder the CSV, report and chart go to.
        #[arg(long, default_value = "target/bench")]
        out: PathBuf,
        /// Runs per point (the time is their median).
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=100))]
        runs: u32,
        /// Solvers, comma separated (default: all).
        #[arg(long, value_delimiter = ',', value_parser = solver_kind)]
        solvers: Option<Vec<SolverKind>>,
        /// Iteration counts, comma separated (default: 1,2,4,8,16,32,64).
        #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=64))]
        iterations: Option<Vec<u32>>,
        /// Substep counts for soft step, comma separated (default: 1,2,4,8).
        #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=16))]
        substeps: Option<Vec<u32>>,
        /// Joint stiffnesses for soft step on scenes with joints, Hz, comma separated (default:
        /// 60,240). Each is capped at a quarter of the substep rate; those the cap makes equal
        /// run once.
        #[arg(long, value_delimiter = ',', value_parser = joint_hertz)]
        joint_hertz: Option<Vec<Real>>,
        /// Direct joints for soft step on scenes with joints, comma separated: off, on or
        /// both (default: off,on).
        #[arg(long, value_delimiter = ',', value_parser = on_or_off)]
        direct_joints: Option<Vec<bool>>,
        /// Shock propagation for soft step on scenes of bodies at rest under gravity, comma
        /// separated: off, on or both (default: off,on).
        #[arg(long, value_delimiter = ',', value_parser = on_or_off)]
        shock_propagation: Option<Vec<bool>>,
        /// How long scenes without an accuracy measure run, s.
        #[arg(long, default_value_t = 10.0)]
        seconds: Real,
        /// Engines, comma separated: carom, box2d, rapier (default: carom). Box2D is swept
        /// over its substeps (1 to 16) and contact stiffness (30 and 60 Hz), Rapier over its
        /// solver and stabilization iterations (1 to 16), on the same scenes.
        #[arg(long, value_delimiter = ',', value_parser = engine)]
        engines: Option<Vec<Engine>>,
    },
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

/// A solver from its name on the command line (`soft-step` or `soft_step`).
fn solver_kind(text: &str) -> Result<SolverKind, String> {
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

/// `on` or `off` from the command line.
fn on_or_off(text: &str) -> Result<bool, String> {
    match text {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("{text:?} is neither on nor off")),
    }
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
    let cli = Cli::parse();
    match cli.command.clone() {
        None => {
            let options = match window_options(&cli) {
                Ok(options) => options,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            };
            match window::run(options) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
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
            match run(&scene, &options) {
                Ok(report) => {
                    if json {
                        println!("{}", report.to_json());
                    } else {
                        println!("{}", report.summary(&scene.display().to_string()));
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Some(Command::Bench {
            scenes,
            out,
            runs,
            solvers,
            iterations,
            substeps,
            joint_hertz,
            direct_joints,
            shock_propagation,
            seconds,
            engines,
        }) => {
            let defaults = SweepOptions::default();
            let options = SweepOptions {
                scenes: if scenes.is_empty() {
                    defaults.scenes
                } else {
                    scenes
                },
                runs: runs as usize,
                solvers: solvers.unwrap_or(defaults.solvers),
                iterations: iterations.unwrap_or(defaults.iterations),
                substeps: substeps.unwrap_or(defaults.substeps),
                joint_hertz: joint_hertz.unwrap_or(defaults.joint_hertz),
                direct_joints: direct_joints.unwrap_or(defaults.direct_joints),
                shock_propagation: shock_propagation.unwrap_or(defaults.shock_propagation),
                seconds,
                engines: engines.unwrap_or(defaults.engines),
                ..defaults
            };
            let command: Vec<String> = std::env::args().collect();
            match sweep_to_folder(&options, &out, &command.join(" ")) {
                Ok(points) => {
                    println!(
                        "{} points -> {}",
                        points.len(),
                        out.join("README.md").display()
                    );
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Some(Command::Record { scene, steps, out }) => {
            let written = recording::record(&scene, steps).and_then(|recording| {
                std::fs::write(&out, recording.to_text())
                    .map_err(|e| format!("cannot write {}: {e}", out.display()))
            });
            match written {
                Ok(()) => {
                    println!("{}: {steps} steps -> {}", scene.display(), out.display());
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Some(Command::Replay { run, json }) => {
            let replayed = std::fs::read_to_string(&run)
                .map_err(|e| format!("cannot read {}: {e}", run.display()))
                .and_then(|text| recording::replay(&text, &run.display().to_string()));
            match replayed {
                Ok(replayed) => {
                    if json {
                        println!("{}", replayed.to_json());
                    } else {
                        println!("{}", replayed.summary());
                    }
                    if replayed.parting.is_none() {
                        ExitCode::SUCCESS
                    } else {
                        ExitCode::FAILURE
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
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
            match snapshot_command(&scene, &options, &out, time_frames) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
    }
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
