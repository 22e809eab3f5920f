//! # carom-bench
//!
//! Runs carom and [Rapier](https://rapier.rs) (`rapier2d` 0.36.1, single-threaded: features
//! `dim2`, `f32`, `std`, `block-solver` — its defaults, spelled out, with no `parallel` and no
//! `simd-*`) side by side on the same scene, in one process, the way Box2D's benchmark harness
//! times engines: dt = 1/60, the first step untimed, the total wall time of the remaining steps,
//! the minimum over runs. [`RapierWorld::from_carom`] rebuilds a carom [`carom::World`] in Rapier;
//! [`compare`] times one run in either engine and measures how far the top body fell.
//!
//! [`scaling`] times rows of pyramids from about a thousand boxes to a hundred thousand in
//! every engine and draws how each one's cost grows (`carom-bench scaling`).
//!
//! It also runs every hard case of `tests/stability.rs` in carom and in
//! [Box2D v3](https://box2d.org) (`boxdd` 0.6, the bindings of Box2D 3.2.0, compiled with AVX2):
//! [`Box2dWorld::from_carom`] rebuilds a carom world in Box2D, and [`hard_cases`] measures each
//! case the same way in both engines (`carom-bench hard-cases`).
//!
//! [`sweep`] is the accuracy sweep behind the demo's `carom bench` and its accuracy panel:
//! every solver setting's time against its error on scenes with an exact answer.
//!
//! [`measured`] keeps the tables that programs outside this crate measure (the page in a
//! browser, the npm package under Node, the window, the Bevy plugins) under the same lines
//! naming the machine, the date and the command, for the docs to draw (`carom-bench measure`).
//!
//! [`cases`] holds what the stability suite and the hard cases share: their worlds, the joint
//! measures, a seeded random number generator. Box2D and Rapier sit behind the default feature
//! `peers`, the command line and the PNG charts behind the default feature `native`, the sweep
//! behind the default feature `sweep`; without them the library is [`cases`] and [`notes`],
//! which build on the core and the scene crate only (the test package `carom-tests` uses it
//! so).
//!
//! ## Parameter mapping, carom → Rapier
//!
//! | carom | Rapier | exact? |
//! |---|---|---|
//! | `BodyKind::Static` / `Kinematic` / `Dynamic` | `Fixed` / `KinematicVelocityBased` / `Dynamic` | yes |
//! | position, angle, linear and angular velocity | `translation`, `rotation`, `linvel`, `angvel` | yes (velocities not set on fixed bodies) |
//! | `gravity_scale` | `gravity_scale` | yes |
//! | linear / angular damping (the `Drag` effect with [`carom::DragModel::Exponential`]) | `linear_damping` / `angular_damping` | yes: both apply `v /= 1 + dt c`; with `Drag` off, or the tutorial drag model, no damping is set |
//! | `Shape::Circle` | `ColliderBuilder::ball(radius)` | yes |
//! | `Shape::Polygon`, an axis-aligned rectangle in body space | `ColliderBuilder::cuboid(hx, hy)`, or `round_cuboid(hx, hy, radius)` when it is rounded | yes |
//! | any other `Shape::Polygon` (convex, CCW, centred on its centroid) | `convex_polyline` (no hull recomputed), `convex_hull` as a fallback; `round_convex_polyline` when it is rounded | yes |
//! | `Shape::Capsule` | `capsule_from_endpoints(center1, center2, radius)` | yes |
//! | `Shape::Segment` | `segment(point1, point2)` | yes |
//! | `Shape::ChainSegment` (a chain's link) | `segment(point1, point2)` | no: Rapier's segment is two-sided and has no ghost vertices, so its joins are not smoothed; noted |
//! | each collider: density, offset and angle | a collider with `density` and `position` relative to its body (mass and inertia from the shapes) | yes |
//! | friction, mixed by geometric mean (`Friction` effect; 0 when off) | collider `friction` + `CoefficientCombineRule::GeometricMean` | yes |
//! | restitution, mixed by max (`Restitution` effect; 0 when off) | collider `restitution` + `CoefficientCombineRule::Max` | rule yes; carom does not bounce below 1 m/s approach, Rapier has no such threshold |
//! | gravity (zero when the `Gravity` effect is off) | `gravity` argument of `PhysicsPipeline::step` | yes |
//! | `Sleeping` effect | `can_sleep(true)` on every body; off → `can_sleep(false)` | switch yes, thresholds close: both 0.05 m/s and 0.5 s, but carom measures the fastest point's speed (`|v| + r |ω|`) and sleeps islands, Rapier its own per-body linear (0.05) and angular (0.5 rad/s) thresholds |
//! | a body's `sleep_threshold` other than 0.05 m/s | its activation's `normalized_linear_threshold` | yes: both on the fastest point's speed |
//! | a body asleep when the copy is made (one added with `awake: false`) | `sleeping(true)` | yes |
//! | `is_bullet` (with the `Continuous` effect) | `ccd_enabled(true)` | partly: carom also sweeps every fast dynamic body against static ones; Rapier's CCD is only switched on for bullets here |
//! | soft step's `substeps` (default 4) | `num_solver_iterations` (Rapier's solver iterations are its substeps) | yes |
//! | soft step's `iterations` (default 1) | `num_internal_pgs_iterations` (default 1) | yes; the classic solvers (no substeps) map to 1 substep of `iterations` PGS sweeps, which is not the same algorithm |
//! | `warm_starting` | `warmstart_coefficient` 1 or 0 | yes |
//! | `direct_joints`, `shock_propagation` (off by default) | none: Rapier's impulse joints and contacts are solved as always | no |
//! | `friction_in_bias_pass` (default on, as Box2D v3.1) | `friction_in_bias_pass` left at Rapier's default, off | no: Rapier's 5050-box pyramid collapses with it on (top box 34 m down in 500 steps), so Rapier keeps its own setting |
//! | `look_ahead` (default on: with `Continuous`, contacts are made as far as the pair can close in a step) | none: Rapier's contacts keep points within its prediction distance only | no; off, carom's contacts keep points within `speculative_distance` only, as Rapier's do |
//! | `speculative_distance` (0.02 m = 4 × slop) | `normalized_prediction_distance` (default 0.02, `length_unit` 1) | yes; collider `contact_skin` stays at its default 0 |
//! | `LINEAR_SLOP` (0.005 m) | `normalized_allowed_linear_error` (default 0.005) | yes |
//! | `max_push_speed` (3 m/s) | `normalized_max_corrective_velocity` (default 3) | yes |
//! | `max_linear_speed` (400 m/s) | `normalized_max_linear_velocity` (default 400) | yes |
//! | `contact_hertz` 30, `damping_ratio` 10, `static_stiffness` 2 | left at Rapier's defaults: `contact_softness` 30 Hz, ζ 10; `static_contact_softness` 60 Hz, ζ 10 | equal at carom's defaults (Box2D's); a scene that changes carom's softness is not followed |
//! | collision filter: `category`, `mask` (`u64`), `group` | `collision_groups`: memberships = category, filter = mask, test `And` | yes when the collider has no group and every category in the world fits Rapier's 32 bits (a mask's higher bits then meet no category); otherwise the collider lets every pair through its groups and a contact-pair hook applies carom's rule (same group: collide if positive, never if negative; else both masks) exactly |
//! | a joint: bodies, anchors in each body, reference angle, axis in A's frame | an impulse joint (`GenericJoint`): `local_frame1` at A's anchor turned to the axis, `local_frame2` at B's anchor turned by the axis less the reference angle | yes |
//! | `collide_connected` | `contacts_enabled` (Rapier's default is true, carom's false) | yes |
//! | revolute: limits / motor / spring toward `target_angle` | `AngX` free: limits, a velocity motor (rigid: damping 1e10) capped at the motor's torque, or a position motor | yes; with both a spring and a motor (a ragdoll's sprung hinge with joint friction), the spring is the joint's position motor and the motor a second joint's velocity motor on the same frames, every axis free (Rapier has one motor per axis) |
//! | prismatic: axis, limits, motor, spring toward `target_translation` | `LinX` free along A's frame's x: limits, motor as for the revolute | yes, same spring-and-motor note |
//! | wheel: axis, suspension spring, limits, motor | pin-slot (`LinY` locked): a position motor at 0 on `LinX`, limits on `LinX`, a velocity motor on `AngX` | yes |
//! | weld, rigid / with linear and angular springs | all axes locked / a sprung part freed and pulled home by position motors | rigid yes; a linear spring acts per axis of A's frame (carom and Box2D solve the point as one block) |
//! | distance: rope (0 Hz spring, limits) / spring / rigid rod | coupled linear axes (the anchors' distance): upper limit; position motor at the length; for a rod, the upper limit and a spring as stiff as Rapier's joints | rope and spring yes, except a lower limit above 0 (Rapier's coupled limit has no lower side), noted; the rod is rigid only against stretching, noted |
//! | filter joint | a joint with no axis locked, contacts off | yes |
//! | a spring of `hertz`, `damping_ratio` | motor stiffness `ω²` and damping `2ζω`, acceleration-based (Rapier's default model), `ω = 2π hertz` | yes: Box2D's soft-constraint bias, mass and impulse scales |
//! | soft step's `joint_hertz` 60, `joint_damping_ratio` 2 | not followed: Rapier's joint `softness` stays at its default (1 MHz, ζ 1) | no: Rapier softens joints in every pass, Box2D and carom only in the biased one, so 60 Hz makes Rapier's joints far softer (the joint grid's widest joint opens 0.82 m in a second against 0.67 m at Rapier's default; carom and Box2D 0.36 m) |
//!
//! ## What does not map
//!
//! - Chain links: carom's are one-sided and smooth across their joins (ghost vertices, as
//!   Box2D's); Rapier's segments are two-sided, so a body sliding along a chain may catch on
//!   a join in Rapier that it glides over in carom.
//! - Rapier 0.36 uses Box2D-like soft contacts but has its own block solver for two-point
//!   manifolds (`block-solver` feature, on by default), contact clustering and contact recycling;
//!   carom solves the points one by one.
//! - carom's `max_rotation` guard is π/4 per step and settable; Rapier's is a fixed π/4 per
//!   step. carom's restitution threshold (1 m/s) has no Rapier counterpart.
//!   Rapier's `length_unit` is 1 m, as carom's units.
//! - Motor and mouse joints: Rapier has no joint that closes a fraction of an offset per step
//!   within force caps, and no mouse joint; they are left out, and break thresholds too (its
//!   joints do not break). [`RapierWorld::notes`] lists what was left out or approximated, and
//!   `carom-bench` prints it under its table.
//! - Scene events: a scene's spawn events are replayed. `carom-bench` writes out their schedule
//!   before timing ([`carom_scene::SceneWorld::spawn_schedule`]) and, inside the timed steps,
//!   makes and removes the same bodies and joints before the same steps
//!   ([`RapierWorld::add_spawned`], [`RapierWorld::remove_spawned`]); carom fires every
//!   event itself. Its other events (launches, respawns, spins) are not replayed in the
//!   peers, and `carom-bench` notes them.
//!
//! ## Parameter mapping, carom → Box2D
//!
//! | carom | Box2D v3 | exact? |
//! |---|---|---|
//! | `BodyKind::Static` / `Kinematic` / `Dynamic` | `b2_staticBody` / `b2_kinematicBody` / `b2_dynamicBody` | yes |
//! | position (the body's origin), angle, linear and angular velocity, `gravity_scale` | `position`, `rotation`, `linearVelocity`, `angularVelocity`, `gravityScale` | yes (velocities not set on static bodies) |
//! | each collider (shape, offset, angle, material) | one shape, placed in the body's frame | yes |
//! | gravity (zero when the `Gravity` effect is off) | world `gravity` | yes |
//! | linear / angular drag (`Drag` effect, exponential model) | `linearDamping` / `angularDamping` | yes; none set with `Drag` off or the tutorial model |
//! | `Shape::Circle` | `b2Circle` | yes |
//! | `Shape::Polygon` (convex, CCW, centred on its centroid, sharp or rounded) | `b2Polygon` from carom's vertices and normals, with carom's radius | yes, up to Box2D's 8 vertices; no hull recomputed |
//! | `Shape::Capsule` / `Shape::Segment` | `b2Capsule` / `b2Segment` | yes |
//! | `Shape::ChainSegment` (a chain's link) | `b2ChainSegment` with the link's ghost vertices | yes: one-sided and smooth in both |
//! | density | shape `density` | yes |
//! | friction (geometric mean) / restitution (max); 0 when the effect is off | shape material `friction` / `restitution`, Box2D's default mixing (the same rules) | yes |
//! | `restitution_threshold` (1 m/s) | world `restitutionThreshold` (1 m/s) | yes |
//! | `Sleeping` effect | world `enableSleep` (0.05 m/s for 0.5 s in both) | yes |
//! | a body's `sleep_threshold` | body `sleepThreshold` | yes |
//! | `Continuous` effect / `is_bullet` | world `enableContinuous` / body `isBullet` | yes |
//! | soft step's `substeps` (4) | `subStepCount` (4) | yes |
//! | `contact_hertz` (30), `damping_ratio` (10), `max_push_speed` (3 m/s) | world `contactHertz`, `contactDampingRatio`, `contactSpeed` (3.1's `maxContactPushSpeed`) | yes |
//! | `max_linear_speed` (400 m/s), `warm_starting` | world `maximumLinearSpeed`, `b2World_EnableWarmStarting` | yes |
//! | collision filter (`category`, `mask`, `group`) | shape `filter` (`categoryBits`, `maskBits`, `groupIndex`) | yes: the same rule, the same widths |
//! | joints: distance, revolute, prismatic, weld, wheel, filter, with their limits, motors and springs; `collide_connected`; `joint_hertz`, `joint_damping_ratio` | Box2D 3.2's joints of the same kinds, from local frames (anchor, and rotation for the axis and reference angle); `collideConnected`; each joint's `constraintHertz`, `constraintDampingRatio` | yes (hinge limits narrowed to Box2D's ±0.99π, noted) |
//!
//! What does not map: Box2D has only its soft step (a carom world set to another solver still
//! runs soft step in Box2D); one solve and one relax pass per substep (carom's default
//! `iterations` 1); static contacts always twice as stiff (carom's default `static_stiffness`
//! 2); friction in the relax pass only, where carom's default `friction_in_bias_pass` also solves
//! it in the biased pass; always graph colouring; `LINEAR_SLOP` and `speculative_distance` are
//! Box2D constants with carom's default values; motor and mouse joints (Box2D 3.2's motor
//! joint drives velocities and springs, and it has no mouse joint) and break thresholds (Box2D
//! reports, it does not break) are left out and noted ([`Box2dWorld::notes`]); both cap
//! rotation at π/4 per step, carom's
//! settable; Box2D caps contact stiffness at an eighth of the substep rate, carom at a
//! quarter (equal at the default 30 Hz with 4 substeps); contact recycling stays at
//! Box2D's default (on); the tutorial drag model has no counterpart; of a scene's events only
//! its spawns are replayed, as in Rapier. Details in [`box2d_world`].

