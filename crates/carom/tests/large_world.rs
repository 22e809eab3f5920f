//! Worlds far from the origin, in the double-precision build (`--features f64`): a pyramid
//! 100 km out on each axis settles as it does beside the origin, to the millimetre, and a
//! character walks the same path there, to the centimetre. (In single precision a position
//! 100 km out resolves to 8 mm; `examples/far_away.rs` measures both builds.)

#![cfg(feature = "f64")]

#[path = "support/far_away.rs"]
#[allow(dead_code, reason = "the step times are for the example")]
mod far_away;

use carom::vec2;

const FAR: carom::Real = 100_000.0;

#[test]
fn a_pyramid_far_away_settles_as_it_does_beside_the_origin() {
    let near = far_away::pyramid(vec2(0.0, 0.0), 20, 300);
    let far = far_away::pyramid(vec2(FAR, FAR), 20, 300);
    let gap = far_away::widest_gap(&near.positions, &far.positions);
    assert!(
        gap < 1e-3,
        "a box ends {gap} m from where it ends beside the origin"
    );
    assert!(
        (near.top_drift - far.top_drift).abs() < 1e-3,
        "the top drifts {} m beside the origin, {} m far away",
        near.top_drift,
        far.top_drift
    );
    assert!(
        (near.deepest - far.deepest).abs() < 1e-3,
        "the deepest overlap is {} m beside the origin, {} m far away",
        near.deepest,
        far.deepest
    );
    // And it stood: the top box barely moved.
    assert!(near.top_drift < 0.05, "the top moved {} m", near.top_drift);
}

#[test]
fn a_character_far_away_walks_the_path_it_walks_beside_the_origin() {
    let near = far_away::walk(vec2(0.0, 0.0), 300);
    let far = far_away::walk(vec2(FAR, FAR), 300);
    let gap = far_away::widest_gap(&near, &far);
    assert!(gap < 0.01, "the paths part by {gap} m");
    // It got over the ramp and down the step: 15 m in 5 s, at floor level again.
    let end = near[near.len() - 1];
    assert!(
        (end.x - 15.0).abs() < 0.1 && (end.y - 0.8).abs() < 0.01,
        "ends at {end}"
    );
}
