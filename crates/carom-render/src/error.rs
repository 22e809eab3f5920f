//! What can go wrong when rendering.

/// A rendering failure, with what to do about it.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No GPU or software rasteriser was found.
    #[error(
        "no graphics adapter ({0}); on Debian install mesa-vulkan-drivers (Vulkan, lavapipe) \
         or libegl1 libegl-mesa0 libgl1-mesa-dri (GL, llvmpipe)"
    )]
    NoAdapter(String),
    /// The adapter lacks something the renderer's shaders use.
    #[error(
        "the graphics adapter {0} cannot read 32-bit float textures, which the polygon \
         shader needs; Mesa's lavapipe (mesa-vulkan-drivers) and llvmpipe can"
    )]
    Unsupported(String),
    /// No surface could be made for the window.
    #[error("cannot make a drawing surface for the window: {0}")]
    Surface(String),
    /// The adapter found cannot present to the window's surface.
    #[error("the graphics adapter {0} cannot draw into this window")]
    Incompatible(String),
    /// The adapter refused to open a device.
    #[error("cannot open the graphics device: {0}")]
    Device(String),
    /// Reading the image back failed.
    #[error("reading the image back failed: {0}")]
    Readback(String),
}
