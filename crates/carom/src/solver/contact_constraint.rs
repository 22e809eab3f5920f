//! A touching contact as the solver sees it: fixed anchors, effective masses, impulses.

use super::body_state::BodyState;
use crate::collision::contact::{Contact, PointImpulse};
use crate::dynamics::body::Body;
use crate::geometry::query::manifold::ManifoldPoint;
use crate::math::{Real, Vec2, cross, cross_sv, perp_cw};

/// One point of a contact constraint.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ConstraintPoint {
    /// From A's centre of mass to the contact point, at the start of the step.
    pub anchor_a: Vec2,
    /// From B's centre of mass to the contact point, at the start of the step.
    pub anchor_b: Vec2,
    /// The separation at the start of the step, less the anchors' offset along the normal, so
    /// the current separation is `base_separation + normal · (dp_B + R(dq_B) r_B - dp_A -
    /// R(dq_A) r_A)`, without re-running collision.
    pub base_separation: Real,
    /// The separation at the start of the step.
    pub separation: Real,
    /// `1 / k` along the normal.
    pub normal_mass: Real,
    /// `1 / k` along the tangent.
    pub tangent_mass: Real,
    /// Accumulated normal impulse.
    pub normal_impulse: Real,
    /// Accumulated friction impulse.
    pub tangent_impulse: Real,
    /// The normal impulse applied over the step, warm start included (Box2D's
    /// `totalNormalImpulse`): restitution only acts on points that pushed.
    pub total_normal_impulse: Real,
    /// The most normal impulse applied in one substep (the accumulated impulse at a substep's
    /// end, when the next one starts over from it), reported with the step's total.
    pub max_normal_impulse: Real,
    /// Normal velocity of B relative to A at the start of the step (for restitution).
    pub relative_velocity: Real,
}

impl ConstraintPoint {
    /// A manifold point of a contact of normal `normal` between bodies `a` and `b`.
    #[inline(always)]
    pub(crate) fn new(mp: &ManifoldPoint, normal: Vec2, a: &SolverBody, b: &SolverBody) -> Self {
        let tangent = perp_cw(normal);
        let (ma, ia) = (a.mass.inv_mass, a.mass.inv_inertia);
        let (mb, ib) = (b.mass.inv_mass, b.mass.inv_inertia);
        let (ra, rb) = (mp.anchor_a, mp.anchor_b);
        let k_normal = ma + mb + ia * cross(ra, normal).powi(2) + ib * cross(rb, normal).powi(2);
        let k_tangent = ma + mb + ia * cross(ra, tangent).powi(2) + ib * cross(rb, tangent).powi(2);
        let relative = b.v + cross_sv(b.w, rb) - a.v - cross_sv(a.w, ra);
        ConstraintPoint {
            anchor_a: ra,
            anchor_b: rb,
            base_separation: mp.separation - normal.dot(&(rb - ra)),
            separation: mp.separation,
            normal_mass: if k_normal > 0.0 { 1.0 / k_normal } else { 0.0 },
            tangent_mass: if k_tangent > 0.0 {
                1.0 / k_tangent
            } else {
                0.0
            },
            normal_impulse: mp.normal_impulse,
            tangent_impulse: mp.tangent_impulse,
            total_normal_impulse: 0.0,
            max_normal_impulse: 0.0,
            relative_velocity: normal.dot(&relative),
        }
    }
}

/// A touching contact prepared for solving.
#[derive(Debug, Clone)]
pub(crate) struct ContactConstraint {
    /// Where the contact lives in the contact set.
    pub contact_index: usize,
    /// Body A's index among the solver's states (the spare state if A is not in the awake set).
    pub a: usize,
    /// Body B's index among the solver's states.
    pub b: usize,
    pub inv_mass_a: Real,
    pub inv_inertia_a: Real,
    pub inv_mass_b: Real,
    pub inv_inertia_b: Real,
    /// Unit normal from A to B.
    pub normal: Vec2,
    /// Friction coefficient: the geometric mean of the colliders'.
    pub friction: Real,
    /// Restitution: the larger of the colliders'.
    pub restitution: Real,
    /// The surfaces' speed along the tangent: friction drives the relative tangent velocity
    /// to it instead of to zero.
    pub tangent_speed: Real,
    /// The most rolling-resistance torque per unit normal impulse, m (0: none).
    pub rolling_resistance: Real,
    /// `1 / (iA + iB)`: the effective mass against relative spin (0 without rolling
    /// resistance).
    pub rolling_mass: Real,
    /// The accumulated rolling-resistance angular impulse.
    pub rolling_impulse: Real,
    /// True when one body is static (soft step makes such contacts stiffer).
    pub touches_static: bool,
    points: [ConstraintPoint; 2],
    point_count: usize,
}

