//! Joints as the solver takes them: prepared once per step (anchors relative to the centres of
//! mass, fixed for the step; effective masses; softness), then warm started and solved in
//! every substep beside the contacts, as Box2D v3 does: soft in the biased pass (a stiff,
//! damped spring closes a joint's drift), rigid in the relaxation, so the push back into
//! place leaves no energy behind. Each kind's equations are in its own file.
//!
//! Soft step solves the joints after the contacts in each pass, in colours of their own: no
//! two joints of a colour share a dynamic body, so a colour's joints are solved on several
//! threads at once ([`crate::graph::joints::JointColors::order`]). Sequential impulse solves them one by one,
//! rigidly, and closes their drift in its position passes
//! ([`JointConstraint::correct_positions`]).

mod distance;
mod motor;
mod mouse;
mod mover;
mod pogo;
mod prismatic;
mod revolute;
mod weld;
mod wheel;

use super::body_state::{BodyState, SpeedCaps};
use super::params::{Softness, SolverParams};
use crate::dynamics::body::Body;
use crate::joint::{Joint, JointImpulses, JointKind, Limits};
use crate::math::{Real, Rot, Vec2, angle_of, cross, rotation};

/// A joint prepared for one step.
#[derive(Debug, Clone)]
pub(crate) struct JointConstraint {
    /// Body A's and B's indices among the solver's states (the spare state when not awake).
    pub a: usize,
    pub b: usize,
    /// Which of them take impulses (dynamic and awake).
    pub moves_a: bool,
    pub moves_b: bool,
    /// Its anchors and its bodies' masses.
    frame: JointFrame,
    /// A's rotation, and B's less the reference angle, at the start of the step: the joint's
    /// angle is the one from the first to the second.
    rot_a: Rot,
    rot_b: Rot,
    /// The accumulated impulses, for the warm start and the reaction.
    pub impulses: JointImpulses,
    /// The kind's settings and what was prepared from them.
    data: JointData,
    /// A hinge whose point (and limits) the joint trees solve ([`crate::solver::soft_step::joint_trees`]): its
    /// own solve leaves them alone, and so does its warm start.
    point_in_tree: bool,
}

/// What a joint sees of its bodies for the step: where its anchors are, and the masses that
/// take its impulses (zero for a body that does not move). The joint trees copy a hinge's.
#[derive(Debug, Clone, Copy)]
pub(crate) struct JointFrame {
    /// From each centre of mass to its anchor, at the start of the step.
    frame_a: Vec2,
    frame_b: Vec2,
    /// B's centre of mass less A's at the start of the step (a mouse joint: less the target).
    delta_center: Vec2,
    inv_mass_a: Real,
    inv_inertia_a: Real,
    inv_mass_b: Real,
    inv_inertia_b: Real,
}

impl JointFrame {
    /// The anchors' offsets from the centres of mass now.
    #[inline]
    pub(crate) fn anchors(&self, a: &BodyState, b: &BodyState) -> (Vec2, Vec2) {
        (a.dq * self.frame_a, b.dq * self.frame_b)
    }

    /// B's anchor less A's now.
    #[inline]
    pub(crate) fn separation(&self, a: &BodyState, b: &BodyState, ra: Vec2, rb: Vec2) -> Vec2 {
        (b.dp - a.dp) + (rb - ra) + self.delta_center
    }

    /// The velocity of B's anchor relative to A's.
    #[inline]
    pub(crate) fn velocity(a: &BodyState, b: &BodyState, ra: Vec2, rb: Vec2) -> Vec2 {
        JointConstraint::relative_velocity(a, b, ra, rb)
    }

    /// `(1/mA, 1/IA, 1/mB, 1/IB)`, zero for a body that does not move.
    #[inline]
    pub(crate) fn inverse_masses(&self) -> (Real, Real, Real, Real) {
        (
            self.inv_mass_a,
            self.inv_inertia_a,
            self.inv_mass_b,
            self.inv_inertia_b,
        )
    }

