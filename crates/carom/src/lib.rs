//! # carom
//!
//! A 2D rigid-body physics engine: bodies made of circles, capsules, convex polygons (sharp or
//! rounded), segments and smooth chains ([`ChainDef`]) with mass from density, forces, drag,
//! collision filters ([`CollisionFilter`]), sensors, contact and hit events, a pre-solve hook,
//! queries (boxes, shapes, rays, shape casts) and explosions, a dynamic-tree broadphase, SAT
//! narrowphase with clipped contact manifolds, joints ([`JointDef`]), contact solvers from the
//! tutorial's push-out to Box2D v3's soft step, continuous collision and sleeping. It has no
//! graphics dependency.
//!
//! Units are SI: metres, kilograms, seconds, radians. Angles are counter-clockwise. Shapes are
//! centred on their centroid when built; a body's colliders place them in its frame, whose
//! origin is the body's position. A body of one shape at its origin has its centre of mass
//! there; with more, the centre of mass is found from them all ([`Body::center_of_mass`]).
//!
//! The everyday types are in [`prelude`]; two shapes against each other with no world around
//! them in [`query`]; what a world draws in [`draw`].
//!
//! Drop a box under gravity:
//!
//! ```
//! use carom::prelude::*;
//!
//! let mut world = World::new(); // gravity (0, -10)
//! let falling_box = world.add_body(
//!     BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 10.0)),
//! )?;
//! for _ in 0..60 {
//!     world.step(1.0 / 60.0)?;
//! }
//! let body = world.body(falling_box).unwrap();
//! // One second of free fall: v = g t, and y drops by g t² / 2 = 5 m, give or take the
//! // integrator's error (semi-implicit Euler in 4 substeps per step: g t² / (2 n), n = 240).
//! assert!((body.linear_velocity().y + 10.0).abs() < 1e-4);
//! assert!((body.position().y - (10.0 - 5.0 * 241.0 / 240.0)).abs() < 1e-3);
//! # Ok::<(), carom::CaromError>(())
//! ```

// A panic that a caller's input can reach is a bug. Each `expect`, `unreachable!` and
// `panic!` left in the library says, in the `allow` beside it, why no input reaches it.
#![cfg_attr(
    not(test),
    warn(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::unreachable,
        clippy::todo,
        clippy::unimplemented
    )
)]
// Every public item says what it is, in every build (the workspace only warns).
#![deny(missing_docs)]
// Every `pub` item is reachable from outside the crate; the rest say `pub(crate)`. The items
// that `carom::testing` opens are public only with that feature, so the lint runs where it is
// on (every workspace build).
#![cfg_attr(feature = "testing", warn(unreachable_pub))]
// Single precision widens to `f64` where sums need it; in the double-precision build those
// casts are no-ops.
#![cfg_attr(feature = "f64", allow(clippy::unnecessary_cast))]
// A world-placed polygon holds its points inline; in double precision that is over the lint's
// size bound, and boxing it would cost the single-precision build a pointer chase.
#![cfg_attr(feature = "f64", allow(clippy::large_enum_variant))]

mod capacity;
mod character;
mod clone_in_place;
mod collision;
mod constants;
mod debug_draw;
mod dynamics;
mod error;
mod geometry;
mod graph;
mod handle_map;
mod heap_bytes;
mod joint;
mod math;
mod parallel;
mod partition;
mod prefetch;
mod solver;
mod solver_set;
#[cfg(feature = "serde")]
mod sorted_map;
mod stats;
mod world;

