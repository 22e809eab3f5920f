//! The mover joint (Box2D's): drives B's velocity relative to A's on each world axis with
//! at most so much force, through the centres of mass, leaving rotation alone. Each axis is
//! capped on its own (a box, not a disc), and an axis whose cap is 0 is free. Both passes
//! drive.

use super::{JointConstraint, JointPass, inverse_or_zero};
use crate::joint::MoverJoint;
use crate::math::{Real, Vec2};
use crate::solver::body_state::BodyState;

#[derive(Debug, Clone, Copy)]
pub(super) struct Prepared {
    settings: MoverJoint,
    mass: Real,
}

/// Prepares the joint, forgetting the impulse on a free axis.
pub(super) fn prepare(c: &mut JointConstraint, settings: MoverJoint) -> Prepared {
    let (ma, _, mb, _) = c.masses();
    let drive = &mut c.impulses.drive;
    if settings.max_force.x <= 0.0 {
        drive.x = 0.0;
    }
    if settings.max_force.y <= 0.0 {
        drive.y = 0.0;
    }
    Prepared {
        settings,
        mass: inverse_or_zero(ma + mb),
    }
}

pub(super) fn warm_start(c: &JointConstraint, a: &mut BodyState, b: &mut BodyState) {
    apply(c, a, b, c.impulses.drive);
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
    let impulse = -(b.v - a.v - s.velocity) * p.mass;
    let old = c.impulses.drive;
    let max = s.max_force * pass.h;
    c.impulses.drive = Vec2::new(
        (old.x + impulse.x).clamp(-max.x, max.x),
        (old.y + impulse.y).clamp(-max.y, max.y),
    );
    apply(c, a, b, c.impulses.drive - old);
}

/// Applies `p` to B's centre of mass, and its opposite to A's.
fn apply(c: &JointConstraint, a: &mut BodyState, b: &mut BodyState, p: Vec2) {
    let (ma, _, mb, _) = c.masses();
    a.v -= p * ma;
    b.v += p * mb;
}
