//! Any shape against any shape: capsules, rounded polygons, segments and chain segments
//! with each other and with circles and polygons.
#![no_main]

#[path = "common.rs"]
mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: (
    common::AnyShape,
    common::Place,
    common::AnyShape,
    common::Place
)| {
    let (shape_a, place_a, shape_b, place_b) = input;
    if let (Some(a), Some(b)) = (shape_a.build(), shape_b.build()) {
        common::check_pair(&place_a.put(&a), &place_b.put(&b));
    }
});
