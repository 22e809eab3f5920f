//! # carom
//!
//! A 2D rigid-body physics engine: circles and convex polygons, bodies with mass from density,
//! forces, drag, queries, a dynamic-tree broadphase, SAT narrowphase with clipped contact
//! manifolds, and contact solvers from the tutorial's push-out to Box2D v3's soft step; continuous
//! collision and sleeping are on their way. It has no graphics dependency.
//!
//! Units are SI: metres, kilograms, seconds, radians. Angles are counter-clockwise. Every body's
//! origin is its centre of mass: shapes are recentred on their centroid when built.
//!
//! Drop a box under gravity:
//!
//! ```
//! use carom::{BodyDef, Shape, World, vec2};
//!
//! let mut world = World::new(); // gravity (0, -10)
//! let falling_box = world.add_body(
//!     BodyDef::dynamic(Shape::rect(0.5, 0.5)?).position(vec2(0.0, 10.0)),
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

pub mod aabb;
pub mod body;
mod body_set;
pub mod broadphase;
pub mod contact;
mod continuous;
pub mod debug_draw;
pub mod drag;
pub mod effects;
pub mod error;
pub mod manifold;
pub mod mass;
pub mod math;
pub mod mouse_joint;
pub mod narrowphase;
mod parallel;
pub mod ray;
pub mod recycle;
pub mod segment;
pub mod settings;
pub mod shape;
pub mod sleep;
pub mod solver;
pub mod stats;
pub mod world;

pub use aabb::Aabb;
pub use body::{Body, BodyDef, BodyHandle, BodyKind};
pub use broadphase::{BroadPhase, DynamicTree};
pub use contact::{Contact, ContactEvent};
pub use debug_draw::{Color, DebugDraw, DrawFlags, DrawList, DrawOptions};
pub use drag::DragModel;
pub use effects::{Effect, Effects};
pub use error::CaromError;
pub use manifold::{FeatureId, Manifold, ManifoldPoint};
pub use mass::MassProperties;
pub use math::{Isometry, Mat3, Real, Rot, Vec2, vec2};
pub use mouse_joint::MouseJoint;
pub use narrowphase::Separation;
pub use ray::{Ray, RayHit};
pub use segment::{SegmentIntersection, intersect_segments};
pub use settings::WorldSettings;
pub use shape::{Circle, Polygon, Shape, WorldShape};
pub use solver::{SolverKind, SolverParams};
pub use stats::{StageTimes, StepStats, Work};
pub use world::{World, WorldRayHit};
