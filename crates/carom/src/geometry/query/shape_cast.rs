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
