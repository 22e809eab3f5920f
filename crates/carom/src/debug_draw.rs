//! How a world describes itself for drawing, without knowing how drawing is done.
//!
//! [`World::debug_draw`] walks the bodies, joints and contacts and calls a [`DebugDraw`] sink
//! with a handful of primitives: filled convex polygons, discs, segments, arrows and points.
//! The [`DrawFlags`] choose what is described. [`DrawList`] is a sink that just records, so a
//! renderer (the `carom-render` crate) can upload it in one go; a test can inspect it.
//!
//! Positions and lengths of shapes are in metres. Line widths and point sizes are in screen
//! pixels, so overlays stay readable at any zoom.
//!
//! Joints are drawn as Box2D draws them: their anchors, lines from each body's centre of mass
//! to its anchor (or, for a distance joint, between the anchors), a slider's axis, and limits
//! in green (lower) and red (upper); on request, each joint's reaction force as an arrow.

use crate::collision::manifold::PairSide;
use crate::dynamics::body::{Body, BodyKind};
use crate::dynamics::collider::Collider;
use crate::geometry::shape::WorldShape;
use crate::joint::{Joint, JointKind, Limits};
use crate::math::{Real, Rot, Vec2, vec2};
use crate::world::World;

/// A colour with straight (not premultiplied) alpha, components in `0..=1`, sRGB-encoded as
/// colours are usually written down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Color {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
    /// Opacity.
    pub a: f32,
}

impl Color {
    /// An opaque colour.
    pub const fn rgb(r: f32, g: f32, b: f32) -> Self {
        Color { r, g, b, a: 1.0 }
    }

    /// The same colour with opacity `a`.
    pub const fn with_alpha(self, a: f32) -> Self {
        Color { a, ..self }
    }

    /// Blended toward `other` by `t` (0 keeps this colour, 1 gives `other`).
    pub fn mix(self, other: Color, t: f32) -> Self {
        let lerp = |x: f32, y: f32| x + (y - x) * t;
        Color {
            r: lerp(self.r, other.r),
            g: lerp(self.g, other.g),
            b: lerp(self.b, other.b),
            a: lerp(self.a, other.a),
        }
    }

    /// The components as an array, red first.
    pub const fn to_array(self) -> [f32; 4] {
        [self.r, self.g, self.b, self.a]
    }

    /// The background the demo and the snapshots clear to.
    pub const BACKGROUND: Color = Color::rgb(0.09, 0.10, 0.12);
}

/// Which parts of the world [`World::debug_draw`] describes. Combine with `|`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DrawFlags(u32);

impl DrawFlags {
    /// Nothing.
    pub const NONE: DrawFlags = DrawFlags(0);
    /// Bodies' shapes, filled and outlined; circles with a radius line to show their turn.
    pub const SHAPES: DrawFlags = DrawFlags(1);
    /// Each polygon edge's outward normal, from the edge's middle.
    pub const EDGE_NORMALS: DrawFlags = DrawFlags(1 << 1);
    /// Bodies' bounding boxes.
    pub const AABBS: DrawFlags = DrawFlags(1 << 2);
    /// Contact points of touching pairs.
    pub const CONTACT_POINTS: DrawFlags = DrawFlags(1 << 3);
    /// Contact normals, from each contact point.
    pub const CONTACT_NORMALS: DrawFlags = DrawFlags(1 << 4);
    /// The reference (red) and incident (blue) edges of polygon contacts.
    pub const CONTACT_EDGES: DrawFlags = DrawFlags(1 << 5);
    /// Centres of mass.
    pub const CENTERS_OF_MASS: DrawFlags = DrawFlags(1 << 6);
    /// Linear velocities, as arrows from the centre of mass.
    pub const VELOCITIES: DrawFlags = DrawFlags(1 << 7);
    /// Sleeping bodies dimmed.
    pub const SLEEPING: DrawFlags = DrawFlags(1 << 8);
    /// Joints: anchors, the lines joining them to their bodies' centres, axes and limits.
    /// Mouse joints are left to whoever drives them (the demo draws its grab); filter joints
    /// have nothing to show.
    pub const JOINTS: DrawFlags = DrawFlags(1 << 9);
    /// Each joint's reaction force on body B in the last step, as an arrow from B's anchor.
    pub const JOINT_FORCES: DrawFlags = DrawFlags(1 << 10);

