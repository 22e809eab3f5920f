//! `carom-render` will draw the description a [`carom::World`] gives of itself with wgpu, to a
//! window surface or to an offscreen image.
//!
//! It is a placeholder until the renderer issue lands: the physics core does not depend on it,
//! and nothing here draws yet.

/// The WGSL folder, relative to the workspace root, that the renderer will include at compile time.
pub const SHADER_DIR: &str = "shaders";
