//! Rigid bodies: kind, placement, velocity, mass, material and accumulated forces.

use crate::error::{CaromError, check_finite, check_finite_vec};
use crate::geometry::aabb::Aabb;
use crate::geometry::shape::{Shape, WorldShape};
use crate::math::{Isometry, Mat3, Real, Rot, Vec2, cross, cross_sv};

/// How a body moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BodyKind {
    /// Never moves; infinite mass. Floors and walls.
    Static,
    /// Moves with the velocity it is given and ignores forces and contacts; infinite mass.
    /// Moving platforms, rotating drums.
    Kinematic,
    /// Moves under forces, gravity and contacts.
    Dynamic,
}

/// A stable reference to a body in a [`crate::World`].
///
/// Handles are generational: once a body is removed its handle stays dead, and a body added
/// later never answers to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BodyHandle {
    pub(crate) index: u32,
    pub(crate) generation: u32,
}

impl BodyHandle {
    /// A handle from its parts, for tools that store handles elsewhere. A world only answers
    /// to handles it issued.
    pub fn from_raw_parts(index: u32, generation: u32) -> Self {
        BodyHandle { index, generation }
    }

    /// The slot index (reused after removal, with a new generation).
    #[inline]
    pub fn index(&self) -> u32 {
        self.index
    }

    /// The generation of the slot this handle was issued for.
    #[inline]
    pub fn generation(&self) -> u32 {
        self.generation
    }
}

/// Everything needed to create a body; build one with [`BodyDef::dynamic`],
/// [`BodyDef::static_body`] or [`BodyDef::kinematic`] and the chained setters.
///
/// Values are checked when the body is added to a world.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyDef {
    /// How the body moves.
    pub kind: BodyKind,
    /// Its shape, centred on the centre of mass.
    pub shape: Shape,
    /// World position of the centre of mass.
    pub position: Vec2,
    /// Rotation in radians, counter-clockwise.
    pub angle: Real,
    /// Linear velocity in m/s.
    pub linear_velocity: Vec2,
    /// Angular velocity in rad/s, counter-clockwise.
    pub angular_velocity: Real,
    /// Mass per unit area, kg/m². Must be positive for dynamic bodies.
    pub density: Real,
    /// Coulomb friction coefficient (0 is ice).
    pub friction: Real,
    /// Bounciness: 0 does not bounce, 1 bounces back at the speed it came.
    pub restitution: Real,
    /// Multiplies the world's gravity for this body.
    pub gravity_scale: Real,
    /// Linear drag coefficient, 1/s.
    pub linear_damping: Real,
    /// Angular drag coefficient, 1/s.
    pub angular_damping: Real,
    /// Fast body that must not pass through other moving bodies either.
    pub bullet: bool,
    /// Free for the user (an id into game data, a colour...).
    pub user_tag: u64,
}

impl BodyDef {
    /// A body of the given kind with default material: density 1, friction 0.6, no restitution,
    /// no drag, at the origin at rest.
    pub fn new(kind: BodyKind, shape: Shape) -> Self {
        BodyDef {
            kind,
            shape,
            position: Vec2::zeros(),
            angle: 0.0,
            linear_velocity: Vec2::zeros(),
            angular_velocity: 0.0,
            density: 1.0,
            friction: 0.6,
            restitution: 0.0,
            gravity_scale: 1.0,
            linear_damping: 0.0,
            angular_damping: 0.0,
            bullet: false,
            user_tag: 0,
        }
    }

    /// A dynamic body.
    pub fn dynamic(shape: Shape) -> Self {
        Self::new(BodyKind::Dynamic, shape)
    }

    /// A static body.
    pub fn static_body(shape: Shape) -> Self {
        Self::new(BodyKind::Static, shape)
    }

    /// A kinematic body.
    pub fn kinematic(shape: Shape) -> Self {
        Self::new(BodyKind::Kinematic, shape)
    }

    /// Sets the position of the centre of mass.
    pub fn position(mut self, position: Vec2) -> Self {
        self.position = position;
        self
    }

