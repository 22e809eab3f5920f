//! Shapes and placements from fuzz input, and the checks every pair's answer must pass.
#![allow(dead_code)] // each target uses part of it

use arbitrary::Arbitrary;
use carom::collide;
use carom::separation;
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
