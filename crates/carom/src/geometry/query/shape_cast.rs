//! Shape cast: where a shape moved in a straight line, unturned, first meets another.
//!
//! Conservative advancement, as Box2D's `b2ShapeCast`: at the current fraction the exact
//! separation and its direction bound the gap along that direction, which closes no faster
//! than the translation's component along it; advancing by gap over that closing speed never
//! steps past contact, and for two convex shapes each advance lands closer (on a face, in one
//! advance). The cast stops when the gap is within [`SHAPE_CAST_TOLERANCE`], short of
//! touching, so the shape moved by the reported fraction does not overlap.

use crate::constants::{MAX_TIME_OF_IMPACT_ITERATIONS, SHAPE_CAST_TOLERANCE};
use crate::geometry::query::collide::collide;
use crate::geometry::query::distance::{closest_points, separation, with_core};
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2};

/// Where a cast shape first meets another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ShapeCastHit {
    /// How far along the translation, in `[0, max_fraction]`; 0 when the shapes already
    /// touch or overlap at the start.
    pub fraction: Real,
    /// Where they meet, on the other shape's surface (within the tolerance).
    pub point: Vec2,
    /// The other shape's outward unit normal there: the way the cast shape is pushed back.
    pub normal: Vec2,
}

/// Casts `shape` along `fraction * translation`, `fraction` in `[0, max_fraction]`, against
/// `other`. `scratch` is a copy of `shape` the cast moves (kept to reuse its storage across
/// casts; its content on entry does not matter).
pub(crate) fn cast_shape(
    shape: &WorldShape,
    translation: Vec2,
    other: &WorldShape,
    max_fraction: Real,
    scratch: &mut WorldShape,
) -> Option<ShapeCastHit> {
    scratch.clone_from(shape);
    let mut fraction: Real = 0.0;
    for _ in 0..MAX_TIME_OF_IMPACT_ITERATIONS {
        let s = separation(scratch, other);
        if s.separation < SHAPE_CAST_TOLERANCE {
            return Some(meeting(scratch, other, fraction));
        }
        // The rate the gap along `s.normal` (from the cast shape toward the other) closes.
        let closing = s.normal.dot(&translation);
        if closing <= 0.0 {
            return None;
        }
        let advance = s.separation / closing;
        fraction += advance;
        if fraction > max_fraction {
            return None;
        }
        scratch.translate(translation * advance);
    }
    // Still closing in after many small advances (a graze): this is as near as it gets, and
    // never past contact.
    Some(meeting(scratch, other, fraction))
}

