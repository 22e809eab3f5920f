//! `carom`: the demo app.
//!
//! The windowed demo (scenes from `demos/`, grabbing and throwing with the mouse, solver
//! controls) and the headless `run` / `snapshot` subcommands arrive with later work. Until
//! then this binary says so and drops a few bodies headless, printing where they go, so
//! `cargo run --release` exercises the physics core end to end.

use carom::{BodyDef, CaromError, Shape, World, vec2};
use std::process::ExitCode;

const USAGE: &str = "\
carom: the carom physics demo

USAGE:
    carom            drop a few bodies headless and print their fall
    carom --help     show this message

Coming next: a window with scenes from demos/, mouse grabbing, solver and
iteration controls with live timing, and the headless `carom run` and
`carom snapshot` subcommands.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        None => match drop_demo() {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Some("-h" | "--help") => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        Some(other) => {
            eprintln!("error: unknown argument `{other}`\n\n{USAGE}");
            ExitCode::from(2)
        }
    }
}

/// Drops a box, a ball and a spinning pentagon for two seconds and prints a table.
fn drop_demo() -> Result<(), CaromError> {
    println!("{USAGE}\n");
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
    let dt = 1.0 / 60.0;
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
        world.step(dt)?;
    }
    Ok(())
}