// Widening carom's numbers to `f64` is a no-op in its double-precision build.
#![cfg_attr(
    feature = "f64",
    allow(clippy::unnecessary_cast, clippy::useless_conversion)
)]

// The peers take carom's world in single precision.
#[cfg(all(feature = "f64", feature = "peers"))]
compile_error!(
    "Box2D and Rapier are single precision: build carom's f64 side without them \
     (--no-default-features, then the features wanted, with f64)"
);

pub mod cases;
pub mod notes;
#[cfg(feature = "sweep")]
pub mod sweep;

#[cfg(feature = "peers")]
pub mod box2d_heap;
#[cfg(feature = "peers")]
pub mod box2d_world;
#[cfg(all(feature = "peers", feature = "native"))]
pub mod compare;
#[cfg(all(feature = "peers", feature = "sweep"))]
pub mod docs;
#[cfg(feature = "peers")]
pub mod hard_cases;
#[cfg(all(feature = "peers", feature = "native", feature = "sweep"))]
pub mod look_ahead;
#[cfg(feature = "sweep")]
pub mod measured;
pub mod projection;
#[cfg(feature = "peers")]
pub mod rapier_world;
#[cfg(feature = "native")]
pub mod scaling;
#[cfg(feature = "native")]
pub mod snapshot_cost;
#[cfg(feature = "native")]
pub mod timeline_cost;

#[cfg(feature = "peers")]
pub use box2d_world::Box2dWorld;
#[cfg(all(feature = "peers", feature = "native"))]
pub use compare::{RunResult, run_box2d, run_carom, run_rapier};
pub use notes::Notes;
#[cfg(feature = "peers")]
pub use rapier_world::RapierWorld;

/// Gives plotters' charts their one font, "sans-serif" (Ubuntu Light, as egui draws text):
/// plotters' bitmap backend has no system fonts to fall back on.
#[cfg(feature = "native")]
fn register_fonts() {
    use plotters::style::{FontStyle, register_font};
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is compiled in and known to parse.
        let _ = register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}
