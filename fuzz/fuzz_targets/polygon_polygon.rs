//! Convex polygon against convex polygon.
#![no_main]

#[path = "common.rs"]
mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: (
    Vec<(f32, f32)>,
    common::Place,
    Vec<(f32, f32)>,
    common::Place
)| {
    let (points_a, place_a, points_b, place_b) = input;
    if let (Some(a), Some(b)) = (common::polygon(&points_a), common::polygon(&points_b)) {
        common::check_pair(&place_a.put(&a), &place_b.put(&b));
    }
});