    /// Every flag, each with its name as scenes and the command line spell it. New flags go
    /// at the end: serde writes a flag as its index here.
    pub const NAMED: [(&'static str, DrawFlags); 11] = [
        ("shapes", DrawFlags::SHAPES),
        ("edge_normals", DrawFlags::EDGE_NORMALS),
        ("aabbs", DrawFlags::AABBS),
        ("contact_points", DrawFlags::CONTACT_POINTS),
        ("contact_normals", DrawFlags::CONTACT_NORMALS),
        ("contact_edges", DrawFlags::CONTACT_EDGES),
        ("centers_of_mass", DrawFlags::CENTERS_OF_MASS),
        ("velocities", DrawFlags::VELOCITIES),
        ("sleeping", DrawFlags::SLEEPING),
        ("joints", DrawFlags::JOINTS),
        ("joint_forces", DrawFlags::JOINT_FORCES),
    ];

    /// Everything.
    pub const ALL: DrawFlags = DrawFlags((1 << 11) - 1);

    /// The flag called `name` (see [`DrawFlags::NAMED`]).
    pub fn from_name(name: &str) -> Option<DrawFlags> {
        DrawFlags::NAMED
            .iter()
            .find(|(known, _)| *known == name)
            .map(|(_, flag)| *flag)
    }

    /// True if every flag of `other` is set here.
    pub const fn contains(self, other: DrawFlags) -> bool {
        self.0 & other.0 == other.0
    }

    /// Sets or clears the flags of `other`.
    pub fn set(&mut self, other: DrawFlags, on: bool) {
        if on {
            self.0 |= other.0;
        } else {
            self.0 &= !other.0;
        }
    }
}

impl Default for DrawFlags {
    /// Shapes, with sleeping bodies dimmed, and joints (which Box2D also draws by default:
    /// without them a jointed body looks like it floats).
    fn default() -> Self {
        DrawFlags::SHAPES | DrawFlags::SLEEPING | DrawFlags::JOINTS
    }
}

impl std::ops::BitOr for DrawFlags {
    type Output = DrawFlags;
    fn bitor(self, other: DrawFlags) -> DrawFlags {
        DrawFlags(self.0 | other.0)
    }
}

/// What to draw and at what scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawOptions {
    /// Which parts to describe.
    pub flags: DrawFlags,
    /// Length of contact and edge normal arrows, m.
    pub normal_length: Real,
    /// Velocity arrows are the distance covered in this many seconds.
    pub velocity_scale: Real,
    /// Size of joint markings, m: a revolute joint's limit lines are this long, an axis
    /// without limits reaches this far either side of its anchor, and a limit's tick is 0.4
    /// of it across.
    pub joint_size: Real,
    /// Reaction force arrows are this many metres per newton, capped at 2 m so a joint under
    /// a heavy load still fits the view. At 0.01 m/N a 1 kg body hanging under 10 m/s²
    /// gravity shows a 0.1 m arrow.
    pub force_scale: Real,
}

impl Default for DrawOptions {
    fn default() -> Self {
        DrawOptions {
            flags: DrawFlags::default(),
            normal_length: 0.5,
            velocity_scale: 0.1,
            joint_size: 0.5,
            force_scale: 0.01,
        }
    }
}

/// A sink for drawing primitives. Widths and sizes are screen pixels; everything else is metres.
pub trait DebugDraw {
    /// A convex polygon, vertices counter-clockwise, filled and outlined
    /// [`OUTLINE_WIDTH`] pixels thick.
    fn polygon(&mut self, vertices: &[Vec2], fill: Color, outline: Color);
    /// A disc, filled and outlined.
    fn circle(&mut self, center: Vec2, radius: Real, fill: Color, outline: Color);
    /// A straight line `width` pixels thick.
    fn segment(&mut self, start: Vec2, end: Vec2, width: f32, color: Color);
    /// An arrow from `start` to the head at `end`.
    fn arrow(&mut self, start: Vec2, end: Vec2, color: Color);
    /// A dot `size` pixels across.
    fn point(&mut self, at: Vec2, size: f32, color: Color);
}

/// A filled, outlined convex polygon of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawPolygon {
    /// Index of its first vertex in [`DrawList::vertices`].
    pub first: u32,
    /// How many vertices, counter-clockwise.
    pub count: u32,
    /// Interior colour.
    pub fill: Color,
    /// Outline colour.
    pub outline: Color,
}

/// A filled, outlined disc of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawCircle {
    /// Centre, m.
    pub center: Vec2,
    /// Radius, m.
    pub radius: Real,
    /// Interior colour.
    pub fill: Color,
    /// Outline colour.
    pub outline: Color,
}

/// A thick line (or an arrow) of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawSegment {
    /// Start, m.
    pub start: Vec2,
    /// End, m.
    pub end: Vec2,
    /// Thickness, pixels.
    pub width: f32,
    /// Colour.
    pub color: Color,
}

/// A dot of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawPoint {
    /// Where, m.
    pub at: Vec2,
    /// Diameter, pixels.
    pub size: f32,
    /// Colour.
    pub color: Color,
}

/// Every primitive recorded, by type, in drawing order within each type. A renderer draws
/// polygons, then circles, then segments and arrows, then points, so overlays stay on top.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrawList {
    /// Polygon vertices, shared by [`DrawList::polygons`].
    pub vertices: Vec<Vec2>,
    /// Filled polygons.
    pub polygons: Vec<DrawPolygon>,
    /// Filled discs.
    pub circles: Vec<DrawCircle>,
    /// Lines, polygon outlines included.
    pub segments: Vec<DrawSegment>,
    /// Arrows, drawn as segments with a head.
    pub arrows: Vec<DrawSegment>,
    /// Dots.
    pub points: Vec<DrawPoint>,
}

impl DrawList {
    /// An empty list.
    pub fn new() -> Self {
        Self::default()
    }

    /// Empties the list, keeping its memory for the next frame.
    pub fn clear(&mut self) {
        self.vertices.clear();
        self.polygons.clear();
        self.circles.clear();
        self.segments.clear();
        self.arrows.clear();
        self.points.clear();
    }

