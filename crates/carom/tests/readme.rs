//! The code examples of the README and of `docs/features.md`, compiled and run as they are
//! written there. A test checks that every Rust example in those two pages appears here line
//! for line, so they cannot drift apart.

#[rustfmt::skip]
fn joint_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, JointDef, RevoluteJointDef, Shape, World, vec2};

    let mut world = World::new();
    let hook = world.add_body(BodyDef::static_body(Shape::rect(0.2, 0.2)))?;
    let door = world.add_body(BodyDef::dynamic(Shape::rect(1.0, 0.1)).position(vec2(1.0, 0.0)))?;
    // A hinge at the hook, swinging at most 45° either way, with a little friction.
    let def = JointDef::revolute(hook, door, vec2(0.0, 0.0)).limits(-0.785, 0.785).motor_drive(0.0, 0.5);
    // The same hinge from its own definition, whose setters are a hinge's alone.
    let hinge_def = RevoluteJointDef::new(hook, door, vec2(0.0, 0.0)).limits(-0.785, 0.785).motor(0.0, 0.5);
    assert_eq!(JointDef::from(hinge_def), def);
    let hinge = world.add_joint(hinge_def)?;
    world.step(1.0 / 60.0)?;
    println!("{:?}", world.joint(hinge).unwrap().reaction_force());
    Ok(())
}

#[rustfmt::skip]
fn sensor_example() -> Result<(), carom::CaromError> {
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
fn shape_cast_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, QueryFilter, Shape, World, WorldShape, vec2};

    let mut world = World::new();
    world.add_body(BodyDef::static_body(Shape::rect(0.5, 2.0)).position(vec2(5.0, 0.0)))?;
    let crate_box = WorldShape::at(&Shape::rect(0.5, 0.5), vec2(0.0, 0.0), 0.0);
    let hit = world
        .cast_shape(&crate_box, vec2(10.0, 0.0), QueryFilter::ALL)
        .expect("the wall is in the way");
    // The box's right side reaches the wall's left side, x = 4.5, after 4 m of the 10.
    assert!((hit.fraction - 0.4).abs() < 1e-3);
    assert_eq!(hit.normal, vec2(-1.0, 0.0));
    Ok(())
}

#[rustfmt::skip]
fn snapshot_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, Shape, World, vec2};

    let mut world = World::new();
    let ball = world.add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 4.0)))?;
    let start = world.snapshot();
    for _ in 0..30 {
        world.step(1.0 / 60.0)?;
    }
    let first = world.body(ball).unwrap().position();

    world.restore(&start); // back to step 0: the ball is at (0, 4) again
    for _ in 0..30 {
        world.step(1.0 / 60.0)?;
    }
    assert_eq!(world.body(ball).unwrap().position(), first);
    Ok(())
}

#[rustfmt::skip]
fn capacity_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, Real, Shape, World, vec2};

    // The level: a floor and a pile of crates.
    let level = || -> Result<World, carom::CaromError> {
        let mut world = World::new();
        world.add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)))?;
        for i in 0..200 {
            let at = vec2((i % 20) as Real - 10.0, 1.0 + (i / 20) as Real);
            world.add_body(BodyDef::dynamic(Shape::rect(0.4, 0.4)).position(at))?;
        }
        Ok(world)
    };
    // Once, offline or in a test: play the level and note the most it held.
    let mut rehearsal = level()?;
    for _ in 0..300 {
        rehearsal.step(1.0 / 60.0)?;
    }
    let most = rehearsal.high_water(); // bodies, colliders, contacts, joints

    // When the level loads: room for that much, so its steps take nothing from the heap.
    let mut world = level()?;
    world.reserve(most)?;
    for _ in 0..300 {
        world.step(1.0 / 60.0)?;
    }
    Ok(())
}

#[rustfmt::skip]
fn character_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, Character, CharacterDef, Shape, World, vec2};

    let mut world = World::new();
    world.add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))?;
    // A capsule 1.6 m tall standing on the floor: centres 0.5 m above and below its middle.
    let mut hero = Character::new(CharacterDef::capsule(0.5, 0.3).position(vec2(0.0, 0.8)))?;
    let dt = 1.0 / 60.0;
    let mut velocity = vec2(0.0, 0.0);
    for _ in 0..60 {
        velocity.x = 3.0; // walk
        velocity.y -= 10.0 * dt; // fall
        world.move_character(&mut hero, velocity * dt, dt)?;
        velocity = hero.clip_velocity(velocity); // landed: no more falling
        world.step(dt)?;
    }
    assert!(hero.is_grounded());
    assert!((hero.position().x - 3.0).abs() < 0.01);
    Ok(())
}

