//! The classic solvers, from the tutorial's to Box2D v2.4's: each takes the touching
//! contacts one by one in contact order, over the whole step (no substeps).
//!
//! - [`push_out`]: overlapping bodies moved apart, approaching velocity removed; no impulses.
//! - [`tutorial_impulse`]: the tutorial's per-point impulses with a Baumgarte bias.
//! - [`sequential_impulse`]: accumulated, clamped, warm-started impulses with joints, and
//!   position passes after the bodies move (Catto 2006, Box2D v2.4).

pub(crate) mod push_out;
pub(crate) mod sequential_impulse;
pub(crate) mod tutorial_impulse;

use crate::solver::body_state::BodyState;
use crate::solver::body_state::{SpeedCaps, integrate_positions, integrate_velocities};
use crate::solver::context::SolverContext;
use crate::stats::Work;

/// The tutorial's order, which its two solvers keep: its bodies moved, then it found and
/// resolved the contacts (`resolve`, once per iteration), and only then integrated forces into
/// velocities and velocities into positions. Gravity comes after the resolution, so a resting
/// body sinks g dt² a step unless a bias lifts it. Returns the work the effects did.
fn in_tutorial_order(
    context: &SolverContext,
    states: &mut [BodyState],
    mut resolve: impl FnMut(&mut [BodyState]),
) -> Work {
    let SolverContext {
        params,
        environment,
        drives,
        dt,
    } = *context;
    for _ in 0..params.effective_iterations() {
        resolve(states);
    }
    let caps = SpeedCaps::new(params, dt);
    let work = integrate_velocities(environment, drives, states, dt, caps);
    integrate_positions(drives, states, dt, caps);
    work
}
