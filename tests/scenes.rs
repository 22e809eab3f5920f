//! Scene files: bad input says where and why; good input builds the world it describes.

use carom_scene::{SceneError, load};
use std::path::PathBuf;

fn path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(name)
}

/// The first RON code block after `heading` in `text`.
fn ron_block<'a>(text: &'a str, heading: &str) -> &'a str {
    let after = &text[text.find(heading).expect("the heading")..];
    let start = after
        .find("```ron\n")
        .expect("a RON block after the heading")
        + 7;
    let end = start + after[start..].find("```").expect("the block's end");
    &after[start..end]
}

/// Loads a bad file and returns its error message, which must start with the file's path.
fn error_of(name: &str) -> (SceneError, String) {
    let file = path(name);
    let error = load(&file).expect_err("a bad scene must not load");
    let message = error.to_string();
    assert!(
        message.starts_with(&file.display().to_string()),
        "{message}"
    );
    (error, message)
}

#[test]
fn malformed_ron_names_file_line_and_column() {
    let (error, message) = error_of("scenes/bad_syntax.ron");
    let SceneError::Syntax { line, column, .. } = error else {
        panic!("expected a syntax error, got {message}");
    };
    assert_eq!(line, 3, "{message}");
    assert!(column >= 5, "{message}");
    assert!(message.contains(":3:"), "{message}");
}

/// A scene written for another version of the format is refused for that, with both versions
/// and the place named, before a field that version added can fail to read; a scene that does
/// not say its version is read as this one's.
#[test]
fn a_scene_in_another_format_is_refused_naming_both_versions() {
    let ours = carom_scene::SCENE_FORMAT;
    for other in [ours + 1, ours.wrapping_sub(1)] {
        let text =
            format!("(\n    format: {other},\n    name: \"later\",\n    gravity_well: 3.0,\n)");
        let error = carom_scene::parse(&text, "later.ron").expect_err("another format is refused");
        let message = error.to_string();
        assert!(
            matches!(error, SceneError::Syntax { line: 2, .. }),
            "{message}"
        );
        for named in [
            format!("scene format {other}"),
            format!("scene format {ours}"),
        ] {
            assert!(
                message.contains(&named),
                "`{message}` does not name {named}"
            );
        }
    }
    let unsaid = carom_scene::parse("(name: \"no version\")", "inline.ron").unwrap();
    assert_eq!(unsaid.format, ours);
    // What this crate writes says its version first, and reads back.
    let text = carom_scene::to_text(&unsaid, "inline.ron").unwrap();
    assert!(
        text.trim_start_matches('(')
            .trim_start()
            .starts_with(&format!("format: {ours},")),
        "{text}"
    );
    carom_scene::parse(&text, "inline.ron").unwrap_or_else(|e| panic!("{e}\n{text}"));
}

#[test]
fn an_unknown_effect_is_named_with_its_place() {
    let (error, message) = error_of("scenes/bad_effect.ron");
    assert!(
        matches!(error, SceneError::Syntax { line: 3, .. }),
        "{message}"
    );
    assert!(message.contains("magnetism"), "{message}");
}

#[test]
fn semantic_errors_name_the_body_or_event_and_the_reason() {
    for (file, what, reason) in [
        ("scenes/bad_polygon.ron", "body 0 (\"arrow\")", "not convex"),
        (
            "scenes/bad_density.ron",
            "body 1",
            "density must be positive",
        ),
        ("scenes/bad_nan.ron", "body 0 (\"lost\")", "finite"),
        (
            "scenes/bad_no_shape.ron",
            "body 0 (\"ghost\")",
            "needs at least one collider",
        ),
        (
            "scenes/bad_event.ron",
            "event 0",
            "no body is named \"bal\"",
        ),
        (
            "scenes/bad_spin.ron",
            "event 0",
            "\"crate\" must be kinematic to spin",
        ),
        (
            "scenes/bad_accuracy.ron",
            "accuracy",
            "no body is named \"crate\"",
        ),
        (
            "scenes/bad_accuracy_joint.ron",
            "accuracy",
            "\"crate\" has no joint to measure",
        ),
        (
            "scenes/bad_accuracy_hinges.ron",
            "accuracy",
            "no hinges (revolute joints) to measure",
        ),
        (
            "scenes/bad_accuracy_gaps.ron",
            "accuracy",
            "no joints to measure",
        ),
        (
            "scenes/bad_joint_body.ron",
            "joint 1 (\"hook\" to \"lamb\")",
            "no body is named \"lamb\"",
        ),
        (
            "scenes/bad_joint_self.ron",
            "joint 0",
            "needs two different bodies",
        ),
        (
            "scenes/bad_joint_setting.ron",
            "joint 0",
            "motor max force must be not negative, got -3",
        ),
        (
            "scenes/bad_joint_nan.ron",
            "joint 0",
            "spring hertz must be finite",
        ),
        (
            "scenes/bad_time_step.ron",
            "time_step",
            "from 1e-6 s to 10 s, got 3600",
        ),
        (
            "scenes/bad_sensor_one_way.ron",
            "body 1 (\"trap\")",
            "a sensor never collides, so it cannot be one_way",
        ),
    ] {
        let (error, message) = error_of(file);
        assert!(matches!(error, SceneError::Invalid { .. }), "{message}");
        assert!(message.contains(what), "{message} should name {what}");
        assert!(message.contains(reason), "{message} should say {reason}");
    }
}

