//! Rigid bodies: kind, placement, velocity, mass and accumulated forces. What a body is made
//! of, its shapes and their material, are its colliders ([`crate::dynamics::collider`]).
//!
//! A body's frame has its origin where the user put it; its centre of mass sits at
//! `local_center` in that frame, summed over its colliders. A body of one shape at the origin
//! (the common case) has its centre of mass at its origin, as shapes are centred on their
//! centroid. The solver moves centres of mass; the origin follows.

use crate::constants::{
    MAX_BODY_INERTIA, MAX_BODY_MASS, MIN_BODY_INERTIA, MIN_BODY_MASS, TIME_STEP_RANGE,
};
use crate::dynamics::body_def::BodyDef;
use crate::dynamics::collider::{Collider, ColliderHandle, check_non_negative};
use crate::error::{CaromError, check_finite, check_within};
use crate::geometry::aabb::Aabb;
use crate::geometry::mass::MassProperties;
use crate::handle_map::generational_handle;
use crate::heap_bytes::{HeapBytes, array};
use crate::math::{Isometry, Mat3, Real, Rot, Vec2, angle_of, cross_sv, rotation};

/// How a body moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum BodyKind {
    /// Never moves; infinite mass. Floors and walls.
    Static,
    /// Moves with the velocity it is given and ignores forces and contacts; infinite mass.
    /// Moving platforms, rotating drums.
    Kinematic,
    /// Moves under forces, gravity and contacts.
    Dynamic,
}

generational_handle!(
    /// A stable reference to a body in a [`crate::World`].
    ///
    /// Handles are generational: once a body is removed its handle stays dead, and a body added
    /// later never answers to it.
    BodyHandle,
    "body"
);

/// Mass and inertia with their inverses, zero (inverses too) for static and kinematic bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct MassData {
    mass: Real,
    inv_mass: Real,
    inertia: Real,
    inv_inertia: Real,
}

/// A rigid body: where it is, how it moves, its mass; its shapes are its colliders.
// Laid out as written, what the narrowphase reads of each of a contact's bodies first (its
// kind, whether it sleeps, where it is and how fast it goes), so that those reads share one or
// two cache lines instead of spanning the record; its flags side by side, so that the order
// costs no padding.
#[derive(Debug)]
#[repr(C)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Body {
    handle: BodyHandle,
    kind: BodyKind,
    /// Asleep: skipped by every stage until something wakes it.
    sleeping: bool,
    /// Continuous collision cut this step's motion short.
    had_time_of_impact: bool,
    /// Its contacts look a step ahead whatever the world does ([`crate::BodyDef::look_ahead`]).
    #[cfg_attr(feature = "serde", serde(default))]
    look_ahead: bool,
    bullet: bool,
    /// Never turns: no inverse inertia, no spin ([`crate::BodyDef::fixed_rotation`]).
    #[cfg_attr(feature = "serde", serde(default))]
    fixed_rotation: bool,
    /// The origin of the body's frame, in the world.
    position: Vec2,
    rotation: Rot,
    /// The centre of mass in the world: `position + rotation * local_center`.
    center: Vec2,
    /// The farthest any collider point lies from the centre of mass, m.
    reach: Real,
    /// The smallest collider's smallest extent, m: below it a body could pass through a thin
    /// wall in one step.
    min_extent: Real,
    linear_velocity: Vec2,
    angular_velocity: Real,
    colliders: Vec<ColliderHandle>,
    /// The centre of mass in the body's frame (zero for static and kinematic bodies).
    local_center: Vec2,
    force: Vec2,
    torque: Real,
    mass: MassData,
    gravity_scale: Real,
    linear_damping: Real,
    angular_damping: Real,
    user_tag: u64,
    /// The union of the colliders' boxes, as of the last step or edit.
    aabb: Aabb,
    /// Where the centre of mass was at the start of the last solved step, and how the body
    /// was turned (for continuous collision), as Box2D keeps `center0` in its bodies.
    #[cfg_attr(feature = "serde", serde(skip))]
    start: Pose,
    /// How far the body's farthest point moved in the last step, m: the solver's position
    /// correction moves bodies without leaving them a velocity, and sleep must see that.
    last_motion: Real,
    /// How long the body has moved slower than its sleep threshold, s.
    sleep_time: Real,
    /// The speed below which the body counts as resting, m/s.
    #[cfg_attr(
        feature = "serde",
        serde(default = "crate::dynamics::body_def::sleep_threshold")
    )]
    sleep_threshold: Real,
    /// The fraction of its smallest extent it must move in a step to be swept.
    #[cfg_attr(
        feature = "serde",
        serde(default = "crate::dynamics::body_def::sweep_threshold")
    )]
    sweep_threshold: Real,
    /// A dynamic body's island (see [`crate::dynamics::island`]), and its neighbours in the
    /// island's list.
    island: Option<u32>,
    island_prev: Option<BodyHandle>,
    island_next: Option<BodyHandle>,
}

