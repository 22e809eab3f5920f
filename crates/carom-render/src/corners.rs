//! Polygon corners in a float texture that the polygon shader reads by index.
//!
//! A texture rather than a storage buffer because WebGL2 has no storage buffers, and it holds
//! the same 32-bit floats, so the pixels are the same. Corner `i` is texel
//! (`i % WIDTH`, `i / WIDTH`); the texture grows by doubling its rows and is otherwise reused.

/// A polygon corner for the shader: the vertex and the outward unit normal of the edge that
/// starts there.
pub(crate) type Corner = [f32; 4];

/// Texels a row. WebGL2 guarantees textures 2048 wide; the polygon shader divides by this.
pub(crate) const WIDTH: u32 = 1024;

/// The corner texture.
pub(crate) struct CornerTexture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl CornerTexture {
    /// A texture of `rows` rows.
    pub(crate) fn new(device: &wgpu::Device, rows: u32) -> CornerTexture {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("polygon corners"),
            size: wgpu::Extent3d {
                width: WIDTH,
                height: rows.max(1),
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        CornerTexture { texture, view }
    }

    /// The view the bind group names.
    pub(crate) fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// Bytes held.
    pub(crate) fn size(&self) -> u64 {
        let size = self.texture.size();
        (size.width * size.height) as u64 * std::mem::size_of::<Corner>() as u64
    }

    /// Writes `corners` from the first texel on, padding them to whole rows with zeros; true
    /// when the texture had to be replaced by a taller one (its view changed).
    pub(crate) fn upload(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        corners: &mut Vec<Corner>,
    ) -> bool {
        let rows = (corners.len() as u32).div_ceil(WIDTH);
        let grown = rows > self.texture.height();
        if grown {
            let limit = device.limits().max_texture_dimension_2d;
            *self = CornerTexture::new(device, rows.next_power_of_two().min(limit));
        }
        let rows = rows.min(self.texture.height());
        if rows > 0 {
            corners.resize((rows * WIDTH) as usize, [0.0; 4]);
            queue.write_texture(
                self.texture.as_image_copy(),
                bytemuck::cast_slice(corners),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(WIDTH * std::mem::size_of::<Corner>() as u32),
                    rows_per_image: Some(rows),
                },
                wgpu::Extent3d {
                    width: WIDTH,
                    height: rows,
                    depth_or_array_layers: 1,
                },
            );
        }
        grown
    }
}

/// Four 32-bit floats a texel, read with `textureLoad` (never filtered).
pub(crate) const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The bind group layout entry of the texture at `binding`.
pub(crate) fn layout_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

#[cfg(test)]
mod tests {
    use super::WIDTH;

    #[test]
    fn the_polygon_shader_reads_rows_as_wide_as_the_texture() {
        let declared = format!("const CORNER_ROW: u32 = {WIDTH}u;");
        assert!(crate::shaders::POLYGONS_WGSL.contains(&declared));
    }
}