    /// Applies impulse `p` at the anchors (to B, and its opposite to A).
    #[inline]
    pub(crate) fn push(&self, a: &mut BodyState, b: &mut BodyState, ra: Vec2, rb: Vec2, p: Vec2) {
        a.v -= p * self.inv_mass_a;
        a.w -= self.inv_inertia_a * cross(ra, p);
        b.v += p * self.inv_mass_b;
        b.w += self.inv_inertia_b * cross(rb, p);
    }
}

/// A hinge's limits on its angle, as the joint trees hold them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HingeLimit {
    pub limits: Limits,
    /// As the joint's own: A's rotation, and B's less the reference angle, at the start of
    /// the step.
    rot_a: Rot,
    rot_b: Rot,
}

impl HingeLimit {
    /// The hinge's angle now.
    #[inline]
    pub(crate) fn angle(&self, a: &BodyState, b: &BodyState) -> Real {
        relative_angle(a, b, self.rot_a, self.rot_b)
    }
}

/// Each kind's settings, and the spring softness and masses prepared for the step.
#[derive(Debug, Clone, Copy)]
enum JointData {
    Distance(distance::Prepared),
    Revolute(revolute::Prepared),
    Prismatic(prismatic::Prepared),
    Weld(weld::Prepared),
    Wheel(wheel::Prepared),
    Motor(motor::Prepared),
    Mover(mover::Prepared),
    Pogo(pogo::Prepared),
    Mouse(mouse::Prepared),
    Filter,
}

/// How a pass treats a joint's drift.
#[derive(Debug, Clone, Copy)]
pub(crate) struct JointPass {
    /// The (sub)step.
    pub h: Real,
    pub inv_h: Real,
    /// Push drift back (the biased pass), or hold the velocities only (relaxation).
    pub use_bias: bool,
    /// How drift is pushed back.
    pub softness: Softness,
    /// Springs and motors act (off in a pass that only corrects positions).
    pub drive: bool,
    /// Soft step's relaxation, after the positions moved: a pogo leg's spring then holds
    /// still instead of driving.
    pub relaxing: bool,
}

impl JointPass {
    /// Soft step's pass over substeps of `h`: the joint softness of `params` (its stiffness
    /// at most a quarter of the substep rate, as Box2D caps it).
    pub(crate) fn soft(params: &SolverParams, h: Real, use_bias: bool) -> Self {
        let inv_h = 1.0 / h;
        let hertz = params.joint_hertz.min(0.25 * inv_h);
        JointPass {
            h,
            inv_h,
            use_bias,
            softness: Softness::new(hertz, params.joint_damping_ratio, h),
            drive: true,
            relaxing: !use_bias,
        }
    }

    /// Sequential impulse's velocity pass over a step of `dt`: rigid, drift left to the
    /// position passes.
    pub(crate) fn velocities(dt: Real) -> Self {
        JointPass {
            h: dt,
            inv_h: 1.0 / dt,
            use_bias: false,
            softness: Softness::new(0.0, 0.0, dt),
            drive: true,
            relaxing: false,
        }
    }

    /// Sequential impulse's position pass ([`JointConstraint::correct_positions`]): the
    /// whole drift closed, nothing driven.
    pub(crate) fn positions(dt: Real) -> Self {
        JointPass {
            h: dt,
            inv_h: 1.0 / dt,
            use_bias: true,
            softness: Softness {
                bias_rate: 1.0 / dt,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            },
            drive: false,
            relaxing: false,
        }
    }

    /// The bias, mass scale and impulse scale of a rigid constraint with error `c`.
    #[inline]
    pub(crate) fn rigid(&self, c: Real) -> (Real, Real, Real) {
        if self.use_bias {
            let s = self.softness;
            (s.bias_rate * c, s.mass_scale, s.impulse_scale)
        } else {
            (0.0, 1.0, 0.0)
        }
    }

    /// The same for a limit with slack `c` (positive: not yet reached, which may close
    /// exactly this substep).
    #[inline]
    pub(crate) fn limit(&self, c: Real) -> (Real, Real, Real) {
        if c > 0.0 {
            (c * self.inv_h, 1.0, 0.0)
        } else {
            self.rigid(c)
        }
    }
}

