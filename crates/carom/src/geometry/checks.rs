//! Checks every shape constructor shares: finite values within the size carom supports.

use crate::constants::{LINEAR_SLOP, MAX_SHAPE_EXTENT, WELD_TOLERANCE};
use crate::error::{CaromError, check_finite, check_finite_vec};
use crate::math::{Real, Vec2};

/// Checks that a shape's coordinate or size is no larger than [`MAX_SHAPE_EXTENT`].
pub(crate) fn check_extent(what: &'static str, value: Real) -> Result<(), CaromError> {
    check_finite(what, value)?;
    if value.abs() <= MAX_SHAPE_EXTENT {
        Ok(())
    } else {
        Err(CaromError::OutOfRange {
            name: what,
            expected: "within 100 km (100000 m)",
            value,
        })
    }
}

/// Checks a shape's point: finite (`what` names it) and within [`MAX_SHAPE_EXTENT`]
/// (`coordinate` names its coordinates: "capsule coordinate").
pub(crate) fn check_point(
    (what, coordinate): (&str, &'static str),
    point: Vec2,
) -> Result<(), CaromError> {
    check_finite_vec(what, point)?;
    check_extent(coordinate, point.x)?;
    check_extent(coordinate, point.y)
}

/// Checks that two points are farther apart than rounding can blur.
pub(crate) fn check_apart(what: &str, p: Vec2, q: Vec2) -> Result<(), CaromError> {
    let extent = p.abs().max().max(q.abs().max()).max(1.0);
    // Shorter than the linear slop, a segment is a point to the solver, and its direction
    // (the normal of every contact with it) is rounding noise (Box2D refuses it too).
    if (q - p).norm() > (WELD_TOLERANCE * extent).max(LINEAR_SLOP) {
        Ok(())
    } else {
        Err(CaromError::CoincidentPoints {
            what: what.to_owned(),
            x: p.x,
            y: p.y,
        })
    }
}
