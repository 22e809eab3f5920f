//! Files from anyone: scene files and saved worlds read from any text. The scene-file and
//! saved-world fuzz targets (`fuzz/fuzz_targets/scene_file.rs`, `saved_world.rs`) feed them
//! what libFuzzer makes; `tests/robustness.rs` feeds them the demos with seeded damage.
//!
//! What carom promises of any text: it reads to a scene or a world, or to an error, never a
//! panic. What reads steps without panicking and stays whole (its invariants hold), and a
//! scene that builds keeps its bodies finite as it steps.

use carom::World;

/// Steps a read world or scene this many times.
const STEPS: usize = 4;

/// A world with more bodies than this is read but not stepped or checked: the large demos'
/// bodies are many copies of the same few, and stepping and checking them would only slow
/// the search.
const MAX_CHECKED_BODIES: usize = 300;

/// A scene file's text: parsed, built and stepped. Returns whether it built.
///
/// # Panics
/// A promise broken (above).
pub fn scene_file(text: &str) -> bool {
    let Ok(scene) = carom_scene::parse(text, "fuzz.ron") else {
        return false;
    };
    let Ok(mut built) = carom_scene::build(&scene, "fuzz.ron") else {
        return false;
    };
    if built.world.body_count() > MAX_CHECKED_BODIES {
        return true;
    }
    for _ in 0..STEPS {
        built
            .step()
            .expect("a scene that builds steps at its own time step");
        crate::assert_bodies_finite(&built.world);
    }
    built.world.check_invariants();
    true
}

/// A saved world's text (carom's own RON form): read, stepped and checked. Returns whether it
/// read.
///
/// # Panics
/// A promise broken (above).
pub fn saved_world(text: &str) -> bool {
    let Ok(mut world) = ron::from_str::<World>(text) else {
        return false;
    };
    if world.body_count() > MAX_CHECKED_BODIES {
        return true;
    }
    for _ in 0..STEPS {
        world.step(1.0 / 60.0).expect("a 1/60 s step is valid");
    }
    world.check_invariants();
    true
}
