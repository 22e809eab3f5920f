//! The pogo joint (Box2D's): a leg. Its spring is a unit-mass oscillator on the leg's
//! length (along B's up), advanced once per (sub)step; the speed it gives is the target of
//! one bounded row along the ground's normal, pushing at most `max_compression` and pulling
//! at most `max_tension`. The relaxing pass drives that row to rest instead, so the spring
//! moves the body without leaving it the spring's speed: a correction of position, which
//! keeps the leg from launching a character up a stair.

use super::{JointConstraint, JointPass, inverse_or_zero};
use crate::joint::PogoJoint;
use crate::math::{Real, Vec2, cross};
use crate::solver::body_state::BodyState;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    settings: PogoJoint,
    /// The ground's normal in the world, for the step.
    pub(super) normal: Vec2,
    /// B's up in the world at the start of the step: the leg's length is measured along it.
    up: Vec2,
    mass: Real,
    h: Real,
}

/// Prepares the joint for (sub)steps of `h`, with B's up `up`.
pub(super) fn prepare(c: &JointConstraint, settings: PogoJoint, h: Real, up: Vec2) -> Prepared {
    let normal = c.rot_a * settings.normal;
    let (ma, ia, mb, ib) = c.masses();
    let (ra, rb) = (
        cross(c.frame.frame_a, normal),
        cross(c.frame.frame_b, normal),
    );
    Prepared {
        settings,
        normal,
        up,
        mass: inverse_or_zero(ma + mb + ia * ra * ra + ib * rb * rb),
        h,
    }
}

/// Advances the leg's spring by one (sub)step from where the bodies are now; called once
/// per (sub)step, before the warm start.
pub(super) fn advance_spring(c: &mut JointConstraint, p: &Prepared, a: &BodyState, b: &BodyState) {
    let spring = p.settings.spring;
    if spring.hertz == 0.0 {
        c.impulses.spring_velocity = 0.0;
        return;
    }
    let (ra, rb) = c.anchors(a, b);
    let stretch = p.up.dot(&c.separation(a, b, ra, rb)) - p.settings.rest_length;
    // Implicit in both the stretch and the speed: stable at any stiffness and step.
    let omega = 2.0 * crate::math::consts::PI * spring.hertz;
    let omega_h = omega * p.h;
    c.impulses.spring_velocity = (c.impulses.spring_velocity - omega * omega_h * stretch)
        / (1.0 + 2.0 * spring.damping_ratio * omega_h + omega_h * omega_h);
}

pub(super) fn warm_start(c: &JointConstraint, p: &Prepared, a: &mut BodyState, b: &mut BodyState) {
    let (ra, rb) = c.anchors(a, b);
    c.apply_linear(a, b, ra, rb, p.normal * c.impulses.axial);
}

pub(super) fn solve(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    if !pass.drive {
        return;
    }
    let s = &p.settings;
    if s.spring.hertz == 0.0 {
        c.impulses.axial = 0.0;
        return;
    }
    let target = if pass.relaxing {
        0.0
    } else {
        c.impulses.spring_velocity
    };
    let (ra, rb) = c.anchors(a, b);
    let speed = p
        .normal
        .dot(&JointConstraint::relative_velocity(a, b, ra, rb));
    let impulse = -p.mass * (speed - target);
    let old = c.impulses.axial;
    c.impulses.axial = (old + impulse).clamp(-pass.h * s.max_tension, pass.h * s.max_compression);
    c.apply_linear(a, b, ra, rb, p.normal * (c.impulses.axial - old));
}
