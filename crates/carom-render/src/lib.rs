//! `carom-render` draws the description a [`carom::World`] gives of itself
//! ([`carom::DrawList`]) with wgpu, to a window surface or to an offscreen image.
//!
//! Today it holds the [`Camera`], the world-to-screen mapping the demo's input handling and the
//! renderer share; the wgpu pipelines (WGSL in the top-level `shaders/` folder) are still to
//! land. The physics core does not depend on this crate.

mod camera;

pub use camera::Camera;

/// The WGSL folder, relative to the workspace root, that the renderer includes at compile time.
pub const SHADER_DIR: &str = "shaders";
