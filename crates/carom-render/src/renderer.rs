//! Draws a [`DrawList`] with three instanced pipelines: polygons (filled and outlined in one
//! pass), discs and thick segments. Buffers are kept and grown, never rebuilt for a frame that
//! fits.

use crate::camera::Camera;
use crate::corners::{self, Corner, CornerTexture};
use crate::error::RenderError;
use crate::shaders;
use bytemuck::{Pod, Zeroable};
use carom::draw::{Color, DrawList};
use carom::{Real, Vec2};
use std::ops::Range;

/// The uniform all shaders share.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct View {
    viewport: [f32; 2],
    zoom: f32,
    srgb_target: f32,
}

/// One polygon: its corners in the corner texture and its colours.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct PolygonInstance {
    first: u32,
    count: u32,
    fill: [f32; 4],
    outline: [f32; 4],
    outline_width: f32,
}

/// Polygons are drawn in one call per vertex count (a fan of `count - 2` triangles each).
struct PolygonBatch {
    vertex_count: u32,
    instances: Range<u32>,
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct DiscInstance {
    center: [f32; 2],
    /// Metres and extra pixels.
    radius: [f32; 2],
    fill: [f32; 4],
    outline: [f32; 4],
    outline_width: f32,
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct SegmentInstance {
    start: [f32; 2],
    end: [f32; 2],
    width: f32,
    color: [f32; 4],
}

/// Arrow heads are this long on screen, pixels.
const ARROW_HEAD: f32 = 10.0;
/// An arrow's shaft and head, pixels thick.
pub const ARROW_WIDTH: f32 = 2.0;
/// Every polygon's and disc's outline, pixels thick (carom's debug draw draws a circle's
/// radius line as thick).
pub const OUTLINE_WIDTH: f32 = 1.5;

/// A buffer that grows by doubling and is otherwise reused.
struct GrowingBuffer {
    buffer: wgpu::Buffer,
    label: &'static str,
    usage: wgpu::BufferUsages,
}

impl GrowingBuffer {
    fn new(device: &wgpu::Device, label: &'static str, usage: wgpu::BufferUsages) -> Self {
        let usage = usage | wgpu::BufferUsages::COPY_DST;
        GrowingBuffer {
            buffer: Self::create(device, label, usage, 4096),
            label,
            usage,
        }
    }

    fn create(
        device: &wgpu::Device,
        label: &'static str,
        usage: wgpu::BufferUsages,
        size: u64,
    ) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage,
            mapped_at_creation: false,
        })
    }

    /// Writes `bytes` at the start; true when the buffer had to be replaced by a larger one.
    fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, bytes: &[u8]) -> bool {
        let needed = bytes.len() as u64;
        let grown = needed > self.buffer.size();
        if grown {
            self.buffer = Self::create(device, self.label, self.usage, needed.next_power_of_two());
        }
        if !bytes.is_empty() {
            queue.write_buffer(&self.buffer, 0, bytes);
        }
        grown
    }
}

/// The draw list's pipelines and buffers; give it a render pass to draw into.
pub struct Renderer {
    polygons: wgpu::RenderPipeline,
    discs: wgpu::RenderPipeline,
    segments: wgpu::RenderPipeline,
    view: wgpu::Buffer,
    bind_group_layout: wgpu::BindGroupLayout,
    bind_group: wgpu::BindGroup,
    corner_texture: CornerTexture,
    polygon_buffer: GrowingBuffer,
    disc_buffer: GrowingBuffer,
    segment_buffer: GrowingBuffer,
    srgb_target: bool,
    // Staging, kept to avoid allocating per frame.
    corners: Vec<Corner>,
    polygon_instances: Vec<PolygonInstance>,
    polygon_scratch: Vec<PolygonInstance>,
    disc_instances: Vec<DiscInstance>,
    segment_instances: Vec<SegmentInstance>,
    // What the last `prepare` uploaded, as ranges to draw.
    polygon_batches: Vec<PolygonBatch>,
    circle_range: Range<u32>,
    point_range: Range<u32>,
}

