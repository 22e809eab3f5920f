//! The weld joint: the angle and the anchors held together, each rigidly (soft only in the
//! biased pass) or through its own spring. The angle is solved first, then the point.

use super::{JointConstraint, JointPass, inverse_or_zero, solve22};
use crate::joint::{Spring, WeldJoint};
use crate::math::{Real, Vec2};
use crate::solver::body_state::BodyState;
use crate::solver::params::Softness;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    /// The springs, if soft (else the pass's softness holds them rigidly).
    linear: Option<Softness>,
    angular: Option<Softness>,
    axial_mass: Real,
}

pub(super) fn prepare(c: &JointConstraint, settings: WeldJoint, h: Real) -> Prepared {
    let (_, ia, _, ib) = c.masses();
    let soft = |spring: Option<Spring>| {
        spring
            .filter(|s| s.hertz > 0.0)
            .map(|s| Softness::new(s.hertz, s.damping_ratio, h))
    };
    Prepared {
        linear: soft(settings.linear),
        angular: soft(settings.angular),
        axial_mass: inverse_or_zero(ia + ib),
    }
}

pub(super) fn warm_start(c: &JointConstraint, a: &mut BodyState, b: &mut BodyState) {
    let (ra, rb) = c.anchors(a, b);
    c.apply_angular(a, b, c.impulses.angular);
    c.apply_linear(a, b, ra, rb, c.impulses.linear);
}

/// The bias, mass and impulse scales of a part with error `error`: its spring's if it has
/// one (in both passes: a spring is no drift to relax), else the pass's rigid ones.
fn scales(spring: Option<Softness>, pass: &JointPass, error: Real) -> (Real, Real, Real) {
    match spring {
        Some(s) => (s.bias_rate * error, s.mass_scale, s.impulse_scale),
        None => pass.rigid(error),
    }
}

pub(super) fn solve(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    // A spring is no drift: a pass that only corrects positions leaves it be.
    let angular = p.angular.is_none() || pass.drive;
    let linear = p.linear.is_none() || pass.drive;
    if angular {
        solve_angle(c, p, a, b, pass);
    }
    if linear {
        solve_point(c, p, a, b, pass);
    }
}

fn solve_angle(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    let (bias, mass_scale, impulse_scale) = scales(p.angular, pass, c.angle(a, b));
    let impulse =
        -mass_scale * p.axial_mass * (b.w - a.w + bias) - impulse_scale * c.impulses.angular;
    c.impulses.angular += impulse;
    c.apply_angular(a, b, impulse);
}

fn solve_point(
    c: &mut JointConstraint,
    p: &Prepared,
    a: &mut BodyState,
    b: &mut BodyState,
    pass: &JointPass,
) {
    let (ra, rb) = c.anchors(a, b);
    let separation = c.separation(a, b, ra, rb);
    let (bias_rate, mass_scale, impulse_scale) = scales(p.linear, pass, 1.0);
    let bias: Vec2 = separation * bias_rate;
    let velocity = JointConstraint::relative_velocity(a, b, ra, rb);
    let k = c.point_mass(ra, rb);
    let impulse = -solve22(k, velocity + bias) * mass_scale - c.impulses.linear * impulse_scale;
    c.impulses.linear += impulse;
    c.apply_linear(a, b, ra, rb, impulse);
}
