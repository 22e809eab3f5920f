//! Convex polygons: counter-clockwise, recentred on their centroid, optionally rounded.

use crate::clone_in_place::clone_in_place;
use crate::constants::{COLLINEAR_SINE, CONTAINMENT_TOLERANCE, MAX_REGULAR_SIDES, WELD_TOLERANCE};
use crate::error::{CaromError, check_finite};
use crate::geometry::checks::{check_extent, check_point};
use crate::geometry::mass;
use crate::geometry::points::Points;
use crate::geometry::segment::distance_to_segment;
use crate::heap_bytes::HeapBytes;
use crate::math::{Real, Vec2, atan2_f64, cross, perp_cw, sin_cos_f64};
use std::f64::consts::TAU;

/// A convex polygon, counter-clockwise, recentred so that its centroid is the local origin,
/// and optionally rounded: grown by a radius all round, as Box2D's rounded polygons are.
///
/// Edge `i` runs from vertex `i` to vertex `i + 1` (wrapping); its outward normal is the unit
/// clockwise perpendicular of the edge. Edges and normals are computed once, here. A rounded
/// polygon's vertices are its *core*: the shape is every point within [`Polygon::radius`] of
/// the core, so its corners are arcs and its faces lie `radius` out from the core's edges.
#[derive(Debug, PartialEq)]
pub struct Polygon {
    // Inline up to eight points (as Box2D holds them), so a polygon is read, placed and
    // copied without a visit to the heap.
    vertices: Points,
    edges: Points,
    normals: Points,
    /// Where the centroid was in the coordinates the points were given in.
    source_centroid: Vec2,
    /// Distance from the centroid to the farthest vertex of the core.
    circumradius: Real,
    /// Distance from the centroid to the nearest edge of the core: kept because contacts ask
    /// for it every time they build a manifold.
    inradius: Real,
    /// How far the shape reaches beyond its core (0: sharp corners).
    radius: Real,
    /// Why the arguments of an infallible constructor ([`Polygon::rect`]) made no polygon;
    /// [`Polygon::validate`] reports it. The vertices are then a unit square's.
    problem: Option<Box<CaromError>>,
}

clone_in_place!(Polygon {
    vertices,
    edges,
    normals,
    source_centroid,
    circumradius,
    inradius,
    radius,
    problem,
});

impl HeapBytes for Polygon {
    fn heap_bytes(&self) -> usize {
        let Polygon {
            vertices,
            edges,
            normals,
            source_centroid: _,
            circumradius: _,
            inradius: _,
            radius: _,
            problem,
        } = self;
        // A world refuses a polygon with a problem, so a snapshot's have none: the box alone
        // is counted, not the text an error may hold.
        let problem = problem.as_ref().map_or(0, |_| size_of::<CaromError>());
        vertices.heap_bytes() + edges.heap_bytes() + normals.heap_bytes() + problem
    }
}

impl Polygon {
    /// Builds a convex polygon from its vertices in order around the outline.
    ///
    /// Clockwise input is reversed; points collinear with their neighbours are dropped. The
    /// result is recentred on its centroid: [`Polygon::source_centroid`] tells where that was.
    ///
    /// # Errors
    /// Fewer than 3 points, a NaN or infinite coordinate, two coinciding points, zero area, a
    /// reflex (inward-turning) vertex, or edges that cross each other.
    pub fn new(points: &[Vec2]) -> Result<Self, CaromError> {
        if points.len() < 3 {
            return Err(CaromError::TooFewVertices {
                count: points.len(),
            });
        }
        for (i, p) in points.iter().enumerate() {
            check_point((&format!("polygon vertex {i}"), "polygon coordinate"), *p)?;
        }
        let weld = weld_distance(points);
        for i in 0..points.len() {
            for j in i + 1..points.len() {
                if (points[i] - points[j]).norm() <= weld {
                    return Err(CaromError::DuplicateVertex {
                        first: i,
                        second: j,
                        x: points[i].x,
                        y: points[i].y,
                    });
                }
            }
        }
        // Keep each point's index in the input so errors can name it.
        let mut outline: Vec<(usize, Vec2)> = points.iter().copied().enumerate().collect();
        let area = mass::polygon_area(points);
        if area == 0.0 {
            return Err(CaromError::ZeroArea);
        }
        if area < 0.0 {
            outline.reverse();
        }
        drop_collinear(&mut outline)?;
        let vertices: Vec<Vec2> = outline.iter().map(|&(_, p)| p).collect();
        let turns = winding_turns(&vertices);
        if turns != 1 {
            return Err(CaromError::SelfIntersecting { turns });
        }
        Self::from_convex_ccw(vertices)
    }