/// The point and normal where `shape`, placed at its hit, meets `other`: the middle of their
/// contact points when the manifold has any (the middle of a face resting on a face), else
/// the nearest points of their cores.
fn meeting(shape: &WorldShape, other: &WorldShape, fraction: Real) -> ShapeCastHit {
    let manifold = collide(shape, other, 2.0 * SHAPE_CAST_TOLERANCE);
    let points = manifold.points();
    if !points.is_empty() {
        let sum: Vec2 = points.iter().map(|p| p.point).sum();
        return ShapeCastHit {
            fraction,
            point: sum / points.len() as Real,
            normal: -manifold.normal,
        };
    }
    // A chain link's manifold may be empty where its neighbour takes the contact; the cores'
    // nearest points still say where the shapes meet.
    let near = with_core(shape, |a, _, _| {
        with_core(other, |b, _, _| closest_points(a, b))
    });
    let toward = near.point_b - near.point_a;
    let normal = if toward.norm() > Real::EPSILON {
        -toward.normalize()
    } else {
        -separation(shape, other).normal
    };
    ShapeCastHit {
        fraction,
        point: near.point_b + normal * other.radius(),
        normal,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    fn cast(
        shape: &WorldShape,
        translation: Vec2,
        other: &WorldShape,
        max: Real,
    ) -> Option<ShapeCastHit> {
        cast_shape(shape, translation, other, max, &mut shape.clone())
    }

    #[test]
    fn a_box_cast_face_on_meets_the_middle_of_the_face_and_stops_there() {
        let mover = WorldShape::at(&Shape::rect(0.5, 0.5), vec2(0.0, 0.0), 0.0);
        let wall = WorldShape::at(&Shape::rect(0.5, 0.5), vec2(3.0, 0.0), 0.0);
        let hit = cast(&mover, vec2(4.0, 0.0), &wall, 1.0).expect("it meets the wall");
        assert!(
            (hit.fraction - 0.5).abs() <= SHAPE_CAST_TOLERANCE,
            "{hit:?}"
        );
        assert!((hit.normal - vec2(-1.0, 0.0)).norm() < 1e-5, "{hit:?}");
        // The middle of the two faces' shared patch, on the wall's face.
        assert!(
            (hit.point - vec2(2.5, 0.0)).norm() < 2.0 * SHAPE_CAST_TOLERANCE,
            "{hit:?}"
        );
        // Moved by the fraction, it touches and does not overlap.
        let mut moved = mover.clone();
        moved.translate(vec2(4.0, 0.0) * hit.fraction);
        let gap = separation(&moved, &wall).separation;
        assert!((-1e-5..SHAPE_CAST_TOLERANCE).contains(&gap), "{gap}");
    }

    #[test]
    fn a_cast_ends_at_its_max_fraction() {
        let mover = WorldShape::at(&Shape::circle(0.5), vec2(0.0, 0.0), 0.0);
        let wall = WorldShape::at(&Shape::rect(0.5, 2.0), vec2(3.0, 0.0), 0.0);
        // Contact at half the translation.
        assert!(cast(&mover, vec2(4.0, 0.0), &wall, 0.4).is_none());
        assert!(cast(&mover, vec2(4.0, 0.0), &wall, 0.6).is_some());
        // Moving away, or along the wall, it never meets it.
        assert!(cast(&mover, vec2(-4.0, 0.0), &wall, 1.0).is_none());
    }

    #[test]
    fn a_tilted_box_meets_the_floor_at_its_lowest_corner() {
        let angle = 0.3;
        let mover = WorldShape::at(&Shape::rect(0.5, 0.5), vec2(0.0, 2.0), angle);
        let floor = WorldShape::at(&Shape::rect(5.0, 0.5), vec2(0.0, -0.5), 0.0);
        let hit = cast(&mover, vec2(0.0, -4.0), &floor, 1.0).expect("it lands");
        // The corner lowest when turned by `angle`: (-0.5, -0.5) turned.
        let (s, c) = (angle.sin(), angle.cos());
        let corner = vec2(-0.5 * c + 0.5 * s, -0.5 * s - 0.5 * c) + vec2(0.0, 2.0);
        assert!((hit.point.x - corner.x).abs() < 1e-3, "{hit:?} {corner:?}");
        assert!(hit.point.y.abs() < 2.0 * SHAPE_CAST_TOLERANCE, "{hit:?}");
        assert!((hit.normal - vec2(0.0, 1.0)).norm() < 1e-5, "{hit:?}");
        assert!((hit.fraction * 4.0 - corner.y).abs() < 2.0 * SHAPE_CAST_TOLERANCE);
    }

    #[test]
    fn the_meeting_of_shapes_apart_faces_from_the_other_to_the_cast_one() {
        // Apart by more than the manifold's margin: the cores' nearest points say where.
        let a = WorldShape::at(&Shape::circle(0.5), vec2(1.0, 1.0), 0.0);
        let b = WorldShape::at(&Shape::circle(0.5), vec2(3.0, 1.0), 0.0);
        let hit = meeting(&a, &b, 0.25);
        assert_eq!(hit.fraction, 0.25);
        assert!((hit.normal - vec2(-1.0, 0.0)).norm() < 1e-6, "{hit:?}");
        assert!((hit.point - vec2(2.5, 1.0)).norm() < 1e-6, "{hit:?}");
    }

    #[test]
    fn the_meeting_of_overlapping_shapes_pushes_back_the_way_they_overlap_least() {
        // Crossed capsules: the cast one, nearer the other's left end, goes back left.
        let a = WorldShape::at(
            &Shape::capsule(vec2(0.0, -1.0), vec2(0.0, 1.0), 0.1),
            vec2(0.0, 0.0),
            0.0,
        );
        let b = WorldShape::at(
            &Shape::capsule(vec2(-1.0, 0.0), vec2(1.0, 0.0), 0.1),
            vec2(0.9, 0.0),
            0.0,
        );
        let hit = meeting(&a, &b, 0.0);
        assert!(hit.normal.x < -0.9, "{hit:?}");
    }
}
