//! Saved worlds from any text (`carom_tests::untrusted_files::saved_world`): a world or an
//! error, never a panic; what reads is whole and steps.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    carom_tests::untrusted_files::saved_world(text);
});