    /// The convex hull of any cloud of points (Andrew's monotone chain).
    ///
    /// Interior points, coinciding points and points on the hull's edges are dropped.
    ///
    /// # Errors
    /// A NaN or infinite coordinate, or fewer than 3 points not all on one line.
    pub fn hull(points: &[Vec2]) -> Result<Self, CaromError> {
        for (i, p) in points.iter().enumerate() {
            check_point((&format!("hull point {i}"), "polygon coordinate"), *p)?;
        }
        let mut sorted: Vec<Vec2> = points.to_vec();
        sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let weld = weld_distance(points);
        sorted.dedup_by(|a, b| (*a - *b).norm() <= weld);
        if sorted.len() < 3 {
            return Err(CaromError::TooFewVertices {
                count: sorted.len(),
            });
        }
        // A point is kept only when the chain turns strictly left at it.
        let turns_left = |o: Vec2, a: Vec2, b: Vec2| {
            let (e, f) = (a - o, b - a);
            let sine = cross(e, f) as f64 / (e.norm() as f64 * f.norm() as f64);
            sine > COLLINEAR_SINE
        };
        let mut hull: Vec<Vec2> = Vec::with_capacity(sorted.len() + 1);
        // Lower chain left to right, then upper chain right to left.
        for &p in &sorted {
            while hull.len() >= 2 && !turns_left(hull[hull.len() - 2], hull[hull.len() - 1], p) {
                hull.pop();
            }
            hull.push(p);
        }
        let lower_len = hull.len() + 1;
        for &p in sorted.iter().rev().skip(1) {
            while hull.len() >= lower_len
                && !turns_left(hull[hull.len() - 2], hull[hull.len() - 1], p)
            {
                hull.pop();
            }
            hull.push(p);
        }
        // The upper chain ends where the lower one started.
        hull.pop();
        if hull.len() < 3 {
            return Err(CaromError::ZeroArea);
        }
        Self::from_convex_ccw(hull)
    }

    /// An axis-aligned rectangle `2 half_width` by `2 half_height`, centred on the origin.
    /// The half sizes must be finite,
    /// positive and within 100 km, which [`Polygon::validate`] checks (a world checks it
    /// when the rectangle is added).
    pub fn rect(half_width: Real, half_height: Real) -> Self {
        let check = || {
            for (name, value) in [("half_width", half_width), ("half_height", half_height)] {
                check_finite(name, value)?;
                if value <= 0.0 {
                    return Err(CaromError::OutOfRange {
                        name,
                        expected: "positive",
                        value,
                    });
                }
                check_extent(name, value)?;
            }
            Ok(())
        };
        let (w, h, problem) = match check() {
            Ok(()) => (half_width, half_height, None),
            Err(e) => (0.5, 0.5, Some(Box::new(e))),
        };
        let corners = vec![
            Vec2::new(-w, -h),
            Vec2::new(w, -h),
            Vec2::new(w, h),
            Vec2::new(-w, h),
        ];
        let mut rect = Self::from_convex_ccw(corners).unwrap_or_else(|e| Polygon {
            problem: Some(Box::new(e)),
            ..Self::rect(0.5, 0.5)
        });
        rect.problem = rect.problem.take().or(problem);
        rect
    }

    /// Checks a polygon made by an infallible constructor ([`Polygon::rect`]); the others
    /// check their input as they build and always pass.
    ///
    /// # Errors
    /// What was wrong with the constructor's arguments.
    pub fn validate(&self) -> Result<(), CaromError> {
        match &self.problem {
            Some(problem) => Err((**problem).clone()),
            None => Ok(()),
        }
    }

