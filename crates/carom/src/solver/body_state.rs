//! The solver's copy of a body: velocities and the motion accumulated over the step, stored
//! contiguously so the inner loops touch little memory. Every solver path (one contact at a
//! time, or several in SIMD lanes) reads and writes this one array.

use super::context::Environment;

use super::params::SolverParams;
use crate::constants::ITEMS_PER_TASK;
use crate::dynamics::body::{Body, BodyKind};
use crate::math::{Real, Rot, Vec2, clamp_magnitude, rotation};
use crate::parallel::{for_each_with, sum_with};
use crate::stats::Work;

/// Whether the speed caps cut a body's velocities (see [`BodyState::held`]): a word as wide
/// as [`Real`], so a state is eight words with no padding.
#[cfg(not(feature = "f64"))]
pub(crate) type Held = u32;
/// Whether the speed caps cut a body's velocities (see [`BodyState::held`]): a word as wide
/// as [`Real`], so a state is eight words with no padding.
#[cfg(feature = "f64")]
pub(crate) type Held = u64;

/// One body as the solver sees it: eight floats in one 32-byte line (Box2D's `b2BodyState`),
/// so the SIMD solver loads a body with one or two vector loads and transposes bodies into
/// lanes: `[v.x, v.y, w, held, dp.x, dp.y, dq.cos, dq.sin]`. Aligned to its size, so no
/// state straddles two cache lines.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(not(feature = "f64"), repr(C, align(32)))]
#[cfg_attr(feature = "f64", repr(C, align(64)))]
pub(crate) struct BodyState {
    /// Linear velocity.
    pub v: Vec2,
    /// Angular velocity.
    pub w: Real,
    /// 1 if the speed caps cut the velocities since the body's joints last warm started,
    /// else 0 (see [`SpeedCaps::hold`]). A word, not a `bool`, so every byte of the line is
    /// set (the SIMD solver loads it whole, and leaves this word as it was when it stores the
    /// velocities).
    pub held: Held,
    /// Translation since the start of the step.
    pub dp: Vec2,
    /// Rotation since the start of the step.
    pub dq: Rot,
}

// The SIMD solver reads a state as eight floats in this order (see `shared_states`): 32
// bytes in single precision, 64 in double, aligned to that.
const _: () = {
    use std::mem::{align_of, offset_of, size_of};
    const R: usize = size_of::<Real>();
    assert!(size_of::<BodyState>() == 8 * R && align_of::<BodyState>() == 8 * R);
    assert!(offset_of!(BodyState, v) == 0 && offset_of!(BodyState, w) == 2 * R);
    assert!(offset_of!(BodyState, held) == 3 * R && size_of::<Held>() == R);
    assert!(offset_of!(BodyState, dp) == 4 * R);
    assert!(offset_of!(BodyState, dq) == 6 * R && size_of::<Rot>() == 2 * R);
};

impl BodyState {
    pub(crate) fn from_body(body: &Body) -> Self {
        BodyState {
            v: body.linear_velocity(),
            w: body.angular_velocity(),
            held: 0,
            dp: Vec2::zeros(),
            dq: Rot::identity(),
        }
    }

    /// A state at rest that belongs to no body.
    pub(crate) fn spare() -> Self {
        BodyState {
            v: Vec2::zeros(),
            w: 0.0,
            held: 0,
            dp: Vec2::zeros(),
            dq: Rot::identity(),
        }
    }

    /// Commits the step: the body moves by `dp` and `dq` and takes the new velocities, a
    /// dynamic body's held to `caps` (the passes after the last position integration may
    /// have pushed them past).
    pub(crate) fn write_back(&self, body: &mut Body, caps: SpeedCaps) {
        if !body.moves() {
            return;
        }
        let (v, w) = if body.kind() == BodyKind::Dynamic {
            let (v, w, _) = caps.hold(self.v, self.w);
            (v, w)
        } else {
            (self.v, self.w)
        };
        body.finish_step(v, w, self.dp, self.dq);
    }

