//! Smooth collision against chains: Box2D v3's answer to ghost collisions.
//!
//! A chain is a run of one-sided segments. A body sliding along it meets each join between two
//! links; tested against the next link alone, the body's leading corner would find that link's
//! end and be pushed back along the chain, catching on a join that is flat in fact (a *ghost*
//! collision). Each link therefore knows its neighbours' far ends (its ghost vertices), and with
//! them the directions in which it may push (its Gauss map, see
//! <https://box2d.org/posts/2020/06/ghost-collisions/>):
//!
//! - across its own face, always;
//! - round a *convex* end (the chain turns away from the body there), in the directions between
//!   its normal and its neighbour's; directions beyond the neighbour's normal are the
//!   neighbour's to handle, and this link skips them;
//! - at a *concave* or flat end, only its own normal: a normal leaning toward that end is
//!   snapped back to the link's, so the body meets the surface, not the corner.
//!
//! The rest is the polygon machinery: the link is the reference face or the polygon's admitted
//! face is, and the other side's edge is clipped against it. A shape whose centre is behind
//! the link (and behind its convex neighbours) does not collide at all: chains are one-sided.

use super::distance;
use super::manifold::{Core, FeatureId, Manifold, Margins};
use crate::constants::{CHAIN_CONVEX_SINE, CHAIN_NORMAL_SINE, LINEAR_SLOP};
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2, cross, perp_cw};

/// A chain's link in world coordinates.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChainLink {
    ghost1: Vec2,
    point1: Vec2,
    point2: Vec2,
    ghost2: Vec2,
}

impl ChainLink {
    /// The link of a placed chain segment.
    #[allow(
        clippy::unreachable,
        reason = "links are made only of chain segments: the caller matched the shape first"
    )]
    pub(crate) fn of(shape: &WorldShape) -> Self {
        match *shape {
            WorldShape::ChainSegment {
                ghost1,
                point1,
                point2,
                ghost2,
            } => ChainLink {
                ghost1,
                point1,
                point2,
                ghost2,
            },
            _ => unreachable!("only chain segments are links"),
        }
    }
}

/// What a contact normal means to a link.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum NormalKind {
    /// Past a convex end, beyond the neighbour's normal: the neighbour's contact.
    Skip,
    /// Within the link's own directions: used as it is.
    Admit,
    /// Toward a concave or flat end: replaced by the link's own normal.
    Snap,
}

/// A link's normal and its neighbours', and which of its ends are convex.
#[derive(Debug, Clone, Copy)]
struct GaussMap {
    /// Unit direction from `point1` to `point2`.
    edge1: Vec2,
    normal0: Vec2,
    normal1: Vec2,
    normal2: Vec2,
    convex1: bool,
    convex2: bool,
}

impl GaussMap {
    fn of(link: &ChainLink) -> Self {
        let edge0 = (link.point1 - link.ghost1).normalize();
        let edge1 = (link.point2 - link.point1).normalize();
        let edge2 = (link.ghost2 - link.point2).normalize();
        GaussMap {
            edge1,
            normal0: perp_cw(edge0),
            normal1: perp_cw(edge1),
            normal2: perp_cw(edge2),
            convex1: cross(edge0, edge1) >= CHAIN_CONVEX_SINE,
            convex2: cross(edge1, edge2) >= CHAIN_CONVEX_SINE,
        }
    }

    fn classify(&self, normal: Vec2) -> NormalKind {
        let (convex, beyond) = if normal.dot(&self.edge1) <= 0.0 {
            // Leaning toward the tail, `point1`.
            (self.convex1, cross(normal, self.normal0))
        } else {
            (self.convex2, cross(self.normal2, normal))
        };
        match (convex, beyond > CHAIN_NORMAL_SINE) {
            (false, _) => NormalKind::Snap,
            (true, true) => NormalKind::Skip,
            (true, false) => NormalKind::Admit,
        }
    }

    /// The neighbours' normals, a concave neighbour's replaced by the link's own.
    fn neighbour_normals(&self) -> (Vec2, Vec2) {
        (
            if self.convex1 {
                self.normal0
            } else {
                self.normal1
            },
            if self.convex2 {
                self.normal2
            } else {
                self.normal1
            },
        )
    }
}

