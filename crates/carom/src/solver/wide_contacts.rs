//! Soft step's contact solve four constraints at a time: the constraints of one graph colour
//! (no shared moving body) are packed into bundles of four lanes, stored as structures of
//! arrays, and solved with `wide`'s 4-lane floats. The arithmetic per lane is exactly the scalar
//! solver's ([`super::soft_step`]); only the order of constraints differs (colour by colour).

use super::contact_constraint::ContactConstraint;
use super::contact_graph::ContactGraph;
use super::{BodyState, Softness};
use crate::math::Real;
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
    max_normal_impulse: f32x4,
}

/// Four constraints; lanes past the colour's end are empty (zero masses, no impulse).
#[derive(Debug, Clone, Copy)]
struct Bundle {
    /// Indices into the solver's constraint array (`usize::MAX` for an empty lane).
    constraints: [usize; LANES],
    /// Dense body indices (the spare state for an empty lane).
    a: [usize; LANES],
    b: [usize; LANES],
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
    fn gather(states: &[BodyState], indices: &[usize; LANES]) -> Self {
        let s = indices.map(|i| &states[i]);
        let lanes = |f: fn(&BodyState) -> Real| f32x4::new([f(s[0]), f(s[1]), f(s[2]), f(s[3])]);
        WideBody {
            v_x: lanes(|s| s.v.x),
            v_y: lanes(|s| s.v.y),
            w: lanes(|s| s.w),
            dp_x: lanes(|s| s.dp.x),
            dp_y: lanes(|s| s.dp.y),
            cos: lanes(|s| s.dq.re),
            sin: lanes(|s| s.dq.im),
        }
    }

    /// Writes the velocities back (positions do not change in a solve).
    fn scatter(&self, states: &mut [BodyState], indices: &[usize; LANES]) {
        let (v_x, v_y, w) = (self.v_x.to_array(), self.v_y.to_array(), self.w.to_array());
        for (lane, &i) in indices.iter().enumerate() {
            let state = &mut states[i];
            state.v.x = v_x[lane];
            state.v.y = v_y[lane];
            state.w = w[lane];
        }
    }
}

/// The constraints of a step in bundles, colour by colour, and the constraints left over.
#[derive(Debug, Clone, Default)]
pub(crate) struct WideContacts {
    bundles: Vec<Bundle>,
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
        self.bundles.clear();
        for color in &graph.colors {
            for chunk in color.chunks(LANES) {
                let softness = [soft, static_soft];
                self.bundles
                    .push(Bundle::pack(constraints, chunk, softness, spare));
            }
        }
        self.overflow.clear();
        self.overflow.extend_from_slice(&graph.overflow);
    }

    /// Applies the accumulated impulses (warm start).
    pub fn warm_start(&self, states: &mut [BodyState]) {
        for bundle in &self.bundles {
            let mut a = WideBody::gather(states, &bundle.a);
            let mut b = WideBody::gather(states, &bundle.b);
            let (tangent_x, tangent_y) = (bundle.normal_y, -bundle.normal_x);
            for point in &bundle.points {
                let p_x =
                    bundle.normal_x * point.normal_impulse + tangent_x * point.tangent_impulse;
                let p_y =
                    bundle.normal_y * point.normal_impulse + tangent_y * point.tangent_impulse;
                bundle.apply(point, p_x, p_y, &mut a, &mut b);
            }
            a.scatter(states, &bundle.a);
            b.scatter(states, &bundle.b);
        }
    }

    /// One pass: non-penetration (soft-biased or relaxed), then friction if asked.
    pub fn solve(&mut self, states: &mut [BodyState], pass: PassBias, friction: bool) {
        let zero = f32x4::splat(0.0);
        let one = f32x4::splat(1.0);
        let inv_h = f32x4::splat(pass.inv_h);
        let max_push = f32x4::splat(-pass.max_push_speed);
        for bundle in &mut self.bundles {
            let mut a = WideBody::gather(states, &bundle.a);
            let mut b = WideBody::gather(states, &bundle.b);
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
                let s = point.base_separation + normal_x * d_x + normal_y * d_y;
                let speculative = s.simd_gt(zero);
                let (bias, mass_scale, impulse_scale) = if pass.use_bias {
                    (
                        (bundle.bias_rate * s).max(max_push),
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
                let impulse = -point.normal_mass * mass_scale * (vn + bias)
                    - impulse_scale * point.normal_impulse;
                let total = (point.normal_impulse + impulse).max(zero);
                let applied = total - point.normal_impulse;
                let point = &mut bundle.points[j];
                point.normal_impulse = total;
                point.max_normal_impulse = point.max_normal_impulse.max(applied);
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
            a.scatter(states, &bundle.a);
            b.scatter(states, &bundle.b);
        }
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
                    point.max_normal_impulse = wide.max_normal_impulse.to_array()[lane];
                }
            }
        }
    }
}

impl Bundle {
    /// Packs up to four constraints; `softness` is for moving and static partners.
    fn pack(
        constraints: &[ContactConstraint],
        chunk: &[usize],
        softness: [Softness; 2],
        spare: usize,
    ) -> Self {
        let mut lanes = [[0.0; LANES]; 10];
        let mut points = [[[0.0; LANES]; 10]; 2];
        let mut bundle_constraints = [usize::MAX; LANES];
        let (mut a, mut b) = ([spare; LANES], [spare; LANES]);
        for (lane, &index) in chunk.iter().enumerate() {
            let c = &constraints[index];
            bundle_constraints[lane] = index;
            (a[lane], b[lane]) = (c.a, c.b);
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
                    p.max_normal_impulse,
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
            max_normal_impulse: f32x4::new(p[9]),
        };
        Bundle {
            constraints: bundle_constraints,
            a,
            b,
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
