//! Scene files: any text parses to a scene or a located error, and any scene that parses
//! builds to a world or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(scene) = carom_scene::parse(text, "fuzz.ron") {
        let _ = carom_scene::build(&scene, "fuzz.ron");
    }
});
