//! What a body's own values must be to be accepted: a position within reach of the origin,
//! velocities within the speeds the solver's products carry, and a sweep threshold.

use crate::constants::{MAX_ANGULAR_SPEED, MAX_GRAVITY_SCALE, MAX_POSITION, MAX_SPEED};
use crate::error::{CaromError, check_finite_vec, check_within};
use crate::math::{Real, Vec2};

/// Checks a position a body is given: finite and within [`MAX_POSITION`] of the origin on
/// each axis.
pub(crate) fn check_position(what: &'static str, position: Vec2) -> Result<Vec2, CaromError> {
    check_finite_vec(what, position)?;
    for value in [position.x, position.y] {
        if value.abs() > MAX_POSITION {
            return Err(CaromError::OutOfRange {
                name: what,
                expected: "within 1000 km (1e6 m) of the origin",
                value,
            });
        }
    }
    Ok(position)
}

/// Checks a linear velocity a body is given: finite and within [`MAX_SPEED`] on each axis.
pub(crate) fn check_velocity(what: &'static str, velocity: Vec2) -> Result<Vec2, CaromError> {
    check_finite_vec(what, velocity)?;
    for value in [velocity.x, velocity.y] {
        check_within(
            what,
            value,
            -MAX_SPEED..=MAX_SPEED,
            "within 1e6 m/s either way",
        )?;
    }
    Ok(velocity)
}

/// Checks an angular velocity a body is given: finite and within [`MAX_ANGULAR_SPEED`].
pub(crate) fn check_spin(what: &'static str, spin: Real) -> Result<Real, CaromError> {
    check_within(
        what,
        spin,
        -MAX_ANGULAR_SPEED..=MAX_ANGULAR_SPEED,
        "within 1e6 rad/s either way",
    )
}

/// Checks a gravity scale: finite and within [`MAX_GRAVITY_SCALE`] either way.
pub(super) fn check_gravity_scale(scale: Real) -> Result<Real, CaromError> {
    let bound = MAX_GRAVITY_SCALE;
    check_within(
        "gravity scale",
        scale,
        -bound..=bound,
        "within 1000 either way",
    )
}

/// A sweep threshold: not negative, and not a number's absence (infinity, never swept, is
/// allowed).
pub(crate) fn check_sweep_threshold(fraction: Real) -> Result<Real, CaromError> {
    if fraction.is_nan() {
        return Err(CaromError::non_finite("sweep threshold", fraction));
    }
    if fraction >= 0.0 {
        Ok(fraction)
    } else {
        Err(CaromError::OutOfRange {
            name: "sweep threshold",
            expected: "zero or more (infinity never sweeps)",
            value: fraction,
        })
    }
}
