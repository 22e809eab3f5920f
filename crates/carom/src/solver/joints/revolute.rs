//! The revolute joint: a hinge. The anchors coincide (a 2x2 point constraint); the angle may
//! be held within limits, driven by a motor, or pulled toward a target by a spring. Solved in
//! Box2D's order: spring, motor, limits, then the point, so the point constraint, which
//! matters most, has the last word.

use super::{
    JointConstraint, JointPass, inverse_or_zero, push_only, solve_limits, solve22, spring_softness,
};
use crate::joint::{Limits, RevoluteJoint};
use crate::math::{Real, unwind_angle};
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    settings: RevoluteJoint,
    /// `1 / (iA + iB)`: the mass the angle feels.
    axial_mass: Real,
    spring: Softness,
}

impl Prepared {
    /// Its limits, if it has them and its angle can turn.
    pub(super) fn limits(&self) -> Option<Limits> {
        self.settings.limits.filter(|_| self.axial_mass > 0.0)
    }
}

pub(super) fn prepare(c: &JointConstraint, settings: RevoluteJoint, h: Real) -> Prepared {
    let (_, ia, _, ib) = c.masses();
    let spring = spring_softness(settings.spring, h);
    Prepared {
        settings,
        axial_mass: inverse_or_zero(ia + ib),
        spring,
    }
}

pub(super) fn warm_start(c: &JointConstraint, a: &mut BodyState, b: &mut BodyState) {
    let (ra, rb) = c.anchors(a, b);
    let i = &c.impulses;
    if c.point_in_tree {
        // The tree warm starts the point and the limits.
        c.apply_angular(a, b, i.axial + i.motor);
    } else {
        c.apply_angular(a, b, i.axial + i.motor + i.lower - i.upper);
        c.apply_linear(a, b, ra, rb, i.linear);
    }
}

pub(super) fn solve(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    let settings = &p.settings;
    let turns = p.axial_mass > 0.0;
    if pass.drive && turns && settings.spring.is_some_and(|s| s.hertz > 0.0) {
        let error = unwind_angle(c.angle(a, b) - settings.target_angle);
        let s = p.spring;
        let impulse = -s.mass_scale * p.axial_mass * (b.w - a.w + s.bias_rate * error)
            - s.impulse_scale * c.impulses.axial;
        c.impulses.axial += impulse;
        c.apply_angular(a, b, impulse);
    }
    if let (true, Some(motor)) = (pass.drive && turns, settings.motor) {
        let impulse = -p.axial_mass * (b.w - a.w - motor.speed);
        let old = c.impulses.motor;
        let max = pass.h * motor.max_force;
        c.impulses.motor = (old + impulse).clamp(-max, max);
        c.apply_angular(a, b, c.impulses.motor - old);
    }
    if let (false, Some(limits)) = (c.point_in_tree, p.limits()) {
        let angle = c.angle(a, b);
        let mut impulses = (c.impulses.lower, c.impulses.upper);
        let (lower, upper) = (&mut impulses.0, &mut impulses.1);
        solve_limits(
            angle,
            limits,
            (lower, upper),
            pass,
            |scales, accumulated, upper| {
                // The upper stop is the lower one with the signs flipped.
                let speed = if upper { a.w - b.w } else { b.w - a.w };
                let applied = push_only(scales, accumulated, p.axial_mass, speed);
                c.apply_angular(a, b, if upper { -applied } else { applied });
            },
        );
        (c.impulses.lower, c.impulses.upper) = impulses;
    }
    // The point, unless the joint trees solve it (and the limits with it).
    if c.point_in_tree {
        return;
    }
    let (ra, rb) = c.anchors(a, b);
    let velocity = JointConstraint::relative_velocity(a, b, ra, rb);
    let (bias, mass_scale, impulse_scale) = if pass.use_bias {
        let s = pass.softness;
        let separation = c.separation(a, b, ra, rb);
        (separation * s.bias_rate, s.mass_scale, s.impulse_scale)
    } else {
        (crate::math::Vec2::zeros(), 1.0, 0.0)
    };
    let k = c.point_mass(ra, rb);
    let impulse = -solve22(k, velocity + bias) * mass_scale - c.impulses.linear * impulse_scale;
    c.impulses.linear += impulse;
    c.apply_linear(a, b, ra, rb, impulse);
}
