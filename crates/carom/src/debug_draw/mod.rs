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

mod color;
mod joints;
mod options;
mod sink;

pub use color::Color;
pub(crate) use color::palette;
pub use options::{DrawFlags, DrawOptions};
pub use sink::{DebugDraw, DrawArrow, DrawCircle, DrawList, DrawPoint, DrawPolygon, DrawSegment};

use crate::dynamics::body::{Body, BodyKind};
use crate::dynamics::collider::Collider;
use crate::geometry::query::manifold::PairSide;
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2, vec2};
use crate::world::World;

/// A circle's radius line, pixels (as thick as carom-render's outlines).
const RADIUS_LINE_WIDTH: f32 = 1.5;
/// A segment or chain link drawn as a shape, pixels: twice the radius line, so that a shape
/// with no inside still reads as one.
const SHAPE_LINE_WIDTH: f32 = 2.0 * RADIUS_LINE_WIDTH;
/// Reference and incident edge thickness, pixels.
const CONTACT_EDGE_WIDTH: f32 = 4.0;
/// Contact point diameter, pixels.
const CONTACT_POINT_SIZE: f32 = 7.0;

/// The colour a body is drawn in when the caller has none for it.
pub(crate) fn default_color(body: &Body) -> Color {
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
        if flags.intersects(DrawFlags::JOINTS | DrawFlags::JOINT_FORCES) {
            self.draw_joints(options, out);
        }
        let contact_flags =
            DrawFlags::CONTACT_POINTS | DrawFlags::CONTACT_NORMALS | DrawFlags::CONTACT_EDGES;
        if flags.intersects(contact_flags) {
            self.draw_contacts(options, out);
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
            out.segment(vertices[0], vertices[1], SHAPE_LINE_WIDTH, outline);
        }
        WorldShape::ChainSegment { point1, point2, .. } => {
            out.segment(*point1, *point2, SHAPE_LINE_WIDTH, outline);
        }
        WorldShape::Circle { center, radius } => {
            out.circle(*center, *radius, fill, outline);
            let turn = body.rotation() * collider.local_transform().rotation;
            let rim = center + turn * vec2(*radius, 0.0);
            out.segment(*center, rim, RADIUS_LINE_WIDTH, outline);
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
        let steps = (turn / (crate::math::consts::TAU / 16.0)).ceil().max(1.0) as usize;
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
    use crate::{BodyDef, Shape};

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

    pub(super) fn draw(world: &World, flags: DrawFlags) -> DrawList {
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
}
