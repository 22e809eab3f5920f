//! Shock propagation's supports in SIMD bundles ([`super::shock_propagation`]).
//!
//! A support moves only its upper body and reads its lower one, which lies on a lower level
//! and is never moved in the same level's pass. So within one level, supports of different
//! upper bodies commute exactly, and each level's supports are solved [`Lanes::WIDTH`] at a
//! time: the `k`-th support of each upper body goes in the level's `k`-th round, so an upper
//! body appears once in a round and its own supports keep their order. A lane gives the scalar
//! support's result bit for bit (tested; in the double-precision build, whose lanes are
//! single, to single precision), so the bundles change the cost, not the answer.

#[cfg(target_arch = "x86_64")]
use super::bundles::Width;
#[cfg(target_arch = "x86_64")]
use super::lanes::avx::Avx8;
use super::lanes::{Four, Kernel, Lane, Lanes};
use super::shared_states::SharedStates;
use super::shock_propagation::{Support, SupportPoint};
use crate::math::Real;
use std::ops::Range;

/// The supports of a step in bundles, level by level and round by round.
#[derive(Debug, Clone)]
pub(crate) enum ShockBundles {
    Four(Vec<ShockBundle<Four>>),
    #[cfg(target_arch = "x86_64")]
    Eight(Vec<ShockBundle<Avx8>>),
}

impl Default for ShockBundles {
    fn default() -> Self {
        #[cfg(target_arch = "x86_64")]
        if Width::widest() == Width::Eight && !test_hooks::FOUR_LANES.get() {
            return ShockBundles::Eight(Vec::new());
        }
        ShockBundles::Four(Vec::new())
    }
}

/// What the tests of shock propagation set on their own thread: four lanes where eight would
/// be taken, or every support one at a time; and how many bundles were made.
#[cfg(test)]
pub(crate) mod test_hooks {
    use std::cell::Cell;

    thread_local! {
        pub static FOUR_LANES: Cell<bool> = const { Cell::new(false) };
        pub static ONE_AT_A_TIME: Cell<bool> = const { Cell::new(false) };
        pub static BUNDLES_MADE: Cell<usize> = const { Cell::new(0) };
    }
}

/// Outside the tests, the hooks are always off.
#[cfg(not(test))]
pub(crate) mod test_hooks {
    /// A hook that is never set.
    pub(crate) struct Off;

    impl Off {
        #[inline(always)]
        pub(crate) fn get(&self) -> bool {
            false
        }
    }

    #[cfg(target_arch = "x86_64")]
    pub(crate) const FOUR_LANES: Off = Off;
    pub(crate) const ONE_AT_A_TIME: Off = Off;
}

/// Evaluates `$body` with `$bundles` bound to the bundles of whichever width they are.
macro_rules! with_shock_bundles {
    ($bundles:expr, |$b:ident| $body:expr) => {
        match $bundles {
            ShockBundles::Four($b) => $body,
            #[cfg(target_arch = "x86_64")]
            ShockBundles::Eight($b) => $body,
        }
    };
}

impl ShockBundles {
    /// No bundles.
    pub(crate) fn clear(&mut self) {
        with_shock_bundles!(self, |bundles| bundles.clear())
    }

    /// Adds bundles of the supports `members` (of one level's round: different upper
    /// bodies); `spare` is the state of empty lanes. Returns the bundles' range.
    pub(crate) fn push(
        &mut self,
        supports: &[Support],
        members: &[u32],
        spare: u32,
    ) -> Range<usize> {
        with_shock_bundles!(self, |bundles| {
            let start = bundles.len();
            for lanes in members.chunks(lanes_of(bundles)) {
                bundles.push(ShockBundle::of(supports, lanes, spare));
            }
            #[cfg(test)]
            test_hooks::BUNDLES_MADE.set(test_hooks::BUNDLES_MADE.get() + bundles.len() - start);
            start..bundles.len()
        })
    }