/// What a contact's constraint needs of one of its bodies, from the solver's compact arrays:
/// its state's index, mass and velocity. A body outside the awake set (static) is the spare
/// state: at rest, immovable.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SolverBody {
    pub index: usize,
    pub mass: BodyMass,
    pub v: Vec2,
    pub w: Real,
    /// In the awake set (else the spare state of a static body).
    pub awake: bool,
}

/// A body's inverse mass and inertia as the solver takes them (zero for a static or
/// kinematic body), and whether it is dynamic (takes impulses).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct BodyMass {
    pub inv_mass: Real,
    pub inv_inertia: Real,
    pub dynamic: bool,
}

impl BodyMass {
    pub(crate) fn of(body: &Body) -> Self {
        BodyMass {
            inv_mass: body.inv_mass(),
            inv_inertia: body.inv_inertia(),
            dynamic: body.is_dynamic(),
        }
    }
}

impl ContactConstraint {
    /// Prepares a contact (at `contact_index` among the awake contacts) from its manifold and
    /// its mixed material.
    #[inline]
    pub(crate) fn new(
        contact_index: usize,
        contact: &Contact,
        a: SolverBody,
        b: SolverBody,
    ) -> Self {
        let manifold = contact.manifold();
        let normal = manifold.normal;
        let mut points = [ConstraintPoint::default(); 2];
        let point_count = manifold.points().len();
        for (point, mp) in points.iter_mut().zip(manifold.points()) {
            *point = ConstraintPoint::new(mp, normal, &a, &b);
        }
        let (ma, ia) = (a.mass.inv_mass, a.mass.inv_inertia);
        let (mb, ib) = (b.mass.inv_mass, b.mass.inv_inertia);
        let (rolling_mass, rolling_impulse) = rolling(contact, ia, ib);
        ContactConstraint {
            contact_index,
            a: a.index,
            b: b.index,
            inv_mass_a: ma,
            inv_inertia_a: ia,
            inv_mass_b: mb,
            inv_inertia_b: ib,
            normal,
            friction: contact.friction(),
            restitution: contact.restitution(),
            tangent_speed: contact.tangent_speed(),
            rolling_resistance: contact.rolling_resistance(),
            rolling_mass,
            rolling_impulse,
            touches_static: !a.awake || !b.awake,
            points,
            point_count,
        }
    }

    /// The points.
    #[inline]
    pub(crate) fn points(&self) -> &[ConstraintPoint] {
        &self.points[..self.point_count]
    }

    /// The points, mutably.
    #[inline]
    pub(crate) fn points_mut(&mut self) -> &mut [ConstraintPoint] {
        &mut self.points[..self.point_count]
    }

    /// The tangent direction used for friction.
    #[inline]
    pub(crate) fn tangent(&self) -> Vec2 {
        perp_cw(self.normal)
    }

    /// The separation of a point now, from the bodies' motion since the step began.
    #[inline]
    pub(crate) fn current_separation(
        &self,
        point: &ConstraintPoint,
        a: &BodyState,
        b: &BodyState,
    ) -> Real {
        separation_now(
            self.normal,
            point.base_separation,
            point.anchor_a,
            point.anchor_b,
            a,
            b,
        )
    }

