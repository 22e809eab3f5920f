//! Sequential impulses (Catto, GDC 2006): accumulated impulses clamped as a whole, so many
//! iterations converge to the contact forces; warm started from the last step; Baumgarte
//! bias pushes out overlap beyond the slop; restitution as a final pass.

use super::body_state::{integrate_positions, integrate_velocities};
use super::contact_constraint::pair_mut;
use super::soft_step::{apply_restitution, forget_impulses, solve_friction, warm_start};
use super::{BodyState, ContactConstraint, SolverContext};
use crate::stats::Work;

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
                // The slowest normal velocity allowed: close a speculative gap exactly, or
                // push out a fraction of the overlap beyond the slop.
                let target = if point.separation > 0.0 {
                    -point.separation * inv_dt
                } else {
                    params.baumgarte * inv_dt * (-point.separation - params.linear_slop).max(0.0)
                };
                let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
                c.add_normal_impulse(i, point.normal_mass * (target - vn), a, b);
            }
        }
    }
    if environment.restitution {
        work.restitution_impulses = apply_restitution(params, constraints, states);
    }
    integrate_positions(bodies, states, dt);
    work
}
