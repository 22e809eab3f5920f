//! Pairwise distance: how far apart two shapes are, or how deep they overlap (Box2D's
//! `distance.c` and the separating-axis helpers of its `manifold.c`).
//!
//! Every query answers with a [`Separation`]: a unit `normal` pointing **from shape A to
//! shape B** and a signed `separation` along it, the distance between the shapes when they
//! are apart and minus the penetration depth when they overlap. Moving B by the minimum
//! translation vector [`Separation::mtv`] (`normal × depth`) leaves the pair just touching.
//!
//! Polygon pairs use the separating axis theorem over both polygons' edge normals, which is
//! exact for overlap. Apart, SAT only gives a lower bound (two corners facing each other are
//! farther apart than either face says), so the exact distance between closest features is
//! computed too. Polygon–circle is exact in every Voronoi region: inside, across an edge, or
//! off a corner.

use crate::constants::COINCIDENT_NORMAL;
use crate::geometry::segment::closest_on_segment;
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2, perp_cw};

/// Where B stands relative to A along the direction that separates them best.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Separation {
    /// Unit direction from A to B.
    pub normal: Vec2,
    /// Distance along `normal`: positive apart, negative overlapping (minus the depth).
    pub separation: Real,
}

impl Separation {
    /// True when the shapes overlap (or touch).
    #[inline]
    pub fn is_overlapping(&self) -> bool {
        self.separation <= 0.0
    }

    /// The minimum translation vector: moving B by it separates the pair. Zero when apart.
    #[inline]
    pub fn mtv(&self) -> Vec2 {
        self.normal * (-self.separation).max(0.0)
    }

    /// The same separation seen from B.
    #[inline]
    pub fn flipped(self) -> Self {
        Separation {
            normal: -self.normal,
            separation: self.separation,
        }
    }
}

/// Signed separation of two placed shapes; see the module documentation. A chain segment
/// counts as a plain segment here, both sides solid: a query asks where shapes are, not which
/// way they may collide.
pub fn separation(a: &WorldShape, b: &WorldShape) -> Separation {
    match (a, b) {
        (
            WorldShape::Circle {
                center: ca,
                radius: ra,
            },
            WorldShape::Circle {
                center: cb,
                radius: rb,
            },
        ) => circle_circle(*ca, *ra, *cb, *rb),
        (WorldShape::Circle { .. }, _) => separation(b, a).flipped(),
        (_, WorldShape::Circle { center, radius }) => {
            with_core(a, |vertices, normals, rounding| {
                polygon_circle(vertices, normals, *center, radius + rounding).separation
            })
        }
        _ => with_core(a, |va, na, ra| {
            with_core(b, |vb, nb, rb| {
                let mut s = polygon_polygon(va, na, vb, nb).separation;
                s.separation -= ra + rb;
                s
            })
        }),
    }
}

/// Calls `f` with a polygon's or chain segment's core (vertices and outward normals) and its
/// rounding; a chain segment is a two-vertex core, both sides solid, and a circle a
/// one-vertex core rounded by its radius.
pub(crate) fn with_core<R>(shape: &WorldShape, f: impl FnOnce(&[Vec2], &[Vec2], Real) -> R) -> R {
    match shape {
        WorldShape::Polygon {
            vertices,
            normals,
            radius,
        } => f(vertices, normals, *radius),
        WorldShape::ChainSegment { point1, point2, .. } => {
            let normal = perp_cw(point2 - point1).normalize();
            f(&[*point1, *point2], &[normal, -normal], 0.0)
        }
        WorldShape::Circle { center, radius } => f(&[*center], &[], *radius),
    }
}

/// Two circles. Coincident centres separate along [`COINCIDENT_NORMAL`] by the sum of radii.
pub(crate) fn circle_circle(
    center_a: Vec2,
    radius_a: Real,
    center_b: Vec2,
    radius_b: Real,
) -> Separation {
    let offset = center_b - center_a;
    let distance = offset.norm();
    if distance > Real::EPSILON * (1.0 + center_a.norm()) {
        Separation {
            normal: offset / distance,
            separation: distance - radius_a - radius_b,
        }
    } else {
        // No direction to prefer: push B the full sum of radii along the fixed fallback.
        Separation {
            normal: COINCIDENT_NORMAL,
            separation: -(radius_a + radius_b),
        }
    }
}