impl Renderer {
    /// Whether `adapter` can run the renderer's shaders: polygon corners are read from a
    /// 32-bit float texture, which WebGL2 and downlevel GL have as well as Vulkan and WebGPU.
    pub fn check(adapter: &wgpu::Adapter) -> Result<(), RenderError> {
        let usages = adapter
            .get_texture_format_features(corners::FORMAT)
            .allowed_usages;
        if usages.contains(wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST) {
            Ok(())
        } else {
            Err(RenderError::Unsupported(adapter.get_info().name))
        }
    }

    /// Pipelines for a target of `format`, on a device whose adapter passed
    /// [`Renderer::check`].
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Renderer {
        let view = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view"),
            size: std::mem::size_of::<View>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view and polygon corners"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                corners::layout_entry(1),
            ],
        });
        let corner_texture = CornerTexture::new(device, 1);
        let bind_group = bind_group(device, &layout, &view, corner_texture.view());
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("carom"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let polygon_attributes = wgpu::vertex_attr_array![
            0 => Uint32, 1 => Uint32, 2 => Float32x4, 3 => Float32x4, 4 => Float32
        ];
        let disc_attributes = wgpu::vertex_attr_array![
            0 => Float32x2, 1 => Float32x2, 2 => Float32x4, 3 => Float32x4, 4 => Float32
        ];
        let segment_attributes =
            wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32x2, 2 => Float32, 3 => Float32x4];
        let make = |name: &str, source: &str, layout: wgpu::VertexBufferLayout| {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(name),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(name),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs"),
                    compilation_options: Default::default(),
                    buffers: &[Some(layout)],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format,
                        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let polygons = make(
            "polygons",
            shaders::POLYGONS_WGSL,
            wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<PolygonInstance>() as u64,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &polygon_attributes,
            },
        );
        let discs = make(
            "discs",
            shaders::DISCS_WGSL,
            wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<DiscInstance>() as u64,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &disc_attributes,
            },
        );
        let segments = make(
            "segments",
            shaders::SEGMENTS_WGSL,
            wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<SegmentInstance>() as u64,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &segment_attributes,
            },
        );
        let instance = wgpu::BufferUsages::VERTEX;
        Renderer {
            polygons,
            discs,
            segments,
            view,
            bind_group_layout: layout,
            bind_group,
            corner_texture,
            polygon_buffer: GrowingBuffer::new(device, "polygon instances", instance),
            disc_buffer: GrowingBuffer::new(device, "disc instances", instance),
            segment_buffer: GrowingBuffer::new(device, "segment instances", instance),
            srgb_target: format.is_srgb(),
            corners: Vec::new(),
            polygon_instances: Vec::new(),
            polygon_scratch: Vec::new(),
            disc_instances: Vec::new(),
            segment_instances: Vec::new(),
            polygon_batches: Vec::new(),
            circle_range: 0..0,
            point_range: 0..0,
        }
    }

    /// Bytes of GPU buffer held for geometry, for checking that frames reuse them.
    pub fn buffer_capacity(&self) -> u64 {
        self.corner_texture.size()
            + self.polygon_buffer.buffer.size()
            + self.disc_buffer.buffer.size()
            + self.segment_buffer.buffer.size()
    }

    /// Uploads the list and the camera for the next [`Renderer::render`].
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        list: &DrawList,
        camera: &Camera,
        viewport: [u32; 2],
    ) {
        let view = View {
            viewport: [viewport[0].max(1) as f32, viewport[1].max(1) as f32],
            zoom: camera.zoom,
            srgb_target: if self.srgb_target { 1.0 } else { 0.0 },
        };
        // Everything goes up relative to the camera's centre, subtracted here in the engine's
        // precision: 100 km out, a double-precision world's positions would resolve to 8 mm
        // as `f32`, their offsets from the camera resolve to micrometres.
        let origin = camera.center;
        queue.write_buffer(&self.view, 0, bytemuck::bytes_of(&view));

        self.segment_instances.clear();
        self.disc_instances.clear();
        self.batch_polygons(list, origin);
        for line in &list.segments {
            self.segment_instances.push(segment(
                line.start - origin,
                line.end - origin,
                line.width,
                line.color,
            ));
        }
        let head = (ARROW_HEAD / camera.zoom.max(1e-6)) as Real;
        for arrow in &list.arrows {
            let (start, end) = (arrow.start - origin, arrow.end - origin);
            self.segment_instances
                .push(segment(start, end, ARROW_WIDTH, arrow.color));
            let shaft = end - start;
            if shaft.norm() > 1e-9 {
                let back = -shaft.normalize() * head.min(shaft.norm() * 0.5);
                for turn in [0.45 as Real, -0.45] {
                    let (sin, cos) = turn.sin_cos();
                    let wing =
                        carom::vec2(back.x * cos - back.y * sin, back.x * sin + back.y * cos);
                    self.segment_instances
                        .push(segment(end, end + wing, ARROW_WIDTH, arrow.color));
                }
            }
        }
        for circle in &list.circles {
            self.disc_instances.push(DiscInstance {
                center: relative(circle.center, origin),
                radius: [circle.radius as f32, 0.0],
                fill: circle.fill.to_array(),
                outline: circle.outline.to_array(),
                outline_width: OUTLINE_WIDTH,
            });
        }
        let circles = self.disc_instances.len() as u32;
        for point in &list.points {
            self.disc_instances.push(DiscInstance {
                center: relative(point.at, origin),
                radius: [0.0, point.size * 0.5],
                fill: point.color.to_array(),
                outline: point.color.to_array(),
                outline_width: 0.0,
            });
        }
        self.circle_range = 0..circles;
        self.point_range = circles..self.disc_instances.len() as u32;
        if self.corner_texture.upload(device, queue, &mut self.corners) {
            // The bind group names the corner texture, so a new texture needs a new group.
            self.bind_group = bind_group(
                device,
                &self.bind_group_layout,
                &self.view,
                self.corner_texture.view(),
            );
        }
        self.polygon_buffer
            .upload(device, queue, bytemuck::cast_slice(&self.polygon_instances));
        self.segment_buffer
            .upload(device, queue, bytemuck::cast_slice(&self.segment_instances));
        self.disc_buffer
            .upload(device, queue, bytemuck::cast_slice(&self.disc_instances));
    }

    /// [`Renderer::render`] in a pass of its own on `encoder`, into `target` cleared to `clear`
    /// first: a whole frame, for a window or an offscreen image.
    pub(crate) fn render_cleared(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        clear: wgpu::Color,
        label: &str,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        self.render(&mut pass);
    }

    /// Draws what the last [`Renderer::prepare`] uploaded: polygons, circles, lines and arrows,
    /// then points on top.
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.bind_group, &[]);
        if !self.polygon_batches.is_empty() {
            pass.set_pipeline(&self.polygons);
            for batch in &self.polygon_batches {
                set_instances::<PolygonInstance>(pass, &self.polygon_buffer, &batch.instances);
                pass.draw(0..batch.vertex_count, 0..batch.instances.len() as u32);
            }
        }
        self.draw_discs(pass, self.circle_range.clone());
        // Every segment is an overlay now that outlines are drawn with their polygons.
        self.draw_segments(pass, 0..self.segment_instances.len() as u32);
        self.draw_discs(pass, self.point_range.clone());
    }

    /// Fills the corner and polygon staging, polygons grouped by vertex count (a counting sort,
    /// so a frame allocates nothing once the staging has grown).
    fn batch_polygons(&mut self, list: &DrawList, origin: Vec2) {
        self.corners.clear();
        self.polygon_scratch.clear();
        self.polygon_batches.clear();
        let mut counts = [0u32; MAX_BATCHED_COUNT + 1];
        let mut corners_before = 0u32;
        for polygon in &list.polygons {
            let vertices = list.polygon_vertices(polygon);
            if vertices.len() < 3 {
                continue;
            }
            let Some(normals) = outward_normals(vertices) else {
                continue;
            };
            counts[vertices.len().min(MAX_BATCHED_COUNT)] += 1;
            self.corners
                .extend(vertices.iter().zip(normals).map(|(v, n)| {
                    let [x, y] = relative(*v, origin);
                    [x, y, n.x as f32, n.y as f32]
                }));
            self.polygon_scratch.push(PolygonInstance {
                first: corners_before,
                count: vertices.len() as u32,
                fill: polygon.fill.to_array(),
                outline: polygon.outline.to_array(),
                outline_width: OUTLINE_WIDTH,
            });
            corners_before += vertices.len() as u32;
        }
        // Polygons with more corners than the table holds share its last row, drawn one by
        // one; carom's own shapes never have that many.
        let mut start = 0u32;
        let mut offsets = [0u32; MAX_BATCHED_COUNT + 1];
        for (count, &n) in counts.iter().enumerate() {
            offsets[count] = start;
            if n > 0 && count < MAX_BATCHED_COUNT {
                self.polygon_batches.push(PolygonBatch {
                    vertex_count: 3 * (count as u32 - 2),
                    instances: start..start + n,
                });
            }
            start += n;
        }
        self.polygon_instances.clear();
        self.polygon_instances
            .resize(self.polygon_scratch.len(), PolygonInstance::zeroed());
        for instance in &self.polygon_scratch {
            let row = (instance.count as usize).min(MAX_BATCHED_COUNT);
            let slot = offsets[row];
            offsets[row] += 1;
            self.polygon_instances[slot as usize] = *instance;
            if row == MAX_BATCHED_COUNT {
                self.polygon_batches.push(PolygonBatch {
                    vertex_count: 3 * (instance.count - 2),
                    instances: slot..slot + 1,
                });
            }
        }
    }

    fn draw_segments(&self, pass: &mut wgpu::RenderPass<'_>, range: Range<u32>) {
        if !range.is_empty() {
            pass.set_pipeline(&self.segments);
            set_instances::<SegmentInstance>(pass, &self.segment_buffer, &range);
            pass.draw(0..6, 0..range.len() as u32);
        }
    }

    fn draw_discs(&self, pass: &mut wgpu::RenderPass<'_>, range: Range<u32>) {
        if !range.is_empty() {
            pass.set_pipeline(&self.discs);
            set_instances::<DiscInstance>(pass, &self.disc_buffer, &range);
            pass.draw(0..6, 0..range.len() as u32);
        }
    }
}

