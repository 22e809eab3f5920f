//! What a step reports besides motion, through the public interface: the impulses each contact
//! point applied.

use carom::{
    BodyDef, BodyHandle, Effect, Real, Shape, SolverKind, SolverParams, World, WorldSettings, vec2,
};

const DT: Real = 1.0 / 60.0;

/// A world with gravity (0, -10), sleeping off so resting bodies stay solved, the given solver
/// at its defaults, and a static floor whose top is y = 0.
fn world_with(kind: SolverKind) -> World {
    let mut settings = WorldSettings {
        solver: SolverParams::for_kind(kind),
        ..WorldSettings::default()
    };
    settings.effects.set(Effect::Sleeping, false);
    let mut world = World::with_settings(settings).unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    world
}

/// The sum over `body`'s contact points of what the last step applied there, total and most
/// in one substep.
fn impulses_on(world: &World, body: BodyHandle) -> (Real, Real) {
    let points = world
        .contacts()
        .filter(|c| c.body_a() == body || c.body_b() == body)
        .flat_map(|c| c.manifold().points());
    points.fold((0.0, 0.0), |(total, max), p| {
        (total + p.total_normal_impulse, max + p.max_normal_impulse)
    })
}

#[test]
fn a_resting_box_reports_its_weight_as_the_step_impulse_in_both_solvers() {
    for (kind, substeps) in [
        (SolverKind::SoftStep, 4.0),
        (SolverKind::SequentialImpulse, 1.0),
    ] {
        let mut world = world_with(kind);
        // 1 m x 1 m at density 2: 2 kg.
        let crate_box = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .position(vec2(0.0, 0.5))
                    .density(2.0),
            )
            .unwrap();
        let weight_impulse = 2.0 * 10.0 * DT;
        for step in 0..180 {
            world.step(DT).unwrap();
            if step < 60 {
                continue;
            }
            let (total, max) = impulses_on(&world, crate_box);
            assert!(
                (total - weight_impulse).abs() < 0.01 * weight_impulse,
                "{kind:?} step {step}: {total} N·s for a weight of {weight_impulse}"
            );
            // Soft step starts each substep over from the accumulated impulse, so a substep
            // holds a quarter of the step's; the classic solvers' step is its one substep.
            let per_substep = weight_impulse / substeps;
            assert!(
                (max - per_substep).abs() < 0.05 * per_substep,
                "{kind:?} step {step}: {max} N·s at most in a substep, expected {per_substep}"
            );
        }
        // Force is impulse over time: the box's weight.
        let floor_contact = world.contacts().find(|c| c.body_b() == crate_box).unwrap();
        let force = floor_contact.total_normal_impulse() / DT;
        assert!((force - 20.0).abs() < 0.2, "{kind:?}: {force} N");
    }
}
