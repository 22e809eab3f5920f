//! The motor joint: drives B toward an offset and an angle relative to A, closing a fraction
//! of the error per step with at most so much force and torque (Box2D v3.0's). Both passes
//! drive: the target is a wish, not drift.

use super::{JointConstraint, JointPass, inverse_or_zero, solve22};
use crate::joint::MotorJoint;
use crate::math::{Real, clamp_magnitude, unwind_angle};
use crate::solver::BodyState;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    settings: MotorJoint,
    angular_mass: Real,
}

pub(super) fn prepare(c: &JointConstraint, settings: MotorJoint) -> Prepared {
    let (_, ia, _, ib) = c.masses();
    Prepared {
        settings,
        angular_mass: inverse_or_zero(ia + ib),
    }
}

pub(super) fn warm_start(c: &JointConstraint, a: &mut BodyState, b: &mut BodyState) {
    let (ra, rb) = c.anchors(a, b);
    c.apply_angular(a, b, c.impulses.angular);
    c.apply_linear(a, b, ra, rb, c.impulses.linear);
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
    let rate = s.correction_factor * pass.inv_h;
    // The angle.
    let error = unwind_angle(c.angle(a, b) - s.angular_offset);
    let impulse = -p.angular_mass * (b.w - a.w + rate * error);
    let old = c.impulses.angular;
    let max = pass.h * s.max_torque;
    c.impulses.angular = (old + impulse).clamp(-max, max);
    c.apply_angular(a, b, c.impulses.angular - old);
    // The offset.
    let (ra, rb) = c.anchors(a, b);
    let offset = a.dq * (c.rot_a * s.linear_offset);
    let error = c.separation(a, b, ra, rb) - offset;
    let velocity = JointConstraint::relative_velocity(a, b, ra, rb);
    let impulse = -solve22(c.point_mass(ra, rb), velocity + error * rate);
    let old = c.impulses.linear;
    c.impulses.linear = clamp_magnitude(old + impulse, pass.h * s.max_force);
    c.apply_linear(a, b, ra, rb, c.impulses.linear - old);
}
