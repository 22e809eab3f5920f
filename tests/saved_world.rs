//! A saved world restores exactly: every scene in `demos/` steps on after a save and restore
//! to the very state it would have reached without one.

use carom::World;
use carom_scene::load;
use std::path::PathBuf;

fn demos() -> Vec<PathBuf> {
    carom_tests::demo_files()
}

fn save(world: &World) -> String {
    ron::ser::to_string(world).expect("a world serializes")
}

fn restore(text: &str) -> World {
    ron::from_str(text).unwrap_or_else(|e| panic!("a saved world reads back: {e}"))
}

#[test]
fn every_demo_restores_to_the_same_state() {
    let mut checked = 0;
    for file in demos() {
        let mut scene = load(&file).unwrap();
        if scene.world.body_count() > 1500 {
            continue;
        }
        checked += 1;
        let name = file.display();
        let dt = scene.time_step;
        for _ in 0..100 {
            scene.step().unwrap();
        }
        let mut world = scene.world;
        // The pre-solve hook is code and is not saved (a scene sets it again when it loads a
        // saved world); both worlds go on without it.
        world.clear_pre_solve();
        let saved = save(&world);
        for _ in 0..100 {
            world.step(dt).unwrap();
        }
        let mut restored = restore(&saved);
        for _ in 0..100 {
            restored.step(dt).unwrap();
        }
        assert_eq!(
            restored.state_hash(),
            world.state_hash(),
            "{name}: the restored world went elsewhere"
        );
        // Not only the bodies: contacts, impulses, islands and trees are the same too.
        assert!(
            save(&restored) == save(&world),
            "{name}: the restored state differs"
        );
    }
    println!("{checked} scenes restored exactly");
    assert!(
        checked >= 25,
        "only {checked} scenes were small enough to check"
    );
}

/// A running scene saved to a file and opened again goes on exactly as it would have: timed
/// events (launches, respawns, spinning frames) carry on where they were, and the one-way
/// platforms' pre-solve rule is set again.
#[test]
fn every_demo_saved_as_a_scene_opens_as_it_was() {
    let folder = std::env::temp_dir().join(format!("carom-saved-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    for file in demos() {
        let scene = carom_scene::read(&file).unwrap();
        let mut running = carom_scene::build(&scene, "scene").unwrap();
        if running.world.body_count() > 1500 {
            continue;
        }
        let name = file.display();
        for _ in 0..90 {
            running.step().unwrap();
        }
        let saved = folder.join(file.file_name().unwrap());
        carom_scene::write(&running.save(&scene), &saved).unwrap();
        let mut reopened = load(&saved).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(reopened.names, running.names, "{name}");
        assert_eq!(reopened.colors, running.colors, "{name}");
        for _ in 0..90 {
            running.step().unwrap();
            reopened.step().unwrap();
        }
        assert_eq!(
            reopened.world.state_hash(),
            running.world.state_hash(),
            "{name}: the reopened scene went elsewhere"
        );
    }
    std::fs::remove_dir_all(&folder).unwrap();
}

/// A small world with something of everything a save holds: stacked boxes in contact, a
/// chain of hinged links, a sensor, a sleeping body and a kinematic one, after a removal left
/// free slots behind.
fn small_world() -> World {
    use carom::{BodyDef, JointDef, Shape, vec2};
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let mut boxes = Vec::new();
    for i in 0..4 {
        let def = BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(-3.0, 0.5 + i as f32));
        boxes.push(world.add_body(def).unwrap());
    }
    world.remove_body(boxes[3]).unwrap();
    let mut previous = world
        .add_body(BodyDef::static_body(Shape::circle(0.1)).position(vec2(3.0, 5.0)))
        .unwrap();
    for i in 0..3 {
        let link = BodyDef::dynamic(Shape::capsule(vec2(0.0, 0.0), vec2(0.8, 0.0), 0.1))
            .position(vec2(3.0 + 0.8 * i as f32, 5.0));
        let link = world.add_body(link).unwrap();
        world
            .add_joint(JointDef::revolute(
                previous,
                link,
                vec2(3.0 + 0.8 * i as f32, 5.0),
            ))
            .unwrap();
        previous = link;
    }
    world
        .add_body(
            BodyDef::static_body(Shape::rect(1.0, 1.0))
                .position(vec2(0.0, 1.0))
                .sensor(true),
        )
        .unwrap();
    world
        .add_body(BodyDef::dynamic(Shape::circle(0.3)).position(vec2(0.0, 3.0)))
        .unwrap();
    world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.3))
                .position(vec2(6.0, 0.3))
                .awake(false),
        )
        .unwrap();
    world
        .add_body(
            BodyDef::kinematic(Shape::rect(0.5, 0.1))
                .position(vec2(-6.0, 2.0))
                .linear_velocity(vec2(0.5, 0.0)),
        )
        .unwrap();
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    world
}