/// The manifold of a link (A) and another shape (B); the normal points from the link.
/// Chains do not collide with chains.
pub(crate) fn collide(link: &ChainLink, other: &WorldShape, margins: Margins) -> Manifold {
    match other {
        WorldShape::Circle { center, radius } => collide_circle(link, *center, *radius, margins),
        WorldShape::Polygon {
            vertices,
            normals,
            radius,
        } => collide_polygon(link, Core::new(vertices, normals, *radius), margins),
        WorldShape::ChainSegment { .. } => Manifold::default(),
    }
}

/// A link against a circle: the nearest point of the link, unless the centre is behind it or
/// in a neighbour's region.
fn collide_circle(link: &ChainLink, center: Vec2, radius: Real, margins: Margins) -> Manifold {
    let (p1, p2) = (link.point1, link.point2);
    let edge = p2 - p1;
    let normal1 = perp_cw(edge).normalize();
    let empty = Manifold::with_normal(normal1);
    if normal1.dot(&(center - p1)) < 0.0 {
        return empty;
    }
    // Where the centre projects: before the link, after it, or on it.
    let before = edge.dot(&(center - p1));
    let after = edge.dot(&(p2 - center));
    let (nearest, at_end) = if before <= 0.0 {
        // In the previous link's region unless past its end too.
        if (p1 - link.ghost1).dot(&(center - p1)) <= 0.0 {
            return empty;
        }
        (p1, true)
    } else if after <= 0.0 {
        if (link.ghost2 - p2).dot(&(center - p2)) > 0.0 {
            return empty;
        }
        (p2, true)
    } else {
        (p1 + edge * (before / edge.norm_squared()), false)
    };
    let offset = center - nearest;
    let distance = offset.norm();
    let normal = if distance > Real::EPSILON * (1.0 + center.norm()) {
        offset / distance
    } else {
        normal1
    };
    let separation = distance - radius;
    let margin = if at_end { margins.any } else { margins.face };
    if separation > margin {
        return empty;
    }
    let mut manifold = Manifold::with_normal(normal);
    manifold.push(
        nearest + normal * (0.5 * separation),
        separation,
        FeatureId::SINGLE,
    );
    manifold
}

/// Which edge of the polygon meets the link's face.
enum Incident {
    /// The edge next to this vertex that faces the link most squarely.
    Vertex(usize),
    /// This edge.
    Edge(usize),
}

