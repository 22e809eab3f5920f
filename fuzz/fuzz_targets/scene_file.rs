//! Scene files from any text (`carom_tests::untrusted_files::scene_file`): a scene or a
//! located error, a world or an error, never a panic; a scene that builds steps with its
//! bodies finite. Seeded with the demos, whose joints, chains and timed events the fuzzer
//! then bends.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    carom_tests::untrusted_files::scene_file(text);
});
