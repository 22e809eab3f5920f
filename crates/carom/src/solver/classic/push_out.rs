//! The tutorial with impulse resolution unchecked: overlapping bodies are moved apart along
//! the contact normal, each in proportion to its inverse mass, and their approaching velocity
//! is removed. No rotation, friction or bounce: it shows why impulses are needed. Bodies still
//! apart (speculative points) may close the gap but not pass it.

use super::in_tutorial_order;
use crate::math::Real;
use crate::solver::body_state::BodyState;
use crate::solver::contact_constraint::ContactConstraint;
use crate::solver::contact_constraint::pair_mut;
use crate::solver::context::SolverContext;
use crate::stats::Work;

pub(crate) fn solve(
    context: &SolverContext,
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
) -> Work {
    let dt = context.dt;
    in_tutorial_order(context, states, |states| {
        for c in constraints.iter() {
            let total = c.inv_mass_a + c.inv_mass_b;
            if total == 0.0 {
                continue;
            }
            let (a, b) = pair_mut(states, c.a, c.b);
            let deepest = c
                .points()
                .iter()
                .map(|p| c.current_separation(p, a, b))
                .fold(Real::INFINITY, Real::min);
            let correction = c.normal * (-deepest).max(0.0);
            a.dp -= correction * (c.inv_mass_a / total);
            b.dp += correction * (c.inv_mass_b / total);
            // Approaching faster than closes the gap this step (any approach, once touching) is
            // removed; the allowance for a gap matters after continuous collision, which leaves
            // fast bodies just short of a surface.
            let excess = (b.v - a.v).dot(&c.normal) + deepest.max(0.0) / dt;
            if excess < 0.0 {
                a.v += c.normal * (excess * c.inv_mass_a / total);
                b.v -= c.normal * (excess * c.inv_mass_b / total);
            }
        }
    })
}
