//! Box2D v3's soft step: substeps with soft contacts, relaxation and a restitution pass.
//!
//! Per substep: integrate velocities, warm start, solve with a soft-constraint bias (a stiff,
//! heavily damped spring pulls overlap out at a bounded speed), integrate positions, then
//! relax (solve again without bias, so the push-out leaves no energy behind). Anchors stay
//! fixed for the step; each point's separation is updated from the bodies' motion. Joints are
//! solved the same way, after the contacts in each pass ([`super::joints`]).

use super::body_state::SpeedCaps;
use super::contact_constraint::pair_mut;
use super::joints::{JointColors, JointConstraint};
use super::wide_contacts::{Pass, PassBias, Stage, StageInputs, WideContacts};
use super::{BodyState, ContactConstraint, Environment, Softness, SolverContext, SolverParams};
use crate::math::Real;
use crate::stats::Work;

/// One step in Box2D's stage order: per substep, integrate velocities, warm start, solve
/// (biased), integrate positions, relax (unbiased); then restitution. Each contact pass runs
/// colour by colour over `wide`'s SIMD bundles, already prepared, then over `constraints`,
/// the overflow's, one by one. The stage list is built here and run by
/// [`WideContacts::execute`] on as many threads as rayon gives, in one parallel region.
/// `bias` is for the step's substeps (the bundles were prepared with its softness).
pub(super) fn solve(
    context: &SolverContext,
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
    (joints, joint_colors): (&mut [JointConstraint], &JointColors),
    wide: &mut WideContacts,
    plan: &mut Vec<Stage>,
    bias: &Bias,
) -> Work {
    let SolverContext {
        params,
        environment,
        bodies,
        dt,
    } = *context;
    let substeps = params.substeps.max(1);
    let h = dt / substeps as Real;
    let bias_friction = environment.friction && params.friction_in_bias_pass;
    let bouncy = wide.bouncy() || constraints.iter().any(|c| c.restitution > 0.0);
    let shape = (wide.color_count(), !constraints.is_empty(), bouncy);
    plan_stages(plan, params, environment, bias, joint_colors, shape);
    let inputs = StageInputs {
        bodies,
        environment,
        h,
        caps: SpeedCaps::new(params, dt),
        bias,
        params,
    };
    let (mut work, bounces) =
        wide.execute(plan, states, constraints, (joints, joint_colors), &inputs);
    let points = wide.point_count() + constraints.iter().map(|c| c.points().len()).sum::<usize>();
    let friction_passes = u32::from(bias_friction) + u32::from(environment.friction);
    work.friction_impulses = points * (friction_passes * params.iterations * substeps) as usize;
    work.restitution_impulses = bounces;
    work
}

/// The stages of one step, into `plan`: each pass over the contacts' `colors` colours in turn,
/// then the contacts' overflow if it has constraints, then the joint colours that have joints
/// (the last being their overflow); the restitution pass (contacts only) only if `bouncy`
/// (some contact has restitution: the pass does nothing for the others). Joints have the last
/// word in each pass, as contacts with the ground have among contacts: a limb struck in a pile
/// is pulled back onto its joint before the pass ends. (Box2D solves joints first; in a pile
/// of ragdolls that parts their joints about twice as far.)
fn plan_stages(
    plan: &mut Vec<Stage>,
    params: &SolverParams,
    environment: Environment,
    bias: &Bias,
    joint_colors: &JointColors,
    (colors, overflow, bouncy): (usize, bool, bool),
) {
    plan.clear();
    let pass = |plan: &mut Vec<Stage>, pass: Pass| {
        plan.extend((0..colors).map(|color| Stage::Color(color, pass)));
        if overflow {
            plan.push(Stage::Overflow(pass));
        }
        if !matches!(pass, Pass::Restitution(_)) {
            let joints = joint_colors.ranges.iter().enumerate();
            let used = joints.filter(|(_, range)| !range.is_empty());
            plan.extend(used.map(|(color, _)| Stage::Joints(color, pass)));
        }
    };
    let bias_friction = environment.friction && params.friction_in_bias_pass;
    for _ in 0..params.substeps.max(1) {
        plan.push(Stage::IntegrateVelocities);
        pass(plan, Pass::WarmStart);
        for _ in 0..params.iterations {
            pass(plan, Pass::Solve(bias.pass(true), bias_friction));
        }
        plan.push(Stage::IntegratePositions);
        for i in 0..params.iterations {
            let relax = PassBias {
                substep_end: i + 1 == params.iterations,
                ..bias.pass(false)
            };
            pass(plan, Pass::Solve(relax, environment.friction));
        }
    }
    if environment.restitution && bouncy {
        pass(plan, Pass::Restitution(params.restitution_threshold));
    }
}

