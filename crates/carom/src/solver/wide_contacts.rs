//! Soft step's contact solve four constraints at a time: the constraints of one graph colour
//! (no shared moving body) are packed into bundles of four lanes, stored as structures of
//! arrays, and solved with `wide`'s 4-lane floats. The arithmetic per lane is the scalar
//! solver's ([`super::soft_step`]) operation for operation, summed in the same order, so a lane
//! gives the scalar result bit for bit (tested); only the order of constraints differs (colour
//! by colour).

use super::color_passes::for_each_by_color;
use super::contact_constraint::ContactConstraint;
use super::contact_graph::ContactGraph;
use super::{BodyState, Softness};
use crate::constants::{COLOR_COUNT, ITEMS_PER_TASK};
use crate::math::Real;
use crate::parallel::{for_each_with, map_into};
use std::ops::Range;
use std::sync::atomic::AtomicU32;
use std::sync::atomic::Ordering::Relaxed;
use wide::f32x4;

/// Lanes per bundle.
const LANES: usize = 4;

/// One contact point of four constraints.
#[derive(Debug, Clone, Copy)]
struct WidePoint {
    anchor_a_x: f32x4,
    anchor_a_y: f32x4,
    anchor_b_x: f32x4,
    anchor_b_y: f32x4,
    base_separation: f32x4,
    normal_mass: f32x4,
    tangent_mass: f32x4,
    normal_impulse: f32x4,
    tangent_impulse: f32x4,
    total_normal_impulse: f32x4,
}

/// Four constraints; lanes past the colour's end are empty (zero masses, no impulse).
#[derive(Debug, Clone, Copy)]
struct Bundle {
    /// Indices into the solver's constraint array (`usize::MAX` for an empty lane).
    constraints: [usize; LANES],
    /// Dense body indices (the spare state for an empty lane).
    a: [usize; LANES],
    b: [usize; LANES],
    /// Per lane, whether A and B take impulses (dynamic bodies): only those velocities are
    /// written back, as Box2D skips static ones, so a static or kinematic body's velocity is
    /// never touched (nor shared between threads' caches) whatever the lanes computed.
    writes_a: [bool; LANES],
    writes_b: [bool; LANES],
    inv_mass_a: f32x4,
    inv_inertia_a: f32x4,
    inv_mass_b: f32x4,
    inv_inertia_b: f32x4,
    normal_x: f32x4,
    normal_y: f32x4,
    friction: f32x4,
    /// Soft step's coefficients per lane (stiffer against static bodies).
    bias_rate: f32x4,
    mass_scale: f32x4,
    impulse_scale: f32x4,
    points: [WidePoint; 2],
}

/// Four bodies' states gathered into lanes.
#[derive(Debug, Clone, Copy)]
struct WideBody {
    v_x: f32x4,
    v_y: f32x4,
    w: f32x4,
    dp_x: f32x4,
    dp_y: f32x4,
    cos: f32x4,
    sin: f32x4,
}

impl WideBody {
    /// Positions from the states, velocities from the shared copy.
    #[inline(always)]
    fn gather(
        states: &[BodyState],
        velocities: &SharedVelocities,
        indices: &[usize; LANES],
    ) -> Self {
        let [i0, i1, i2, i3] = *indices;
        let s = [&states[i0], &states[i1], &states[i2], &states[i3]];
        let v = [
            velocities.get(i0),
            velocities.get(i1),
            velocities.get(i2),
            velocities.get(i3),
        ];
        let lanes = |f: fn(&BodyState) -> Real| f32x4::new([f(s[0]), f(s[1]), f(s[2]), f(s[3])]);
        WideBody {
            v_x: f32x4::new([v[0][0], v[1][0], v[2][0], v[3][0]]),
            v_y: f32x4::new([v[0][1], v[1][1], v[2][1], v[3][1]]),
            w: f32x4::new([v[0][2], v[1][2], v[2][2], v[3][2]]),
            dp_x: lanes(|s| s.dp.x),
            dp_y: lanes(|s| s.dp.y),
            cos: lanes(|s| s.dq.re),
            sin: lanes(|s| s.dq.im),
        }
    }

    /// Writes back the velocities of the lanes that take impulses (positions do not change
    /// in a solve).
    #[inline(always)]
    fn scatter(
        &self,
        velocities: &SharedVelocities,
        indices: &[usize; LANES],
        writes: &[bool; LANES],
    ) {
        let (v_x, v_y, w) = (self.v_x.to_array(), self.v_y.to_array(), self.w.to_array());
        for (lane, (&i, &write)) in indices.iter().zip(writes).enumerate() {
            if write {
                velocities.set(i, [v_x[lane], v_y[lane], w[lane]]);
            }
        }
    }
}

