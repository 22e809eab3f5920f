// Convex polygons, filled and outlined in one pass, one instance each.
//
// Every polygon's vertices sit in a float texture beside the outward normal of the edge that
// starts there (a texture, not a storage buffer, so WebGL2 draws them too). The vertex shader
// fans the polygon, pushed out by the outline's half width and a pixel of smoothing; the
// fragment shader takes the signed distance to the polygon (the largest distance to an edge
// line, exact inside a convex polygon) and shades fill, outline and the smooth rim from it.
// Outlines drawn as separate thick segments cost five times the triangles, which is what a
// software rasteriser pays for.

struct View {
    viewport: vec2<f32>, // pixels
    zoom: f32,           // pixels per metre
    srgb_target: f32,    // 1 when the target encodes sRGB itself: colours are decoded first
};

@group(0) @binding(0) var<uniform> view: View;
// Texel i % CORNER_ROW, i / CORNER_ROW is corner i. xy: a vertex, m from the view's centre; zw: the outward unit
// normal of the edge from it to the next vertex.
@group(0) @binding(1) var corners: texture_2d<f32>;
const CORNER_ROW: u32 = 1024u; // corners::WIDTH

fn corner(i: u32) -> vec4<f32> {
    return textureLoad(corners, vec2<i32>(i32(i % CORNER_ROW), i32(i / CORNER_ROW)), 0);
}

struct Polygon {
    @location(0) first: u32,
    @location(1) count: u32,
    @location(2) fill: vec4<f32>,
    @location(3) outline: vec4<f32>,
    @location(4) outline_width: f32, // pixels
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec2<f32>,
    @location(1) @interpolate(flat) first: u32,
    @location(2) @interpolate(flat) count: u32,
    @location(3) @interpolate(flat) fill: vec4<f32>,
    @location(4) @interpolate(flat) outline: vec4<f32>,
    @location(5) @interpolate(flat) half_width: f32,
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
fn vs(@builtin(vertex_index) index: u32, polygon: Polygon) -> VertexOut {
    // Triangle t of the fan is (0, t + 1, t + 2).
    let triangle = index / 3u;
    let k = index % 3u;
    let at = select(0u, triangle + k, k > 0u);
    let here = corner(polygon.first + at);
    let before = corner(polygon.first + (at + polygon.count - 1u) % polygon.count);
    // The mitre: the offset one unit away from both edges that meet here. Sharp corners are
    // capped so a needle does not throw a long spike.
    let sum = before.zw + here.zw;
    let mitre = sum / max(0.5 * dot(sum, sum), 0.125);
    let half_width = 0.5 * polygon.outline_width;
    let reach = (half_width + 1.0) / view.zoom;
    let world = here.xy + mitre * reach;
    var out: VertexOut;
    out.clip = vec4<f32>(2.0 * world * view.zoom / view.viewport, 0.0, 1.0);
    out.world = world;
    out.first = polygon.first;
    out.count = polygon.count;
    out.fill = target_color(polygon.fill);
    out.outline = target_color(polygon.outline);
    out.half_width = half_width;
    return out;
}

@fragment
fn fs(in: VertexOut) -> @location(0) vec4<f32> {
    var distance = -1e30;
    for (var i = 0u; i < in.count; i = i + 1u) {
        let edge = corner(in.first + i);
        distance = max(distance, dot(in.world - edge.xy, edge.zw));
    }
    let pixels = distance * view.zoom; // negative inside
    let coverage = clamp(0.5 - (pixels - in.half_width), 0.0, 1.0);
    if coverage <= 0.0 {
        discard;
    }
    let ring = clamp(pixels + in.half_width + 0.5, 0.0, 1.0);
    var color = mix(in.fill, in.outline, ring);
    color.a = color.a * coverage;
    return color;
}