/// Which feature of a polygon is closest to a circle's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PolygonFeature {
    /// The edge with this index (its Voronoi region, or the centre is inside the polygon).
    Edge(usize),
    /// The vertex with this index.
    Vertex(usize),
}

/// Polygon A against circle B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolygonCircle {
    /// Normal from the polygon to the circle and signed separation.
    pub separation: Separation,
    /// The point of the polygon's boundary nearest the circle.
    pub polygon_point: Vec2,
    /// The feature that point lies on.
    pub feature: PolygonFeature,
}

/// Polygon A (world vertices and normals) against circle B.
pub fn polygon_circle(
    vertices: &[Vec2],
    normals: &[Vec2],
    center: Vec2,
    radius: Real,
) -> PolygonCircle {
    let n = vertices.len();
    // The edge the centre is farthest in front of.
    let (mut best_edge, mut best_distance) = (0, Real::NEG_INFINITY);
    for i in 0..n {
        let d = normals[i].dot(&(center - vertices[i]));
        if d > best_distance {
            best_edge = i;
            best_distance = d;
        }
    }
    // A two-vertex core (a capsule's or segment's) has no inside: a centre on its line may
    // still lie beyond its ends.
    if best_distance <= 0.0 && n >= 3 {
        // Inside: the nearest way out is through the nearest edge.
        let normal = normals[best_edge];
        return PolygonCircle {
            separation: Separation {
                normal,
                separation: best_distance - radius,
            },
            polygon_point: center - normal * best_distance,
            feature: PolygonFeature::Edge(best_edge),
        };
    }
    // Outside: the nearest boundary point, over every edge, decides the Voronoi region.
    let mut best = (Real::INFINITY, Vec2::zeros(), PolygonFeature::Edge(0));
    for i in 0..n {
        let (start, end) = (vertices[i], vertices[(i + 1) % n]);
        let edge = end - start;
        let length_sq = edge.norm_squared();
        // A zero-length edge (a hairline polygon far from the origin rounds to one) is its
        // start vertex.
        let t = if length_sq > 0.0 {
            (center - start).dot(&edge) / length_sq
        } else {
            0.0
        };
        let (point, feature) = if t <= 0.0 {
            (start, PolygonFeature::Vertex(i))
        } else if t >= 1.0 {
            (end, PolygonFeature::Vertex((i + 1) % n))
        } else if normals[i].dot(&(center - start)) < 0.0 {
            // The edge faces away: the same line facing the centre is the other edge of a
            // two-vertex core (a polygon's nearest edge from outside always faces the centre).
            continue;
        } else {
            (start + edge * t, PolygonFeature::Edge(i))
        };
        let distance_sq = (center - point).norm_squared();
        if distance_sq < best.0 {
            best = (distance_sq, point, feature);
        }
    }
    let (distance_sq, polygon_point, feature) = best;
    let normal = match feature {
        // A distance whose square is subnormal has lost its direction to rounding.
        PolygonFeature::Vertex(_) if distance_sq >= Real::MIN_POSITIVE => {
            (center - polygon_point) / distance_sq.sqrt()
        }
        // On the vertex itself (outside only by rounding): the edge it was outside of.
        PolygonFeature::Vertex(_) => normals[best_edge],
        PolygonFeature::Edge(i) => normals[i],
    };
    PolygonCircle {
        separation: Separation {
            normal,
            separation: normal.dot(&(center - polygon_point)) - radius,
        },
        polygon_point,
        feature,
    }
}

/// The edge of polygon A that B's vertices are farthest in front of, and by how much: the
/// separating-axis test over A's edge normals.
pub(crate) fn max_separation(
    a_vertices: &[Vec2],
    a_normals: &[Vec2],
    b_vertices: &[Vec2],
) -> (usize, Real) {
    let mut best = (0, Real::NEG_INFINITY);
    for (i, (v, n)) in a_vertices.iter().zip(a_normals).enumerate() {
        let deepest = b_vertices
            .iter()
            .map(|b| n.dot(&(b - v)))
            .fold(Real::INFINITY, Real::min);
        if deepest > best.1 {
            best = (i, deepest);
        }
    }
    best
}

