//! carom for JavaScript: the physics core (no renderer, no demo) compiled to WebAssembly
//! with wasm-bindgen, packed as the npm package `carom-js` by `crates/carom-js/build-package.sh`.
//!
//! JavaScript holds small handles (`Body`, `Collider`, `Joint`) that name a world by key and
//! an object by carom's generational handle; the worlds themselves live here, in
//! `registry`, so freeing a `World` frees its memory at once. Every value that comes in is
//! checked (`convert`, `defs`): bad input, a stale handle or another world's handle is a
//! JavaScript `Error` with a message, never a trap.

mod convert;
mod defs;
mod events;
mod handles;
mod queries;
mod registry;
mod sim;
mod world;

pub use handles::{Body, Collider, Joint};
pub use world::{Snapshot, World};

use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TYPES: &str = include_str!("types.d.ts");

/// The package's version.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}
