//! Making carom bodies, colliders and joints for the entities that gained their components.
//! New objects are made in the order of their entities' indices (the order a fresh world
//! spawns them in), so that the same spawns make the same world.

use crate::body::{
    BodyMirror, Bullet, CaromBody, Damping, GravityScale, LockedRotation, LookAhead, RigidBody,
    Sleeping, Velocity,
};
use crate::collider::{
    CaromCollider, Collider, ColliderMaterial, ColliderParts, CollisionFilter, HitEvents, Sensor,
};
use crate::convert::{Pose, angle_of, to_carom};
use crate::joint::{CaromJoint, Joint, JointMirror};
use crate::messages::PhysicsError;
use crate::world::CaromWorld;
use bevy::ecs::component::Component;
use bevy::ecs::entity::Entity;
use bevy::ecs::hierarchy::{ChildOf, Children};
use bevy::ecs::message::MessageWriter;
use bevy::ecs::query::{Changed, Has, Or, With, Without};
use bevy::ecs::system::{Commands, Query, ResMut};
use bevy::math::Vec2;
use bevy::transform::components::Transform;
use carom::{BodyDef, BodyHandle, CaromError, Real, Shape};

/// Marks an entity whose components carom refused (the error went out as a
/// [`PhysicsError`]); it is tried again once they change.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Refused;

type NewBody<'a> = (
    Entity,
    &'a RigidBody,
    &'a Transform,
    &'a Velocity,
    &'a Damping,
    &'a GravityScale,
    &'a Sleeping,
    Has<LockedRotation>,
    Has<Bullet>,
    Has<LookAhead>,
);

/// What a collider's definition is made from; a query's data.
pub(crate) type NewCollider<'a> = (
    Entity,
    &'a Collider,
    Option<&'a ColliderMaterial>,
    Option<&'a CollisionFilter>,
    Has<Sensor>,
    Has<HitEvents>,
    &'a Transform,
);

/// A [`NewCollider`] query's item.
pub(crate) type ColliderItem<'a> = (
    Entity,
    &'a Collider,
    Option<&'a ColliderMaterial>,
    Option<&'a CollisionFilter>,
    bool,
    bool,
    &'a Transform,
);

/// Gives a static body to each collider that has none on its entity or its parent: a lone
/// collider is fixed ground.
pub(crate) fn give_lone_colliders_bodies(
    colliders: Query<
        (Entity, Option<&ChildOf>),
        (With<Collider>, Without<RigidBody>, Without<CaromCollider>),
    >,
    bodies: Query<(), With<RigidBody>>,
    mut commands: Commands,
) {
    for (entity, parent) in &colliders {
        if parent.is_none_or(|p| !bodies.contains(p.parent())) {
            commands.entity(entity).insert(RigidBody::Static);
        }
    }
}

/// Lets refused entities try again once their physics components change.
pub(crate) fn retry_refused(
    changed: Query<
        Entity,
        (
            With<Refused>,
            Or<(
                Changed<RigidBody>,
                Changed<Transform>,
                Changed<Velocity>,
                Changed<Collider>,
                Changed<ColliderMaterial>,
                Changed<Joint>,
            )>,
        ),
    >,
    mut commands: Commands,
) {
    for entity in &changed {
        commands.entity(entity).remove::<Refused>();
    }
}

fn refuse(
    commands: &mut Commands,
    errors: &mut MessageWriter<PhysicsError>,
    entity: Entity,
    error: CaromError,
) {
    commands.entity(entity).insert(Refused);
    errors.write(PhysicsError {
        entity: Some(entity),
        error,
    });
}

/// Makes the bodies of entities that gained a [`RigidBody`], each with its colliders (its
/// own, then its children's) in its definition. carom's bodies have at least one collider: a
/// body with none waits for one.
pub(crate) fn create_bodies(
    mut world: ResMut<CaromWorld>,
    new_bodies: Query<NewBody, (Without<CaromBody>, Without<Refused>)>,
    colliders: Query<NewCollider, (Without<CaromCollider>, Without<Refused>)>,
    children: Query<&Children>,
    mut commands: Commands,
    mut errors: MessageWriter<PhysicsError>,
) {
    let mut new: Vec<_> = new_bodies.iter().collect();
    new.sort_unstable_by_key(|b| b.0.index());
    for (
        entity,
        kind,
        transform,
        velocity,
        damping,
        gravity,
        sleeping,
        locked,
        bullet,
        look_ahead,
    ) in new
    {
        let pose = Pose::of_transform(transform);
        let mut def = BodyDef::new((*kind).into(), Shape::circle(1.0));
        def.colliders.clear();
        // Which entity each of the definition's colliders is.
        let mut owners = Vec::new();
        let own = colliders.get(entity).into_iter();
        let kids = children.get(entity).into_iter().flat_map(|c| c.iter());
        let mut refused = false;
        for item in own.chain(kids.filter_map(|child| colliders.get(*child).ok())) {
            match collider_defs(entity, item) {
                Ok(defs) => {
                    owners.extend(std::iter::repeat_n(item.0, defs.len()));
                    def.colliders.extend(defs);
                }
                Err(error) => {
                    refuse(&mut commands, &mut errors, item.0, error);
                    refused = true;
                }
            }
        }
        if def.colliders.is_empty() || refused {
            continue;
        }
        def.position = to_carom(pose.position);
        def.angle = pose.angle() as Real;
        def.linear_velocity = to_carom(velocity.linear);
        def.angular_velocity = velocity.angular as Real;
        def.linear_damping = damping.linear as Real;
        def.angular_damping = damping.angular as Real;
        def.gravity_scale = gravity.0 as Real;
        def.awake = !sleeping.0;
        def.fixed_rotation = locked;
        def.bullet = bullet;
        def.look_ahead = look_ahead;
        let handle = match world.world.add_body(def) {
            Ok(handle) => handle,
            Err(error) => {
                refuse(&mut commands, &mut errors, entity, error);
                continue;
            }
        };
        world.link_body(entity, handle);
        commands.entity(entity).insert((
            CaromBody(handle),
            BodyMirror {
                transform: *transform,
                velocity: *velocity,
                sleeping: sleeping.0,
                locked,
                bullet,
                look_ahead,
                targeted: false,
                previous: pose,
                current: pose,
            },
        ));
        let made = world
            .world
            .body(handle)
            .map(|b| b.colliders().to_vec())
            .unwrap_or_default();
        let mut start = 0;
        while start < owners.len() {
            let owner = owners[start];
            let end = start + owners[start..].iter().take_while(|&&o| o == owner).count();
            world.link_colliders(owner, &made[start..end]);
            commands.entity(owner).insert(CaromCollider {
                handles: made[start..end].to_vec(),
                body: entity,
            });
            start = end;
        }
    }
}