    /// True when nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
            && self.circles.is_empty()
            && self.segments.is_empty()
            && self.arrows.is_empty()
            && self.points.is_empty()
    }

    /// The vertices of one recorded polygon.
    pub fn polygon_vertices(&self, polygon: &DrawPolygon) -> &[Vec2] {
        let first = polygon.first as usize;
        &self.vertices[first..first + polygon.count as usize]
    }
}

impl DebugDraw for DrawList {
    fn polygon(&mut self, vertices: &[Vec2], fill: Color, outline: Color) {
        self.polygons.push(DrawPolygon {
            first: self.vertices.len() as u32,
            count: vertices.len() as u32,
            fill,
            outline,
        });
        self.vertices.extend_from_slice(vertices);
    }

    fn circle(&mut self, center: Vec2, radius: Real, fill: Color, outline: Color) {
        self.circles.push(DrawCircle {
            center,
            radius,
            fill,
            outline,
        });
    }

    fn segment(&mut self, start: Vec2, end: Vec2, width: f32, color: Color) {
        self.segments.push(DrawSegment {
            start,
            end,
            width,
            color,
        });
    }

    fn arrow(&mut self, start: Vec2, end: Vec2, color: Color) {
        self.arrows.push(DrawSegment {
            start,
            end,
            width: ARROW_WIDTH,
            color,
        });
    }

    fn point(&mut self, at: Vec2, size: f32, color: Color) {
        self.points.push(DrawPoint { at, size, color });
    }
}

/// The house colours: kinds, contacts and overlays.
pub mod palette {
    use super::Color;

    /// Static bodies.
    pub const STATIC: Color = Color::rgb(0.42, 0.52, 0.45);
    /// Kinematic bodies.
    pub const KINEMATIC: Color = Color::rgb(0.45, 0.55, 0.85);
    /// Dynamic bodies take one of these, by handle, so neighbours differ.
    pub const DYNAMIC: [Color; 6] = [
        Color::rgb(0.90, 0.62, 0.35),
        Color::rgb(0.55, 0.78, 0.45),
        Color::rgb(0.40, 0.70, 0.85),
        Color::rgb(0.85, 0.50, 0.55),
        Color::rgb(0.80, 0.75, 0.40),
        Color::rgb(0.65, 0.55, 0.85),
    ];
    /// What sleeping bodies fade toward.
    pub const ASLEEP: Color = Color::rgb(0.35, 0.35, 0.38);
    /// Contact points.
    pub const CONTACT_POINT: Color = Color::rgb(1.0, 0.85, 0.2);
    /// Contact normals.
    pub const CONTACT_NORMAL: Color = Color::rgb(0.95, 0.95, 0.95);
    /// Reference edges.
    pub const REFERENCE_EDGE: Color = Color::rgb(0.95, 0.25, 0.2);
    /// Incident edges.
    pub const INCIDENT_EDGE: Color = Color::rgb(0.25, 0.55, 1.0);
    /// Edge normals.
    pub const EDGE_NORMAL: Color = Color::rgb(0.3, 0.9, 0.9);
    /// Bounding boxes.
    pub const AABB: Color = Color::rgb(0.85, 0.4, 0.85);
    /// Velocities.
    pub const VELOCITY: Color = Color::rgb(0.4, 1.0, 0.4);
    /// Centres of mass.
    pub const CENTER_OF_MASS: Color = Color::rgb(0.95, 0.95, 0.95);
    /// Joints' links: from each body's centre of mass to its anchor, and between anchors.
    pub const JOINT: Color = Color::rgb(0.55, 0.85, 0.80);
    /// Joints' anchors.
    pub const JOINT_ANCHOR: Color = Color::rgb(1.0, 1.0, 1.0);
    /// Prismatic and wheel joints' axes.
    pub const JOINT_AXIS: Color = Color::rgb(0.6, 0.6, 0.65);
    /// Lower limits: a revolute joint's least angle, the least length or translation.
    pub const JOINT_LOWER_LIMIT: Color = Color::rgb(0.45, 0.9, 0.45);
    /// Upper limits: a revolute joint's greatest angle, the greatest length or translation.
    pub const JOINT_UPPER_LIMIT: Color = Color::rgb(0.95, 0.35, 0.3);
    /// Joints' reaction forces.
    pub const JOINT_FORCE: Color = Color::rgb(1.0, 0.55, 0.15);
}

/// Arrow shaft thickness, pixels.
pub const ARROW_WIDTH: f32 = 2.0;
/// Shape outline thickness, pixels: renderers draw polygon and circle outlines this thick,
/// and circles' radius lines.
pub const OUTLINE_WIDTH: f32 = 1.5;
/// Reference and incident edge thickness, pixels.
const CONTACT_EDGE_WIDTH: f32 = 4.0;
/// Contact point diameter, pixels.
const CONTACT_POINT_SIZE: f32 = 7.0;
/// Joint link and axis thickness, pixels.
const JOINT_WIDTH: f32 = 1.5;
/// Joint limit line and tick thickness, pixels: thicker than the links they cross.
const JOINT_LIMIT_WIDTH: f32 = 2.5;
/// Joint anchor diameter, pixels.
const JOINT_ANCHOR_SIZE: f32 = 3.0;
/// The longest reaction force arrow, m.
const MAX_FORCE_ARROW: Real = 2.0;