/// A link against a convex core grown by its radius (a polygon, rounded or not, or a capsule).
#[allow(
    clippy::expect_used,
    reason = "a polygon has at least three vertices, so the ranges over them are not empty"
)]
fn collide_polygon(link: &ChainLink, polygon: Core, margins: Margins) -> Manifold {
    let map = GaussMap::of(link);
    let (p1, p2) = (link.point1, link.point2);
    let normal1 = map.normal1;
    let empty = Manifold::with_normal(normal1);
    let count = polygon.vertices.len();
    let centroid = polygon.vertices.iter().sum::<Vec2>() / count as Real;
    let behind = |normal: Vec2, point: Vec2| normal.dot(&(centroid - point)) < 0.0;
    let behind1 = behind(normal1, p1);
    let behind0 = !map.convex1 || behind(map.normal0, p1);
    let behind2 = !map.convex2 || behind(map.normal2, p2);
    if behind1 && behind0 && behind2 {
        return empty;
    }
    let pp = distance::polygon_polygon_within(
        &[p1, p2],
        &[normal1, -normal1],
        polygon.vertices,
        polygon.normals,
        0.1 * LINEAR_SLOP,
        |separation| separation - polygon.radius > margins.face,
    );
    if pp.separation.separation - polygon.radius > margins.face {
        return empty;
    }

    let mut incident = None;
    if !behind1 && let Some(closest) = pp.closest {
        // Apart: the closest features may be two corners, or a corner and an edge, even when
        // the contact ought to be face to face.
        // Corners closer than rounding can tell apart (a segment ending on the link's end) give
        // no direction: the link's face decides, as for a corner on it.
        let apart = closest.distance > Real::EPSILON * (1.0 + closest.point_a.norm());
        match (closest.vertex_a, closest.vertex_b) {
            (Some(_), Some(corner)) if !apart => incident = Some(Incident::Vertex(corner)),
            (Some(end), Some(corner)) => {
                let normal = (closest.point_b - closest.point_a) / closest.distance;
                match map.classify(normal) {
                    NormalKind::Skip => return empty,
                    NormalKind::Admit => {
                        let separation = closest.distance - polygon.radius;
                        let mut manifold = Manifold::with_normal(normal);
                        if separation <= margins.any {
                            manifold.push(
                                closest.point_a + normal * (0.5 * separation),
                                separation,
                                FeatureId::vertex_pair(end, corner),
                            );
                        }
                        return manifold;
                    }
                    NormalKind::Snap => incident = Some(Incident::Vertex(corner)),
                }
            }
            (Some(_), None) => {
                // A link's end against a face of the polygon: which face.
                let toward_link = closest.point_a - closest.point_b;
                let face = (0..count)
                    .max_by(|&i, &j| {
                        let (di, dj) = (
                            polygon.normals[i].dot(&toward_link),
                            polygon.normals[j].dot(&toward_link),
                        );
                        di.total_cmp(&dj)
                    })
                    .expect("a core has edges");
                match map.classify(-polygon.normals[face]) {
                    NormalKind::Skip => return empty,
                    NormalKind::Admit => return polygon_face(link, &map, polygon, face, margins),
                    NormalKind::Snap => incident = Some(Incident::Edge(face)),
                }
            }
            (None, Some(corner)) => incident = Some(Incident::Vertex(corner)),
            (None, None) => {}
        }
    }

    let incident = match incident {
        Some(incident) => incident,
        None => {
            // Touching or overlapping: the separating axis among the link's normal, its convex
            // neighbours' and the polygon's admitted faces.
            let deepest = |normal: Vec2, from: Vec2| {
                (0..count)
                    .map(|i| (i, normal.dot(&(polygon.vertices[i] - from))))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .expect("a core has vertices")
            };
            let (deepest_vertex, mut edge_separation) = deepest(normal1, p1);
            let mut neighbour_owns = false;
            for (convex, normal, at) in [
                (map.convex1, map.normal0, p1),
                (map.convex2, map.normal2, p2),
            ] {
                if convex {
                    let (_, s) = deepest(normal, at);
                    if s > edge_separation {
                        edge_separation = s;
                        neighbour_owns = true;
                    }
                }
            }
            let mut best_face = None;
            let mut face_separation = Real::NEG_INFINITY;
            for i in 0..count {
                let n = polygon.normals[i];
                if map.classify(-n) != NormalKind::Admit {
                    continue;
                }
                let v = polygon.vertices[i];
                let s = n.dot(&(p2 - v)).min(n.dot(&(p1 - v)));
                if s > face_separation {
                    face_separation = s;
                    best_face = Some(i);
                }
            }
            if let Some(face) = best_face
                && face_separation > edge_separation
            {
                return polygon_face(link, &map, polygon, face, margins);
            }
            if neighbour_owns {
                return empty;
            }
            Incident::Vertex(deepest_vertex)
        }
    };

    // The link's face is the reference; clip the polygon's edge that faces it.
    let (b1, b2) = match incident {
        Incident::Edge(i) => (i, (i + 1) % count),
        Incident::Vertex(i2) => {
            let i1 = (i2 + count - 1) % count;
            if normal1.dot(&polygon.normals[i1]) < normal1.dot(&polygon.normals[i2]) {
                (i1, i2)
            } else {
                (i2, (i2 + 1) % count)
            }
        }
    };
    clip_segments(
        Side {
            start: p1,
            end: p2,
            radius: 0.0,
        },
        Side {
            start: polygon.vertices[b1],
            end: polygon.vertices[b2],
            radius: polygon.radius,
        },
        normal1,
        [(false, 0, b2), (false, 1, b1)],
        margins.face,
    )
}

