//! The SIMD kernels: one bundle of [`Lanes::WIDTH`] contact constraints, laid out as
//! structures of arrays, prepared, warm started, solved, bounced and stored four or eight
//! lanes at a time. The arithmetic per lane is the scalar path's ([`super::scalar`]) operation
//! for operation, summed in the same order, so a lane gives the scalar result bit for bit
//! (where a lane is as wide as [`Real`]: not in the double-precision build).

use super::inputs::{BundleInputs, PassBias};
use super::lanes::{Lane, Lanes};
use super::shared_states::SharedStates;
use crate::collision::contact::{Contact, PointImpulse};
use crate::math::Real;
use crate::solver::contact_constraint::{ConstraintPoint, rolling};
use crate::solver::params::Softness;

/// One contact point of a bundle's constraints.
#[derive(Debug, Clone, Copy)]
pub(super) struct WidePoint<L> {
    pub(super) anchor_a_x: L,
    pub(super) anchor_a_y: L,
    pub(super) anchor_b_x: L,
    pub(super) anchor_b_y: L,
    pub(super) base_separation: L,
    pub(super) normal_mass: L,
    pub(super) tangent_mass: L,
    pub(super) normal_impulse: L,
    pub(super) tangent_impulse: L,
    pub(super) total_normal_impulse: L,
    pub(super) max_normal_impulse: L,
    pub(super) relative_velocity: L,
}

impl<L: Lanes> WidePoint<L> {
    /// Puts a prepared point in `lane`.
    #[inline(always)]
    fn set_lane(&mut self, lane: usize, p: &ConstraintPoint) {
        let values = [
            p.anchor_a.x,
            p.anchor_a.y,
            p.anchor_b.x,
            p.anchor_b.y,
            p.base_separation,
            p.normal_mass,
            p.tangent_mass,
            p.normal_impulse,
            p.tangent_impulse,
            p.total_normal_impulse,
            p.max_normal_impulse,
            p.relative_velocity,
        ];
        let fields = [
            &mut self.anchor_a_x,
            &mut self.anchor_a_y,
            &mut self.anchor_b_x,
            &mut self.anchor_b_y,
            &mut self.base_separation,
            &mut self.normal_mass,
            &mut self.tangent_mass,
            &mut self.normal_impulse,
            &mut self.tangent_impulse,
            &mut self.total_normal_impulse,
            &mut self.max_normal_impulse,
            &mut self.relative_velocity,
        ];
        for (field, value) in fields.into_iter().zip(values) {
            field.lanes_mut()[lane] = value as Lane;
        }
    }
}

/// [`Lanes::WIDTH`] constraints; lanes past the colour's end are empty (zero masses, no
/// impulse, the spare state for both bodies).
#[derive(Debug, Clone, Copy)]
pub(super) struct Bundle<L: Lanes> {
    /// Each lane's contact, an index into the awake contacts (`u32::MAX` when empty).
    pub(super) contacts: L::Indices,
    /// Body states (the spare state for a static body or an empty lane).
    pub(super) a: L::Indices,
    pub(super) b: L::Indices,
    /// One bit per lane: whether A (B) takes impulses (a dynamic body). Only those velocities
    /// are written back, as Box2D skips static ones, so a static or kinematic body's velocity
    /// is never touched (nor shared between threads' caches) whatever the lanes computed.
    pub(super) writes_a: u32,
    pub(super) writes_b: u32,
    /// Manifold points in all lanes (for the step's statistics).
    pub(super) point_count: u32,
    pub(super) inv_mass_a: L,
    pub(super) inv_inertia_a: L,
    pub(super) inv_mass_b: L,
    pub(super) inv_inertia_b: L,
    pub(super) normal_x: L,
    pub(super) normal_y: L,
    pub(super) friction: L,
    pub(super) restitution: L,
    /// The surfaces' tangent speed (conveyor belts).
    pub(super) tangent_speed: L,
    /// Rolling resistance: its coefficient times the rolling radius, the effective mass
    /// against relative spin, and the accumulated angular impulse.
    pub(super) rolling_resistance: L,
    pub(super) rolling_mass: L,
    pub(super) rolling_impulse: L,
    /// Whether any lane has rolling resistance: without, its row is skipped.
    pub(super) rolling: bool,
    /// Soft step's coefficients per lane (stiffer against static bodies).
    pub(super) bias_rate: L,
    pub(super) mass_scale: L,
    pub(super) impulse_scale: L,
    pub(super) points: [WidePoint<L>; 2],
}