/// Closest points of two disjoint convex polygons.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ClosestPoints {
    /// On A.
    pub point_a: Vec2,
    /// On B.
    pub point_b: Vec2,
    /// Their distance.
    pub distance: Real,
    /// The vertex of A at `point_a`, when `point_a` is a vertex.
    pub vertex_a: Option<usize>,
    /// The vertex of B at `point_b`, when `point_b` is a vertex.
    pub vertex_b: Option<usize>,
}

/// Closest points of two convex polygons that do not overlap: the nearest pair among every
/// vertex of one against every edge of the other.
pub(crate) fn closest_points(a: &[Vec2], b: &[Vec2]) -> ClosestPoints {
    let mut best = ClosestPoints {
        point_a: a[0],
        point_b: b[0],
        distance: Real::INFINITY,
        vertex_a: None,
        vertex_b: None,
    };
    // `from` are vertices, `onto` the polygon whose edges they are projected on.
    let mut search = |from: &[Vec2], onto: &[Vec2], from_is_a: bool| {
        for (i, &p) in from.iter().enumerate() {
            for j in 0..onto.len() {
                let (start, end) = (onto[j], onto[(j + 1) % onto.len()]);
                let (q, t) = closest_on_segment(p, start, end);
                let distance = (p - q).norm();
                if distance < best.distance {
                    let onto_vertex = if t <= 0.0 {
                        Some(j)
                    } else if t >= 1.0 {
                        Some((j + 1) % onto.len())
                    } else {
                        None
                    };
                    best = if from_is_a {
                        ClosestPoints {
                            point_a: p,
                            point_b: q,
                            distance,
                            vertex_a: Some(i),
                            vertex_b: onto_vertex,
                        }
                    } else {
                        ClosestPoints {
                            point_a: q,
                            point_b: p,
                            distance,
                            vertex_a: onto_vertex,
                            vertex_b: Some(i),
                        }
                    };
                }
            }
        }
    };
    search(a, b, true);
    search(b, a, false);
    best
}

/// Polygon A against polygon B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PolygonPolygon {
    /// Normal from A to B and signed separation.
    pub separation: Separation,
    /// SAT's best edge on A and its separation.
    pub edge_a: (usize, Real),
    /// SAT's best edge on B and its separation.
    pub edge_b: (usize, Real),
    /// When apart, the exact closest points.
    pub closest: Option<ClosestPoints>,
}

/// Polygon A against polygon B (world vertices and normals).
pub(crate) fn polygon_polygon(
    a_vertices: &[Vec2],
    a_normals: &[Vec2],
    b_vertices: &[Vec2],
    b_normals: &[Vec2],
) -> PolygonPolygon {
    polygon_polygon_within(a_vertices, a_normals, b_vertices, b_normals, 0.0, |_| false)
}

/// Polygon A against polygon B by the separating-axis test alone: SAT's axis and distance,
/// which for polygons apart corner to corner is less than the true distance.
pub(crate) fn polygon_sat(
    a_vertices: &[Vec2],
    a_normals: &[Vec2],
    b_vertices: &[Vec2],
    b_normals: &[Vec2],
) -> PolygonPolygon {
    polygon_polygon_within(
        a_vertices,
        a_normals,
        b_vertices,
        b_normals,
        Real::INFINITY,
        |_| false,
    )
}