#[test]
fn a_missing_file_is_an_error_not_a_panic() {
    let (error, _) = error_of("scenes/no_such_scene.ron");
    assert!(matches!(error, SceneError::Io { .. }));
}

#[test]
fn the_documented_example_is_a_valid_scene() {
    // The commented example in demos/README.md must parse and build as documented.
    let readme = std::fs::read_to_string(path("../demos/README.md")).unwrap();
    let scene = carom_scene::parse(ron_block(&readme, "## Every field"), "demos/README.md")
        .unwrap_or_else(|e| panic!("{e}"));
    let mut built = carom_scene::build(&scene, "demos/README.md").unwrap_or_else(|e| panic!("{e}"));
    // 21 bodies, a stack of 10, a pyramid of 15, grids of 8 and 5 and one compound, a joint
    // grid of 3 x 2, 4 walls, 20 drops, 2 stacks of 3, a chain of 6 links, 2 groups of 2.
    assert_eq!(
        built.world.body_count(),
        21 + 10 + 15 + 8 + 5 + 1 + 6 + 4 + 20 + 6 + 6 + 4
    );
    // Every kind of shape is there; the chain of 3 points is 2 links.
    let mut shapes: Vec<&str> = built
        .world
        .colliders()
        .map(|c| match c.shape() {
            carom::Shape::Circle(_) => "circle",
            carom::Shape::Capsule(_) => "capsule",
            carom::Shape::Polygon(p) if p.radius() > 0.0 => "rounded polygon",
            carom::Shape::Polygon(_) => "polygon",
            carom::Shape::Segment(_) => "segment",
            carom::Shape::ChainSegment(_) => "chain segment",
        })
        .collect();
    assert_eq!(shapes.iter().filter(|&&s| s == "chain segment").count(), 2);
    shapes.sort_unstable();
    shapes.dedup();
    assert_eq!(
        shapes,
        [
            "capsule",
            "chain segment",
            "circle",
            "polygon",
            "rounded polygon",
            "segment"
        ]
    );
    // The shelf is a one-way platform (its contacts go to the pre-solve hook), the zone a
    // sensor, the ball neither.
    let collider = |name: &str| {
        let body = built.world.body(built.names[name]).unwrap();
        built.world.collider(body.colliders()[0]).unwrap()
    };
    assert!(collider("shelf").pre_solve() && !collider("shelf").is_sensor());
    assert!(collider("zone").is_sensor() && !collider("zone").pre_solve());
    assert!(!collider("ball").is_sensor() && !collider("ball").pre_solve());
    // 10 joints, one of each kind; the joint grid's 3 down its columns and 4 across its rows;
    // the chain's 6; one in each group.
    assert_eq!(built.world.joint_count(), 10 + 3 + 4 + 6 + 2);
    let mut kinds: Vec<&str> = built.world.joints().map(|j| j.kind().name()).collect();
    kinds.sort_unstable();
    kinds.dedup();
    assert_eq!(
        kinds,
        [
            "distance",
            "filter",
            "motor",
            "mouse",
            "mover",
            "pogo",
            "prismatic",
            "revolute",
            "weld",
            "wheel"
        ]
    );
    // The hammer is one body of three colliders, its head heavier than its handle.
    let hammer = built.world.body(built.names["hammer"]).unwrap();
    assert_eq!(hammer.colliders().len(), 3);
    assert!(hammer.local_center().x > 0.4, "{:?}", hammer.local_center());
    let ball = built.names["ball"];
    for _ in 0..16 {
        built.step().unwrap();
    }
    // The launch at 0.25 s threw the ball up while it fell in the open (gravity and drag
    // aside).
    let velocity = built.world.body(ball).unwrap().linear_velocity();
    assert!(velocity.y > 6.0, "after the launch: {velocity:?}");
    // The spawn event makes its first pair of circles at 1 s.
    let before = built.world.body_count();
    for _ in 16..61 {
        built.step().unwrap();
    }
    assert_eq!(built.world.body_count(), before + 2);
}

#[test]
fn a_spun_frame_turns_rigidly_about_its_pivot() {
    // Two kinematic arms on either side of a pivot, turned at 1 rad/s for 20 s: each ends
    // exactly where the analytic rotation puts it, however many steps it took.
    let text = r#"(
        name: "spin",
        world: (effects: []),
        bodies: [
            (name: Some("east"), kind: kinematic, shape: Box(width: 1.0, height: 0.2), position: (3.0, 1.0)),
            (name: Some("west"), kind: kinematic, shape: Box(width: 1.0, height: 0.2), position: (-1.0, 1.0)),
        ],
        events: [Spin(bodies: ["east", "west"], pivot: (1.0, 1.0), angular_velocity: 1.0)],
    )"#;
    let scene = carom_scene::parse(text, "spin.ron").unwrap();
    let mut built = carom_scene::build(&scene, "spin.ron").unwrap();
    for _ in 0..1200 {
        built.step().unwrap();
    }
    let turn = built.world.time() as f32;
    for (name, offset) in [("east", 2.0f32), ("west", -2.0)] {
        let body = built.world.body(built.names[name]).unwrap();
        let expected = carom::vec2(1.0 + offset * turn.cos(), 1.0 + offset * turn.sin());
        assert!(
            (body.position() - expected).norm() < 1e-3,
            "{name} at {:?}, expected {expected:?}",
            body.position()
        );
        let angle_error = (body.rotation() * carom::Rot::new(turn).inverse()).angle();
        assert!(
            angle_error.abs() < 1e-3,
            "{name} turned {angle_error} rad off"
        );
        assert!((body.angular_velocity() - 1.0).abs() < 1e-3);
    }
}