/// A joint's lower and upper limits on one coordinate, `position` (an angle, a length, a
/// translation): the lower stop holds `position >= limits.lower`, the upper `position <=
/// limits.upper`. Both are solved in every pass, however far away, as Box2D does: a stop not
/// yet reached is speculative and acts only if this (sub)step would carry the joint past it.
/// `stop(scales, impulse, upper)` solves one stop with the pass's `(bias, mass scale,
/// impulse scale)` in the joint's own terms, keeping its accumulated `impulse` pushing only.
pub(super) fn solve_limits(
    position: Real,
    limits: Limits,
    (lower, upper): (&mut Real, &mut Real),
    pass: &JointPass,
    mut stop: impl FnMut((Real, Real, Real), &mut Real, bool),
) {
    stop(pass.limit(position - limits.lower), lower, false);
    stop(pass.limit(limits.upper - position), upper, true);
}

/// One stop's impulse on a coordinate whose effective mass is `mass`, closing at `closing`
/// (positive: moving away from the stop), with a pass's `(bias, mass scale, impulse scale)`:
/// the accumulated impulse only ever pushes. Returns the impulse to apply.
fn push_only(
    (bias, mass_scale, impulse_scale): (Real, Real, Real),
    accumulated: &mut Real,
    mass: Real,
    closing: Real,
) -> Real {
    let old = *accumulated;
    let impulse = -mass_scale * mass * (closing + bias) - impulse_scale * old;
    *accumulated = (old + impulse).max(0.0);
    *accumulated - old
}

/// What a joint needs of one of its bodies: its pose and mass, and where its state is.
pub(crate) struct JointBody<'a> {
    pub body: &'a Body,
    /// Its state's index (the spare one if it is not awake).
    pub state: usize,
    /// Awake and dynamic: it takes impulses.
    pub moves: bool,
}

impl JointConstraint {
    /// Prepares `joint` for a step whose substeps last `h`.
    pub(crate) fn prepare(
        joint: &Joint,
        a: JointBody,
        b: JointBody,
        h: Real,
        warm_starting: bool,
    ) -> Self {
        let mass = |side: &JointBody| {
            if side.moves {
                (side.body.inv_mass(), side.body.inv_inertia())
            } else {
                (0.0, 0.0)
            }
        };
        let ((ma, ia), (mb, ib)) = (mass(&a), mass(&b));
        let [local_a, local_b] = joint.local_anchors();
        let mouse = matches!(joint.kind(), JointKind::Mouse(_));
        let offset = |side: &JointBody, local: Vec2| {
            side.body.rotation() * (local - side.body.local_center())
        };
        let frame_b = offset(&b, local_b);
        // Most joints are made at their zero angle: no sine and cosine to work out each step.
        let rot_b = match joint.reference_angle() {
            0.0 => b.body.rotation(),
            reference => b.body.rotation() * rotation(-reference),
        };
        let (frame_a, rot_a, delta_center, a_state, moves_a) = match joint.kind() {
            // A mouse joint holds B to a point of the world: A is the world, at rest.
            JointKind::Mouse(settings) => (
                Vec2::zeros(),
                Rot::identity(),
                b.body.center_of_mass() - settings.target,
                usize::MAX,
                false,
            ),
            _ => (
                offset(&a, local_a),
                a.body.rotation(),
                b.body.center_of_mass() - a.body.center_of_mass(),
                a.state,
                a.moves,
            ),
        };
        let (ma, ia) = if mouse { (0.0, 0.0) } else { (ma, ia) };
        let mut c = JointConstraint {
            a: if mouse { b.state } else { a_state },
            b: b.state,
            moves_a,
            moves_b: b.moves,
            frame: JointFrame {
                frame_a,
                frame_b,
                delta_center,
                inv_mass_a: ma,
                inv_inertia_a: ia,
                inv_mass_b: mb,
                inv_inertia_b: ib,
            },
            rot_a,
            rot_b,
            impulses: if warm_starting {
                joint.impulses
            } else {
                // A leg's spring is motion, not an impulse: it goes on.
                JointImpulses {
                    spring_velocity: joint.impulses.spring_velocity,
                    ..JointImpulses::default()
                }
            },
            data: JointData::Filter,
            point_in_tree: false,
        };
        c.data = match *joint.kind() {
            JointKind::Distance(s) => JointData::Distance(distance::prepare(&c, s, h)),
            JointKind::Revolute(s) => JointData::Revolute(revolute::prepare(&c, s, h)),
            JointKind::Prismatic(s) => JointData::Prismatic(prismatic::prepare(&c, s, h)),
            JointKind::Weld(s) => JointData::Weld(weld::prepare(&c, s, h)),
            JointKind::Wheel(s) => JointData::Wheel(wheel::prepare(&c, s, h)),
            JointKind::Motor(s) => JointData::Motor(motor::prepare(&mut c, s, h)),
            JointKind::Mover(s) => JointData::Mover(mover::prepare(&mut c, s)),
            JointKind::Pogo(s) => {
                let up = b.body.rotation() * Vec2::new(0.0, 1.0);
                JointData::Pogo(pogo::prepare(&c, s, h, up))
            }
            JointKind::Mouse(s) => JointData::Mouse(mouse::prepare(&c, s, h)),
            JointKind::Filter => JointData::Filter,
        };
        c
    }