    /// Whether the caps cut this body's velocities since its joints last warm started, or
    /// would cut them now.
    pub(crate) fn is_held(&self, caps: SpeedCaps) -> bool {
        self.held != 0 || caps.hold(self.v, self.w).2
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
    pub(crate) fn new(params: &SolverParams, dt: Real) -> Self {
        SpeedCaps {
            linear: params.max_linear_speed,
            angular: params.max_rotation / dt,
        }
    }

    /// Velocities `v` and `w` held to the caps, and whether either had to be cut.
    ///
    /// A cut takes away velocity that the joints' accumulated impulses gave, so a joint with
    /// a body cut since its last warm start starts cold (see `held`). Warm starting it anyway
    /// is how a joint anchored far from a light body ran away: its impulse, re-applied
    /// through a lever that had turned since, gave more velocity than the cut took, and the
    /// impulse grew tenfold a substep to NaN (Box2D 3.2 does the same).
    #[inline]
    pub(crate) fn hold(&self, v: Vec2, w: Real) -> (Vec2, Real, bool) {
        let held_v = clamp_magnitude(v, self.linear);
        let held_w = w.clamp(-self.angular, self.angular);
        (held_v, held_w, held_v != v || held_w != w)
    }
}

/// What integration reads of an awake body, copied from it once a step: each substep's two
/// integration passes then stream through these few words instead of the bodies, whose
/// fields they need lie on several cache lines.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Drive {
    pub force: Vec2,
    pub torque: Real,
    pub inv_mass: Real,
    pub inv_inertia: Real,
    pub gravity_scale: Real,
    pub linear_damping: Real,
    pub angular_damping: Real,
    /// A dynamic body, awake: gravity, forces, drag and the speed caps act on it.
    pub dynamic: bool,
    /// A body that is not static, awake: its velocities move it.
    pub moves: bool,
}

impl Drive {
    pub(crate) fn of(body: &Body) -> Self {
        Drive {
            force: body.force(),
            torque: body.torque(),
            inv_mass: body.inv_mass(),
            inv_inertia: body.inv_inertia(),
            gravity_scale: body.gravity_scale(),
            linear_damping: body.linear_damping(),
            angular_damping: body.angular_damping(),
            dynamic: body.is_dynamic() && !body.is_sleeping(),
            moves: body.moves(),
        }
    }
}

/// Velocities from gravity, applied forces and drag over `h`. Gravity and drag are skipped
/// entirely when off.
pub(crate) fn integrate_velocities(
    environment: Environment,
    drives: &[Drive],
    states: &mut [BodyState],
    h: Real,
    caps: SpeedCaps,
) -> Work {
    sum_with(drives, states, ITEMS_PER_TASK, |drive, state| {
        integrate_velocity(environment, drive, state, h, caps)
    })
}

/// [`integrate_velocities`] of one body. Always inlined: called once per body per substep,
/// a call (and its `Work` returned through memory) costs as much as the integration.
#[inline(always)]
pub(crate) fn integrate_velocity(
    environment: Environment,
    drive: &Drive,
    state: &mut BodyState,
    h: Real,
    caps: SpeedCaps,
) -> Work {
    let mut work = Work::default();
    if !drive.dynamic {
        return work;
    }
    let mut v = state.v + drive.force * (drive.inv_mass * h);
    let mut w = state.w + drive.torque * drive.inv_inertia * h;
    if let Some(gravity) = environment.gravity {
        v += gravity * (drive.gravity_scale * h);
        work.gravity_terms += 1;
    }
    if let Some(model) = environment.drag
        && (drive.linear_damping > 0.0 || drive.angular_damping > 0.0)
    {
        v = model.apply_linear(v, drive.linear_damping, h);
        w = model.apply_angular(w, drive.angular_damping, h);
        work.drag_terms += 1;
    }
    let (v, w, cut) = caps.hold(v, w);
    (state.v, state.w) = (v, w);
    // Added to a cut at the last position integration, which the warm start to come has not
    // seen yet.
    state.held |= Held::from(cut);
    work
}

/// Positions from velocities over `h` (accumulated in `dp` and `dq`), dynamic bodies' velocities
/// first held to the speed caps (after the contacts and joints had their say, as Box2D 3.2
/// does, so the cap bounds the motion itself). Kinematic bodies move as they are told.
pub(crate) fn integrate_positions(
    drives: &[Drive],
    states: &mut [BodyState],
    h: Real,
    caps: SpeedCaps,
) {
    for_each_with(drives, states, ITEMS_PER_TASK, |drive, state| {
        integrate_position(drive, state, h, caps)
    });
}

/// [`integrate_positions`] of one body.
#[inline]
pub(crate) fn integrate_position(drive: &Drive, state: &mut BodyState, h: Real, caps: SpeedCaps) {
    if !drive.moves {
        return;
    }
    if drive.dynamic {
        let (v, w, cut) = caps.hold(state.v, state.w);
        (state.v, state.w) = (v, w);
        // The warm start since the last position integration has seen the cuts before it.
        state.held = Held::from(cut);
    }
    state.dp += state.v * h;
    state.dq = rotation(state.w * h) * state.dq;
}
