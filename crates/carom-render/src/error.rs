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
    /// The adapter refused to open a device.
    #[error("cannot open the graphics device: {0}")]
    Device(String),
    /// Reading the image back failed.
    #[error("reading the image back failed: {0}")]
    Readback(String),
}
