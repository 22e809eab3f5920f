//! Reading a rendered texture back into an image: the window's screenshot.

use image::RgbaImage;

/// A texture copied into a mappable buffer, waiting to be read.
pub struct Capture {
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    padded_row: u32,
}

/// Records a copy of `texture` (which needs `COPY_SRC` usage) into a new buffer; read it with
/// [`Capture::read`] once the encoder has been submitted.
pub fn copy_to_buffer(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> Capture {
    let (width, height) = (texture.width(), texture.height());
    // Rows of a texture-to-buffer copy must start at multiples of 256 bytes.
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let padded_row = (width * 4).div_ceil(align) * align;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("screenshot"),
        size: padded_row as u64 * height as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    Capture {
        buffer,
        width,
        height,
        padded_row,
    }
}

impl Capture {
    /// Waits for the copy and returns the pixels as RGBA, whatever the texture's byte order.
    pub fn read(
        self,
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
    ) -> Result<RgbaImage, String> {
        let slice = self.buffer.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| format!("reading the screenshot back failed: {e}"))?;
        let mapped = slice
            .get_mapped_range()
            .map_err(|e| format!("reading the screenshot back failed: {e}"))?;
        let bgra = matches!(
            format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        );
        let mut pixels = Vec::with_capacity((self.width * self.height * 4) as usize);
        for row in mapped.chunks(self.padded_row as usize) {
            for texel in row[..(self.width * 4) as usize].chunks_exact(4) {
                let [a, b, c] = [texel[0], texel[1], texel[2]];
                // The window is opaque whatever the alpha channel says.
                pixels.extend_from_slice(&if bgra { [c, b, a, 255] } else { [a, b, c, 255] });
            }
        }
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| "the screenshot has the wrong size".to_string())
    }
}
