//! The narrowphase, pair by pair: separation (SAT and the minimum translation vector) and the
//! clipped manifold for circle-circle, polygon-circle and polygon-polygon, each for a touching
//! pair (the common case in a pile) and a deeply overlapping one.
//!
//! Run with `cargo bench -p carom-bench --features criterion --bench narrowphase`.

use carom::query::collide;
use carom::query::separation;
use carom::{Shape, WorldShape, vec2};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// Pairs by name: two placed shapes.
fn pairs() -> Vec<(&'static str, WorldShape, WorldShape)> {
    let circle = Shape::circle(0.5);
    let square = Shape::rect(0.5, 0.5);
    let hexagon = Shape::regular(6, 0.6).unwrap();
    let pentagon = Shape::regular(5, 0.6).unwrap();
    let at = |shape: &Shape, x: f32, y: f32, angle: f32| WorldShape::at(shape, vec2(x, y), angle);
    vec![
        (
            "circle_circle/touching",
            at(&circle, 0.0, 0.0, 0.0),
            at(&circle, 0.99, 0.1, 0.0),
        ),
        (
            "circle_circle/deep",
            at(&circle, 0.0, 0.0, 0.0),
            at(&circle, 0.3, 0.1, 0.0),
        ),
        (
            "polygon_circle/touching",
            at(&square, 0.0, 0.0, 0.0),
            at(&circle, 0.2, 0.995, 0.0),
        ),
        (
            "polygon_circle/deep",
            at(&square, 0.0, 0.0, 0.0),
            at(&circle, 0.1, 0.4, 0.0),
        ),
        (
            "box_box/resting",
            at(&square, 0.0, 0.0, 0.0),
            at(&square, 0.01, 0.998, 0.0),
        ),
        (
            "box_box/deep_rotated",
            at(&square, 0.0, 0.0, 0.0),
            at(&square, 0.3, 0.6, 0.5),
        ),
        (
            "hexagon_pentagon/touching",
            at(&hexagon, 0.0, 0.0, 0.0),
            at(&pentagon, 0.3, 1.05, 0.2),
        ),
    ]
}

fn narrowphase(c: &mut Criterion) {
    let mut group = c.benchmark_group("separation");
    for (name, a, b) in pairs() {
        group.bench_function(name, |bench| {
            bench.iter(|| separation(black_box(&a), black_box(&b)))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("manifold");
    for (name, a, b) in pairs() {
        group.bench_function(name, |bench| {
            bench.iter(|| collide(black_box(&a), black_box(&b), black_box(0.02)))
        });
    }
    group.finish();
}

criterion_group!(benches, narrowphase);
criterion_main!(benches);
