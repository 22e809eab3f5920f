//! The pre-solve hook: the user's say, contact by contact and step by step, over whether a
//! contact is solved.
//!
//! A world may hold one hook ([`crate::World::set_pre_solve`]). Each step, right after the
//! narrowphase has updated a contact whose manifold has points, speculative ones included, the
//! hook is asked about it if one of its colliders opted in
//! ([`crate::ColliderDef::pre_solve`]), as Box2D's `enablePreSolveEvents`. Answering false
//! disables the contact for this step: its points are dropped, so the solver applies no
//! impulse and nothing is warm started from it next step, it stops touching (an end event if
//! it touched) and leaves its colour and island links, exactly as if the shapes were apart.
//! The next step asks again. One-way platforms are the classic use: solid when the other body
//! comes down onto the top, disabled otherwise.
//!
//! The hook runs inside the narrowphase, on as many threads as it uses, in no set order, so it
//! must be `Send + Sync` and should be a pure function of what it is shown (and of state the
//! user changes only between steps): the world then stays deterministic on any number of
//! threads. Continuous collision leaves out pairs that asked for the hook while one is set:
//! their contacts, which look a step ahead, decide. A world without a hook, or whose colliders
//! do not opt in, asks nothing.

use crate::collision::contact::ContactPair;
use crate::dynamics::body::Body;
use crate::dynamics::collider::Collider;
use crate::geometry::query::manifold::Manifold;
use std::sync::Arc;

/// What the pre-solve hook is shown of a contact about to be solved: which colliders and
/// bodies, where they touch, and the colliders and bodies themselves as the step began (to
/// read a body's rotation, say).
#[derive(Debug, Clone, Copy)]
pub struct PreSolveContact<'a> {
    /// Which colliders and bodies the contact joins.
    pub pair: ContactPair,
    /// Where they touch or are about to: the normal points from the first collider to the
    /// second; points may be speculative (positive separation).
    pub manifold: &'a Manifold,
    /// The first and second colliders.
    pub colliders: [&'a Collider; 2],
    /// Their bodies.
    pub bodies: [&'a Body; 2],
}

/// The hook's signature: true solves the contact this step, false disables it.
type Hook = dyn Fn(&PreSolveContact) -> bool + Send + Sync;

/// A world's pre-solve hook (shared by the world's clones).
#[derive(Clone)]
pub(crate) struct PreSolveHook(Arc<Hook>);

impl PreSolveHook {
    /// Wraps a hook.
    pub(crate) fn new(hook: impl Fn(&PreSolveContact) -> bool + Send + Sync + 'static) -> Self {
        PreSolveHook(Arc::new(hook))
    }

    /// Whether the contact is solved this step.
    #[inline]
    pub(crate) fn allows(&self, contact: &PreSolveContact) -> bool {
        (self.0)(contact)
    }
}

impl std::fmt::Debug for PreSolveHook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("PreSolveHook")
    }
}
