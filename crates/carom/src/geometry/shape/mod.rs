//! Collision shapes: circles, capsules, convex polygons (rounded or not), segments and chain
//! segments, in their local frame and in the world.

#[cfg(feature = "serde")]
pub(crate) mod saved;

use crate::error::CaromError;
use crate::geometry::aabb::Aabb;
use crate::geometry::mass::{self, MassProperties};
pub use crate::geometry::points::Points;
use crate::geometry::ray::{self, Ray, RayHit};
use crate::heap_bytes::{HeapBytes, nothing};
use crate::math::{Isometry, Real, Vec2, perp_cw};

pub use crate::geometry::capsule::Capsule;
pub use crate::geometry::circle::Circle;
pub use crate::geometry::polygon::Polygon;
pub use crate::geometry::segment::{ChainSegment, Segment};

/// A collision shape. Matched on in hot code (no dynamic dispatch).
///
/// Circles and polygons are centred on their centroid when built; capsules, segments and chain
/// segments keep the points they are given, in the collider's frame.
// A polygon holds its points inline, so the polygon variant is the large one: boxing it would
// bring back the visit to the heap that holding them inline saves.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, PartialEq)]
pub enum Shape {
    /// A circle centred on the local origin.
    Circle(Circle),
    /// Two circles' centres joined by their radius.
    Capsule(Capsule),
    /// A convex polygon, rounded or not, whose centroid is the local origin.
    Polygon(Polygon),
    /// A two-sided segment of no thickness, for static geometry (it has no mass).
    Segment(Segment),
    /// One link of a chain: one-sided, with ghost vertices (see [`crate::ChainDef`]).
    ChainSegment(ChainSegment),
}

// A polygon's arrays are cloned into the old polygon's, so restoring a snapshot reuses them.
impl Clone for Shape {
    fn clone(&self) -> Self {
        match self {
            Shape::Circle(circle) => Shape::Circle(*circle),
            Shape::Capsule(capsule) => Shape::Capsule(*capsule),
            Shape::Polygon(polygon) => Shape::Polygon(polygon.clone()),
            Shape::Segment(segment) => Shape::Segment(*segment),
            Shape::ChainSegment(chain) => Shape::ChainSegment(*chain),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        match (self, source) {
            (Shape::Polygon(into), Shape::Polygon(from)) => into.clone_from(from),
            (into, from) => *into = from.clone(),
        }
    }
}

// A polygon's points, when it has more than it holds inline; the other shapes are plain
// values.
impl HeapBytes for Shape {
    fn heap_bytes(&self) -> usize {
        match self {
            Shape::Polygon(polygon) => polygon.heap_bytes(),
            Shape::Circle(circle) => nothing(circle),
            Shape::Capsule(capsule) => nothing(capsule),
            Shape::Segment(segment) => nothing(segment),
            Shape::ChainSegment(chain) => nothing(chain),
        }
    }
}

impl Shape {
    /// A circle shape; see [`Circle::new`]. The radius is checked when the shape is added to
    /// a world, or by [`Shape::validate`].
    pub fn circle(radius: Real) -> Self {
        Shape::Circle(Circle::new(radius))
    }

    /// A rectangle shape; see [`Polygon::rect`]. The sizes are checked when the shape is
    /// added to a world, or by [`Shape::validate`].
    pub fn rect(half_width: Real, half_height: Real) -> Self {
        Shape::Polygon(Polygon::rect(half_width, half_height))
    }

    /// A rectangle `2 half_width` by `2 half_height` rounded by `radius`, so `radius` larger
    /// on every side, as Box2D's `b2MakeRoundedBox`; see [`Polygon::rounded`].
    pub fn rounded_rect(half_width: Real, half_height: Real, radius: Real) -> Self {
        Shape::Polygon(Polygon::rect(half_width, half_height).rounded(radius))
    }

    /// A capsule; see [`Capsule::new`].
    pub fn capsule(center1: Vec2, center2: Vec2, radius: Real) -> Self {
        Shape::Capsule(Capsule::new(center1, center2, radius))
    }

