//! What removing one body costs in a large world: 20 pyramids of 1081 boxes (21,620 bodies),
//! settled a second so every box has its contacts, then one box from the middle of each
//! pyramid removed in turn, each timed alone. Run with `cargo bench -p carom-bench --features criterion --bench removal`;
//! it prints the median and the slowest removal.

use carom::{BodyDef, BodyHandle, Real, Shape, World, vec2};
use std::time::{Duration, Instant};

/// Boxes in the bottom row of each pyramid.
const BASE: usize = 46;

/// Pyramids side by side.
const PYRAMIDS: usize = 20;

/// The world, and a box from the middle of each pyramid.
fn pyramids() -> (World, Vec<BodyHandle>) {
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(1200.0, 1.0)).position(vec2(0.0, -1.0)))
        .unwrap();
    let mut middles = Vec::new();
    for pyramid in 0..PYRAMIDS {
        let left = pyramid as Real * 60.0 - 600.0;
        for row in 0..BASE {
            for column in 0..BASE - row {
                let x = left + column as Real + 0.5 * row as Real;
                let y = 0.5 + row as Real;
                let handle = world
                    .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, y)))
                    .unwrap();
                if row == BASE / 2 && column == (BASE - row) / 2 {
                    middles.push(handle);
                }
            }
        }
    }
    for _ in 0..60 {
        world.step(1.0 / 60.0).unwrap();
    }
    (world, middles)
}

fn main() {
    let mut times: Vec<Duration> = Vec::new();
    for _ in 0..3 {
        let (mut world, middles) = pyramids();
        assert!(world.body_count() > 21_000 && world.contacts().len() > 40_000);
        for handle in middles {
            let start = Instant::now();
            world.remove_body(handle).unwrap();
            times.push(start.elapsed());
        }
    }
    times.sort();
    println!(
        "removing one body of {}: median {:.1} µs, slowest {:.1} µs ({} removals)",
        PYRAMIDS * BASE * (BASE + 1) / 2,
        times[times.len() / 2].as_secs_f64() * 1e6,
        times[times.len() - 1].as_secs_f64() * 1e6,
        times.len()
    );
}
