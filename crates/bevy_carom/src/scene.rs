//! Scenes in carom's RON format (the demo's `demos/*.ron`) as entities: [`LoadScene`].

use crate::body::{
    BodyMirror, Bullet, CaromBody, Damping, GravityScale, LockedRotation, LookAhead, RigidBody,
    Sleeping, Velocity,
};
use crate::collider::{
    CaromCollider, Collider, ColliderMaterial, CollisionFilter, HitEvents, Sensor,
};
use crate::convert::{Pose, to_bevy};
use crate::joint::{CaromJoint, Joint, JointMirror};
use crate::world::CaromWorld;
use bevy::ecs::entity::Entity;
use bevy::ecs::hierarchy::ChildOf;
use bevy::ecs::message::Message;
use bevy::ecs::name::Name;
use bevy::ecs::query::{Or, With};
use bevy::ecs::system::Command;
use bevy::ecs::world::World;
use bevy::math::Quat;
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;
use carom::{Anchors, Real};
use std::collections::HashMap;

/// A command that loads a scene: the scene's world replaces the [`CaromWorld`] (its settings
/// too), the entities of the old world's bodies, colliders and joints are despawned, and each
/// of the scene's bodies becomes an entity (with its name, if the scene gives one), each of
/// its colliders a [`Collider`] (on the body's entity when it is the only one and unmoved,
/// else on a child), and each joint an entity with a [`Joint`]. The fixed timestep becomes
/// the scene's. A [`SceneLoaded`] message says what was spawned, or why nothing was.
///
/// The scene's timed events and player are not run.
///
/// ```no_run
/// # use bevy::prelude::*;
/// # use bevy_carom::LoadScene;
/// fn load(mut commands: Commands) {
///     let text = std::fs::read_to_string("demos/pyramid.ron").unwrap();
///     commands.queue(LoadScene::new(text, "pyramid.ron"));
/// }
/// ```
#[derive(Debug, Clone)]
pub struct LoadScene {
    text: String,
    file: String,
}

impl LoadScene {
    /// Loads the scene in `text`; `file` names it in error messages.
    pub fn new(text: impl Into<String>, file: impl Into<String>) -> Self {
        LoadScene {
            text: text.into(),
            file: file.into(),
        }
    }
}

/// A scene was loaded by [`LoadScene`], or could not be.
#[derive(Message, Debug, Clone)]
pub struct SceneLoaded {
    /// The file named in the command.
    pub file: String,
    /// The spawned entities, or what was wrong with the scene (the world is then unchanged).
    pub result: Result<SceneEntities, String>,
}

/// The entities a scene became.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SceneEntities {
    /// Its bodies, in the world's order.
    pub bodies: Vec<Entity>,
    /// Its joints.
    pub joints: Vec<Entity>,
    /// Its named bodies.
    pub names: HashMap<String, Entity>,
}

impl Command for LoadScene {
    type Out = ();

    fn apply(self, world: &mut World) {
        let result = load(world, &self.text, &self.file);
        world.write_message(SceneLoaded {
            file: self.file,
            result,
        });
    }
}