    /// A two-sided segment; see [`Segment::new`].
    pub fn segment(point1: Vec2, point2: Vec2) -> Self {
        Shape::Segment(Segment::new(point1, point2))
    }

    /// Checks the shape: a circle's or capsule's radius, a segment's ends, or the arguments a
    /// rectangle or a rounding was made from (polygons from points are checked as they are
    /// built).
    ///
    /// # Errors
    /// The first thing wrong with the shape.
    pub fn validate(&self) -> Result<(), CaromError> {
        match self {
            Shape::Circle(c) => c.validate(),
            Shape::Capsule(c) => c.validate(),
            Shape::Polygon(p) => p.validate(),
            Shape::Segment(s) => s.validate(),
            Shape::ChainSegment(s) => s.validate(),
        }
    }

    /// A convex polygon shape; see [`Polygon::new`].
    pub fn polygon(points: &[Vec2]) -> Result<Self, CaromError> {
        Polygon::new(points).map(Shape::Polygon)
    }

    /// A regular polygon shape; see [`Polygon::regular`].
    pub fn regular(sides: usize, radius: Real) -> Result<Self, CaromError> {
        Polygon::regular(sides, radius).map(Shape::Polygon)
    }

    /// The convex hull of a point cloud; see [`Polygon::hull`].
    pub fn hull(points: &[Vec2]) -> Result<Self, CaromError> {
        Polygon::hull(points).map(Shape::Polygon)
    }

    /// True for the shapes that enclose area and so can give a body mass; segments and chain
    /// segments do not.
    pub fn has_area(&self) -> bool {
        !matches!(self, Shape::Segment(_) | Shape::ChainSegment(_))
    }

    /// Mass properties at uniform `density`, about the shape's centroid, which
    /// [`MassProperties::center`] gives in the local frame (the origin for circles and
    /// polygons). Segments have no area, hence no mass.
    ///
    /// # Errors
    /// An invalid shape ([`Shape::validate`]), or a density that is not finite and positive.
    pub fn mass_properties(&self, density: Real) -> Result<MassProperties, CaromError> {
        self.validate()?;
        mass::check_density(density)?;
        Ok(match self {
            Shape::Circle(c) => mass::circle_mass(c.radius(), density),
            Shape::Capsule(c) => {
                mass::rounded_mass(&[c.center1(), c.center2()], c.radius(), density)
            }
            Shape::Polygon(p) if p.radius() > 0.0 => {
                let mut m = mass::rounded_mass(p.vertices(), p.radius(), density);
                // Rounding a polygon about its centroid keeps the centroid only for
                // symmetric cores; otherwise the rounded centroid is a little off the origin.
                if m.center.norm() <= 1e-6 * p.circumradius() {
                    m.center = Vec2::zeros();
                }
                m
            }
            Shape::Polygon(p) => {
                let mut m =
                    mass::polygon_mass(p.vertices(), density).ok_or(CaromError::ZeroArea)?;
                // The polygon is recentred already; drop the rounding residue.
                m.center = Vec2::zeros();
                m
            }
            Shape::Segment(s) => massless((s.point1() + s.point2()) * 0.5),
            Shape::ChainSegment(s) => massless((s.point1() + s.point2()) * 0.5),
        })
    }

    /// True when the local point lies inside or on the shape (on it, for segments).
    #[inline]
    pub fn contains_local(&self, point: Vec2) -> bool {
        match self {
            Shape::Circle(c) => c.contains_local(point),
            Shape::Capsule(c) => c.contains_local(point),
            Shape::Polygon(p) => p.contains_local(point),
            Shape::Segment(s) => s.contains_local(point),
            Shape::ChainSegment(s) => s.contains_local(point),
        }
    }