    /// Sets the angle in radians.
    pub fn angle(mut self, angle: Real) -> Self {
        self.angle = angle;
        self
    }

    /// Sets the linear velocity.
    pub fn linear_velocity(mut self, velocity: Vec2) -> Self {
        self.linear_velocity = velocity;
        self
    }

    /// Sets the angular velocity.
    pub fn angular_velocity(mut self, velocity: Real) -> Self {
        self.angular_velocity = velocity;
        self
    }

    /// Sets the density.
    pub fn density(mut self, density: Real) -> Self {
        self.density = density;
        self
    }

    /// Sets the friction coefficient.
    pub fn friction(mut self, friction: Real) -> Self {
        self.friction = friction;
        self
    }

    /// Sets the restitution.
    pub fn restitution(mut self, restitution: Real) -> Self {
        self.restitution = restitution;
        self
    }

    /// Sets the gravity scale.
    pub fn gravity_scale(mut self, scale: Real) -> Self {
        self.gravity_scale = scale;
        self
    }

    /// Sets the linear and angular drag coefficients.
    pub fn damping(mut self, linear: Real, angular: Real) -> Self {
        self.linear_damping = linear;
        self.angular_damping = angular;
        self
    }

    /// Marks the body as a bullet.
    pub fn bullet(mut self, bullet: bool) -> Self {
        self.bullet = bullet;
        self
    }

    /// Sets the user tag.
    pub fn user_tag(mut self, tag: u64) -> Self {
        self.user_tag = tag;
        self
    }
}

/// Mass and inertia with their inverses, zero (inverses too) for static and kinematic bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct MassData {
    mass: Real,
    inv_mass: Real,
    inertia: Real,
    inv_inertia: Real,
}

/// A rigid body. Its origin is its centre of mass: shapes are centred on their centroid.
#[derive(Debug, Clone)]
pub struct Body {
    handle: BodyHandle,
    kind: BodyKind,
    shape: Shape,
    position: Vec2,
    rotation: Rot,
    linear_velocity: Vec2,
    angular_velocity: Real,
    force: Vec2,
    torque: Real,
    mass: MassData,
    density: Real,
    friction: Real,
    restitution: Real,
    gravity_scale: Real,
    linear_damping: Real,
    angular_damping: Real,
    bullet: bool,
    user_tag: u64,
    world_shape: WorldShape,
    aabb: Aabb,
    /// Borrowed mutably since the last step: the world must re-check its broadphase entry.
    touched: bool,
    /// Continuous collision cut this step's motion short.
    had_time_of_impact: bool,
    /// How far the body's farthest point moved in the last step, m: the solver's position
    /// correction moves bodies without leaving them a velocity, and sleep must see that.
    last_motion: Real,
    /// How long the body has moved slower than the sleep threshold, s.
    sleep_time: Real,
    /// Asleep: skipped by every stage until something wakes it.
    sleeping: bool,
    /// The island the body fell asleep with; its whole island wakes together.
    sleep_group: u32,
}

/// Checks that a coefficient is finite and not negative.
fn check_non_negative(name: &'static str, value: Real) -> Result<Real, CaromError> {
    check_finite(name, value)?;
    if value < 0.0 {
        return Err(CaromError::OutOfRange {
            name,
            expected: "zero or positive",
            value,
        });
    }
    Ok(value)
}