    /// Begins a (sub)step: advances a leg's spring, and applies the accumulated impulses;
    /// or, if the speed caps cut either body's velocities since the last warm start, forgets
    /// them and starts cold ([`super::SpeedCaps::hold`]). Called once per (sub)step whether
    /// warm starting is on or not (off, the impulses were forgotten when prepared).
    pub(crate) fn warm_start(&mut self, a: &mut BodyState, b: &mut BodyState) {
        if let JointData::Pogo(p) = self.data {
            pogo::advance_spring(self, &p, a, b);
        }
        if a.held != 0 || b.held != 0 {
            let spring_velocity = self.impulses.spring_velocity;
            self.impulses = JointImpulses {
                spring_velocity,
                ..JointImpulses::default()
            };
            return;
        }
        match self.data {
            JointData::Distance(p) => distance::warm_start(self, &p, a, b),
            JointData::Revolute(_) => revolute::warm_start(self, a, b),
            JointData::Prismatic(p) => prismatic::warm_start(self, &p, a, b),
            JointData::Weld(_) => weld::warm_start(self, a, b),
            JointData::Wheel(p) => wheel::warm_start(self, &p, a, b),
            JointData::Motor(_) => motor::warm_start(self, a, b),
            JointData::Mover(_) => mover::warm_start(self, a, b),
            JointData::Pogo(p) => pogo::warm_start(self, &p, a, b),
            JointData::Mouse(_) => mouse::warm_start(self, b),
            JointData::Filter => {}
        }
    }

    /// One pass.
    pub(crate) fn solve(&mut self, a: &mut BodyState, b: &mut BodyState, pass: &JointPass) {
        match self.data {
            JointData::Distance(p) => distance::solve(self, &p, a, b, pass),
            JointData::Revolute(p) => revolute::solve(self, &p, a, b, pass),
            JointData::Prismatic(p) => prismatic::solve(self, &p, a, b, pass),
            JointData::Weld(p) => weld::solve(self, &p, a, b, pass),
            JointData::Wheel(p) => wheel::solve(self, &p, a, b, pass),
            JointData::Motor(p) => motor::solve(self, &p, a, b, pass),
            JointData::Mover(p) => mover::solve(self, &p, a, b, pass),
            JointData::Pogo(p) => pogo::solve(self, &p, a, b, pass),
            JointData::Mouse(p) => mouse::solve(self, &p, b, pass),
            JointData::Filter => {}
        }
    }

