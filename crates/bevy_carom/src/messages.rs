//! What happened in a step, as Bevy messages: contacts beginning and ending, sensors entered
//! and left, hard hits, broken joints, and components that could not become carom objects.
//! Read them with a `MessageReader` in any schedule.

use crate::convert::to_bevy;
use crate::world::CaromWorld;
use bevy::ecs::entity::Entity;
use bevy::ecs::message::{Message, MessageWriter};
use bevy::ecs::system::{Commands, Res};
use bevy::math::Vec2;
use carom::{ContactEvent, ContactPair, JointEvent, SensorEvent};

/// Two colliders began to touch.
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq)]
pub struct ContactStarted {
    /// The first collider's entity.
    pub collider_a: Entity,
    /// The second collider's entity.
    pub collider_b: Entity,
    /// The first collider's body.
    pub body_a: Entity,
    /// The second collider's body.
    pub body_b: Entity,
}

/// Two colliders stopped touching (or one of them was removed).
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq)]
pub struct ContactEnded {
    /// The first collider's entity.
    pub collider_a: Entity,
    /// The second collider's entity.
    pub collider_b: Entity,
    /// The first collider's body.
    pub body_a: Entity,
    /// The second collider's body.
    pub body_b: Entity,
}

/// A collider began to overlap a [`crate::Sensor`].
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorEntered {
    /// The sensor's entity.
    pub sensor: Entity,
    /// The entity of the collider that entered it.
    pub visitor: Entity,
    /// The visitor's body.
    pub visitor_body: Entity,
}

/// A collider stopped overlapping a [`crate::Sensor`].
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorExited {
    /// The sensor's entity.
    pub sensor: Entity,
    /// The entity of the collider that left it.
    pub visitor: Entity,
    /// The visitor's body.
    pub visitor_body: Entity,
}

/// A hard impact: two colliders, one with [`crate::HitEvents`], met faster than the world's
/// hit speed.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The first collider's entity.
    pub collider_a: Entity,
    /// The second collider's entity.
    pub collider_b: Entity,
    /// Where they met, in the world.
    pub point: Vec2,
    /// The contact normal, unit, from the first collider to the second.
    pub normal: Vec2,
    /// How fast they approached along the normal, m/s.
    pub approach_speed: f32,
}

/// A joint pulled harder than its break force or torque and was removed; the plugin takes
/// the [`crate::Joint`] off its entity.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct JointBroken {
    /// The joint's entity.
    pub joint: Entity,
    /// The force it applied in its last step, N.
    pub force: Vec2,
    /// The torque it applied in its last step, N·m.
    pub torque: f32,
}

/// An entity's components could not become a carom object (a collider's shape out of range,
/// a joint whose bodies cannot take it), or a step failed. The entity stays as it is, without
/// the object.
#[derive(Message, Debug, Clone, PartialEq)]
pub struct PhysicsError {
    /// The entity, when the error is about one.
    pub entity: Option<Entity>,
    /// What was wrong.
    pub error: carom::CaromError,
}

/// The entities of a contact pair, when both are still known.
fn pair_entities(world: &CaromWorld, pair: &ContactPair) -> Option<[Entity; 4]> {
    Some([
        world.collider_entity(pair.collider_a)?,
        world.collider_entity(pair.collider_b)?,
        world.body_entity(pair.body_a)?,
        world.body_entity(pair.body_b)?,
    ])
}

/// The last step's events, as messages. An event about an object whose entity is already
/// gone is dropped.
pub(crate) fn write_messages(
    world: Res<CaromWorld>,
    mut commands: Commands,
    mut started: MessageWriter<ContactStarted>,
    mut ended: MessageWriter<ContactEnded>,
    mut entered: MessageWriter<SensorEntered>,
    mut exited: MessageWriter<SensorExited>,
    mut hits: MessageWriter<Hit>,
    mut broken: MessageWriter<JointBroken>,
) {
    for event in world.world.contact_events() {
        let Some([collider_a, collider_b, body_a, body_b]) = pair_entities(&world, &event.pair())
        else {
            continue;
        };
        match event {
            ContactEvent::Begin(_) => {
                started.write(ContactStarted {
                    collider_a,
                    collider_b,
                    body_a,
                    body_b,
                });
            }
            ContactEvent::End(_) => {
                ended.write(ContactEnded {
                    collider_a,
                    collider_b,
                    body_a,
                    body_b,
                });
            }
        }
    }
    for event in world.world.sensor_events() {
        let overlap = event.overlap();
        let (Some(sensor), Some(visitor), Some(visitor_body)) = (
            world.collider_entity(overlap.sensor),
            world.collider_entity(overlap.visitor),
            world.body_entity(overlap.visitor_body),
        ) else {
            continue;
        };
        match event {
            SensorEvent::Begin(_) => {
                entered.write(SensorEntered {
                    sensor,
                    visitor,
                    visitor_body,
                });
            }
            SensorEvent::End(_) => {
                exited.write(SensorExited {
                    sensor,
                    visitor,
                    visitor_body,
                });
            }
        }
    }
    for hit in world.world.hit_events() {
        let Some([collider_a, collider_b, _, _]) = pair_entities(&world, &hit.pair) else {
            continue;
        };
        hits.write(Hit {
            collider_a,
            collider_b,
            point: to_bevy(hit.point),
            normal: to_bevy(hit.normal),
            approach_speed: hit.approach_speed as f32,
        });
    }
    for event in world.world.joint_events() {
        // Events carom adds later have no message here yet.
        let JointEvent::Broken {
            joint,
            force,
            torque,
            ..
        } = *event
        else {
            continue;
        };
        let Some(entity) = world.joint_entity(joint) else {
            continue;
        };
        // The joint is gone from the world; without its component the plugin would make it
        // again. Its link is forgotten when the component's removal is observed.
        commands.entity(entity).try_remove::<(
            crate::Joint,
            crate::joint::CaromJoint,
            crate::joint::JointMirror,
        )>();
        broken.write(JointBroken {
            joint: entity,
            force: to_bevy(force),
            torque: torque as f32,
        });
    }
}