impl Body {
    /// Validates a definition and builds the body, with its world shape placed.
    pub(crate) fn new(handle: BodyHandle, def: BodyDef) -> Result<Self, CaromError> {
        def.shape.validate()?;
        check_finite_vec("body position", def.position)?;
        check_finite("body angle", def.angle)?;
        check_finite_vec("body linear velocity", def.linear_velocity)?;
        check_finite("body angular velocity", def.angular_velocity)?;
        check_finite("gravity scale", def.gravity_scale)?;
        let transform = Isometry::new(def.position, def.angle);
        let world_shape = WorldShape::new(&def.shape, &transform);
        let aabb = world_shape.aabb();
        let mut body = Body {
            handle,
            kind: def.kind,
            shape: def.shape,
            position: def.position,
            rotation: transform.rotation,
            linear_velocity: Vec2::zeros(),
            angular_velocity: 0.0,
            force: Vec2::zeros(),
            torque: 0.0,
            mass: MassData::default(),
            density: def.density,
            friction: check_non_negative("friction", def.friction)?,
            restitution: check_non_negative("restitution", def.restitution)?,
            gravity_scale: def.gravity_scale,
            linear_damping: check_non_negative("linear damping", def.linear_damping)?,
            angular_damping: check_non_negative("angular damping", def.angular_damping)?,
            bullet: def.bullet,
            user_tag: def.user_tag,
            world_shape,
            aabb,
            touched: false,
            had_time_of_impact: false,
            last_motion: 0.0,
            sleep_time: 0.0,
            sleeping: false,
            sleep_group: 0,
        };
        body.update_mass()?;
        if body.kind != BodyKind::Static {
            body.linear_velocity = def.linear_velocity;
            body.angular_velocity = def.angular_velocity;
        }
        Ok(body)
    }

    /// Recomputes mass and inertia from shape, density and kind.
    fn update_mass(&mut self) -> Result<(), CaromError> {
        self.mass = match self.kind {
            BodyKind::Dynamic => {
                let props = self.shape.mass_properties(self.density)?;
                MassData {
                    mass: props.mass,
                    inv_mass: props.inv_mass(),
                    inertia: props.inertia,
                    inv_inertia: props.inv_inertia(),
                }
            }
            // Static and kinematic bodies ignore density, but a bad value is still a bug.
            BodyKind::Static | BodyKind::Kinematic => {
                check_finite("density", self.density)?;
                MassData::default()
            }
        };
        Ok(())
    }

    /// This body's handle.
    #[inline]
    pub fn handle(&self) -> BodyHandle {
        self.handle
    }

    /// How the body moves.
    #[inline]
    pub fn kind(&self) -> BodyKind {
        self.kind
    }

    /// True for dynamic bodies.
    #[inline]
    pub fn is_dynamic(&self) -> bool {
        self.kind == BodyKind::Dynamic
    }

    /// The shape, in the body's local frame.
    #[inline]
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// World position of the centre of mass (the body's origin).
    #[inline]
    pub fn position(&self) -> Vec2 {
        self.position
    }

    /// The rotation.
    #[inline]
    pub fn rotation(&self) -> Rot {
        self.rotation
    }

    /// The angle in radians, in `(-π, π]`.
    #[inline]
    pub fn angle(&self) -> Real {
        self.rotation.angle()
    }

    /// The body's transform: local to world.
    #[inline]
    pub fn transform(&self) -> Isometry {
        Isometry::from_parts(self.position.into(), self.rotation)
    }

    /// The 3x3 model matrix for renderers: rotate, then translate.
    pub fn model_matrix(&self) -> Mat3 {
        self.transform().to_homogeneous()
    }

    /// Linear velocity of the centre of mass, m/s.
    #[inline]
    pub fn linear_velocity(&self) -> Vec2 {
        self.linear_velocity
    }

    /// Angular velocity, rad/s, counter-clockwise.
    #[inline]
    pub fn angular_velocity(&self) -> Real {
        self.angular_velocity
    }

    /// The velocity of the material point at `world_point`: `v + ω × r`.
    #[inline]
    pub fn velocity_at(&self, world_point: Vec2) -> Vec2 {
        self.linear_velocity + cross_sv(self.angular_velocity, world_point - self.position)
    }

    /// The force accumulated since the last step.
    #[inline]
    pub fn force(&self) -> Vec2 {
        self.force
    }

    /// The torque accumulated since the last step.
    #[inline]
    pub fn torque(&self) -> Real {
        self.torque
    }

    /// Mass in kg; 0 for static and kinematic bodies.
    #[inline]
    pub fn mass(&self) -> Real {
        self.mass.mass
    }

    /// Inverse mass; 0 for static and kinematic bodies.
    #[inline]
    pub fn inv_mass(&self) -> Real {
        self.mass.inv_mass
    }

