//! Any sequence of public calls on a world, spelled by the fuzzer's bytes
//! (`carom_tests::world_ops`): nothing panics, every call succeeds or is refused, bodies stay
//! finite, the world's invariants hold after each call, and a saved world steps on to the same
//! bits as the original.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    carom_tests::world_ops::run(bytes);
});