#[test]
fn a_shuttled_platform_goes_out_and_back_and_carries_its_load() {
    // A kinematic platform sent 4 m right and back every 4 s, a box resting on it: at 2 s
    // the platform is 4 m out, at 4 s home again, and the box went with it.
    let text = r#"(
        name: "shuttle",
        bodies: [
            (name: Some("platform"), kind: kinematic, shape: Box(width: 3.0, height: 0.2), position: (0.0, 0.0)),
            (name: Some("load"), shape: Box(width: 0.5, height: 0.5), position: (0.0, 0.35)),
        ],
        events: [Shuttle(bodies: ["platform"], offset: (4.0, 0.0), period: 4.0)],
    )"#;
    let scene = carom_scene::parse(text, "shuttle.ron").unwrap();
    let mut built = carom_scene::build(&scene, "shuttle.ron").unwrap();
    let x = |built: &carom_scene::SceneWorld, name: &str| {
        built.world.body(built.names[name]).unwrap().position().x
    };
    for _ in 0..120 {
        built.step().unwrap();
    }
    assert!(
        (x(&built, "platform") - 4.0).abs() < 1e-4,
        "{}",
        x(&built, "platform")
    );
    assert!(
        (x(&built, "load") - 4.0).abs() < 0.05,
        "the load is at {}",
        x(&built, "load")
    );
    for _ in 0..120 {
        built.step().unwrap();
    }
    assert!(
        x(&built, "platform").abs() < 1e-4,
        "{}",
        x(&built, "platform")
    );
    assert!(
        x(&built, "load").abs() < 0.05,
        "the load is at {}",
        x(&built, "load")
    );
    // Only a kinematic body shuttles.
    let text = text.replace("kind: kinematic, ", "");
    let scene = carom_scene::parse(&text, "shuttle.ron").unwrap();
    let error = carom_scene::build(&scene, "shuttle.ron")
        .unwrap_err()
        .to_string();
    assert!(error.contains("must be kinematic to shuttle"), "{error}");
}

#[test]
fn a_player_walks_jumps_onto_a_ledge_and_saves_as_it_is() {
    // A floor, a ledge 1 m up from x = 4, the goal at x = 7. Walk right, jump at 0.5 s.
    let text = r#"(
        name: "player",
        bodies: [
            (kind: static, shape: Box(width: 20.0, height: 1.0), position: (0.0, -0.5)),
            (kind: static, shape: Box(width: 6.0, height: 1.0), position: (7.0, 0.5)),
        ],
        player: (position: (0.0, 0.8), goal: Some(7.0)),
    )"#;
    let scene = carom_scene::parse(text, "player.ron").unwrap();
    let mut built = carom_scene::build(&scene, "player.ron").unwrap();
    let mut saved = None;
    for step in 0..120 {
        let player = built.player.as_mut().unwrap();
        player.input = carom_scene::PlayerInput {
            right: true,
            jump: step == 30,
            ..Default::default()
        };
        built.step().unwrap();
        if step == 60 {
            saved = Some(built.save(&scene));
        }
    }
    let player = built.player.as_ref().unwrap();
    let at = player.character().position();
    // 2 s at 4 m/s, standing on the ledge.
    assert!((at.x - 8.0).abs() < 0.05, "at {at}");
    assert!((at.y - 1.8).abs() < 0.01, "at {at}");
    assert!(player.character().is_grounded() && player.finished());
    // Opened again at step 60, the rest of the run ends in the same place, to the bit.
    let saved = saved.unwrap();
    let text = carom_scene::to_text(&saved, "saved.ron").unwrap();
    let again = carom_scene::parse(&text, "saved.ron").unwrap();
    let mut reopened = carom_scene::build(&again, "saved.ron").unwrap();
    for _ in 61..120 {
        reopened.player.as_mut().unwrap().input.right = true;
        reopened.step().unwrap();
    }
    let there = reopened.player.as_ref().unwrap().character().position();
    assert_eq!(there, at);
    assert_eq!(reopened.world.state_hash(), built.world.state_hash());
    // A bad player is refused, naming it.
    let bad = text_with_player("(position: (0.0, 0.8), radius: -1.0)");
    let error = carom_scene::build(&bad, "bad.ron").unwrap_err().to_string();
    assert!(error.contains("player"), "{error}");
}

#[test]
fn holding_jump_jumps_once_and_each_press_again() {
    let text = r#"(
        name: "hop",
        bodies: [(kind: static, shape: Box(width: 20.0, height: 1.0), position: (0.0, -0.5))],
        player: (position: (0.0, 0.8)),
    )"#;
    let scene = carom_scene::parse(text, "hop.ron").unwrap();
    let mut built = carom_scene::build(&scene, "hop.ron").unwrap();
    // Counts take-offs over `steps` steps with the jump key as `held` says.
    let jumps =
        |built: &mut carom_scene::SceneWorld, steps: usize, held: &dyn Fn(usize) -> bool| {
            let mut count = 0;
            for step in 0..steps {
                let player = built.player.as_mut().unwrap();
                let grounded = player.character().is_grounded();
                player.input.jump = held(step);
                built.step().unwrap();
                let rising = built.player.as_ref().unwrap().velocity().y > 1.0;
                count += usize::from(grounded && rising);
            }
            count
        };
    // Settle, then hold the key four seconds: one jump (about 1.4 s in the air).
    assert_eq!(jumps(&mut built, 30, &|_| false), 0);
    assert_eq!(jumps(&mut built, 240, &|_| true), 1);
    // Let go a second, pressed a second, twice: a jump each press.
    assert_eq!(jumps(&mut built, 240, &|step| step % 120 >= 60), 2);
}

