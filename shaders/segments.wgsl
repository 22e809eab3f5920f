// Thick lines, one instance each: a quad around the segment in pixel space, so the width is
// the same at every zoom, shaded by the distance to the segment (round caps, smooth edges).

struct View {
    viewport: vec2<f32>, // pixels
    zoom: f32,           // pixels per metre
    srgb_target: f32,    // 1 when the target encodes sRGB itself: colours are decoded first
};

@group(0) @binding(0) var<uniform> view: View;

struct Segment {
    @location(0) start: vec2<f32>, // m from the view's centre
    @location(1) end: vec2<f32>,   // m from the view's centre
    @location(2) width: f32,       // pixels
    @location(3) color: vec4<f32>,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) pixel: vec2<f32>,
    @location(1) @interpolate(flat) start: vec2<f32>,
    @location(2) @interpolate(flat) end: vec2<f32>,
    @location(3) @interpolate(flat) half_width: f32,
    @location(4) @interpolate(flat) color: vec4<f32>,
};

// Colours arrive sRGB-encoded; an sRGB target wants them linear. Done per vertex, not per pixel.
fn target_color(color: vec4<f32>) -> vec4<f32> {
    if view.srgb_target > 0.5 {
        let low = color.rgb / 12.92;
        let high = pow((color.rgb + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
        return vec4<f32>(select(high, low, color.rgb <= vec3<f32>(0.04045)), color.a);
    }
    return color;
}

@vertex
fn vs(@builtin(vertex_index) corner: u32, segment: Segment) -> VertexOut {
    let start = segment.start * view.zoom;
    let end = segment.end * view.zoom;
    let length_px = length(end - start);
    var along = vec2<f32>(1.0, 0.0);
    if length_px > 1e-4 {
        along = (end - start) / length_px;
    }
    let across = vec2<f32>(-along.y, along.x);
    let half_width = 0.5 * segment.width;
    let reach = half_width + 1.0;
    // Two triangles: x runs from the start (0) to the end (1), y across (-1 to 1).
    let c = vec2<f32>(
        select(0.0, 1.0, corner == 1u || corner == 2u || corner == 4u),
        select(-1.0, 1.0, corner == 2u || corner == 4u || corner == 5u),
    );
    // Extend past both ends by the reach, for the round caps.
    let base = mix(start - along * reach, end + along * reach, c.x);
    let pixel = base + across * reach * c.y;
    var out: VertexOut;
    out.clip = vec4<f32>(2.0 * pixel / view.viewport, 0.0, 1.0);
    out.pixel = pixel;
    out.start = start;
    out.end = end;
    out.half_width = half_width;
    out.color = target_color(segment.color);
    return out;
}

@fragment
fn fs(in: VertexOut) -> @location(0) vec4<f32> {
    let span = in.end - in.start;
    let t = clamp(dot(in.pixel - in.start, span) / max(dot(span, span), 1e-6), 0.0, 1.0);
    let distance = length(in.pixel - (in.start + span * t)) - in.half_width;
    let coverage = clamp(0.5 - distance, 0.0, 1.0);
    if coverage <= 0.0 {
        discard;
    }
    return vec4<f32>(in.color.rgb, in.color.a * coverage);
}