/// The bodies' velocities while the colours are solved, readable and writable from several
/// threads: no two bundles of a colour share a moving body, so each velocity has one writer
/// at a time, and relaxed atomics (plain loads and stores on common hardware) are all the
/// synchronisation needed; rayon orders one colour after the other. Static and kinematic bodies
/// are only read.
#[derive(Debug, Default)]
pub(crate) struct SharedVelocities(Vec<[AtomicU32; 3]>);

impl Clone for SharedVelocities {
    /// Scratch memory: a copy starts empty.
    fn clone(&self) -> Self {
        SharedVelocities::default()
    }
}

impl SharedVelocities {
    /// Takes the states' velocities.
    pub fn load(&mut self, states: &[BodyState]) {
        self.0.resize_with(states.len(), Default::default);
        for_each_with(states, &mut self.0, ITEMS_PER_TASK, |state, shared| {
            let [x, y, w] = shared;
            *x.get_mut() = state.v.x.to_bits();
            *y.get_mut() = state.v.y.to_bits();
            *w.get_mut() = state.w.to_bits();
        });
    }

    /// Gives the velocities back to the states.
    pub fn store(&self, states: &mut [BodyState]) {
        for_each_with(&self.0, states, ITEMS_PER_TASK, |shared, state| {
            let [x, y, w] = shared
                .each_ref()
                .map(|value| Real::from_bits(value.load(Relaxed)));
            state.v.x = x;
            state.v.y = y;
            state.w = w;
        });
    }

    #[inline(always)]
    fn get(&self, index: usize) -> [Real; 3] {
        self.0[index]
            .each_ref()
            .map(|x| Real::from_bits(x.load(Relaxed)))
    }

    #[inline(always)]
    fn set(&self, index: usize, velocity: [Real; 3]) {
        for (shared, value) in self.0[index].iter().zip(velocity) {
            shared.store(value.to_bits(), Relaxed);
        }
    }
}

/// The constraints of a step in bundles, colour by colour, and the constraints left over.
#[derive(Debug, Clone, Default)]
pub(crate) struct WideContacts {
    bundles: Vec<Bundle>,
    /// Each colour's bundles, as a range of `bundles`.
    colors: Vec<Range<usize>>,
    /// Per bundle, its colour and where its constraints start in the colour.
    slots: Vec<(usize, usize)>,
    /// Constraints solved one by one (no colour was free).
    pub overflow: Vec<usize>,
}

/// How a pass treats overlap: soft step's biased solve or its relaxation.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PassBias {
    pub use_bias: bool,
    pub inv_h: Real,
    pub max_push_speed: Real,
}

impl WideContacts {
    /// Packs the coloured constraints into bundles, reusing the memory of the last step;
    /// `spare` is the index of a body state that empty lanes read and write (nothing reads it
    /// back).
    pub fn build(
        &mut self,
        constraints: &[ContactConstraint],
        graph: &ContactGraph,
        soft: Softness,
        static_soft: Softness,
        spare: usize,
    ) {
        // Where each bundle's constraints are, then every bundle packed (on all threads).
        self.slots.clear();
        self.colors.clear();
        self.colors.reserve(COLOR_COUNT);
        for (color, members) in graph.colors().enumerate() {
            if members.is_empty() {
                continue;
            }
            let start = self.slots.len();
            self.slots.extend(
                (0..members.len())
                    .step_by(LANES)
                    .map(|offset| (color, offset)),
            );
            self.colors.push(start..self.slots.len());
        }
        let softness = [soft, static_soft];
        let pack = |&(color, offset): &(usize, usize)| {
            let members = graph.color(color);
            let start = members.start + offset;
            let chunk = start..(start + LANES).min(members.end);
            Bundle::pack(constraints, chunk, softness, spare)
        };
        map_into(&self.slots, &mut self.bundles, ITEMS_PER_TASK / LANES, pack);
        self.overflow.clear();
        self.overflow.extend_from_slice(&graph.overflow);
    }

    /// Applies the accumulated impulses (warm start).
    pub fn warm_start(&mut self, states: &[BodyState], velocities: &SharedVelocities) {
        self.each_color(|bundle| bundle.warm_start(states, velocities));
    }

    /// One pass: non-penetration (soft-biased or relaxed), then friction if asked.
    pub fn solve(
        &mut self,
        states: &[BodyState],
        velocities: &SharedVelocities,
        pass: PassBias,
        friction: bool,
    ) {
        self.each_color(|bundle| bundle.solve(states, velocities, pass, friction));
    }