/// The bytes at the head of a [`Body`] that the narrowphase reads of it: the fields before its
/// list of colliders.
pub(crate) const HEAD_BYTES: usize = std::mem::offset_of!(Body, colliders);

// In the default build the head is no more than a cache line's worth of bytes.
#[cfg(not(feature = "f64"))]
const _: () = assert!(HEAD_BYTES <= 64, "a body's head outgrew a cache line");

/// Where a body's centre of mass was at the start of the step, and how it was turned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pose {
    pub center: Vec2,
    pub rotation: Rot,
}

impl Default for Pose {
    fn default() -> Self {
        Pose {
            center: Vec2::zeros(),
            rotation: Rot::identity(),
        }
    }
}

// A body's one array is its list of colliders; the rest is plain values, copied whole (a
// field that is not `Copy` fails to compile here). Restoring a snapshot clones every body into
// the old one, and the list keeps its buffer.
impl Clone for Body {
    fn clone(&self) -> Self {
        Body {
            colliders: self.colliders.clone(),
            ..*self
        }
    }

    fn clone_from(&mut self, source: &Self) {
        let colliders = std::mem::take(&mut self.colliders);
        *self = Body {
            colliders,
            ..*source
        };
        self.colliders.clone_from(&source.colliders);
    }
}

// Its list of colliders; the rest is plain values (see `Clone`).
impl HeapBytes for Body {
    fn heap_bytes(&self) -> usize {
        let Body {
            handle: _,
            kind: _,
            colliders,
            position: _,
            rotation: _,
            center: _,
            local_center: _,
            reach: _,
            min_extent: _,
            linear_velocity: _,
            angular_velocity: _,
            force: _,
            torque: _,
            mass: _,
            gravity_scale: _,
            linear_damping: _,
            angular_damping: _,
            bullet: _,
            user_tag: _,
            aabb: _,
            had_time_of_impact: _,
            start: _,
            last_motion: _,
            sleep_time: _,
            sleep_threshold: _,
            sweep_threshold: _,
            look_ahead: _,
            fixed_rotation: _,
            sleeping: _,
            island: _,
            island_prev: _,
            island_next: _,
        } = self;
        array(colliders)
    }
}

impl Body {
    /// Checks the body's own values in a definition (and each collider's) and builds the
    /// body, still without its colliders or mass: the world attaches the colliders, then calls
    /// [`Body::rebuild_mass`].
    pub(crate) fn new(handle: BodyHandle, def: &BodyDef) -> Result<Self, CaromError> {
        if def.colliders.is_empty() {
            return Err(CaromError::NoCollider);
        }
        for collider in &def.colliders {
            collider.validate()?;
        }
        check_position("body position", def.position)?;
        check_finite("body angle", def.angle)?;
        check_velocity("body linear velocity", def.linear_velocity)?;
        check_spin("body angular velocity", def.angular_velocity)?;
        check_gravity_scale(def.gravity_scale)?;
        let moves = def.kind != BodyKind::Static;
        Ok(Body {
            handle,
            kind: def.kind,
            colliders: Vec::with_capacity(def.colliders.len()),
            position: def.position,
            rotation: rotation(def.angle),
            center: def.position,
            local_center: Vec2::zeros(),
            reach: 0.0,
            min_extent: Real::INFINITY,
            linear_velocity: if moves {
                def.linear_velocity
            } else {
                Vec2::zeros()
            },
            angular_velocity: if moves { def.angular_velocity } else { 0.0 },
            force: Vec2::zeros(),
            torque: 0.0,
            mass: MassData::default(),
            gravity_scale: def.gravity_scale,
            linear_damping: check_non_negative("linear damping", def.linear_damping)?,
            angular_damping: check_non_negative("angular damping", def.angular_damping)?,
            bullet: def.bullet,
            user_tag: def.user_tag,
            aabb: Aabb::new(def.position, def.position),
            had_time_of_impact: false,
            start: Pose::default(),
            last_motion: 0.0,
            sleep_time: 0.0,
            sleep_threshold: check_non_negative("sleep threshold", def.sleep_threshold)?,
            sweep_threshold: check_sweep_threshold(def.sweep_threshold)?,
            look_ahead: def.look_ahead,
            fixed_rotation: def.fixed_rotation,
            sleeping: false,
            island: None,
            island_prev: None,
            island_next: None,
        })
    }

