//! Grab a shape with the mouse, drag it and throw it: the room of demos/grabbing.ron, loaded
//! as entities, with a mouse joint made on a press and removed on release.
//!
//! `cargo run --release -p bevy_carom --example grab --features examples`

use bevy::camera::{OrthographicProjection, Projection, ScalingMode};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_carom::SceneLoaded;
use bevy_carom::carom::JointKind;
use bevy_carom::prelude::*;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, CaromPlugin, CaromDebugDrawPlugin))
        .init_resource::<Grab>()
        .init_resource::<Cursor>()
        .add_systems(Startup, setup)
        .add_systems(Update, (find_anchor, track_cursor, grab).chain())
        .run();
}

/// The static body mouse joints pull against, and the joint of the grab in progress.
#[derive(Resource, Default)]
struct Grab {
    anchor: Option<Entity>,
    joint: Option<Entity>,
}

/// Where the mouse points, in the world.
#[derive(Resource, Default)]
struct Cursor(Option<Vec2>);

fn setup(mut commands: Commands) {
    commands.spawn((
        Camera2d,
        Projection::Orthographic(OrthographicProjection {
            scaling_mode: ScalingMode::FixedVertical {
                viewport_height: 12.0,
            },
            ..OrthographicProjection::default_2d()
        }),
        Transform::from_xyz(0.0, 5.0, 0.0),
    ));
    let scene = include_str!("../../../demos/grabbing.ron");
    commands.queue(LoadScene::new(scene, "grabbing.ron"));
}

/// Takes the scene's first static body (a wall) as the anchor once it is loaded.
fn find_anchor(
    mut loaded: MessageReader<SceneLoaded>,
    bodies: Query<&RigidBody>,
    mut grab: ResMut<Grab>,
) {
    for message in loaded.read() {
        match &message.result {
            Ok(scene) => {
                grab.anchor = scene
                    .bodies
                    .iter()
                    .copied()
                    .find(|&e| bodies.get(e) == Ok(&RigidBody::Static));
            }
            Err(error) => error!("{error}"),
        }
    }
}

fn track_cursor(
    window: Query<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform)>,
    mut cursor: ResMut<Cursor>,
) {
    let (Ok(window), Ok((camera, camera_transform))) = (window.single(), camera.single()) else {
        return;
    };
    cursor.0 = window
        .cursor_position()
        .and_then(|p| camera.viewport_to_world_2d(camera_transform, p).ok());
}

fn grab(
    mouse: Res<ButtonInput<MouseButton>>,
    cursor: Res<Cursor>,
    query: CaromQuery,
    world: Res<CaromWorld>,
    mut joints: Query<&mut Joint>,
    mut grab: ResMut<Grab>,
    mut commands: Commands,
) {
    if mouse.just_released(MouseButton::Left)
        && let Some(joint) = grab.joint.take()
    {
        // The body flies on with the velocity the drag gave it.
        commands.entity(joint).despawn();
    }
    let Some(cursor) = cursor.0 else {
        return;
    };
    if mouse.just_pressed(MouseButton::Left)
        && let Some(anchor) = grab.anchor
        && let Some(body) = query.body_at(cursor)
        && let Some(state) = world
            .entity_body(body)
            .and_then(|handle| world.world().body(handle))
            .filter(|state| state.is_dynamic())
    {
        let joint = Joint::mouse(anchor, body, cursor, 1000.0 * state.mass());
        grab.joint = Some(commands.spawn(joint).id());
    }
    if let Some(joint) = grab.joint
        && let Ok(mut joint) = joints.get_mut(joint)
        && let JointKind::Mouse(mouse) = &mut joint.kind
    {
        mouse.target = bevy_carom::carom::vec2(cursor.x, cursor.y);
    }
}
