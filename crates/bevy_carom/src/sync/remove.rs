//! Removing from the world what the game despawned or took off its entities.

use crate::body::{BodyMirror, CaromBody, RigidBody};
use crate::collider::{CaromCollider, Collider};
use crate::joint::{CaromJoint, Joint, JointMirror};
use crate::world::CaromWorld;
use bevy::ecs::lifecycle::Remove;
use bevy::ecs::observer::On;
use bevy::ecs::system::{Commands, ResMut};
use carom::CaromError;

/// Notes a body component's removal (or its entity's despawn) as it happens.
pub(crate) fn body_removed(removed: On<Remove, RigidBody>, mut world: ResMut<CaromWorld>) {
    world.links.removed.bodies.push(removed.entity);
}

/// Notes a collider component's removal.
pub(crate) fn collider_removed(removed: On<Remove, Collider>, mut world: ResMut<CaromWorld>) {
    world.links.removed.colliders.push(removed.entity);
}

/// Notes a joint component's removal.
pub(crate) fn joint_removed(removed: On<Remove, Joint>, mut world: ResMut<CaromWorld>) {
    world.links.removed.joints.push(removed.entity);
}

/// Removes from the world the joints, colliders and bodies whose components went away, in
/// that order (a body's removal takes its joints and colliders with it), and the plugin's
/// links from entities that are still there.
pub(crate) fn remove_gone(mut world: ResMut<CaromWorld>, mut commands: Commands) {
    let world = &mut *world;
    let removed = std::mem::take(&mut world.links.removed);
    for entity in removed.joints {
        if let Some(joint) = world.unlink_joint(entity) {
            // A joint its body's removal or its break already took is gone: nothing to do.
            let _ = world.world.remove_joint(joint);
            if let Ok(mut e) = commands.get_entity(entity) {
                e.try_remove::<(CaromJoint, JointMirror)>();
            }
        }
    }
    let mut bodies = removed.bodies;
    for entity in removed.colliders {
        let colliders = world.unlink_colliders(entity);
        for collider in &colliders {
            let body = world.world.collider(*collider).map(|c| c.body());
            if let Err(CaromError::NoCollider) = world.world.remove_collider(*collider) {
                // Its body's last: carom's bodies have one, so the body goes too, and is made
                // again when its entity gets a collider again.
                if let Some(owner) = body.and_then(|b| world.body_entity(b)) {
                    bodies.push(owner);
                }
            }
        }
        if !colliders.is_empty()
            && let Ok(mut e) = commands.get_entity(entity)
        {
            e.try_remove::<CaromCollider>();
        }
    }
    for entity in bodies {
        if let Some(body) = world.unlink_body(entity) {
            // Its colliders go with it: forget them, and let their entities (children, or
            // this one) make colliders again if they get a body again.
            if let Some(b) = world.world.body(body) {
                for collider in b.colliders().to_vec() {
                    if let Some(owner) = world.links.colliders.remove(&collider) {
                        world.links.entity_colliders.remove(&owner);
                        if let Ok(mut e) = commands.get_entity(owner) {
                            e.try_remove::<CaromCollider>();
                        }
                    }
                }
            }
            // So do its joints: their entities keep their `Joint`, made again once both
            // bodies are back.
            let joints = world.world.joints_of(body).to_vec();
            for joint in joints {
                if let Some(owner) = world.links.joints.remove(&joint) {
                    world.links.entity_joints.remove(&owner);
                    if let Ok(mut e) = commands.get_entity(owner) {
                        e.try_remove::<(CaromJoint, JointMirror)>();
                    }
                }
            }
            let _ = world.world.remove_body(body);
            if let Ok(mut e) = commands.get_entity(entity) {
                e.try_remove::<(CaromBody, BodyMirror)>();
            }
        }
    }
}
