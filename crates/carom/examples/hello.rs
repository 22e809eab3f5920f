//! A box falls onto the ground and comes to rest: the smallest carom program.
//!
//! `cargo run -p carom --example hello`

use carom::{BodyDef, CaromError, Shape, World, vec2};

fn main() -> Result<(), CaromError> {
    let mut world = World::new(); // gravity (0, -10) m/s²
    // A static ground 20 m wide whose top is at y = 0, and a 1 m box 4 m above it.
    world.add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))?;
    let crate_box =
        world.add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 4.5)))?;

    for step in 0..=120 {
        if step % 10 == 0 {
            let body = world.body(crate_box).expect("the box is in the world");
            println!(
                "t = {:.2} s  y = {:.3} m  vy = {:+.3} m/s",
                step as f32 / 60.0,
                body.position().y,
                body.linear_velocity().y
            );
        }
        world.step(1.0 / 60.0)?;
    }
    Ok(())
}