    /// Rotational inertia about the centre of mass, kg·m²; 0 for static and kinematic bodies.
    #[inline]
    pub fn inertia(&self) -> Real {
        self.mass.inertia
    }

    /// Inverse rotational inertia; 0 for static and kinematic bodies.
    #[inline]
    pub fn inv_inertia(&self) -> Real {
        self.mass.inv_inertia
    }

    /// Density, kg/m².
    #[inline]
    pub fn density(&self) -> Real {
        self.density
    }

    /// Friction coefficient.
    #[inline]
    pub fn friction(&self) -> Real {
        self.friction
    }

    /// Restitution.
    #[inline]
    pub fn restitution(&self) -> Real {
        self.restitution
    }

    /// Gravity scale.
    #[inline]
    pub fn gravity_scale(&self) -> Real {
        self.gravity_scale
    }

    /// Linear drag coefficient.
    #[inline]
    pub fn linear_damping(&self) -> Real {
        self.linear_damping
    }

    /// Angular drag coefficient.
    #[inline]
    pub fn angular_damping(&self) -> Real {
        self.angular_damping
    }

    /// Whether the body is a bullet.
    #[inline]
    pub fn is_bullet(&self) -> bool {
        self.bullet
    }

    /// The user tag.
    #[inline]
    pub fn user_tag(&self) -> u64 {
        self.user_tag
    }

    /// The shape in world coordinates, as of the last step or placement.
    #[inline]
    pub fn world_shape(&self) -> &WorldShape {
        &self.world_shape
    }

    /// The tight world bounding box, as of the last step or placement.
    #[inline]
    pub fn aabb(&self) -> Aabb {
        self.aabb
    }

    /// True when the body sleeps: it is skipped by every stage of the step until touched by a
    /// moving body, pushed, or moved by the user. Only dynamic bodies sleep.
    #[inline]
    pub fn is_sleeping(&self) -> bool {
        self.sleeping
    }

    /// True when the step moves this body: it is not static and not asleep.
    #[inline]
    pub fn moves(&self) -> bool {
        self.kind != BodyKind::Static && !self.sleeping
    }

    /// How long the body has been slower than the sleep threshold, s.
    #[inline]
    pub fn sleep_time(&self) -> Real {
        self.sleep_time
    }

    /// Wakes the body (its island follows at the next step, through their contacts).
    pub fn wake_up(&mut self) {
        self.sleeping = false;
        self.sleep_time = 0.0;
    }

    /// Puts the body to sleep with its island: it stops until woken.
    pub(crate) fn fall_asleep(&mut self, group: u32) {
        self.sleeping = true;
        self.sleep_group = group;
        self.linear_velocity = Vec2::zeros();
        self.angular_velocity = 0.0;
    }

    /// The island the body fell asleep with.
    pub(crate) fn sleep_group(&self) -> u32 {
        self.sleep_group
    }

    /// Advances or resets the sleep timer from the body's fastest point speed, or from half
    /// the speed its last step's motion implies if that is more (Box2D's rule): a body still
    /// being pushed out of an overlap, with no velocity left after relaxing, stays awake.
    pub(crate) fn update_sleep_time(&mut self, threshold: Real, dt: Real) {
        /// How much position correction counts beside true velocity (Box2D's 0.5).
        const CORRECTION_WEIGHT: Real = 0.5;
        let reach = self.shape.max_extent();
        let speed = self.linear_velocity.norm() + reach * self.angular_velocity.abs();
        let speed = speed.max(CORRECTION_WEIGHT * self.last_motion / dt);
        if speed > threshold || self.kind != BodyKind::Dynamic {
            self.sleep_time = 0.0;
        } else {
            self.sleep_time += dt;
        }
    }

    /// Kinetic energy, linear plus rotational, in joules.
    pub fn kinetic_energy(&self) -> Real {
        0.5 * self.mass.mass * self.linear_velocity.norm_squared()
            + 0.5 * self.mass.inertia * self.angular_velocity * self.angular_velocity
    }

