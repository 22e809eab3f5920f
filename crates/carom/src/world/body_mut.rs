//! A body lent out to be changed, so that moving it takes its colliders along.

use crate::dynamics::body::{Body, BodyKind};
use crate::dynamics::collider::place_colliders;
use crate::error::CaromError;
use crate::math::{Real, Vec2};
use crate::world::{World, margin_for};
use std::ops::Deref;

/// A body borrowed from its world to be changed ([`crate::World::body_mut`]). It reads as a
/// [`Body`] and has the body's setters; moving or turning it takes its colliders and their
/// broadphase boxes along at once, so queries and the next step see it where it now is. A
/// change that wakes the body (a push, a move) wakes its whole island at once.
#[derive(Debug)]
pub struct BodyMut<'w> {
    world: &'w mut World,
    /// The body's dense index, kept current as waking moves it.
    index: usize,
}

impl<'w> BodyMut<'w> {
    pub(crate) fn new(world: &'w mut World, index: usize) -> Self {
        BodyMut { world, index }
    }

    /// Applies a change to the body; if the change woke it (a push, a move), its island wakes
    /// with it at once. Where the last step said its colliders were going no longer holds, so
    /// the broadphase stops judging their new pairs by it.
    #[allow(
        clippy::expect_used,
        reason = "the body is lent live, and waking it moves it but keeps it"
    )]
    fn edit<T>(&mut self, change: impl FnOnce(&mut Body) -> T) -> T {
        let body = &mut self.world.state.bodies.as_mut_slice()[self.index];
        let result = change(body);
        for &collider in body.colliders() {
            self.world.state.broadphase.forget_motion(collider);
        }
        if !body.is_sleeping() {
            let handle = body.handle();
            self.world.wake_body(self.index);
            // Waking moved the island's bodies into the awake set.
            self.index = self.world.state.bodies.dense_index(handle).expect("live");
        }
        result
    }

    /// Places the colliders and their broadphase boxes where the body now is.
    fn follow(&mut self) {
        let world = &mut *self.world;
        let body = &mut world.state.bodies.as_mut_slice()[self.index];
        place_colliders(body, &mut world.state.colliders);
        let kind = body.kind();
        let margin = margin_for(&world.state.settings, kind);
        for &collider in body.colliders() {
            if let Some(placed) = world.state.colliders.get(collider) {
                world
                    .state
                    .broadphase
                    .update(collider, kind, placed.aabb(), margin);
            }
        }
    }

    /// Wakes the body and its island.
    pub fn wake_up(&mut self) {
        self.edit(|body| body.wake_up())
    }

    /// Moves the body's origin (teleports it: no velocity change).
    pub fn set_position(&mut self, position: Vec2) -> Result<(), CaromError> {
        let result = self.edit(|body| body.set_position(position));
        self.follow();
        result
    }

    /// Turns the body about its origin to `angle` radians.
    pub fn set_angle(&mut self, angle: Real) -> Result<(), CaromError> {
        let result = self.edit(|body| body.set_angle(angle));
        self.follow();
        result
    }

    /// Sets the linear velocity, within [`crate::MAX_SPEED`] on each axis (ignored by static
    /// bodies, which never move).
    pub fn set_linear_velocity(&mut self, velocity: Vec2) -> Result<(), CaromError> {
        self.edit(|body| body.set_linear_velocity(velocity))
    }

    /// Sets the angular velocity, within [`crate::MAX_ANGULAR_SPEED`] (ignored by static
    /// bodies).
    pub fn set_angular_velocity(&mut self, velocity: Real) -> Result<(), CaromError> {
        self.edit(|body| body.set_angular_velocity(velocity))
    }

    /// Gives a kinematic body the velocities that carry it to `position` and `angle` in
    /// exactly `dt` seconds, so a scripted path (a rotating drum, a lift) is followed
    /// without drift while contacts still see a velocity to push with. Other kinds are
    /// left alone: dynamic bodies move by forces and static ones never move. A move whose
    /// velocities would exceed [`crate::MAX_SPEED`] or [`crate::MAX_ANGULAR_SPEED`] is
    /// refused.
    pub fn move_kinematic_to(
        &mut self,
        position: Vec2,
        angle: Real,
        dt: Real,
    ) -> Result<(), CaromError> {
        self.edit(|body| body.move_kinematic_to(position, angle, dt))
    }

    /// Sets the gravity scale, within [`crate::MAX_GRAVITY_SCALE`] either way (negative
    /// makes the body rise).
    pub fn set_gravity_scale(&mut self, scale: Real) -> Result<(), CaromError> {
        self.edit(|body| body.set_gravity_scale(scale))
    }

    /// Sets the linear and angular drag coefficients (finite, not negative).
    pub fn set_damping(&mut self, linear: Real, angular: Real) -> Result<(), CaromError> {
        self.edit(|body| body.set_damping(linear, angular))
    }

    /// Sets the fraction of its smallest extent it must move in a step to be swept by
    /// continuous collision (see [`crate::BodyDef::sweep_threshold`]).
    ///
    /// # Errors
    /// A negative or NaN fraction; it is then left as it was.
    pub fn set_sweep_threshold(&mut self, fraction: Real) -> Result<(), CaromError> {
        self.edit(|body| body.set_sweep_threshold(fraction))
    }

    /// Locks or frees the body's rotation (see [`crate::BodyDef::fixed_rotation`]); locking
    /// stops its spin.
    #[allow(
        clippy::expect_used,
        reason = "a live dynamic body's mass was built from these colliders before"
    )]
    pub fn set_fixed_rotation(&mut self, fixed: bool) {
        let handle = self.handle();
        self.edit(|body| body.set_fixed_rotation(fixed));
        self.world
            .rebuild_mass_of(handle)
            .expect("the same colliders give the same mass");
    }

    /// Marks or unmarks the body as a bullet.
    pub fn set_bullet(&mut self, bullet: bool) {
        self.edit(|body| body.set_bullet(bullet))
    }

    /// Makes its contacts look a step ahead even in a world that does not, or not (see
    /// [`crate::BodyDef::look_ahead`]).
    pub fn set_look_ahead(&mut self, look_ahead: bool) {
        self.edit(|body| body.set_look_ahead(look_ahead))
    }

    /// Sets the user tag.
    pub fn set_user_tag(&mut self, tag: u64) {
        self.edit(|body| body.set_user_tag(tag))
    }

    /// Adds a force at a world point: it also adds the torque `r × F`, with `r` from the
    /// centre of mass. Forces last until the end of the next step. Only dynamic bodies feel it.
    pub fn apply_force(&mut self, force: Vec2, world_point: Vec2) -> Result<(), CaromError> {
        self.edit(|body| body.apply_force(force, world_point))
    }

    /// Adds a force through the centre of mass (no torque).
    pub fn apply_force_at_center(&mut self, force: Vec2) -> Result<(), CaromError> {
        self.edit(|body| body.apply_force_at_center(force))
    }

    /// Adds a torque, N·m, counter-clockwise.
    pub fn apply_torque(&mut self, torque: Real) -> Result<(), CaromError> {
        self.edit(|body| body.apply_torque(torque))
    }

    /// Applies an impulse at a world point: it changes the velocities at once,
    /// `Δv = J / m`, `Δω = (r × J) / I`.
    ///
    /// # Errors
    /// [`CaromError::OutOfRange`] for an impulse that would take the body past
    /// [`crate::MAX_SPEED`] or [`crate::MAX_ANGULAR_SPEED`]; the body is then left as it was.
    pub fn apply_impulse(&mut self, impulse: Vec2, world_point: Vec2) -> Result<(), CaromError> {
        self.edit(|body| body.apply_impulse(impulse, world_point))
    }

    /// Applies an impulse through the centre of mass.
    ///
    /// # Errors
    /// [`CaromError::OutOfRange`] for an impulse that would take the body past
    /// [`crate::MAX_SPEED`] or [`crate::MAX_ANGULAR_SPEED`]; the body is then left as it was.
    pub fn apply_impulse_at_center(&mut self, impulse: Vec2) -> Result<(), CaromError> {
        self.edit(|body| body.apply_impulse_at_center(impulse))
    }

    /// Applies an angular impulse, N·m·s.
    ///
    /// # Errors
    /// [`CaromError::OutOfRange`] for an impulse that would take the body past
    /// [`crate::MAX_SPEED`] or [`crate::MAX_ANGULAR_SPEED`]; the body is then left as it was.
    pub fn apply_angular_impulse(&mut self, impulse: Real) -> Result<(), CaromError> {
        self.edit(|body| body.apply_angular_impulse(impulse))
    }

    /// Changes how the body moves: its mass is rebuilt, a static body stops, and its
    /// colliders move to the broadphase tree of the new kind. Its island wakes.
    ///
    /// # Errors
    /// A dynamic body without mass (no collider with a positive density); the kind is then
    /// left as it was.
    #[allow(
        clippy::expect_used,
        reason = "the body is lent live, and changing its kind moves it but keeps it"
    )]
    pub fn set_kind(&mut self, kind: BodyKind) -> Result<(), CaromError> {
        let handle = self.handle();
        self.world.set_body_kind(handle, kind)?;
        // The body moved to its new kind's set.
        self.index = self.world.state.bodies.dense_index(handle).expect("live");
        Ok(())
    }

    /// Forgets the accumulated force and torque.
    pub fn clear_forces(&mut self) {
        self.edit(|body| body.clear_forces())
    }
}

impl Deref for BodyMut<'_> {
    type Target = Body;

    fn deref(&self) -> &Body {
        &self.world.state.bodies.as_slice()[self.index]
    }
}