    /// A regular polygon with `sides` vertices (3 to 65536) on a circle of `radius`.
    ///
    /// It is turned so its bottom edge is horizontal: boxes (4 sides) come out axis-aligned
    /// and every regular polygon can rest flat on a floor.
    pub fn regular(sides: usize, radius: Real) -> Result<Self, CaromError> {
        if sides < 3 {
            return Err(CaromError::TooFewVertices { count: sides });
        }
        if sides > MAX_REGULAR_SIDES {
            return Err(CaromError::OutOfRange {
                name: "regular polygon sides",
                expected: "at most 65536 (a circle is the shape beyond that)",
                value: sides as Real,
            });
        }
        check_finite("regular polygon radius", radius)?;
        check_extent("regular polygon radius", radius)?;
        if radius <= 0.0 {
            return Err(CaromError::OutOfRange {
                name: "regular polygon radius",
                expected: "positive",
                value: radius,
            });
        }
        let n = sides as f64;
        let start = -0.25 * TAU - 0.5 * TAU / n;
        let vertices = (0..sides)
            .map(|i| {
                let (sin, cos) = sin_cos_f64(start + TAU * i as f64 / n);
                Vec2::new((radius as f64 * cos) as Real, (radius as f64 * sin) as Real)
            })
            .collect();
        Self::from_convex_ccw(vertices)
    }

    /// Builds the cached data from vertices already known to be convex and counter-clockwise.
    fn from_convex_ccw(mut vertices: Vec<Vec2>) -> Result<Self, CaromError> {
        let source_centroid = mass::polygon_centroid(&vertices).ok_or(CaromError::ZeroArea)?;
        for v in &mut vertices {
            *v -= source_centroid;
        }
        Self::around_centroid(vertices, source_centroid)
    }

    /// A polygon from vertices already around their centroid, kept exactly as they are (as a
    /// saved world holds them), with where that centroid was. They are checked as
    /// [`Polygon::new`] checks its points, and must already be counter-clockwise and convex to
    /// within rounding (a vertex a rounding's width inside its neighbours' line, which
    /// [`Polygon::new`] would drop, is kept).
    #[cfg(feature = "serde")]
    pub(crate) fn from_centred(
        vertices: Vec<Vec2>,
        source_centroid: Vec2,
    ) -> Result<Self, CaromError> {
        check_point(("polygon centroid", "polygon coordinate"), source_centroid)?;
        // Checked as Polygon::new checks points, but kept as they are: recentring may have
        // left a vertex a rounding's width inside the line of its neighbours, which
        // Polygon::new would drop.
        Polygon::new(&vertices)?;
        let n = vertices.len();
        let convex = (0..n).all(|i| {
            let (prev, here, next) = (
                vertices[(i + n - 1) % n],
                vertices[i],
                vertices[(i + 1) % n],
            );
            !turns_back(here - prev, next - here)
        });
        if !convex || mass::polygon_area(&vertices) <= 0.0 || winding_turns(&vertices) != 1 {
            return Err(CaromError::SavedPolygon);
        }
        Self::around_centroid(vertices, source_centroid)
    }

    /// Finishes a polygon from its vertices around the centroid.
    fn around_centroid(mut vertices: Vec<Vec2>, source_centroid: Vec2) -> Result<Self, CaromError> {
        // Recentring rounds: points a hair apart far from the centroid can land on one
        // another. Merge them, so no edge is too short to have a normal.
        let weld = weld_distance(&vertices);
        let mut i = 0;
        while vertices.len() >= 3 && i < vertices.len() {
            let next = (i + 1) % vertices.len();
            if (vertices[next] - vertices[i]).norm() <= weld {
                vertices.remove(next);
            } else {
                i += 1;
            }
        }
        if vertices.len() < 3 {
            return Err(CaromError::ZeroArea);
        }
        let n = vertices.len();
        let edges: Points = (0..n)
            .map(|i| vertices[(i + 1) % n] - vertices[i])
            .collect();
        let normals: Points = edges.iter().map(|e| perp_cw(*e).normalize()).collect();
        if normals
            .iter()
            .any(|n| !(n.x.is_finite() && n.y.is_finite()))
        {
            return Err(CaromError::ZeroArea);
        }
        let circumradius = vertices.iter().map(|v| v.norm()).fold(0.0, Real::max);
        let inradius = vertices
            .iter()
            .zip(&normals)
            .map(|(v, n)| n.dot(v))
            .fold(Real::INFINITY, Real::min);
        Ok(Polygon {
            vertices: vertices.into_iter().collect(),
            edges,
            normals,
            source_centroid,
            circumradius,
            inradius,
            radius: 0.0,
            problem: None,
        })
    }