    /// Casts a ray given in the shape's local frame; see [`Ray`]. A chain segment is hit only
    /// from its colliding side.
    pub fn ray_cast_local(&self, ray: &Ray) -> Option<RayHit> {
        match self {
            Shape::Circle(c) => ray::ray_cast_circle(Vec2::zeros(), c.radius(), ray),
            Shape::Capsule(c) => ray::ray_cast_capsule(c.center1(), c.center2(), c.radius(), ray),
            Shape::Polygon(p) if p.radius() > 0.0 => {
                ray::ray_cast_rounded(p.vertices(), p.normals(), p.radius(), ray)
            }
            Shape::Polygon(p) => ray::ray_cast_polygon(p.vertices(), p.normals(), ray),
            Shape::Segment(s) => ray::ray_cast_segment(s.point1(), s.point2(), false, ray),
            Shape::ChainSegment(s) => ray::ray_cast_segment(s.point1(), s.point2(), true, ray),
        }
    }

    /// The largest distance from the local origin to the boundary: how far any point of the
    /// shape moves when the body turns by a small angle, per radian.
    pub fn max_extent(&self) -> Real {
        match self {
            Shape::Circle(c) => c.radius(),
            Shape::Capsule(c) => c.center1().norm().max(c.center2().norm()) + c.radius(),
            Shape::Polygon(p) => p.circumradius() + p.radius(),
            Shape::Segment(s) => s.point1().norm().max(s.point2().norm()),
            Shape::ChainSegment(s) => s.point1().norm().max(s.point2().norm()),
        }
    }

    /// How thick the shape is at its thinnest, halved: the size below which a body could
    /// pass through a thin wall in one step. A polygon's inradius about its centroid (plus
    /// its rounding), a capsule's radius, zero for segments.
    pub fn min_extent(&self) -> Real {
        match self {
            Shape::Circle(c) => c.radius(),
            Shape::Capsule(c) => c.radius(),
            Shape::Polygon(p) => p.inradius() + p.radius(),
            Shape::Segment(_) | Shape::ChainSegment(_) => 0.0,
        }
    }
}

/// No mass, centred at `center`.
fn massless(center: Vec2) -> MassProperties {
    MassProperties {
        mass: 0.0,
        center,
        inertia: 0.0,
    }
}

/// A shape placed in the world: what collision and queries read, computed once per step.
///
/// Capsules and segments are placed as two-vertex polygons: the core's two edges are the same
/// line facing both ways, and a capsule's radius rounds it. Collision then treats every
/// convex shape but the circle alike.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum WorldShape {
    /// A circle in world coordinates.
    Circle {
        /// World centre.
        center: Vec2,
        /// Radius.
        radius: Real,
    },
    /// A convex polygon (or a capsule's or segment's two-vertex core) in world coordinates,
    /// rounded by `radius`.
    Polygon {
        /// World vertices of the core, counter-clockwise.
        vertices: Points,
        /// World outward unit normals, one per edge.
        normals: Points,
        /// How far the shape reaches beyond its core (0 for sharp polygons and segments).
        radius: Real,
    },
    /// A chain's link in world coordinates: collides on the right of `point1` → `point2`.
    ChainSegment {
        /// The previous link's first point.
        ghost1: Vec2,
        /// The first end.
        point1: Vec2,
        /// The second end.
        point2: Vec2,
        /// The next link's second point.
        ghost2: Vec2,
    },
}

impl HeapBytes for WorldShape {
    fn heap_bytes(&self) -> usize {
        match self {
            WorldShape::Polygon {
                vertices,
                normals,
                radius: _,
            } => vertices.heap_bytes() + normals.heap_bytes(),
            WorldShape::Circle {
                center: _,
                radius: _,
            }
            | WorldShape::ChainSegment {
                ghost1: _,
                point1: _,
                point2: _,
                ghost2: _,
            } => 0,
        }
    }
}

