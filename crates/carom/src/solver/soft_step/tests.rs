//! Soft step's SIMD bundles against the scalar path, and its stage plan.

use super::scalar::{apply_restitution, solve_one, warm_start_one};
use super::*;
use crate::dynamics::body_def::BodyDef;
use crate::geometry::shape::Shape;
use crate::graph::order::ContactGraph;
use crate::graph::order::{ColorCheck, order_constraints};
use crate::math::{rotation, vec2};
use crate::solver::contact_constraint::BodyMass;
use crate::solver::soft_step::bundles::Width;
use crate::solver::soft_step::inputs::BundleInputs;
use crate::solver::soft_step::lanes::tests::agrees;
use crate::world::World;

/// A pile in motion: a pyramid with a kinematic paddle pushing into it and circles
/// dropped on it, a few steps in, so contacts carry impulses and bodies move.
fn pile() -> World {
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    for row in 0..6 {
        for column in 0..6 - row {
            let x = column as Real - 0.5 * (5 - row) as Real;
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(x, 0.5 + row as Real))
                        .angle(0.01 * column as Real),
                )
                .unwrap();
        }
    }
    for i in 0..4 {
        world
            .add_body(
                BodyDef::dynamic(Shape::circle(0.3))
                    .position(vec2(-1.0 + 0.7 * i as Real, 7.0))
                    .density(3.0),
            )
            .unwrap();
    }
    world
        .add_body(
            BodyDef::kinematic(Shape::rect(0.2, 1.0))
                .position(vec2(-3.6, 1.0))
                .linear_velocity(vec2(1.0, 0.0))
                .angular_velocity(0.3),
        )
        .unwrap();
    for _ in 0..40 {
        world.step(1.0 / 60.0).unwrap();
    }
    world
}

/// One substep of `world`'s soft step, part-way through it (the bodies have moved by one
/// substep of their velocity): the states, every touching contact as a scalar constraint
/// in the solve order (colour by colour), the same contacts in SIMD bundles of `width`,
/// and the biases.
fn substep(
    world: &World,
    h: Real,
    width: Width,
) -> (Vec<BodyState>, Vec<ContactConstraint>, WideContacts, Bias) {
    let (bodies, awake, contacts, body_indices, colors) = world.solver_inputs();
    let mut states: Vec<BodyState> = bodies[awake.clone()]
        .iter()
        .map(|body| {
            let mut state = BodyState::from_body(body);
            if body.moves() {
                state.dp = state.v * h;
                state.dq = rotation(state.w * h);
            }
            state
        })
        .collect();
    states.push(BodyState::spare());
    let mut masses: Vec<BodyMass> = bodies[awake.clone()].iter().map(BodyMass::of).collect();
    masses.push(BodyMass::default());
    let (mut order, mut demoted, mut claims) = (Vec::new(), Vec::new(), Vec::new());
    let mut graph = ContactGraph::default();
    let check = ColorCheck {
        moves: |i: usize| masses[i].dynamic,
        awake: awake.clone(),
        body_indices: &body_indices,
        claims: &mut claims,
    };
    order_constraints(
        |i| contacts[i].serial(),
        &colors,
        Some(check),
        &mut order,
        &mut graph,
        &mut demoted,
    );
    let bias = Bias::new(&SolverParams::default(), h);
    let inputs = BundleInputs {
        awake,
        states: &states,
        masses: &masses,
        contacts,
        body_indices: &body_indices,
        order: &order,
        graph: &graph,
        soft: bias.soft,
        static_soft: bias.static_soft,
        warm_starting: true,
    };
    let mut wide = WideContacts::new(width);
    wide.prepare(&inputs);
    assert!(wide.overflow.is_empty() && demoted.is_empty());
    let constraints = order.iter().map(|&i| inputs.constraint(i)).collect();
    (states, constraints, wide, bias)
}

/// The wide solver's warm start, biased pass and relaxation over `states`.
fn solve_wide(states: &mut [BodyState], wide: &mut WideContacts, bias: &Bias) {
    wide.warm_start(states);
    for use_bias in [true, false] {
        wide.solve(states, bias.pass(use_bias), true);
    }
}

/// The widths this CPU runs.
fn widths() -> Vec<Width> {
    let mut widths = vec![Width::Four];
    if Width::widest() != Width::Four {
        widths.push(Width::widest());
    }
    widths
}

