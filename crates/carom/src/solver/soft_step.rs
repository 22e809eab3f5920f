//! Box2D v3's soft step: substeps with soft contacts, relaxation and a restitution pass.
//!
//! Per substep: integrate velocities, warm start, solve with a soft-constraint bias (a stiff,
//! heavily damped spring pulls overlap out at a bounded speed), integrate positions, then
//! relax (solve again without bias, so the push-out leaves no energy behind). Anchors stay
//! fixed for the step; each point's separation is updated from the bodies' motion.

use super::body_state::{integrate_positions, integrate_velocities};
use super::contact_constraint::pair_mut;
use super::contact_graph::ContactGraph;
use super::wide_contacts::{PassBias, SharedVelocities, WideContacts};
use super::{BodyState, ContactConstraint, Softness, SolverContext, SolverParams};
use crate::math::Real;
use crate::stats::Work;

pub(super) fn solve(
    context: &SolverContext,
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
    graph: &mut ContactGraph,
    wide: &mut WideContacts,
    velocities: &mut SharedVelocities,
) -> Work {
    let SolverContext {
        params,
        environment,
        bodies,
        dt,
    } = *context;
    let substeps = params.substeps.max(1);
    let h = dt / substeps as Real;
    let inv_h = 1.0 / h;
    // Stiffer than a quarter of the substep rate would ring.
    let hertz = params.contact_hertz.min(0.25 * inv_h);
    let bias = Bias {
        soft: Softness::new(hertz, params.damping_ratio, h),
        static_soft: Softness::new(params.static_stiffness * hertz, params.damping_ratio, h),
        inv_h,
        max_push_speed: params.max_push_speed,
    };
    if !params.warm_starting {
        forget_impulses(constraints);
    }
    // The last state is a spare for the empty lanes of the last bundle of each colour.
    let spare = states.len() - 1;
    if params.graph_coloring {
        graph.build(constraints, states.len());
    } else {
        graph.leave_uncolored(constraints.len());
    }
    wide.build(constraints, graph, bias.soft, bias.static_soft, spare);
    let pass = |use_bias| PassBias {
        use_bias,
        inv_h,
        max_push_speed: params.max_push_speed,
    };
    let bias_friction = environment.friction && params.friction_in_bias_pass;
    let points: usize = constraints.iter().map(|c| c.points().len()).sum();
    let mut work = Work::default();
    // The wide passes work on the shared velocities, the rest on the states: the velocities
    // cross over only where the other side needs them.
    let overflow = !wide.overflow.is_empty();
    for _ in 0..substeps {
        work += integrate_velocities(params, environment, bodies, states, h);
        velocities.load(states);
        wide.warm_start(states, velocities);
        if overflow {
            velocities.store(states);
            for &index in &wide.overflow {
                warm_start_one(&constraints[index], states);
            }
            velocities.load(states);
        }
        for _ in 0..params.iterations {
            wide.solve(states, velocities, pass(true), bias_friction);
            if overflow {
                velocities.store(states);
                for &index in &wide.overflow {
                    solve_one(&mut constraints[index], states, &bias, true, bias_friction);
                }
                velocities.load(states);
            }
            if bias_friction {
                work.friction_impulses += points;
            }
        }
        velocities.store(states);
        integrate_positions(bodies, states, h);
        velocities.load(states);
        for _ in 0..params.iterations {
            wide.solve(states, velocities, pass(false), environment.friction);
            if overflow {
                velocities.store(states);
                for &index in &wide.overflow {
                    solve_one(
                        &mut constraints[index],
                        states,
                        &bias,
                        false,
                        environment.friction,
                    );
                }
                velocities.load(states);
            }
            if environment.friction {
                work.friction_impulses += points;
            }
        }
        velocities.store(states);
    }
    wide.store(constraints);
    if environment.restitution {
        work.restitution_impulses = apply_restitution(params, constraints, states);
    }
    work
}

/// How the biased pass pushes overlap out in one substep.
struct Bias {
    /// Softness of contacts between moving bodies.
    soft: Softness,
    /// Softness of contacts with static bodies (stiffer).
    static_soft: Softness,
    /// One over the substep.
    inv_h: Real,
    /// The fastest push-out, m/s.
    max_push_speed: Real,
}

/// Starts from zero impulses (warm starting off).
pub(super) fn forget_impulses(constraints: &mut [ContactConstraint]) {
    for point in constraints.iter_mut().flat_map(|c| c.points_mut()) {
        point.normal_impulse = 0.0;
        point.tangent_impulse = 0.0;
    }
}

/// Applies the accumulated impulses, so the solve starts near last time's answer.
pub(super) fn warm_start(constraints: &[ContactConstraint], states: &mut [BodyState]) {
    for c in constraints {
        warm_start_one(c, states);
    }
}

/// Applies one constraint's accumulated impulses.
fn warm_start_one(c: &ContactConstraint, states: &mut [BodyState]) {
    let (a, b) = pair_mut(states, c.a, c.b);
    let tangent = c.tangent();
    for point in c.points() {
        let p = c.normal * point.normal_impulse + tangent * point.tangent_impulse;
        c.apply(point, p, a, b);
    }
}

/// One constraint: non-penetration with the soft bias (or none when relaxing), then Coulomb
/// friction if asked (in both passes by default, as Box2D v3.1; in the relaxation only with
/// `friction_in_bias_pass` off, as Box2D 3.2 and Rapier). The wide solver does the same four
/// constraints at a time; this one serves the constraints no colour was free for.
fn solve_one(
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
            (
                (softness.bias_rate * s).max(-bias.max_push_speed),
                softness.mass_scale,
                softness.impulse_scale,
            )
        } else {
            (0.0, 1.0, 0.0)
        };
        let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
        let impulse = -point.normal_mass * mass_scale * (vn + velocity_bias)
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

/// Bounces: points that approached faster than the threshold and pushed this step get a
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
                || point.max_normal_impulse == 0.0
            {
                continue;
            }
            impulses += 1;
            let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
            let impulse = -point.normal_mass * (vn + c.restitution * point.relative_velocity);
            c.add_normal_impulse(i, impulse, a, b);
        }
    }
    impulses
}