    /// One Gauss-Seidel pass on positions, as Box2D v2.4 corrects joints after its velocity
    /// iterations: the velocity solve run on bodies at rest with a bias of the whole drift
    /// gives the velocities that would close it in `dt`; the bodies are moved by them, and
    /// keep their real velocities and the joint its impulses.
    pub(crate) fn correct_positions(&self, a: &mut BodyState, b: &mut BodyState, dt: Real) {
        let pass = JointPass::positions(dt);
        let mut scratch = self.clone();
        scratch.impulses = JointImpulses::default();
        let still = |s: &BodyState| BodyState {
            v: Vec2::zeros(),
            w: 0.0,
            ..*s
        };
        let (mut pa, mut pb) = (still(a), still(b));
        scratch.solve(&mut pa, &mut pb, &pass);
        for (state, pushed) in [(a, pa), (b, pb)] {
            state.dp += pushed.v * dt;
            state.dq = rotation(pushed.w * dt) * state.dq;
        }
    }

    /// Its point constraint, if it is a hinge (a revolute joint), which the joint trees may
    /// solve.
    pub(crate) fn hinge_point(&self) -> Option<JointFrame> {
        matches!(self.data, JointData::Revolute(_)).then_some(self.frame)
    }

    /// A hinge's limits, which the joint trees solve with its point.
    pub(crate) fn hinge_limit(&self) -> Option<HingeLimit> {
        match self.data {
            JointData::Revolute(p) => p.limits().map(|limits| HingeLimit {
                limits,
                rot_a: self.rot_a,
                rot_b: self.rot_b,
            }),
            _ => None,
        }
    }

    /// Hands its point and limits to the joint trees for the step: its own solve leaves them
    /// alone.
    pub(crate) fn leave_point_to_tree(&mut self) {
        self.point_in_tree = true;
    }

    /// The impulses for the next step's warm start: none if the speed caps cut either body's
    /// velocities since the last warm start, or would cut them now (`states` as the step left
    /// them), as [`JointConstraint::warm_start`] would forget them.
    pub(crate) fn impulses_to_keep(&self, states: &[BodyState], caps: SpeedCaps) -> JointImpulses {
        let held = |moves: bool, state: usize| moves && states[state].is_held(caps);
        if held(self.moves_a, self.a) || held(self.moves_b, self.b) {
            JointImpulses {
                spring_velocity: self.impulses.spring_velocity,
                ..JointImpulses::default()
            }
        } else {
            self.impulses
        }
    }

    /// The force and torque the accumulated impulses of the last (sub)step of `h` applied
    /// to B.
    pub(crate) fn reaction(&self, inv_h: Real) -> (Vec2, Real) {
        let i = &self.impulses;
        let (linear, angular) = match self.data {
            JointData::Distance(p) => (p.axis * (i.axial + i.lower - i.upper + i.motor), 0.0),
            JointData::Revolute(_) => (i.linear, i.motor + i.lower - i.upper + i.axial),
            JointData::Prismatic(p) => {
                let axis = self.rot_a * p.settings.axis;
                let axial = i.axial + i.motor + i.lower - i.upper;
                (
                    axis * axial + crate::math::cross_sv(1.0, axis) * i.linear.x,
                    i.linear.y,
                )
            }
            JointData::Weld(_) => (i.linear, i.angular),
            JointData::Wheel(p) => {
                let axis = self.rot_a * p.settings.axis;
                let axial = i.axial + i.lower - i.upper;
                (
                    axis * axial + crate::math::cross_sv(1.0, axis) * i.linear.x,
                    i.motor,
                )
            }
            JointData::Motor(_) => (i.linear + i.drive, i.angular + i.motor),
            JointData::Mover(_) => (i.drive, 0.0),
            JointData::Pogo(p) => (p.normal * i.axial, 0.0),
            JointData::Mouse(_) => (i.linear, 0.0),
            JointData::Filter => (Vec2::zeros(), 0.0),
        };
        (linear * inv_h, angular * inv_h)
    }

    // Shared kinematics.

    /// The anchors' offsets from the centres of mass now.
    #[inline]
    fn anchors(&self, a: &BodyState, b: &BodyState) -> (Vec2, Vec2) {
        self.frame.anchors(a, b)
    }

    /// B's anchor less A's now.
    #[inline]
    fn separation(&self, a: &BodyState, b: &BodyState, ra: Vec2, rb: Vec2) -> Vec2 {
        self.frame.separation(a, b, ra, rb)
    }

