//! Checks every shape constructor shares: finite values within the size carom supports.

use crate::constants::MAX_SHAPE_EXTENT;
use crate::error::{CaromError, check_finite_vec};
use crate::math::{Real, Vec2};

/// Checks that a shape's coordinate or size is no larger than [`MAX_SHAPE_EXTENT`].
pub(crate) fn check_extent(what: &'static str, value: Real) -> Result<(), CaromError> {
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

/// Checks a polygon point: finite and within [`MAX_SHAPE_EXTENT`].
pub(crate) fn check_point(what: &str, point: Vec2) -> Result<(), CaromError> {
    check_finite_vec(what, point)?;
    check_extent("polygon coordinate", point.x)?;
    check_extent("polygon coordinate", point.y)
}
