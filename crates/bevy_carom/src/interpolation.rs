//! Drawing [`Interpolated`] bodies between fixed steps: after the frame's steps, each one's
//! `Transform` is put the overstep's fraction of the way from its pose before the last step
//! to its pose after it. The physics never reads it: the next step starts from the stepped
//! pose, and a `Transform` the game sets in between is still a teleport.

use crate::body::{BodyMirror, Interpolated};
use bevy::ecs::query::With;
use bevy::ecs::system::{Query, Res};
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;

/// Puts interpolated bodies where they are drawn this frame.
pub(crate) fn interpolate(
    time: Res<Time<Fixed>>,
    mut bodies: Query<(&mut BodyMirror, &mut Transform), With<Interpolated>>,
) {
    let t = time.overstep_fraction();
    for (mut mirror, mut transform) in &mut bodies {
        // A Transform the game changed since the plugin wrote it is left for the next step.
        if *transform != mirror.transform || mirror.previous == mirror.current {
            continue;
        }
        mirror
            .previous
            .lerp(mirror.current, t)
            .apply_to(&mut transform);
        mirror.transform = *transform;
    }
}
