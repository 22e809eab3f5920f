//! The step itself, and writing its outcome back to the bodies' components.

use crate::body::{BodyMirror, CaromBody, Sleeping, Velocity};
use crate::convert::{Pose, to_bevy};
use crate::messages::PhysicsError;
use crate::world::CaromWorld;
use bevy::ecs::message::MessageWriter;
use bevy::ecs::system::{Query, Res, ResMut};
use bevy::time::Time;
use bevy::transform::components::Transform;
use carom::Real;

/// Advances the world by the fixed timestep.
pub(crate) fn step(
    mut world: ResMut<CaromWorld>,
    time: Res<Time>,
    mut errors: MessageWriter<PhysicsError>,
) {
    let dt = time.delta_secs() as Real;
    if dt <= 0.0 {
        return;
    }
    if let Err(error) = world.world.step(dt) {
        errors.write(PhysicsError {
            entity: None,
            error,
        });
    }
}

/// Writes each body's pose, velocity and sleep back to its components. A body that did not
/// move (asleep, static) is not written, so Bevy sees no change and propagates nothing.
pub(crate) fn write_back(
    world: Res<CaromWorld>,
    mut bodies: Query<(
        &CaromBody,
        &mut BodyMirror,
        &mut Transform,
        &mut Velocity,
        &mut Sleeping,
    )>,
) {
    for (body, mut mirror, mut transform, mut velocity, mut sleeping) in &mut bodies {
        let Some(state) = world.world.body(body.0) else {
            continue;
        };
        let pose = Pose::of_body(state);
        let mirror = &mut *mirror;
        mirror.previous = mirror.current;
        if pose != mirror.current {
            mirror.current = pose;
            pose.apply_to(&mut transform);
        }
        mirror.transform = *transform;
        let v = Velocity {
            linear: to_bevy(state.linear_velocity()),
            angular: state.angular_velocity() as f32,
        };
        if v != mirror.velocity {
            *velocity = v;
            mirror.velocity = v;
        }
        let asleep = state.is_sleeping();
        if asleep != mirror.sleeping {
            sleeping.0 = asleep;
            mirror.sleeping = asleep;
        }
    }
}
