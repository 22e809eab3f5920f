//! Segment-segment intersection.

use crate::math::{Real, Vec2, cross};

/// How two segments meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SegmentIntersection {
    /// They cross or touch at one point.
    Point {
        /// The common point.
        point: Vec2,
        /// Where it lies along the first segment, in `[0, 1]`.
        fraction_a: Real,
        /// Where it lies along the second segment, in `[0, 1]`.
        fraction_b: Real,
    },
    /// They are collinear and share a stretch from `start` to `end` (in the first segment's
    /// direction).
    Overlap {
        /// The end of the shared stretch nearest the first segment's start.
        start: Vec2,
        /// The other end.
        end: Vec2,
    },
}

/// Relative tolerance for "parallel" and "on the segment".
const TOLERANCE: Real = 1.0e-6;

/// Where the segments `a0–a1` and `b0–b1` meet, if they do. Touching counts.
pub fn intersect_segments(a0: Vec2, a1: Vec2, b0: Vec2, b1: Vec2) -> Option<SegmentIntersection> {
    let r = a1 - a0;
    let s = b1 - b0;
    let qp = b0 - a0;
    let scale = r
        .norm()
        .max(s.norm())
        .max(qp.norm())
        .max(Real::MIN_POSITIVE);
    let eps = TOLERANCE * scale * scale;
    let denom = cross(r, s);
    if denom.abs() > eps {
        let fraction_a = cross(qp, s) / denom;
        let fraction_b = cross(qp, r) / denom;
        let within = |t: Real| (-TOLERANCE..=1.0 + TOLERANCE).contains(&t);
        return (within(fraction_a) && within(fraction_b)).then(|| SegmentIntersection::Point {
            point: a0 + r * fraction_a.clamp(0.0, 1.0),
            fraction_a: fraction_a.clamp(0.0, 1.0),
            fraction_b: fraction_b.clamp(0.0, 1.0),
        });
    }
    // Parallel: they meet only if collinear.
    if cross(qp, r).abs() > eps || cross(qp, s).abs() > eps {
        return None;
    }
    let rr = r.norm_squared();
    if rr == 0.0 {
        // `a` is a point: find it on `b`.
        let ss = s.norm_squared();
        let fraction_b = if ss == 0.0 { 0.0 } else { (-qp).dot(&s) / ss };
        let on_b = (-TOLERANCE..=1.0 + TOLERANCE).contains(&fraction_b)
            && (b0 + s * fraction_b.clamp(0.0, 1.0) - a0).norm() <= TOLERANCE * scale;
        return on_b.then_some(SegmentIntersection::Point {
            point: a0,
            fraction_a: 0.0,
            fraction_b: fraction_b.clamp(0.0, 1.0),
        });
    }
    // Project `b`'s ends onto `a` and intersect the intervals. The shared stretch runs between
    // input end points, which are returned exactly rather than recomputed from fractions.
    let t0 = qp.dot(&r) / rr;
    let t1 = t0 + s.dot(&r) / rr;
    let ((t_lo, p_lo), (t_hi, p_hi)) = if t0 <= t1 {
        ((t0, b0), (t1, b1))
    } else {
        ((t1, b1), (t0, b0))
    };
    let (lo, start) = if t_lo > 0.0 { (t_lo, p_lo) } else { (0.0, a0) };
    let (hi, end) = if t_hi < 1.0 { (t_hi, p_hi) } else { (1.0, a1) };
    if lo > hi + TOLERANCE {
        return None;
    }
    if hi - lo <= TOLERANCE {
        let ss = s.norm_squared();
        let fraction_b = if ss == 0.0 {
            0.0
        } else {
            (start - b0).dot(&s) / ss
        };
        return Some(SegmentIntersection::Point {
            point: start,
            fraction_a: lo.clamp(0.0, 1.0),
            fraction_b: fraction_b.clamp(0.0, 1.0),
        });
    }
    Some(SegmentIntersection::Overlap { start, end })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn crossing_touching_and_missing() {
        let hit = intersect_segments(
            vec2(0.0, 0.0),
            vec2(2.0, 2.0),
            vec2(0.0, 2.0),
            vec2(2.0, 0.0),
        );
        assert_eq!(
            hit,
            Some(SegmentIntersection::Point {
                point: vec2(1.0, 1.0),
                fraction_a: 0.5,
                fraction_b: 0.5
            })
        );
        // T-junction: b ends on a.
        let touch = intersect_segments(
            vec2(0.0, 0.0),
            vec2(4.0, 0.0),
            vec2(1.0, 2.0),
            vec2(1.0, 0.0),
        );
        assert!(matches!(
            touch,
            Some(SegmentIntersection::Point {
                fraction_b: 1.0,
                ..
            })
        ));
        assert_eq!(
            intersect_segments(
                vec2(0.0, 0.0),
                vec2(1.0, 0.0),
                vec2(2.0, -1.0),
                vec2(2.0, 1.0)
            ),
            None
        );
        // Parallel, apart.
        assert_eq!(
            intersect_segments(
                vec2(0.0, 0.0),
                vec2(1.0, 0.0),
                vec2(0.0, 1.0),
                vec2(1.0, 1.0)
            ),
            None
        );
    }

    #[test]
    fn collinear_overlap_and_end_to_end() {
        assert_eq!(
            intersect_segments(
                vec2(0.0, 0.0),
                vec2(3.0, 0.0),
                vec2(4.0, 0.0),
                vec2(1.0, 0.0)
            ),
            Some(SegmentIntersection::Overlap {
                start: vec2(1.0, 0.0),
                end: vec2(3.0, 0.0)
            })
        );
        assert!(matches!(
            intersect_segments(
                vec2(0.0, 0.0),
                vec2(1.0, 0.0),
                vec2(1.0, 0.0),
                vec2(2.0, 0.0)
            ),
            Some(SegmentIntersection::Point {
                fraction_a: 1.0,
                fraction_b: 0.0,
                ..
            })
        ));
        assert_eq!(
            intersect_segments(
                vec2(0.0, 0.0),
                vec2(1.0, 0.0),
                vec2(2.0, 0.0),
                vec2(3.0, 0.0)
            ),
            None
        );
        // A degenerate segment (a point) on the other.
        assert!(matches!(
            intersect_segments(
                vec2(0.5, 0.0),
                vec2(0.5, 0.0),
                vec2(0.0, 0.0),
                vec2(1.0, 0.0)
            ),
            Some(SegmentIntersection::Point {
                fraction_b: 0.5,
                ..
            })
        ));
    }
}
