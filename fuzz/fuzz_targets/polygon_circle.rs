//! Convex polygon against circle.
#![no_main]

#[path = "common.rs"]
mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(
    |input: (Vec<(f32, f32)>, common::Place, f32, common::Place)| {
        let (points, place_a, radius, place_b) = input;
        if let (Some(a), Some(b)) = (common::polygon(&points), common::circle(radius)) {
            common::check_pair(&place_a.put(&a), &place_b.put(&b));
        }
    }
);
