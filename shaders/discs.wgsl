// Discs, one instance each: circles (filled, outlined) and points. A quad around the disc,
// shaded by the signed distance to its rim, so edges are smooth at any size.

struct View {
    viewport: vec2<f32>, // pixels
    zoom: f32,           // pixels per metre
    srgb_target: f32,    // 1 when the target encodes sRGB itself: colours are decoded first
};

@group(0) @binding(0) var<uniform> view: View;

struct Disc {
    @location(0) center: vec2<f32>,  // m from the view's centre
    @location(1) radius: vec2<f32>,  // x: radius in m, y: extra radius in pixels
    @location(2) fill: vec4<f32>,
    @location(3) outline: vec4<f32>,
    @location(4) outline_width: f32, // pixels
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) offset: vec2<f32>,  // pixels from the centre
    @location(1) @interpolate(flat) radius: f32,        // pixels
    @location(2) @interpolate(flat) fill: vec4<f32>,
    @location(3) @interpolate(flat) outline: vec4<f32>,
    @location(4) @interpolate(flat) outline_width: f32,
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

// Corner `index` of two triangles covering [-1, 1]^2, by arithmetic: a software rasteriser
// pays for indexing a local array.
fn quad_corner(index: u32) -> vec2<f32> {
    let right = index == 1u || index == 2u || index == 4u;
    let top = index == 2u || index == 4u || index == 5u;
    return vec2<f32>(select(-1.0, 1.0, right), select(-1.0, 1.0, top));
}

@vertex
fn vs(@builtin(vertex_index) corner: u32, disc: Disc) -> VertexOut {
    let radius = disc.radius.x * view.zoom + disc.radius.y;
    // Two triangles covering the disc and one pixel of smoothing around it.
    let offset = quad_corner(corner) * (radius + 1.0);
    let center = disc.center * view.zoom;
    var out: VertexOut;
    out.clip = vec4<f32>(2.0 * (center + offset) / view.viewport, 0.0, 1.0);
    out.offset = offset;
    out.radius = radius;
    out.fill = target_color(disc.fill);
    out.outline = target_color(disc.outline);
    out.outline_width = disc.outline_width;
    return out;
}

@fragment
fn fs(in: VertexOut) -> @location(0) vec4<f32> {
    let distance = length(in.offset) - in.radius; // negative inside
    let coverage = clamp(0.5 - distance, 0.0, 1.0);
    if coverage <= 0.0 {
        discard;
    }
    let ring = clamp(distance + in.outline_width + 0.5, 0.0, 1.0);
    var color = mix(in.fill, in.outline, ring);
    color.a = color.a * coverage;
    return color;
}
