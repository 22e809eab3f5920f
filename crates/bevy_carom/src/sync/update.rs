//! Passing the game's changes to components on to the carom objects made from them. A change
//! is told from the plugin's own writes by comparing with what it last wrote
//! ([`BodyMirror`], [`JointMirror`]) or, for components only the game writes, by Bevy's
//! change ticks.

use crate::body::{
    BodyMirror, Bullet, CaromBody, Damping, ExternalForce, ExternalImpulse, GravityScale,
    LockedRotation, LookAhead, RigidBody, Sleeping, Velocity,
};
use crate::collider::{
    CaromCollider, Collider, ColliderMaterial, CollisionFilter, HitEvents, Sensor,
};
use crate::convert::{Pose, to_carom};
use crate::joint::{CaromJoint, Joint, JointMirror};
use crate::messages::PhysicsError;
use crate::sync::create::{NewCollider, make_colliders};
use crate::world::CaromWorld;
use bevy::ecs::change_detection::{DetectChanges, Ref};
use bevy::ecs::component::Component;
use bevy::ecs::entity::Entity;
use bevy::ecs::hierarchy::ChildOf;
use bevy::ecs::lifecycle::{Add, Remove};
use bevy::ecs::message::MessageWriter;
use bevy::ecs::observer::On;
use bevy::ecs::query::{Changed, Has, Or, With};
use bevy::ecs::system::{Commands, Query, Res, ResMut};
use bevy::time::Time;
use bevy::transform::components::Transform;
use carom::{BodyKind, CaromError, Real};

/// A change made since the plugin's last look, not the component's first appearance (which
/// the body or collider was made from).
fn edited<T>(component: &Ref<T>) -> bool {
    component.is_changed() && !component.is_added()
}

type BodyEdits<'a> = (
    Entity,
    &'a CaromBody,
    &'a mut BodyMirror,
    Ref<'a, RigidBody>,
    &'a Transform,
    &'a Velocity,
    Ref<'a, Damping>,
    Ref<'a, GravityScale>,
    &'a Sleeping,
    Has<LockedRotation>,
    Has<Bullet>,
    Has<LookAhead>,
);

/// Bodies: a new kind, a `Transform` set by the game (a teleport; a kinematic body is moved
/// there over the step instead, pushing what it meets), a new velocity, a wake-up, damping,
/// gravity scale, locked rotation, bullet and look-ahead.
pub(crate) fn update_bodies(
    mut world: ResMut<CaromWorld>,
    mut bodies: Query<BodyEdits>,
    time: Res<Time>,
    mut errors: MessageWriter<PhysicsError>,
) {
    let dt = time.delta_secs() as Real;
    for (
        entity,
        body,
        mut mirror,
        kind,
        transform,
        velocity,
        damping,
        gravity,
        sleeping,
        locked,
        bullet,
        look_ahead,
    ) in &mut bodies
    {
        // Most bodies, most steps, have nothing new: tell so without visiting the world.
        let moved = *transform != mirror.transform;
        let pushed = *velocity != mirror.velocity;
        let woken = sleeping.0 != mirror.sleeping;
        let flags =
            locked != mirror.locked || bullet != mirror.bullet || look_ahead != mirror.look_ahead;
        if !(moved
            || pushed
            || woken
            || flags
            || mirror.targeted
            || edited(&kind)
            || edited(&damping)
            || edited(&gravity))
        {
            continue;
        }
        let Some(mut b) = world.world.body_mut(body.0) else {
            continue;
        };
        let mut result: Result<(), CaromError> = Ok(());
        let mut check = |r: Result<(), CaromError>| {
            if result.is_ok() {
                result = r;
            }
        };
        if edited(&kind) {
            check(b.set_kind((*kind).into()));
        }
        let arrived = mirror.targeted;
        mirror.targeted = false;
        if moved {
            let pose = Pose::of_transform(transform);
            if b.kind() == BodyKind::Kinematic && dt > 0.0 {
                check(b.move_kinematic_to(to_carom(pose.position), pose.angle() as Real, dt));
                mirror.targeted = true;
            } else {
                check(b.set_position(to_carom(pose.position)));
                check(b.set_angle(pose.angle() as Real));
                // A teleport is not drawn as a sweep from where the body was.
                mirror.current = pose;
            }
            mirror.transform = *transform;
        } else if arrived && !pushed {
            // It reached the last pose it was sent to and was sent nowhere since.
            check(b.set_linear_velocity(carom::Vec2::zeros()));
            check(b.set_angular_velocity(0.0));
        }
        if pushed {
            check(b.set_linear_velocity(to_carom(velocity.linear)));
            check(b.set_angular_velocity(velocity.angular as Real));
            mirror.velocity = *velocity;
        }
        if woken {
            if !sleeping.0 {
                b.wake_up();
            }
            mirror.sleeping = sleeping.0;
        }
        if edited(&damping) {
            check(b.set_damping(damping.linear as Real, damping.angular as Real));
        }
        if edited(&gravity) {
            check(b.set_gravity_scale(gravity.0 as Real));
        }
        if locked != mirror.locked {
            b.set_fixed_rotation(locked);
            mirror.locked = locked;
        }
        if bullet != mirror.bullet {
            b.set_bullet(bullet);
            mirror.bullet = bullet;
        }
        if look_ahead != mirror.look_ahead {
            b.set_look_ahead(look_ahead);
            mirror.look_ahead = look_ahead;
        }
        if let Err(error) = result {
            errors.write(PhysicsError {
                entity: Some(entity),
                error,
            });
        }
    }
}

