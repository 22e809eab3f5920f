//! `carom bench`'s measures agree with the physics they measure: each can tell a good solver
//! setting from a bad one, against the exact answer.

use carom::{Real, SolverKind};
use carom_bench::sweep::{ErrorKind, Setting, SweepOptions, measure, sweep};
use std::path::PathBuf;

fn scene(name: &str) -> (carom_scene::Scene, String) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../demos")
        .join(name);
    (
        carom_scene::read(&path).unwrap(),
        path.display().to_string(),
    )
}

fn setting(solver: SolverKind, iterations: u32, substeps: u32) -> Setting {
    Setting::carom(solver, iterations, substeps)
}

#[test]
fn the_slide_angle_is_found_near_atan_mu_and_missed_without_friction() {
    let (incline, file) = scene("incline_friction.ron");
    let soft = measure(&incline, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    assert!(
        soft.error() < 0.5,
        "soft step slides {} deg off",
        soft.error()
    );
    // Push-out has no friction: the box slides on any slope, atan(0.5) = 26.6 deg early.
    let push = measure(&incline, &file, setting(SolverKind::PushOut, 8, 1), 10.0).unwrap();
    assert!(
        (push.error() - 26.57).abs() < 0.1,
        "push-out: {} deg",
        push.error()
    );
    assert!(!soft.step_ms.is_empty());
}

#[test]
fn the_cradle_conserves_with_impulses_and_loses_energy_with_push_out() {
    let (cradle, file) = scene("newtons_cradle.ron");
    let impulse = measure(&cradle, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    assert!(impulse.error() < 1e-3, "soft step: {}", impulse.error());
    let push = measure(&cradle, &file, setting(SolverKind::PushOut, 8, 1), 10.0).unwrap();
    assert!(
        push.error() > 0.5,
        "push-out conserved energy: {}",
        push.error()
    );
}

#[test]
fn a_resting_stack_sinks_less_with_a_better_solver() {
    let (stack, file) = scene("vertical_stack.ron");
    let good = measure(&stack, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    let bad = measure(&stack, &file, setting(SolverKind::PushOut, 1, 1), 10.0).unwrap();
    assert!(
        good.error() < 0.05,
        "soft step moved the top box {} m",
        good.error()
    );
    assert!(
        bad.error() > 10.0 * good.error(),
        "push-out {} vs {}",
        bad.error(),
        good.error()
    );
}

#[test]
fn a_hinged_pendulum_keeps_its_period_and_a_soft_chain_stretches_less_when_stiffer() {
    let (pendulum, file) = scene("pendulum.ron");
    let soft = measure(&pendulum, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    // Box2D 3.2 on the same scene: 0.0002 %.
    assert!(
        soft.error() < 1e-3,
        "soft step period off by {} %",
        soft.error()
    );
    let si = measure(
        &pendulum,
        &file,
        setting(SolverKind::SequentialImpulse, 8, 1),
        10.0,
    );
    let si = si.unwrap().error();
    assert!(si < 0.5, "sequential impulse period off by {si} %");

    let (chain, file) = scene("chain.ron");
    // Box2D's settings: 4 substeps, 60 Hz joints; Box2D 3.2 stretches 6.48 %.
    let box2d = measure(&chain, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    assert!(
        (box2d.error() - 6.48).abs() < 0.2,
        "4 substeps, 60 Hz: {} %",
        box2d.error()
    );
    let stiff = Setting {
        joint_hertz: Some(120.0),
        ..setting(SolverKind::SoftStep, 1, 8)
    };
    let stiff = measure(&chain, &file, stiff, 10.0).unwrap();
    assert!(
        stiff.error() < 2.0,
        "8 substeps, 120 Hz: {} %",
        stiff.error()
    );
}

#[test]
fn a_joint_scene_is_swept_without_the_solvers_that_leave_joints_out() {
    let options = SweepOptions {
        scenes: vec![PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos/chain.ron")],
        runs: 1,
        solvers: SolverKind::ALL.to_vec(),
        iterations: vec![1],
        substeps: vec![4, 8],
        joint_hertz: vec![60.0, 240.0],
        seconds: 1.0,
        contact_hertz: vec![30.0],
        ..SweepOptions::default()
    };
    let points = sweep(&options, |_, _, _| {}).unwrap();
    let settings: Vec<(SolverKind, u32, Option<Real>, bool)> = points
        .iter()
        .map(|p| {
            let s = p.setting;
            (s.solver, s.substeps, s.joint_hertz, s.direct_joints)
        })
        .collect();
    assert_eq!(
        settings,
        [
            (SolverKind::SequentialImpulse, 1, None, false),
            (SolverKind::SoftStep, 4, None, false),
            (SolverKind::SoftStep, 4, None, true),
            (SolverKind::SoftStep, 8, None, false),
            (SolverKind::SoftStep, 8, Some(120.0), false),
            (SolverKind::SoftStep, 8, None, true),
            (SolverKind::SoftStep, 8, Some(120.0), true),
        ]
    );
    // The chain's light links under their load stretch less solved directly.
    let error = |substeps: u32, direct: bool| {
        points
            .iter()
            .find(|p| {
                p.setting.solver == SolverKind::SoftStep
                    && p.setting.substeps == substeps
                    && p.setting.joint_hertz.is_none()
                    && p.setting.direct_joints == direct
            })
            .unwrap()
            .error
    };
    eprintln!(
        "chain at 4 substeps: {} % iterative, {} % direct",
        error(4, false),
        error(4, true)
    );
    assert!(error(4, true) < error(4, false));
    assert!(
        points
            .iter()
            .all(|p| p.joints && p.error_kind == ErrorKind::Stretch && p.error.is_finite())
    );
}

#[test]
fn a_sweep_has_a_point_per_setting_and_substeps_only_for_soft_step() {
    let options = SweepOptions {
        scenes: vec![
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos/newtons_cradle.ron"),
        ],
        runs: 2,
        solvers: vec![SolverKind::SequentialImpulse, SolverKind::SoftStep],
        iterations: vec![1, 4],
        substeps: vec![1, 2],
        joint_hertz: vec![60.0, 240.0],
        seconds: 1.0,
        contact_hertz: vec![30.0],
        ..SweepOptions::default()
    };
    let mut calls = 0;
    let points = sweep(&options, |_, _, _| calls += 1).unwrap();
    // Sequential impulse: 2 iteration counts; soft step: 2 x 2.
    assert_eq!(points.len(), 6);
    // Told as each point ends, and once when all have.
    assert_eq!(calls, 6 + 1);
    assert!(
        points
            .iter()
            .all(|p| p.error_kind == ErrorKind::Conservation)
    );
    assert!(points.iter().all(|p| p.ms_per_step > 0.0));
    let si_substeps: Vec<u32> = points
        .iter()
        .filter(|p| p.setting.solver == SolverKind::SequentialImpulse)
        .map(|p| p.setting.substeps)
        .collect();
    assert_eq!(si_substeps, [1, 1]);
}

#[cfg(feature = "peers")]
#[test]
fn peers_run_the_same_scene_over_their_own_settings_and_box2d_times_the_pendulum_as_carom() {
    use carom_bench::sweep::Engine;
    let options = SweepOptions {
        scenes: vec![PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos/pendulum.ron")],
        runs: 1,
        solvers: vec![SolverKind::SoftStep],
        iterations: vec![1],
        substeps: vec![4],
        engines: Engine::ALL.to_vec(),
        box2d_substeps: vec![1, 4],
        contact_hertz: vec![30.0],
        rapier_substeps: vec![1, 4],
        rapier_stabilization: vec![1, 2],
        direct_joints: vec![false],
        ..SweepOptions::default()
    };
    let points = sweep(&options, |_, _, _| {}).unwrap();
    let of = |engine| points.iter().filter(move |p| p.setting.engine == engine);
    assert_eq!(of(Engine::Carom).count(), 1);
    assert_eq!(of(Engine::Box2d).count(), 2);
    assert_eq!(of(Engine::Rapier).count(), 4);
    assert!(
        points
            .iter()
            .all(|p| p.error.is_finite() && p.ms_per_step > 0.0)
    );
    assert!(of(Engine::Rapier).all(|p| p.setting.stabilization.is_some()));
    assert!(of(Engine::Carom).all(|p| p.max_penetration.is_finite()));
    assert!(of(Engine::Box2d).all(|p| p.max_penetration.is_nan()));
    // Box2D's soft step and carom's at the same 4 substeps time the swing alike: the same
    // algorithm, rebuilt from the same scene.
    let carom = of(Engine::Carom).next().unwrap().error;
    let box2d = of(Engine::Box2d)
        .find(|p| p.setting.substeps == 4)
        .unwrap()
        .error;
    assert!(carom < 1e-3, "carom's period error {carom} %");
    assert!(
        (carom - box2d).abs() < 1e-5,
        "carom {carom} %, Box2D {box2d} %"
    );
    // More substeps make Rapier's swing truer, as they do Box2D's.
    let rapier = |substeps| {
        of(Engine::Rapier)
            .find(|p| p.setting.substeps == substeps)
            .unwrap()
            .error
    };
    assert!(rapier(4) < rapier(1), "{} against {}", rapier(4), rapier(1));
}

#[test]
fn the_joint_and_sink_measures_tell_the_options_from_plain_soft_step() {
    let soft = setting(SolverKind::SoftStep, 1, 4);
    let direct = Setting {
        direct_joints: true,
        ..soft
    };
    // A taut bridge stretches along its span less when its hinges are solved directly.
    let (bridge, file) = scene("bridge.ron");
    let iterative = measure(&bridge, &file, soft, 10.0).unwrap();
    let exact = measure(&bridge, &file, direct, 10.0).unwrap();
    assert_eq!(iterative.errors[0].0, ErrorKind::Gaps);
    assert!(
        exact.error() < 0.5 * iterative.error() && exact.error() > 0.0,
        "bridge: {} % direct, {} % iterative",
        exact.error(),
        iterative.error()
    );
    // A pile of ragdolls gives two errors, both smaller with direct joints.
    let (ragdolls, file) = scene("ragdolls.ron");
    let iterative = measure(&ragdolls, &file, soft, 10.0).unwrap();
    let exact = measure(&ragdolls, &file, direct, 10.0).unwrap();
    let kinds: Vec<ErrorKind> = exact.errors.iter().map(|e| e.0).collect();
    assert_eq!(kinds, [ErrorKind::HingeGap, ErrorKind::PastLimit]);
    for (exact, iterative) in exact.errors.iter().zip(&iterative.errors) {
        assert!(
            exact.1 < iterative.1 && iterative.1.is_finite(),
            "{:?}: {} direct, {} iterative",
            exact.0,
            exact.1,
            iterative.1
        );
    }
    // Triangles under a box a thousand times heavier are pushed into the ground, unless shock
    // propagation holds the box on them.
    let (heavy, file) = scene("heavy_on_light.ron");
    let plain = measure(&heavy, &file, soft, 10.0).unwrap();
    let shock = Setting {
        shock_propagation: true,
        ..soft
    };
    let held = measure(&heavy, &file, shock, 10.0).unwrap();
    assert_eq!(plain.errors[0].0, ErrorKind::Sink);
    assert!(
        plain.error() > 0.05 && held.error() < 0.01,
        "sunk {} m plain, {} m with shock propagation",
        plain.error(),
        held.error()
    );
}

#[cfg(feature = "peers")]
#[test]
fn the_peers_are_measured_by_the_joint_and_sink_measures_too() {
    use carom_bench::sweep::Engine;
    let box2d = Setting {
        engine: Engine::Box2d,
        contact_hertz: Some(30.0),
        ..setting(SolverKind::SoftStep, 1, 4)
    };
    let carom = setting(SolverKind::SoftStep, 1, 4);
    // At the same settings the two soft steps give the bridge and the heavy box alike.
    for name in ["bridge.ron", "heavy_on_light.ron"] {
        let (scene, file) = scene(name);
        let theirs = measure(&scene, &file, box2d, 10.0).unwrap().error();
        let ours = measure(&scene, &file, carom, 10.0).unwrap().error();
        assert!(
            theirs.is_finite() && ours.is_finite() && theirs < 3.0 * ours && ours < 3.0 * theirs,
            "{name}: Box2D {theirs}, carom {ours}"
        );
    }
    let (ragdolls, file) = scene("ragdolls.ron");
    let theirs = measure(&ragdolls, &file, box2d, 10.0).unwrap();
    assert_eq!(theirs.errors.len(), 2);
    assert!(theirs.errors.iter().all(|e| e.1.is_finite() && e.1 > 0.0));
}

#[test]
fn the_quick_sweep_is_a_part_of_the_whole_measured_alike() {
    let (quick, full) = (SweepOptions::quick(), SweepOptions::full());
    assert_eq!(quick.scenes, full.scenes);
    assert_eq!(quick.seconds, full.seconds);
    assert_eq!(quick.runs, 1);
    for path in &full.scenes {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path);
        let file = path.display().to_string();
        let scene = carom_scene::build(&carom_scene::read(&path).unwrap(), &file).unwrap();
        let (part, whole) = (quick.settings(&scene), full.settings(&scene));
        assert!(
            !part.is_empty() && part.len() * 2 < whole.len(),
            "{file}: {} of {}",
            part.len(),
            whole.len()
        );
        for setting in &part {
            assert!(
                whole.contains(setting),
                "{file}: {setting:?} is not swept whole"
            );
        }
        // Every engine, and soft step with each option it sweeps on the scene.
        for engine in carom_bench::sweep::Engine::ALL {
            assert!(
                part.iter().any(|s| s.engine == engine),
                "{file}: no {engine:?}"
            );
        }
        for (option, of) in [
            (
                "direct joints",
                &(|s: &Setting| s.direct_joints) as &dyn Fn(&Setting) -> bool,
            ),
            ("shock propagation", &|s: &Setting| s.shock_propagation),
        ] {
            assert_eq!(
                part.iter().any(of),
                whole.iter().any(of),
                "{file}: {option}"
            );
        }
    }
}