fn text_with_player(player: &str) -> carom_scene::Scene {
    let text = format!("(name: \"bad\", player: {player})");
    carom_scene::parse(&text, "bad.ron").unwrap()
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: 300,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5ce4e),
        failure_persistence: None,
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// The in-CI cousin of the `scene_file` fuzz target: a shipped scene with a few bytes
    /// deleted, replaced or inserted parses to a scene or to an error that names a line and
    /// column inside the text, and a scene that parses builds or fails cleanly, and steps with
    /// its bodies finite: never a panic.
    #[test]
    fn mangled_scenes_fail_cleanly(
        scene in 0usize..64,
        edits in proptest::collection::vec((0usize..100_000, 0u8..3, 32u8..127), 1..6),
    ) {
        let mut names: Vec<PathBuf> = std::fs::read_dir(path("../demos"))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "ron"))
            .collect();
        names.sort();
        let original = std::fs::read_to_string(&names[scene % names.len()]).unwrap();
        let mut bytes = original.into_bytes();
        for (at, kind, byte) in edits {
            let at = at % (bytes.len() + 1);
            match kind {
                0 if at < bytes.len() => {
                    bytes.remove(at);
                }
                1 if at < bytes.len() => bytes[at] = byte,
                _ => bytes.insert(at, byte),
            }
        }
        let text = String::from_utf8_lossy(&bytes).into_owned();
        match carom_scene::parse(&text, "mangled.ron") {
            Ok(_) => {
                carom_tests::untrusted_files::scene_file(&text);
            }
            Err(SceneError::Syntax { line, column, .. }) => {
                let lines = text.lines().count().max(1);
                proptest::prop_assert!(line >= 1 && line <= lines + 1, "line {line} of {lines}");
                proptest::prop_assert!(column >= 1);
            }
            Err(_) => {}
        }
    }
}

#[test]
fn definitions_and_settings_survive_a_round_trip_through_ron() {
    use carom::{BodyDef, ColliderDef, Effect, Effects, Shape, SolverKind, SolverParams, vec2};
    let body = BodyDef::dynamic(Shape::rect(1.0, 0.25))
        .position(vec2(1.0, 2.0))
        .angle(0.5)
        .collider(
            ColliderDef::new(
                Shape::polygon(&[vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0)]).unwrap(),
            )
            .offset(vec2(-0.75, 1.0))
            .friction(0.2),
        )
        .collider(ColliderDef::new(Shape::circle(0.3)).density(4.0))
        .restitution(0.25);
    let text = ron::to_string(&body).unwrap();
    let back: BodyDef = ron::from_str(&text).unwrap();
    // The material set on the body comes back, for colliders added later.
    assert_eq!(back.every_collider, body.every_collider);
    assert_eq!(back.every_collider.restitution, Some(0.25));
    // Everything comes back; a polygon is centred on its centroid again, to rounding.
    assert_eq!(ron::to_string(&back).unwrap(), text);
    assert_eq!(back.colliders.len(), 3);
    for (read, written) in back.colliders.iter().zip(&body.colliders) {
        let (Shape::Polygon(a), Shape::Polygon(b)) = (&read.shape, &written.shape) else {
            assert_eq!(read, written);
            continue;
        };
        for (p, q) in a.vertices().iter().zip(b.vertices()) {
            assert!((p - q).norm() < 1e-6, "{p:?} vs {q:?}");
        }
        assert_eq!(
            (read.offset, read.friction),
            (written.offset, written.friction)
        );
    }
    assert_eq!((back.position, back.angle), (body.position, body.angle));
    let settings = carom::WorldSettings {
        solver: SolverParams::for_kind(SolverKind::SequentialImpulse),
        effects: Effects::ALL.switched(Effect::Sleeping, false),
        ..carom::WorldSettings::default()
    };
    let text = ron::to_string(&settings).unwrap();
    let back: carom::WorldSettings = ron::from_str(&text).unwrap();
    assert_eq!(back, settings, "{text}");
    // Written by hand, with defaults left out; a bad shape is refused when read.
    let minimal: BodyDef =
        ron::from_str("(kind: kinematic, colliders: [(shape: circle(radius: 0.5))])").unwrap();
    assert_eq!(minimal, BodyDef::kinematic(Shape::circle(0.5)));
    let bad =
        ron::from_str::<BodyDef>("(kind: dynamic, colliders: [(shape: circle(radius: -1.0))])");
    assert!(bad.unwrap_err().to_string().contains("radius"));
}