/// The colour a body is drawn in when the caller has none for it.
pub fn default_color(body: &Body) -> Color {
    match body.kind() {
        BodyKind::Static => palette::STATIC,
        BodyKind::Kinematic => palette::KINEMATIC,
        BodyKind::Dynamic => {
            let index = body.handle().index() as usize;
            palette::DYNAMIC[index % palette::DYNAMIC.len()]
        }
    }
}

impl World {
    /// Describes the parts of the world `options` selects to `out`. `color_of` may give a body
    /// its own colour (a scene's choice); otherwise it is drawn in its kind's colour.
    pub fn debug_draw(
        &self,
        options: &DrawOptions,
        color_of: impl Fn(&Body) -> Option<Color>,
        out: &mut impl DebugDraw,
    ) {
        let flags = options.flags;
        for body in self.bodies() {
            let mut color = color_of(body).unwrap_or_else(|| default_color(body));
            if flags.contains(DrawFlags::SLEEPING) && body.is_sleeping() {
                color = color.mix(palette::ASLEEP, 0.6);
            }
            for collider in body.colliders().iter().filter_map(|&c| self.collider(c)) {
                if flags.contains(DrawFlags::SHAPES) {
                    draw_shape(body, collider, color, out);
                }
                if flags.contains(DrawFlags::EDGE_NORMALS)
                    && let WorldShape::Polygon {
                        vertices, normals, ..
                    } = collider.world_shape()
                {
                    for (i, normal) in normals.iter().enumerate() {
                        let middle = (vertices[i] + vertices[(i + 1) % vertices.len()]) * 0.5;
                        let end = middle + normal * options.normal_length;
                        out.arrow(middle, end, palette::EDGE_NORMAL);
                    }
                }
                if flags.contains(DrawFlags::AABBS) {
                    let aabb = collider.aabb();
                    let corners = [
                        aabb.min,
                        vec2(aabb.max.x, aabb.min.y),
                        aabb.max,
                        vec2(aabb.min.x, aabb.max.y),
                    ];
                    for i in 0..4 {
                        out.segment(corners[i], corners[(i + 1) % 4], 1.0, palette::AABB);
                    }
                }
            }
            if flags.contains(DrawFlags::VELOCITIES) && body.kind() != BodyKind::Static {
                let velocity = body.linear_velocity() * options.velocity_scale;
                if velocity.norm_squared() > 1e-8 {
                    let center = body.center_of_mass();
                    out.arrow(center, center + velocity, palette::VELOCITY);
                }
            }
            if flags.contains(DrawFlags::CENTERS_OF_MASS) {
                out.point(body.center_of_mass(), 5.0, palette::CENTER_OF_MASS);
            }
        }
        if flags.0 & (DrawFlags::JOINTS.0 | DrawFlags::JOINT_FORCES.0) != 0 {
            self.draw_joints(options, out);
        }
        let contact_flags =
            DrawFlags::CONTACT_POINTS | DrawFlags::CONTACT_NORMALS | DrawFlags::CONTACT_EDGES;
        if flags.0 & contact_flags.0 != 0 {
            self.draw_contacts(options, out);
        }
    }

    fn draw_joints(&self, options: &DrawOptions, out: &mut impl DebugDraw) {
        let flags = options.flags;
        for joint in self.joints() {
            let [a, b] = joint.bodies();
            let (Some(a), Some(b)) = (self.body(a), self.body(b)) else {
                continue;
            };
            if flags.contains(DrawFlags::JOINTS) {
                draw_joint(joint, a, b, options.joint_size, out);
            }
            // A filter joint applies no force. A mouse joint's does count: it is a real pull.
            if flags.contains(DrawFlags::JOINT_FORCES) && !matches!(joint.kind(), JointKind::Filter)
            {
                let arrow = joint.reaction_force() * options.force_scale;
                let length = arrow.norm();
                if length > 1e-4 {
                    let arrow = arrow * (MAX_FORCE_ARROW / length).min(1.0);
                    let at = joint.world_anchors(a, b)[1];
                    out.arrow(at, at + arrow, palette::JOINT_FORCE);
                }
            }
        }
    }

    fn draw_contacts(&self, options: &DrawOptions, out: &mut impl DebugDraw) {
        let flags = options.flags;
        for contact in self.contacts().filter(|c| !c.manifold().is_empty()) {
            let manifold = contact.manifold();
            if flags.contains(DrawFlags::CONTACT_EDGES) {
                for (edge, color) in [
                    (manifold.reference_edge, palette::REFERENCE_EDGE),
                    (manifold.incident_edge, palette::INCIDENT_EDGE),
                ] {
                    let Some(edge) = edge else { continue };
                    let collider = match edge.side {
                        PairSide::A => contact.collider_a(),
                        PairSide::B => contact.collider_b(),
                    };
                    let ends = self
                        .collider(collider)
                        .and_then(|c| edge.ends(c.world_shape()));
                    if let Some((start, end)) = ends {
                        out.segment(start, end, CONTACT_EDGE_WIDTH, color);
                    }
                }
            }
            for point in manifold.points() {
                if flags.contains(DrawFlags::CONTACT_NORMALS) {
                    let end = point.point + manifold.normal * options.normal_length;
                    out.arrow(point.point, end, palette::CONTACT_NORMAL);
                }
                if flags.contains(DrawFlags::CONTACT_POINTS) {
                    out.point(point.point, CONTACT_POINT_SIZE, palette::CONTACT_POINT);
                }
            }
        }
    }
}

