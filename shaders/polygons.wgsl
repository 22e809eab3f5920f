// Filled convex polygons: the CPU fan-triangulates every polygon into one vertex buffer.

struct View {
    center: vec2<f32>,   // world point at the middle of the view, m
    viewport: vec2<f32>, // pixels
    zoom: f32,           // pixels per metre
    srgb_target: f32,    // 1 when the target encodes sRGB itself: colours are decoded first
    _pad: vec2<f32>,
};

@group(0) @binding(0) var<uniform> view: View;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
};

fn to_clip(world: vec2<f32>) -> vec4<f32> {
    let pixels = (world - view.center) * view.zoom;
    return vec4<f32>(2.0 * pixels / view.viewport, 0.0, 1.0);
}

fn output_color(color: vec4<f32>) -> vec4<f32> {
    if view.srgb_target > 0.5 {
        let low = color.rgb / 12.92;
        let high = pow((color.rgb + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
        return vec4<f32>(select(high, low, color.rgb <= vec3<f32>(0.04045)), color.a);
    }
    return color;
}

@vertex
fn vs(@location(0) position: vec2<f32>, @location(1) color: vec4<f32>) -> VertexOut {
    var out: VertexOut;
    out.clip = to_clip(position);
    out.color = color;
    return out;
}

@fragment
fn fs(in: VertexOut) -> @location(0) vec4<f32> {
    return output_color(in.color);
}