    /// Runs `task` on every bundle, colour after colour, on as many threads as rayon gives.
    fn each_color(&mut self, task: impl Fn(&mut Bundle) + Sync) {
        for_each_by_color(&mut self.bundles, &self.colors, task);
    }

    /// Copies the impulses back into the constraints (for restitution and the next step's warm
    /// start).
    pub fn store(&self, constraints: &mut [ContactConstraint]) {
        for bundle in &self.bundles {
            for (lane, &index) in bundle.constraints.iter().enumerate() {
                let Some(c) = constraints.get_mut(index) else {
                    continue;
                };
                for (j, point) in c.points_mut().iter_mut().enumerate() {
                    let wide = &bundle.points[j];
                    point.normal_impulse = wide.normal_impulse.to_array()[lane];
                    point.tangent_impulse = wide.tangent_impulse.to_array()[lane];
                    point.total_normal_impulse = wide.total_normal_impulse.to_array()[lane];
                }
            }
        }
    }
}

impl Bundle {
    /// Applies the bundle's accumulated impulses (and counts them as pushed this step).
    #[inline(always)]
    fn warm_start(&mut self, states: &[BodyState], velocities: &SharedVelocities) {
        let mut a = WideBody::gather(states, velocities, &self.a);
        let mut b = WideBody::gather(states, velocities, &self.b);
        let (tangent_x, tangent_y) = (self.normal_y, -self.normal_x);
        for j in 0..2 {
            let point = self.points[j];
            let p_x = self.normal_x * point.normal_impulse + tangent_x * point.tangent_impulse;
            let p_y = self.normal_y * point.normal_impulse + tangent_y * point.tangent_impulse;
            self.apply(&point, p_x, p_y, &mut a, &mut b);
            self.points[j].total_normal_impulse += point.normal_impulse;
        }
        a.scatter(velocities, &self.a, &self.writes_a);
        b.scatter(velocities, &self.b, &self.writes_b);
    }

    /// Solves the bundle's four constraints once.
    #[inline(always)]
    fn solve(
        &mut self,
        states: &[BodyState],
        velocities: &SharedVelocities,
        pass: PassBias,
        friction: bool,
    ) {
        let zero = f32x4::splat(0.0);
        let one = f32x4::splat(1.0);
        let inv_h = f32x4::splat(pass.inv_h);
        let max_push = f32x4::splat(-pass.max_push_speed);
        let bundle = self;
        let mut a = WideBody::gather(states, velocities, &bundle.a);
        let mut b = WideBody::gather(states, velocities, &bundle.b);
        let (normal_x, normal_y) = (bundle.normal_x, bundle.normal_y);
        for j in 0..2 {
            let point = bundle.points[j];
            // Separation now: the anchors turned by the rotation since the step began.
            let ra_x = a.cos * point.anchor_a_x - a.sin * point.anchor_a_y;
            let ra_y = a.sin * point.anchor_a_x + a.cos * point.anchor_a_y;
            let rb_x = b.cos * point.anchor_b_x - b.sin * point.anchor_b_y;
            let rb_y = b.sin * point.anchor_b_x + b.cos * point.anchor_b_y;
            let d_x = (b.dp_x - a.dp_x) + rb_x - ra_x;
            let d_y = (b.dp_y - a.dp_y) + rb_y - ra_y;
            let s = point.base_separation + (normal_x * d_x + normal_y * d_y);
            let speculative = s.simd_gt(zero);
            let (bias, mass_scale, impulse_scale) = if pass.use_bias {
                (
                    (bundle.mass_scale * bundle.bias_rate * s).max(max_push),
                    bundle.mass_scale,
                    bundle.impulse_scale,
                )
            } else {
                (zero, one, zero)
            };
            let bias = speculative.bitselect(s * inv_h, bias);
            let mass_scale = speculative.bitselect(one, mass_scale);
            let impulse_scale = speculative.bitselect(zero, impulse_scale);
            let vn = bundle.relative_normal_velocity(&point, &a, &b, normal_x, normal_y);
            let impulse = -point.normal_mass * (mass_scale * vn + bias)
                - impulse_scale * point.normal_impulse;
            let total = (point.normal_impulse + impulse).max(zero);
            let applied = total - point.normal_impulse;
            let point = &mut bundle.points[j];
            point.normal_impulse = total;
            point.total_normal_impulse += applied;
            let point = *point;
            bundle.apply(
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
                let point = bundle.points[j];
                let vt = bundle.relative_normal_velocity(&point, &a, &b, tangent_x, tangent_y);
                let limit = bundle.friction * point.normal_impulse;
                let total = (point.tangent_impulse - point.tangent_mass * vt)
                    .max(-limit)
                    .min(limit);
                let applied = total - point.tangent_impulse;
                bundle.points[j].tangent_impulse = total;
                bundle.apply(
                    &point,
                    tangent_x * applied,
                    tangent_y * applied,
                    &mut a,
                    &mut b,
                );
            }
        }
        a.scatter(velocities, &bundle.a, &bundle.writes_a);
        b.scatter(velocities, &bundle.b, &bundle.writes_b);
    }

