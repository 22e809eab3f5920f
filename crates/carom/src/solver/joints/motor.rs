//! The motor joint, as Box2D 3.2 solves it: a spring part pulling B's anchor and angle to
//! their offsets from A, and a velocity part driving their rates, each within its own cap.
//! Angular spring, angular velocity, linear spring, linear velocity, in that order. Both
//! passes drive (the targets are wishes, not drift); a part whose cap is 0 holds no impulse.

use super::{JointConstraint, JointPass, inverse_or_zero, solve22};
use crate::joint::{JointImpulses, MotorJoint};
use crate::math::{Real, Vec2, clamp_magnitude, unwind_angle};
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    settings: MotorJoint,
    angular_mass: Real,
    linear_spring: Softness,
    angular_spring: Softness,
}

impl Prepared {
    fn linear_spring_on(&self) -> bool {
        self.settings.max_spring_force > 0.0 && self.settings.linear_spring.hertz > 0.0
    }

    fn angular_spring_on(&self) -> bool {
        self.settings.max_spring_torque > 0.0 && self.settings.angular_spring.hertz > 0.0
    }
}

/// Prepares the joint, forgetting the impulses of the parts that are off so that none is
/// warm started.
pub(super) fn prepare(c: &mut JointConstraint, settings: MotorJoint, h: Real) -> Prepared {
    let (_, ia, _, ib) = c.masses();
    let spring = |s: crate::joint::Spring| Softness::new(s.hertz, s.damping_ratio, h);
    let p = Prepared {
        settings,
        angular_mass: inverse_or_zero(ia + ib),
        linear_spring: spring(settings.linear_spring),
        angular_spring: spring(settings.angular_spring),
    };
    let i: &mut JointImpulses = &mut c.impulses;
    if !p.linear_spring_on() {
        i.linear = Vec2::zeros();
    }
    if !p.angular_spring_on() {
        i.angular = 0.0;
    }
    if settings.max_velocity_force <= 0.0 {
        i.drive = Vec2::zeros();
    }
    if settings.max_velocity_torque <= 0.0 {
        i.motor = 0.0;
    }
    p
}

pub(super) fn warm_start(c: &JointConstraint, a: &mut BodyState, b: &mut BodyState) {
    let (ra, rb) = c.anchors(a, b);
    let i = &c.impulses;
    c.apply_angular(a, b, i.angular + i.motor);
    c.apply_linear(a, b, ra, rb, i.linear + i.drive);
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
    if p.angular_spring_on() {
        let error = unwind_angle(c.angle(a, b) - s.angular_offset);
        let k = p.angular_spring;
        let old = c.impulses.angular;
        let impulse = -k.mass_scale * p.angular_mass * (b.w - a.w + k.bias_rate * error)
            - k.impulse_scale * old;
        let max = pass.h * s.max_spring_torque;
        c.impulses.angular = (old + impulse).clamp(-max, max);
        c.apply_angular(a, b, c.impulses.angular - old);
    }
    if s.max_velocity_torque > 0.0 {
        let impulse = -p.angular_mass * (b.w - a.w - s.angular_velocity);
        let old = c.impulses.motor;
        let max = pass.h * s.max_velocity_torque;
        c.impulses.motor = (old + impulse).clamp(-max, max);
        c.apply_angular(a, b, c.impulses.motor - old);
    }
    let (ra, rb) = c.anchors(a, b);
    let mass = c.point_mass(ra, rb);
    if p.linear_spring_on() {
        let offset = a.dq * (c.rot_a * s.linear_offset);
        let error = c.separation(a, b, ra, rb) - offset;
        let k = p.linear_spring;
        let velocity = JointConstraint::relative_velocity(a, b, ra, rb);
        let old = c.impulses.linear;
        let impulse =
            -solve22(mass, velocity + error * k.bias_rate) * k.mass_scale - old * k.impulse_scale;
        c.impulses.linear = clamp_magnitude(old + impulse, pass.h * s.max_spring_force);
        c.apply_linear(a, b, ra, rb, c.impulses.linear - old);
    }
    if s.max_velocity_force > 0.0 {
        let velocity = JointConstraint::relative_velocity(a, b, ra, rb);
        let impulse = -solve22(mass, velocity - s.linear_velocity);
        let old = c.impulses.drive;
        c.impulses.drive = clamp_magnitude(old + impulse, pass.h * s.max_velocity_force);
        c.apply_linear(a, b, ra, rb, c.impulses.drive - old);
    }
}
