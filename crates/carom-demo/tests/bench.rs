//! `carom bench`'s measures agree with the physics they measure: each can tell a good solver
//! setting from a bad one, against the exact answer.

use carom::SolverKind;
use carom_demo::bench::{ErrorKind, Setting, SweepOptions, measure, sweep};
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
    Setting {
        solver,
        iterations,
        substeps,
    }
}

#[test]
fn the_slide_angle_is_found_near_atan_mu_and_missed_without_friction() {
    let (incline, file) = scene("incline_friction.ron");
    let soft = measure(&incline, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    assert!(soft.error < 0.5, "soft step slides {} deg off", soft.error);
    // Push-out has no friction: the box slides on any slope, atan(0.5) = 26.6 deg early.
    let push = measure(&incline, &file, setting(SolverKind::PushOut, 8, 1), 10.0).unwrap();
    assert!(
        (push.error - 26.57).abs() < 0.1,
        "push-out: {} deg",
        push.error
    );
    assert!(!soft.step_ms.is_empty());
}

#[test]
fn the_cradle_conserves_with_impulses_and_loses_energy_with_push_out() {
    let (cradle, file) = scene("newtons_cradle.ron");
    let impulse = measure(&cradle, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    assert!(impulse.error < 1e-3, "soft step: {}", impulse.error);
    let push = measure(&cradle, &file, setting(SolverKind::PushOut, 8, 1), 10.0).unwrap();
    assert!(
        push.error > 0.5,
        "push-out conserved energy: {}",
        push.error
    );
}

#[test]
fn a_resting_stack_sinks_less_with_a_better_solver() {
    let (stack, file) = scene("vertical_stack.ron");
    let good = measure(&stack, &file, setting(SolverKind::SoftStep, 1, 4), 10.0).unwrap();
    let bad = measure(&stack, &file, setting(SolverKind::PushOut, 1, 1), 10.0).unwrap();
    assert!(
        good.error < 0.05,
        "soft step moved the top box {} m",
        good.error
    );
    assert!(
        bad.error > 10.0 * good.error,
        "push-out {} vs {}",
        bad.error,
        good.error
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
        seconds: 1.0,
    };
    let mut calls = 0;
    let points = sweep(&options, |_, _, _| calls += 1).unwrap();
    // Sequential impulse: 2 iteration counts; soft step: 2 x 2.
    assert_eq!(points.len(), 6);
    assert_eq!(calls, 6 * 2 + 1);
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