    /// Applies the accumulated pushes of bundles `range`.
    pub(crate) fn warm_start(&mut self, states: &SharedStates, range: Range<usize>) {
        with_shock_bundles!(self, |bundles| run_pass(&mut bundles[range], states, None))
    }

    /// One pass over bundles `range`, biased or relaxing, with friction or not.
    pub(crate) fn solve(&mut self, states: &SharedStates, range: Range<usize>, bias: PassInputs) {
        with_shock_bundles!(self, |bundles| {
            run_pass(&mut bundles[range], states, Some(bias))
        })
    }

    /// Copies the lanes' impulses back into `supports`.
    pub(crate) fn unpack(&self, supports: &mut [Support]) {
        with_shock_bundles!(self, |bundles| {
            for bundle in bundles {
                bundle.unpack(supports);
            }
        })
    }
}

/// What a solve pass needs of the step's bias.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PassInputs {
    pub use_bias: bool,
    pub friction: bool,
    pub inv_h: Real,
    pub max_push_speed: Real,
    /// The softness of contacts between moving bodies.
    pub bias_rate: Real,
    pub mass_scale: Real,
    pub impulse_scale: Real,
}

/// [`Lanes::WIDTH`] of bundles of `L`.
fn lanes_of<L: Lanes>(_: &[ShockBundle<L>]) -> usize {
    L::WIDTH
}

fn run_pass<L: Lanes>(
    bundles: &mut [ShockBundle<L>],
    states: &SharedStates,
    bias: Option<PassInputs>,
) {
    L::run(ShockPass {
        bundles,
        states,
        bias,
    });
}

/// A pass over the bundles, compiled for their lanes.
struct ShockPass<'a, L: Lanes> {
    bundles: &'a mut [ShockBundle<L>],
    states: &'a SharedStates<'a>,
    /// `None`: the warm start.
    bias: Option<PassInputs>,
}

impl<L: Lanes> Kernel for ShockPass<'_, L> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        match self.bias {
            None => {
                for bundle in self.bundles.iter_mut() {
                    bundle.warm_start(self.states);
                }
            }
            Some(bias) => {
                for bundle in self.bundles.iter_mut() {
                    bundle.solve(self.states, &bias);
                }
            }
        }
    }
}

/// One point of a bundle's supports.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ShockPoint<L> {
    anchor_a_x: L,
    anchor_a_y: L,
    anchor_b_x: L,
    anchor_b_y: L,
    base_separation: L,
    normal_mass: L,
    tangent_mass: L,
    normal_impulse: L,
    tangent_impulse: L,
    total_normal_impulse: L,
    /// A mask: the lanes whose support has this point.
    present: L,
}

/// [`Lanes::WIDTH`] supports of different upper bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ShockBundle<L: Lanes> {
    /// Each lane's support (`u32::MAX` when empty).
    supports: L::Indices,
    /// The bodies' states, A and B as in the contact (the spare state in an empty lane).
    a: L::Indices,
    b: L::Indices,
    /// The upper body's state, and one bit per lane that has a support.
    upper: L::Indices,
    writes: u32,
    /// Masks: the lanes whose upper body is B, and those whose upper body is A.
    upper_b: L,
    upper_a: L,
    inv_mass: L,
    inv_inertia: L,
    normal_x: L,
    normal_y: L,
    friction: L,
    tangent_speed: L,
    /// Whether any lane has a second point.
    two_points: bool,
    points: [ShockPoint<L>; 2],
}

/// A lane's pair of bodies' velocities and motion since the step began.
#[derive(Clone, Copy)]
struct Side<L> {
    v_x: L,
    v_y: L,
    w: L,
    dp_x: L,
    dp_y: L,
    cos: L,
    sin: L,
}

impl<L: Lanes> Side<L> {
    #[inline(always)]
    fn gather(states: &SharedStates, indices: &L::Indices) -> Self {
        let [v_x, v_y, w, _, dp_x, dp_y, cos, sin] = L::gather(states, indices);
        Side {
            v_x,
            v_y,
            w,
            dp_x,
            dp_y,
            cos,
            sin,
        }
    }

