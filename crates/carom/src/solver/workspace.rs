//! The solver's memory, kept from step to step.

use super::body_state::{BodyState, Drive};
use super::contact_constraint::{BodyMass, ContactConstraint};
use super::joints::JointConstraint;
use super::soft_step::{JointTrees, ShockPropagation, Stage, WideContacts};
use crate::capacity::room;
use crate::graph::joints::JointColors;
use crate::graph::order::ContactGraph;
use std::collections::TryReserveError;

/// The solver's memory, kept from step to step so a step in steady state allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct Workspace {
    /// The awake bodies' states and masses, then the spare state's, and what integration
    /// reads of each awake body.
    pub(super) states: Vec<BodyState>,
    pub(super) masses: Vec<BodyMass>,
    pub(super) drives: Vec<Drive>,
    /// The constraints solved one at a time: every touching contact for the classic solvers
    /// and for soft step without colours, the overflow's with them.
    pub(super) constraints: Vec<ContactConstraint>,
    pub(super) graph: ContactGraph,
    /// Soft step's coloured constraints, in SIMD bundles, and its list of stages.
    pub(super) wide: WideContacts,
    pub(super) plan: Vec<Stage>,
    /// The order the touching contacts are solved in (indices into the awake contacts).
    pub(super) order: Vec<usize>,
    /// While the order is checked: the colour (plus one) that last claimed each awake body,
    /// and the contacts sent to the overflow because their colour had claimed a body already.
    pub(super) claims: Vec<u8>,
    pub(super) demoted: Vec<usize>,
    /// The awake joints prepared for the step, sorted by colour for soft step.
    pub(super) joints: Vec<JointConstraint>,
    pub(super) joint_colors: JointColors,
    /// Soft step's joint trees, solved exactly ([`crate::SolverParams::direct_joints`]).
    pub(super) joint_trees: JointTrees,
    /// Soft step's contacts between levels ([`crate::SolverParams::shock_propagation`]).
    pub(super) shock: ShockPropagation,
}

impl Workspace {
    /// Makes room for a step of `bodies` awake bodies, `contacts` touching contacts and
    /// `joints` awake joints.
    pub(crate) fn reserve(
        &mut self,
        bodies: usize,
        contacts: usize,
        joints: usize,
    ) -> Result<(), TryReserveError> {
        // The states end with the spare one, shared by static bodies and empty lanes.
        room(&mut self.states, bodies.saturating_add(1))?;
        room(&mut self.masses, bodies.saturating_add(1))?;
        room(&mut self.drives, bodies)?;
        room(&mut self.constraints, contacts)?;
        room(&mut self.graph.overflow, contacts)?;
        self.wide.reserve(contacts)?;
        room(&mut self.order, contacts)?;
        room(&mut self.claims, bodies)?;
        room(&mut self.demoted, contacts)?;
        room(&mut self.joints, joints)?;
        self.joint_colors.reserve(joints, bodies.saturating_add(1))
    }

    /// With direct joints, after a step: each awake body's group of bodies joined by hinges
    /// (a representative state index, by state index), for continuous collision to put a
    /// group back together.
    pub(crate) fn joint_groups(&self) -> Option<&[u32]> {
        self.joint_trees.groups()
    }
}
