//! The components of a body: what kind it is and how it moves. An entity with a [`RigidBody`]
//! becomes a carom body at its `Transform` (x, y and the rotation about z; bodies are meant to
//! be top-level entities, not children).

use crate::convert::Pose;
use bevy::ecs::component::Component;
use bevy::math::Vec2;
use bevy::transform::components::Transform;
use carom::BodyHandle;

/// A rigid body, of one of carom's three kinds. Its colliders are the [`crate::Collider`] on
/// the same entity and on its children.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
#[require(Transform, Velocity, Damping, GravityScale, Sleeping)]
pub enum RigidBody {
    /// Moved by gravity, forces, contacts and joints.
    #[default]
    Dynamic,
    /// Moved only by its [`Velocity`], or to a `Transform` the game sets (over the next fixed
    /// step, stopping there unless set again: set it in `FixedUpdate` to drive the body along
    /// a path); pushes dynamic bodies, is not pushed.
    Kinematic,
    /// Never moves (unless its `Transform` is set): ground, walls.
    Static,
}

impl From<RigidBody> for carom::BodyKind {
    fn from(kind: RigidBody) -> Self {
        match kind {
            RigidBody::Dynamic => carom::BodyKind::Dynamic,
            RigidBody::Kinematic => carom::BodyKind::Kinematic,
            RigidBody::Static => carom::BodyKind::Static,
        }
    }
}

impl From<carom::BodyKind> for RigidBody {
    fn from(kind: carom::BodyKind) -> Self {
        match kind {
            carom::BodyKind::Dynamic => RigidBody::Dynamic,
            carom::BodyKind::Kinematic => RigidBody::Kinematic,
            carom::BodyKind::Static => RigidBody::Static,
        }
    }
}

/// A body's velocity: set it to launch the body; the plugin writes it back after each step.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct Velocity {
    /// Of its origin, m/s.
    pub linear: Vec2,
    /// Counter-clockwise, rad/s.
    pub angular: f32,
}

impl Velocity {
    /// Moving at `linear` m/s without turning.
    pub fn linear(linear: Vec2) -> Self {
        Velocity {
            linear,
            angular: 0.0,
        }
    }
}

/// How fast a body's velocities decay on their own, 1/s (0: not at all).
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct Damping {
    /// Of its linear velocity.
    pub linear: f32,
    /// Of its angular velocity.
    pub angular: f32,
}

/// How much of the world's gravity acts on a body: 1 all of it, 0 none, -1 upward.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct GravityScale(pub f32);

impl Default for GravityScale {
    fn default() -> Self {
        GravityScale(1.0)
    }
}

/// Whether a body sleeps: the plugin writes it after each step, and setting it to `false`
/// wakes the body (with the bodies it touches). A body spawned with `true` starts asleep.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sleeping(pub bool);

/// Keeps a body from rotating (a character's capsule, say).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LockedRotation;

/// Continuous collision against dynamic bodies too, not only static ones: for fast, small
/// bodies (projectiles) that must not pass through others.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Bullet;

/// Its contacts look a step ahead even in a world that does not
/// ([`carom::WorldSettings::look_ahead`], off to save time where many bodies move fast): an
/// impact of this body at any speed is stopped at the surface, where without look-ahead a
/// fast body sinks into what it hits for a step before it is pushed back out. For the few
/// fast bodies whose impacts must look right (a ball, a thrown crate).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LookAhead;

/// A force and torque applied at the body's centre of mass on every step until changed.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct ExternalForce {
    /// N.
    pub force: Vec2,
    /// N·m, counter-clockwise.
    pub torque: f32,
}

/// An impulse applied at the body's centre of mass on the next step, then cleared to zero.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct ExternalImpulse {
    /// N·s.
    pub impulse: Vec2,
    /// N·m·s, counter-clockwise.
    pub angular: f32,
}

/// Draws the body between fixed steps at a pose interpolated from its last two steps, so
/// that it moves smoothly at any frame rate. Physics and queries always see the stepped pose.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Interpolated;

/// The carom body an entity is, added by the plugin once it has made it.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
#[component(immutable)]
pub struct CaromBody(pub(crate) BodyHandle);

impl CaromBody {
    /// The body's handle in the [`crate::CaromWorld`].
    pub fn handle(&self) -> BodyHandle {
        self.0
    }
}

/// What the plugin last wrote to a body's components, so that a change the game makes is told
/// from its own, and the two poses interpolation draws between.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct BodyMirror {
    /// The `Transform` the plugin last wrote.
    pub transform: Transform,
    /// The `Velocity` it last wrote.
    pub velocity: Velocity,
    /// The `Sleeping` it last wrote.
    pub sleeping: bool,
    /// Whether the body has [`LockedRotation`], as the world has it.
    pub locked: bool,
    /// Whether it is a [`Bullet`], as the world has it.
    pub bullet: bool,
    /// Whether it has [`LookAhead`], as the world has it.
    pub look_ahead: bool,
    /// A kinematic body given a `Transform` to move to over the last step: it stops there
    /// unless given another.
    pub targeted: bool,
    /// The pose before the last step.
    pub previous: Pose,
    /// The pose after it.
    pub current: Pose,
}
