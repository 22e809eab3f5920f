//! The solver's copy of a body: velocities and the motion accumulated over the step, stored
//! contiguously so the inner loops touch little memory. Every solver path (one contact at a
//! time, or several in SIMD lanes) reads and writes this one array.

use super::{Environment, SolverParams};
use crate::constants::ITEMS_PER_TASK;
use crate::dynamics::body::{Body, BodyKind};
use crate::math::{Real, Rot, Vec2, clamp_magnitude};
use crate::parallel::{for_each_with, sum_with};
use crate::stats::Work;

/// One body as the solver sees it: eight floats in one 32-byte line (Box2D's `b2BodyState`),
/// so the SIMD solver loads a body with one or two vector loads and transposes bodies into
/// lanes: `[v.x, v.y, w, 0, dp.x, dp.y, dq.cos, dq.sin]`.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
pub(crate) struct BodyState {
    /// Linear velocity.
    pub v: Vec2,
    /// Angular velocity.
    pub w: Real,
    /// Unused: keeps the velocities in the first half of the line and the motion in the
    /// second. Always 0.
    pub pad: Real,
    /// Translation since the start of the step.
    pub dp: Vec2,
    /// Rotation since the start of the step.
    pub dq: Rot,
}

// The SIMD solver reads a state as eight floats in this order (see `shared_states`).
const _: () = {
    use std::mem::{align_of, offset_of, size_of};
    assert!(size_of::<BodyState>() == 32 && align_of::<BodyState>() == 32);
    assert!(offset_of!(BodyState, v) == 0 && offset_of!(BodyState, w) == 8);
    assert!(offset_of!(BodyState, pad) == 12 && offset_of!(BodyState, dp) == 16);
    assert!(offset_of!(BodyState, dq) == 24 && size_of::<Rot>() == 8);
};

impl BodyState {
    pub fn from_body(body: &Body) -> Self {
        BodyState {
            v: body.linear_velocity(),
            w: body.angular_velocity(),
            pad: 0.0,
            dp: Vec2::zeros(),
            dq: Rot::identity(),
        }
    }

    /// A state at rest that belongs to no body.
    pub fn spare() -> Self {
        BodyState {
            v: Vec2::zeros(),
            w: 0.0,
            pad: 0.0,
            dp: Vec2::zeros(),
            dq: Rot::identity(),
        }
    }

    /// Commits the step: the body moves by `dp` and `dq` and takes the new velocities.
    pub fn write_back(&self, body: &mut Body) {
        if !body.moves() {
            return;
        }
        body.finish_step(self.v, self.w, self.dp, self.dq);
    }
}

/// The guard rails on speed: how fast any dynamic body may move and turn.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpeedCaps {
    /// m/s.
    pub linear: Real,
    /// rad/s: `max_rotation` per whole step, as Box2D caps it, whatever the substeps. A cap
    /// per substep would let a body turn more than half a turn in a step with 8 substeps, and
    /// a turn rebuilt from the step's start and end rotations (the continuous sweep's) would
    /// then alias to the short way round.
    pub angular: Real,
}

impl SpeedCaps {
    /// The caps for a step of `dt`.
    pub fn new(params: &SolverParams, dt: Real) -> Self {
        SpeedCaps {
            linear: params.max_linear_speed,
            angular: params.max_rotation / dt,
        }
    }
}

/// Velocities from gravity, applied forces and drag over `h`. Gravity and drag are skipped
/// entirely when off.
pub(crate) fn integrate_velocities(
    environment: Environment,
    bodies: &[Body],
    states: &mut [BodyState],
    h: Real,
    caps: SpeedCaps,
) -> Work {
    sum_with(bodies, states, ITEMS_PER_TASK, |body, state| {
        integrate_velocity(environment, body, state, h, caps)
    })
}

/// [`integrate_velocities`] of one body.
#[inline]
pub(crate) fn integrate_velocity(
    environment: Environment,
    body: &Body,
    state: &mut BodyState,
    h: Real,
    caps: SpeedCaps,
) -> Work {
    let mut work = Work::default();
    if body.kind() != BodyKind::Dynamic || body.is_sleeping() {
        return work;
    }
    let mut v = state.v + body.force() * (body.inv_mass() * h);
    let mut w = state.w + body.torque() * body.inv_inertia() * h;
    if let Some(gravity) = environment.gravity {
        v += gravity * (body.gravity_scale() * h);
        work.gravity_terms += 1;
    }
    if let Some(model) = environment.drag
        && (body.linear_damping() > 0.0 || body.angular_damping() > 0.0)
    {
        v = model.apply_linear(v, body.linear_damping(), h);
        w = model.apply_angular(w, body.angular_damping(), h);
        work.drag_terms += 1;
    }
    state.v = clamp_magnitude(v, caps.linear);
    state.w = w.clamp(-caps.angular, caps.angular);
    work
}

/// Positions from velocities over `h` (accumulated in `dp` and `dq`), dynamic bodies' velocities
/// first held to the speed caps (after the contacts had their say, as Box2D 3.2 does, so the
/// cap bounds the motion itself). Kinematic bodies move as they are told.
pub(crate) fn integrate_positions(bodies: &[Body], states: &mut [BodyState], h: Real) {
    for_each_with(bodies, states, ITEMS_PER_TASK, |body, state| {
        integrate_position(body, state, h)
    });
}

/// [`integrate_positions`] of one body.
#[inline]
pub(crate) fn integrate_position(body: &Body, state: &mut BodyState, h: Real) {
    if !body.moves() {
        return;
    }
    state.dp += state.v * h;
    state.dq = Rot::new(state.w * h) * state.dq;
}