    /// The vertices, counter-clockwise, relative to the centroid.
    #[inline]
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices
    }

    /// The edges: `edges()[i] = vertices()[i + 1] - vertices()[i]`, wrapping.
    #[inline]
    pub fn edges(&self) -> &[Vec2] {
        &self.edges
    }

    /// The unit outward normal of each edge.
    #[inline]
    pub fn normals(&self) -> &[Vec2] {
        &self.normals
    }

    /// The number of vertices (and of edges).
    #[inline]
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Always false: a polygon has at least three vertices. Present for API symmetry with `len`.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Where the centroid was in the coordinates the points were given in: the offset that
    /// was subtracted from every point. Place the body there to keep the shape where it was.
    #[inline]
    pub fn source_centroid(&self) -> Vec2 {
        self.source_centroid
    }

    /// Distance from the centroid to the farthest vertex of the core.
    #[inline]
    pub fn circumradius(&self) -> Real {
        self.circumradius
    }

    /// Distance from the centroid to the nearest edge of the core.
    pub(crate) fn inradius(&self) -> Real {
        self.inradius
    }

    /// How far the shape reaches beyond its core: 0 for a sharp polygon.
    #[inline]
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// The same polygon rounded by `radius`: every point within `radius` of it, so a box grows
    /// by `radius` on every side and its corners become quarter circles (Box2D's
    /// `b2MakeRoundedBox`). Rounded shapes roll over edges and corners more smoothly and
    /// their contacts are steadier. The radius must be finite and not negative, which
    /// [`Polygon::validate`] checks.
    pub fn rounded(mut self, radius: Real) -> Self {
        let check = || {
            check_finite("polygon radius", radius)?;
            if radius < 0.0 {
                return Err(CaromError::OutOfRange {
                    name: "polygon radius",
                    expected: "zero or positive",
                    value: radius,
                });
            }
            check_extent("polygon radius", radius)
        };
        match check() {
            Ok(()) => self.radius = radius,
            Err(e) => {
                self.problem = self.problem.take().or(Some(Box::new(e)));
            }
        }
        self
    }

    /// True when the local point lies inside or on the polygon.
    ///
    /// The tutorial's test: the point is on the inner side of every edge, i.e. the cross
    /// product of the edge with the vector from its start to the point is not negative. With
    /// unit normals that is `normal · (point - vertex) <= 0`, which lets the tolerance be a
    /// distance. A rounded polygon also holds every point within its radius of the core.
    pub fn contains_local(&self, point: Vec2) -> bool {
        let inside_core = self
            .vertices
            .iter()
            .zip(&self.normals)
            .all(|(v, n)| n.dot(&(point - v)) <= CONTAINMENT_TOLERANCE);
        inside_core
            || (self.radius > 0.0
                && distance_to_outline(&self.vertices, point)
                    <= self.radius + CONTAINMENT_TOLERANCE)
    }

    /// The index of the vertex farthest along `direction` (the support point).
    pub fn support(&self, direction: Vec2) -> usize {
        let mut best = 0;
        let mut best_dot = self.vertices[0].dot(&direction);
        for (i, v) in self.vertices.iter().enumerate().skip(1) {
            let d = v.dot(&direction);
            if d > best_dot {
                best = i;
                best_dot = d;
            }
        }
        best
    }
}

/// The distance from `point` to the nearest point of a closed outline's edges.
pub(crate) fn distance_to_outline(vertices: &[Vec2], point: Vec2) -> Real {
    let n = vertices.len();
    (0..n)
        .map(|i| distance_to_segment(point, vertices[i], vertices[(i + 1) % n]))
        .fold(Real::INFINITY, Real::min)
}

/// How close two points of this cloud must be to count as one.
fn weld_distance(points: &[Vec2]) -> Real {
    let extent = points
        .iter()
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(0.0, Real::max);
    WELD_TOLERANCE * extent.max(1.0)
}