/// A saved world edited by hand, one number at a time, reads back as an error or as a world
/// that steps without a panic or a NaN: what `World`'s reading checks.
#[test]
fn an_edited_save_is_refused_or_steps_cleanly() {
    let text = save(&small_world());
    // Where each number in the text starts and ends.
    let bytes = text.as_bytes();
    let mut numbers = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit() || bytes[i] == b'-';
        let after_word = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if starts && !after_word {
            let start = i;
            i += 1;
            while i < bytes.len()
                && matches!(bytes[i], b'0'..=b'9' | b'.' | b'e' | b'E' | b'-' | b'+')
            {
                i += 1;
            }
            numbers.push(start..i);
        } else {
            i += 1;
        }
    }
    assert!(numbers.len() > 500, "found only {} numbers", numbers.len());
    let replacements = [
        "0",
        "1",
        "2",
        "3",
        "7",
        "100",
        "4294967295",
        "-1",
        "0.5",
        "1e30",
        "-3.5",
    ];
    let mut rng = carom_bench::cases::Rng::new(0x2545_f491_4f6c_dd1d);
    let mut next = |below: usize| rng.below(below);
    let (mut refused, mut stepped) = (0, 0);
    let trials: usize = std::env::var("CAROM_SAVE_TRIALS")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or(1500);
    for trial in 0..trials {
        let at = numbers[next(numbers.len())].clone();
        let with = replacements[next(replacements.len())];
        let edited = format!("{}{}{}", &text[..at.start], with, &text[at.end..]);
        let Ok(mut world) = ron::from_str::<World>(&edited) else {
            refused += 1;
            continue;
        };
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            for _ in 0..20 {
                world.step(1.0 / 60.0)?;
            }
            Ok::<_, carom::CaromError>(
                world
                    .bodies()
                    .all(|b| b.position().iter().all(|x| x.is_finite())),
            )
        }));
        match outcome {
            // A value far out of any sane range (a speed of 1e30 m/s) that the public setters
            // would take as well may overflow; anything else must stay finite.
            Ok(Ok(finite)) => assert!(
                finite || with.len() > 3,
                "trial {trial}: `{}` → `{with}` stepped to a NaN; context: {}<<HERE>>{}",
                &text[at.clone()],
                &text[at.start.saturating_sub(300)..at.start],
                &text[at.start..(at.end + 40).min(text.len())]
            ),
            Ok(Err(_)) => {}
            Err(_) => panic!(
                "trial {trial}: `{}` → `{with}` at byte {} made the step panic; context: {}",
                &text[at.clone()],
                at.start,
                &text[at.start.saturating_sub(120)..(at.end + 40).min(text.len())]
            ),
        }
        stepped += 1;
    }
    println!("refused {refused}, stepped {stepped}");
    assert!(
        refused > 0 && stepped > 0,
        "refused {refused}, stepped {stepped}"
    );
}

#[test]
fn the_small_world_restores() {
    let world = small_world();
    let restored = restore(&save(&world));
    assert_eq!(restored.state_hash(), world.state_hash());
}

