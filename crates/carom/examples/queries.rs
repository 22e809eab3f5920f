//! Queries: cast a ray across a scattered world, pick the body under a point, and find how
//! far a box can slide before it touches anything.
//!
//! `cargo run -p carom --example queries`

use carom::{BodyDef, CaromError, QueryFilter, Ray, Real, Shape, World, WorldShape, vec2};

fn main() -> Result<(), CaromError> {
    let mut world = World::new();
    world.add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))?;
    for i in 0..5 {
        let x = -6.0 + 3.0 * i as Real;
        world.add_body(
            BodyDef::dynamic(Shape::circle(0.4 + 0.1 * i as Real)).position(vec2(x, 1.0)),
        )?;
    }

    // The closest body a ray from the left meets, then every body along it.
    let ray = Ray::new(vec2(-12.0, 1.0), vec2(24.0, 0.0));
    if let Some(hit) = world.cast_ray(&ray, QueryFilter::ALL) {
        println!(
            "the ray first enters {:?} at {:?}, normal {:?}",
            hit.body, hit.point, hit.normal
        );
    }
    let all = world.cast_ray_all(&ray, QueryFilter::ALL);
    println!("it enters {} bodies in all", all.len());

    // The body under a point (a mouse click, say).
    match world.body_at(vec2(0.1, 1.1)) {
        Some(body) => println!("under (0.1, 1.1): {body:?}"),
        None => println!("nothing under (0.1, 1.1)"),
    }

    // How far a box at the left can slide right before it touches the first ball.
    let crate_box = WorldShape::at(&Shape::rect(0.5, 0.5), vec2(-10.0, 1.0), 0.0);
    if let Some(hit) = world.cast_shape(&crate_box, vec2(20.0, 0.0), QueryFilter::ALL) {
        println!(
            "the box can move {:.3} m before touching {:?} at {:?}",
            hit.fraction * 20.0,
            hit.body,
            hit.point
        );
    }
    Ok(())
}