/// Four or eight bodies' states in lanes.
#[derive(Debug, Clone, Copy)]
pub(super) struct WideBody<L> {
    v_x: L,
    v_y: L,
    w: L,
    dp_x: L,
    dp_y: L,
    cos: L,
    sin: L,
}

impl<L: Lanes> WideBody<L> {
    /// Gathers the states of bodies `indices`.
    #[inline(always)]
    fn gather(states: &SharedStates, indices: &L::Indices) -> Self {
        let [v_x, v_y, w, _, dp_x, dp_y, cos, sin] = L::gather(states, indices);
        WideBody {
            v_x,
            v_y,
            w,
            dp_x,
            dp_y,
            cos,
            sin,
        }
    }

    /// Writes back the velocities of the lanes set in `lanes` (positions do not change in a
    /// solve).
    #[inline(always)]
    fn scatter(&self, states: &SharedStates, indices: &L::Indices, lanes: u32) {
        L::scatter(states, indices, lanes, [self.v_x, self.v_y, self.w]);
    }

    /// The lanes set in `mask` from `self`, the others from `old`.
    #[inline(always)]
    fn select(self, mask: L, old: Self) -> Self {
        WideBody {
            v_x: mask.select(self.v_x, old.v_x),
            v_y: mask.select(self.v_y, old.v_y),
            w: mask.select(self.w, old.w),
            ..old
        }
    }
}

impl<L: Lanes> Bundle<L> {
    /// A bundle of empty lanes, to be prepared.
    #[inline(always)]
    pub(super) fn empty() -> Self {
        let zero = L::splat(0.0);
        let point = WidePoint {
            anchor_a_x: zero,
            anchor_a_y: zero,
            anchor_b_x: zero,
            anchor_b_y: zero,
            base_separation: zero,
            normal_mass: zero,
            tangent_mass: zero,
            normal_impulse: zero,
            tangent_impulse: zero,
            total_normal_impulse: zero,
            max_normal_impulse: zero,
            relative_velocity: zero,
        };
        Bundle {
            contacts: L::Indices::default(),
            a: L::Indices::default(),
            b: L::Indices::default(),
            writes_a: 0,
            writes_b: 0,
            point_count: 0,
            inv_mass_a: zero,
            inv_inertia_a: zero,
            inv_mass_b: zero,
            inv_inertia_b: zero,
            normal_x: zero,
            normal_y: zero,
            friction: zero,
            restitution: zero,
            tangent_speed: zero,
            rolling_resistance: zero,
            rolling_mass: zero,
            rolling_impulse: zero,
            rolling: false,
            bias_rate: zero,
            mass_scale: zero,
            impulse_scale: zero,
            points: [point; 2],
        }
    }

    /// Prepares the contacts `members` (up to [`Lanes::WIDTH`]) in place, one float at a
    /// time into its lane, as Box2D does (building whole constraints and packing them moved
    /// more memory than the arithmetic costs); `softness` is for moving and static partners.
    #[inline(always)]
    pub(super) fn prepare(
        &mut self,
        inputs: &BundleInputs,
        members: &[usize],
        softness: [Softness; 2],
        spare: u32,
    ) {
        (self.writes_a, self.writes_b, self.point_count) = (0, 0, 0);
        self.rolling = false;
        for lane in 0..L::WIDTH {
            let Some(&index) = members.get(lane) else {
                self.clear_lane(lane, spare);
                continue;
            };
            let contact = &inputs.contacts[index];
            let manifold = contact.manifold();
            let [a, b] = inputs.body_indices[index].map(|i| i as usize);
            let (a, b) = (inputs.solver_body(a), inputs.solver_body(b));
            self.contacts.as_mut()[lane] = index as u32;
            self.a.as_mut()[lane] = a.index as u32;
            self.b.as_mut()[lane] = b.index as u32;
            self.writes_a |= u32::from(a.mass.dynamic) << lane;
            self.writes_b |= u32::from(b.mass.dynamic) << lane;
            let soft = softness[usize::from(!a.awake || !b.awake)];
            let normal = manifold.normal;
            let (rolling_mass, mut rolling_impulse) =
                rolling(contact, a.mass.inv_inertia, b.mass.inv_inertia);
            if !inputs.warm_starting {
                rolling_impulse = 0.0;
            }
            self.rolling |= rolling_mass > 0.0;
            let values = [
                a.mass.inv_mass,
                a.mass.inv_inertia,
                b.mass.inv_mass,
                b.mass.inv_inertia,
                normal.x,
                normal.y,
                contact.friction(),
                contact.restitution(),
                contact.tangent_speed(),
                contact.rolling_resistance(),
                rolling_mass,
                rolling_impulse,
                soft.bias_rate,
                soft.mass_scale,
                soft.impulse_scale,
            ];
            for (field, value) in self.fields_mut().into_iter().zip(values) {
                field.lanes_mut()[lane] = value as Lane;
            }
            let points = manifold.points();
            self.point_count += points.len() as u32;
            for (j, wide) in self.points.iter_mut().enumerate() {
                // A missing point keeps zero mass: it never takes an impulse.
                let mut p = points.get(j).map_or_else(ConstraintPoint::default, |mp| {
                    ConstraintPoint::new(mp, normal, &a, &b)
                });
                if !inputs.warm_starting {
                    (p.normal_impulse, p.tangent_impulse) = (0.0, 0.0);
                }
                wide.set_lane(lane, &p);
            }
        }
    }