    /// Velocity at a point `(r_x, r_y)` from the centre, along `(d_x, d_y)`.
    #[inline(always)]
    fn along(&self, r_x: L, r_y: L, d_x: L, d_y: L) -> L {
        (self.v_x - self.w * r_y) * d_x + (self.v_y + self.w * r_x) * d_y
    }
}

/// `x.clamp(low, high)` lane by lane, as the scalar `clamp` decides it.
#[inline(always)]
fn clamp<L: Lanes>(x: L, low: L, high: L) -> L {
    let x = low.gt(x).select(low, x);
    x.gt(high).select(high, x)
}

impl<L: Lanes> ShockBundle<L> {
    /// The supports `members` (up to [`Lanes::WIDTH`], of different upper bodies) in lanes.
    fn of(supports: &[Support], members: &[u32], spare: u32) -> Self {
        let zero = L::splat(0.0);
        let point = ShockPoint {
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
            present: zero,
        };
        let mut bundle = ShockBundle {
            supports: L::Indices::default(),
            a: L::Indices::default(),
            b: L::Indices::default(),
            upper: L::Indices::default(),
            writes: 0,
            upper_b: zero,
            upper_a: zero,
            inv_mass: zero,
            inv_inertia: zero,
            normal_x: zero,
            normal_y: zero,
            friction: zero,
            tangent_speed: zero,
            two_points: false,
            points: [point; 2],
        };
        let set = Lane::from_bits(!0);
        for lane in 0..L::WIDTH {
            let Some(&index) = members.get(lane) else {
                bundle.supports.as_mut()[lane] = u32::MAX;
                for indices in [&mut bundle.a, &mut bundle.b, &mut bundle.upper] {
                    indices.as_mut()[lane] = spare;
                }
                continue;
            };
            let s = &supports[index as usize];
            bundle.supports.as_mut()[lane] = index;
            bundle.a.as_mut()[lane] = s.a as u32;
            bundle.b.as_mut()[lane] = s.b as u32;
            bundle.upper.as_mut()[lane] = if s.upper_b { s.b } else { s.a } as u32;
            bundle.writes |= 1 << lane;
            let values = [
                if s.upper_b { set } else { 0.0 },
                if s.upper_b { 0.0 } else { set },
                s.inv_mass as Lane,
                s.inv_inertia as Lane,
                s.normal.x as Lane,
                s.normal.y as Lane,
                s.friction as Lane,
                s.tangent_speed as Lane,
            ];
            let fields = [
                &mut bundle.upper_b,
                &mut bundle.upper_a,
                &mut bundle.inv_mass,
                &mut bundle.inv_inertia,
                &mut bundle.normal_x,
                &mut bundle.normal_y,
                &mut bundle.friction,
                &mut bundle.tangent_speed,
            ];
            for (field, value) in fields.into_iter().zip(values) {
                field.lanes_mut()[lane] = value;
            }
            bundle.two_points |= s.point_count == 2;
            for (j, wide) in bundle.points.iter_mut().enumerate() {
                let Some(p) = s.points().get(j) else {
                    continue;
                };
                let values = [
                    p.anchor_a.x as Lane,
                    p.anchor_a.y as Lane,
                    p.anchor_b.x as Lane,
                    p.anchor_b.y as Lane,
                    p.base_separation as Lane,
                    p.normal_mass as Lane,
                    p.tangent_mass as Lane,
                    p.normal_impulse as Lane,
                    p.tangent_impulse as Lane,
                    p.total_normal_impulse as Lane,
                    set,
                ];
                let fields = [
                    &mut wide.anchor_a_x,
                    &mut wide.anchor_a_y,
                    &mut wide.anchor_b_x,
                    &mut wide.anchor_b_y,
                    &mut wide.base_separation,
                    &mut wide.normal_mass,
                    &mut wide.tangent_mass,
                    &mut wide.normal_impulse,
                    &mut wide.tangent_impulse,
                    &mut wide.total_normal_impulse,
                    &mut wide.present,
                ];
                for (field, value) in fields.into_iter().zip(values) {
                    field.lanes_mut()[lane] = value;
                }
            }
        }
        bundle
    }

