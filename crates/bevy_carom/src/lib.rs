//! carom physics in Bevy.
//!
//! Add [`CaromPlugin`], then spawn entities with a [`RigidBody`] and a [`Collider`]; the
//! plugin makes carom bodies of them, steps the world on Bevy's fixed timestep and writes
//! each body's `Transform`, [`Velocity`] and [`Sleeping`] back:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_carom::prelude::*;
//!
//! App::new()
//!     .add_plugins((MinimalPlugins, TransformPlugin, CaromPlugin))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         // Ground: a collider alone is static.
//!         commands.spawn((Collider::rectangle(20.0, 1.0), Transform::from_xyz(0.0, -0.5, 0.0)));
//!         commands.spawn((RigidBody::Dynamic, Collider::circle(0.5), Transform::from_xyz(0.0, 4.0, 0.0)));
//!     })
//!     .run();
//! ```
//!
//! - Bodies: [`RigidBody`], [`Velocity`], [`Damping`], [`GravityScale`], [`Sleeping`],
//!   [`LockedRotation`], [`Bullet`], [`LookAhead`], [`ExternalForce`], [`ExternalImpulse`], and
//!   [`Interpolated`] for smooth drawing between fixed steps.
//! - Colliders: [`Collider`] (every carom shape and chains), [`ColliderMaterial`],
//!   [`CollisionFilter`], [`Sensor`], [`HitEvents`]; on the body's entity or its children.
//! - Joints: [`Joint`], of every carom kind, on an entity of its own.
//! - The world and its settings: [`CaromWorld`]. Queries: [`CaromQuery`]. What happened:
//!   [`ContactStarted`], [`ContactEnded`], [`SensorEntered`], [`SensorExited`], [`Hit`],
//!   [`JointBroken`], [`PhysicsError`] messages.
//! - Scenes in carom's RON format: [`LoadScene`]. Debug drawing through gizmos, with the
//!   `debug-draw` feature: `CaromDebugDrawPlugin`.

// carom's `Real` is `f32` unless its `f64` feature is on; the casts between it and Bevy's
// `f32` keep the plugin building either way.
#![allow(clippy::unnecessary_cast)]
// Bevy's queries spell their filters as types, and its systems take one parameter per
// resource, query and message stream.
#![allow(clippy::type_complexity, clippy::too_many_arguments)]

mod body;
mod collider;
mod convert;
#[cfg(feature = "debug-draw")]
mod debug_draw;
mod interpolation;
mod joint;
mod messages;
mod plugin;
mod query;
mod scene;
mod step;
mod sync;
mod world;

pub use body::{
    Bullet, CaromBody, Damping, ExternalForce, ExternalImpulse, GravityScale, Interpolated,
    LockedRotation, LookAhead, RigidBody, Sleeping, Velocity,
};
pub use collider::{CaromCollider, Collider, ColliderMaterial, CollisionFilter, HitEvents, Sensor};
#[cfg(feature = "debug-draw")]
pub use debug_draw::{CaromDebugDrawPlugin, DebugDrawOptions};
pub use joint::{CaromJoint, Joint};
pub use messages::{
    ContactEnded, ContactStarted, Hit, JointBroken, PhysicsError, SensorEntered, SensorExited,
};
pub use plugin::{CaromPlugin, CaromSystems};
pub use query::{CaromQuery, QueryFilter, QueryHit};
pub use scene::{LoadScene, SceneLoaded};
pub use world::CaromWorld;

/// carom itself, for its settings, shapes and joint kinds.
pub use carom;

/// What a game usually needs: `use bevy_carom::prelude::*`.
pub mod prelude {
    pub use crate::{
        Bullet, CaromPlugin, CaromQuery, CaromSystems, CaromWorld, Collider, ColliderMaterial,
        CollisionFilter, ContactEnded, ContactStarted, Damping, ExternalForce, ExternalImpulse,
        GravityScale, Hit, HitEvents, Interpolated, Joint, JointBroken, LoadScene, LockedRotation,
        LookAhead, PhysicsError, QueryFilter, RigidBody, Sensor, SensorEntered, SensorExited,
        Sleeping, Velocity,
    };
    #[cfg(feature = "debug-draw")]
    pub use crate::{CaromDebugDrawPlugin, DebugDrawOptions};
}
