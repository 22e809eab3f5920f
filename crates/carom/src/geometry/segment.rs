//! Segments: lines of no thickness for static geometry, two-sided on their own or one-sided
//! as the links of a chain.
//!
//! A [`ChainSegment`] is one link of a chain ([`crate::ChainDef`]): it collides only on its
//! right side, seen walking from `point1` to `point2` (so a counter-clockwise loop collides on
//! its outside, like a polygon), and it knows its neighbours' far ends, its *ghost vertices*.
//! They tell the narrowphase which way the chain turns at each end, so a body sliding across
//! a join meets one smooth surface instead of catching on the corner of the next link (Box2D's
//! smooth collision; see `geometry::query::chain_segment`).
//!
//! Both keep the points they are given, in the collider's frame: they are not recentred.

use crate::constants::CONTAINMENT_TOLERANCE;
use crate::error::CaromError;
use crate::geometry::checks::{check_apart, check_point};
use crate::math::{Real, Vec2, perp_cw};

/// The nearest point to `p` on the segment `start`–`end`, and where along it (`0..=1`).
#[inline]
pub(crate) fn closest_on_segment(p: Vec2, start: Vec2, end: Vec2) -> (Vec2, Real) {
    let edge = end - start;
    let length_sq = edge.norm_squared();
    if length_sq == 0.0 {
        return (start, 0.0);
    }
    let t = ((p - start).dot(&edge) / length_sq).clamp(0.0, 1.0);
    (start + edge * t, t)
}

/// The closest points of segments `p1`–`q1` and `p2`–`q2` and where along each they lie
/// (`0..=1`): the unclamped closest points of the two lines, clamped to the first segment and
/// then found again on the second (a segment of no length is its start point).
pub(crate) fn closest_between_segments(
    (p1, q1): (Vec2, Vec2),
    (p2, q2): (Vec2, Vec2),
) -> ((Vec2, Real), (Vec2, Real)) {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (dd1, dd2) = (d1.norm_squared(), d2.norm_squared());
    let (rd1, rd2) = (r.dot(&d1), r.dot(&d2));
    let tiny = Real::EPSILON * Real::EPSILON;
    let (f1, f2) = if dd1 < tiny && dd2 < tiny {
        (0.0, 0.0)
    } else if dd1 < tiny {
        (0.0, (rd2 / dd2).clamp(0.0, 1.0))
    } else if dd2 < tiny {
        ((-rd1 / dd1).clamp(0.0, 1.0), 0.0)
    } else {
        let d12 = d1.dot(&d2);
        let denominator = dd1 * dd2 - d12 * d12;
        // Parallel lines: any point of the first will do, its start first.
        let f1 = if denominator != 0.0 {
            ((d12 * rd2 - rd1 * dd2) / denominator).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let f2 = (d12 * f1 + rd2) / dd2;
        if f2 < 0.0 {
            ((-rd1 / dd1).clamp(0.0, 1.0), 0.0)
        } else if f2 > 1.0 {
            (((d12 - rd1) / dd1).clamp(0.0, 1.0), 1.0)
        } else {
            (f1, f2)
        }
    };
    ((p1 + d1 * f1, f1), (p2 + d2 * f2, f2))
}

/// The distance from `point` to the segment `start`–`end`.
pub(crate) fn distance_to_segment(point: Vec2, start: Vec2, end: Vec2) -> Real {
    (closest_on_segment(point, start, end).0 - point).norm()
}

/// A two-sided line segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    point1: Vec2,
    point2: Vec2,
}

impl Segment {
    /// The segment from `point1` to `point2`, checked when it is added to a world or by
    /// [`Segment::validate`].
    pub fn new(point1: Vec2, point2: Vec2) -> Self {
        Segment { point1, point2 }
    }

    /// Checks the segment: finite ends within 100 km that do not coincide.
    ///
    /// # Errors
    /// The first value that is not so.
    pub fn validate(&self) -> Result<(), CaromError> {
        check_point(("segment point1", "segment coordinate"), self.point1)?;
        check_point(("segment point2", "segment coordinate"), self.point2)?;
        check_apart("segment ends", self.point1, self.point2)
    }

    /// The first end.
    #[inline]
    pub fn point1(&self) -> Vec2 {
        self.point1
    }