    /// Copies the lanes' impulses back into their supports.
    fn unpack(&self, supports: &mut [Support]) {
        let mut values = [[[0.0; 8]; 3]; 2];
        for (j, point) in self.points.iter().enumerate() {
            point.normal_impulse.write_to(&mut values[j][0]);
            point.tangent_impulse.write_to(&mut values[j][1]);
            point.total_normal_impulse.write_to(&mut values[j][2]);
        }
        for (lane, &index) in self.supports.as_ref().iter().enumerate() {
            let Some(support) = supports.get_mut(index as usize) else {
                continue;
            };
            for (j, point) in support.points_mut().iter_mut().enumerate() {
                let SupportPoint {
                    normal_impulse,
                    tangent_impulse,
                    total_normal_impulse,
                    ..
                } = point;
                *normal_impulse = values[j][0][lane] as Real;
                *tangent_impulse = values[j][1][lane] as Real;
                *total_normal_impulse = values[j][2][lane] as Real;
            }
        }
    }

    /// Both bodies of every lane.
    #[inline(always)]
    fn sides(&self, states: &SharedStates) -> (Side<L>, Side<L>) {
        (Side::gather(states, &self.a), Side::gather(states, &self.b))
    }

    /// Writes back the upper bodies' velocities.
    #[inline(always)]
    fn write(&self, states: &SharedStates, a: &Side<L>, b: &Side<L>) {
        let pick = |from_b: L, from_a: L| self.upper_b.select(from_b, from_a);
        let velocity = [pick(b.v_x, a.v_x), pick(b.v_y, a.v_y), pick(b.w, a.w)];
        L::scatter(states, &self.upper, self.writes, velocity);
    }

    /// Pushes the upper body by `(p_x, p_y)`, along A to B, at point `j`, in the lanes where
    /// `lanes` (a mask) is set.
    #[inline(always)]
    fn push(&self, j: usize, p_x: L, p_y: L, lanes: L, a: &mut Side<L>, b: &mut Side<L>) {
        let point = &self.points[j];
        let upper_b = self.upper_b;
        let (p_x, p_y) = (upper_b.select(p_x, -p_x), upper_b.select(p_y, -p_y));
        let anchor_x = upper_b.select(point.anchor_b_x, point.anchor_a_x);
        let anchor_y = upper_b.select(point.anchor_b_y, point.anchor_a_y);
        let upper = |from_b: L, from_a: L| upper_b.select(from_b, from_a);
        let v_x = upper(b.v_x, a.v_x) + p_x * self.inv_mass;
        let v_y = upper(b.v_y, a.v_y) + p_y * self.inv_mass;
        let w = upper(b.w, a.w) + self.inv_inertia * (anchor_x * p_y - anchor_y * p_x);
        let (on_b, on_a) = (upper_b.and(lanes), self.upper_a.and(lanes));
        b.v_x = on_b.select(v_x, b.v_x);
        b.v_y = on_b.select(v_y, b.v_y);
        b.w = on_b.select(w, b.w);
        a.v_x = on_a.select(v_x, a.v_x);
        a.v_y = on_a.select(v_y, a.v_y);
        a.w = on_a.select(w, a.w);
    }

    #[inline(always)]
    fn warm_start(&mut self, states: &SharedStates) {
        let (mut a, mut b) = self.sides(states);
        let (tangent_x, tangent_y) = (self.normal_y, -self.normal_x);
        for j in 0..self.point_rows() {
            let point = self.points[j];
            let p_x = self.normal_x * point.normal_impulse + tangent_x * point.tangent_impulse;
            let p_y = self.normal_y * point.normal_impulse + tangent_y * point.tangent_impulse;
            self.push(j, p_x, p_y, point.present, &mut a, &mut b);
            let point = &mut self.points[j];
            point.total_normal_impulse = point.present.select(
                point.total_normal_impulse + point.normal_impulse,
                point.total_normal_impulse,
            );
        }
        self.write(states, &a, &b);
    }