impl WorldShape {
    /// True when every figure of it is finite: a shape placed from one a world would refuse
    /// (a capsule whose ends coincide, say) may have a normal that is not a number.
    pub(crate) fn is_finite(&self) -> bool {
        let finite = |v: &Vec2| v.x.is_finite() && v.y.is_finite();
        match self {
            WorldShape::Circle { center, radius } => finite(center) && radius.is_finite(),
            WorldShape::Polygon {
                vertices,
                normals,
                radius,
            } => vertices.iter().chain(normals.iter()).all(finite) && radius.is_finite(),
            WorldShape::ChainSegment {
                ghost1,
                point1,
                point2,
                ghost2,
            } => [ghost1, point1, point2, ghost2].into_iter().all(finite),
        }
    }

    /// The shape with its local origin at `position`, turned by `angle` radians.
    pub fn at(shape: &Shape, position: Vec2, angle: Real) -> Self {
        WorldShape::new(shape, &Isometry::new(position, angle))
    }

    /// The shape placed by `transform`.
    pub fn new(shape: &Shape, transform: &Isometry) -> Self {
        let mut world = match shape {
            Shape::Circle(c) => WorldShape::Circle {
                center: Vec2::zeros(),
                radius: c.radius(),
            },
            Shape::Capsule(_) | Shape::Polygon(_) | Shape::Segment(_) => WorldShape::Polygon {
                vertices: Points::default(),
                normals: Points::default(),
                radius: 0.0,
            },
            Shape::ChainSegment(s) => WorldShape::ChainSegment {
                ghost1: s.ghost1(),
                point1: s.point1(),
                point2: s.point2(),
                ghost2: s.ghost2(),
            },
        };
        world.update(shape, transform);
        world
    }

