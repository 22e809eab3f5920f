//! Ray casts against circles, polygons (rounded or not), capsules and segments.
//!
//! A ray is a segment: the points `origin + t * translation` for fractions `t` in `[0, 1]`.
//! A cast reports where the ray *enters* a shape; a ray that starts inside a shape does not hit
//! it (as in Box2D), so a query from inside a body looks past that body.

use crate::constants::CONTAINMENT_TOLERANCE;
use crate::math::{Real, Vec2, perp_cw};

/// A ray: from `origin` along `translation` (its length is the ray's reach).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec2,
    /// Where the ray goes: it ends at `origin + translation`.
    pub translation: Vec2,
}

impl Ray {
    /// A ray from `origin` along `translation`.
    #[inline]
    pub fn new(origin: Vec2, translation: Vec2) -> Self {
        Ray {
            origin,
            translation,
        }
    }

    /// The ray from `start` to `end`.
    #[inline]
    pub fn between(start: Vec2, end: Vec2) -> Self {
        Ray::new(start, end - start)
    }

    /// The point at `fraction` along the ray.
    #[inline]
    pub fn at(&self, fraction: Real) -> Vec2 {
        self.origin + self.translation * fraction
    }
}

/// Where a ray enters a shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// The entry point.
    pub point: Vec2,
    /// The shape's outward unit normal there.
    pub normal: Vec2,
    /// How far along the ray, in `[0, 1]`.
    pub fraction: Real,
}

/// Casts a ray against a circle. A circle without a positive, finite radius is never hit.
pub(crate) fn ray_cast_circle(center: Vec2, radius: Real, ray: &Ray) -> Option<RayHit> {
    let length = ray.translation.norm();
    if length == 0.0 || !length.is_finite() || !(radius > 0.0 && radius.is_finite()) {
        return None;
    }
    let direction = ray.translation / length;
    // Distance along the ray to the point closest to the centre, and how far that point is
    // from the centre: solving from the closest approach keeps precision for distant origins.
    let to_origin = ray.origin - center;
    let closest_along = -to_origin.dot(&direction);
    let closest = to_origin + direction * closest_along;
    let half_chord_sq = radius * radius - closest.norm_squared();
    if half_chord_sq < 0.0 {
        return None;
    }
    let distance = closest_along - half_chord_sq.sqrt();
    if distance < 0.0 || distance > length {
        return None;
    }
    let point = ray.origin + direction * distance;
    Some(RayHit {
        point,
        normal: (closest - direction * half_chord_sq.sqrt()) / radius,
        fraction: distance / length,
    })
}

/// Casts a ray against a convex polygon given by its counter-clockwise vertices and unit
/// outward normals (in the same frame as the ray).
///
/// The ray is clipped against each edge's half-plane: entering the last one is the hit. A ray
/// running along an edge's line counts as inside that half-plane, so it enters at the edge's
/// first corner, as geometry says; so does a ray that only touches a corner.
pub(crate) fn ray_cast_polygon(vertices: &[Vec2], normals: &[Vec2], ray: &Ray) -> Option<RayHit> {
    let length = ray.translation.norm();
    if length == 0.0 || !length.is_finite() {
        return None;
    }
    // A ray that only touches a corner enters and leaves at the same fraction; rounding may
    // order the two the wrong way by a hair, so they may cross by the containment tolerance.
    let slack = CONTAINMENT_TOLERANCE / length;
    let mut lower: Real = 0.0;
    let mut upper: Real = 1.0;
    let mut entry_edge = None;
    for (v, n) in vertices.iter().zip(normals) {
        // Distance of the origin behind this edge (positive: on the inner side).
        let depth = n.dot(&(v - ray.origin));
        let approach = n.dot(&ray.translation);
        if approach == 0.0 {
            if depth < -CONTAINMENT_TOLERANCE {
                return None;
            }
        } else {
            let t = depth / approach;
            if approach < 0.0 {
                if t > lower {
                    lower = t;
                    entry_edge = Some(n);
                }
            } else if t < upper {
                upper = t;
            }
            if upper + slack < lower {
                return None;
            }
        }
    }
    let normal = *entry_edge?;
    Some(RayHit {
        point: ray.at(lower),
        normal,
        fraction: lower,
    })
}

