//! What distance from the origin costs: a pyramid of 20 and a walking character, beside the
//! origin and 100 km out on each axis, in whichever precision this build has. Prints how far
//! the far runs stray from the near ones, and the pyramids' step times.
//!
//! ```text
//! cargo run --release -p carom --example far_away
//! cargo run --release -p carom --features f64 --example far_away
//! ```

#[path = "../tests/support/far_away.rs"]
mod far_away;

use carom::{Real, vec2};

fn main() {
    let precision = if size_of::<Real>() == 8 { "f64" } else { "f32" };
    println!("precision: {precision}");
    for far in [0.0, 1_000.0, 10_000.0, 100_000.0] {
        let at = vec2(far, far);
        let near = far_away::pyramid(vec2(0.0, 0.0), 20, 300);
        let there = far_away::pyramid(at, 20, 300);
        let walk_gap = far_away::widest_gap(
            &far_away::walk(vec2(0.0, 0.0), 300),
            &far_away::walk(at, 300),
        );
        println!(
            "at ({far} m, {far} m): boxes end up to {:.2e} m from the near run's; top drift {:.2e} m \
             (near {:.2e}); deepest overlap {:.2e} m (near {:.2e}); the character's path strays \
             {walk_gap:.2e} m",
            far_away::widest_gap(&near.positions, &there.positions),
            there.top_drift,
            near.top_drift,
            there.deepest,
            near.deepest,
        );
    }
    // Step time of Box2D's large pyramid (100 in the base, 5050 boxes), best of three.
    let best = (0..3)
        .map(|_| far_away::pyramid(vec2(0.0, 0.0), 100, 150).seconds)
        .fold(f64::INFINITY, f64::min);
    println!(
        "large pyramid (5050 boxes), 150 steps: {:.3} ms a step",
        best * 1e3 / 150.0
    );
}
