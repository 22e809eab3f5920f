//! `carom-render` draws the description a [`carom::World`] gives of itself
//! ([`carom::draw::DrawList`]) with wgpu: to a window through [`Screen`], into a render pass of your
//! own through [`Renderer`], or to an offscreen texture read back as an image through
//! [`Offscreen`], so tests and CI render real pixels with no window and no GPU (Mesa's
//! lavapipe or llvmpipe do). WGSL lives in the workspace's top-level `shaders/` and is built
//! in. The physics core does not depend on this crate.

// The GPU takes `f32`. World values are carom's `Real`, `f32` or `f64` by its `f64` feature,
// so each cast between them is a no-op in one of the two builds.
#![allow(clippy::unnecessary_cast)]

mod camera;
mod corners;
mod error;
mod gpu;
mod offscreen;
mod renderer;
mod screen;
pub mod shaders;

pub use camera::Camera;
pub use error::RenderError;
pub use gpu::Gpu;
pub use offscreen::Offscreen;
pub use renderer::{ARROW_WIDTH, OUTLINE_WIDTH, Renderer, clear_color};
pub use screen::{Screen, ScreenFrame, ScreenOptions};