/// The wide solver, one lane per constraint, gives the scalar solver's results bit for bit
/// when both take the constraints in the same (colour) order (to single precision in the
/// double-precision build, whose lanes are single): warm start, a biased pass and a
/// relaxation, with the bodies part-way through a substep; at every width, and the same bits
/// at every width.
#[test]
fn the_wide_solver_gives_the_scalar_solvers_bits() {
    let world = pile();
    let mut at_each_width: Vec<Vec<BodyState>> = Vec::new();
    for width in widths() {
        let (mut states, mut constraints, mut wide, bias) = substep(&world, 1.0 / 240.0, width);
        assert!(constraints.len() > 30, "a pile has many contacts");
        assert!(
            constraints
                .iter()
                .any(|c| c.inv_mass_a == 0.0 || c.inv_mass_b == 0.0),
            "some touch the ground or the paddle"
        );
        let mut wide_states = states.clone();
        solve_wide(&mut wide_states, &mut wide, &bias);

        for c in constraints.iter_mut() {
            warm_start_one(c, &mut states);
        }
        for use_bias in [true, false] {
            for c in constraints.iter_mut() {
                solve_one(c, &mut states, &bias, use_bias, true);
            }
        }

        for (i, (scalar, wide)) in states.iter().zip(&wide_states).enumerate() {
            assert!(
                same_velocity(wide, scalar),
                "{width:?}, body {i}: scalar {scalar:?}, wide {wide:?}"
            );
        }
        let impulses = wide.impulses();
        for c in &constraints {
            let wide = impulses[&c.contact_index];
            for (p, q) in c.points().iter().zip(wide) {
                let scalar = (p.normal_impulse, p.tangent_impulse, p.total_normal_impulse);
                assert!(
                    agrees(q.0, scalar.0) && agrees(q.1, scalar.1) && agrees(q.2, scalar.2),
                    "{width:?}: wide {q:?}, scalar {scalar:?}"
                );
            }
        }
        at_each_width.push(wide_states);
    }
    let bits = |states: &[BodyState]| -> Vec<u64> {
        let floats = states.iter().flat_map(|s| [s.v.x, s.v.y, s.w]);
        floats.map(|x| x.to_bits() as u64).collect()
    };
    let first = bits(&at_each_width[0]);
    assert!(at_each_width.iter().all(|states| bits(states) == first));
}

/// Whether a body's velocities solved in lanes agree with those solved one at a time.
fn same_velocity(wide: &BodyState, scalar: &BodyState) -> bool {
    agrees(wide.v.x, scalar.v.x) && agrees(wide.v.y, scalar.v.y) && agrees(wide.w, scalar.w)
}

/// Impulses stored on several threads, the colours shared among them and a colour's bundles
/// split in halves down to one bundle, land in the same contacts as stored on one thread,
/// each lane's in its own.
#[test]
fn impulses_stored_in_halves_land_in_their_own_contacts() {
    let world = pile();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for width in widths() {
        let (mut states, _, mut wide, bias) = substep(&world, 1.0 / 240.0, width);
        solve_wide(&mut states, &mut wide, &bias);
        let awake = world.solver_inputs().2;
        let (mut whole, mut halves) = (awake.to_vec(), awake.to_vec());
        wide.store_in_tasks_of(&mut whole, usize::MAX / 2);
        pool.install(|| wide.store_in_tasks_of(&mut halves, 1));
        let impulses = wide.impulses();
        assert!(impulses.len() > 30, "a pile has many contacts");
        for (&index, points) in impulses.iter().filter(|(i, _)| **i != u32::MAX as usize) {
            for stored in [&whole, &halves] {
                let manifold = stored[index].manifold();
                for (p, q) in manifold.points().iter().zip(points) {
                    assert_eq!((p.normal_impulse, p.tangent_impulse), (q.0, q.1));
                }
            }
        }
    }
}

