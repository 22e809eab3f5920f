//! Capsules: a segment grown by a radius, a rectangle with half circles at its ends.
//!
//! A capsule is given by the centres of its two end circles and their radius, in the collider's
//! frame: unlike circles and polygons it is not recentred, so `(-h, 0)`–`(h, 0)` is centred and
//! `(0, 0)`–`(0, 2h)` stands on its first centre. Collision treats it as a two-vertex polygon
//! rounded by its radius, which is what it is.

use crate::constants::CONTAINMENT_TOLERANCE;
use crate::error::{CaromError, check_finite};
use crate::geometry::checks::{check_apart, check_extent, check_point};
use crate::geometry::segment::distance_to_segment;
use crate::math::{Real, Vec2};

/// Two circles' centres and their radius, joined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Capsule {
    center1: Vec2,
    center2: Vec2,
    radius: Real,
}

impl Capsule {
    /// A capsule through `center1` and `center2` of the given radius. The values are checked
    /// when the capsule is added to a world, or by [`Capsule::validate`].
    pub fn new(center1: Vec2, center2: Vec2, radius: Real) -> Self {
        Capsule {
            center1,
            center2,
            radius,
        }
    }

    /// Checks the capsule: finite centres within 100 km that do not coincide, and a finite,
    /// positive radius within 100 km.
    ///
    /// # Errors
    /// The first value that is not so.
    pub fn validate(&self) -> Result<(), CaromError> {
        check_point(("capsule center1", "capsule coordinate"), self.center1)?;
        check_point(("capsule center2", "capsule coordinate"), self.center2)?;
        check_finite("capsule radius", self.radius)?;
        if self.radius <= 0.0 {
            return Err(CaromError::InvalidRadius {
                radius: self.radius,
            });
        }
        check_extent("capsule radius", self.radius)?;
        check_apart("capsule centres", self.center1, self.center2)
    }

    /// The first centre.
    #[inline]
    pub fn center1(&self) -> Vec2 {
        self.center1
    }

    /// The second centre.
    #[inline]
    pub fn center2(&self) -> Vec2 {
        self.center2
    }

    /// The radius.
    #[inline]
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// The distance between the centres.
    #[inline]
    pub fn length(&self) -> Real {
        (self.center2 - self.center1).norm()
    }

    /// True when the local point lies inside or on the capsule.
    pub fn contains_local(&self, point: Vec2) -> bool {
        distance_to_segment(point, self.center1, self.center2)
            <= self.radius + CONTAINMENT_TOLERANCE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn bad_capsules_are_named_errors() {
        let good = Capsule::new(vec2(-1.0, 0.0), vec2(1.0, 0.0), 0.5);
        assert!(good.validate().is_ok());
        assert!((good.length() - 2.0).abs() < 1e-6);
        let same = Capsule::new(vec2(1.0, 2.0), vec2(1.0, 2.0), 0.5).validate();
        assert!(matches!(same, Err(CaromError::CoincidentPoints { .. })));
        assert!(same.unwrap_err().to_string().contains("capsule centres"));
        assert!(
            Capsule::new(vec2(0.0, 0.0), vec2(1.0, 0.0), 0.0)
                .validate()
                .is_err()
        );
        assert!(
            Capsule::new(vec2(0.0, Real::NAN), vec2(1.0, 0.0), 0.1)
                .validate()
                .is_err()
        );
        assert!(
            Capsule::new(vec2(0.0, 0.0), vec2(1.0e6, 0.0), 0.1)
                .validate()
                .is_err()
        );
    }

    #[test]
    fn containment_is_within_the_radius_of_the_core() {
        let capsule = Capsule::new(vec2(-1.0, 0.0), vec2(1.0, 0.0), 0.5);
        assert!(capsule.contains_local(vec2(0.0, 0.5)));
        assert!(capsule.contains_local(vec2(1.4, 0.2)));
        assert!(!capsule.contains_local(vec2(1.4, 0.4)));
        assert!(!capsule.contains_local(vec2(0.0, 0.51)));
    }
}
