//! The contact passes one constraint at a time: warm starting, the soft non-penetration and
//! friction impulses, and restitution. Soft step runs them for the overflow's constraints
//! (those no colour was free for), the SIMD kernels the same four or eight at a time; the
//! sequential-impulse solver shares warm starting, friction and restitution.

use super::Bias;
use crate::math::Real;
use crate::solver::body_state::BodyState;
use crate::solver::contact_constraint::ContactConstraint;
use crate::solver::contact_constraint::pair_mut;
use crate::solver::params::{Softness, SolverParams};

/// Starts from zero impulses (warm starting off).
pub(crate) fn forget_impulses(constraints: &mut [ContactConstraint]) {
    for c in constraints.iter_mut() {
        for point in c.points_mut() {
            point.normal_impulse = 0.0;
            point.tangent_impulse = 0.0;
        }
        c.rolling_impulse = 0.0;
    }
}

/// Applies the accumulated impulses, so the solve starts near last time's answer.
pub(crate) fn warm_start(constraints: &mut [ContactConstraint], states: &mut [BodyState]) {
    for c in constraints {
        warm_start_one(c, states);
    }
}

/// Applies one constraint's accumulated impulses (and counts them as pushed this step).
pub(crate) fn warm_start_one(c: &mut ContactConstraint, states: &mut [BodyState]) {
    let (a, b) = pair_mut(states, c.a, c.b);
    let tangent = c.tangent();
    for i in 0..c.points().len() {
        let point = c.points()[i];
        let p = c.normal * point.normal_impulse + tangent * point.tangent_impulse;
        c.apply(&point, p, a, b);
        c.points_mut()[i].total_normal_impulse += point.normal_impulse;
    }
    if c.rolling_resistance > 0.0 {
        a.w -= c.inv_inertia_a * c.rolling_impulse;
        b.w += c.inv_inertia_b * c.rolling_impulse;
    }
}

/// One constraint: non-penetration with the soft bias (or none when relaxing), then Coulomb
/// friction if asked (in both passes by default, as Box2D v3.1; in the relaxation only with
/// `friction_in_bias_pass` off, as Box2D 3.2 and Rapier). The wide solver does the same four
/// constraints at a time; this one serves the constraints no colour was free for.
pub(crate) fn solve_one(
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
        let (velocity_bias, mass_scale, impulse_scale) = point_bias(s, softness, bias, use_bias);
        let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
        let impulse = -point.normal_mass * (mass_scale * vn + velocity_bias)
            - impulse_scale * point.normal_impulse;
        c.add_normal_impulse(i, impulse, a, b);
    }
    if friction {
        solve_friction(c, a, b);
    }
}

/// How a point `s` apart (negative: overlapping) is solved in a pass, biased or relaxing:
/// its velocity bias, and the soft constraint's mass and impulse scales.
#[inline]
pub(crate) fn point_bias(
    s: Real,
    softness: Softness,
    bias: &Bias,
    use_bias: bool,
) -> (Real, Real, Real) {
    if s > 0.0 {
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
    }
}

/// Coulomb friction at each point: the tangent impulse stays within `μ ×` the normal one,
/// driving the relative tangent velocity to the surfaces' tangent speed; then rolling
/// resistance, whose angular impulse stays within its coefficient times the contact's
/// normal impulse. Returns how many impulses were computed.
pub(crate) fn solve_friction(
    c: &mut ContactConstraint,
    a: &mut BodyState,
    b: &mut BodyState,
) -> usize {
    let tangent = c.tangent();
    for i in 0..c.points().len() {
        let mut point = c.points()[i];
        let vt = ContactConstraint::relative_velocity(&point, a, b).dot(&tangent) - c.tangent_speed;
        let limit = c.friction * point.normal_impulse;
        let total = (point.tangent_impulse - point.tangent_mass * vt).clamp(-limit, limit);
        let applied = total - point.tangent_impulse;
        point.tangent_impulse = total;
        c.apply(&point, tangent * applied, a, b);
        c.points_mut()[i] = point;
    }
    if c.rolling_resistance > 0.0 {
        let pressed: Real = c.points().iter().map(|p| p.normal_impulse).sum();
        let limit = c.rolling_resistance * pressed;
        let spin = b.w - a.w;
        let total = (c.rolling_impulse - c.rolling_mass * spin).clamp(-limit, limit);
        let applied = total - c.rolling_impulse;
        c.rolling_impulse = total;
        a.w -= c.inv_inertia_a * applied;
        b.w += c.inv_inertia_b * applied;
    }
    c.points().len()
}

/// Bounces: points that approached faster than the threshold and pushed this step (warm start
/// included, as Box2D) get a
/// normal velocity of `-restitution ×` their approach speed. Returns how many impulses were
/// computed.
pub(crate) fn apply_restitution(
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
