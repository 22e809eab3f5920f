//! What a step did and what it cost: the figures the demo and the benchmarks show.

use crate::math::Real;
use std::time::Duration;

/// The clock steps are timed by. In a browser (wasm32 with no operating system) the standard
/// clock panics, so there the page's clock (`performance.now()`) stands in.
#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
pub(crate) use std::time::Instant;
#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
pub(crate) use web_time::Instant;

/// Wall-clock time spent in each stage of one step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageTimes {
    /// Finding new pairs and refreshing the trees.
    pub broadphase: Duration,
    /// Building contact manifolds.
    pub narrowphase: Duration,
    /// Integrating and resolving contacts and joints, then placing the moved colliders,
    /// [`StageTimes::prepare`] and [`StageTimes::store`] included.
    pub solve: Duration,
    /// Of `solve`: taking the bodies in and preparing the contact and joint constraints.
    pub prepare: Duration,
    /// Of `solve`: storing the impulses for the next step and writing the bodies back.
    pub store: Duration,
    /// Sweeping fast bodies.
    pub continuous: Duration,
    /// Sleep timers and islands.
    pub sleep: Duration,
    /// The whole step.
    pub total: Duration,
}

/// Work the optional effects did in the last step: zero for effects that are off.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Work {
    /// Gravity terms added to body velocities (one per body per substep).
    pub gravity_terms: usize,
    /// Drag terms applied (one per damped body per substep).
    pub drag_terms: usize,
    /// Tangent (friction) impulses computed.
    pub friction_impulses: usize,
    /// Restitution impulses computed.
    pub restitution_impulses: usize,
    /// Fast bodies swept by continuous collision.
    pub sweeps: usize,
    /// Bodies whose sleep timers were advanced.
    pub sleep_checks: usize,
}

impl std::ops::AddAssign for Work {
    fn add_assign(&mut self, other: Work) {
        self.gravity_terms += other.gravity_terms;
        self.drag_terms += other.drag_terms;
        self.friction_impulses += other.friction_impulses;
        self.restitution_impulses += other.restitution_impulses;
        self.sweeps += other.sweeps;
        self.sleep_checks += other.sleep_checks;
    }
}

/// What the collision stages did in the last step: the counts behind their times, to compare
/// with another engine's on the same scene.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CollisionWork {
    /// Colliders that left their fat boxes and were moved in the broadphase.
    pub proxies_moved: usize,
    /// Pairs of overlapping fat boxes with a moved collider that the pair update met in the
    /// trees (before any test), each pair once.
    pub pair_candidates: usize,
    /// Contacts created for new pairs.
    pub contacts_created: usize,
    /// Contacts destroyed as their fat boxes parted.
    pub contacts_destroyed: usize,
    /// Manifolds computed from the shapes.
    pub manifolds_built: usize,
    /// Manifolds carried along from the last step instead (the pair barely moved).
    pub manifolds_recycled: usize,
    /// Contacts that gained their first points.
    pub touches_began: usize,
    /// Contacts that lost their last points.
    pub touches_ended: usize,
    /// Islands split to find which parts can sleep.
    pub island_splits: usize,
}

/// Counts and measures from the last step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepStats {
    /// Bodies in the world.
    pub bodies: usize,
    /// Bodies asleep after the step.
    pub sleeping_bodies: usize,
    /// Pairs the narrowphase watches.
    pub contacts: usize,
    /// Pairs with contact points.
    pub touching_contacts: usize,
    /// Contact points solved.
    pub contact_points: usize,
    /// Joints solved.
    pub joints: usize,
    /// The deepest overlap among the contacts built this step, m.
    pub max_penetration: Real,
    /// Kinetic energy of the moving bodies after the step, J.
    pub kinetic_energy: Real,
    /// Fast bodies continuous collision moved back to an impact.
    pub continuous_impacts: usize,
    /// Time per stage.
    pub times: StageTimes,
    /// Work done by the optional effects.
    pub work: Work,
    /// What the collision stages did.
    pub collision: CollisionWork,
}
