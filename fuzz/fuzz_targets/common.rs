//! Shapes and placements from fuzz input, and the checks every pair's answer must pass.
#![allow(dead_code)] // each target uses part of it

use arbitrary::Arbitrary;
use carom::query::collide;
use carom::query::separation;
use carom::{MAX_POSITION, Shape, WorldShape, vec2};

/// A placement: any bits, the whole of `f32`.
#[derive(Debug, Arbitrary)]
pub struct Place {
    x: f32,
    y: f32,
    angle: f32,
}

/// How far out a placement is, which decides what its answers promise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Reach {
    /// Within 1 km of the origin: every check, separations within the margin included.
    Near,
    /// Within `MAX_POSITION`, where a world places bodies: finite answers and unit normals
    /// (a position this far out resolves to centimetres, so depths are that coarse).
    Far,
    /// Beyond where a world places anything, or not finite: a query answers without a panic,
    /// and promises nothing of its figures.
    Beyond,
}

impl Place {
    /// The shape placed, and how far out it is.
    pub fn put(&self, shape: &Shape) -> (WorldShape, Reach) {
        let farthest = self.x.abs().max(self.y.abs());
        let reach = if !(self.x.is_finite() && self.y.is_finite() && self.angle.is_finite()) {
            Reach::Beyond
        } else if farthest <= 1000.0 {
            Reach::Near
        } else if farthest <= MAX_POSITION {
            Reach::Far
        } else {
            Reach::Beyond
        };
        (WorldShape::at(shape, vec2(self.x, self.y), self.angle), reach)
    }
}

/// A circle from any radius a world accepts.
pub fn circle(radius: f32) -> Option<Shape> {
    let circle = Shape::circle(radius);
    circle.validate().ok().map(|()| circle)
}

/// A convex polygon from any points the hull accepts (the constructor refuses the rest with an
/// error, which must not panic either).
pub fn polygon(points: &[(f32, f32)]) -> Option<Shape> {
    let points: Vec<_> = points.iter().take(16).map(|&(x, y)| vec2(x, y)).collect();
    let _ = Shape::polygon(&points);
    Shape::hull(&points).ok()
}

/// Any shape carom has, from fuzz input; [`AnyShape::build`] keeps those a world accepts.
#[derive(Debug, Arbitrary)]
pub enum AnyShape {
    Circle(f32),
    Polygon(Vec<(f32, f32)>),
    Rounded(Vec<(f32, f32)>, f32),
    Capsule((f32, f32), (f32, f32), f32),
    Segment((f32, f32), (f32, f32)),
    ChainSegment([(f32, f32); 4]),
}

impl AnyShape {
    pub fn build(&self) -> Option<Shape> {
        let point = |(x, y): (f32, f32)| vec2(x, y);
        let shape = match self {
            AnyShape::Circle(radius) => return circle(*radius),
            AnyShape::Polygon(points) => return polygon(points),
            AnyShape::Rounded(points, radius) => match polygon(points)? {
                Shape::Polygon(p) => Shape::Polygon(p.rounded(*radius)),
                other => other,
            },
            AnyShape::Capsule(c1, c2, radius) => Shape::capsule(point(*c1), point(*c2), *radius),
            AnyShape::Segment(p, q) => Shape::segment(point(*p), point(*q)),
            AnyShape::ChainSegment([g1, p1, p2, g2]) => Shape::ChainSegment(
                carom::ChainSegment::new(point(*g1), point(*p1), point(*p2), point(*g2)),
            ),
        };
        shape.validate().ok().map(|()| shape)
    }
}

/// Separation and manifold of a pair, both ways: finite, unit normals, opposite when swapped,
/// as far as the farther placement's [`Reach`] promises.
pub fn check_pair((a, reach_a): &(WorldShape, Reach), (b, reach_b): &(WorldShape, Reach)) {
    let reach = (*reach_a).max(*reach_b);
    let ab = separation(a, b);
    let ba = separation(b, a);
    let manifolds = [0.0, 0.02].map(|margin| (margin, collide(a, b, margin)));
    if reach == Reach::Beyond {
        return;
    }
    for s in [ab, ba] {
        assert!(s.separation.is_finite(), "{s:?}");
        assert!((s.normal.norm() - 1.0).abs() < 1e-3, "{s:?}");
    }
    for (margin, manifold) in manifolds {
        assert!(manifold.points().len() <= 2);
        for point in manifold.points() {
            assert!(point.point.iter().all(|x| x.is_finite()), "{manifold:?}");
            assert!(point.separation.is_finite(), "{manifold:?}");
            assert!(
                reach == Reach::Far || point.separation <= margin + 1e-3 * (1.0 + margin),
                "{manifold:?}"
            );
        }
        if !manifold.is_empty() {
            assert!((manifold.normal.norm() - 1.0).abs() < 1e-3, "{manifold:?}");
        }
    }
}