    /// One pass over the supports: each stops its upper body on the lower one as a soft
    /// contact with the ground would, then (with friction) holds it within `μ ×` that push.
    #[inline(always)]
    fn solve(&mut self, states: &SharedStates, bias: &PassInputs) {
        let zero = L::splat(0.0);
        let one = L::splat(1.0);
        let (mut a, mut b) = self.sides(states);
        let (normal_x, normal_y) = (self.normal_x, self.normal_y);
        let upper_b = self.upper_b;
        let rows = self.point_rows();
        for j in 0..rows {
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
            let (velocity_bias, mass_scale, impulse_scale) = if bias.use_bias {
                let mass_scale = L::splat(bias.mass_scale as Lane);
                let rate = mass_scale * L::splat(bias.bias_rate as Lane);
                (
                    (rate * s).max(L::splat(-bias.max_push_speed as Lane)),
                    mass_scale,
                    L::splat(bias.impulse_scale as Lane),
                )
            } else {
                (zero, one, zero)
            };
            let velocity_bias = speculative.select(s * L::splat(bias.inv_h as Lane), velocity_bias);
            let mass_scale = speculative.select(one, mass_scale);
            let impulse_scale = speculative.select(zero, impulse_scale);
            // The lower body's motion counts only where it moves away from the upper one.
            let (r_ax, r_ay) = (point.anchor_a_x, point.anchor_a_y);
            let (r_bx, r_by) = (point.anchor_b_x, point.anchor_b_y);
            let va = a.along(r_ax, r_ay, normal_x, normal_y);
            let vb = b.along(r_bx, r_by, normal_x, normal_y);
            let (va, vb) = (
                upper_b.select(va.min(zero), va),
                upper_b.select(vb, vb.max(zero)),
            );
            let impulse = -point.normal_mass * (mass_scale * (vb - va) + velocity_bias)
                - impulse_scale * point.normal_impulse;
            let total = (point.normal_impulse + impulse).max(zero);
            let applied = total - point.normal_impulse;
            let present = point.present;
            let point = &mut self.points[j];
            point.normal_impulse = present.select(total, point.normal_impulse);
            point.total_normal_impulse = present.select(
                point.total_normal_impulse + applied,
                point.total_normal_impulse,
            );
            self.push(
                j,
                normal_x * applied,
                normal_y * applied,
                present,
                &mut a,
                &mut b,
            );
        }
        if bias.friction {
            let (tangent_x, tangent_y) = (normal_y, -normal_x);
            for j in 0..rows {
                let point = self.points[j];
                let (r_ax, r_ay) = (point.anchor_a_x, point.anchor_a_y);
                let (r_bx, r_by) = (point.anchor_b_x, point.anchor_b_y);
                let va = a.along(r_ax, r_ay, tangent_x, tangent_y);
                let vb = b.along(r_bx, r_by, tangent_x, tangent_y);
                // The lower body's sliding counts only the same way as the upper's, slower.
                let (upper, lower) = (upper_b.select(vb, va), upper_b.select(va, vb));
                let backwards = zero.gt(upper);
                let lower = clamp(
                    lower,
                    backwards.select(upper, zero),
                    backwards.select(zero, upper),
                );
                let (va, vb) = (upper_b.select(lower, upper), upper_b.select(upper, lower));
                let vt = vb - va - self.tangent_speed;
                let limit = self.friction * point.normal_impulse;
                let total = clamp(
                    point.tangent_impulse - point.tangent_mass * vt,
                    -limit,
                    limit,
                );
                let applied = total - point.tangent_impulse;
                let present = point.present;
                self.points[j].tangent_impulse = present.select(total, point.tangent_impulse);
                self.push(
                    j,
                    tangent_x * applied,
                    tangent_y * applied,
                    present,
                    &mut a,
                    &mut b,
                );
            }
        }
        self.write(states, &a, &b);
    }

    #[inline(always)]
    fn point_rows(&self) -> usize {
        if self.two_points { 2 } else { 1 }
    }
}