    /// Packs up to four constraints; `softness` is for moving and static partners.
    fn pack(
        constraints: &[ContactConstraint],
        chunk: Range<usize>,
        softness: [Softness; 2],
        spare: usize,
    ) -> Self {
        let mut lanes = [[0.0; LANES]; 10];
        let mut points = [[[0.0; LANES]; 10]; 2];
        let mut bundle_constraints = [usize::MAX; LANES];
        let (mut a, mut b) = ([spare; LANES], [spare; LANES]);
        let (mut writes_a, mut writes_b) = ([false; LANES], [false; LANES]);
        for (lane, index) in chunk.enumerate() {
            let c = &constraints[index];
            bundle_constraints[lane] = index;
            (a[lane], b[lane]) = (c.a, c.b);
            (writes_a[lane], writes_b[lane]) = (c.dynamic_a, c.dynamic_b);
            let soft = softness[usize::from(c.touches_static)];
            let values = [
                c.inv_mass_a,
                c.inv_inertia_a,
                c.inv_mass_b,
                c.inv_inertia_b,
                c.normal.x,
                c.normal.y,
                c.friction,
                soft.bias_rate,
                soft.mass_scale,
                soft.impulse_scale,
            ];
            for (field, value) in lanes.iter_mut().zip(values) {
                field[lane] = value;
            }
            // A missing point keeps zero mass: it never takes an impulse.
            for (j, p) in c.points().iter().enumerate() {
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
                ];
                for (field, value) in points[j].iter_mut().zip(values) {
                    field[lane] = value;
                }
            }
        }
        let point = |p: &[[Real; LANES]; 10]| WidePoint {
            anchor_a_x: f32x4::new(p[0]),
            anchor_a_y: f32x4::new(p[1]),
            anchor_b_x: f32x4::new(p[2]),
            anchor_b_y: f32x4::new(p[3]),
            base_separation: f32x4::new(p[4]),
            normal_mass: f32x4::new(p[5]),
            tangent_mass: f32x4::new(p[6]),
            normal_impulse: f32x4::new(p[7]),
            tangent_impulse: f32x4::new(p[8]),
            total_normal_impulse: f32x4::new(p[9]),
        };
        Bundle {
            constraints: bundle_constraints,
            a,
            b,
            writes_a,
            writes_b,
            inv_mass_a: f32x4::new(lanes[0]),
            inv_inertia_a: f32x4::new(lanes[1]),
            inv_mass_b: f32x4::new(lanes[2]),
            inv_inertia_b: f32x4::new(lanes[3]),
            normal_x: f32x4::new(lanes[4]),
            normal_y: f32x4::new(lanes[5]),
            friction: f32x4::new(lanes[6]),
            bias_rate: f32x4::new(lanes[7]),
            mass_scale: f32x4::new(lanes[8]),
            impulse_scale: f32x4::new(lanes[9]),
            points: [point(&points[0]), point(&points[1])],
        }
    }

    /// Velocity of B relative to A at a point, along `(dir_x, dir_y)`.
    #[inline(always)]
    fn relative_normal_velocity(
        &self,
        point: &WidePoint,
        a: &WideBody,
        b: &WideBody,
        dir_x: f32x4,
        dir_y: f32x4,
    ) -> f32x4 {
        let dv_x = (b.v_x - b.w * point.anchor_b_y) - (a.v_x - a.w * point.anchor_a_y);
        let dv_y = (b.v_y + b.w * point.anchor_b_x) - (a.v_y + a.w * point.anchor_a_x);
        dv_x * dir_x + dv_y * dir_y
    }

    /// Applies the impulse `(p_x, p_y)` at a point: minus to A, plus to B.
    #[inline(always)]
    fn apply(&self, point: &WidePoint, p_x: f32x4, p_y: f32x4, a: &mut WideBody, b: &mut WideBody) {
        a.v_x -= self.inv_mass_a * p_x;
        a.v_y -= self.inv_mass_a * p_y;
        a.w -= self.inv_inertia_a * (point.anchor_a_x * p_y - point.anchor_a_y * p_x);
        b.v_x += self.inv_mass_b * p_x;
        b.v_y += self.inv_mass_b * p_y;
        b.w += self.inv_inertia_b * (point.anchor_b_x * p_y - point.anchor_b_y * p_x);
    }
}