    /// Recomputes mass, inertia and centre of mass from the colliders (the body's own, in its
    /// order) and the kind: summed over the colliders with the parallel-axis theorem for a
    /// dynamic body, none for static and kinematic ones. Also how far the colliders reach.
    ///
    /// # Errors
    /// A dynamic body whose colliders have no mass; the body is left as it was.
    pub(crate) fn rebuild_mass<'c>(
        &mut self,
        colliders: impl Iterator<Item = &'c Collider> + Clone,
    ) -> Result<(), CaromError> {
        let mut mass: Real = 0.0;
        let mut weighted = Vec2::zeros();
        let mut parts = Vec::new();
        for collider in colliders.clone() {
            let props = collider.mass_properties()?;
            mass += props.mass;
            weighted += props.center * props.mass;
            parts.push(props);
        }
        let center = if mass > 0.0 {
            weighted / mass
        } else {
            Vec2::zeros()
        };
        let inertia = parts.iter().map(|p| p.inertia_about(center)).sum();
        let total = MassProperties {
            mass,
            center,
            inertia,
        };
        let (data, local_center) = match self.kind {
            BodyKind::Dynamic => {
                if mass <= 0.0 {
                    return Err(CaromError::OutOfRange {
                        name: "density",
                        expected: "positive for some collider of a dynamic body",
                        value: 0.0,
                    });
                }
                // A mass or inertia so small that its inverse, times what the solver
                // multiplies it by, overflows (a tiny density, or a sliver). Checked whether
                // the rotation is fixed or not, so that freeing it cannot fail later.
                if mass < MIN_BODY_MASS {
                    return Err(CaromError::OutOfRange {
                        name: "density",
                        expected: "enough for a dynamic body's mass (the value given) to be at \
                                   least 1e-20 kg",
                        value: mass,
                    });
                }
                if inertia > 0.0 && inertia < MIN_BODY_INERTIA {
                    return Err(CaromError::OutOfRange {
                        name: "density",
                        expected: "enough for a dynamic body's rotational inertia (the value \
                                   given) to be at least 1e-28 kg·m²",
                        value: inertia,
                    });
                }
                // A mass or inertia so large that it, times what the solver multiplies it
                // by, overflows (a huge density), or is past f32 already.
                if mass > MAX_BODY_MASS {
                    return Err(CaromError::OutOfRange {
                        name: "density",
                        expected: "small enough for a dynamic body's mass (the value given) to \
                                   be at most 1e30 kg",
                        value: mass,
                    });
                }
                if inertia > MAX_BODY_INERTIA {
                    return Err(CaromError::OutOfRange {
                        name: "density",
                        expected: "small enough for a dynamic body's rotational inertia (the \
                                   value given) to be at most 1e36 kg·m²",
                        value: inertia,
                    });
                }
                let data = MassData {
                    mass,
                    inv_mass: total.inv_mass(),
                    inertia,
                    inv_inertia: if self.fixed_rotation {
                        0.0
                    } else {
                        total.inv_inertia()
                    },
                };
                if self.fixed_rotation {
                    self.angular_velocity = 0.0;
                }
                (data, center)
            }
            // Static and kinematic bodies have no mass; they turn about their origin.
            BodyKind::Static | BodyKind::Kinematic => (MassData::default(), Vec2::zeros()),
        };
        self.mass = data;
        self.local_center = local_center;
        // The centre of mass may have moved in the body: its velocity is now that of the
        // material point there, so every point keeps its velocity (as Box2D does).
        let old_center = self.center;
        self.center = self.position + self.rotation * local_center;
        self.linear_velocity += cross_sv(self.angular_velocity, self.center - old_center);
        self.reach = colliders
            .clone()
            .map(|c| c.reach_from(local_center))
            .fold(0.0, Real::max);
        self.min_extent = colliders
            .map(|c| c.shape().min_extent())
            .fold(Real::INFINITY, Real::min);
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

    /// Its colliders, in the order they were added.
    #[inline]
    pub fn colliders(&self) -> &[ColliderHandle] {
        &self.colliders
    }

    /// World position of the body's origin (its centre of mass too, for a body of one shape
    /// at its origin).
    #[inline]
    pub fn position(&self) -> Vec2 {
        self.position
    }

    /// World position of the centre of mass.
    #[inline]
    pub fn center_of_mass(&self) -> Vec2 {
        self.center
    }

    /// The centre of mass in the body's frame (zero for static and kinematic bodies).
    #[inline]
    pub fn local_center(&self) -> Vec2 {
        self.local_center
    }

    /// The rotation.
    #[inline]
    pub fn rotation(&self) -> Rot {
        self.rotation
    }

    /// The angle in radians, in `(-π, π]`.
    #[inline]
    pub fn angle(&self) -> Real {
        angle_of(&self.rotation)
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
        self.linear_velocity + cross_sv(self.angular_velocity, world_point - self.center)
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

    /// Whether its contacts look a step ahead whatever the world does
    /// ([`crate::BodyDef::look_ahead`]).
    #[inline]
    pub fn looks_ahead(&self) -> bool {
        self.look_ahead
    }

    /// The user tag.
    #[inline]
    pub fn user_tag(&self) -> u64 {
        self.user_tag
    }

    /// The tight world bounding box of all its colliders, as of the last step or edit.
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

    /// How long the body has been slower than its sleep threshold, s.
    #[inline]
    pub fn sleep_time(&self) -> Real {
        self.sleep_time
    }

    /// The speed of its fastest point below which the body counts as resting, m/s.
    #[inline]
    pub fn sleep_threshold(&self) -> Real {
        self.sleep_threshold
    }

    /// The fraction of its smallest extent it must move in a step to be swept by continuous
    /// collision ([`crate::BodyDef::sweep_threshold`]).
    #[inline]
    pub fn sweep_threshold(&self) -> Real {
        self.sweep_threshold
    }

    /// Whether it never turns ([`crate::BodyDef::fixed_rotation`]).
    pub fn fixed_rotation(&self) -> bool {
        self.fixed_rotation
    }

    /// Wakes the body (its island follows at the next step, through their contacts).
    pub(crate) fn wake_up(&mut self) {
        self.sleeping = false;
        self.sleep_time = 0.0;
    }

    /// Puts the body to sleep with its island: it stops until woken.
    pub(crate) fn fall_asleep(&mut self) {
        self.sleeping = true;
        self.linear_velocity = Vec2::zeros();
        self.angular_velocity = 0.0;
    }

    /// The island of a dynamic body.
    #[inline]
    pub(crate) fn island(&self) -> Option<u32> {
        self.island
    }

    /// The bodies before and after it in its island's list.
    #[inline]
    pub(crate) fn island_neighbours(&self) -> (Option<BodyHandle>, Option<BodyHandle>) {
        (self.island_prev, self.island_next)
    }

    /// Puts the body in an island's list, between `prev` and `next` (`None`s take it out).
    pub(crate) fn set_island(
        &mut self,
        island: Option<u32>,
        prev: Option<BodyHandle>,
        next: Option<BodyHandle>,
    ) {
        self.island = island;
        self.island_prev = prev;
        self.island_next = next;
    }

    /// Moves the body to another island, keeping its place in the list.
    pub(crate) fn set_island_id(&mut self, island: Option<u32>) {
        self.island = island;
    }

    /// Sets the body after it in its island's list.
    pub(crate) fn set_island_next(&mut self, next: Option<BodyHandle>) {
        self.island_next = next;
    }

    /// Sets the body before it in its island's list.
    pub(crate) fn set_island_prev(&mut self, prev: Option<BodyHandle>) {
        self.island_prev = prev;
    }

    /// Advances or resets the sleep timer from the body's fastest point speed, or from half
    /// the speed its last step's motion implies if that is more (Box2D's rule): a body still
    /// being pushed out of an overlap, with no velocity left after relaxing, stays awake.
    pub(crate) fn update_sleep_time(&mut self, dt: Real) {
        let threshold = self.sleep_threshold;
        /// How much position correction counts beside true velocity (Box2D's 0.5).
        const CORRECTION_WEIGHT: Real = 0.5;
        let speed = self.linear_velocity.norm() + self.reach * self.angular_velocity.abs();
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

    /// Moves the body's origin (teleports it: no velocity change).
    pub(crate) fn set_position(&mut self, position: Vec2) -> Result<(), CaromError> {
        self.position = check_position("body position", position)?;
        self.center = self.position + self.rotation * self.local_center;
        self.wake_up();
        Ok(())
    }

    /// Turns the body about its origin to `angle` radians.
    pub(crate) fn set_angle(&mut self, angle: Real) -> Result<(), CaromError> {
        self.rotation = rotation(check_finite("body angle", angle)?);
        self.center = self.position + self.rotation * self.local_center;
        self.wake_up();
        Ok(())
    }

    /// Sets the linear velocity (ignored by static bodies, which never move).
    pub(crate) fn set_linear_velocity(&mut self, velocity: Vec2) -> Result<(), CaromError> {
        check_velocity("linear velocity", velocity)?;
        if self.kind != BodyKind::Static {
            self.linear_velocity = velocity;
            self.wake_up();
        }
        Ok(())
    }

    /// Sets the angular velocity (ignored by static bodies).
    pub(crate) fn set_angular_velocity(&mut self, velocity: Real) -> Result<(), CaromError> {
        check_spin("angular velocity", velocity)?;
        let locked = self.fixed_rotation && self.kind == BodyKind::Dynamic;
        if self.kind != BodyKind::Static && !locked {
            self.angular_velocity = velocity;
            self.wake_up();
        }
        Ok(())
    }

    /// Gives a kinematic body the velocities that carry it to `position` and `angle` in
    /// exactly `dt` seconds, so a scripted path (a rotating drum, a lift) is followed
    /// without drift while contacts still see a velocity to push with. Other kinds are
    /// left alone: dynamic bodies move by forces and static ones never move.
    pub(crate) fn move_kinematic_to(
        &mut self,
        position: Vec2,
        angle: Real,
        dt: Real,
    ) -> Result<(), CaromError> {
        check_position("kinematic target", position)?;
        check_finite("kinematic target angle", angle)?;
        check_within("time step", dt, TIME_STEP_RANGE, "from 1e-6 s to 10 s")?;
        if self.kind != BodyKind::Kinematic {
            return Ok(());
        }
        // The shortest turn: the body's angle is kept as a rotation, not a winding count.
        let rotation = rotation(angle);
        let turn = angle_of(&(rotation * self.rotation.inverse()));
        let center = position + rotation * self.local_center;
        let velocity = check_velocity("kinematic move's velocity", (center - self.center) / dt)?;
        let spin = check_spin("kinematic move's angular velocity", turn / dt)?;
        self.linear_velocity = velocity;
        self.angular_velocity = spin;
        self.wake_up();
        Ok(())
    }

    /// Sets the gravity scale (finite; negative makes the body rise).
    pub(crate) fn set_gravity_scale(&mut self, scale: Real) -> Result<(), CaromError> {
        self.gravity_scale = check_gravity_scale(scale)?;
        Ok(())
    }

    /// Sets the linear and angular drag coefficients (finite, not negative).
    pub(crate) fn set_damping(&mut self, linear: Real, angular: Real) -> Result<(), CaromError> {
        let linear = check_non_negative("linear damping", linear)?;
        self.angular_damping = check_non_negative("angular damping", angular)?;
        self.linear_damping = linear;
        Ok(())
    }

    /// Locks or frees its rotation; the caller rebuilds the mass.
    pub(crate) fn set_fixed_rotation(&mut self, fixed: bool) {
        self.fixed_rotation = fixed;
    }

    /// Sets the sweep threshold, if [`check_sweep_threshold`] accepts it.
    pub(crate) fn set_sweep_threshold(&mut self, fraction: Real) -> Result<(), CaromError> {
        self.sweep_threshold = check_sweep_threshold(fraction)?;
        Ok(())
    }

    /// Marks or unmarks the body as a bullet.
    pub(crate) fn set_bullet(&mut self, bullet: bool) {
        self.bullet = bullet;
    }

    /// Makes its contacts look a step ahead whatever the world does, or not.
    pub(crate) fn set_look_ahead(&mut self, look_ahead: bool) {
        self.look_ahead = look_ahead;
    }

    /// Sets the user tag.
    pub(crate) fn set_user_tag(&mut self, tag: u64) {
        self.user_tag = tag;
    }

    /// Puts the body back along its path to where continuous collision found the impact
    /// (`center` is the centre of mass there); it keeps its velocity.
    pub(crate) fn move_to_time_of_impact(&mut self, center: Vec2, mut rotation: Rot) {
        // Renormalised as a step's end is (as Box2D normalises its sweep's rotation): the
        // next step's sweep starts from it, so a body stopped step after step would
        // otherwise carry each product's rounding into the next and drift off the unit circle.
        rotation.renormalize_fast();
        self.center = center;
        self.rotation = rotation;
        self.position = center - rotation * self.local_center;
        self.had_time_of_impact = true;
    }

    /// True when continuous collision put the body back along its path in the last step: it
    /// ended near where it started although it moves fast, so how far it moved says nothing
    /// about how much its contacts changed.
    pub(crate) fn had_time_of_impact(&self) -> bool {
        self.had_time_of_impact
    }

    /// Where the body started its last solved step ([`Body::finish_step`]), for continuous
    /// collision to sweep from.
    pub(crate) fn start_pose(&self) -> Pose {
        self.start
    }

    /// Commits a solved step: velocities, and the motion of the centre of mass accumulated
    /// over it; the origin follows, and the pose it started from is kept for continuous
    /// collision (here, where the body is written anyway, rather than in a pass of its own).
    /// Forces are cleared; the world re-places the colliders.
    pub(crate) fn finish_step(&mut self, v: Vec2, w: Real, dp: Vec2, dq: Rot) {
        self.start = Pose {
            center: self.center,
            rotation: self.rotation,
        };
        self.linear_velocity = v;
        self.angular_velocity = w;
        self.center += dp;
        self.rotation = dq * self.rotation;
        // Renormalise so thousands of small rotations do not drift off the unit circle.
        self.rotation.renormalize_fast();
        self.position = self.center - self.rotation * self.local_center;
        self.had_time_of_impact = false;
        self.last_motion = dp.norm() + dq.im.abs() * self.reach;
        self.clear_forces();
    }

    /// How far its colliders reach from the centre of mass, m.
    #[inline]
    pub(crate) fn reach(&self) -> Real {
        self.reach
    }

    /// The smallest collider's smallest extent, m.
    #[inline]
    pub(crate) fn min_extent(&self) -> Real {
        self.min_extent
    }

    /// Attaches a collider (the world stores it).
    pub(crate) fn attach(&mut self, collider: ColliderHandle) {
        self.colliders.push(collider);
    }

    /// Detaches a collider.
    pub(crate) fn detach(&mut self, collider: ColliderHandle) {
        self.colliders.retain(|&c| c != collider);
    }

    /// Sets the box around all its colliders.
    pub(crate) fn set_aabb(&mut self, aabb: Aabb) {
        self.aabb = aabb;
    }

    /// Changes the kind; the world rebuilds the mass and stops a static body.
    pub(crate) fn set_kind_unchecked(&mut self, kind: BodyKind) {
        self.kind = kind;
        if kind == BodyKind::Static {
            self.linear_velocity = Vec2::zeros();
            self.angular_velocity = 0.0;
        }
        self.clear_forces();
        self.wake_up();
    }
}

mod applied;
mod checks;
#[cfg(feature = "serde")]
mod saved;

pub(crate) use checks::check_position;
pub(crate) use checks::check_sweep_threshold;
use checks::{check_gravity_scale, check_spin, check_velocity};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;
    use std::mem::offset_of;

    /// What the narrowphase reads of a body lies in its head.
    #[test]
    fn what_a_contact_reads_lies_in_the_head() {
        let ends = [
            offset_of!(Body, handle) + size_of::<BodyHandle>(),
            offset_of!(Body, kind) + size_of::<BodyKind>(),
            offset_of!(Body, sleeping) + 1,
            offset_of!(Body, had_time_of_impact) + 1,
            offset_of!(Body, look_ahead) + 1,
            offset_of!(Body, position) + size_of::<Vec2>(),
            offset_of!(Body, rotation) + size_of::<Rot>(),
            offset_of!(Body, center) + size_of::<Vec2>(),
            offset_of!(Body, reach) + size_of::<Real>(),
            offset_of!(Body, min_extent) + size_of::<Real>(),
            offset_of!(Body, linear_velocity) + size_of::<Vec2>(),
            offset_of!(Body, angular_velocity) + size_of::<Real>(),
        ];
        assert!(
            ends.iter().all(|&end| end <= HEAD_BYTES),
            "{ends:?} > {HEAD_BYTES}"
        );
    }

    /// A unit box of density 1 on its own, its collider attached as a world would.
    fn unit_box(kind: BodyKind) -> Body {
        let handle = BodyHandle {
            index: 0,
            generation: 0,
        };
        let def = BodyDef::new(kind, Shape::rect(0.5, 0.5));
        let mut body = Body::new(handle, &def).unwrap();
        let collider = Collider::new(handle, 0, def.colliders[0].clone(), &body.transform());
        body.rebuild_mass(std::iter::once(&collider)).unwrap();
        body
    }

    /// Continuous collision's pose is renormalised: the next step's sweep starts from it.
    #[test]
    fn a_body_put_back_by_continuous_collision_keeps_a_unit_rotation() {
        let mut b = unit_box(BodyKind::Dynamic);
        let off = Rot::from_cos_sin_unchecked(0.6 * 1.0001, 0.8 * 1.0001);
        b.move_to_time_of_impact(Vec2::new(1.0, 2.0), off);
        assert!(
            (b.rotation().norm() - 1.0).abs() < 1e-6,
            "{:?}",
            b.rotation()
        );
        assert!((b.angle() - off.angle()).abs() < 1e-6);
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
        assert!(b.set_angle(Real::NAN).is_err());
        assert_eq!(b.position(), Vec2::zeros());
        assert_eq!(b.force(), Vec2::zeros());
        assert_eq!(b.mass(), 1.0);
    }

    #[test]
    fn model_matrix_rotates_then_translates() {
        let mut b = unit_box(BodyKind::Dynamic);
        b.set_position(vec2(3.0, 1.0)).unwrap();
        b.set_angle(crate::math::consts::FRAC_PI_2).unwrap();
        let m = b.model_matrix();
        let local = nalgebra::Vector3::new(1.0, 0.0, 1.0);
        let world = m * local;
        assert!((world.x - 3.0).abs() < 1e-6 && (world.y - 2.0).abs() < 1e-6);
        assert!((b.world_point(vec2(1.0, 0.0)) - vec2(3.0, 2.0)).norm() < 1e-6);
        assert!((b.local_point(vec2(3.0, 2.0)) - vec2(1.0, 0.0)).norm() < 1e-6);
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
        let short_turn = 2.0 * crate::math::consts::PI - 6.0;
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
        body.update_sleep_time(dt);
        assert_eq!(body.sleep_time(), dt);
        // No velocity left, but pushed 1 cm this step (0.3 m/s, half counted): awake.
        body.finish_step(Vec2::zeros(), 0.0, vec2(0.0, 0.01), Rot::identity());
        body.update_sleep_time(dt);
        assert_eq!(body.sleep_time(), 0.0);
        // Turned 0.01 rad: its corners moved 7 mm. Awake too.
        body.finish_step(Vec2::zeros(), 0.0, Vec2::zeros(), Rot::new(0.01));
        body.update_sleep_time(dt);
        assert_eq!(body.sleep_time(), 0.0);
    }

    #[test]
    fn each_body_rests_below_its_own_sleep_threshold() {
        let handle = BodyHandle {
            index: 0,
            generation: 0,
        };
        let dt = 1.0 / 60.0;
        // Drifting at 7 cm/s: moving by the default 5 cm/s, resting by Box2D's ragdolls' 10.
        let drifting = |threshold: Real| {
            let def = BodyDef::dynamic(Shape::circle(0.5)).sleep_threshold(threshold);
            let mut body = Body::new(handle, &def).unwrap();
            body.finish_step(vec2(0.07, 0.0), 0.0, vec2(0.07 * dt, 0.0), Rot::identity());
            body.update_sleep_time(dt);
            body.sleep_time()
        };
        assert_eq!(drifting(crate::SLEEP_THRESHOLD), 0.0);
        assert_eq!(drifting(0.1), dt);
        let negative = BodyDef::dynamic(Shape::circle(0.5)).sleep_threshold(-1.0);
        assert!(Body::new(handle, &negative).is_err());
    }
}