/// How the biased pass pushes overlap out in one substep.
pub(super) struct Bias {
    /// Softness of contacts between moving bodies.
    pub soft: Softness,
    /// Softness of contacts with static bodies (stiffer).
    pub static_soft: Softness,
    /// One over the substep.
    inv_h: Real,
    /// The fastest push-out, m/s.
    max_push_speed: Real,
}

impl Bias {
    /// The biases of `params` for substeps of `h`.
    pub fn new(params: &SolverParams, h: Real) -> Self {
        let inv_h = 1.0 / h;
        // Stiffer than a quarter of the substep rate would ring.
        let hertz = params.contact_hertz.min(0.25 * inv_h);
        Bias {
            soft: Softness::new(hertz, params.damping_ratio, h),
            static_soft: Softness::new(params.static_stiffness * hertz, params.damping_ratio, h),
            inv_h,
            max_push_speed: params.max_push_speed,
        }
    }

    /// What the wide solver needs of it for one pass, biased or relaxing.
    pub fn pass(&self, use_bias: bool) -> PassBias {
        PassBias {
            use_bias,
            inv_h: self.inv_h,
            max_push_speed: self.max_push_speed,
            substep_end: false,
        }
    }
}

/// Starts from zero impulses (warm starting off).
pub(super) fn forget_impulses(constraints: &mut [ContactConstraint]) {
    for point in constraints.iter_mut().flat_map(|c| c.points_mut()) {
        point.normal_impulse = 0.0;
        point.tangent_impulse = 0.0;
    }
}

/// Applies the accumulated impulses, so the solve starts near last time's answer.
pub(super) fn warm_start(constraints: &mut [ContactConstraint], states: &mut [BodyState]) {
    for c in constraints {
        warm_start_one(c, states);
    }
}

/// Applies one constraint's accumulated impulses (and counts them as pushed this step).
pub(super) fn warm_start_one(c: &mut ContactConstraint, states: &mut [BodyState]) {
    let (a, b) = pair_mut(states, c.a, c.b);
    let tangent = c.tangent();
    for i in 0..c.points().len() {
        let point = c.points()[i];
        let p = c.normal * point.normal_impulse + tangent * point.tangent_impulse;
        c.apply(&point, p, a, b);
        c.points_mut()[i].total_normal_impulse += point.normal_impulse;
    }
}

/// One constraint: non-penetration with the soft bias (or none when relaxing), then Coulomb
/// friction if asked (in both passes by default, as Box2D v3.1; in the relaxation only with
/// `friction_in_bias_pass` off, as Box2D 3.2 and Rapier). The wide solver does the same four
/// constraints at a time; this one serves the constraints no colour was free for.
pub(super) fn solve_one(
    c: &mut ContactConstraint,
    states: &mut [BodyState],
    bias: &Bias,
    use_bias: bool,
    friction: bool,
) {
    let (a, b) = pair_mut(states, c.a, c.b);
    let softness = if c.touches_static {
        bias.static_soft
    } else {
        bias.soft
    };
    for i in 0..c.points().len() {
        let point = c.points()[i];
        let s = c.current_separation(&point, a, b);
        let (velocity_bias, mass_scale, impulse_scale) = if s > 0.0 {
            // Speculative: may close exactly the gap this substep.
            (s * bias.inv_h, 1.0, 0.0)
        } else if use_bias {
            // The push-out speed capped after softening, so the cap is the real speed.
            (
                (softness.mass_scale * softness.bias_rate * s).max(-bias.max_push_speed),
                softness.mass_scale,
                softness.impulse_scale,
            )
        } else {
            (0.0, 1.0, 0.0)
        };
        let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
        let impulse = -point.normal_mass * (mass_scale * vn + velocity_bias)
            - impulse_scale * point.normal_impulse;
        c.add_normal_impulse(i, impulse, a, b);
    }
    if friction {
        solve_friction(c, a, b);
    }
}