#[test]
fn the_front_page_scene_rolls_its_ball_into_the_boxes() {
    // The first scene demos/README.md offers to start from must load and do what it says.
    let readme = std::fs::read_to_string(path("../demos/README.md")).unwrap();
    let scene = carom_scene::parse(ron_block(&readme, "## A first scene"), "demos/README.md")
        .unwrap_or_else(|e| panic!("{e}"));
    let mut built = carom_scene::build(&scene, "demos/README.md").unwrap_or_else(|e| panic!("{e}"));
    let ball = built.names["ball"];
    let boxes: Vec<_> = built
        .world
        .bodies()
        .filter(|b| b.is_dynamic() && b.handle() != ball)
        .map(|b| (b.handle(), b.position()))
        .collect();
    assert_eq!(boxes.len(), 6, "a column of six boxes");
    for _ in 0..600 {
        built.step().unwrap();
    }
    let moved = boxes
        .iter()
        .filter(|(h, start)| (built.world.body(*h).unwrap().position() - start).norm() > 0.05)
        .count();
    assert!(moved > 0, "the ball reached the column and moved a box");
}

#[test]
fn a_scene_file_sets_every_world_setting() {
    // Every field of the world's and the solver's settings, each away from its default,
    // written out and read back: the built world has exactly these settings.
    use carom::{DragModel, Effect, Effects, SolverKind, SolverParams, WorldSettings, vec2};
    let defaults = WorldSettings::default();
    let wanted = WorldSettings {
        gravity: vec2(1.0, -3.0),
        drag: DragModel::Tutorial,
        speculative_distance: 0.03,
        aabb_margin: 0.07,
        solver: SolverParams {
            kind: SolverKind::SequentialImpulse,
            impulse_resolution: false,
            iterations: Some(12),
            substeps: 6,
            warm_starting: false,
            graph_coloring: false,
            friction_in_bias_pass: false,
            contact_hertz: 45.0,
            damping_ratio: 5.0,
            static_stiffness: 3.0,
            joint_hertz: 90.0,
            joint_damping_ratio: 1.5,
            direct_joints: true,
            shock_propagation: true,
            max_push_speed: 2.0,
            baumgarte: 0.3,
            restitution_threshold: 0.5,
            max_linear_speed: 300.0,
            max_rotation: 0.5,
        },
        effects: Effects::of(&[Effect::Gravity, Effect::Drag]),
        look_ahead: false,
        contact_recycling: false,
        hit_event_threshold: 2.0,
    };
    // A field added later but not set here would keep its default and fail below.
    let differs = format!("{wanted:?}");
    for (field, default) in format!("{defaults:?}")
        .split([',', '{', '}'])
        .zip(differs.split([',', '{', '}']))
    {
        let value = field.contains(':') && !field.contains("SolverParams");
        assert!(!value || field != default, "{field} keeps its default");
    }
    let mut scene = carom_scene::parse("(name: \"every setting\")", "inline").unwrap();
    scene.world = wanted;
    let text = carom_scene::to_text(&scene, "inline").unwrap();
    let read = carom_scene::parse(&text, "inline").unwrap_or_else(|e| panic!("{e}\n{text}"));
    let built = carom_scene::build(&read, "inline").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(*built.world.settings(), wanted, "{text}");
    // A solver named alone takes its own iteration count.
    let classic = carom_scene::parse(
        "(name: \"classic\", world: (solver: (kind: sequential_impulse)))",
        "inline",
    )
    .unwrap();
    assert_eq!(classic.world.solver.effective_iterations(), 8);
    let unknown = carom_scene::parse("(name: \"typo\", world: (solver: (substep: 8)))", "inline");
    assert!(unknown.unwrap_err().to_string().contains("substep"));
}

/// Builds an inline scene, panicking with its error.
fn inline(text: &str) -> carom_scene::SceneWorld {
    let scene = carom_scene::parse(text, "inline.ron").unwrap_or_else(|e| panic!("{e}"));
    carom_scene::build(&scene, "inline.ron").unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_rounded_segment_is_a_capsule_where_its_ends_are_given() {
    // Box2D's ragdoll hip: a capsule between (0, -0.02) and (0, 0.02), radius 0.095, on a body
    // at (0, 0.95). The ends stay exactly where they are written; the bare segment has none.
    let built = inline(
        r#"(name: "capsule", bodies: [
            (name: "hip", shape: Segment(from: (0.0, -0.02), to: (0.0, 0.02), radius: 0.095),
             position: (0.0, 0.95), sleep_threshold: 0.1),
            (name: "floor", kind: static, shape: Segment(from: (-1.0, 0.0), to: (1.0, 0.0))),
        ])"#,
    );
    let world = &built.world;
    let hip = world.body(built.names["hip"]).unwrap();
    let carom::Shape::Capsule(c) = world.collider(hip.colliders()[0]).unwrap().shape() else {
        panic!("a rounded segment should be a capsule");
    };
    assert_eq!(
        (c.center1(), c.center2(), c.radius()),
        (carom::vec2(0.0, -0.02), carom::vec2(0.0, 0.02), 0.095)
    );
    assert!(hip.mass() > 0.0);
    assert_eq!(hip.sleep_threshold(), 0.1);
    let floor = world.body(built.names["floor"]).unwrap();
    let floor_shape = world.collider(floor.colliders()[0]).unwrap().shape();
    assert!(matches!(floor_shape, carom::Shape::Segment(_)));
    assert_eq!(floor.sleep_threshold(), carom::SLEEP_THRESHOLD);
}