/// The clear colour for a target of `format`: the sRGB colour as it is for a plain target,
/// decoded to linear for an sRGB one (which encodes it again on write).
pub fn clear_color(color: Color, format: wgpu::TextureFormat) -> wgpu::Color {
    let channel = |c: f32| {
        let c = c as f64;
        if !format.is_srgb() {
            c
        } else if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    wgpu::Color {
        r: channel(color.r),
        g: channel(color.g),
        b: channel(color.b),
        a: color.a as f64,
    }
}

/// Polygons up to this many vertices are drawn in one call per vertex count.
const MAX_BATCHED_COUNT: usize = 16;

/// The outward unit normal of each edge (from each vertex to the next) of a counter-clockwise
/// polygon. A zero-length edge borrows the normal before it (its line is then that edge's
/// line again); None when every edge has zero length.
fn outward_normals(vertices: &[Vec2]) -> Option<impl Iterator<Item = Vec2> + '_> {
    let n = vertices.len();
    let normal = move |i: usize| {
        let edge = vertices[(i + 1) % n] - vertices[i];
        let length = edge.norm();
        (length > 1e-12).then(|| carom::vec2(edge.y, -edge.x) / length)
    };
    let last_valid = (0..n).rev().find_map(normal)?;
    Some((0..n).scan(last_valid, move |previous, i| {
        *previous = normal(i).unwrap_or(*previous);
        Some(*previous)
    }))
}

/// Binds `instances` of `buffer` as the instance data, so the draw counts them from 0: a
/// first instance other than 0 is beyond WebGL2.
fn set_instances<T>(
    pass: &mut wgpu::RenderPass<'_>,
    buffer: &GrowingBuffer,
    instances: &Range<u32>,
) {
    let stride = std::mem::size_of::<T>() as u64;
    let bytes = instances.start as u64 * stride..instances.end as u64 * stride;
    pass.set_vertex_buffer(0, buffer.buffer.slice(bytes));
}

fn bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    view: &wgpu::Buffer,
    corners: &wgpu::TextureView,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("view and polygon corners"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: view.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(corners),
            },
        ],
    })
}

/// `point` less `origin`, in the GPU's single precision.
fn relative(point: Vec2, origin: Vec2) -> [f32; 2] {
    let offset = point - origin;
    [offset.x as f32, offset.y as f32]
}

/// A segment between two points already relative to the camera.
fn segment(start: Vec2, end: Vec2, width: f32, color: Color) -> SegmentInstance {
    SegmentInstance {
        start: [start.x as f32, start.y as f32],
        end: [end.x as f32, end.y as f32],
        width,
        color: color.to_array(),
    }
}