/// A joint's anchors, links, axis and limits, as Box2D draws them; `size` is
/// [`DrawOptions::joint_size`].
fn draw_joint(joint: &Joint, a: &Body, b: &Body, size: Real, out: &mut impl DebugDraw) {
    let [anchor_a, anchor_b] = joint.world_anchors(a, b);
    // Centre to anchor to anchor to centre: shows which bodies are joined and where.
    let chain = [a.center_of_mass(), anchor_a, anchor_b, b.center_of_mass()];
    let link = |out: &mut _| {
        for pair in chain.windows(2) {
            segment_unless_empty(pair[0], pair[1], JOINT_WIDTH, palette::JOINT, out);
        }
    };
    match joint.kind() {
        JointKind::Mouse(_) | JointKind::Filter => return,
        JointKind::Distance(distance) => {
            out.segment(anchor_a, anchor_b, JOINT_WIDTH, palette::JOINT);
            let apart = anchor_b - anchor_a;
            if let Some(limits) = distance.limits
                && apart.norm() > 1e-6
            {
                let along = apart.normalize();
                // A least length of 0 (a rope's) would put a tick on anchor A: nothing to say.
                if limits.lower > 0.0 {
                    let at = anchor_a + along * limits.lower;
                    tick(at, along, size, palette::JOINT_LOWER_LIMIT, out);
                }
                let at = anchor_a + along * limits.upper;
                tick(at, along, size, palette::JOINT_UPPER_LIMIT, out);
            }
        }
        JointKind::Revolute(revolute) => {
            link(out);
            if let Some(limits) = revolute.limits {
                // The joint's zero is A's rotation turned by the reference angle; the limits
                // turn on from there. B's own line meets a limit's when it reaches it, and is
                // drawn first so the limit's colour shows when they meet.
                let zero = a.rotation() * Rot::new(joint.reference_angle());
                let arm = vec2(size, 0.0);
                let b_line = anchor_b + b.rotation() * arm;
                out.segment(anchor_b, b_line, JOINT_WIDTH, palette::JOINT);
                for (angle, color) in [
                    (limits.lower, palette::JOINT_LOWER_LIMIT),
                    (limits.upper, palette::JOINT_UPPER_LIMIT),
                ] {
                    let end = anchor_a + zero * Rot::new(angle) * arm;
                    out.segment(anchor_a, end, JOINT_LIMIT_WIDTH, color);
                }
            }
        }
        JointKind::Prismatic(slider) => {
            draw_axis(a, anchor_a, slider.axis, slider.limits, size, out);
            link(out);
        }
        JointKind::Wheel(wheel) => {
            draw_axis(a, anchor_a, wheel.axis, wheel.limits, size, out);
            link(out);
        }
        JointKind::Weld(_) | JointKind::Motor(_) => link(out),
    }
    out.point(anchor_a, JOINT_ANCHOR_SIZE, palette::JOINT_ANCHOR);
    out.point(anchor_b, JOINT_ANCHOR_SIZE, palette::JOINT_ANCHOR);
}

/// A prismatic or wheel joint's axis (`local_axis` in A's frame) through anchor A: from the
/// lower to the upper limit with a tick at each, or `size` either side without limits.
fn draw_axis(
    a: &Body,
    anchor_a: Vec2,
    local_axis: Vec2,
    limits: Option<Limits>,
    size: Real,
    out: &mut impl DebugDraw,
) {
    let axis = a.rotation() * local_axis;
    match limits {
        Some(limits) => {
            let lower = anchor_a + axis * limits.lower;
            let upper = anchor_a + axis * limits.upper;
            out.segment(lower, upper, JOINT_WIDTH, palette::JOINT_AXIS);
            tick(lower, axis, size, palette::JOINT_LOWER_LIMIT, out);
            tick(upper, axis, size, palette::JOINT_UPPER_LIMIT, out);
        }
        None => {
            let reach = axis * size;
            out.segment(
                anchor_a - reach,
                anchor_a + reach,
                JOINT_WIDTH,
                palette::JOINT_AXIS,
            );
        }
    }
}

/// A short line across unit direction `along` at `at`, marking a limit.
fn tick(at: Vec2, along: Vec2, size: Real, color: Color, out: &mut impl DebugDraw) {
    let across = vec2(-along.y, along.x) * (0.2 * size);
    out.segment(at - across, at + across, JOINT_LIMIT_WIDTH, color);
}

/// A segment, unless its ends coincide (a wheel's anchor on its centre): a renderer would
/// draw a stray dot.
fn segment_unless_empty(
    start: Vec2,
    end: Vec2,
    width: f32,
    color: Color,
    out: &mut impl DebugDraw,
) {
    if (end - start).norm_squared() > 1e-12 {
        out.segment(start, end, width, color);
    }
}