#[test]
fn a_grid_takes_its_shapes_in_turn_stops_at_its_count_and_may_be_one_body() {
    // Seven cells of a 3 x 3 grid, row by row, cycling a circle, a box and a capsule.
    let built = inline(
        r#"(name: "grid", generators: [
            Grid(origin: (0.0, 1.0), columns: 3, rows: 3, spacing: (2.0, 1.0), count: 7,
                 shapes: [Circle(radius: 0.2), Box(width: 0.4, height: 0.4),
                          Capsule(length: 0.2, radius: 0.1)]),
            Grid(origin: (-10.0, 0.0), columns: 4, rows: 2, spacing: (0.5, 45.0), kind: static,
                 shape: Box(width: 0.5, height: 0.5), compound: true,
                 material: (friction: 0.3)),
        ])"#,
    );
    let world = &built.world;
    assert_eq!(world.body_count(), 7 + 1);
    let kinds: Vec<(&str, (f32, f32))> = world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| {
            let kind = match world.collider(b.colliders()[0]).unwrap().shape() {
                carom::Shape::Circle(_) => "circle",
                carom::Shape::Polygon(_) => "box",
                carom::Shape::Capsule(_) => "capsule",
                other => panic!("{other:?}"),
            };
            (kind, (b.position().x, b.position().y))
        })
        .collect();
    assert_eq!(
        kinds,
        [
            ("circle", (0.0, 1.0)),
            ("box", (2.0, 1.0)),
            ("capsule", (4.0, 1.0)),
            ("circle", (0.0, 2.0)),
            ("box", (2.0, 2.0)),
            ("capsule", (4.0, 2.0)),
            ("circle", (0.0, 3.0)),
        ]
    );
    // The compound: one static body at the origin, its 8 boxes where the cells are, each
    // with the grid's material.
    let ground = world.bodies().find(|b| !b.is_dynamic()).unwrap();
    assert_eq!(ground.position(), carom::Vec2::zeros());
    let offsets: Vec<(f32, f32)> = ground
        .colliders()
        .iter()
        .map(|&c| {
            let collider = world.collider(c).unwrap();
            assert_eq!(collider.friction(), 0.3);
            let t = collider.local_transform().translation;
            (t.x, t.y)
        })
        .collect();
    assert_eq!(
        offsets,
        [
            (-10.0, 0.0),
            (-9.5, 0.0),
            (-9.0, 0.0),
            (-8.5, 0.0),
            (-10.0, 45.0),
            (-9.5, 45.0),
            (-9.0, 45.0),
            (-8.5, 45.0)
        ]
    );
    // A grid needs exactly one of `shape` and `shapes`, and no more cells than it has.
    for (grid, reason) in [
        (
            "origin: (0.0, 0.0), columns: 2, rows: 2, spacing: (1.0, 1.0)",
            "needs a `shape`",
        ),
        (
            "origin: (0.0, 0.0), columns: 2, rows: 2, spacing: (1.0, 1.0), \
             shape: Circle(radius: 0.1), shapes: [Circle(radius: 0.1)]",
            "not both",
        ),
        (
            "origin: (0.0, 0.0), columns: 2, rows: 2, spacing: (1.0, 1.0), count: 5, \
             shape: Circle(radius: 0.1)",
            "more than the 2 x 2 cells",
        ),
    ] {
        let text = format!("(name: \"bad\", generators: [Grid({grid})])");
        let scene = carom_scene::parse(&text, "bad.ron").unwrap();
        let error = carom_scene::build(&scene, "bad.ron")
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("generator 0 (grid)") && error.contains(reason),
            "{error}"
        );
    }
}

/// A floor, and a spawn event remaking a jointed pair of balls at the six places of a 3 x 2
/// grid: turn `n` at 0.05 + 0.1 n s, at 60 Hz before steps 3, 9, 15, 21, ...
const SPAWNING: &str = r#"(name: "spawning",
    bodies: [(name: "floor", kind: static, shape: Box(width: 40.0, height: 1.0),
              position: (0.0, -0.5))],
    events: [Spawn(at: 0.05, every: 0.1, origin: (-5.0, 3.0), columns: 3, rows: 2,
                   spacing: (5.0, 2.0),
                   of: Group(self_collide: false,
                       bodies: [(name: "a", shape: Circle(radius: 0.2),
                                 material: (color: (1.0, 0.0, 0.0))),
                                (name: "b", shape: Circle(radius: 0.2), position: (0.5, 0.0))],
                       joints: [(bodies: ("a", "b"), anchor: (0.25, 0.0), kind: Revolute())]))],
)"#;

