//! Circles.

use crate::constants::CONTAINMENT_TOLERANCE;
use crate::error::{CaromError, check_finite};
use crate::geometry::checks::check_extent;
use crate::math::{Real, Vec2};

/// A circle centred on its body's centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    radius: Real,
}

impl Circle {
    /// A circle of the given radius. The radius must be finite and positive, which
    /// [`Circle::validate`] checks (a world checks it when the circle is added).
    pub fn new(radius: Real) -> Self {
        Circle { radius }
    }

    /// Checks the radius: finite, positive, within 100 km.
    ///
    /// # Errors
    /// A radius that is not all three.
    pub fn validate(&self) -> Result<(), CaromError> {
        check_finite("circle radius", self.radius)?;
        if self.radius <= 0.0 {
            return Err(CaromError::InvalidRadius {
                radius: self.radius,
            });
        }
        check_extent("circle radius", self.radius)
    }

    /// The radius.
    #[inline]
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// True when the local point lies inside or on the circle.
    #[inline]
    pub fn contains_local(&self, point: Vec2) -> bool {
        let r = self.radius + CONTAINMENT_TOLERANCE;
        point.norm_squared() <= r * r
    }
}