/// [`polygon_polygon`], except that polygons apart by no more than `sat_is_enough` keep SAT's
/// axis and distance without searching for the exact closest points. Two polygons that barely
/// touch (a tenth of the slop, Box2D's rule) differ from the exact answer by less than anything
/// a contact can tell, and resting contacts are nearly all like that. Nor are polygons that
/// SAT already puts `too_far` apart searched: the exact distance is never less than SAT's, so
/// they are too far either way, and most pairs a moving scene watches are.
pub(crate) fn polygon_polygon_within(
    a_vertices: &[Vec2],
    a_normals: &[Vec2],
    b_vertices: &[Vec2],
    b_normals: &[Vec2],
    sat_is_enough: Real,
    too_far: impl Fn(Real) -> bool,
) -> PolygonPolygon {
    let edge_a = max_separation(a_vertices, a_normals, b_vertices);
    let edge_b = max_separation(b_vertices, b_normals, a_vertices);
    let mut sat = if edge_b.1 > edge_a.1 {
        Separation {
            normal: -b_normals[edge_b.0],
            separation: edge_b.1,
        }
    } else {
        Separation {
            normal: a_normals[edge_a.0],
            separation: edge_a.1,
        }
    };
    if let ([a0, a1], [b0, b1]) = (a_vertices, b_vertices) {
        // Two segments' cores: their normals miss the gap between two on one line, end to end
        // (the Minkowski difference is then a segment along that line), so the line is an
        // axis too.
        let along = (a1 - a0).normalize();
        let (a_lo, a_hi) = min_max(along.dot(a0), along.dot(a1));
        let (b_lo, b_hi) = min_max(along.dot(b0), along.dot(b1));
        let (ahead, behind) = (b_lo - a_hi, a_lo - b_hi);
        if ahead.max(behind) > sat.separation {
            sat = Separation {
                normal: if ahead >= behind { along } else { -along },
                separation: ahead.max(behind),
            };
        }
    }
    if sat.separation <= sat_is_enough || too_far(sat.separation) {
        return PolygonPolygon {
            separation: sat,
            edge_a,
            edge_b,
            closest: None,
        };
    }
    let closest = closest_points(a_vertices, b_vertices);
    // Facing features: the SAT axis is the true normal. Corner to corner: the line between
    // the closest points is.
    let separation = if closest.distance > sat.separation * (1.0 + 1e-5) + 1e-7 {
        Separation {
            normal: (closest.point_b - closest.point_a) / closest.distance,
            separation: closest.distance,
        }
    } else {
        sat
    };
    PolygonPolygon {
        separation,
        edge_a,
        edge_b,
        closest: Some(closest),
    }
}

