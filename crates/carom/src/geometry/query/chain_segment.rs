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
