//! Box2D's spinner and rain recipes rebuilt in the peers, and a scene's spawn events replayed
//! there: the same bodies and joints, made and removed before the same steps.

use std::path::PathBuf;

use carom_bench::{Box2dWorld, RapierWorld, run_box2d, run_carom, run_rapier};
use carom_scene::{SceneWorld, SpawnChange};

const DT: f32 = 1.0 / 60.0;

fn demo(name: &str) -> SceneWorld {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../demos/{name}.ron"));
    carom_scene::load(&file).unwrap_or_else(|e| panic!("{e}"))
}

/// A floor, and pairs of hinged balls made at the six places of a 3 x 2 grid, a column every
/// 0.1 s from 0.05 s (before steps 3, 9, 15, ...), each remade at its next turn.
const SPAWNING: &str = r#"(name: "spawning",
    bodies: [(kind: static, shape: Box(width: 40.0, height: 1.0), position: (0.0, -0.5))],
    events: [Spawn(at: 0.05, every: 0.1, origin: (-5.0, 3.0), columns: 3, rows: 2,
                   spacing: (5.0, 2.0),
                   of: Group(bodies: [(name: "a", shape: Circle(radius: 0.2)),
                                      (name: "b", shape: Circle(radius: 0.2),
                                       position: (0.5, 0.0))],
                             joints: [(bodies: ("a", "b"), anchor: (0.25, 0.0),
                                       kind: Revolute(motor: (speed: 0.0, max_force: 0.1),
                                                      spring: (hertz: 2.0, damping_ratio: 0.5)))]))],
)"#;

fn spawning() -> SceneWorld {
    let scene = carom_scene::parse(SPAWNING, "spawning.ron").unwrap();
    carom_scene::build(&scene, "spawning.ron").unwrap()
}

#[test]
fn the_peers_make_and_remove_a_scene_s_spawned_copies_before_the_same_steps() {
    let mut scene = spawning();
    let schedule = scene.spawn_schedule(40).unwrap();
    assert!(
        schedule
            .changes
            .iter()
            .any(|c| matches!(c, SpawnChange::Remove { .. }))
    );
    let mut box2d = Box2dWorld::from_carom(&scene.world).unwrap();
    let mut rapier = RapierWorld::from_carom(&scene.world, DT).unwrap();
    let mut next = 0;
    for step in 0..40u64 {
        while let Some(change) = schedule.changes.get(next).filter(|c| c.step() == step) {
            match *change {
                SpawnChange::Add { copy, .. } => {
                    let made = &schedule.copies[copy];
                    box2d.add_spawned(copy, &schedule.world, made).unwrap();
                    rapier.add_spawned(copy, &schedule.world, made).unwrap();
                }
                SpawnChange::Remove { copy, .. } => {
                    box2d.remove_spawned(copy).unwrap();
                    rapier.remove_spawned(copy).unwrap();
                }
            }
            next += 1;
        }
        scene.step().unwrap();
        box2d.step(DT).unwrap();
        rapier.step();
        // The same bodies and joints at every step; Rapier's hinges carry their friction
        // motor as a second joint.
        let bodies = scene.world.body_count();
        assert_eq!(box2d.native_body_count().unwrap(), bodies, "step {step}");
        assert_eq!(rapier.body_count(), bodies, "step {step}");
        let joints = scene.world.joint_count();
        assert_eq!(box2d.joint_count().unwrap(), joints, "step {step}");
        assert_eq!(rapier.joint_count(), 2 * joints, "step {step}");
    }
    assert_eq!(next, schedule.changes.len());
    assert!(box2d.notes().is_empty(), "{:?}", box2d.notes().lines());
    assert!(rapier.notes().is_empty(), "{:?}", rapier.notes().lines());
    // The balls made last fell alike in all three: the same heights within a centimetre.
    let heights = |mut ys: Vec<f32>| {
        ys.sort_by(f32::total_cmp);
        ys
    };
    let carom = heights(
        scene
            .world
            .bodies()
            .filter(|b| b.is_dynamic())
            .map(|b| b.position().y)
            .collect(),
    );
    let box2d = heights(
        box2d
            .spawned_positions()
            .unwrap()
            .iter()
            .map(|p| p[1])
            .collect(),
    );
    let rapier = heights(rapier.spawned_positions().iter().map(|p| p[1]).collect());
    assert_eq!(carom.len(), 12);
    for (peer, ys) in [("Box2D", box2d), ("Rapier", rapier)] {
        for (a, b) in carom.iter().zip(&ys) {
            assert!((a - b).abs() < 0.01, "{peer}: {ys:?}, carom {carom:?}");
        }
    }
}