/// The smaller and the larger of two numbers.
#[inline]
fn min_max(p: Real, q: Real) -> (Real, Real) {
    if p <= q { (p, q) } else { (q, p) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    fn placed(shape: Shape, x: Real, y: Real, angle: Real) -> WorldShape {
        WorldShape::at(&shape, vec2(x, y), angle)
    }

    #[test]
    fn circles_apart_touching_overlapping_and_coincident() {
        let s = circle_circle(vec2(0.0, 0.0), 1.0, vec2(3.0, 0.0), 1.0);
        assert_eq!((s.normal, s.separation), (vec2(1.0, 0.0), 1.0));
        let s = circle_circle(vec2(0.0, 0.0), 1.0, vec2(0.0, 1.5), 1.0);
        assert_eq!((s.normal, s.separation), (vec2(0.0, 1.0), -0.5));
        assert!((s.mtv() - vec2(0.0, 0.5)).norm() < 1e-6);
        let s = circle_circle(vec2(2.0, 2.0), 0.5, vec2(2.0, 2.0), 0.25);
        assert_eq!(s.normal, COINCIDENT_NORMAL);
        assert_eq!(s.separation, -0.75);
    }

    #[test]
    fn polygon_circle_in_every_region() {
        let square = placed(Shape::rect(1.0, 1.0), 0.0, 0.0, 0.0);
        let WorldShape::Polygon {
            vertices, normals, ..
        } = &square
        else {
            unreachable!()
        };
        // Across an edge.
        let pc = polygon_circle(vertices, normals, vec2(0.3, 1.5), 1.0);
        assert_eq!(pc.feature, PolygonFeature::Edge(2));
        assert!((pc.separation.separation + 0.5).abs() < 1e-6);
        assert_eq!(pc.separation.normal, vec2(0.0, 1.0));
        // Off a corner: the tutorial's "closest vertex" axis, and only there.
        let pc = polygon_circle(vertices, normals, vec2(2.0, 2.0), 1.0);
        assert_eq!(pc.feature, PolygonFeature::Vertex(2));
        assert!((pc.separation.separation - ((2.0 as Real).sqrt() - 1.0)).abs() < 1e-6);
        // Near a corner but in the edge's region: the vertex axis would be wrong here.
        let pc = polygon_circle(vertices, normals, vec2(0.9, 1.2), 0.5);
        assert_eq!(pc.feature, PolygonFeature::Edge(2));
        assert!((pc.separation.separation - (0.2 - 0.5)).abs() < 1e-6);
        // Centre inside: out through the nearest edge, depth plus radius.
        let pc = polygon_circle(vertices, normals, vec2(0.8, 0.1), 0.5);
        assert_eq!(pc.separation.normal, vec2(1.0, 0.0));
        assert!((pc.separation.separation + 0.7).abs() < 1e-6);
    }

    #[test]
    fn corner_to_corner_distance_is_exact() {
        let a = placed(Shape::rect(0.5, 0.5), 0.0, 0.0, 0.0);
        let b = placed(Shape::rect(0.5, 0.5), 1.3, 1.4, 0.0);
        let s = separation(&a, &b);
        // SAT alone would say 0.4; the corners are sqrt(0.3² + 0.4²) = 0.5 apart.
        assert!((s.separation - 0.5).abs() < 1e-6);
        assert!((s.normal - vec2(0.6, 0.8)).norm() < 1e-5);
        // Facing: the face distance.
        let c = placed(Shape::rect(0.5, 0.5), 0.2, 1.25, 0.0);
        let s = separation(&a, &c);
        assert!((s.separation - 0.25).abs() < 1e-6);
        assert_eq!(s.normal, vec2(0.0, 1.0));
    }

    /// The shapes every kind of pair is drawn from: a circle, polygons sharp and rounded, a
    /// capsule, a segment and a chain's link (both sides solid to a query).
    fn kinds(x: Real, y: Real, angle: Real) -> Vec<WorldShape> {
        let triangle = Shape::polygon(&[vec2(-0.4, -0.2), vec2(0.5, -0.3), vec2(0.0, 0.45)]);
        let mut shapes: Vec<WorldShape> = [
            Shape::circle(0.3),
            Shape::rect(0.4, 0.25),
            triangle.unwrap(),
            Shape::capsule(vec2(-0.3, 0.0), vec2(0.3, 0.1), 0.15),
            Shape::rounded_rect(0.25, 0.15, 0.1),
            Shape::segment(vec2(-0.5, 0.1), vec2(0.4, -0.2)),
        ]
        .iter()
        .map(|shape| WorldShape::at(shape, vec2(x, y), angle))
        .collect();
        let (c, s) = (angle.cos(), angle.sin());
        let at = |px: Real, py: Real| vec2(x + c * px - s * py, y + s * px + c * py);
        shapes.push(WorldShape::ChainSegment {
            ghost1: at(-1.0, 0.3),
            point1: at(-0.45, -0.1),
            point2: at(0.45, 0.15),
            ghost2: at(1.0, 0.0),
        });
        shapes
    }

    /// Signed distance from `p` to a shape: negative inside it.
    fn signed_distance(p: Vec2, shape: &WorldShape) -> Real {
        with_core(shape, |vertices, normals, radius| {
            let n = vertices.len();
            let outside = (0..n)
                .map(|i| {
                    let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                    (p - closest_on_segment(p, a, b).0).norm()
                })
                .fold(Real::INFINITY, Real::min);
            let inside = n > 2 && (0..n).all(|i| normals[i].dot(&(p - vertices[i])) < 0.0);
            (if inside { -outside } else { outside }) - radius
        })
    }

    /// Points along a shape's boundary, its corners among them: between them only faces
    /// (measured to exactly from the other side's points) and arcs (which bend away from a
    /// chord by the square of the spacing).
    fn boundary(shape: &WorldShape) -> Vec<Vec2> {
        with_core(shape, |vertices, normals, radius| {
            let n = vertices.len();
            let mut points = Vec::new();
            let arc = |points: &mut Vec<Vec2>, at: Vec2, from: Real, to: Real| {
                let steps = 200;
                for k in 0..=steps {
                    let t = from + (to - from) * k as Real / steps as Real;
                    points.push(at + vec2(t.cos(), t.sin()) * radius);
                }
            };
            if n == 1 {
                arc(&mut points, vertices[0], 0.0, crate::math::consts::TAU);
                return points;
            }
            for i in 0..n {
                let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                let normal = normals[i];
                let steps = 100;
                for k in 0..=steps {
                    let t = k as Real / steps as Real;
                    points.push(a + (b - a) * t + normal * radius);
                }
                if radius > 0.0 {
                    // Round the corner at `b`, from this edge's normal to the next's.
                    let next = normals[(i + 1) % n];
                    let from = normal.y.atan2(normal.x);
                    let mut to = next.y.atan2(next.x);
                    if to < from {
                        to += crate::math::consts::TAU;
                    }
                    arc(&mut points, b, from, to);
                }
            }
            points
        })
    }

    /// The distance between A and B measured by brute force: the least signed distance of
    /// any point on either's boundary to the other (one of the two nearest points is a corner
    /// or lies on a face, and is then sampled or measured to exactly).
    fn measured(a: &WorldShape, b: &WorldShape) -> Real {
        let one_way = |from: &WorldShape, to: &WorldShape| {
            boundary(from)
                .iter()
                .map(|&p| signed_distance(p, to))
                .fold(Real::INFINITY, Real::min)
        };
        one_way(a, b).min(one_way(b, a))
    }

    fn moved(shape: &WorldShape, by: Vec2) -> WorldShape {
        let mut moved = shape.clone();
        moved.translate(by);
        moved
    }

    /// Every kind of pair, apart and overlapping, turned and placed many ways: apart, the
    /// separation is the shapes' distance measured by brute force, along the line between
    /// their nearest points; overlapping, moving B by the minimum translation leaves the two
    /// just touching. Swapping the pair keeps the separation and turns the normal round.
    #[test]
    fn the_separation_of_every_pair_is_the_measured_distance() {
        let mut apart = 0;
        let mut overlapping = 0;
        for k in 0..8 {
            let t = k as Real;
            let (x, y) = ((0.9 * t).cos(), (0.9 * t).sin());
            for reach in [0.35, 0.8, 1.3] {
                let shapes_a = kinds(0.0, 0.0, 0.4 * t);
                let shapes_b = kinds(reach * x, reach * y, -0.7 * t + 0.2);
                for a in &shapes_a {
                    for b in &shapes_b {
                        let s = separation(a, b);
                        let back = separation(b, a);
                        assert!(
                            (s.separation - back.separation).abs() < 1e-4,
                            "{a:?} {b:?}: {s:?} but {back:?}"
                        );
                        assert!((s.normal.norm() - 1.0).abs() < 1e-5, "{s:?}");
                        assert_eq!(s.is_overlapping(), s.separation <= 0.0);
                        if s.separation > 0.0 {
                            let distance = measured(a, b);
                            assert!(
                                (s.separation - distance).abs() < 2e-3,
                                "{a:?} {b:?}: {s:?}, measured {distance}"
                            );
                            assert!(s.mtv() == Vec2::zeros());
                            // B moved back along the normal by the separation touches A.
                            let touching = moved(b, -s.normal * s.separation);
                            let gap = measured(a, &touching);
                            assert!(gap.abs() < 2e-3, "{a:?} {b:?}: {s:?}, then {gap}");
                            assert!((s.normal + back.normal).norm() < 1e-3, "{s:?} {back:?}");
                            apart += 1;
                        } else {
                            // Moved out by the minimum translation, B touches A and no more.
                            let out = moved(b, s.mtv());
                            let gap = measured(a, &out);
                            assert!(gap.abs() < 2e-3, "{a:?} {b:?}: {s:?}, then {gap}");
                            overlapping += 1;
                        }
                    }
                }
            }
        }
        assert!(
            apart > 400 && overlapping > 400,
            "{apart} apart, {overlapping} overlapping"
        );
    }
}