/// Coulomb friction at each point: the tangent impulse stays within `μ ×` the normal one.
/// Returns how many impulses were computed.
pub(super) fn solve_friction(
    c: &mut ContactConstraint,
    a: &mut BodyState,
    b: &mut BodyState,
) -> usize {
    let tangent = c.tangent();
    for i in 0..c.points().len() {
        let mut point = c.points()[i];
        let vt = ContactConstraint::relative_velocity(&point, a, b).dot(&tangent);
        let limit = c.friction * point.normal_impulse;
        let total = (point.tangent_impulse - point.tangent_mass * vt).clamp(-limit, limit);
        let applied = total - point.tangent_impulse;
        point.tangent_impulse = total;
        c.apply(&point, tangent * applied, a, b);
        c.points_mut()[i] = point;
    }
    c.points().len()
}

/// Bounces: points that approached faster than the threshold and pushed this step (warm start
/// included, as Box2D) get a
/// normal velocity of `-restitution ×` their approach speed. Returns how many impulses were
/// computed.
pub(super) fn apply_restitution(
    params: &SolverParams,
    constraints: &mut [ContactConstraint],
    states: &mut [BodyState],
) -> usize {
    let mut impulses = 0;
    for c in constraints.iter_mut().filter(|c| c.restitution > 0.0) {
        let (a, b) = pair_mut(states, c.a, c.b);
        for i in 0..c.points().len() {
            let point = c.points()[i];
            if point.relative_velocity > -params.restitution_threshold
                || point.total_normal_impulse == 0.0
            {
                continue;
            }
            impulses += 1;
            let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
            let impulse = -point.normal_mass * (vn + c.restitution * point.relative_velocity);
            c.add_normal_impulse(i, impulse, a, b);
            let point = &mut c.points_mut()[i];
            point.max_normal_impulse = point.max_normal_impulse.max(point.normal_impulse);
        }
    }
    impulses
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body::BodyDef;
    use crate::geometry::shape::Shape;
    use crate::math::{rotation, vec2};
    use crate::solver::contact_constraint::BodyMass;
    use crate::solver::contact_graph::ContactGraph;
    use crate::solver::wide_contacts::{BundleInputs, Width};
    use crate::solver::{ColorCheck, order_constraints};
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
            masses: &masses,
            awake: awake.clone(),
            body_indices: &body_indices,
            claims: &mut claims,
        };
        order_constraints(
            contacts,
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
    /// when both take the constraints in the same (colour) order: warm start, a biased pass
    /// and a relaxation, with the bodies part-way through a substep; at every width.
    #[test]
    fn the_wide_solver_gives_the_scalar_solvers_bits() {
        let world = pile();
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
                    scalar.v == wide.v && scalar.w == wide.w,
                    "{width:?}, body {i}: scalar {scalar:?}, wide {wide:?}"
                );
            }
            let impulses = wide.impulses();
            for c in &constraints {
                let wide = impulses[&c.contact_index];
                for (p, q) in c.points().iter().zip(wide) {
                    assert_eq!(
                        (p.normal_impulse, p.tangent_impulse, p.total_normal_impulse),
                        q
                    );
                }
            }
        }
    }

    /// Impulses stored on several threads, a colour's bundles split in halves down to one
    /// bundle, land in the same contacts as stored on one thread, each lane's in its own.
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

    /// Bounces in SIMD lanes give the scalar pass's bits, and only bounce the points that
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
                assert!(scalar.v == wide.v && scalar.w == wide.w);
            }
        }
    }

    /// A deep overlap is pushed apart at exactly the push cap: the cap bounds the softened
    /// bias, not the bias before softening (which would make it about 6 % slower).
    #[test]
    fn a_deep_overlap_rises_at_the_push_cap() {
        let mut world = World::new();
        world.set_effects(crate::Effects::NONE);
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
}