fn load(world: &mut World, text: &str, file: &str) -> Result<SceneEntities, String> {
    let scene = carom_scene::parse(text, file).map_err(|e| e.to_string())?;
    let built = carom_scene::build(&scene, file).map_err(|e| e.to_string())?;

    let old: Vec<Entity> = world
        .query_filtered::<Entity, Or<(With<CaromBody>, With<CaromCollider>, With<CaromJoint>)>>()
        .iter(world)
        .collect();
    for entity in old {
        // A child already went with its parent.
        let _ = world.try_despawn(entity);
    }
    if let Some(mut time) = world.get_resource_mut::<Time<Fixed>>() {
        time.set_timestep_seconds(built.time_step as f64);
    }
    let names: HashMap<_, _> = built.names.iter().map(|(n, &b)| (b, n.clone())).collect();
    let mut carom_world = CaromWorld {
        world: built.world,
        ..CaromWorld::default()
    };
    let mut spawned = SceneEntities::default();
    for body in carom_world.world.bodies() {
        let pose = Pose::of_body(body);
        let mut transform = Transform::default();
        pose.apply_to(&mut transform);
        let velocity = Velocity {
            linear: to_bevy(body.linear_velocity()),
            angular: body.angular_velocity() as f32,
        };
        let mut entity = world.spawn((
            RigidBody::from(body.kind()),
            transform,
            velocity,
            Damping {
                linear: body.linear_damping() as f32,
                angular: body.angular_damping() as f32,
            },
            GravityScale(body.gravity_scale() as f32),
            Sleeping(body.is_sleeping()),
            CaromBody(body.handle()),
            BodyMirror {
                transform,
                velocity,
                sleeping: body.is_sleeping(),
                locked: body.fixed_rotation(),
                bullet: body.is_bullet(),
                look_ahead: body.looks_ahead(),
                targeted: false,
                previous: pose,
                current: pose,
            },
        ));
        if body.fixed_rotation() {
            entity.insert(LockedRotation);
        }
        if body.is_bullet() {
            entity.insert(Bullet);
        }
        if body.looks_ahead() {
            entity.insert(LookAhead);
        }
        if let Some(name) = names.get(&body.handle()) {
            entity.insert(Name::new(name.clone()));
            spawned.names.insert(name.clone(), entity.id());
        }
        let body_entity = entity.id();
        spawned.bodies.push(body_entity);
        let colliders: Vec<_> = body
            .colliders()
            .iter()
            .filter_map(|&c| Some((c, carom_world.world.collider(c)?)))
            .collect();
        let alone =
            colliders.len() == 1 && colliders[0].1.local_transform() == carom::Isometry::identity();
        for (handle, collider) in colliders {
            let components = (
                Collider::from_shape(collider.shape().clone()),
                ColliderMaterial::of(collider),
                CollisionFilter::from(collider.filter()),
                CaromCollider {
                    handles: vec![handle],
                    body: body_entity,
                },
            );
            let collider_entity = if alone {
                world.entity_mut(body_entity).insert(components).id()
            } else {
                let local = collider.local_transform();
                let offset = to_bevy(local.translation.vector);
                let angle = local.rotation.angle() as f32;
                world
                    .spawn((
                        components,
                        Transform::from_translation(offset.extend(0.0))
                            .with_rotation(Quat::from_rotation_z(angle)),
                        ChildOf(body_entity),
                    ))
                    .id()
            };
            if collider.is_sensor() {
                world.entity_mut(collider_entity).insert(Sensor);
            }
            if collider.hit_events() {
                world.entity_mut(collider_entity).insert(HitEvents);
            }
            carom_world.links.colliders.insert(handle, collider_entity);
            carom_world
                .links
                .entity_colliders
                .entry(collider_entity)
                .or_default()
                .push(handle);
        }
        carom_world.links.bodies.insert(body.handle(), body_entity);
        carom_world
            .links
            .entity_bodies
            .insert(body_entity, body.handle());
    }
    for joint in carom_world.world.joints() {
        let [a, b] = joint.bodies();
        let (Some(&ea), Some(&eb)) = (
            carom_world.links.bodies.get(&a),
            carom_world.links.bodies.get(&b),
        ) else {
            continue;
        };
        let [anchor_a, anchor_b] = joint.local_anchors();
        let (break_force, break_torque) = joint.break_thresholds();
        let component = Joint {
            body_a: ea,
            body_b: eb,
            anchors: Anchors::Local {
                a: anchor_a,
                b: anchor_b,
                reference_angle: joint.reference_angle() as Real,
            },
            kind: *joint.kind(),
            collide_connected: joint.collide_connected(),
            break_force: break_force as f32,
            break_torque: break_torque as f32,
        };
        let entity = world
            .spawn((
                component,
                CaromJoint(joint.handle()),
                JointMirror(component),
            ))
            .id();
        carom_world.links.joints.insert(joint.handle(), entity);
        carom_world
            .links
            .entity_joints
            .insert(entity, joint.handle());
        spawned.joints.push(entity);
    }
    world.insert_resource(carom_world);
    Ok(spawned)
}
