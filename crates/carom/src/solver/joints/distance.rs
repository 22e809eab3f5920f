//! The distance joint: a rigid rod between the anchors, or a spring with stops (a rope is a
//! spring of 0 Hz stopped at its length).
//!
//! `C = |d| - L` along the unit `u = d / |d|`, `d` from A's anchor to B's; `J = [-u, -rA × u,
//! u, rB × u]`. The axis is taken once per step (the anchors move little in one).

use super::{
    JointConstraint, JointPass, inverse_or_zero, push_only, solve_limits, spring_softness,
};
use crate::joint::DistanceJoint;
use crate::math::{Real, Vec2, cross};
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    pub settings: DistanceJoint,
    /// The direction from A's anchor to B's at the start of the step.
    pub axis: Vec2,
    axial_mass: Real,
    spring: Softness,
}

pub(super) fn prepare(c: &JointConstraint, settings: DistanceJoint, h: Real) -> Prepared {
    let (ra, rb) = (c.frame.frame_a, c.frame.frame_b);
    let d = c.frame.delta_center + rb - ra;
    let length = d.norm();
    let axis = if length > 1.0e-9 {
        d / length
    } else {
        Vec2::new(0.0, 1.0)
    };
    let (ma, ia, mb, ib) = c.masses();
    let (cra, crb) = (cross(ra, axis), cross(rb, axis));
    let spring = spring_softness(settings.spring, h);
    Prepared {
        settings,
        axis,
        axial_mass: inverse_or_zero(ma + mb + ia * cra * cra + ib * crb * crb),
        spring,
    }
}

pub(super) fn warm_start(c: &JointConstraint, p: &Prepared, a: &mut BodyState, b: &mut BodyState) {
    let (ra, rb) = c.anchors(a, b);
    let axis = axis_now(c, a, b, ra, rb, p.axis).0;
    let i = &c.impulses;
    let mut total = i.axial + i.lower - i.upper;
    // A motor taken away leaves no impulse to start from.
    if p.settings.motor.is_some() {
        total += i.motor;
    }
    c.apply_linear(a, b, ra, rb, axis * total);
}

/// The axis and length now.
fn axis_now(
    c: &JointConstraint,
    a: &BodyState,
    b: &BodyState,
    ra: Vec2,
    rb: Vec2,
    fallback: Vec2,
) -> (Vec2, Real) {
    let d = c.separation(a, b, ra, rb);
    let length = d.norm();
    if length > 1.0e-9 {
        (d / length, length)
    } else {
        (fallback, length)
    }
}

pub(super) fn solve(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    let (ra, rb) = c.anchors(a, b);
    let (axis, length) = axis_now(c, a, b, ra, rb, p.axis);
    let speed =
        |a: &BodyState, b: &BodyState| JointConstraint::relative_velocity(a, b, ra, rb).dot(&axis);
    let settings = &p.settings;
    let Some(spring) = settings.spring else {
        // A rigid rod.
        let (bias, mass_scale, impulse_scale) = pass.rigid(length - settings.length);
        let impulse =
            -mass_scale * p.axial_mass * (speed(a, b) + bias) - impulse_scale * c.impulses.axial;
        c.impulses.axial += impulse;
        c.apply_linear(a, b, ra, rb, axis * impulse);
        return;
    };
    if pass.drive && spring.hertz > 0.0 {
        let bias = p.spring.bias_rate * (length - settings.length);
        let impulse = -p.spring.mass_scale * p.axial_mass * (speed(a, b) + bias)
            - p.spring.impulse_scale * c.impulses.axial;
        let applied = match settings.spring_force {
            None => impulse,
            Some(range) => {
                let total =
                    (c.impulses.axial + impulse).clamp(range.lower * pass.h, range.upper * pass.h);
                total - c.impulses.axial
            }
        };
        c.impulses.axial += applied;
        c.apply_linear(a, b, ra, rb, axis * applied);
    }
    if settings.motor.is_none() {
        c.impulses.motor = 0.0;
    }
    if pass.drive
        && let Some(motor) = settings.motor
    {
        let impulse = p.axial_mass * (motor.speed - speed(a, b));
        let limit = motor.max_force * pass.h;
        let total = (c.impulses.motor + impulse).clamp(-limit, limit);
        let applied = total - c.impulses.motor;
        c.impulses.motor = total;
        c.apply_linear(a, b, ra, rb, axis * applied);
    }
    if let Some(limits) = settings.limits {
        let mut impulses = (c.impulses.lower, c.impulses.upper);
        let (lower, upper) = (&mut impulses.0, &mut impulses.1);
        solve_limits(
            length,
            limits,
            (lower, upper),
            pass,
            |scales, accumulated, upper| {
                // The upper stop is the lower one with the signs flipped.
                let closing = if upper { -speed(a, b) } else { speed(a, b) };
                let applied = push_only(scales, accumulated, p.axial_mass, closing);
                c.apply_linear(a, b, ra, rb, axis * if upper { -applied } else { applied });
            },
        );
        (c.impulses.lower, c.impulses.upper) = impulses;
    }
}
