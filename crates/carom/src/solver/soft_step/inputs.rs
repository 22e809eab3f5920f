//! What soft step's contact passes read: the awake contacts to prepare as constraints
//! ([`BundleInputs`], for the bundles, the overflow and shock propagation's supports) and how
//! a pass treats overlap ([`PassBias`]).

use crate::collision::contact::{BodyIndices, Contact};
use crate::graph::order::ContactGraph;
use crate::math::Real;
use crate::solver::body_state::BodyState;
use crate::solver::contact_constraint::{BodyMass, ContactConstraint, SolverBody};
use crate::solver::params::Softness;
use std::ops::Range;

/// How a pass treats overlap: soft step's biased solve or its relaxation.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PassBias {
    pub use_bias: bool,
    pub inv_h: Real,
    pub max_push_speed: Real,
    /// The substep's last pass: each point's accumulated normal impulse is then what the
    /// substep applied, and the largest is kept for the user.
    pub substep_end: bool,
}

/// What preparing the constraints reads.
pub(crate) struct BundleInputs<'a> {
    /// Where the awake set's bodies are among all bodies (dense indices).
    pub awake: Range<usize>,
    /// The awake bodies' states and masses, then the spare state's (a static body's).
    pub states: &'a [BodyState],
    pub masses: &'a [BodyMass],
    /// The awake contacts, and where each one's bodies are among all bodies.
    pub contacts: &'a [Contact],
    pub body_indices: &'a [BodyIndices],
    /// The solve order (contact indices) and its colours.
    pub order: &'a [usize],
    pub graph: &'a ContactGraph,
    /// Softness against moving and static partners.
    pub soft: Softness,
    pub static_soft: Softness,
    /// Start from last step's impulses (else from zero).
    pub warm_starting: bool,
}

impl BundleInputs<'_> {
    /// A contact's body at dense index `index`, as the solver takes it: its state, or the
    /// spare state (past the awake ones) if it is not in the awake set.
    pub(super) fn solver_body(&self, index: usize) -> SolverBody {
        let awake = self.awake.contains(&index);
        let index = self.state(index);
        let state = &self.states[index];
        SolverBody {
            index,
            mass: self.masses[index],
            v: state.v,
            w: state.w,
            awake,
        }
    }

    /// The state of the body at dense index `index`: its own, or the spare state (past the
    /// awake ones) if it is not in the awake set.
    pub(crate) fn state(&self, index: usize) -> usize {
        if self.awake.contains(&index) {
            index - self.awake.start
        } else {
            self.awake.len()
        }
    }

    /// Contact `index` prepared as a constraint.
    pub(crate) fn constraint(&self, index: usize) -> ContactConstraint {
        let contact = &self.contacts[index];
        let [a, b] = self.body_indices[index].map(|i| self.solver_body(i as usize));
        let mut constraint = ContactConstraint::new(index, contact, a, b);
        if !self.warm_starting {
            for point in constraint.points_mut() {
                point.normal_impulse = 0.0;
                point.tangent_impulse = 0.0;
            }
            constraint.rolling_impulse = 0.0;
        }
        constraint
    }
}