/// Casts a ray against a segment, from either side or, `one_sided`, only from the right of
/// `point1` → `point2` (a chain's colliding side). A ray along the segment's line misses it.
pub(crate) fn ray_cast_segment(
    point1: Vec2,
    point2: Vec2,
    one_sided: bool,
    ray: &Ray,
) -> Option<RayHit> {
    let edge = point2 - point1;
    let length = edge.norm();
    if length == 0.0 || !length.is_finite() {
        return None;
    }
    let mut normal = perp_cw(edge) / length;
    let approach = normal.dot(&ray.translation);
    if approach == 0.0 || (one_sided && approach > 0.0) {
        return None;
    }
    let fraction = normal.dot(&(point1 - ray.origin)) / approach;
    if !(0.0..=1.0).contains(&fraction) {
        return None;
    }
    let point = ray.at(fraction);
    let along = (point - point1).dot(&edge) / (length * length);
    if !(0.0..=1.0).contains(&along) {
        return None;
    }
    if approach > 0.0 {
        normal = -normal;
    }
    Some(RayHit {
        point,
        normal,
        fraction,
    })
}

/// Casts a ray against a capsule: the segment `center1`–`center2` grown by `radius`.
pub(crate) fn ray_cast_capsule(
    center1: Vec2,
    center2: Vec2,
    radius: Real,
    ray: &Ray,
) -> Option<RayHit> {
    let normal = perp_cw(center2 - center1).normalize();
    ray_cast_rounded(&[center1, center2], &[normal, -normal], radius, ray)
}

