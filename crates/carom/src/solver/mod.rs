//! Contact solvers, from the tutorial's to the state of the art, all selectable at run time.
//!
//! Every solver here owns the motion of one step: it integrates forces into velocities,
//! resolves contacts, and integrates velocities into positions, because the state of the art
//! (soft step) interleaves those stages in substeps. The bodies are copied into contiguous
//! `BodyState`s, the touching contacts prepared as constraints (soft step's coloured ones
//! straight into SIMD bundles, the rest as `ContactConstraint`s), solved, and written back.
//!
//! - [`SolverKind::PushOut`]: the tutorial with "impulse resolution" unchecked.
//! - [`SolverKind::TutorialImpulse`]: the tutorial's impulse loop, exactly.
//! - [`SolverKind::SequentialImpulse`]: Catto's 2006 accumulated impulses with warm starting.
//! - [`SolverKind::SoftStep`]: Box2D v3's substepped soft-constraint solver (the default).

mod body_state;
mod classic;
mod contact_constraint;
mod context;
mod joints;
mod params;
mod soft_step;
mod step;
mod workspace;

pub(crate) use context::{AwakeJoint, AwakeSet, Environment, StepReport};
pub use params::{SolverKind, SolverParams};
pub(crate) use step::step;
pub(crate) use workspace::Workspace;