    /// Applies an impulse `p` at a point: `-p` to A, `+p` to B.
    #[inline]
    pub(crate) fn apply(
        &self,
        point: &ConstraintPoint,
        p: Vec2,
        a: &mut BodyState,
        b: &mut BodyState,
    ) {
        a.v -= p * self.inv_mass_a;
        a.w -= self.inv_inertia_a * cross(point.anchor_a, p);
        b.v += p * self.inv_mass_b;
        b.w += self.inv_inertia_b * cross(point.anchor_b, p);
    }

    /// Adds `impulse` to point `index`'s accumulated normal impulse, keeping the total from
    /// pulling (≥ 0), and applies what was actually added to the bodies.
    #[inline]
    pub(crate) fn add_normal_impulse(
        &mut self,
        index: usize,
        impulse: Real,
        a: &mut BodyState,
        b: &mut BodyState,
    ) {
        let mut point = self.points[index];
        let total = (point.normal_impulse + impulse).max(0.0);
        let applied = total - point.normal_impulse;
        point.normal_impulse = total;
        point.total_normal_impulse += applied;
        self.apply(&point, self.normal * applied, a, b);
        self.points[index] = point;
    }

    /// Velocity of B relative to A at a point (each body's point velocity first, summed as the
    /// wide solver sums its lanes, so both give the same bits).
    #[inline]
    pub(crate) fn relative_velocity(point: &ConstraintPoint, a: &BodyState, b: &BodyState) -> Vec2 {
        (b.v + cross_sv(b.w, point.anchor_b)) - (a.v + cross_sv(a.w, point.anchor_a))
    }

    /// Copies accumulated impulses back into the contact's manifold for warm starting, and
    /// what the step applied and the approach it started from beside it, for the user.
    pub(crate) fn store_impulses(&self, contact: &mut Contact) {
        contact.rolling_impulse = self.rolling_impulse;
        let (manifold, reports) = contact.manifold_and_impulses_mut();
        for ((mp, report), point) in manifold
            .points_mut()
            .iter_mut()
            .zip(reports)
            .zip(self.points())
        {
            mp.normal_impulse = point.normal_impulse;
            mp.tangent_impulse = point.tangent_impulse;
            *report = PointImpulse {
                total_normal_impulse: point.total_normal_impulse,
                max_normal_impulse: point.max_normal_impulse,
                normal_velocity: point.relative_velocity,
            };
        }
    }

    /// Notes, at the end of a substep, each point's accumulated normal impulse (what the
    /// substep applied, warm start included) as the largest yet if it is.
    #[inline]
    pub(crate) fn note_substep_impulses(&mut self) {
        for point in self.points_mut() {
            point.max_normal_impulse = point.max_normal_impulse.max(point.normal_impulse);
        }
    }
}

/// A contact's rolling-resistance effective mass and warm-start impulse for bodies of
/// inverse inertias `ia` and `ib`: both 0 for a contact without rolling resistance.
#[inline]
pub(crate) fn rolling(contact: &Contact, ia: Real, ib: Real) -> (Real, Real) {
    if contact.rolling_resistance() > 0.0 && ia + ib > 0.0 {
        (1.0 / (ia + ib), contact.rolling_impulse)
    } else {
        (0.0, 0.0)
    }
}

/// The separation now of a point of normal `normal` (A to B), with the separation
/// `base_separation` at the start of the step less the anchors' offset along the normal, from
/// the bodies' motion since the step began.
#[inline]
pub(crate) fn separation_now(
    normal: Vec2,
    base_separation: Real,
    anchor_a: Vec2,
    anchor_b: Vec2,
    a: &BodyState,
    b: &BodyState,
) -> Real {
    let d = (b.dp - a.dp) + b.dq * anchor_b - a.dq * anchor_a;
    base_separation + normal.dot(&d)
}

/// Two distinct states out of one slice, mutably.
#[inline]
pub(crate) fn pair_mut(
    states: &mut [BodyState],
    a: usize,
    b: usize,
) -> (&mut BodyState, &mut BodyState) {
    debug_assert_ne!(a, b);
    if a < b {
        let (low, high) = states.split_at_mut(b);
        (&mut low[a], &mut high[0])
    } else {
        let (low, high) = states.split_at_mut(a);
        (&mut high[0], &mut low[b])
    }
}