#[test]
fn the_runs_follow_a_scene_s_spawn_events() {
    let mut scene = spawning();
    let schedule = scene.spawn_schedule(30).unwrap();
    let carom = run_carom(&mut scene, 30).unwrap();
    let mut box2d = Box2dWorld::from_carom(&spawning().world).unwrap();
    let b = run_box2d(&mut box2d, DT, 30, Some(&schedule)).unwrap();
    let mut rapier = RapierWorld::from_carom(&spawning().world, DT).unwrap();
    let r = run_rapier(&mut rapier, 30, Some(&schedule)).unwrap();
    assert!(!carom.nan && !b.nan && !r.nan);
    assert_eq!(box2d.native_body_count().unwrap(), scene.world.body_count());
    assert_eq!(rapier.body_count(), scene.world.body_count());
    assert_eq!(scene.world.body_count(), 1 + 12);
}

#[test]
fn the_spinner_is_rebuilt_whole_in_the_peers() {
    let scene = demo("spinner");
    let box2d = Box2dWorld::from_carom(&scene.world).unwrap();
    let rapier = RapierWorld::from_carom(&scene.world, DT).unwrap();
    assert_eq!(box2d.native_body_count().unwrap(), 2 + 6076);
    assert_eq!(rapier.body_count(), 2 + 6076);
    assert_eq!((box2d.joint_count().unwrap(), rapier.joint_count()), (1, 1));
    // Box2D takes every part as it is; Rapier's chain links are plain segments.
    assert!(box2d.notes().is_empty(), "{:?}", box2d.notes().lines());
    assert_eq!(
        rapier.notes().lines(),
        [
            "a chain link: a plain segment in Rapier (two-sided, without the ghost vertices that \
          smooth a chain's joins) (× 360)"
        ]
    );
}

#[test]
fn the_ragdoll_rain_is_replayed_whole_in_the_peers() {
    // The first two turns: ten groups of five ragdolls, 550 bones and 500 hinges.
    let mut scene = demo("ragdoll_rain");
    let schedule = scene.spawn_schedule(9).unwrap();
    assert_eq!(schedule.changes.len(), 10);
    let mut box2d = Box2dWorld::from_carom(&scene.world).unwrap();
    let mut rapier = RapierWorld::from_carom(&scene.world, DT).unwrap();
    run_carom(&mut scene, 9).unwrap();
    run_box2d(&mut box2d, DT, 9, Some(&schedule)).unwrap();
    run_rapier(&mut rapier, 9, Some(&schedule)).unwrap();
    assert_eq!(scene.world.body_count(), 1 + 550);
    assert_eq!(box2d.native_body_count().unwrap(), 1 + 550);
    assert_eq!(rapier.body_count(), 1 + 550);
    assert_eq!(box2d.joint_count().unwrap(), 500);
    // Each sprung hinge's joint friction is a second joint in Rapier.
    assert_eq!(rapier.joint_count(), 1000);
    assert!(box2d.notes().is_empty(), "{:?}", box2d.notes().lines());
    assert!(rapier.notes().is_empty(), "{:?}", rapier.notes().lines());
}