/// Makes the colliders of entities that gained a [`Collider`] on a body that already exists.
pub(crate) fn create_colliders(
    mut world: ResMut<CaromWorld>,
    new_colliders: Query<
        (NewCollider, Option<&ChildOf>),
        (Without<CaromCollider>, Without<Refused>),
    >,
    bodies: Query<&CaromBody>,
    mut commands: Commands,
    mut errors: MessageWriter<PhysicsError>,
) {
    let mut new: Vec<_> = new_colliders.iter().collect();
    new.sort_unstable_by_key(|(c, _)| c.0.index());
    for (collider, parent) in new {
        let entity = collider.0;
        let body_entity = if bodies.contains(entity) {
            entity
        } else if let Some(parent) = parent.filter(|p| bodies.contains(p.parent())) {
            parent.parent()
        } else {
            continue;
        };
        let Ok(body) = bodies.get(body_entity) else {
            continue;
        };
        make_colliders(
            &mut world,
            body.0,
            body_entity,
            collider,
            &mut commands,
            &mut errors,
        );
    }
}

/// The definitions of an entity's colliders in the body of `body_entity` (its own entity, or
/// its parent, which places them at the entity's `Transform`).
fn collider_defs(
    body_entity: Entity,
    (entity, collider, material, filter, sensor, hit_events, transform): ColliderItem,
) -> Result<Vec<carom::ColliderDef>, CaromError> {
    let (offset, angle) = if entity == body_entity {
        (Vec2::ZERO, 0.0)
    } else {
        (transform.translation.truncate(), angle_of(transform))
    };
    let parts = ColliderParts {
        material: material.copied().unwrap_or_default(),
        filter: filter.copied().unwrap_or_default(),
        sensor,
        hit_events,
    };
    collider.defs(&parts, offset, angle)
}

/// Adds an entity's collider to `body`, the body of `body_entity`; whether it could.
pub(crate) fn make_colliders(
    world: &mut CaromWorld,
    body: BodyHandle,
    body_entity: Entity,
    item: ColliderItem,
    commands: &mut Commands,
    errors: &mut MessageWriter<PhysicsError>,
) -> bool {
    let entity = item.0;
    let made = collider_defs(body_entity, item).and_then(|defs| {
        let mut handles = Vec::with_capacity(defs.len());
        for def in defs {
            match world.world.add_collider(body, def) {
                Ok(handle) => handles.push(handle),
                Err(error) => {
                    for handle in handles {
                        let _ = world.world.remove_collider(handle);
                    }
                    return Err(error);
                }
            }
        }
        Ok(handles)
    });
    match made {
        Ok(handles) => {
            world.link_colliders(entity, &handles);
            commands.entity(entity).insert(CaromCollider {
                handles,
                body: body_entity,
            });
            true
        }
        Err(error) => {
            refuse(commands, errors, entity, error);
            false
        }
    }
}

/// Makes the joints of entities that gained a [`Joint`], once both its bodies exist.
pub(crate) fn create_joints(
    mut world: ResMut<CaromWorld>,
    new_joints: Query<(Entity, &Joint), (Without<CaromJoint>, Without<Refused>)>,
    bodies: Query<&CaromBody>,
    mut commands: Commands,
    mut errors: MessageWriter<PhysicsError>,
) {
    let mut new: Vec<_> = new_joints.iter().collect();
    new.sort_unstable_by_key(|j| j.0.index());
    for (entity, joint) in new {
        let (Ok(a), Ok(b)) = (bodies.get(joint.body_a), bodies.get(joint.body_b)) else {
            continue;
        };
        match world.world.add_joint(joint.def(a.0, b.0)) {
            Ok(handle) => {
                world.link_joint(entity, handle);
                commands
                    .entity(entity)
                    .insert((CaromJoint(handle), JointMirror(*joint)));
            }
            Err(error) => refuse(&mut commands, &mut errors, entity, error),
        }
    }
}