/// Casts a ray against a convex core (counter-clockwise vertices and outward unit normals, or
/// a capsule's two) grown by `radius`: the first of its faces, each `radius` out from an edge,
/// and its corners' circles that the ray meets. A ray starting inside never enters.
pub(crate) fn ray_cast_rounded(
    vertices: &[Vec2],
    normals: &[Vec2],
    radius: Real,
    ray: &Ray,
) -> Option<RayHit> {
    let length = ray.translation.norm();
    if length == 0.0 || !length.is_finite() {
        return None;
    }
    let n = vertices.len();
    let inside_core = n >= 3
        && vertices
            .iter()
            .zip(normals)
            .all(|(v, normal)| normal.dot(&(ray.origin - v)) <= 0.0);
    if inside_core || crate::geometry::polygon::distance_to_outline(vertices, ray.origin) < radius {
        return None;
    }
    let mut best: Option<RayHit> = None;
    let mut keep = |hit: RayHit| {
        if best.is_none_or(|b| hit.fraction < b.fraction) {
            best = Some(hit);
        }
    };
    for i in 0..n {
        let (start, end, normal) = (vertices[i], vertices[(i + 1) % n], normals[i]);
        let approach = normal.dot(&ray.translation);
        if approach < 0.0 {
            let fraction = normal.dot(&(start + normal * radius - ray.origin)) / approach;
            let edge = end - start;
            let along = (ray.at(fraction) - start).dot(&edge) / edge.norm_squared();
            if (0.0..=1.0).contains(&fraction) && (0.0..=1.0).contains(&along) {
                keep(RayHit {
                    point: ray.at(fraction),
                    normal,
                    fraction,
                });
            }
        }
        if let Some(hit) = ray_cast_circle(start, radius, ray) {
            keep(hit);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::Polygon;
    use crate::math::vec2;

    #[test]
    fn circle_hit_miss_and_inside() {
        let ray = Ray::new(vec2(-5.0, 0.0), vec2(10.0, 0.0));
        let hit = ray_cast_circle(vec2(0.0, 0.0), 1.0, &ray).unwrap();
        assert!((hit.point - vec2(-1.0, 0.0)).norm() < 1e-6);
        assert!((hit.normal - vec2(-1.0, 0.0)).norm() < 1e-6);
        assert!((hit.fraction - 0.4).abs() < 1e-6);
        assert!(ray_cast_circle(vec2(0.0, 3.0), 1.0, &ray).is_none());
        // Too short to reach.
        assert!(
            ray_cast_circle(
                vec2(0.0, 0.0),
                1.0,
                &Ray::new(vec2(-5.0, 0.0), vec2(3.0, 0.0))
            )
            .is_none()
        );
        // Degenerate circles are never hit (no NaN normal).
        assert!(ray_cast_circle(vec2(0.0, 0.0), 0.0, &ray).is_none());
        assert!(ray_cast_circle(vec2(0.0, 0.0), Real::NAN, &ray).is_none());
        // Starting inside: no entry.
        assert!(
            ray_cast_circle(
                vec2(0.0, 0.0),
                1.0,
                &Ray::new(vec2(0.0, 0.0), vec2(3.0, 0.0))
            )
            .is_none()
        );
        // Tangent ray grazes the top.
        let tangent = ray_cast_circle(
            vec2(0.0, 0.0),
            1.0,
            &Ray::new(vec2(-2.0, 1.0), vec2(4.0, 0.0)),
        )
        .unwrap();
        assert!((tangent.point - vec2(0.0, 1.0)).norm() < 1e-6);
    }

    #[test]
    fn segments_and_rounded_shapes() {
        let ray = Ray::new(vec2(0.5, 2.0), vec2(0.0, -4.0));
        let flat = (vec2(-1.0, 0.0), vec2(1.0, 0.0));
        // Walking from (1, 0) to (-1, 0), the right side is up.
        let hit = ray_cast_segment(flat.1, flat.0, true, &ray).unwrap();
        assert!((hit.point - vec2(0.5, 0.0)).norm() < 1e-6);
        assert_eq!(hit.normal, vec2(0.0, 1.0));
        // One-sided: the other way round the ray comes from behind.
        assert!(ray_cast_segment(flat.0, flat.1, true, &ray).is_none());
        assert_eq!(
            ray_cast_segment(flat.0, flat.1, false, &ray)
                .unwrap()
                .normal,
            vec2(0.0, 1.0)
        );
        // A capsule along x of radius 0.5: the top face, then the end cap.
        let hit = ray_cast_capsule(flat.0, flat.1, 0.5, &ray).unwrap();
        assert!((hit.point - vec2(0.5, 0.5)).norm() < 1e-6);
        assert!((hit.fraction - 0.375).abs() < 1e-6);
        let side = Ray::new(vec2(3.0, 0.0), vec2(-4.0, 0.0));
        let hit = ray_cast_capsule(flat.0, flat.1, 0.5, &side).unwrap();
        assert!((hit.point - vec2(1.5, 0.0)).norm() < 1e-6);
        assert!((hit.normal - vec2(1.0, 0.0)).norm() < 1e-6);
        // Inside: no entry.
        assert!(
            ray_cast_capsule(
                flat.0,
                flat.1,
                0.5,
                &Ray::new(vec2(1.2, 0.1), vec2(4.0, 0.0))
            )
            .is_none()
        );
        // A rounded square: the corner arc.
        let square = Polygon::rect(1.0, 1.0);
        let diagonal = Ray::new(vec2(3.0, 3.0), vec2(-3.0, -3.0));
        let hit = ray_cast_rounded(square.vertices(), square.normals(), 0.5, &diagonal).unwrap();
        let corner = vec2(1.0, 1.0) + vec2(1.0, 1.0).normalize() * 0.5;
        assert!((hit.point - corner).norm() < 1e-5);
    }

    #[test]
    fn polygon_hit_from_each_side() {
        let square = Polygon::rect(1.0, 1.0);
        let cast = |o: Vec2, d: Vec2| {
            ray_cast_polygon(square.vertices(), square.normals(), &Ray::new(o, d))
        };
        let hit = cast(vec2(-3.0, 0.5), vec2(4.0, 0.0)).unwrap();
        assert!((hit.point - vec2(-1.0, 0.5)).norm() < 1e-6);
        assert_eq!(hit.normal, vec2(-1.0, 0.0));
        assert!((hit.fraction - 0.5).abs() < 1e-6);
        let from_top = cast(vec2(0.2, 5.0), vec2(0.0, -10.0)).unwrap();
        assert_eq!(from_top.normal, vec2(0.0, 1.0));
        assert!(cast(vec2(-3.0, 2.0), vec2(6.0, 0.0)).is_none());
        assert!(cast(vec2(0.0, 0.0), vec2(6.0, 0.0)).is_none());
        assert!(cast(vec2(-3.0, 0.0), vec2(1.0, 0.0)).is_none());
    }
}
