//! The WGSL sources, built into the binary. They live in the workspace's top-level `shaders/`;
//! the crate's `shaders/` is a symlink to it, which `cargo package` follows.

/// Filled polygons.
pub const POLYGONS_WGSL: &str = include_str!("../shaders/polygons.wgsl");
/// Instanced discs: circles and points.
pub const DISCS_WGSL: &str = include_str!("../shaders/discs.wgsl");
/// Instanced thick segments: outlines, lines, arrows.
pub const SEGMENTS_WGSL: &str = include_str!("../shaders/segments.wgsl");

/// Every shader, with its file name.
pub const ALL: [(&str, &str); 3] = [
    ("polygons.wgsl", POLYGONS_WGSL),
    ("discs.wgsl", DISCS_WGSL),
    ("segments.wgsl", SEGMENTS_WGSL),
];
