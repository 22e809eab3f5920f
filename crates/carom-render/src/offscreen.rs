//! Rendering into a texture and reading it back as an image: snapshots without a window.

use crate::camera::Camera;
use crate::error::RenderError;
use crate::gpu::Gpu;
use crate::renderer::{Renderer, clear_color};
use carom::draw::{Color, DrawList};
use image::RgbaImage;

/// The format offscreen images are drawn in: bytes come back in RGBA order, sRGB-encoded.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// A renderer with its own device and an image-sized target, reused frame after frame.
pub struct Offscreen {
    gpu: Gpu,
    renderer: Renderer,
    texture: wgpu::Texture,
    readback: wgpu::Buffer,
    width: u32,
    height: u32,
}

impl Offscreen {
    /// A `width` x `height` target on the first adapter [`Gpu::headless`] finds.
    pub fn new(width: u32, height: u32) -> Result<Offscreen, RenderError> {
        let gpu = Gpu::headless()?;
        let renderer = Renderer::new(&gpu.device, FORMAT);
        let (texture, readback) = target(&gpu.device, width.max(1), height.max(1));
        Ok(Offscreen {
            gpu,
            renderer,
            texture,
            readback,
            width: width.max(1),
            height: height.max(1),
        })
    }

    /// The device in use.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The renderer, to inspect its buffers.
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// Changes the image size (nothing is rebuilt when it is the same).
    pub fn resize(&mut self, width: u32, height: u32) {
        let (width, height) = (width.max(1), height.max(1));
        if (width, height) != (self.width, self.height) {
            (self.texture, self.readback) = target(&self.gpu.device, width, height);
            (self.width, self.height) = (width, height);
        }
    }

    /// Clears to `background`, draws `list` as `camera` sees it, and returns the pixels.
    pub fn render(
        &mut self,
        list: &DrawList,
        camera: &Camera,
        background: Color,
    ) -> Result<RgbaImage, RenderError> {
        let Gpu { device, queue, .. } = &self.gpu;
        self.renderer
            .prepare(device, queue, list, camera, [self.width, self.height]);
        let view = self
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let clear = clear_color(background, FORMAT);
        (self.renderer).render_cleared(&mut encoder, &view, clear, "offscreen");
        let padded_row = padded_row(self.width);
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
        queue.submit([encoder.finish()]);
        let slice = self.readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mut pixels = Vec::with_capacity((self.width * self.height * 4) as usize);
        {
            let mapped = slice
                .get_mapped_range()
                .map_err(|e| RenderError::Readback(e.to_string()))?;
            // Rows are padded to 256 bytes for the copy; keep only the image's bytes.
            for row in mapped.chunks(padded_row as usize) {
                pixels.extend_from_slice(&row[..(self.width * 4) as usize]);
            }
        }
        self.readback.unmap();
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| RenderError::Readback("the image has the wrong size".into()))
    }
}

fn padded_row(width: u32) -> u32 {
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    (width * 4).div_ceil(align) * align
}

fn target(device: &wgpu::Device, width: u32, height: u32) -> (wgpu::Texture, wgpu::Buffer) {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("offscreen"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded_row(width) as u64 * height as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    (texture, readback)
}