#[test]
fn a_spawn_event_makes_and_remakes_its_copies_in_turn() {
    let mut built = inline(SPAWNING);
    let run = |built: &mut carom_scene::SceneWorld, steps: u64| {
        while built.world.step_count() < steps {
            built.step().unwrap();
        }
    };
    run(&mut built, 3);
    assert_eq!(built.world.body_count(), 1, "nothing before step 3");
    run(&mut built, 4);
    // Column 0: a pair at each row, each where the place puts it, joined, coloured.
    assert_eq!(
        (built.world.body_count(), built.world.joint_count()),
        (5, 2)
    );
    let first: Vec<carom::BodyHandle> = built
        .world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| b.handle())
        .collect();
    run(&mut built, 21);
    assert_eq!(
        (built.world.body_count(), built.world.joint_count()),
        (13, 6)
    );
    // A ball of each copy, with its collision group: every place its own.
    let groups = |built: &carom_scene::SceneWorld| -> Vec<((f32, f32), i32)> {
        let world = &built.world;
        let mut groups: Vec<_> = world
            .bodies()
            .filter(|b| b.is_dynamic() && built.colors.contains_key(&b.handle()))
            .map(|b| {
                let group = world.collider(b.colliders()[0]).unwrap().filter().group;
                ((b.position().x.round(), b.position().y.round()), group)
            })
            .collect();
        groups.sort_by_key(|&(_, g)| -g);
        groups
    };
    let before = groups(&built);
    assert_eq!(before.len(), 6);
    assert_eq!(
        before.iter().map(|&(_, g)| g).collect::<Vec<_>>(),
        [-1, -2, -3, -4, -5, -6]
    );
    // Turn 3 remakes column 0: its first copies are gone, the new ones stand where they did
    // and keep their places' groups.
    run(&mut built, 22);
    assert_eq!(
        (built.world.body_count(), built.world.joint_count()),
        (13, 6)
    );
    assert!(first.iter().all(|&h| built.world.body(h).is_none()));
    assert!(first.iter().all(|h| !built.colors.contains_key(h)));
    let after = groups(&built);
    for (row, &(place, group)) in after.iter().take(2).enumerate() {
        assert_eq!(group, -(1 + row as i32));
        assert_eq!(
            place,
            (-5.0, 3.0 + 2.0 * row as f32),
            "made again at its place"
        );
    }
    // Saved and reopened, it goes on remaking the same copies.
    let scene = carom_scene::parse(SPAWNING, "inline.ron").unwrap();
    let saved = built.save(&scene);
    let text = carom_scene::to_text(&saved, "saved.ron").unwrap();
    let mut reopened = inline(&text);
    for _ in 0..40 {
        built.step().unwrap();
        reopened.step().unwrap();
    }
    assert_eq!(reopened.world.state_hash(), built.world.state_hash());
    assert_eq!(reopened.world.body_count(), 13);
}

#[test]
fn a_spawn_schedule_makes_and_removes_what_the_scene_does_before_the_same_steps() {
    let built = inline(SPAWNING);
    let schedule = built.spawn_schedule(30).unwrap();
    use carom_scene::SpawnChange::{Add, Remove};
    assert_eq!(
        schedule.changes,
        [
            Add { step: 3, copy: 0 },
            Add { step: 3, copy: 1 },
            Add { step: 9, copy: 2 },
            Add { step: 9, copy: 3 },
            Add { step: 15, copy: 4 },
            Add { step: 15, copy: 5 },
            Remove { step: 21, copy: 0 },
            Add { step: 21, copy: 6 },
            Remove { step: 21, copy: 1 },
            Add { step: 21, copy: 7 },
            Remove { step: 27, copy: 2 },
            Add { step: 27, copy: 8 },
            Remove { step: 27, copy: 3 },
            Add { step: 27, copy: 9 },
        ]
    );
    assert!(schedule.other_events.is_empty());
    // Each copy as the scene makes it: two balls and their hinge, at its place, in its group.
    let mut live = inline(SPAWNING);
    for _ in 0..28 {
        live.step().unwrap();
    }
    for (copy, place) in [(6, 0i32), (7, 1), (8, 2), (9, 3)] {
        let made = &schedule.copies[copy];
        assert_eq!((made.bodies.len(), made.joints.len()), (2, 1));
        let a = schedule.world.body(made.bodies[0]).unwrap();
        let (column, row) = (place / 2, place % 2);
        let at = carom::vec2(-5.0 + 5.0 * column as f32, 3.0 + 2.0 * row as f32);
        assert_eq!(a.position(), at);
        let group = schedule
            .world
            .collider(a.colliders()[0])
            .unwrap()
            .filter()
            .group;
        assert_eq!(group, -(1 + place));
        // The live world holds the same copy now: a ball in that group, near its place.
        let twin = live.world.bodies().find(|b| {
            live.colors.contains_key(&b.handle())
                && live
                    .world
                    .collider(b.colliders()[0])
                    .unwrap()
                    .filter()
                    .group
                    == group
        });
        assert!((twin.unwrap().position() - at).norm() < 0.5);
    }
    // A schedule starts from a scene that has made nothing yet.
    assert!(live.spawn_schedule(10).is_err());
}

#[test]
fn a_spawn_event_refuses_what_it_cannot_make() {
    for (event, reason) in [
        (
            "Spawn(every: 0.0, columns: 1, of: Grid(origin: (0.0, 0.0), columns: 1, rows: 1, \
             spacing: (1.0, 1.0), shape: Circle(radius: 0.1)))",
            "`every` must be positive",
        ),
        (
            "Spawn(every: 1.0, columns: 0, of: Grid(origin: (0.0, 0.0), columns: 1, rows: 1, \
             spacing: (1.0, 1.0), shape: Circle(radius: 0.1)))",
            "at least one column",
        ),
        (
            "Spawn(every: 1.0, columns: 1, of: Group(bodies: [(name: \"a\", \
             shape: Circle(radius: 0.1))], joints: [(bodies: (\"a\", \"floor\"), \
             kind: Revolute())]))",
            "must join its own bodies",
        ),
        (
            "Spawn(every: 1.0, columns: 1, of: Grid(origin: (0.0, 0.0), columns: 1, rows: 1, \
             spacing: (1.0, 1.0), shape: Circle(radius: 0.1), material: (density: 0.0)))",
            "a copy cannot be made",
        ),
    ] {
        let text = format!(
            "(name: \"bad\", bodies: [(name: \"floor\", kind: static, \
             shape: Box(width: 1.0, height: 1.0))], events: [{event}])"
        );
        let scene = carom_scene::parse(&text, "bad.ron").unwrap_or_else(|e| panic!("{e}"));
        let error = carom_scene::build(&scene, "bad.ron")
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("event 0") && error.contains(reason),
            "{error}"
        );
    }
}