/// Marks a collider made or unmade a sensor or a hit reporter since it was made.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Remake;

/// Notes [`Sensor`] or [`HitEvents`] put on a collider.
pub(crate) fn collider_flag_added(added: On<Add, (Sensor, HitEvents)>, mut commands: Commands) {
    commands.entity(added.entity).try_insert(Remake);
}

/// Notes [`Sensor`] or [`HitEvents`] taken off a collider.
pub(crate) fn collider_flag_removed(
    removed: On<Remove, (Sensor, HitEvents)>,
    mut commands: Commands,
) {
    commands.entity(removed.entity).try_insert(Remake);
}

type ColliderEdits<'a> = (
    &'a CaromCollider,
    NewCollider<'a>,
    Ref<'a, Collider>,
    Option<Ref<'a, ColliderMaterial>>,
    Option<Ref<'a, CollisionFilter>>,
    Ref<'a, Transform>,
);

/// Colliders: a new shape, a child collider moved on its body, or a collider made or unmade
/// a sensor or a hit reporter, makes it anew; a new material or filter changes it in place.
pub(crate) fn update_colliders(
    mut world: ResMut<CaromWorld>,
    colliders: Query<
        ColliderEdits,
        Or<(
            Changed<Collider>,
            Changed<ColliderMaterial>,
            Changed<CollisionFilter>,
            (Changed<Transform>, With<ChildOf>),
            With<Remake>,
        )>,
    >,
    mut commands: Commands,
    mut errors: MessageWriter<PhysicsError>,
) {
    for (link, parts, shape, material, filter, transform) in &colliders {
        let entity = parts.0;
        commands.entity(entity).try_remove::<Remake>();
        let Some(first) = link.handles.first().and_then(|&c| world.world.collider(c)) else {
            continue;
        };
        let is_chain = shape.shape().is_none();
        let flags_differ =
            !is_chain && (first.is_sensor() != parts.4 || first.hit_events() != parts.5);
        let moved = entity != link.body && edited(&transform);
        if edited(&shape) || flags_differ || moved {
            let Some(body) = world.entity_body(link.body) else {
                continue;
            };
            // The new colliders first: a body keeps at least one.
            world.unlink_colliders(entity);
            if make_colliders(
                &mut world,
                body,
                link.body,
                parts,
                &mut commands,
                &mut errors,
            ) {
                for &c in &link.handles {
                    let _ = world.world.remove_collider(c);
                }
            } else {
                world.link_colliders(entity, &link.handles);
            }
            continue;
        }
        if let Some(material) = material.filter(edited) {
            for &c in &link.handles {
                if let Some(mut collider) = world.world.collider_mut(c) {
                    let result = collider
                        .set_density(material.density as Real)
                        .and_then(|()| collider.set_friction(material.friction as Real))
                        .and_then(|()| collider.set_restitution(material.restitution as Real))
                        .and_then(|()| {
                            collider.set_rolling_resistance(material.rolling_resistance as Real)
                        })
                        .and_then(|()| collider.set_tangent_speed(material.tangent_speed as Real));
                    if let Err(error) = result {
                        errors.write(PhysicsError {
                            entity: Some(entity),
                            error,
                        });
                        break;
                    }
                }
            }
        }
        if let Some(filter) = filter.filter(edited) {
            for &c in &link.handles {
                if let Some(mut collider) = world.world.collider_mut(c) {
                    collider.set_filter((*filter).into());
                }
            }
        }
    }
}