/// A collider's shape: polygons filled and outlined, rounded ones along their arcs, circles
/// with a radius line at their angle, segments and chain links as lines.
fn draw_shape(body: &Body, collider: &Collider, color: Color, out: &mut impl DebugDraw) {
    let outline = color.mix(Color::rgb(1.0, 1.0, 1.0), 0.45);
    let fill = color.mix(Color::BACKGROUND, 0.35);
    match collider.world_shape() {
        WorldShape::Polygon {
            vertices, radius, ..
        } if *radius == 0.0 && vertices.len() >= 3 => {
            out.polygon(vertices, fill, outline);
        }
        WorldShape::Polygon {
            vertices,
            normals,
            radius,
        } if *radius > 0.0 => {
            out.polygon(&rounded_outline(vertices, normals, *radius), fill, outline);
        }
        WorldShape::Polygon { vertices, .. } => {
            out.segment(vertices[0], vertices[1], 2.0 * OUTLINE_WIDTH, outline);
        }
        WorldShape::ChainSegment { point1, point2, .. } => {
            out.segment(*point1, *point2, 2.0 * OUTLINE_WIDTH, outline);
        }
        WorldShape::Circle { center, radius } => {
            out.circle(*center, *radius, fill, outline);
            let turn = body.rotation() * collider.local_transform().rotation;
            let rim = center + turn * vec2(*radius, 0.0);
            out.segment(*center, rim, OUTLINE_WIDTH, outline);
        }
    }
}

