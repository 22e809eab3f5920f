//! Debug drawing through Bevy's gizmos (the `debug-draw` feature): carom's own
//! [`carom::draw::DebugDraw`] description of the world (shapes, contacts, joints, velocities, as
//! [`DebugDrawOptions`] selects) drawn as gizmo lines each frame.

use crate::convert::to_bevy;
use crate::world::CaromWorld;
use bevy::app::{App, Plugin, PostUpdate};
use bevy::color::Color;
use bevy::ecs::resource::Resource;
use bevy::ecs::system::Res;
use bevy::gizmos::gizmos::Gizmos;
use bevy::math::Isometry2d;
use carom::Real;
use carom::draw::{DebugDraw, DrawOptions};

/// Draws the [`CaromWorld`] with gizmos every frame (with a renderer that draws gizmos, such
/// as `DefaultPlugins`).
#[derive(Debug, Default, Clone, Copy)]
pub struct CaromDebugDrawPlugin;

/// What the debug drawing shows: carom's [`DrawOptions`] (shapes by default; contact points
/// and normals, joints, centres of mass, velocities, bounding boxes, sleep at will).
#[derive(Resource, Debug, Clone, Default)]
pub struct DebugDrawOptions(pub DrawOptions);

impl Plugin for CaromDebugDrawPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<DebugDrawOptions>()
            .add_systems(PostUpdate, draw);
    }
}

fn draw(world: Res<CaromWorld>, options: Res<DebugDrawOptions>, gizmos: Gizmos) {
    let mut sink = GizmoSink { gizmos };
    world.world().debug_draw(&options.0, |_| None, &mut sink);
}

/// carom's drawing calls as gizmo lines: outlines only, since gizmos do not fill.
struct GizmoSink<'w, 's> {
    gizmos: Gizmos<'w, 's>,
}

fn color(c: carom::draw::Color) -> Color {
    Color::srgba(c.r, c.g, c.b, c.a)
}

impl DebugDraw for GizmoSink<'_, '_> {
    fn polygon(
        &mut self,
        vertices: &[carom::Vec2],
        _fill: carom::draw::Color,
        outline: carom::draw::Color,
    ) {
        let points = vertices.iter().chain(vertices.first()).map(|&v| to_bevy(v));
        self.gizmos.linestrip_2d(points, color(outline));
    }

    fn circle(
        &mut self,
        center: carom::Vec2,
        radius: Real,
        _fill: carom::draw::Color,
        outline: carom::draw::Color,
    ) {
        self.gizmos.circle_2d(
            Isometry2d::from_translation(to_bevy(center)),
            radius as f32,
            color(outline),
        );
    }

    fn segment(
        &mut self,
        start: carom::Vec2,
        end: carom::Vec2,
        _width: f32,
        c: carom::draw::Color,
    ) {
        self.gizmos.line_2d(to_bevy(start), to_bevy(end), color(c));
    }

    fn arrow(&mut self, start: carom::Vec2, end: carom::Vec2, c: carom::draw::Color) {
        self.gizmos.arrow_2d(to_bevy(start), to_bevy(end), color(c));
    }

    fn point(&mut self, at: carom::Vec2, size: f32, c: carom::draw::Color) {
        // `size` is in pixels, which gizmos do not know: a dot of 1 cm per pixel.
        self.gizmos.circle_2d(
            Isometry2d::from_translation(to_bevy(at)),
            0.005 * size,
            color(c),
        );
    }
}