pub use capacity::Capacity;
pub use character::controller::{Character, CharacterDef, CharacterMove, CharacterState, Ground};
pub use character::mover::MoverPlane;
pub use character::planes::{CollisionPlane, PlaneSolution, clip_velocity, solve_planes};
pub use collision::contact::{Contact, ContactEvent, ContactPair, PointImpulse};
pub use collision::hits::HitEvent;
pub use collision::pre_solve::PreSolveContact;
pub use collision::query_filter::QueryFilter;
pub use collision::sensor::{SensorEvent, SensorOverlap};
pub use constants::{
    LINEAR_SLOP, MAX_ACCELERATION, MAX_ANGULAR_SPEED, MAX_BODY_INERTIA, MAX_BODY_MASS,
    MAX_GRAVITY_SCALE, MAX_JOINT_LENGTH, MAX_POSITION, MAX_REGULAR_SIDES, MAX_SHAPE_EXTENT,
    MAX_SPEED, MAX_SPRING, MAX_SURFACE_COEFFICIENT, MAX_TANGENT_SPEED, MIN_BODY_INERTIA,
    MIN_BODY_MASS, SHAPE_CAST_TOLERANCE, SLEEP_THRESHOLD, SPECULATIVE_DISTANCE, SWEEP_THRESHOLD,
    TIME_STEP_RANGE, TIME_TO_SLEEP,
};
pub use dynamics::body::{Body, BodyHandle, BodyKind};
pub use dynamics::body_def::{BodyDef, ColliderSettings};
pub use dynamics::chain::ChainDef;
pub use dynamics::collider::{Collider, ColliderDef, ColliderHandle};
pub use dynamics::drag::DragModel;
pub use dynamics::filter::CollisionFilter;
pub use dynamics::surface::{MaterialMixer, Surface};
pub use error::CaromError;
pub use geometry::aabb::Aabb;
pub use geometry::mass::MassProperties;
pub use geometry::ray::{Ray, RayHit};
pub use geometry::shape::{
    Capsule, ChainSegment, Circle, Points, Polygon, Segment, Shape, WorldShape,
};
pub use joint::{
    Anchors, DistanceJoint, DistanceJointDef, Joint, JointDef, JointEvent, JointHandle, JointKind,
    Limits, Motor, MotorJoint, MotorJointDef, MouseJoint, MouseJointDef, MoverJoint, MoverJointDef,
    PogoJoint, PogoJointDef, PrismaticJoint, PrismaticJointDef, RevoluteJoint, RevoluteJointDef,
    Spring, WeldJoint, WeldJointDef, WheelJoint, WheelJointDef,
};
pub use math::{Isometry, Mat3, Real, Rot, Vec2, angle_of, atan2, consts, rotation, vec2};
pub use solver::{SolverKind, SolverParams};
pub use stats::{CollisionWork, StageTimes, StepStats, Work};
pub use world::body_mut::BodyMut;
pub use world::collider_mut::ColliderMut;
pub use world::effects::{Effect, Effects};
pub use world::explosion::ExplosionDef;
pub use world::joint_mut::JointMut;
pub use world::settings::WorldSettings;
pub use world::snapshot::Snapshot;
pub use world::{CastHit, World};

/// The everyday types, for `use carom::prelude::*`: a world and its settings, bodies,
/// colliders, shapes and joints, the solver's settings, the error type and the maths.
pub mod prelude {
    pub use crate::{
        Body, BodyDef, BodyHandle, BodyKind, CaromError, ChainDef, Collider, ColliderDef,
        ColliderHandle, CollisionFilter, Effect, Effects, Joint, JointDef, JointHandle,
        QueryFilter, Real, Rot, Shape, SolverKind, SolverParams, Surface, Vec2, World,
        WorldSettings, vec2,
    };
}

/// Two placed shapes against each other, with no world around them: their signed distance
/// ([`separation`](query::separation)) and where they touch ([`collide`](query::collide)),
/// as the world's narrowphase finds them.
pub mod query {
    pub use crate::geometry::query::collide::collide;
    pub use crate::geometry::query::distance::{Separation, separation};
    pub use crate::geometry::query::manifold::{FeatureId, Manifold, ManifoldPoint};
}

/// How a world describes itself for drawing ([`World::debug_draw`]): a
/// [`DebugDraw`](draw::DebugDraw) sink, or the [`DrawList`](draw::DrawList) it fills, of
/// circles, polygons, segments, arrows and points in world coordinates with colours, and
/// the widths of lines and dots in pixels (how thick outlines and arrows are is the
/// renderer's choice).
pub mod draw {
    pub use crate::debug_draw::{
        Color, DebugDraw, DrawArrow, DrawCircle, DrawFlags, DrawList, DrawOptions, DrawPoint,
        DrawPolygon, DrawSegment,
    };
}

/// Internals for carom's own tests, benchmarks and fuzz targets: reference implementations
/// and the narrowphase's parts. Not part of the supported interface.
#[cfg(feature = "testing")]
pub mod testing {
    pub use crate::collision::broadphase::{BroadPhase, brute_force_pairs};
    pub use crate::constants::{COINCIDENT_NORMAL, SPURIOUS_TOLERANCE};
    pub use crate::geometry::dynamic_tree::DynamicTree;
    pub use crate::geometry::mass::{
        polygon_area, polygon_centroid, polygon_inertia_about_origin, polygon_mass,
    };
    pub use crate::geometry::query::distance::polygon_circle;
    pub use crate::geometry::query::manifold::PairSide;
    pub use crate::math::cross;
}