    /// Makes `lane` empty: no contact, the spare state on both sides, zero masses and impulses.
    #[inline(always)]
    pub(super) fn clear_lane(&mut self, lane: usize, spare: u32) {
        self.contacts.as_mut()[lane] = u32::MAX;
        self.a.as_mut()[lane] = spare;
        self.b.as_mut()[lane] = spare;
        for field in self.fields_mut() {
            field.lanes_mut()[lane] = 0.0;
        }
        for wide in &mut self.points {
            wide.set_lane(lane, &ConstraintPoint::default());
        }
    }

    /// The per-constraint fields, in the order `prepare` fills them.
    #[inline(always)]
    pub(super) fn fields_mut(&mut self) -> [&mut L; 15] {
        [
            &mut self.inv_mass_a,
            &mut self.inv_inertia_a,
            &mut self.inv_mass_b,
            &mut self.inv_inertia_b,
            &mut self.normal_x,
            &mut self.normal_y,
            &mut self.friction,
            &mut self.restitution,
            &mut self.tangent_speed,
            &mut self.rolling_resistance,
            &mut self.rolling_mass,
            &mut self.rolling_impulse,
            &mut self.bias_rate,
            &mut self.mass_scale,
            &mut self.impulse_scale,
        ]
    }

    /// Gathers both sides' bodies.
    #[inline(always)]
    pub(super) fn bodies(&self, states: &SharedStates) -> (WideBody<L>, WideBody<L>) {
        (
            WideBody::gather(states, &self.a),
            WideBody::gather(states, &self.b),
        )
    }

    /// Writes back both sides' moving bodies (a colour's moving bodies are distinct, so no two
    /// written lanes share a state).
    #[inline(always)]
    pub(super) fn write(&self, states: &SharedStates, a: &WideBody<L>, b: &WideBody<L>) {
        a.scatter(states, &self.a, self.writes_a);
        b.scatter(states, &self.b, self.writes_b);
    }

    /// Applies the bundle's accumulated impulses (and counts them as pushed this step).
    #[inline(always)]
    pub(super) fn warm_start(&mut self, states: &SharedStates) {
        let (mut a, mut b) = self.bodies(states);
        let (tangent_x, tangent_y) = (self.normal_y, -self.normal_x);
        for j in 0..2 {
            let point = self.points[j];
            let p_x = self.normal_x * point.normal_impulse + tangent_x * point.tangent_impulse;
            let p_y = self.normal_y * point.normal_impulse + tangent_y * point.tangent_impulse;
            self.apply(&point, p_x, p_y, &mut a, &mut b);
            self.points[j].total_normal_impulse += point.normal_impulse;
        }
        if self.rolling {
            a.w -= self.inv_inertia_a * self.rolling_impulse;
            b.w += self.inv_inertia_b * self.rolling_impulse;
        }
        self.write(states, &a, &b);
    }