    /// A world point in the body's local frame.
    #[inline]
    pub fn local_point(&self, world_point: Vec2) -> Vec2 {
        self.rotation.inverse() * (world_point - self.position)
    }

    /// A local point in world coordinates.
    #[inline]
    pub fn world_point(&self, local_point: Vec2) -> Vec2 {
        self.rotation * local_point + self.position
    }

    /// True when the world point lies inside or on the body's shape.
    pub fn contains_point(&self, world_point: Vec2) -> bool {
        self.aabb
            .fattened(crate::constants::CONTAINMENT_TOLERANCE)
            .contains_point(world_point)
            && self.shape.contains_local(self.local_point(world_point))
    }

    /// Moves the body (teleports it: no velocity change).
    pub fn set_position(&mut self, position: Vec2) -> Result<(), CaromError> {
        self.position = check_finite_vec("body position", position)?;
        self.wake_up();
        self.sync_world_shape();
        Ok(())
    }

    /// Turns the body to `angle` radians.
    pub fn set_angle(&mut self, angle: Real) -> Result<(), CaromError> {
        self.rotation = Rot::new(check_finite("body angle", angle)?);
        self.wake_up();
        self.sync_world_shape();
        Ok(())
    }

    /// Sets the linear velocity (ignored by static bodies, which never move).
    pub fn set_linear_velocity(&mut self, velocity: Vec2) -> Result<(), CaromError> {
        check_finite_vec("linear velocity", velocity)?;
        if self.kind != BodyKind::Static {
            self.linear_velocity = velocity;
            self.wake_up();
        }
        Ok(())
    }

    /// Sets the angular velocity (ignored by static bodies).
    pub fn set_angular_velocity(&mut self, velocity: Real) -> Result<(), CaromError> {
        check_finite("angular velocity", velocity)?;
        if self.kind != BodyKind::Static {
            self.angular_velocity = velocity;
            self.wake_up();
        }
        Ok(())
    }

