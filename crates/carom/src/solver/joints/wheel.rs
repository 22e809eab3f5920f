//! The wheel joint: B's anchor stays on the line through A's along the axis (a point-on-line
//! constraint), sprung along it (the suspension) within limits, and B turns freely, driven by
//! a motor. Solved in Box2D's order: motor, spring, limits, then the line.

use super::prismatic::{Slide, axial_impulse, stop};
use super::{JointConstraint, JointPass, inverse_or_zero, solve_limits, spring_softness};
use crate::joint::WheelJoint;
use crate::math::Real;
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    pub settings: WheelJoint,
    spring: Softness,
    /// `1 / (iA + iB)`: the mass the motor turns.
    motor_mass: Real,
}

pub(super) fn prepare(c: &JointConstraint, settings: WheelJoint, h: Real) -> Prepared {
    let (_, ia, _, ib) = c.masses();
    let spring = spring_softness(settings.spring, h);
    Prepared {
        settings,
        spring,
        motor_mass: inverse_or_zero(ia + ib),
    }
}

pub(super) fn warm_start(c: &JointConstraint, p: &Prepared, a: &mut BodyState, b: &mut BodyState) {
    let slide = Slide::now(c, a, b, p.settings.axis);
    let (a1, a2) = slide.arms(slide.axis);
    let (s1, s2) = slide.arms(slide.perp);
    let i = &c.impulses;
    let axial = i.axial + i.lower - i.upper;
    let linear = slide.axis * axial + slide.perp * i.linear.x;
    let la = axial * a1 + i.linear.x * s1 + i.motor;
    let lb = axial * a2 + i.linear.x * s2 + i.motor;
    super::prismatic::apply(c, a, b, linear, la, lb);
}

pub(super) fn solve(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    let settings = &p.settings;
    let mut impulses = c.impulses;
    if let (true, Some(motor)) = (pass.drive && p.motor_mass > 0.0, settings.motor) {
        let impulse = -p.motor_mass * (b.w - a.w - motor.speed);
        let old = impulses.motor;
        let max = pass.h * motor.max_force;
        impulses.motor = (old + impulse).clamp(-max, max);
        c.apply_angular(a, b, impulses.motor - old);
    }
    let slide = Slide::now(c, a, b, settings.axis);
    let translation = slide.axis.dot(&slide.d);
    let arms = slide.arms(slide.axis);
    if pass.drive && settings.spring.is_some_and(|s| s.hertz > 0.0) {
        let s = p.spring;
        let scales = (s.bias_rate * translation, s.mass_scale, s.impulse_scale);
        let free = (Real::NEG_INFINITY, Real::INFINITY);
        axial_impulse(c, a, b, slide.axis, arms, scales, &mut impulses.axial, free);
    }
    if let Some(limits) = settings.limits {
        let (lower, upper) = (&mut impulses.lower, &mut impulses.upper);
        solve_limits(
            translation,
            limits,
            (lower, upper),
            pass,
            |scales, impulse, upper| stop(c, a, b, slide.axis, arms, scales, impulse, upper),
        );
    }
    // On the line.
    let perp_arms = slide.arms(slide.perp);
    let scales = pass.rigid(slide.perp.dot(&slide.d));
    let free = (Real::NEG_INFINITY, Real::INFINITY);
    axial_impulse(
        c,
        a,
        b,
        slide.perp,
        perp_arms,
        scales,
        &mut impulses.linear.x,
        free,
    );
    c.impulses = impulses;
}