    /// Solves the bundle's constraints once.
    #[inline(always)]
    pub(super) fn solve(&mut self, states: &SharedStates, pass: PassBias, friction: bool) {
        let zero = L::splat(0.0);
        let one = L::splat(1.0);
        let inv_h = L::splat(pass.inv_h as Lane);
        let max_push = L::splat(-pass.max_push_speed as Lane);
        let (mut a, mut b) = self.bodies(states);
        let (normal_x, normal_y) = (self.normal_x, self.normal_y);
        for j in 0..2 {
            let point = self.points[j];
            // Separation now: the anchors turned by the rotation since the step began.
            let ra_x = a.cos * point.anchor_a_x - a.sin * point.anchor_a_y;
            let ra_y = a.sin * point.anchor_a_x + a.cos * point.anchor_a_y;
            let rb_x = b.cos * point.anchor_b_x - b.sin * point.anchor_b_y;
            let rb_y = b.sin * point.anchor_b_x + b.cos * point.anchor_b_y;
            let d_x = (b.dp_x - a.dp_x) + rb_x - ra_x;
            let d_y = (b.dp_y - a.dp_y) + rb_y - ra_y;
            let s = point.base_separation + (normal_x * d_x + normal_y * d_y);
            let speculative = s.gt(zero);
            let (bias, mass_scale, impulse_scale) = if pass.use_bias {
                (
                    (self.mass_scale * self.bias_rate * s).max(max_push),
                    self.mass_scale,
                    self.impulse_scale,
                )
            } else {
                (zero, one, zero)
            };
            let bias = speculative.select(s * inv_h, bias);
            let mass_scale = speculative.select(one, mass_scale);
            let impulse_scale = speculative.select(zero, impulse_scale);
            let vn = relative_velocity(&point, &a, &b, normal_x, normal_y);
            let impulse = -point.normal_mass * (mass_scale * vn + bias)
                - impulse_scale * point.normal_impulse;
            let total = (point.normal_impulse + impulse).max(zero);
            let applied = total - point.normal_impulse;
            let point = &mut self.points[j];
            point.normal_impulse = total;
            point.total_normal_impulse += applied;
            if pass.substep_end {
                point.max_normal_impulse = point.max_normal_impulse.max(total);
            }
            let point = *point;
            self.apply(
                &point,
                normal_x * applied,
                normal_y * applied,
                &mut a,
                &mut b,
            );
        }
        if friction {
            let (tangent_x, tangent_y) = (normal_y, -normal_x);
            for j in 0..2 {
                let point = self.points[j];
                let vt =
                    relative_velocity(&point, &a, &b, tangent_x, tangent_y) - self.tangent_speed;
                let limit = self.friction * point.normal_impulse;
                let total = (point.tangent_impulse - point.tangent_mass * vt)
                    .max(-limit)
                    .min(limit);
                let applied = total - point.tangent_impulse;
                self.points[j].tangent_impulse = total;
                self.apply(
                    &point,
                    tangent_x * applied,
                    tangent_y * applied,
                    &mut a,
                    &mut b,
                );
            }
            if self.rolling {
                let pressed = self.points[0].normal_impulse + self.points[1].normal_impulse;
                let limit = self.rolling_resistance * pressed;
                let spin = b.w - a.w;
                let total = (self.rolling_impulse - self.rolling_mass * spin)
                    .max(-limit)
                    .min(limit);
                let applied = total - self.rolling_impulse;
                self.rolling_impulse = total;
                a.w -= self.inv_inertia_a * applied;
                b.w += self.inv_inertia_b * applied;
            }
        }
        self.write(states, &a, &b);
    }

    /// Bounces the points that approached faster than `threshold` and pushed this step;
    /// returns how many.
    #[inline(always)]
    pub(super) fn restitution(&mut self, states: &SharedStates, threshold: Real) -> usize {
        let zero = L::splat(0.0);
        let bouncy = self.restitution.gt(zero);
        if bouncy.bits() == 0 {
            return 0;
        }
        let (mut a, mut b) = self.bodies(states);
        let mut bounced = 0;
        for j in 0..2 {
            let point = self.points[j];
            let slow = point.relative_velocity.gt(L::splat(-threshold as Lane));
            let pushed = point.total_normal_impulse.ne(zero).and(bouncy);
            let bounce = slow.select(zero, pushed);
            let lanes = bounce.bits();
            if lanes == 0 {
                continue;
            }
            bounced += lanes.count_ones() as usize;
            let vn = relative_velocity(&point, &a, &b, self.normal_x, self.normal_y);
            let impulse = -point.normal_mass * (vn + self.restitution * point.relative_velocity);
            let total = (point.normal_impulse + impulse).max(zero);
            let applied = total - point.normal_impulse;
            let point = &mut self.points[j];
            point.normal_impulse = bounce.select(total, point.normal_impulse);
            point.total_normal_impulse = bounce.select(
                point.total_normal_impulse + applied,
                point.total_normal_impulse,
            );
            point.max_normal_impulse = bounce.select(
                point.max_normal_impulse.max(total),
                point.max_normal_impulse,
            );
            let point = *point;
            let (old_a, old_b) = (a, b);
            let (p_x, p_y) = (self.normal_x * applied, self.normal_y * applied);
            self.apply(&point, p_x, p_y, &mut a, &mut b);
            // Lanes that do not bounce keep their velocities bit for bit.
            a = a.select(bounce, old_a);
            b = b.select(bounce, old_b);
        }
        self.write(states, &a, &b);
        bounced
    }

