//! `carom`: the demo app.
//!
//! The windowed demo (scenes from `demos/`, grabbing and throwing with the mouse, solver
//! controls) arrives with the demo work. Today: `carom run` runs a scene headless and reports
//! what it measured; plain `carom` says what is coming and drops a few bodies.

use carom::{BodyDef, CaromError, Effect, Shape, SolverKind, World, vec2};
use carom_demo::run::{RunOptions, run};
use carom_demo::snapshot::{self, SnapshotOptions, parse_size};
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

/// The carom physics demo.
#[derive(Parser, Debug)]
#[command(name = "carom", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a scene headless and print what it measured.
    Run {
        /// The scene file, for example demos/pyramid.ron.
        scene: PathBuf,
        /// How many steps.
        #[arg(long, default_value_t = 600)]
        steps: usize,
        /// Replace the scene's solver.
        #[arg(long, value_enum)]
        solver: Option<SolverArg>,
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
struct DrawChanges(Vec<(carom::DrawFlags, bool)>);

fn parse_draw_changes(text: &str) -> Result<DrawChanges, String> {
    snapshot::parse_draw_changes(text).map(DrawChanges)
}

/// The solvers, as the command line names them.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum SolverArg {
    PushOut,
    TutorialImpulse,
    SequentialImpulse,
    SoftStep,
}

impl From<SolverArg> for SolverKind {
    fn from(arg: SolverArg) -> Self {
        match arg {
            SolverArg::PushOut => SolverKind::PushOut,
            SolverArg::TutorialImpulse => SolverKind::TutorialImpulse,
            SolverArg::SequentialImpulse => SolverKind::SequentialImpulse,
            SolverArg::SoftStep => SolverKind::SoftStep,
        }
    }
}

/// Effects to switch on (`true`) and off, in order.
#[derive(Debug, Clone)]
struct EffectChanges(Vec<(Effect, bool)>);

/// Parses `+continuous,-drag` into effects to switch on and off.
fn parse_effects(text: &str) -> Result<EffectChanges, String> {
    text.split(',')
        .filter(|part| !part.is_empty())
        .map(|part| {
            let (on, name) = match part.split_at(1) {
                ("+", name) => (true, name),
                ("-", name) => (false, name),
                _ => return Err(format!("`{part}`: start each effect with + or -")),
            };
            let effect = Effect::from_name(name).ok_or_else(|| {
                let known: Vec<&str> = Effect::ALL.iter().map(|e| e.name()).collect();
                format!("unknown effect `{name}`; known: {}", known.join(", "))
            })?;
            Ok((effect, on))
        })
        .collect::<Result<_, _>>()
        .map(EffectChanges)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        None => match drop_demo() {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Some(Command::Run {
            scene,
            steps,
            solver,
            iterations,
            substeps,
            effects,
            json,
        }) => {
            let options = RunOptions {
                steps,
                solver: solver.map(SolverKind::from),
                iterations,
                substeps,
                effects: effects.map(|changes| changes.0).unwrap_or_default(),
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

/// Drops a box, a ball and a spinning pentagon for two seconds and prints a table.
fn drop_demo() -> Result<(), CaromError> {
    println!(
        "carom: the window, scenes, mouse grabbing and solver controls arrive with the demo work.\n\
         Try `carom run demos/pyramid.ron` to run a scene headless. Meanwhile, three bodies fall:\n"
    );
    let mut world = World::new();
    let bodies = [
        (
            "box",
            world.add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)?).position(vec2(-2.0, 10.0)))?,
        ),
        (
            "ball",
            world.add_body(
                BodyDef::dynamic(Shape::circle(0.5)?)
                    .position(vec2(0.0, 10.0))
                    .damping(0.5, 0.0),
            )?,
        ),
        (
            "pentagon",
            world.add_body(
                BodyDef::dynamic(Shape::regular(5, 0.6)?)
                    .position(vec2(2.0, 10.0))
                    .linear_velocity(vec2(1.0, 5.0))
                    .angular_velocity(3.0),
            )?,
        ),
    ];
    println!(
        "{:>6} {:>10} {:>18} {:>18} {:>9}",
        "t (s)", "body", "position", "velocity", "angle"
    );
    for step in 0..=120 {
        if step % 30 == 0 {
            for (name, handle) in &bodies {
                let body = world.body(*handle).expect("bodies are never removed here");
                let (p, v) = (body.position(), body.linear_velocity());
                println!(
                    "{:>6.2} {:>10} {:>18} {:>18} {:>9.3}",
                    world.time(),
                    name,
                    format!("({:.2}, {:.2})", p.x, p.y),
                    format!("({:.2}, {:.2})", v.x, v.y),
                    body.angle()
                );
            }
        }
        world.step(1.0 / 60.0)?;
    }
    Ok(())
}