/// A scene whose generators ask for more than any machine holds is refused before anything is
/// made, naming the generator; the limits can be raised.
#[test]
fn scenes_asking_for_more_than_their_limits_are_refused_before_building() {
    use carom_scene::{Limits, build, build_with_limits, parse};
    let scene = |generators: &str, events: &str| {
        let text =
            format!("(format: 2, name: \"big\", generators: [{generators}], events: [{events}])");
        parse(&text, "big.ron").unwrap()
    };
    let huge = [
        "Pyramid(base: (0.0, 0.0), count: 4000000000)",
        "Stack(base: (0.0, 0.0), count: 4000000000)",
        "Rain(low: (0.0, 0.0), high: (1.0, 1.0), count: 600000, shape: Circle(radius: 0.1))",
        "Grid(origin: (0.0, 0.0), columns: 70000, rows: 70000, spacing: (1.0, 1.0), \
         shape: Circle(radius: 0.1))",
        "JointGrid(origin: (0.0, 0.0), columns: 1000, rows: 1000, spacing: (1.0, 1.0), \
         shape: Circle(radius: 0.1))",
        "Chain(from: (0.0, 0.0), to: (1.0, 0.0), count: 4000000000)",
        "Repeat(columns: 100000, rows: 100000, spacing: (1.0, 1.0), \
         of: Stack(base: (0.0, 0.0), count: 1000))",
        "Repeat(columns: 65535, rows: 65535, spacing: (1.0, 1.0), of: Repeat(columns: 65535, \
         rows: 65535, spacing: (1.0, 1.0), of: Repeat(columns: 65535, rows: 65535, \
         spacing: (1.0, 1.0), of: Stack(base: (0.0, 0.0), count: 65535))))",
    ];
    for generator in huge {
        let Err(error) = build(&scene(generator, ""), "big.ron") else {
            panic!("{generator} built");
        };
        let message = error.to_string();
        assert!(
            message.contains("generator 0") && message.contains("more than the limit of"),
            "{message}"
        );
    }
    // Together past the limit, each within it: the generator that crosses it is named.
    let two = "Stack(base: (0.0, 0.0), count: 300000), Stack(base: (5.0, 0.0), count: 300000)";
    let message = build(&scene(two, ""), "big.ron").err().unwrap().to_string();
    assert!(message.contains("generator 1 (stack)"), "{message}");
    // One spawn of more copies than the limit allows.
    let spawn = "Spawn(every: 1.0, origin: (0.0, 10.0), columns: 100000, rows: 100000, \
                 spacing: (1.0, 1.0), of: Stack(base: (0.0, 0.0), count: 2))";
    let message = build(&scene("", spawn), "big.ron")
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("event 0") && message.contains("one spawn would add"),
        "{message}"
    );
    // Copies of nothing are nothing, however many.
    let empty = "Repeat(columns: 4000000000, rows: 4000000000, spacing: (1.0, 1.0), \
                 of: Group(bodies: []))";
    assert_eq!(
        build(&scene(empty, ""), "big.ron")
            .unwrap()
            .world
            .body_count(),
        0
    );
    // The limits are the caller's to set.
    let eleven = scene("Stack(base: (0.0, 0.0), count: 11)", "");
    let ten = Limits {
        bodies: 10,
        ..Limits::default()
    };
    assert!(build_with_limits(&eleven, "big.ron", ten).is_err());
    let built = build_with_limits(&eleven, "big.ron", Limits { bodies: 11, ..ten }).unwrap();
    assert_eq!(built.world.body_count(), 11);
    let chain = scene("Chain(from: (0.0, 0.0), to: (10.0, 0.0), count: 10)", "");
    let few_joints = Limits {
        joints: 10,
        ..Limits::default()
    };
    assert!(build_with_limits(&chain, "big.ron", few_joints).is_err());
    assert!(
        build_with_limits(
            &chain,
            "big.ron",
            Limits {
                joints: 11,
                ..few_joints
            }
        )
        .is_ok()
    );
}

/// Generators nested deeper than a scene needs are refused as the file is read, not by
/// running out of stack.
#[test]
fn generators_nested_without_end_are_refused_as_the_file_is_read() {
    let depth = 10_000;
    let mut generator = "Stack(base: (0.0, 0.0), count: 1)".to_owned();
    for _ in 0..depth {
        generator = format!("Repeat(columns: 1, rows: 1, spacing: (1.0, 1.0), of: {generator})");
    }
    let text = format!("(format: 2, name: \"deep\", generators: [{generator}])");
    let error = carom_scene::parse(&text, "deep.ron")
        .unwrap_err()
        .to_string();
    assert!(
        error.starts_with("deep.ron:1:") && error.contains("recursion limit"),
        "{error}"
    );
}
