//! The mouse joint: a soft spring from a point of B to a target in the world, its force
//! capped, with some spin damping so a grabbed body hangs from the cursor instead of whirling
//! (Box2D v3.0's). The spring acts in both passes: it is the user's pull, not drift.

use super::{JointConstraint, JointPass, solve22};
use crate::constants::{MOUSE_ANGULAR_DAMPING_RATIO, MOUSE_ANGULAR_HERTZ};
use crate::joint::MouseJoint;
use crate::math::{Real, Vec2, clamp_magnitude, cross};
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    settings: MouseJoint,
    linear: Softness,
    angular: Softness,
}

pub(super) fn prepare(_c: &JointConstraint, settings: MouseJoint, h: Real) -> Prepared {
    let spring = settings.spring;
    Prepared {
        settings,
        linear: Softness::new(spring.hertz, spring.damping_ratio, h),
        angular: Softness::new(MOUSE_ANGULAR_HERTZ, MOUSE_ANGULAR_DAMPING_RATIO, h),
    }
}

pub(super) fn warm_start(c: &JointConstraint, b: &mut BodyState) {
    let (_, _, mb, ib) = c.masses();
    let rb = b.dq * c.frame.frame_b;
    b.w += ib * c.impulses.angular;
    b.v += c.impulses.linear * mb;
    b.w += ib * cross(rb, c.impulses.linear);
}

pub(super) fn solve(c: &mut JointConstraint, p: &Prepared, b: &mut BodyState, pass: &JointPass) {
    if !pass.drive {
        return;
    }
    let (_, _, mb, ib) = c.masses();
    // Spin damping: a soft constraint toward no spin, without bias.
    if ib > 0.0 {
        let impulse =
            p.angular.mass_scale * (-b.w / ib) - p.angular.impulse_scale * c.impulses.angular;
        c.impulses.angular += impulse;
        b.w += ib * impulse;
    }
    let rb = b.dq * c.frame.frame_b;
    let velocity = b.v + crate::math::cross_sv(b.w, rb);
    let separation = b.dp + rb + c.frame.delta_center;
    let bias = separation * p.linear.bias_rate;
    let k = [
        mb + rb.y * rb.y * ib,
        -rb.y * rb.x * ib,
        mb + rb.x * rb.x * ib,
    ];
    let impulse: Vec2 = -solve22(k, velocity + bias) * p.linear.mass_scale
        - c.impulses.linear * p.linear.impulse_scale;
    let old = c.impulses.linear;
    c.impulses.linear = clamp_magnitude(old + impulse, pass.h * p.settings.max_force);
    let applied = c.impulses.linear - old;
    b.v += applied * mb;
    b.w += ib * cross(rb, applied);
}
