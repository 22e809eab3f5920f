//! Circle against circle, coincident centres included.
#![no_main]

#[path = "common.rs"]
mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: (f32, common::Place, f32, common::Place)| {
    let (radius_a, place_a, radius_b, place_b) = input;
    if let (Some(a), Some(b)) = (common::circle(radius_a), common::circle(radius_b)) {
        common::check_pair(&place_a.put(&a), &place_b.put(&b));
    }
});
