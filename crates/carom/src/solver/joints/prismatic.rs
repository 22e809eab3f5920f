//! The prismatic joint: a slider. B's anchor stays on the line through A's along the axis
//! (fixed in A), and B does not turn relative to A: one 2x2 block for the perpendicular
//! offset and the angle. Along the axis it is free, within limits, driven by a motor or
//! pulled by a spring.
//!
//! The axis and lever arms are taken from the bodies' motion so far in the step, at every
//! pass: `d` from A's anchor to B's, lever arms `a1 = (rA + d) × axis`, `a2 = rB × axis`.

use super::{JointConstraint, JointPass, inverse_or_zero, solve_limits, solve22, spring_softness};
use crate::joint::PrismaticJoint;
use crate::math::{Real, Vec2, cross, cross_sv};
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    pub settings: PrismaticJoint,
    spring: Softness,
}

pub(super) fn prepare(_c: &JointConstraint, settings: PrismaticJoint, h: Real) -> Prepared {
    let spring = spring_softness(settings.spring, h);
    Prepared { settings, spring }
}

/// The slider's geometry now: anchors, the offset between them, the axis and its normal.
pub(super) struct Slide {
    pub ra: Vec2,
    pub rb: Vec2,
    pub d: Vec2,
    pub axis: Vec2,
    pub perp: Vec2,
}

impl Slide {
    pub(crate) fn now(c: &JointConstraint, a: &BodyState, b: &BodyState, local_axis: Vec2) -> Self {
        let (ra, rb) = c.anchors(a, b);
        let d = c.separation(a, b, ra, rb);
        let axis = a.dq * (c.rot_a * local_axis);
        Slide {
            ra,
            rb,
            d,
            axis,
            perp: cross_sv(1.0, axis),
        }
    }

    /// The lever arms of a force along `direction`: A's (from its centre of mass to B's
    /// anchor) and B's.
    pub(crate) fn arms(&self, direction: Vec2) -> (Real, Real) {
        (
            cross(self.ra + self.d, direction),
            cross(self.rb, direction),
        )
    }

    /// The velocity along `direction` with lever arms `(a1, a2)`.
    pub(crate) fn speed(
        a: &BodyState,
        b: &BodyState,
        direction: Vec2,
        (a1, a2): (Real, Real),
    ) -> Real {
        direction.dot(&(b.v - a.v)) + a2 * b.w - a1 * a.w
    }
}

/// Applies linear impulse `p` with angular impulses `la` about A and `lb` about B.
pub(super) fn apply(
    c: &JointConstraint,
    a: &mut BodyState,
    b: &mut BodyState,
    p: Vec2,
    la: Real,
    lb: Real,
) {
    let (ma, ia, mb, ib) = c.masses();
    a.v -= p * ma;
    a.w -= ia * la;
    b.v += p * mb;
    b.w += ib * lb;
}

/// One constraint along `direction` with arms `arms`: a velocity impulse toward `target`
/// speed with `bias`, mass and impulse scales, accumulated in `accumulated` and clamped to
/// `range`. Returns the impulse applied.
#[allow(clippy::too_many_arguments)]
pub(super) fn axial_impulse(
    c: &JointConstraint,
    a: &mut BodyState,
    b: &mut BodyState,
    direction: Vec2,
    arms: (Real, Real),
    (bias, mass_scale, impulse_scale): (Real, Real, Real),
    accumulated: &mut Real,
    range: (Real, Real),
) {
    let (ma, ia, mb, ib) = c.masses();
    let k = ma + mb + ia * arms.0 * arms.0 + ib * arms.1 * arms.1;
    let speed = Slide::speed(a, b, direction, arms);
    let impulse = -mass_scale * inverse_or_zero(k) * (speed + bias) - impulse_scale * *accumulated;
    let old = *accumulated;
    *accumulated = (old + impulse).clamp(range.0, range.1);
    let applied = *accumulated - old;
    apply(
        c,
        a,
        b,
        direction * applied,
        applied * arms.0,
        applied * arms.1,
    );
}

/// A stop along `axis` with lever arms `arms`: the lower one pushes B along the axis, the
/// upper one (`upper`) back against it; the accumulated impulse only ever pushes.
#[allow(clippy::too_many_arguments)]
pub(super) fn stop(
    c: &JointConstraint,
    a: &mut BodyState,
    b: &mut BodyState,
    axis: Vec2,
    arms: (Real, Real),
    scales: (Real, Real, Real),
    accumulated: &mut Real,
    upper: bool,
) {
    let (axis, arms) = if upper {
        (-axis, (-arms.0, -arms.1))
    } else {
        (axis, arms)
    };
    axial_impulse(
        c,
        a,
        b,
        axis,
        arms,
        scales,
        accumulated,
        (0.0, Real::INFINITY),
    );
}

pub(super) fn warm_start(c: &JointConstraint, p: &Prepared, a: &mut BodyState, b: &mut BodyState) {
    let slide = Slide::now(c, a, b, p.settings.axis);
    let (a1, a2) = slide.arms(slide.axis);
    let (s1, s2) = slide.arms(slide.perp);
    let i = &c.impulses;
    let axial = i.axial + i.motor + i.lower - i.upper;
    let linear = slide.axis * axial + slide.perp * i.linear.x;
    let la = axial * a1 + i.linear.x * s1 + i.linear.y;
    let lb = axial * a2 + i.linear.x * s2 + i.linear.y;
    apply(c, a, b, linear, la, lb);
}

pub(super) fn solve(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    let settings = &p.settings;
    let slide = Slide::now(c, a, b, settings.axis);
    let translation = slide.axis.dot(&slide.d);
    let arms = slide.arms(slide.axis);
    let free = (Real::NEG_INFINITY, Real::INFINITY);
    let mut impulses = c.impulses;
    if pass.drive && settings.spring.is_some_and(|s| s.hertz > 0.0) {
        let s = p.spring;
        let bias = s.bias_rate * (translation - settings.target_translation);
        let scales = (bias, s.mass_scale, s.impulse_scale);
        axial_impulse(c, a, b, slide.axis, arms, scales, &mut impulses.axial, free);
    }
    if let (true, Some(motor)) = (pass.drive, settings.motor) {
        let max = pass.h * motor.max_force;
        let scales = (-motor.speed, 1.0, 0.0);
        axial_impulse(
            c,
            a,
            b,
            slide.axis,
            arms,
            scales,
            &mut impulses.motor,
            (-max, max),
        );
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
    // Perpendicular offset and angle, as one block.
    let (s1, s2) = slide.arms(slide.perp);
    let (ma, ia, mb, ib) = c.masses();
    let velocity = Vec2::new(Slide::speed(a, b, slide.perp, (s1, s2)), b.w - a.w);
    let (bias, mass_scale, impulse_scale) = if pass.use_bias {
        let s = pass.softness;
        let error = Vec2::new(slide.perp.dot(&slide.d), c.angle(a, b));
        (error * s.bias_rate, s.mass_scale, s.impulse_scale)
    } else {
        (Vec2::zeros(), 1.0, 0.0)
    };
    let k22 = ia + ib;
    let k = [
        ma + mb + ia * s1 * s1 + ib * s2 * s2,
        ia * s1 + ib * s2,
        if k22 == 0.0 { 1.0 } else { k22 },
    ];
    let impulse = -solve22(k, velocity + bias) * mass_scale - impulses.linear * impulse_scale;
    impulses.linear += impulse;
    let la = impulse.x * s1 + impulse.y;
    let lb = impulse.x * s2 + impulse.y;
    apply(c, a, b, slide.perp * impulse.x, la, lb);
    c.impulses = impulses;
}
