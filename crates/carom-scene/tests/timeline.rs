//! Going back through a run and playing it again: every step reached from a keyframe is at
//! the bits it had the first time, a new input after going back branches the run, and the
//! keyframes stay inside their memory budget with the whole run still reachable.

use carom_scene::{Course, Input, Recording, SceneWorld, Timeline, TimelineError, build, parse};

const SCENE: &str = r#"(
    name: "timeline",
    bodies: [
        (kind: static, shape: Box(width: 40.0, height: 1.0), position: (0.0, -0.5)),
        (shape: Box(width: 1.0, height: 1.0), position: (0.0, 0.5)),
        (shape: Box(width: 1.0, height: 1.0), position: (0.1, 1.5)),
        (shape: Box(width: 1.0, height: 1.0), position: (-0.1, 2.5)),
        (shape: Circle(radius: 0.5), position: (3.0, 4.0)),
        (shape: Capsule(length: 1.0, radius: 0.25), position: (-3.0, 2.0)),
    ],
)"#;

fn start() -> (SceneWorld, Recording) {
    let scene = build(&parse(SCENE, "timeline.ron").unwrap(), "timeline.ron").unwrap();
    (scene, Recording::new("timeline.ron", SCENE))
}

/// A run of `steps` in which the top box is grabbed at step 20, thrown at step 50 and the
/// circle grabbed at step 90; the state hash after every step.
fn play(timeline: &mut Timeline, scene: &mut SceneWorld, steps: u64) -> Vec<u64> {
    let mut hashes = Vec::new();
    for step in 0..steps {
        match step {
            20 => {
                grab_body_at(timeline, scene, carom::vec2(-0.1, 2.5));
            }
            21..50 => {
                let moved = (step - 20) as carom::Real;
                let point = (-0.1 + 0.1 * moved, 2.5 + 0.05 * moved);
                timeline.input(scene, Input::Drag { point }).unwrap();
            }
            50 => {
                timeline.input(scene, Input::LetGo).unwrap();
            }
            90 => {
                grab_body_at(timeline, scene, carom::vec2(3.0, 0.5));
            }
            _ => {}
        }
        timeline.step(scene).unwrap();
        hashes.push(scene.world.state_hash());
    }
    hashes
}

/// Grabs the body under `point`, at its centre.
fn grab_body_at(timeline: &mut Timeline, scene: &mut SceneWorld, point: carom::Vec2) {
    let body = scene.world.body_at(point).unwrap();
    let at = scene.world.body(body).unwrap().position();
    let grab = Input::Grab {
        point: (at.x, at.y),
    };
    timeline.input(scene, grab).unwrap();
}

#[test]
fn every_step_gone_back_to_is_at_its_first_bits() {
    let (mut scene, recording) = start();
    let mut timeline = Timeline::new(recording, &scene);
    let first = play(&mut timeline, &mut scene, 150);
    assert!(timeline.is_live());
    assert_eq!(timeline.end(), 150);
    assert_eq!(timeline.recording().hashes, first);
    assert!(timeline.hand().grabbed().is_some(), "the circle is held");

    // Back to steps between keyframes, on them, and into the grab, in no particular order.
    for target in [100, 37, 20, 21, 0, 149, 60, 59, 1] {
        timeline.go_to(&mut scene, target).unwrap();
        assert_eq!(timeline.at(), target);
        assert!(!timeline.is_live() || target == 150);
        if target > 0 {
            assert_eq!(
                scene.world.state_hash(),
                first[target as usize - 1],
                "step {target}"
            );
        }
        let held = (20..50).contains(&target) || target >= 90;
        assert_eq!(timeline.hand().grabbed().is_some(), held, "step {target}");
    }

    // Played on from step 1, the run is the same run, to its end and past it.
    timeline.go_to(&mut scene, 1).unwrap();
    while !timeline.is_live() {
        timeline.step(&mut scene).unwrap();
        assert_eq!(scene.world.state_hash(), first[timeline.at() as usize - 1]);
    }
    timeline.step(&mut scene).unwrap();
    assert_eq!(timeline.end(), 151);

    // Past the end is the end.
    timeline.go_to(&mut scene, 10_000).unwrap();
    assert_eq!(timeline.at(), 151);
}