#[rustfmt::skip]
fn dynamic_character_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, JointDef, QueryFilter, Ray, Shape, World, vec2};

    let mut world = World::new();
    let ground = world.add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))?;
    let hero = world.add_body(
        BodyDef::dynamic(Shape::rect(0.3, 0.5)).position(vec2(0.0, 1.4)).friction(0.0).fixed_rotation(true),
    )?;
    let weight = world.body(hero).unwrap().mass() * 10.0;
    // Walk right at 2 m/s with at most 50 N along x; y is left to gravity and the leg.
    world.add_joint(JointDef::mover(ground, hero, vec2(2.0, 0.0), vec2(50.0, 0.0)))?;
    let mut leg = None;
    for _ in 0..60 {
        let foot = world.body(hero).unwrap().position() - vec2(0.0, 0.5);
        let previous = leg.take().map(|leg| world.remove_joint(leg)).transpose()?;
        let down = Ray::new(foot, vec2(0.0, -1.8));
        if let Some(hit) = world.cast_ray(&down, QueryFilter::ALL.excluding(hero)) {
            let mut def = JointDef::pogo(
                hit.body, hero, hit.point, foot, hit.normal, 0.9, (50.0 * weight, 50.0 * weight),
            );
            if let Some(previous) = &previous {
                def = def.continue_from(previous);
            }
            leg = Some(world.add_joint(def)?);
        }
        world.step(1.0 / 60.0)?;
    }
    let body = world.body(hero).unwrap();
    assert!((body.linear_velocity().x - 2.0).abs() < 0.01);
    assert!((body.position().y - 1.4).abs() < 0.02); // the foot 0.9 m up
    assert_eq!(body.angle(), 0.0);
    Ok(())
}

/// The README's example: a program of one's own crate, its `main` nested here.
#[rustfmt::skip]
fn own_crate_example() -> Result<(), carom::CaromError> {
    use carom::{BodyDef, CaromError, ContactEvent, Shape, World, vec2};

    fn main() -> Result<(), CaromError> {
        let mut world = World::new(); // gravity (0, -10) m/s², Box2D v3's soft step solver
        // Static ground 20 m wide with its top at y = 0, and a bouncy ball dropped from 3 m.
        world.add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))?;
        let ball = world.add_body(
            BodyDef::dynamic(Shape::circle(0.25)).position(vec2(0.0, 3.0)).restitution(0.5),
        )?;
        for step in 0..180 {
            world.step(1.0 / 60.0)?;
            for event in world.contact_events() {
                if let ContactEvent::Begin(_) = event {
                    println!("the ball lands at t = {:.2} s", (step + 1) as f32 / 60.0);
                }
            }
        }
        let ball = world.body(ball).expect("the ball is in the world");
        println!("after 3 s: y = {:.3} m, asleep: {}", ball.position().y, ball.is_sleeping());
        Ok(())
    }

    main()
}

#[test]
fn the_readme_examples_run() {
    own_crate_example().unwrap();
    joint_example().unwrap();
    sensor_example().unwrap();
    shape_cast_example().unwrap();
    character_example().unwrap();
    dynamic_character_example().unwrap();
    snapshot_example().unwrap();
    capacity_example().unwrap();
}

/// Lines without their leading spaces, blank ones dropped.
fn trimmed(text: &str) -> Vec<&str> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect()
}

/// How many Rust examples a page has, checking each is in this file line for line.
fn examples_in(page: &str, text: &str) -> usize {
    let here = trimmed(include_str!("readme.rs"));
    let mut examples = 0;
    for block in text.split("```rust\n").skip(1) {
        let code = block.split("```").next().unwrap();
        let lines = trimmed(code);
        assert!(
            here.windows(lines.len()).any(|w| w == lines.as_slice()),
            "this {page} example is not in crates/carom/tests/readme.rs:\n{code}"
        );
        examples += 1;
    }
    examples
}

#[test]
fn every_rust_example_in_the_readme_is_one_of_these() {
    let readme = include_str!("../../../README.md");
    assert_eq!(
        examples_in("README", readme),
        1,
        "a new README example: add it here"
    );
}

#[test]
fn every_rust_example_in_the_features_guide_is_one_of_these() {
    let guide = include_str!("../../../docs/features.md");
    assert_eq!(
        examples_in("docs/features.md", guide),
        7,
        "a new example in docs/features.md: add it here"
    );
}
