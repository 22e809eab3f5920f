//! Contact events: balls dropped onto the ground report when they begin touching it, and a
//! ball thrown back up reports when it stops.
//!
//! `cargo run -p carom --example events`

use carom::{BodyDef, CaromError, ContactEvent, Real, Shape, World, vec2};

fn main() -> Result<(), CaromError> {
    let mut world = World::new();
    let ground =
        world.add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))?;
    let balls: Vec<_> = (0..3)
        .map(|i| {
            let at = vec2(-2.0 + 2.0 * i as Real, 1.0 + i as Real);
            world.add_body(BodyDef::dynamic(Shape::circle(0.25)).position(at))
        })
        .collect::<Result<_, _>>()?;

    for step in 0..240 {
        // Two seconds in, throw the first ball up again.
        if step == 120 {
            world
                .body_mut(balls[0])
                .expect("a ball")
                .set_linear_velocity(vec2(0.0, 8.0))?;
        }
        world.step(1.0 / 60.0)?;
        for event in world.contact_events() {
            let pair = event.pair();
            let ball = if pair.body_a == ground {
                pair.body_b
            } else {
                pair.body_a
            };
            let which = balls
                .iter()
                .position(|&b| b == ball)
                .map_or(-1, |i| i as i32);
            let what = match event {
                ContactEvent::Begin(_) => "begins touching",
                ContactEvent::End(_) => "stops touching",
            };
            println!(
                "t = {:.2} s: ball {which} {what} the ground",
                (step + 1) as f32 / 60.0
            );
        }
    }
    Ok(())
}