/// Jointed islands asleep and awake, a joint hanging from a kinematic body and one between two
/// static bodies: restored, the world keeps each joint in its set (reading checks it) and
/// steps on, through the sleeping islands' waking, bit for bit as the saved one.
#[test]
fn jointed_islands_asleep_and_awake_restore_exactly() {
    use carom::{BodyDef, JointDef, Shape, vec2};
    let mut world = World::new();
    let ground = world
        .add_body(BodyDef::static_body(Shape::rect(30.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let post = world
        .add_body(BodyDef::static_body(Shape::rect(0.2, 1.0)).position(vec2(-20.0, 1.0)))
        .unwrap();
    world
        .add_joint(JointDef::weld(ground, post, vec2(-20.0, 0.0)))
        .unwrap();
    let crane = world
        .add_body(BodyDef::kinematic(Shape::rect(0.5, 0.2)).position(vec2(20.0, 6.0)))
        .unwrap();
    let load = world
        .add_body(BodyDef::dynamic(Shape::rect(0.4, 0.4)).position(vec2(20.0, 4.0)))
        .unwrap();
    world
        .add_joint(JointDef::distance(
            crane,
            load,
            vec2(20.0, 5.8),
            vec2(20.0, 4.4),
        ))
        .unwrap();
    let mut firsts = Vec::new();
    for i in 0..6 {
        let x = -12.0 + 4.0 * i as f32;
        firsts.push(hinged_pair(&mut world, x));
    }
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert!(world.body(load).unwrap().is_sleeping());
    assert!(firsts.iter().all(|&a| world.body(a).unwrap().is_sleeping()));
    // Two pairs wake, in an order that shuffles the awake joints.
    for &a in [firsts[4], firsts[1]].iter() {
        world
            .body_mut(a)
            .unwrap()
            .apply_impulse_at_center(vec2(0.5, 3.0))
            .unwrap();
    }
    world.step(1.0 / 60.0).unwrap();
    let mut restored = restore(&save(&world));
    for step in 0..120 {
        if step == 30 {
            for w in [&mut world, &mut restored] {
                w.body_mut(firsts[2])
                    .unwrap()
                    .apply_impulse_at_center(vec2(-0.5, 3.0))
                    .unwrap();
            }
        }
        world.step(1.0 / 60.0).unwrap();
        restored.step(1.0 / 60.0).unwrap();
        assert_eq!(restored.state_hash(), world.state_hash(), "step {step}");
        assert_eq!(restored.stats().joints, world.stats().joints, "step {step}");
    }
}

/// A save whose joints are moved to another set (the awake pair's joint filed as asleep) is
/// refused as it is read.
#[test]
fn a_save_with_a_joint_in_the_wrong_set_is_refused() {
    use carom::{BodyDef, Shape, vec2};
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(30.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    let mut pairs = Vec::new();
    for x in [-5.0, 5.0] {
        pairs.push(hinged_pair(&mut world, x));
    }
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    world
        .body_mut(pairs[1])
        .unwrap()
        .apply_impulse_at_center(vec2(0.0, 1.0))
        .unwrap();
    let text = save(&world);
    restore(&text);
    // One joint awake, none static, one asleep.
    let sets = "sets:([1,1])";
    assert_eq!(text.matches(sets).count(), 1, "the joints' sets in {text}");
    let edited = text.replace(sets, "sets:([0,0])");
    let error = ron::from_str::<World>(&edited).expect_err("a joint in the wrong set");
    assert!(error.to_string().contains("wrong set"), "{error}");
}

/// Two unit boxes resting side by side on the ground from `x`, hinged where they meet;
/// returns the first.
fn hinged_pair(world: &mut World, x: f32) -> carom::BodyHandle {
    use carom::{BodyDef, JointDef, Shape, vec2};
    let a = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, 0.5)))
        .unwrap();
    let b = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x + 1.0, 0.5)))
        .unwrap();
    world
        .add_joint(JointDef::revolute(a, b, vec2(x + 0.5, 0.5)))
        .unwrap();
    a
}

/// A world saved by another version of carom is refused for that, naming both save formats,
/// before a field that version laid out differently can fail to read.
#[test]
fn a_world_saved_in_another_format_is_refused_naming_both() {
    let text = save(&small_world());
    let start = text.find("format:").expect("the save names its format") + "format:".len();
    let digits = text[start..]
        .find(|c: char| !c.is_ascii_digit())
        .expect("a number");
    let ours: u32 = text[start..start + digits].parse().unwrap();
    // The other version's file: another format number and a field this version lacks.
    for other in [ours - 1, ours + 1] {
        let edited = format!(
            "{}{other},made_by_another_version:(),{}",
            &text[..start],
            &text[start + digits + 1..]
        );
        let error = ron::from_str::<World>(&edited)
            .expect_err("a world in another format is refused")
            .to_string();
        for named in [
            format!("save format {other}"),
            format!("save format {ours}"),
        ] {
            assert!(error.contains(&named), "`{error}` does not name {named}");
        }
    }
    // The same file in this version's format fails on the unknown field instead.
    let edited = format!(
        "{}{ours},made_by_another_version:(),{}",
        &text[..start],
        &text[start + digits + 1..]
    );
    let error = ron::from_str::<World>(&edited).unwrap_err().to_string();
    assert!(error.contains("made_by_another_version"), "{error}");
}

/// A saved body's damping or sleep threshold that is negative, which no setter takes, is
/// refused as the world is read: negative damping speeds a body up every step, to NaN.
#[test]
fn a_save_with_negative_damping_is_refused() {
    let text = save(&small_world());
    for field in ["linear_damping:", "angular_damping:", "sleep_threshold:"] {
        let at = text.find(field).expect(field) + field.len();
        let end = at + text[at..].find([',', ')']).expect("a number, then more");
        let edited = format!("{}-60.0{}", &text[..at], &text[end..]);
        let error = ron::from_str::<World>(&edited)
            .expect_err(field)
            .to_string();
        assert!(error.contains("negative"), "{field} {error}");
    }
}
