//! Sequential impulses (Catto, GDC 2006) as Box2D v2.4 runs them: accumulated impulses clamped
//! as a whole, so many iterations converge to the contact forces; warm started from the last
//! step; restitution as a final pass. Overlap is removed on positions, not velocities: after
//! the bodies move, a few Gauss-Seidel passes push overlap beyond the slop out directly
//! (Baumgarte's fraction per pass, at most [`MAX_CORRECTION`]). A velocity bias would stay in
//! the bodies as energy and, in a pressed pile, feed on itself until it explodes.

use super::body_state::{integrate_positions, integrate_velocities};
use super::contact_constraint::pair_mut;
use super::soft_step::{apply_restitution, forget_impulses, solve_friction, warm_start};
use super::{BodyState, ContactConstraint, SolverContext, SolverParams};
use crate::math::{Real, Rot, cross};
use crate::stats::Work;

/// Position passes after each step (Box2D v2.4's default).
pub const POSITION_ITERATIONS: usize = 3;

/// The most overlap one position pass removes at a point, m (Box2D v2.4's
/// `b2_maxLinearCorrection`): a deep overlap is taken apart over several steps, not flung.
pub const MAX_CORRECTION: Real = 0.2;

pub(super) fn solve(
    context: &SolverContext,
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
) -> Work {
    let SolverContext {
        params,
        environment,
        bodies,
        dt,
    } = *context;
    let inv_dt = 1.0 / dt;
    let mut work = integrate_velocities(params, environment, bodies, states, dt);
    if params.warm_starting {
        warm_start(constraints, states);
    } else {
        forget_impulses(constraints);
    }
    for _ in 0..params.iterations {
        for c in constraints.iter_mut() {
            let (a, b) = pair_mut(states, c.a, c.b);
            // Friction first, against last iteration's normal impulse (Box2D v2's order).
            if environment.friction {
                work.friction_impulses += solve_friction(c, a, b);
            }
            for i in 0..c.points().len() {
                let point = c.points()[i];
                // The slowest normal velocity allowed: close a speculative gap exactly; an
                // overlap is the position passes' business.
                let target = -point.separation.max(0.0) * inv_dt;
                let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
                c.add_normal_impulse(i, point.normal_mass * (target - vn), a, b);
            }
        }
    }
    if environment.restitution {
        work.restitution_impulses = apply_restitution(params, constraints, states);
    }
    integrate_positions(bodies, states, dt);
    for _ in 0..POSITION_ITERATIONS {
        correct_positions(params, constraints, states);
    }
    work
}

/// One Gauss-Seidel pass on positions: each point's overlap beyond the slop, a Baumgarte
/// fraction of it and at most [`MAX_CORRECTION`], is pushed out along the normal by moving the
/// two bodies as an impulse would (no velocity changes).
fn correct_positions(
    params: &SolverParams,
    constraints: &[ContactConstraint],
    states: &mut [BodyState],
) {
    for c in constraints {
        let (a, b) = pair_mut(states, c.a, c.b);
        for point in c.points() {
            let separation = c.current_separation(point, a, b);
            let correction =
                (params.baumgarte * (separation + params.linear_slop)).clamp(-MAX_CORRECTION, 0.0);
            if correction == 0.0 {
                continue;
            }
            let (ra, rb) = (a.dq * point.anchor_a, b.dq * point.anchor_b);
            let (rna, rnb) = (cross(ra, c.normal), cross(rb, c.normal));
            let k = c.inv_mass_a
                + c.inv_mass_b
                + c.inv_inertia_a * rna * rna
                + c.inv_inertia_b * rnb * rnb;
            if k <= 0.0 {
                continue;
            }
            let push = c.normal * (-correction / k);
            a.dp -= push * c.inv_mass_a;
            a.dq = Rot::new(-c.inv_inertia_a * cross(ra, push)) * a.dq;
            b.dp += push * c.inv_mass_b;
            b.dq = Rot::new(c.inv_inertia_b * cross(rb, push)) * b.dq;
        }
    }
}