/// Removes vertices collinear with their neighbours; rejects inward turns and spikes.
fn drop_collinear(outline: &mut Vec<(usize, Vec2)>) -> Result<(), CaromError> {
    let mut i = 0;
    let mut unchanged = 0;
    // Walk around until a full lap removes nothing: dropping a point changes its neighbours.
    while unchanged < outline.len() {
        if outline.len() < 3 {
            return Err(CaromError::ZeroArea);
        }
        let n = outline.len();
        let prev = outline[(i + n - 1) % n].1;
        let (index, here) = outline[i % n];
        let next = outline[(i + 1) % n].1;
        let (e, f) = (here - prev, next - here);
        let sine = turn_sine(e, f);
        if turns_back(e, f) {
            return Err(CaromError::ReflexVertex {
                index,
                x: here.x,
                y: here.y,
            });
        }
        if sine <= COLLINEAR_SINE {
            outline.remove(i % n);
            unchanged = 0;
        } else {
            i = (i + 1) % n;
            unchanged += 1;
        }
    }
    Ok(())
}

/// True when the turn from edge `e` to edge `f` is a right turn, or a spike that doubles back
/// on itself, beyond rounding: a vertex no convex counter-clockwise outline may have.
fn turns_back(e: Vec2, f: Vec2) -> bool {
    let sine = turn_sine(e, f);
    sine < -COLLINEAR_SINE || (sine <= COLLINEAR_SINE && e.dot(&f) < 0.0)
}

/// The sine of the turn from edge `e` to edge `f`: positive to the left.
fn turn_sine(e: Vec2, f: Vec2) -> f64 {
    cross(e, f) as f64 / (e.norm() as f64 * f.norm() as f64)
}

