//! The tutorial's impulse resolution, exactly: per contact point the impulse
//! `j = max((-vn + bias) / k, 0)`, with `k` from masses and inertias and the Baumgarte bias
//! `0.2 / dt · max(0, depth - 0.01)`, applied to both bodies and repeated for the iterations.
//! Nothing accumulates between iterations or steps, and there is no friction or restitution.
//! The one addition: a point still apart by `s` (a speculative point, which the tutorial
//! lacked) gets the bias `-s / dt`, so the bodies may close the gap but not pass it; without it
//! continuous collision would leave fast bodies frozen just short of a surface.

use super::in_tutorial_order;
use crate::constants::TUTORIAL_SLOP;
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
    let (params, dt) = (context.params, context.dt);
    let work = in_tutorial_order(context, states, |states| {
        for c in constraints.iter_mut() {
            let (a, b) = pair_mut(states, c.a, c.b);
            for i in 0..c.points().len() {
                let point = &c.points()[i];
                let vn = ContactConstraint::relative_velocity(point, a, b).dot(&c.normal);
                let bias = if point.separation > 0.0 {
                    -point.separation / dt
                } else {
                    let depth = -point.separation;
                    params.baumgarte / dt * (depth - TUTORIAL_SLOP).max(0.0)
                };
                let j = ((-vn + bias) * point.normal_mass).max(0.0);
                c.apply(point, c.normal * j, a, b);
                // Reported, not accumulated: each iteration's impulse stands alone.
                c.points_mut()[i].total_normal_impulse += j;
            }
        }
    });
    // One step, no substeps: the most applied in a substep is the step's total.
    for point in constraints.iter_mut().flat_map(|c| c.points_mut()) {
        point.max_normal_impulse = point.total_normal_impulse;
    }
    work
}