    /// Gives a kinematic body the velocities that carry it to `position` and `angle` in
    /// exactly `dt` seconds, so a scripted path (a rotating drum, a lift) is followed
    /// without drift while contacts still see a velocity to push with. Other kinds are
    /// left alone: dynamic bodies move by forces and static ones never move.
    pub fn move_kinematic_to(
        &mut self,
        position: Vec2,
        angle: Real,
        dt: Real,
    ) -> Result<(), CaromError> {
        check_finite_vec("kinematic target", position)?;
        check_finite("kinematic target angle", angle)?;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(CaromError::OutOfRange {
                name: "time step",
                expected: "positive and finite",
                value: dt,
            });
        }
        if self.kind != BodyKind::Kinematic {
            return Ok(());
        }
        // The shortest turn: the body's angle is kept as a rotation, not a winding count.
        let turn = (Rot::new(angle) * self.rotation.inverse()).angle();
        self.linear_velocity = (position - self.position) / dt;
        self.angular_velocity = turn / dt;
        self.wake_up();
        Ok(())
    }

    /// Changes how the body moves; mass is recomputed and a static body stops.
    pub fn set_kind(&mut self, kind: BodyKind) -> Result<(), CaromError> {
        let previous = self.kind;
        self.kind = kind;
        if let Err(e) = self.update_mass() {
            self.kind = previous;
            return Err(e);
        }
        if kind == BodyKind::Static {
            self.linear_velocity = Vec2::zeros();
            self.angular_velocity = 0.0;
        }
        self.clear_forces();
        self.wake_up();
        Ok(())
    }

    /// Changes the density; mass and inertia are recomputed.
    pub fn set_density(&mut self, density: Real) -> Result<(), CaromError> {
        let previous = self.density;
        self.density = density;
        if let Err(e) = self.update_mass() {
            self.density = previous;
            return Err(e);
        }
        Ok(())
    }

    /// Changes the shape; mass, inertia and the world shape are recomputed.
    pub fn set_shape(&mut self, shape: Shape) -> Result<(), CaromError> {
        shape.validate()?;
        let previous = std::mem::replace(&mut self.shape, shape);
        if let Err(e) = self.update_mass() {
            self.shape = previous;
            return Err(e);
        }
        self.wake_up();
        self.sync_world_shape();
        Ok(())
    }

    /// Sets the friction coefficient (finite, not negative).
    pub fn set_friction(&mut self, friction: Real) -> Result<(), CaromError> {
        self.friction = check_non_negative("friction", friction)?;
        Ok(())
    }

    /// Sets the restitution (finite, not negative).
    pub fn set_restitution(&mut self, restitution: Real) -> Result<(), CaromError> {
        self.restitution = check_non_negative("restitution", restitution)?;
        Ok(())
    }

    /// Sets the gravity scale (finite; negative makes the body rise).
    pub fn set_gravity_scale(&mut self, scale: Real) -> Result<(), CaromError> {
        self.gravity_scale = check_finite("gravity scale", scale)?;
        Ok(())
    }

    /// Sets the linear and angular drag coefficients (finite, not negative).
    pub fn set_damping(&mut self, linear: Real, angular: Real) -> Result<(), CaromError> {
        let linear = check_non_negative("linear damping", linear)?;
        self.angular_damping = check_non_negative("angular damping", angular)?;
        self.linear_damping = linear;
        Ok(())
    }

    /// Marks or unmarks the body as a bullet.
    pub fn set_bullet(&mut self, bullet: bool) {
        self.bullet = bullet;
    }

    /// Sets the user tag.
    pub fn set_user_tag(&mut self, tag: u64) {
        self.user_tag = tag;
    }

    /// Adds a force at a world point: it also adds the torque `r × F`, with `r` from the
    /// centre of mass. Forces last until the end of the next step. Only dynamic bodies feel it.
    pub fn apply_force(&mut self, force: Vec2, world_point: Vec2) -> Result<(), CaromError> {
        check_finite_vec("force", force)?;
        check_finite_vec("force application point", world_point)?;
        if self.is_dynamic() {
            self.force += force;
            self.torque += cross(world_point - self.position, force);
            self.wake_up();
        }
        Ok(())
    }

    /// Adds a force through the centre of mass (no torque).
    pub fn apply_force_at_center(&mut self, force: Vec2) -> Result<(), CaromError> {
        check_finite_vec("force", force)?;
        if self.is_dynamic() {
            self.force += force;
            self.wake_up();
        }
        Ok(())
    }

    /// Adds a torque, N·m, counter-clockwise.
    pub fn apply_torque(&mut self, torque: Real) -> Result<(), CaromError> {
        check_finite("torque", torque)?;
        if self.is_dynamic() {
            self.torque += torque;
            self.wake_up();
        }
        Ok(())
    }

    /// Applies an impulse at a world point: it changes the velocities at once,
    /// `Δv = J / m`, `Δω = (r × J) / I`.
    pub fn apply_impulse(&mut self, impulse: Vec2, world_point: Vec2) -> Result<(), CaromError> {
        check_finite_vec("impulse", impulse)?;
        check_finite_vec("impulse application point", world_point)?;
        self.wake_up();
        self.linear_velocity += impulse * self.mass.inv_mass;
        self.angular_velocity +=
            self.mass.inv_inertia * cross(world_point - self.position, impulse);
        Ok(())
    }

    /// Applies an impulse through the centre of mass.
    pub fn apply_impulse_at_center(&mut self, impulse: Vec2) -> Result<(), CaromError> {
        check_finite_vec("impulse", impulse)?;
        self.wake_up();
        self.linear_velocity += impulse * self.mass.inv_mass;
        Ok(())
    }

    /// Applies an angular impulse, N·m·s.
    pub fn apply_angular_impulse(&mut self, impulse: Real) -> Result<(), CaromError> {
        check_finite("angular impulse", impulse)?;
        self.wake_up();
        self.angular_velocity += self.mass.inv_inertia * impulse;
        Ok(())
    }

    /// Forgets the accumulated force and torque.
    #[inline]
    pub fn clear_forces(&mut self) {
        self.force = Vec2::zeros();
        self.torque = 0.0;
    }

    /// Puts the body back along its path to where continuous collision found the impact; it
    /// keeps its velocity.
    pub(crate) fn move_to_time_of_impact(&mut self, pose: Isometry) {
        self.position = pose.translation.vector;
        self.rotation = pose.rotation;
        self.had_time_of_impact = true;
        self.sync_world_shape();
    }

    /// True when continuous collision put the body back along its path in the last step: it
    /// ended near where it started although it moves fast, so how far it moved says nothing
    /// about how much its contacts changed.
    pub(crate) fn had_time_of_impact(&self) -> bool {
        self.had_time_of_impact
    }

    /// Marks the body as possibly edited by the user; true the first time since the last step.
    pub(crate) fn mark_touched(&mut self) -> bool {
        !std::mem::replace(&mut self.touched, true)
    }

    /// Clears the mark once the world has caught up with the edits.
    pub(crate) fn clear_touched(&mut self) {
        self.touched = false;
    }

    /// Re-places the world shape and bounding box after the body moved.
    pub(crate) fn sync_world_shape(&mut self) {
        self.world_shape.update(&self.shape, &self.transform());
        self.aabb = self.world_shape.aabb();
    }

    /// Commits a solved step: velocities, and the motion accumulated over it. Forces are
    /// cleared and the world shape re-placed.
    pub(crate) fn finish_step(&mut self, v: Vec2, w: Real, dp: Vec2, dq: Rot) {
        self.linear_velocity = v;
        self.angular_velocity = w;
        self.position += dp;
        self.rotation = dq * self.rotation;
        // Renormalise so thousands of small rotations do not drift off the unit circle.
        self.rotation.renormalize_fast();
        self.had_time_of_impact = false;
        self.last_motion = dp.norm() + dq.im.abs() * self.shape.max_extent();
        self.clear_forces();
        self.sync_world_shape();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    fn unit_box(kind: BodyKind) -> Body {
        let handle = BodyHandle {
            index: 0,
            generation: 0,
        };
        Body::new(handle, BodyDef::new(kind, Shape::rect(0.5, 0.5))).unwrap()
    }

    #[test]
    fn mass_comes_from_density_and_static_is_infinite() {
        let b = unit_box(BodyKind::Dynamic);
        assert_eq!(b.mass(), 1.0);
        assert_eq!(b.inv_mass(), 1.0);
        assert!((b.inertia() - 1.0 / 6.0).abs() < 1e-6);
        let s = unit_box(BodyKind::Static);
        assert_eq!((s.inv_mass(), s.inv_inertia()), (0.0, 0.0));
        let k = unit_box(BodyKind::Kinematic);
        assert_eq!((k.inv_mass(), k.inv_inertia()), (0.0, 0.0));
    }

    #[test]
    fn off_centre_force_adds_torque_and_impulse_spins() {
        let mut b = unit_box(BodyKind::Dynamic);
        b.apply_force(vec2(0.0, 2.0), vec2(0.5, 0.0)).unwrap();
        assert_eq!(b.force(), vec2(0.0, 2.0));
        assert_eq!(b.torque(), 1.0);
        b.apply_impulse(vec2(0.0, 1.0), vec2(0.5, 0.0)).unwrap();
        assert_eq!(b.linear_velocity(), vec2(0.0, 1.0));
        assert!((b.angular_velocity() - 0.5 * 6.0).abs() < 1e-5);
        b.clear_forces();
        assert_eq!((b.force(), b.torque()), (Vec2::zeros(), 0.0));
        // Static bodies ignore forces and impulses.
        let mut s = unit_box(BodyKind::Static);
        s.apply_force(vec2(1.0, 0.0), vec2(0.0, 1.0)).unwrap();
        s.apply_impulse(vec2(1.0, 0.0), vec2(0.0, 1.0)).unwrap();
        assert_eq!(s.force(), Vec2::zeros());
        assert_eq!(s.linear_velocity(), Vec2::zeros());
    }

    #[test]
    fn non_finite_inputs_are_rejected_and_leave_the_body_alone() {
        let mut b = unit_box(BodyKind::Dynamic);
        assert!(b.apply_force(vec2(Real::NAN, 0.0), vec2(0.0, 0.0)).is_err());
        assert!(b.set_position(vec2(0.0, Real::INFINITY)).is_err());
        assert!(b.set_density(-1.0).is_err());
        assert!(b.set_friction(-0.1).is_err());
        assert!(b.set_angle(Real::NAN).is_err());
        assert_eq!(b.position(), Vec2::zeros());
        assert_eq!(b.force(), Vec2::zeros());
        assert_eq!(b.density(), 1.0);
        assert_eq!(b.mass(), 1.0);
    }

    #[test]
    fn model_matrix_rotates_then_translates() {
        let mut b = unit_box(BodyKind::Dynamic);
        b.set_position(vec2(3.0, 1.0)).unwrap();
        b.set_angle(std::f32::consts::FRAC_PI_2).unwrap();
        let m = b.model_matrix();
        let local = nalgebra::Vector3::new(1.0, 0.0, 1.0);
        let world = m * local;
        assert!((world.x - 3.0).abs() < 1e-6 && (world.y - 2.0).abs() < 1e-6);
        assert!((b.world_point(vec2(1.0, 0.0)) - vec2(3.0, 2.0)).norm() < 1e-6);
        assert!((b.local_point(vec2(3.0, 2.0)) - vec2(1.0, 0.0)).norm() < 1e-6);
        // The cached AABB followed the move.
        assert!((b.aabb().center() - vec2(3.0, 1.0)).norm() < 1e-6);
    }

    #[test]
    fn point_velocity_includes_spin() {
        let mut b = unit_box(BodyKind::Dynamic);
        b.set_angular_velocity(2.0).unwrap();
        b.set_linear_velocity(vec2(1.0, 0.0)).unwrap();
        assert_eq!(b.velocity_at(vec2(0.0, 1.0)), vec2(-1.0, 0.0));
    }

    #[test]
    fn kinematic_target_sets_the_velocities_that_reach_it() {
        let mut k = unit_box(BodyKind::Kinematic);
        k.set_angle(3.0).unwrap();
        // From 3 rad to -3 rad is a short turn forward across ±π, not 6 rad back.
        k.move_kinematic_to(vec2(1.0, -2.0), -3.0, 0.5).unwrap();
        assert_eq!(k.linear_velocity(), vec2(2.0, -4.0));
        let short_turn = 2.0 * std::f32::consts::PI - 6.0;
        assert!((k.angular_velocity() - short_turn / 0.5).abs() < 1e-4);
        assert!(k.move_kinematic_to(vec2(0.0, 0.0), 0.0, 0.0).is_err());
        assert!(k.move_kinematic_to(vec2(Real::NAN, 0.0), 0.0, 0.1).is_err());
        let mut d = unit_box(BodyKind::Dynamic);
        d.move_kinematic_to(vec2(5.0, 5.0), 1.0, 0.1).unwrap();
        assert_eq!(d.linear_velocity(), Vec2::zeros());
    }

    #[test]
    fn a_body_moved_by_position_correction_stays_awake() {
        let mut body = unit_box(BodyKind::Dynamic);
        let dt = 1.0 / 60.0;
        // At rest and still: the timer runs.
        body.finish_step(Vec2::zeros(), 0.0, Vec2::zeros(), Rot::identity());
        body.update_sleep_time(0.05, dt);
        assert_eq!(body.sleep_time(), dt);
        // No velocity left, but pushed 1 cm this step (0.3 m/s, half counted): awake.
        body.finish_step(Vec2::zeros(), 0.0, vec2(0.0, 0.01), Rot::identity());
        body.update_sleep_time(0.05, dt);
        assert_eq!(body.sleep_time(), 0.0);
        // Turned 0.01 rad: its corners moved 7 mm. Awake too.
        body.finish_step(Vec2::zeros(), 0.0, Vec2::zeros(), Rot::new(0.01));
        body.update_sleep_time(0.05, dt);
        assert_eq!(body.sleep_time(), 0.0);
    }
}