/// The outline of a core grown by `radius`: at each vertex, an arc from the previous edge's
/// normal round to the next one's, in steps of at most a sixteenth of a turn.
fn rounded_outline(vertices: &[Vec2], normals: &[Vec2], radius: Real) -> Vec<Vec2> {
    let n = vertices.len();
    let mut outline = Vec::with_capacity(n * 5);
    for i in 0..n {
        let from = normals[(i + n - 1) % n];
        let to = normals[i];
        let turn = crate::math::cross(from, to).abs().atan2(from.dot(&to));
        let steps = (turn / (std::f32::consts::TAU / 16.0)).ceil().max(1.0) as usize;
        let start = from.y.atan2(from.x);
        for k in 0..=steps {
            let angle = start + turn * k as Real / steps as Real;
            outline.push(vertices[i] + vec2(angle.cos(), angle.sin()) * radius);
        }
    }
    outline
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDef, JointDef, JointHandle, Shape};

    /// A box resting on a floor and a ball in the air, after a few steps.
    fn scene() -> World {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5)))
            .unwrap();
        world
            .add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(2.0, 3.0)))
            .unwrap();
        for _ in 0..5 {
            world.step(1.0 / 60.0).unwrap();
        }
        world
    }

    fn draw(world: &World, flags: DrawFlags) -> DrawList {
        let mut list = DrawList::new();
        let options = DrawOptions {
            flags,
            ..DrawOptions::default()
        };
        world.debug_draw(&options, |_| None, &mut list);
        list
    }

    #[test]
    fn shapes_are_described_in_world_coordinates() {
        let world = scene();
        let list = draw(&world, DrawFlags::SHAPES);
        assert_eq!(list.polygons.len(), 2);
        assert_eq!(list.circles.len(), 1);
        // The ball's radius line, and nothing else, is a segment.
        assert_eq!(list.segments.len(), 1);
        let floor = list.polygon_vertices(&list.polygons[0]);
        assert_eq!(floor.len(), 4);
        assert!(
            floor
                .iter()
                .all(|v| v.y.abs() < 1e-6 || (v.y + 1.0).abs() < 1e-6)
        );
        assert!((list.circles[0].radius - 0.25).abs() < 1e-6);
        assert!(list.points.is_empty() && list.arrows.is_empty());
    }

    #[test]
    fn contacts_are_drawn_only_when_asked() {
        let world = scene();
        assert!(draw(&world, DrawFlags::NONE).is_empty());
        let list = draw(
            &world,
            DrawFlags::CONTACT_POINTS | DrawFlags::CONTACT_NORMALS | DrawFlags::CONTACT_EDGES,
        );
        // The box touches the floor along a face: two points, two normals pointing up,
        // and a reference and an incident edge.
        assert_eq!(list.points.len(), 2);
        assert_eq!(list.arrows.len(), 2);
        for arrow in &list.arrows {
            let direction = (arrow.end - arrow.start).normalize();
            assert!(direction.y.abs() > 0.999, "{direction:?}");
        }
        assert_eq!(list.segments.len(), 2);
        let colors: Vec<Color> = list.segments.iter().map(|s| s.color).collect();
        assert!(colors.contains(&palette::REFERENCE_EDGE));
        assert!(colors.contains(&palette::INCIDENT_EDGE));
    }

    #[test]
    fn overlays_follow_their_flags() {
        let world = scene();
        let list = draw(
            &world,
            DrawFlags::AABBS | DrawFlags::CENTERS_OF_MASS | DrawFlags::EDGE_NORMALS,
        );
        assert_eq!(list.segments.len(), 3 * 4, "four sides per box");
        assert_eq!(list.points.len(), 3);
        assert_eq!(list.arrows.len(), 8, "one normal per polygon edge");
        let falling = draw(&world, DrawFlags::VELOCITIES);
        // The ball falls (the box rests, its velocity too small to draw or pointing down).
        assert!(!falling.arrows.is_empty());
        assert!(falling.arrows.iter().all(|a| a.end.y < a.start.y));
    }

    #[test]
    fn caller_colours_win_and_sleepers_are_dimmed() {
        let mut world = scene();
        let red = Color::rgb(1.0, 0.0, 0.0);
        let options = DrawOptions::default();
        let mut list = DrawList::new();
        world.debug_draw(&options, |_| Some(red), &mut list);
        let awake_fill = list.circles[0].fill;
        assert_eq!(awake_fill, red.mix(Color::BACKGROUND, 0.35));
        let ball = world.bodies().nth(2).unwrap().handle();
        world.body_raw_mut(ball).unwrap().fall_asleep();
        list.clear();
        world.debug_draw(&options, |_| Some(red), &mut list);
        assert_ne!(list.circles[0].fill, awake_fill);
        assert!(list.circles[0].fill.r < awake_fill.r);
    }

    #[test]
    fn flags_have_names() {
        let mut every = DrawFlags::NONE;
        for (name, flag) in DrawFlags::NAMED {
            assert_eq!(DrawFlags::from_name(name), Some(flag));
            assert!(DrawFlags::ALL.contains(flag));
            every = every | flag;
        }
        assert_eq!(every, DrawFlags::ALL, "every flag has a name");
        assert!(DrawFlags::default().contains(DrawFlags::JOINTS));
        assert!(!DrawFlags::default().contains(DrawFlags::JOINT_FORCES));
        assert_eq!(DrawFlags::from_name("sparkles"), None);
        let mut flags = DrawFlags::NONE;
        flags.set(DrawFlags::AABBS, true);
        assert!(flags.contains(DrawFlags::AABBS) && !flags.contains(DrawFlags::SHAPES));
        flags.set(DrawFlags::AABBS, false);
        assert_eq!(flags, DrawFlags::NONE);
    }

    /// A box hanging from a static bar by a hinge with limits, and a ball tied to the box by
    /// a sprung distance joint with limits; also the joints, to find their anchors.
    fn jointed() -> (World, JointHandle, JointHandle) {
        let mut world = World::new();
        let bar = world
            .add_body(BodyDef::static_body(Shape::rect(1.0, 0.2)).position(vec2(0.0, 5.0)))
            .unwrap();
        let boxed = world
            .add_body(BodyDef::dynamic(Shape::rect(0.25, 0.25)).position(vec2(0.0, 4.0)))
            .unwrap();
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.2)).position(vec2(1.5, 4.0)))
            .unwrap();
        let hinge = JointDef::revolute(bar, boxed, vec2(0.0, 4.5))
            .limits(-std::f32::consts::FRAC_PI_4, std::f32::consts::FRAC_PI_2);
        let hinge = world.add_joint(hinge).unwrap();
        let rod = JointDef::distance(boxed, ball, vec2(0.0, 4.0), vec2(1.5, 4.0))
            .spring(2.0, 0.5)
            .limits(1.0, 2.0);
        let rod = world.add_joint(rod).unwrap();
        (world, hinge, rod)
    }

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).norm() < 1e-5
    }

    #[test]
    fn joints_are_drawn_at_their_anchors() {
        let (world, _, _) = jointed();
        let list = draw(&world, DrawFlags::JOINTS);
        assert!(list.polygons.is_empty() && list.circles.is_empty() && list.arrows.is_empty());
        let hinge_at = vec2(0.0, 4.5);
        let (rod_a, rod_b) = (vec2(0.0, 4.0), vec2(1.5, 4.0));
        for at in [hinge_at, rod_a, rod_b] {
            assert!(
                list.points
                    .iter()
                    .any(|p| close(p.at, at) && p.color == palette::JOINT_ANCHOR),
                "an anchor point at {at:?}: {:?}",
                list.points
            );
        }
        // The hinge: bar's centre to the anchor, the anchor to the box's centre.
        let links: Vec<&DrawSegment> = list
            .segments
            .iter()
            .filter(|s| s.color == palette::JOINT)
            .collect();
        assert!(
            links
                .iter()
                .any(|s| close(s.start, vec2(0.0, 5.0)) && close(s.end, hinge_at))
        );
        assert!(
            links
                .iter()
                .any(|s| close(s.start, hinge_at) && close(s.end, vec2(0.0, 4.0)))
        );
        // The rod: anchor to anchor.
        assert!(
            links
                .iter()
                .any(|s| close(s.start, rod_a) && close(s.end, rod_b))
        );
        // The hinge's limits: from the anchor at -45° and 90° (the bar is level and the
        // reference angle 0).
        let limit = |color: Color| {
            list.segments
                .iter()
                .filter(|s| s.color == color && close(s.start, hinge_at))
                .map(|s| (s.end - s.start).normalize())
                .collect::<Vec<_>>()
        };
        let half = std::f32::consts::FRAC_1_SQRT_2;
        let lower = limit(palette::JOINT_LOWER_LIMIT);
        assert!(
            lower.len() == 1 && close(lower[0], vec2(half, -half)),
            "{lower:?}"
        );
        let upper = limit(palette::JOINT_UPPER_LIMIT);
        assert!(
            upper.len() == 1 && close(upper[0], vec2(0.0, 1.0)),
            "{upper:?}"
        );
        // The rod's limits: ticks across the line, 1 m and 2 m out from anchor A.
        for (color, x) in [
            (palette::JOINT_LOWER_LIMIT, 1.0),
            (palette::JOINT_UPPER_LIMIT, 2.0),
        ] {
            let tick = list
                .segments
                .iter()
                .find(|s| s.color == color && !close(s.start, hinge_at))
                .unwrap_or_else(|| panic!("a tick in {color:?}"));
            assert!(
                close((tick.start + tick.end) * 0.5, vec2(x, 4.0)),
                "{tick:?}"
            );
            assert!((tick.start.x - tick.end.x).abs() < 1e-6, "across the rod");
        }
        // Nothing of it is drawn without the flag, whatever else is.
        assert!(draw(&world, DrawFlags::NONE).is_empty());
        let mut others = DrawFlags::ALL;
        others.set(DrawFlags::JOINTS | DrawFlags::JOINT_FORCES, false);
        let off = draw(&world, others);
        let joint_colors = [
            palette::JOINT,
            palette::JOINT_ANCHOR,
            palette::JOINT_AXIS,
            palette::JOINT_LOWER_LIMIT,
            palette::JOINT_UPPER_LIMIT,
        ];
        assert!(
            off.segments
                .iter()
                .all(|s| !joint_colors.contains(&s.color))
        );
        assert!(off.points.iter().all(|p| !joint_colors.contains(&p.color)));
        assert!(!off.points.iter().any(|p| close(p.at, hinge_at)));
        let on = draw(&world, others | DrawFlags::JOINTS);
        assert_eq!(on.segments.len(), off.segments.len() + list.segments.len());
        assert_eq!(on.points.len(), off.points.len() + list.points.len());
    }

    #[test]
    fn axes_span_their_limits_and_mouse_and_filter_joints_draw_nothing() {
        let mut world = World::new();
        let bar = world
            .add_body(BodyDef::static_body(Shape::rect(1.0, 0.2)).position(vec2(0.0, 0.0)))
            .unwrap();
        let slider = world
            .add_body(BodyDef::dynamic(Shape::rect(0.2, 0.2)).position(vec2(0.0, 1.0)))
            .unwrap();
        world
            .add_joint(
                JointDef::prismatic(bar, slider, vec2(0.0, 1.0), vec2(1.0, 0.0)).limits(-0.5, 1.5),
            )
            .unwrap();
        world.add_joint(JointDef::filter(bar, slider)).unwrap();
        world
            .add_joint(JointDef::mouse(slider, vec2(0.1, 1.0), 100.0))
            .unwrap();
        let list = draw(&world, DrawFlags::JOINTS);
        let axis: Vec<&DrawSegment> = list
            .segments
            .iter()
            .filter(|s| s.color == palette::JOINT_AXIS)
            .collect();
        assert_eq!(axis.len(), 1);
        assert!(close(axis[0].start, vec2(-0.5, 1.0)) && close(axis[0].end, vec2(1.5, 1.0)));
        // Only the prismatic joint's two anchors: the mouse and filter joints add none.
        assert_eq!(list.points.len(), 2);
        assert!(list.points.iter().all(|p| close(p.at, vec2(0.0, 1.0))));
    }

    #[test]
    fn joint_forces_are_arrows_from_anchor_b_only_when_asked() {
        let (mut world, hinge, rod) = jointed();
        for _ in 0..10 {
            world.step(1.0 / 60.0).unwrap();
        }
        let without = draw(&world, DrawFlags::JOINTS);
        assert!(without.arrows.is_empty());
        let with = draw(&world, DrawFlags::JOINTS | DrawFlags::JOINT_FORCES);
        assert_eq!(with.segments, without.segments);
        assert_eq!(with.arrows.len(), 2, "{:?}", with.arrows);
        for (arrow, joint) in with.arrows.iter().zip([hinge, rod]) {
            let joint = world.joint(joint).unwrap();
            let [a, b] = joint.bodies().map(|h| world.body(h).unwrap());
            let at = joint.world_anchors(a, b)[1];
            assert!(close(arrow.start, at), "{arrow:?} from {at:?}");
            assert_eq!(arrow.color, palette::JOINT_FORCE);
            let expected = joint.reaction_force() * DrawOptions::default().force_scale;
            assert!(close(arrow.end - arrow.start, expected), "{arrow:?}");
        }
        // The hinge holds the box and the ball up.
        assert!(with.arrows[0].end.y > with.arrows[0].start.y);
        let forces_only = draw(&world, DrawFlags::JOINT_FORCES);
        assert!(forces_only.segments.is_empty() && forces_only.points.is_empty());
        assert_eq!(forces_only.arrows, with.arrows);
    }

    #[test]
    fn force_arrows_are_capped() {
        let (mut world, _, _) = jointed();
        world.step(1.0 / 60.0).unwrap();
        let mut list = DrawList::new();
        let options = DrawOptions {
            flags: DrawFlags::JOINT_FORCES,
            force_scale: 1e3,
            ..DrawOptions::default()
        };
        world.debug_draw(&options, |_| None, &mut list);
        // The hinge holds about 10 N: 10 km at this scale, without the cap.
        let lengths: Vec<Real> = list
            .arrows
            .iter()
            .map(|a| (a.end - a.start).norm())
            .collect();
        assert!((lengths[0] - MAX_FORCE_ARROW).abs() < 1e-4, "{lengths:?}");
        assert!(
            lengths.iter().all(|&l| l < MAX_FORCE_ARROW + 1e-4),
            "{lengths:?}"
        );
    }
}
