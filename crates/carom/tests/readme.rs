//! The README's code examples, compiled and run as they are written there. A test checks that
//! every Rust example in the README appears here line for line, so the two cannot drift apart.

#[rustfmt::skip]
fn joint_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, JointDef, Shape, World, vec2};

    let mut world = World::new();
    let hook = world.add_body(BodyDef::static_body(Shape::rect(0.2, 0.2)))?;
    let door = world.add_body(BodyDef::dynamic(Shape::rect(1.0, 0.1)).position(vec2(1.0, 0.0)))?;
    // A hinge at the hook, swinging at most 45° either way, with a little friction.
    let hinge = world.add_joint(
        JointDef::revolute(hook, door, vec2(0.0, 0.0)).limits(-0.785, 0.785).motor_drive(0.0, 0.5),
    )?;
    world.step(1.0 / 60.0)?;
    println!("{:?}", world.joint(hinge).unwrap().reaction_force());
    Ok(())
}

#[rustfmt::skip]
fn hello_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, SensorEvent, Shape, World, vec2};

    let mut world = World::new();
    let zone = world.add_body(BodyDef::static_body(Shape::rect(2.0, 0.5)).sensor(true))?;
    let zone = world.body(zone).unwrap().colliders()[0];
    world.add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(0.0, 3.0)))?;
    let mut entered = 0;
    for _ in 0..120 {
        world.step(1.0 / 60.0)?;
        for event in world.sensor_events() {
            if let SensorEvent::Begin(overlap) = event {
                assert_eq!(overlap.sensor, zone);
                entered += 1;
            }
        }
    }
    assert_eq!(entered, 1);
    Ok(())
}

#[rustfmt::skip]
fn sensor_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, CollisionFilter, Shape, World, WorldShape, vec2};

    let mut world = World::new();
    world.add_body(BodyDef::static_body(Shape::rect(0.5, 2.0)).position(vec2(5.0, 0.0)))?;
    let crate_box = WorldShape::at(&Shape::rect(0.5, 0.5), vec2(0.0, 0.0), 0.0);
    let hit = world
        .cast_shape(&crate_box, vec2(10.0, 0.0), CollisionFilter::DEFAULT)
        .expect("the wall is in the way");
    // The box's right side reaches the wall's left side, x = 4.5, after 4 m of the 10.
    assert!((hit.fraction - 0.4).abs() < 1e-3);
    assert_eq!(hit.normal, vec2(-1.0, 0.0));
    Ok(())
}

#[rustfmt::skip]
fn shape_cast_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, Shape, World, vec2};

    let mut world = World::new(); // gravity (0, -10) m/s²
    let ball = world.add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 10.0)))?;
    world.step(1.0 / 60.0)?;
    println!("{:?}", world.body(ball).unwrap().position());
    Ok(())
}

#[test]
fn the_readme_examples_run() {
    joint_example().unwrap();
    hello_example().unwrap();
    sensor_example().unwrap();
    shape_cast_example().unwrap();
}

/// Lines without their leading spaces, blank ones dropped.
fn trimmed(text: &str) -> Vec<&str> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect()
}

#[test]
fn every_rust_example_in_the_readme_is_one_of_these() {
    let readme = include_str!("../../../README.md");
    let here = trimmed(include_str!("readme.rs"));
    let mut examples = 0;
    for block in readme.split("```rust\n").skip(1) {
        let code = block.split("```").next().unwrap();
        let lines = trimmed(code);
        assert!(
            here.windows(lines.len()).any(|w| w == lines.as_slice()),
            "this README example is not in crates/carom/tests/readme.rs:\n{code}"
        );
        examples += 1;
    }
    assert_eq!(examples, 4, "a new README example: add it here");
}
