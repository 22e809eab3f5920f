//! Draws a [`DrawList`] with three pipelines: polygon fills, instanced discs and instanced
//! thick segments. Buffers are kept and grown, never rebuilt for a frame that fits.

use crate::camera::Camera;
use crate::shaders;
use bytemuck::{Pod, Zeroable};
use carom::debug_draw::{ARROW_WIDTH, OUTLINE_WIDTH};
use carom::{Color, DrawList, Vec2};
use std::ops::Range;

/// The uniform all shaders share.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct View {
    center: [f32; 2],
    viewport: [f32; 2],
    zoom: f32,
    srgb_target: f32,
    _pad: [f32; 2],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct PolygonVertex {
    position: [f32; 2],
    color: [f32; 4],
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

/// A vertex or instance buffer that grows by doubling and is otherwise reused.
struct GrowingBuffer {
    buffer: wgpu::Buffer,
    label: &'static str,
}

impl GrowingBuffer {
    fn new(device: &wgpu::Device, label: &'static str) -> Self {
        GrowingBuffer {
            buffer: Self::create(device, label, 4096),
            label,
        }
    }

    fn create(device: &wgpu::Device, label: &'static str, size: u64) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, bytes: &[u8]) {
        let needed = bytes.len() as u64;
        if needed > self.buffer.size() {
            self.buffer = Self::create(device, self.label, needed.next_power_of_two());
        }
        if !bytes.is_empty() {
            queue.write_buffer(&self.buffer, 0, bytes);
        }
    }
}

/// The draw list's pipelines and buffers; give it a render pass to draw into.
pub struct Renderer {
    polygons: wgpu::RenderPipeline,
    discs: wgpu::RenderPipeline,
    segments: wgpu::RenderPipeline,
    view: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    polygon_buffer: GrowingBuffer,
    disc_buffer: GrowingBuffer,
    segment_buffer: GrowingBuffer,
    srgb_target: bool,
    // Staging, kept to avoid allocating per frame.
    polygon_vertices: Vec<PolygonVertex>,
    disc_instances: Vec<DiscInstance>,
    segment_instances: Vec<SegmentInstance>,
    // What the last `prepare` uploaded, as ranges to draw.
    polygon_count: u32,
    circle_range: Range<u32>,
    point_range: Range<u32>,
    outline_range: Range<u32>,
    overlay_range: Range<u32>,
}

impl Renderer {
    /// Pipelines for a target of `format`.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Renderer {
        let view = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view"),
            size: std::mem::size_of::<View>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("view"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: view.as_entire_binding(),
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("carom"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let polygon_attributes = wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32x4];
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
                array_stride: std::mem::size_of::<PolygonVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
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
        Renderer {
            polygons,
            discs,
            segments,
            view,
            bind_group,
            polygon_buffer: GrowingBuffer::new(device, "polygon vertices"),
            disc_buffer: GrowingBuffer::new(device, "disc instances"),
            segment_buffer: GrowingBuffer::new(device, "segment instances"),
            srgb_target: format.is_srgb(),
            polygon_vertices: Vec::new(),
            disc_instances: Vec::new(),
            segment_instances: Vec::new(),
            polygon_count: 0,
            circle_range: 0..0,
            point_range: 0..0,
            outline_range: 0..0,
            overlay_range: 0..0,
        }
    }

    /// Bytes of GPU buffer held for geometry, for checking that frames reuse them.
    pub fn buffer_capacity(&self) -> u64 {
        self.polygon_buffer.buffer.size()
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
            center: [camera.center.x, camera.center.y],
            viewport: [viewport[0].max(1) as f32, viewport[1].max(1) as f32],
            zoom: camera.zoom,
            srgb_target: if self.srgb_target { 1.0 } else { 0.0 },
            _pad: [0.0; 2],
        };
        queue.write_buffer(&self.view, 0, bytemuck::bytes_of(&view));

        self.polygon_vertices.clear();
        self.segment_instances.clear();
        self.disc_instances.clear();
        for polygon in &list.polygons {
            let vertices = list.polygon_vertices(polygon);
            for i in 1..vertices.len().saturating_sub(1) {
                for v in [vertices[0], vertices[i], vertices[i + 1]] {
                    self.polygon_vertices.push(PolygonVertex {
                        position: [v.x, v.y],
                        color: polygon.fill.to_array(),
                    });
                }
            }
            for i in 0..vertices.len() {
                let next = vertices[(i + 1) % vertices.len()];
                self.segment_instances.push(segment(
                    vertices[i],
                    next,
                    OUTLINE_WIDTH,
                    polygon.outline,
                ));
            }
        }
        let outlines = self.segment_instances.len() as u32;
        for line in &list.segments {
            self.segment_instances
                .push(segment(line.start, line.end, line.width, line.color));
        }
        let head = ARROW_HEAD / camera.zoom.max(1e-6);
        for arrow in &list.arrows {
            self.segment_instances
                .push(segment(arrow.start, arrow.end, arrow.width, arrow.color));
            let shaft = arrow.end - arrow.start;
            if shaft.norm() > 1e-9 {
                let back = -shaft.normalize() * head.min(shaft.norm() * 0.5);
                for turn in [0.45f32, -0.45] {
                    let (sin, cos) = turn.sin_cos();
                    let wing =
                        carom::vec2(back.x * cos - back.y * sin, back.x * sin + back.y * cos);
                    self.segment_instances.push(segment(
                        arrow.end,
                        arrow.end + wing,
                        ARROW_WIDTH,
                        arrow.color,
                    ));
                }
            }
        }
        for circle in &list.circles {
            self.disc_instances.push(DiscInstance {
                center: [circle.center.x, circle.center.y],
                radius: [circle.radius, 0.0],
                fill: circle.fill.to_array(),
                outline: circle.outline.to_array(),
                outline_width: OUTLINE_WIDTH,
            });
        }
        let circles = self.disc_instances.len() as u32;
        for point in &list.points {
            self.disc_instances.push(DiscInstance {
                center: [point.at.x, point.at.y],
                radius: [0.0, point.size * 0.5],
                fill: point.color.to_array(),
                outline: point.color.to_array(),
                outline_width: 0.0,
            });
        }
        self.polygon_count = self.polygon_vertices.len() as u32;
        self.outline_range = 0..outlines;
        self.overlay_range = outlines..self.segment_instances.len() as u32;
        self.circle_range = 0..circles;
        self.point_range = circles..self.disc_instances.len() as u32;
        self.polygon_buffer
            .upload(device, queue, bytemuck::cast_slice(&self.polygon_vertices));
        self.segment_buffer
            .upload(device, queue, bytemuck::cast_slice(&self.segment_instances));
        self.disc_buffer
            .upload(device, queue, bytemuck::cast_slice(&self.disc_instances));
    }

    /// Draws what the last [`Renderer::prepare`] uploaded: fills, outlines, circles, lines and
    /// arrows, then points on top.
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.bind_group, &[]);
        if self.polygon_count > 0 {
            pass.set_pipeline(&self.polygons);
            pass.set_vertex_buffer(0, self.polygon_buffer.buffer.slice(..));
            pass.draw(0..self.polygon_count, 0..1);
        }
        self.draw_segments(pass, self.outline_range.clone());
        self.draw_discs(pass, self.circle_range.clone());
        self.draw_segments(pass, self.overlay_range.clone());
        self.draw_discs(pass, self.point_range.clone());
    }

    fn draw_segments(&self, pass: &mut wgpu::RenderPass<'_>, range: Range<u32>) {
        if !range.is_empty() {
            pass.set_pipeline(&self.segments);
            pass.set_vertex_buffer(0, self.segment_buffer.buffer.slice(..));
            pass.draw(0..6, range);
        }
    }

    fn draw_discs(&self, pass: &mut wgpu::RenderPass<'_>, range: Range<u32>) {
        if !range.is_empty() {
            pass.set_pipeline(&self.discs);
            pass.set_vertex_buffer(0, self.disc_buffer.buffer.slice(..));
            pass.draw(0..6, range);
        }
    }
}

fn segment(start: Vec2, end: Vec2, width: f32, color: Color) -> SegmentInstance {
    SegmentInstance {
        start: [start.x, start.y],
        end: [end.x, end.y],
        width,
        color: color.to_array(),
    }
}