/// How many times a counter-clockwise outline of left turns goes around (1 for a simple one).
fn winding_turns(vertices: &[Vec2]) -> i32 {
    let n = vertices.len();
    let total: f64 = (0..n)
        .map(|i| {
            let e = vertices[(i + 1) % n] - vertices[i];
            let f = vertices[(i + 2) % n] - vertices[(i + 1) % n];
            atan2_f64(cross(e, f) as f64, e.dot(&f) as f64)
        })
        .sum();
    (total / TAU).round() as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    fn pts(coords: &[(Real, Real)]) -> Vec<Vec2> {
        coords.iter().map(|&(x, y)| vec2(x, y)).collect()
    }

    /// A saved polygon is read back as written, with a vertex that recentring left a
    /// rounding's width inside its neighbours' line (which `Polygon::new` drops); a vertex
    /// clearly inside, or a clockwise outline, is refused.
    #[cfg(feature = "serde")]
    #[test]
    fn a_saved_polygon_keeps_a_vertex_rounding_put_inside_the_line() {
        let written = pts(&[
            (-1.191082, 0.73032445),
            (0.5692599, -1.3215868),
            (0.602494, -0.52909416),
            (0.602494, -0.5127365),
            (0.6024939, 0.60483426),
        ]);
        let centroid = vec2(-0.602494, -0.44849032);
        assert_eq!(Polygon::new(&written).unwrap().len(), 4);
        let read = Polygon::from_centred(written.clone(), centroid).unwrap();
        assert_eq!(read.vertices(), &written[..]);
        let mut dented = written.clone();
        dented[3].x -= 0.01;
        assert!(Polygon::from_centred(dented, centroid).is_err());
        let mut clockwise = written;
        clockwise.reverse();
        assert!(Polygon::from_centred(clockwise, centroid).is_err());
    }

    #[test]
    fn polygon_is_ccw_recentred_with_outward_normals() {
        // Clockwise input is accepted and reversed.
        let poly = Polygon::new(&pts(&[(0.0, 0.0), (0.0, 2.0), (4.0, 2.0), (4.0, 0.0)])).unwrap();
        assert_eq!(poly.source_centroid(), vec2(2.0, 1.0));
        assert!(mass::polygon_area(poly.vertices()) > 0.0);
        for i in 0..poly.len() {
            let v = poly.vertices()[i];
            let next = poly.vertices()[(i + 1) % poly.len()];
            assert_eq!(poly.edges()[i], next - v);
            let n = poly.normals()[i];
            assert!((n.norm() - 1.0).abs() < 1e-6);
            assert!(n.dot(&poly.edges()[i]).abs() < 1e-6);
            // Outward: the centroid (origin) is behind every edge.
            assert!(n.dot(&(Vec2::zeros() - v)) < 0.0);
        }
        assert!(mass::polygon_centroid(poly.vertices()).unwrap().norm() < 1e-6);
    }

    #[test]
    fn collinear_points_are_dropped() {
        let poly = Polygon::new(&pts(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (2.0, 2.0),
            (0.0, 2.0),
        ]))
        .unwrap();
        assert_eq!(poly.len(), 4);
    }

    #[test]
    fn bad_polygons_are_named_errors() {
        assert_eq!(
            Polygon::new(&pts(&[(0.0, 0.0), (1.0, 0.0)])),
            Err(CaromError::TooFewVertices { count: 2 })
        );
        assert!(matches!(
            Polygon::new(&pts(&[(0.0, 0.0), (1.0, Real::NAN), (0.0, 1.0)])),
            Err(CaromError::NonFinite { .. })
        ));
        assert!(matches!(
            Polygon::new(&pts(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (1.0, 0.0)])),
            Err(CaromError::DuplicateVertex {
                first: 1,
                second: 3,
                ..
            })
        ));
        assert_eq!(
            Polygon::new(&pts(&[(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)])),
            Err(CaromError::ZeroArea)
        );
        // An arrow head: vertex 2 points inward.
        let err = Polygon::new(&pts(&[
            (0.0, 0.0),
            (2.0, 0.0),
            (1.0, 0.5),
            (2.0, 2.0),
            (0.0, 2.0),
        ]));
        assert_eq!(
            err,
            Err(CaromError::ReflexVertex {
                index: 2,
                x: 1.0,
                y: 0.5
            })
        );
        assert!(err.unwrap_err().to_string().contains("vertex 2"));
        // A pentagram turns left at every vertex but winds twice.
        let star: Vec<Vec2> = (0..5)
            .map(|i| {
                let a = crate::math::consts::TAU * (2 * i) as Real / 5.0;
                vec2(a.cos(), a.sin())
            })
            .collect();
        assert_eq!(
            Polygon::new(&star),
            Err(CaromError::SelfIntersecting { turns: 2 })
        );
    }

    #[test]
    fn hull_of_a_cloud() {
        let mut cloud = pts(&[(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0), (2.0, 0.0)]);
        // Interior points and duplicates.
        for i in 0..20 {
            cloud.push(vec2(
                0.5 + (i % 5) as Real * 0.6,
                0.5 + (i / 5) as Real * 0.7,
            ));
        }
        cloud.push(vec2(4.0, 4.0));
        let hull = Polygon::hull(&cloud).unwrap();
        assert_eq!(hull.len(), 4);
        assert_eq!(hull.source_centroid(), vec2(2.0, 2.0));
        assert!(matches!(
            Polygon::hull(&pts(&[(0.0, 0.0), (1.0, 1.0), (3.0, 3.0)])),
            Err(CaromError::ZeroArea)
        ));
        assert!(Polygon::hull(&pts(&[(0.0, 0.0), (0.0, 0.0), (0.0, 0.0)])).is_err());
    }

    #[test]
    fn rect_and_regular() {
        let r = Polygon::rect(2.0, 1.0);
        assert_eq!(r.vertices()[0], vec2(-2.0, -1.0));
        assert_eq!(r.normals()[0], vec2(0.0, -1.0));
        assert!(r.validate().is_ok());
        assert!(Polygon::rect(0.0, 1.0).validate().is_err());
        assert!(Polygon::rect(1.0, Real::INFINITY).validate().is_err());
        assert!(Polygon::rect(-1.0, 1.0).validate().is_err());
        assert!(Polygon::rect(1.0e-30, 1.0e-30).validate().is_err());
        // A bad rectangle is still a sane polygon until it is refused.
        let bad = Polygon::rect(Real::NAN, 1.0);
        assert!(
            bad.vertices()
                .iter()
                .all(|v| v.x.is_finite() && v.y.is_finite())
        );
        assert!(Shape::Polygon(bad).mass_properties(1.0).is_err());
        let hex = Polygon::regular(6, 1.0).unwrap();
        assert_eq!(hex.len(), 6);
        // Flat bottom edge.
        assert!((hex.normals()[0] - vec2(0.0, -1.0)).norm() < 1e-6);
        assert!((hex.circumradius() - 1.0).abs() < 1e-6);
        assert!(Polygon::regular(2, 1.0).is_err());
        assert!(Polygon::regular(5, -1.0).is_err());
    }
}