#[test]
fn a_new_input_after_going_back_branches_the_run() {
    let (mut scene, recording) = start();
    let mut timeline = Timeline::with_keyframes(recording, &scene, 10, usize::MAX);
    let first = play(&mut timeline, &mut scene, 120);
    timeline.go_to(&mut scene, 45).unwrap();
    // Letting go early: the box the old run threw at step 50 falls at step 45.
    let course = timeline.input(&mut scene, Input::LetGo).unwrap();
    assert_eq!(
        course,
        Course::Branched {
            at: 45,
            forgotten: 75
        }
    );
    assert_eq!(timeline.end(), 45);
    assert!(timeline.is_live());
    assert!(timeline.keyframe_steps().all(|step| step <= 45));
    for _ in 0..20 {
        timeline.step(&mut scene).unwrap();
    }
    assert_eq!(timeline.end(), 65);
    assert_ne!(
        scene.world.state_hash(),
        first[64],
        "the branch went another way"
    );
    // The branch's inputs replay: the old run's drags up to step 45 and the early let-go.
    let branch = timeline.recording().hashes.clone();
    assert_eq!(&branch[..45], &first[..45]);
    assert_eq!(timeline.recording().replay().unwrap(), None);
    timeline.go_to(&mut scene, 30).unwrap();
    timeline.go_to(&mut scene, 65).unwrap();
    assert_eq!(scene.world.state_hash(), branch[64]);

    // An input at the end of the run is the run's newest, not a branch.
    let course = timeline.input(&mut scene, Input::LetGo).unwrap();
    assert_eq!(course, Course::Live);
}

#[test]
fn inputs_of_the_first_step_apply_when_going_back_to_it() {
    let (mut scene, recording) = start();
    let mut timeline = Timeline::new(recording, &scene);
    let mut solver = *scene.world.solver();
    solver.substeps = 2;
    timeline.input(&mut scene, Input::Solver(solver)).unwrap();
    for _ in 0..30 {
        timeline.step(&mut scene).unwrap();
    }
    let hash = scene.world.state_hash();
    timeline.go_to(&mut scene, 0).unwrap();
    assert_eq!(scene.world.solver().substeps, 2);
    timeline.go_to(&mut scene, 30).unwrap();
    assert_eq!(scene.world.state_hash(), hash);
}

#[test]
fn keyframes_are_thinned_inside_their_budget_and_the_run_stays_reachable() {
    let (mut scene, recording) = start();
    let probe = Timeline::new(recording.clone(), &scene);
    let one = probe.bytes() - recording.scene.capacity();
    // Room for about eight keyframes, one every five steps: 600 steps would make 121.
    let budget = 8 * one;
    let mut timeline = Timeline::with_keyframes(recording, &scene, 5, budget);
    let first = play(&mut timeline, &mut scene, 600);
    let steps: Vec<u64> = timeline.keyframe_steps().collect();
    assert!(steps.len() <= 9, "{steps:?}");
    assert_eq!(steps.first(), Some(&0));
    assert_eq!(steps.last(), Some(&600));
    // Thinning weighs the work of replaying a stretch: the first hundred steps (boxes
    // falling, one thrown) keep their keyframes closer than the quiet end, where only the
    // held circle is awake, although they are older.
    let gaps: Vec<u64> = steps.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(gaps[0] < gaps[gaps.len() - 1], "{steps:?}");
    for target in [3, 250, 599, 404] {
        timeline.go_to(&mut scene, target).unwrap();
        assert_eq!(scene.world.state_hash(), first[target as usize - 1]);
    }
}

#[test]
fn a_setting_out_of_range_is_refused_and_leaves_the_run_as_it_was() {
    let (mut scene, recording) = start();
    let mut timeline = Timeline::new(recording, &scene);
    for _ in 0..10 {
        timeline.step(&mut scene).unwrap();
    }
    timeline.go_to(&mut scene, 4).unwrap();
    let mut solver = *scene.world.solver();
    solver.contact_hertz = -1.0;
    let refused = timeline.input(&mut scene, Input::Solver(solver));
    assert!(
        matches!(refused, Err(TimelineError::Input(_))),
        "{refused:?}"
    );
    assert_eq!(timeline.end(), 10, "a refused input does not branch");
    assert!(!refused.unwrap_err().to_string().is_empty());
}