    /// The joint's angle now: B's rotation relative to A's, less the reference angle.
    #[inline]
    fn angle(&self, a: &BodyState, b: &BodyState) -> Real {
        relative_angle(a, b, self.rot_a, self.rot_b)
    }

    /// Applies impulse `p` at the anchors (to B, and its opposite to A).
    #[inline]
    fn apply_linear(&self, a: &mut BodyState, b: &mut BodyState, ra: Vec2, rb: Vec2, p: Vec2) {
        self.frame.push(a, b, ra, rb, p);
    }

    /// Applies angular impulse `l` (to B, and its opposite to A).
    #[inline]
    fn apply_angular(&self, a: &mut BodyState, b: &mut BodyState, l: Real) {
        a.w -= self.frame.inv_inertia_a * l;
        b.w += self.frame.inv_inertia_b * l;
    }

    /// The point constraint's effective mass matrix, `K = [[k11, k12], [k12, k22]]`.
    #[inline]
    fn point_mass(&self, ra: Vec2, rb: Vec2) -> [Real; 3] {
        let (ma, ia, mb, ib) = self.masses();
        [
            ma + mb + ra.y * ra.y * ia + rb.y * rb.y * ib,
            -ra.y * ra.x * ia - rb.y * rb.x * ib,
            ma + mb + ra.x * ra.x * ia + rb.x * rb.x * ib,
        ]
    }

    #[inline]
    fn masses(&self) -> (Real, Real, Real, Real) {
        self.frame.inverse_masses()
    }

    /// The velocity of B's anchor relative to A's.
    #[inline]
    fn relative_velocity(a: &BodyState, b: &BodyState, ra: Vec2, rb: Vec2) -> Vec2 {
        b.v + crate::math::cross_sv(b.w, rb) - a.v - crate::math::cross_sv(a.w, ra)
    }
}

/// B's rotation relative to A's now, from their rotations at the start of the step (`rot_a`,
/// and `rot_b` less the reference angle).
#[inline]
fn relative_angle(a: &BodyState, b: &BodyState, rot_a: Rot, rot_b: Rot) -> Real {
    angle_of(&((a.dq * rot_a).inverse() * (b.dq * rot_b)))
}

/// `K⁻¹ rhs` for the symmetric `K = [[k11, k12], [k12, k22]]`; zero if `K` is singular.
#[inline]
fn solve22([k11, k12, k22]: [Real; 3], rhs: Vec2) -> Vec2 {
    let mut det = k11 * k22 - k12 * k12;
    let (mut k11, mut k12, mut k22, mut rhs) = (k11, k12, k22, rhs);
    if det != 0.0 && !det.is_normal() {
        // Entries past 1e19 (a light body's inverse inertia at a long lever arm) overflow the
        // determinant, and entries under 1e-19 (two bodies heavier than a mountain) leave it
        // too small to invert: solve the same system scaled to entries of at most one.
        let scale = 1.0 / k11.abs().max(k22.abs()).max(k12.abs());
        (k11, k12, k22, rhs) = (k11 * scale, k12 * scale, k22 * scale, rhs * scale);
        det = k11 * k22 - k12 * k12;
    }
    if !det.is_normal() {
        return Vec2::zeros();
    }
    let inv = 1.0 / det;
    Vec2::new(
        inv * (k22 * rhs.x - k12 * rhs.y),
        inv * (k11 * rhs.y - k12 * rhs.x),
    )
}

/// A joint spring's softness for (sub)steps of `h`; no spring is none (0 Hz: no force).
#[inline]
fn spring_softness(spring: Option<crate::joint::Spring>, h: Real) -> Softness {
    spring.map_or(Softness::new(0.0, 0.0, h), |s| {
        Softness::new(s.hertz, s.damping_ratio, h)
    })
}

/// `1 / k`, or 0 when nothing can move (`k` is 0).
#[inline]
fn inverse_or_zero(k: Real) -> Real {
    if k > 0.0 { 1.0 / k } else { 0.0 }
}
