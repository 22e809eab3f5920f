//! What a body's own values must be to be accepted: a position within reach of the origin, and a
//! sweep threshold.

use crate::constants::MAX_POSITION;
use crate::error::{CaromError, check_finite_vec};
use crate::math::{Real, Vec2};

/// Checks a position a body is given: finite and within [`MAX_POSITION`] of the origin on
/// each axis.
pub(super) fn check_position(what: &'static str, position: Vec2) -> Result<Vec2, CaromError> {
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

/// A sweep threshold: not negative, and not a number's absence (infinity, never swept, is
/// allowed).
pub(crate) fn check_sweep_threshold(fraction: Real) -> Result<Real, CaromError> {
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