/// Joints: a new kind or parameters retunes the joint; new bodies, anchors or settings make
/// it anew.
pub(crate) fn update_joints(
    mut world: ResMut<CaromWorld>,
    mut joints: Query<(Entity, &CaromJoint, &Joint, &mut JointMirror), Changed<Joint>>,
    bodies: Query<&CaromBody>,
    mut commands: Commands,
    mut errors: MessageWriter<PhysicsError>,
) {
    for (entity, link, joint, mut mirror) in &mut joints {
        if *joint == mirror.0 {
            continue;
        }
        let retune = Joint {
            kind: mirror.0.kind,
            ..*joint
        } == mirror.0;
        let result = if retune {
            match world.world.joint_mut(link.0) {
                Some(mut j) => j.set_kind(joint.kind),
                None => Ok(()),
            }
        } else {
            let _ = world.world.remove_joint(link.0);
            world.unlink_joint(entity);
            match (bodies.get(joint.body_a), bodies.get(joint.body_b)) {
                (Ok(a), Ok(b)) => world.world.add_joint(joint.def(a.0, b.0)).map(|handle| {
                    world.link_joint(entity, handle);
                    commands.entity(entity).insert(CaromJoint(handle));
                }),
                // A body not yet made: made with the joint once it is.
                _ => {
                    commands.entity(entity).remove::<CaromJoint>();
                    Ok(())
                }
            }
        };
        mirror.0 = *joint;
        if let Err(error) = result {
            errors.write(PhysicsError {
                entity: Some(entity),
                error,
            });
        }
    }
}

/// Applies each body's [`ExternalForce`] for this step, and its [`ExternalImpulse`] once.
pub(crate) fn apply_forces(
    mut world: ResMut<CaromWorld>,
    mut bodies: Query<
        (
            Entity,
            &CaromBody,
            Option<&ExternalForce>,
            Option<&mut ExternalImpulse>,
        ),
        Or<(With<ExternalForce>, With<ExternalImpulse>)>,
    >,
    mut errors: MessageWriter<PhysicsError>,
) {
    for (entity, body, force, impulse) in &mut bodies {
        let force = force.copied().unwrap_or_default();
        let pending = impulse.as_deref().copied().unwrap_or_default();
        if force == ExternalForce::default() && pending == ExternalImpulse::default() {
            continue;
        }
        let Some(mut b) = world.world.body_mut(body.0) else {
            continue;
        };
        let mut result = Ok(());
        if force.force != bevy::math::Vec2::ZERO {
            result = result.and_then(|()| b.apply_force_at_center(to_carom(force.force)));
        }
        if force.torque != 0.0 {
            result = result.and_then(|()| b.apply_torque(force.torque as Real));
        }
        if pending.impulse != bevy::math::Vec2::ZERO {
            result = result.and_then(|()| b.apply_impulse_at_center(to_carom(pending.impulse)));
        }
        if pending.angular != 0.0 {
            result = result.and_then(|()| b.apply_angular_impulse(pending.angular as Real));
        }
        if let Some(mut impulse) = impulse.filter(|i| **i != ExternalImpulse::default()) {
            *impulse = ExternalImpulse::default();
        }
        if let Err(error) = result {
            errors.write(PhysicsError {
                entity: Some(entity),
                error,
            });
        }
    }
}