    /// Re-places the shape, reusing this cache's storage.
    #[allow(
        clippy::unreachable,
        reason = "the arm is reached only by the shapes its pattern matched"
    )]
    pub fn update(&mut self, shape: &Shape, transform: &Isometry) {
        let rotation = transform.rotation;
        let translation = transform.translation.vector;
        let place = |p: Vec2| rotation * p + translation;
        match (self, shape) {
            (WorldShape::Circle { center, radius }, Shape::Circle(c)) => {
                *center = translation;
                *radius = c.radius();
            }
            (
                WorldShape::Polygon {
                    vertices,
                    normals,
                    radius,
                },
                Shape::Polygon(p),
            ) => {
                vertices.set_mapped(p.vertices(), place);
                normals.set_mapped(p.normals(), |n| rotation * n);
                *radius = p.radius();
            }
            (
                WorldShape::Polygon {
                    vertices,
                    normals,
                    radius,
                },
                Shape::Capsule(_) | Shape::Segment(_),
            ) => {
                let (ends, rounding) = match shape {
                    Shape::Capsule(c) => ([c.center1(), c.center2()], c.radius()),
                    Shape::Segment(s) => ([s.point1(), s.point2()], 0.0),
                    _ => unreachable!("matched above"),
                };
                let [p1, p2] = ends.map(place);
                let along = p2 - p1;
                // Placed so far out that rounding joins its ends (a body flung billions of
                // metres): the normal is then its own, turned, never a division by zero.
                let normal = if along.x != 0.0 || along.y != 0.0 {
                    perp_cw(along).normalize()
                } else {
                    rotation * perp_cw(ends[1] - ends[0]).normalize()
                };
                vertices.set([p1, p2]);
                normals.set([normal, -normal]);
                *radius = rounding;
            }
            (
                WorldShape::ChainSegment {
                    ghost1,
                    point1,
                    point2,
                    ghost2,
                },
                Shape::ChainSegment(s),
            ) => {
                *ghost1 = place(s.ghost1());
                *point1 = place(s.point1());
                *point2 = place(s.point2());
                *ghost2 = place(s.ghost2());
            }
            (world, shape) => *world = WorldShape::new(shape, transform),
        }
    }

    /// The tight bounding box.
    #[allow(
        clippy::expect_used,
        reason = "a placed polygon keeps its shape's vertices, at least three"
    )]
    pub fn aabb(&self) -> Aabb {
        match self {
            WorldShape::Circle { center, radius } => {
                let r = Vec2::new(*radius, *radius);
                Aabb::new(center - r, center + r)
            }
            WorldShape::Polygon {
                vertices, radius, ..
            } => {
                let core =
                    Aabb::from_points(vertices).expect("a polygon has at least two vertices");
                if *radius > 0.0 {
                    core.fattened(*radius)
                } else {
                    core
                }
            }
            WorldShape::ChainSegment { point1, point2, .. } => {
                Aabb::new(point1.inf(point2), point1.sup(point2))
            }
        }
    }

    /// How far the shape reaches beyond the points that define it: a circle's or a rounded
    /// shape's radius, 0 for sharp ones.
    pub fn radius(&self) -> Real {
        match self {
            WorldShape::Circle { radius, .. } | WorldShape::Polygon { radius, .. } => *radius,
            WorldShape::ChainSegment { .. } => 0.0,
        }
    }

    /// Moves the shape by `delta`, unturned.
    pub fn translate(&mut self, delta: Vec2) {
        match self {
            WorldShape::Circle { center, .. } => *center += delta,
            WorldShape::Polygon { vertices, .. } => {
                vertices.as_mut_slice().iter_mut().for_each(|v| *v += delta)
            }
            WorldShape::ChainSegment {
                ghost1,
                point1,
                point2,
                ghost2,
            } => [ghost1, point1, point2, ghost2]
                .into_iter()
                .for_each(|p| *p += delta),
        }
    }

    /// True when the shape is a chain's link and `point` is behind it, on the side it lets
    /// through (Box2D's rule for what a one-sided link ignores).
    pub(crate) fn is_link_behind(&self, point: Vec2) -> bool {
        match self {
            WorldShape::ChainSegment { point1, point2, .. } => {
                perp_cw(point2 - point1).dot(&(point - point1)) < 0.0
            }
            _ => false,
        }
    }

    /// True when the shape is a chain's link that a point going from `from` to `to` only
    /// skims: it closes on the link's line by less than `core` and ends more than `core` in
    /// front of it (Box2D's early out for fast motion along a chain).
    pub(crate) fn is_link_skimmed(&self, from: Vec2, to: Vec2, core: Real) -> bool {
        let WorldShape::ChainSegment { point1, point2, .. } = self else {
            return false;
        };
        let edge = point2 - point1;
        let length = edge.norm();
        if length <= crate::constants::LINEAR_SLOP {
            return false;
        }
        let normal = perp_cw(edge) / length;
        let (before, after) = (normal.dot(&(from - point1)), normal.dot(&(to - point1)));
        before - after < core && after > core
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn world_shape_follows_the_transform() {
        let shape = Shape::rect(1.0, 0.5);
        let iso = Isometry::new(vec2(3.0, 4.0), crate::math::consts::FRAC_PI_2);
        let world = WorldShape::new(&shape, &iso);
        let aabb = world.aabb();
        assert!((aabb.min - vec2(2.5, 3.0)).norm() < 1e-6);
        assert!((aabb.max - vec2(3.5, 5.0)).norm() < 1e-6);
        let WorldShape::Polygon { normals, .. } = &world else {
            panic!("a rectangle is a polygon")
        };
        // The bottom normal (0, -1) turned a quarter counter-clockwise points along +x.
        assert!((normals[0] - vec2(1.0, 0.0)).norm() < 1e-6);
    }

    #[test]
    fn min_extent_is_the_inradius_for_polygons() {
        assert!((Shape::rect(2.0, 0.1).min_extent() - 0.1).abs() < 1e-6);
        assert_eq!(Shape::circle(0.3).min_extent(), 0.3);
    }

    #[test]
    fn max_extent_is_the_circumradius() {
        let diagonal = (2.0 as crate::math::Real * 2.0 + 0.1 * 0.1).sqrt();
        assert!((Shape::rect(2.0, 0.1).max_extent() - diagonal).abs() < 1e-6);
        assert_eq!(Shape::circle(0.3).max_extent(), 0.3);
    }
}
