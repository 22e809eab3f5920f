//! Shapes and placements from fuzz input, and the checks every pair's answer must pass.
#![allow(dead_code)] // each target uses part of it

use arbitrary::Arbitrary;
use carom::query::collide;
use carom::query::separation;
use carom::{Shape, WorldShape, vec2};

/// A placement: any bits, kept to finite values within 1 km.
#[derive(Debug, Arbitrary)]
pub struct Place {
    x: f32,
    y: f32,
    angle: f32,
}

fn tame(value: f32, limit: f32) -> f32 {
    if value.is_finite() {
        value.clamp(-limit, limit)
    } else {
        0.0
    }
}

impl Place {
    pub fn put(&self, shape: &Shape) -> WorldShape {
        WorldShape::at(
            shape,
            vec2(tame(self.x, 1000.0), tame(self.y, 1000.0)),
            tame(self.angle, 100.0),
        )
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

/// Separation and manifold of a pair, both ways: finite, unit normals, opposite when swapped.
pub fn check_pair(a: &WorldShape, b: &WorldShape) {
    let ab = separation(a, b);
    let ba = separation(b, a);
    for s in [ab, ba] {
        assert!(s.separation.is_finite(), "{s:?}");
        assert!((s.normal.norm() - 1.0).abs() < 1e-3, "{s:?}");
    }
    for margin in [0.0, 0.02] {
        let manifold = collide(a, b, margin);
        assert!(manifold.points().len() <= 2);
        for point in manifold.points() {
            assert!(point.point.iter().all(|x| x.is_finite()), "{manifold:?}");
            assert!(point.separation.is_finite(), "{manifold:?}");
            assert!(
                point.separation <= margin + 1e-3 * (1.0 + margin),
                "{manifold:?}"
            );
        }
        if !manifold.is_empty() {
            assert!((manifold.normal.norm() - 1.0).abs() < 1e-3, "{manifold:?}");
        }
    }
}
