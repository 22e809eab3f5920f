//! A pyramid of 210 boxes falling into place on the ground, drawn with carom's debug drawing.
//!
//! `cargo run --release -p bevy_carom --example pyramid --features examples`

use bevy::camera::{OrthographicProjection, Projection, ScalingMode};
use bevy::prelude::*;
use bevy_carom::prelude::*;

/// Boxes in the bottom row.
const BASE: u32 = 20;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, CaromPlugin, CaromDebugDrawPlugin))
        .insert_resource(Time::<Fixed>::from_hz(60.0))
        .add_systems(Startup, setup)
        .run();
}

fn setup(mut commands: Commands) {
    commands.spawn((
        Camera2d,
        Projection::Orthographic(OrthographicProjection {
            scaling_mode: ScalingMode::FixedVertical {
                viewport_height: 26.0,
            },
            ..OrthographicProjection::default_2d()
        }),
        Transform::from_xyz(0.0, 10.0, 0.0),
    ));
    // The ground: a collider alone is a static body.
    commands.spawn((
        Collider::rectangle(80.0, 2.0),
        Transform::from_xyz(0.0, -1.0, 0.0),
    ));
    // The boxes start a little apart and settle onto each other.
    for row in 0..BASE {
        for i in 0..BASE - row {
            let x = i as f32 - (BASE - 1 - row) as f32 * 0.5;
            let y = 0.5 + row as f32 * 1.05;
            commands.spawn((
                RigidBody::Dynamic,
                Collider::rectangle(1.0, 1.0),
                Transform::from_xyz(x, y, 0.0),
            ));
        }
    }
}