/// Static and kinematic bodies are only read by the wide solver: even an impulse gone bad
/// (NaN) in a lane with the ground or the paddle leaves their velocities as they were.
#[test]
fn the_wide_solver_never_writes_static_or_kinematic_velocities() {
    let world = pile();
    for width in widths() {
        let (mut states, constraints, mut wide, bias) = substep(&world, 1.0 / 240.0, width);
        let before = states.clone();
        let mut poisoned = 0;
        let fixed_body = |c: &&ContactConstraint| c.inv_mass_a == 0.0 || c.inv_mass_b == 0.0;
        for c in constraints.iter().filter(fixed_body) {
            wide.set_normal_impulse(c.contact_index, 0, Real::NAN);
            poisoned += 1;
        }
        assert!(poisoned >= 2);
        solve_wide(&mut states, &mut wide, &bias);
        let (bodies, awake, _, _, _) = world.solver_inputs();
        // The awake set's kinematic paddle, and the spare state the static ground reads.
        let kinds = bodies[awake].iter().map(|b| Some(b.kind())).chain([None]);
        let mut fixed = 0;
        for ((kind, after), before) in kinds.zip(&states).zip(&before) {
            if kind != Some(crate::BodyKind::Dynamic) {
                assert_eq!((after.v, after.w), (before.v, before.w), "{kind:?}");
                fixed += 1;
            }
        }
        assert_eq!(fixed, 2, "the paddle and the ground's spare state");
    }
}

/// Bounces in SIMD lanes give the scalar pass's bits (to single precision in the
/// double-precision build), and only bounce the points that
/// approached fast and pushed.
#[test]
fn wide_restitution_gives_the_scalar_bits() {
    let world = pile();
    for width in widths() {
        let (mut states, mut constraints, mut wide, bias) = substep(&world, 1.0 / 240.0, width);
        // Every contact bouncy; a few points approaching fast.
        for (k, c) in constraints.iter_mut().enumerate() {
            c.restitution = 0.5;
            wide.set_restitution(c.contact_index, 0.5);
            if k % 3 == 0 {
                let speed = -2.0 - k as Real * 0.1;
                c.points_mut()[0].relative_velocity = speed;
                wide.set_relative_velocity(c.contact_index, 0, speed);
            }
        }
        let mut wide_states = states.clone();
        solve_wide(&mut wide_states, &mut wide, &bias);
        let params = SolverParams::default();
        let wide_bounces = wide.restitution(&mut wide_states, params.restitution_threshold);
        for c in constraints.iter_mut() {
            warm_start_one(c, &mut states);
        }
        for use_bias in [true, false] {
            for c in constraints.iter_mut() {
                solve_one(c, &mut states, &bias, use_bias, true);
            }
        }
        let bounces = apply_restitution(&params, &mut constraints, &mut states);
        assert!(bounces > 5, "{bounces}");
        assert_eq!(wide_bounces, bounces);
        for (scalar, wide) in states.iter().zip(&wide_states) {
            assert!(
                same_velocity(wide, scalar),
                "wide {wide:?}, scalar {scalar:?}"
            );
        }
    }
}

/// A deep overlap is pushed apart at exactly the push cap: the cap bounds the softened
/// bias, not the bias before softening (which would make it about 6 % slower).
#[test]
fn a_deep_overlap_rises_at_the_push_cap() {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects = crate::Effects::NONE)
        .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    // A ball: one contact point, so one pass converges.
    let block = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 0.0)))
        .unwrap();
    let dt = 1.0 / 60.0;
    world.step(dt).unwrap();
    let risen = world.body(block).unwrap().position().y;
    let cap = world.solver().max_push_speed;
    assert!(
        (risen - cap * dt).abs() < 1e-5,
        "rose {risen}, cap x dt = {}",
        cap * dt
    );
}

/// A point that pushed this step only through its warm start still bounces: restitution
/// looks at the whole step's normal impulse, not just what the passes added.
#[test]
fn a_warm_started_point_counts_as_pushed_for_restitution() {
    let world = pile();
    let (mut states, mut constraints, _, _) = substep(&world, 1.0 / 240.0, Width::Four);
    let c = &mut constraints[0];
    c.restitution = 0.5;
    c.points_mut()[0].normal_impulse = 0.1;
    c.points_mut()[0].relative_velocity = -5.0;
    warm_start_one(c, &mut states);
    assert_eq!(c.points()[0].total_normal_impulse, 0.1);
    let params = SolverParams::default();
    let bounced = apply_restitution(&params, &mut constraints[..1], &mut states);
    assert_eq!(bounced, 1);
}
