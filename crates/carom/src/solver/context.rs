//! What a solver step is handed: the world's forces and effects ([`Environment`]), the
//! settings and bodies it reads ([`SolverContext`]), the awake set it changes ([`AwakeSet`],
//! [`AwakeJoint`]), and what it reports back ([`StepReport`]).

use super::body_state::Drive;
use super::params::SolverParams;
use crate::collision::contact::{BodyIndices, Contact};
use crate::dynamics::body::Body;
use crate::dynamics::drag::DragModel;
use crate::graph::layout::ColorRanges;
use crate::joint::Joint;
use crate::math::{Real, Vec2};
use crate::stats::Work;
use std::ops::Range;
use std::time::Duration;

/// The world's forces and the contact effects in force for one step: `None` or `false` for
/// an effect that is off, which is then not computed at all.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Environment {
    pub gravity: Option<Vec2>,
    pub drag: Option<DragModel>,
    pub friction: bool,
    pub restitution: bool,
}

/// What every solver reads and does not change: its settings, the world's forces, what
/// integration reads of the awake bodies, and the step.
pub(crate) struct SolverContext<'a> {
    pub params: &'a SolverParams,
    pub environment: Environment,
    pub drives: &'a [Drive],
    pub dt: Real,
}

/// The awake set's bodies and contacts as the solver takes them.
pub(crate) struct AwakeSet<'a> {
    /// Every body; the awake ones are `bodies[awake]`.
    pub bodies: &'a mut [Body],
    pub awake: Range<usize>,
    /// The awake contacts, and where each one's bodies are among all bodies.
    pub contacts: &'a mut [Contact],
    pub body_indices: &'a [BodyIndices],
    /// Where each colour's contacts (then the overflow's) are among the awake contacts.
    pub colors: &'a ColorRanges,
    /// Every joint; the ones to solve are `awake_joints`.
    pub joints: &'a mut [Joint],
    pub awake_joints: &'a [AwakeJoint],
}

/// A joint to solve: where it is among the joints, and where its bodies are among all bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AwakeJoint {
    pub index: u32,
    pub bodies: [u32; 2],
}

/// What one solver step did: contact points solved, the work of the optional effects, and
/// how long preparing and storing took.
pub(crate) struct StepReport {
    pub points: usize,
    /// Joints solved.
    pub joints: usize,
    pub work: Work,
    pub prepare: Duration,
    pub store: Duration,
}