/// The polygon's face `face` as the reference, the link clipped against it; nothing when a
/// neighbour of the link faces it better.
fn polygon_face(
    link: &ChainLink,
    map: &GaussMap,
    polygon: Core,
    face: usize,
    margins: Margins,
) -> Manifold {
    let count = polygon.vertices.len();
    let (a1, a2) = (polygon.vertices[face], polygon.vertices[(face + 1) % count]);
    let normal = polygon.normals[face];
    let (n0, n2) = map.neighbour_normals();
    // The link's end that reaches deeper toward the face decides which neighbour competes.
    let neighbour = if normal.dot(&(link.point1 - a1)) < normal.dot(&(link.point2 - a1)) {
        n0
    } else {
        n2
    };
    if neighbour.dot(&normal) < map.normal1.dot(&normal) {
        return Manifold::with_normal(-normal);
    }
    clip_segments(
        Side {
            start: a1,
            end: a2,
            radius: polygon.radius,
        },
        Side {
            start: link.point1,
            end: link.point2,
            radius: 0.0,
        },
        normal,
        [(true, face, 1), (true, (face + 1) % count, 0)],
        margins.face,
    )
    .flipped()
}

/// One side of a clip: a segment grown by a radius.
#[derive(Debug, Clone, Copy)]
struct Side {
    start: Vec2,
    end: Vec2,
    radius: Real,
}

