//! [`CaromWorld`], the resource that holds the carom world and which entity each of its
//! bodies, colliders and joints is.

use bevy::ecs::entity::Entity;
use bevy::ecs::resource::Resource;
use bevy::math::Vec2;
use carom::{
    BodyHandle, Capacity, CaromError, ColliderHandle, ExplosionDef, JointHandle, World,
    WorldSettings,
};
use std::collections::HashMap;

/// The physics world: carom's [`World`] with its settings (gravity, solver, sub-steps,
/// sleeping, events), and the map between its handles and the entities they came from.
///
/// Insert one before adding [`crate::CaromPlugin`] to start from other settings, or change
/// them at any time with [`CaromWorld::update_settings`].
#[derive(Resource, Debug, Default)]
pub struct CaromWorld {
    pub(crate) world: World,
    pub(crate) links: Links,
}

/// Which entity each carom object is, both ways.
#[derive(Debug, Default)]
pub(crate) struct Links {
    pub bodies: HashMap<BodyHandle, Entity>,
    pub colliders: HashMap<ColliderHandle, Entity>,
    pub joints: HashMap<JointHandle, Entity>,
    pub entity_bodies: HashMap<Entity, BodyHandle>,
    pub entity_colliders: HashMap<Entity, Vec<ColliderHandle>>,
    pub entity_joints: HashMap<Entity, JointHandle>,
    /// Entities whose body, collider or joint component went away (despawned or removed),
    /// for the next step to remove from the world: observed as it happens, so that none is
    /// missed in frames with no fixed step.
    pub removed: Removed,
}

#[derive(Debug, Default)]
pub(crate) struct Removed {
    pub bodies: Vec<Entity>,
    pub colliders: Vec<Entity>,
    pub joints: Vec<Entity>,
}

impl CaromWorld {
    /// An empty world with `settings`.
    ///
    /// # Errors
    /// Settings out of range (a negative sub-step count, gravity that is not finite, ...).
    pub fn new(settings: WorldSettings) -> Result<Self, CaromError> {
        Ok(CaromWorld {
            world: World::with_settings(settings)?,
            links: Links::default(),
        })
    }

    /// The carom world, to read: bodies, contacts, joints, statistics, and its queries
    /// beyond [`crate::CaromQuery`]'s.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The world's settings.
    pub fn settings(&self) -> &WorldSettings {
        self.world.settings()
    }

    /// Changes the world's settings; they take effect from the next step.
    ///
    /// # Errors
    /// Settings out of range: the world keeps the ones it had.
    pub fn update_settings(
        &mut self,
        change: impl FnOnce(&mut WorldSettings),
    ) -> Result<(), CaromError> {
        self.world.update_settings(change)
    }

    /// Gravity, m/s².
    pub fn gravity(&self) -> Vec2 {
        crate::convert::to_bevy(self.world.gravity())
    }

    /// The entity a body is.
    pub fn body_entity(&self, body: BodyHandle) -> Option<Entity> {
        self.links.bodies.get(&body).copied()
    }

    /// The entity a collider came from.
    pub fn collider_entity(&self, collider: ColliderHandle) -> Option<Entity> {
        self.links.colliders.get(&collider).copied()
    }

    /// The entity a joint came from.
    pub fn joint_entity(&self, joint: JointHandle) -> Option<Entity> {
        self.links.joints.get(&joint).copied()
    }

    /// The body an entity is.
    pub fn entity_body(&self, entity: Entity) -> Option<BodyHandle> {
        self.links.entity_bodies.get(&entity).copied()
    }

    /// Pushes bodies away from a point (an explosion), waking them; how many it pushed.
    ///
    /// # Errors
    /// A definition out of range.
    pub fn explode(&mut self, explosion: &ExplosionDef) -> Result<usize, CaromError> {
        self.world.explode(explosion)
    }

    /// Makes room ahead of time for `capacity` in the world ([`World::reserve`]) and in the
    /// plugin's maps between handles and entities, so that a world no larger than that steps
    /// without asking for memory after its first step. [`World::high_water`] (through
    /// [`CaromWorld::world`]) tells what a run like the ones made so far needs.
    ///
    /// # Errors
    /// [`CaromError::OutOfMemory`] when the heap cannot give the room.
    pub fn reserve(&mut self, capacity: Capacity) -> Result<(), CaromError> {
        self.world.reserve(capacity)?;
        let Links {
            bodies,
            colliders,
            joints,
            entity_bodies,
            entity_colliders,
            entity_joints,
            removed: _,
        } = &mut self.links;
        let room = |map_len: usize, wanted: usize| wanted.saturating_sub(map_len);
        let out_of_memory = |_| CaromError::OutOfMemory {
            what: "the plugin's maps of entities",
        };
        bodies
            .try_reserve(room(bodies.len(), capacity.bodies))
            .map_err(out_of_memory)?;
        entity_bodies
            .try_reserve(room(entity_bodies.len(), capacity.bodies))
            .map_err(out_of_memory)?;
        colliders
            .try_reserve(room(colliders.len(), capacity.colliders))
            .map_err(out_of_memory)?;
        entity_colliders
            .try_reserve(room(entity_colliders.len(), capacity.colliders))
            .map_err(out_of_memory)?;
        joints
            .try_reserve(room(joints.len(), capacity.joints))
            .map_err(out_of_memory)?;
        entity_joints
            .try_reserve(room(entity_joints.len(), capacity.joints))
            .map_err(out_of_memory)
    }

    /// Wakes every body.
    pub fn wake_all(&mut self) {
        self.world.wake_all();
    }

    /// A hash of the world's whole state: equal for equal worlds on every platform, so that
    /// two runs can be compared by it.
    pub fn state_hash(&self) -> u64 {
        self.world.state_hash()
    }

    /// Steps taken.
    pub fn step_count(&self) -> u64 {
        self.world.step_count()
    }

    pub(crate) fn link_body(&mut self, entity: Entity, body: BodyHandle) {
        self.links.bodies.insert(body, entity);
        self.links.entity_bodies.insert(entity, body);
    }

    pub(crate) fn link_colliders(&mut self, entity: Entity, colliders: &[ColliderHandle]) {
        for &c in colliders {
            self.links.colliders.insert(c, entity);
        }
        self.links
            .entity_colliders
            .insert(entity, colliders.to_vec());
    }

    pub(crate) fn link_joint(&mut self, entity: Entity, joint: JointHandle) {
        self.links.joints.insert(joint, entity);
        self.links.entity_joints.insert(entity, joint);
    }

    /// Forgets an entity's body, and the colliders that went with it.
    pub(crate) fn unlink_body(&mut self, entity: Entity) -> Option<BodyHandle> {
        let body = self.links.entity_bodies.remove(&entity)?;
        self.links.bodies.remove(&body);
        Some(body)
    }

    pub(crate) fn unlink_colliders(&mut self, entity: Entity) -> Vec<ColliderHandle> {
        let colliders = self
            .links
            .entity_colliders
            .remove(&entity)
            .unwrap_or_default();
        for c in &colliders {
            self.links.colliders.remove(c);
        }
        colliders
    }

    pub(crate) fn unlink_joint(&mut self, entity: Entity) -> Option<JointHandle> {
        let joint = self.links.entity_joints.remove(&entity)?;
        self.links.joints.remove(&joint);
        Some(joint)
    }
}