    /// Applies the impulse `(p_x, p_y)` at a point: minus to A, plus to B.
    #[inline(always)]
    pub(super) fn apply(
        &self,
        point: &WidePoint<L>,
        p_x: L,
        p_y: L,
        a: &mut WideBody<L>,
        b: &mut WideBody<L>,
    ) {
        a.v_x -= self.inv_mass_a * p_x;
        a.v_y -= self.inv_mass_a * p_y;
        a.w -= self.inv_inertia_a * (point.anchor_a_x * p_y - point.anchor_a_y * p_x);
        b.v_x += self.inv_mass_b * p_x;
        b.v_y += self.inv_mass_b * p_y;
        b.w += self.inv_inertia_b * (point.anchor_b_x * p_y - point.anchor_b_y * p_x);
    }

    /// The first lane's contact (every prepared bundle has one).
    pub(super) fn first_contact(&self) -> usize {
        self.contacts.as_ref()[0] as usize
    }

    /// The last filled lane's contact.
    pub(super) fn last_contact(&self) -> usize {
        let lanes = self.contacts.as_ref().iter();
        lanes
            .filter(|&&i| i != u32::MAX)
            .max()
            .copied()
            .unwrap_or(0) as usize
    }

    /// Copies the lanes' impulses into their contacts' manifolds (`contacts` begin at contact
    /// `offset`), and what the step applied and the approach it started from beside them.
    #[inline(always)]
    pub(super) fn store(&self, contacts: &mut [Contact], offset: usize) {
        let mut rolling = [0.0; 8];
        self.rolling_impulse.write_to(&mut rolling);
        let mut impulses = [[[0.0; 8]; 5]; 2];
        for (j, point) in self.points.iter().enumerate() {
            point.normal_impulse.write_to(&mut impulses[j][0]);
            point.tangent_impulse.write_to(&mut impulses[j][1]);
            point.total_normal_impulse.write_to(&mut impulses[j][2]);
            point.max_normal_impulse.write_to(&mut impulses[j][3]);
            point.relative_velocity.write_to(&mut impulses[j][4]);
        }
        for (lane, &index) in self.contacts.as_ref().iter().enumerate() {
            // Empty lanes name no contact (`u32::MAX`).
            let Some(contact) = (index as usize)
                .checked_sub(offset)
                .and_then(|i| contacts.get_mut(i))
            else {
                continue;
            };
            contact.rolling_impulse = rolling[lane] as Real;
            let (manifold, reports) = contact.manifold_and_impulses_mut();
            let points = manifold.points_mut().iter_mut().zip(reports);
            for (j, (point, report)) in points.enumerate() {
                let impulse = |k: usize| impulses[j][k][lane] as Real;
                point.normal_impulse = impulse(0);
                point.tangent_impulse = impulse(1);
                *report = PointImpulse {
                    total_normal_impulse: impulse(2),
                    max_normal_impulse: impulse(3),
                    normal_velocity: impulse(4),
                };
            }
        }
    }
}

/// Velocity of B relative to A at a point, along `(dir_x, dir_y)`.
#[inline(always)]
fn relative_velocity<L: Lanes>(
    point: &WidePoint<L>,
    a: &WideBody<L>,
    b: &WideBody<L>,
    dir_x: L,
    dir_y: L,
) -> L {
    let dv_x = (b.v_x - b.w * point.anchor_b_y) - (a.v_x - a.w * point.anchor_a_y);
    let dv_y = (b.v_y + b.w * point.anchor_b_x) - (a.v_y + a.w * point.anchor_a_x);
    dv_x * dir_x + dv_y * dir_y
}