/// Clips the incident segment (which runs against the reference) to the reference's extent
/// along it; the points, midway between the grown surfaces, are kept up to `margin` apart.
/// The normal points from the reference to the incident side; `ids` name the lower and upper
/// point as `(reference_on_b, reference_vertex, incident_vertex)`.
fn clip_segments(
    reference: Side,
    incident: Side,
    normal: Vec2,
    ids: [(bool, usize, usize); 2],
    margin: Real,
) -> Manifold {
    let mut manifold = Manifold::with_normal(normal);
    let tangent = Vec2::new(-normal.y, normal.x);
    let upper1 = (reference.end - reference.start).dot(&tangent);
    let upper2 = (incident.start - reference.start).dot(&tangent);
    let lower2 = (incident.end - reference.start).dot(&tangent);
    if upper2 < 0.0 || upper1 < lower2 {
        return manifold;
    }
    let span = upper2 - lower2;
    let at = |s: Real| incident.end + (incident.start - incident.end) * ((s - lower2) / span);
    let lower = if lower2 < 0.0 && span > Real::EPSILON {
        at(0.0)
    } else {
        incident.end
    };
    let upper = if upper2 > upper1 && span > Real::EPSILON {
        at(upper1)
    } else {
        incident.start
    };
    let rounding = reference.radius + incident.radius;
    for (point, (on_b, reference_vertex, incident_vertex)) in [lower, upper].into_iter().zip(ids) {
        let gap = (point - reference.start).dot(&normal);
        let separation = gap - rounding;
        if separation > margin {
            continue;
        }
        manifold.push(
            point + normal * (0.5 * (reference.radius - incident.radius - gap)),
            separation,
            FeatureId::clipped(on_b, reference_vertex, incident_vertex),
        );
    }
    manifold
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::query::collide::collide as two_sided;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    /// A link from `point1` to `point2` (solid on its right: below, for one running left)
    /// between neighbours ending at `ghost1` and `ghost2`.
    fn link(ghost1: Vec2, point1: Vec2, point2: Vec2, ghost2: Vec2) -> WorldShape {
        WorldShape::ChainSegment {
            ghost1,
            point1,
            point2,
            ghost2,
        }
    }

    /// A flat floor's link from x = 1 to x = -1 (its normal up), with flat neighbours.
    fn flat() -> WorldShape {
        link(
            vec2(3.0, 0.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
            vec2(-3.0, 0.0),
        )
    }

    fn placed(shape: &Shape, x: Real, y: Real, angle: Real) -> WorldShape {
        WorldShape::at(shape, vec2(x, y), angle)
    }

    fn meet(chain: &WorldShape, other: &WorldShape, margin: Real) -> Manifold {
        collide(&ChainLink::of(chain), other, Margins::plain(margin))
    }

    fn close(a: Vec2, b: Vec2, tolerance: Real) -> bool {
        (a - b).norm() <= tolerance
    }

    fn the_shapes() -> [Shape; 4] {
        [
            Shape::rect(0.3, 0.2),
            Shape::circle(0.25),
            Shape::polygon(&[vec2(-0.3, -0.1), vec2(0.3, -0.2), vec2(0.1, 0.3)]).unwrap(),
            Shape::rounded_rect(0.2, 0.1, 0.05),
        ]
    }

    /// Away from its ends, a link meets a shape as a two-sided segment does: the same normal,
    /// points and separations. (A circle's point may lie up to half the overlap apart along
    /// the normal: the link puts it midway between the surfaces, as Box2D does, the segment
    /// in the middle of what overlaps, which for a segment is on it.)
    #[test]
    fn on_its_face_a_link_is_a_segment() {
        let segment = WorldShape::at(
            &Shape::segment(vec2(1.0, 0.0), vec2(-1.0, 0.0)),
            Vec2::zeros(),
            0.0,
        );
        let mut compared = 0;
        for shape in the_shapes() {
            for (x, angle) in [(0.0, 0.0), (0.2, 0.1), (-0.15, -0.3), (0.1, 0.05)] {
                for depth in [-0.05, 0.0, 0.02] {
                    // The shape's lowest point `depth` below the floor.
                    let probe = placed(&shape, x, 0.0, angle);
                    let lowest = support_height(&probe);
                    let shape_at = placed(&shape, x, -lowest - depth, angle);
                    let chain = meet(&flat(), &shape_at, 0.1);
                    let plain = two_sided(&segment, &shape_at, 0.1);
                    assert!(
                        close(chain.normal, plain.normal, 1e-5)
                            && chain.points().len() == plain.points().len(),
                        "{shape:?} at {x}, {angle}: {chain:?} against {plain:?}"
                    );
                    assert!(chain.normal.y > 0.99, "{chain:?}");
                    for (c, p) in chain.points().iter().zip(plain.points()) {
                        let apart = c.point - p.point;
                        let along = perp_cw(chain.normal).dot(&apart).abs();
                        let across = chain.normal.dot(&apart).abs();
                        assert!(
                            along < 1e-5 && across <= 0.5 * c.separation.abs() + 1e-5,
                            "{chain:?} against {plain:?}"
                        );
                        assert!((c.separation - p.separation).abs() < 1e-5);
                    }
                    let deepest = chain.min_separation().unwrap();
                    assert!((deepest + depth).abs() < 1e-4, "{deepest} for {depth}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 48);
    }

    /// How far below `shape`'s centre its lowest point lies (negative: below).
    fn support_height(shape: &WorldShape) -> Real {
        match shape {
            WorldShape::Circle { center, radius } => center.y - radius,
            WorldShape::Polygon {
                vertices, radius, ..
            } => vertices.iter().map(|v| v.y).fold(Real::INFINITY, Real::min) - radius,
            _ => unreachable!(),
        }
    }

    /// A chain is one-sided: a shape whose centre is below a floor's link is not pushed up
    /// through it, though a two-sided segment would push it.
    #[test]
    fn a_shape_behind_a_link_meets_nothing() {
        let segment = WorldShape::at(
            &Shape::segment(vec2(1.0, 0.0), vec2(-1.0, 0.0)),
            Vec2::zeros(),
            0.0,
        );
        for shape in the_shapes() {
            let below = placed(&shape, 0.1, -0.1, 0.0);
            assert!(meet(&flat(), &below, 0.1).points().is_empty(), "{shape:?}");
            assert!(!two_sided(&segment, &below, 0.1).points().is_empty());
        }
    }

    /// A box sliding along a flat chain, a little sunk into it, is pushed straight up by
    /// whichever link meets it, wherever it is over the join: no ghost normal along the chain,
    /// which a lone segment gives at its end.
    #[test]
    fn a_box_over_a_flat_join_is_pushed_only_up() {
        let left = link(
            vec2(3.0, 0.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
            vec2(-3.0, 0.0),
        );
        let right = link(
            vec2(5.0, 0.0),
            vec2(3.0, 0.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
        );
        let lone = WorldShape::at(
            &Shape::segment(vec2(1.0, 0.0), vec2(-1.0, 0.0)),
            Vec2::zeros(),
            0.0,
        );
        let cube = Shape::rect(0.25, 0.25);
        let mut ghost_normals = 0;
        for k in 0..=100 {
            let x = 0.5 + 0.01 * k as Real;
            let at = placed(&cube, x, 0.24, 0.0);
            let mut touched = false;
            for chain in [&left, &right] {
                let manifold = meet(chain, &at, 0.05);
                for point in manifold.points() {
                    touched = true;
                    assert!(
                        close(manifold.normal, vec2(0.0, 1.0), 1e-5),
                        "at x = {x}: {manifold:?}"
                    );
                    assert!(
                        (point.separation + 0.01).abs() < 1e-4,
                        "at x = {x}: {point:?}"
                    );
                }
            }
            assert!(touched, "at x = {x} the box sinks into the floor unmet");
            let alone = two_sided(&lone, &at, 0.05);
            if !alone.points().is_empty() && alone.normal.x.abs() > 0.1 {
                ghost_normals += 1;
            }
        }
        assert!(ghost_normals > 0, "the lone segment was to catch the box");
    }

    /// A box wider than a link is clipped to the link's ends: its points lie at them.
    #[test]
    fn a_wide_box_is_clipped_to_the_link() {
        let plank = placed(&Shape::rect(3.0, 0.2), 0.0, 0.19, 0.0);
        let manifold = meet(&flat(), &plank, 0.05);
        let mut xs: Vec<Real> = manifold.points().iter().map(|p| p.point.x).collect();
        xs.sort_by(Real::total_cmp);
        assert_eq!(xs.len(), 2, "{manifold:?}");
        assert!(
            (xs[0] + 1.0).abs() < 1e-5 && (xs[1] - 1.0).abs() < 1e-5,
            "{xs:?}"
        );
        for point in manifold.points() {
            assert!((point.separation + 0.01).abs() < 1e-5);
            // Midway between the floor and the plank's face.
            assert!((point.point.y + 0.005).abs() < 1e-5, "{point:?}");
        }
        // Tilted, the lower end is deeper, and the point at each end says so.
        let tilted = placed(&Shape::rect(3.0, 0.2), 0.0, 0.25, 0.05);
        let manifold = meet(&flat(), &tilted, 0.5);
        let by_x = |x: Real| {
            manifold
                .points()
                .iter()
                .find(|p| (p.point.x - x).abs() < 1e-3)
                .map(|p| p.separation)
        };
        let (right, left) = (by_x(1.0).unwrap(), by_x(-1.0).unwrap());
        let rise = (2.0 * 0.05_f64.sin()) as Real;
        assert!(((right - left) - rise).abs() < 1e-3, "{left} {right}");
    }

    /// Points are kept up to the margin apart, not beyond.
    #[test]
    fn points_are_kept_within_the_margin() {
        for shape in the_shapes() {
            let probe = placed(&shape, 0.0, 0.0, 0.0);
            let above = placed(&shape, 0.0, -support_height(&probe) + 0.05, 0.0);
            let near = meet(&flat(), &above, 0.1);
            assert!(!near.points().is_empty(), "{shape:?}");
            for point in near.points() {
                assert!((point.separation - 0.05).abs() < 1e-5, "{point:?}");
            }
            assert!(meet(&flat(), &above, 0.04).points().is_empty(), "{shape:?}");
        }
    }

    /// A hilltop's top link, from x = 1 to x = -1 with both ends turning down (convex), and
    /// the slope beyond its end at x = 1, from (2, -1) up to (1, 0).
    fn hilltop() -> (WorldShape, WorldShape) {
        let top = link(
            vec2(2.0, -1.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
            vec2(-2.0, -1.0),
        );
        let slope = link(
            vec2(3.0, -2.0),
            vec2(2.0, -1.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
        );
        (top, slope)
    }

    /// Over a hilltop (both ends turn away, convex) a circle rolling round the corner is met
    /// at the corner, its normal along the line from the corner to its centre; in the wedge
    /// between the two links' normals both links meet it there, alike (as Box2D's do). On
    /// either face, only that face's link meets it.
    #[test]
    fn round_a_convex_end_a_circle_is_met_at_the_corner() {
        let (top, slope) = hilltop();
        let ball = Shape::circle(0.25);
        let corner = vec2(1.0, 0.0);
        for k in 0..=40 {
            // From straight up to along the slope's normal, (1, 1)/√2.
            let turn = (k as Real / 40.0) * crate::math::consts::FRAC_PI_4;
            let direction = vec2(turn.sin(), turn.cos());
            let center = corner + direction * 0.24;
            let at = placed(&ball, center.x, center.y, 0.0);
            let met: Vec<Manifold> = [meet(&top, &at, 0.0), meet(&slope, &at, 0.0)]
                .into_iter()
                .filter(|m| !m.points().is_empty())
                .collect();
            // Inside the wedge both meet it; on its edges at least the face's link does.
            let expected = if k == 0 || k == 40 { 1..=2 } else { 2..=2 };
            assert!(expected.contains(&met.len()), "at {turn} rad: {met:?}");
            for manifold in &met {
                assert!(close(manifold.normal, direction, 1e-4), "{manifold:?}");
                let point = manifold.points()[0];
                assert!((point.separation + 0.01).abs() < 1e-4, "{point:?}");
                assert!(
                    close(point.point, corner - direction * 0.005, 1e-4),
                    "{point:?}"
                );
            }
        }
        let on_top = placed(&ball, 0.5, 0.24, 0.0);
        assert_eq!(meet(&top, &on_top, 0.0).points().len(), 1);
        assert!(meet(&slope, &on_top, 0.0).points().is_empty());
        let slope_normal = vec2(1.0, 1.0).normalize();
        let on_slope = vec2(1.5, -0.5) + slope_normal * 0.24;
        let on_slope = placed(&ball, on_slope.x, on_slope.y, 0.0);
        assert!(meet(&top, &on_slope, 0.0).points().is_empty());
        let manifold = meet(&slope, &on_slope, 0.0);
        assert!(close(manifold.normal, slope_normal, 1e-5), "{manifold:?}");
    }

    /// The same for a box's corner over the hilltop: between the two links it is met, and
    /// every normal lies between the two links' own.
    #[test]
    fn round_a_convex_end_a_box_is_met_between_the_normals() {
        let (top, slope) = hilltop();
        let cube = Shape::rect(0.2, 0.2);
        let up = vec2(0.0, 1.0);
        let along_slope = vec2(1.0, 1.0).normalize();
        for k in 0..=20 {
            let turn = (k as Real / 20.0) * crate::math::consts::FRAC_PI_4;
            // The box turned with the direction, its bottom face's middle at the corner, sunk 0.01.
            let direction = vec2(turn.sin(), turn.cos());
            let center = vec2(1.0, 0.0) + direction * 0.19;
            let at = placed(&cube, center.x, center.y, -turn);
            let mut points = 0;
            for chain in [&top, &slope] {
                let manifold = meet(chain, &at, 0.0);
                if manifold.points().is_empty() {
                    continue;
                }
                points += manifold.points().len();
                let n = manifold.normal;
                assert!(
                    cross(n, up) >= -1e-4 && cross(along_slope, n) >= -1e-4,
                    "at {turn} rad: {manifold:?}"
                );
            }
            assert!(points > 0, "at {turn} rad the box is unmet");
        }
    }

    /// In a valley (the end turns toward the shape: concave) a shape whose nearest feature is
    /// the link's end is pushed along the link's own normal, not toward the end.
    #[test]
    fn at_a_concave_end_the_normal_snaps_to_the_link() {
        let valley = link(
            vec2(2.0, 1.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
            vec2(-3.0, 0.0),
        );
        let cube = Shape::rect(0.2, 0.2);
        // Each box's lowest corner over the link, short of its end at x = 1.
        for (x, angle) in [(0.7, 0.3), (0.75, -0.2), (0.8, 0.6)] {
            let at = placed(&cube, x, 0.25, angle);
            let probe = placed(&cube, x, 0.0, angle);
            let sunk = placed(&cube, x, -support_height(&probe) - 0.01, angle);
            for shape in [&at, &sunk] {
                let manifold = meet(&valley, shape, 0.5);
                if !manifold.points().is_empty() {
                    assert!(close(manifold.normal, vec2(0.0, 1.0), 1e-5), "{manifold:?}");
                }
            }
            assert!(
                !meet(&valley, &sunk, 0.0).points().is_empty(),
                "at {x}, {angle}"
            );
        }
    }

    /// The Gauss map of a link tells a convex end from a concave or flat one, and admits,
    /// skips or snaps normals as the end's kind and the neighbour's normal say.
    #[test]
    fn the_gauss_map_sorts_normals() {
        let map = |ghost1, ghost2| {
            GaussMap::of(&ChainLink {
                ghost1,
                point1: vec2(1.0, 0.0),
                point2: vec2(-1.0, 0.0),
                ghost2,
            })
        };
        let hill = map(vec2(2.0, -1.0), vec2(-2.0, -1.0));
        assert!(hill.convex1 && hill.convex2);
        assert!(close(hill.normal1, vec2(0.0, 1.0), 1e-6));
        assert!(close(hill.normal0, vec2(1.0, 1.0).normalize(), 1e-6));
        assert!(close(hill.normal2, vec2(-1.0, 1.0).normalize(), 1e-6));
        assert!(close(hill.edge1, vec2(-1.0, 0.0), 1e-6));
        let lean = |degrees: Real| {
            let r = degrees.to_radians();
            vec2(r.sin(), r.cos())
        };
        // Toward point1 (+x): admitted up to the neighbour's normal at 45°, skipped past it.
        assert_eq!(hill.classify(lean(0.0)), NormalKind::Admit);
        assert_eq!(hill.classify(lean(30.0)), NormalKind::Admit);
        assert_eq!(hill.classify(lean(44.0)), NormalKind::Admit);
        assert_eq!(hill.classify(lean(50.0)), NormalKind::Skip);
        // Toward point2 (-x), the same mirrored.
        assert_eq!(hill.classify(lean(-44.0)), NormalKind::Admit);
        assert_eq!(hill.classify(lean(-50.0)), NormalKind::Skip);
        // A valley on the point1 side, a hill on the other.
        let mixed = map(vec2(2.0, 1.0), vec2(-2.0, -1.0));
        assert!(!mixed.convex1 && mixed.convex2);
        assert_eq!(mixed.classify(lean(30.0)), NormalKind::Snap);
        assert_eq!(mixed.classify(lean(-30.0)), NormalKind::Admit);
        assert_eq!(mixed.neighbour_normals().0, mixed.normal1);
        assert_eq!(mixed.neighbour_normals().1, mixed.normal2);
        // Flat joins are not convex: normals leaning either way snap.
        let flat = map(vec2(3.0, 0.0), vec2(-3.0, 0.0));
        assert!(!flat.convex1 && !flat.convex2);
        assert_eq!(flat.classify(lean(10.0)), NormalKind::Snap);
        assert_eq!(flat.classify(lean(-10.0)), NormalKind::Snap);
        assert_eq!(flat.neighbour_normals(), (flat.normal1, flat.normal1));
    }

    /// A link's manifold is unchanged by moving the whole scene: it depends on where things
    /// are relative to each other, not on the origin.
    #[test]
    fn a_link_meets_the_same_wherever_it_is() {
        let moved = |p: Vec2| p + vec2(12.5, -7.25);
        let top = link(
            vec2(2.0, -1.0),
            vec2(1.0, 0.0),
            vec2(-1.0, 0.0),
            vec2(-3.0, 0.0),
        );
        let far = link(
            moved(vec2(2.0, -1.0)),
            moved(vec2(1.0, 0.0)),
            moved(vec2(-1.0, 0.0)),
            moved(vec2(-3.0, 0.0)),
        );
        for shape in the_shapes() {
            for x in [-1.1, -0.5, 0.9, 1.1] {
                let here = meet(&top, &placed(&shape, x, 0.2, 0.3), 0.1);
                let there = meet(&far, &placed(&shape, x + 12.5, 0.2 - 7.25, 0.3), 0.1);
                assert!(close(here.normal, there.normal, 1e-5), "{here:?} {there:?}");
                assert_eq!(here.points().len(), there.points().len());
                for (a, b) in here.points().iter().zip(there.points()) {
                    assert!(close(moved(a.point), b.point, 1e-4));
                    assert!((a.separation - b.separation).abs() < 1e-5);
                }
            }
        }
    }

    /// Chains do not collide with chains.
    #[test]
    fn links_do_not_meet_links() {
        let other = link(
            vec2(2.0, 0.1),
            vec2(0.5, 0.1),
            vec2(-0.5, -0.1),
            vec2(-2.0, -0.1),
        );
        assert!(meet(&flat(), &other, 1.0).points().is_empty());
    }
}