    /// The second end.
    #[inline]
    pub fn point2(&self) -> Vec2 {
        self.point2
    }

    /// True when the local point lies on the segment (within the containment tolerance).
    pub fn contains_local(&self, point: Vec2) -> bool {
        distance_to_segment(point, self.point1, self.point2) <= CONTAINMENT_TOLERANCE
    }
}

/// One link of a chain: a one-sided segment with its neighbours' far ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainSegment {
    ghost1: Vec2,
    segment: Segment,
    ghost2: Vec2,
}

impl ChainSegment {
    /// The link from `point1` to `point2`, whose neighbours run from `ghost1` to `point1` and
    /// from `point2` to `ghost2`. Checked when it is added to a world, or by
    /// [`ChainSegment::validate`]; [`crate::ChainDef`] makes whole chains.
    pub fn new(ghost1: Vec2, point1: Vec2, point2: Vec2, ghost2: Vec2) -> Self {
        ChainSegment {
            ghost1,
            segment: Segment::new(point1, point2),
            ghost2,
        }
    }

    /// Checks the link: finite points within 100 km, each different from the next.
    ///
    /// # Errors
    /// The first value that is not so.
    pub fn validate(&self) -> Result<(), CaromError> {
        check_point(("chain ghost1", "chain coordinate"), self.ghost1)?;
        check_point(("chain ghost2", "chain coordinate"), self.ghost2)?;
        self.segment.validate()?;
        check_apart("chain ghost1 and point1", self.ghost1, self.point1())?;
        check_apart("chain point2 and ghost2", self.point2(), self.ghost2)
    }

    /// The segment itself.
    #[inline]
    pub fn segment(&self) -> Segment {
        self.segment
    }

    /// The previous link's first point.
    #[inline]
    pub fn ghost1(&self) -> Vec2 {
        self.ghost1
    }

    /// The first end.
    #[inline]
    pub fn point1(&self) -> Vec2 {
        self.segment.point1
    }

    /// The second end.
    #[inline]
    pub fn point2(&self) -> Vec2 {
        self.segment.point2
    }

    /// The next link's second point.
    #[inline]
    pub fn ghost2(&self) -> Vec2 {
        self.ghost2
    }

    /// The unit normal of the side that collides: to the right of `point1` → `point2`.
    pub fn normal(&self) -> Vec2 {
        perp_cw(self.point2() - self.point1()).normalize()
    }

    /// True when the local point lies on the segment (within the containment tolerance).
    pub fn contains_local(&self, point: Vec2) -> bool {
        self.segment.contains_local(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn closest_points_between_segments() {
        let close = |a, b| closest_between_segments(a, b);
        // Crossing: the crossing point, on both.
        let ((p, f), (q, g)) = close(
            (vec2(-1.0, 0.0), vec2(1.0, 0.0)),
            (vec2(0.5, -1.0), vec2(0.5, 1.0)),
        );
        assert!((p - vec2(0.5, 0.0)).norm() < 1e-6 && (q - p).norm() < 1e-6);
        assert!((f - 0.75).abs() < 1e-6 && (g - 0.5).abs() < 1e-6);
        // End to end: both ends, fractions exactly 1 and 0.
        let ((p, f), (q, g)) = close(
            (vec2(0.0, 0.0), vec2(1.0, 1.0)),
            (vec2(2.0, 1.5), vec2(3.0, 1.0)),
        );
        assert_eq!((p, f, q, g), (vec2(1.0, 1.0), 1.0, vec2(2.0, 1.5), 0.0));
        // Parallel and overlapping along their length: a pair of points one gap apart.
        let ((p, _), (q, _)) = close(
            (vec2(0.0, 0.0), vec2(2.0, 0.0)),
            (vec2(1.0, 0.5), vec2(3.0, 0.5)),
        );
        assert!(((q - p).norm() - 0.5).abs() < 1e-6);
        // A segment of no length is a point.
        let ((p, f), (q, _)) = close(
            (vec2(0.0, 2.0), vec2(0.0, 2.0)),
            (vec2(-1.0, 0.0), vec2(1.0, 0.0)),
        );
        assert_eq!((p, f), (vec2(0.0, 2.0), 0.0));
        assert!((q - vec2(0.0, 0.0)).norm() < 1e-6);
    }
}
