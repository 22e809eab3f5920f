//! Sequential impulses (Catto, GDC 2006) as Box2D v2.4 runs them: accumulated impulses clamped
//! as a whole, so many iterations converge to the contact forces; warm started from the last
//! step; the two points of a face solved as one 2x2 block; restitution as a final pass.
//! Overlap is removed on positions, not velocities: after the bodies move, a few Gauss-Seidel
//! passes push overlap beyond the slop out directly (Baumgarte's fraction per pass, at most
//! [`MAX_CORRECTION`]). A velocity bias would stay in the bodies as energy and, in a pressed
//! pile, feed on itself until it explodes.
//!
//! Joints are solved before the contacts in each iteration, warm started too, rigidly; their
//! drift is closed in the position passes, before the contacts', as Box2D v2.4 does, with as
//! many passes for joints as velocity iterations. (A
//! Baumgarte bias on velocities instead feeds energy into a long chain until it flies apart.)

use crate::constants::{LINEAR_SLOP, MAX_CONDITION, MAX_CORRECTION, POSITION_ITERATIONS};
use crate::math::{Real, cross, rotation};
use crate::solver::body_state::BodyState;
use crate::solver::body_state::{SpeedCaps, integrate_positions, integrate_velocities};
use crate::solver::contact_constraint::ConstraintPoint;
use crate::solver::contact_constraint::ContactConstraint;
use crate::solver::contact_constraint::pair_mut;
use crate::solver::context::SolverContext;
use crate::solver::joints::{JointConstraint, JointPass};
use crate::solver::params::SolverParams;
use crate::solver::soft_step::scalar::{
    apply_restitution, forget_impulses, solve_friction, warm_start,
};
use crate::stats::Work;

pub(crate) fn solve(
    context: &SolverContext,
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
    joints: &mut [JointConstraint],
) -> Work {
    let SolverContext {
        params,
        environment,
        drives,
        dt,
    } = *context;
    let inv_dt = 1.0 / dt;
    let mut work =
        integrate_velocities(environment, drives, states, dt, SpeedCaps::new(params, dt));
    let joint_pass = JointPass::velocities(dt);
    // Joints begin the step either way: without warm starting their impulses were forgotten
    // when prepared, and a leg's spring still advances.
    for joint in joints.iter_mut() {
        with_joint_states(joint, states, |j, a, b| j.warm_start(a, b));
    }
    if params.warm_starting {
        warm_start(constraints, states);
    } else {
        forget_impulses(constraints);
    }
    for _ in 0..params.effective_iterations() {
        for joint in joints.iter_mut() {
            with_joint_states(joint, states, |j, a, b| j.solve(a, b, &joint_pass));
        }
        for c in constraints.iter_mut() {
            let (a, b) = pair_mut(states, c.a, c.b);
            // Friction first, against last iteration's normal impulse (Box2D v2's order).
            if environment.friction {
                work.friction_impulses += solve_friction(c, a, b);
            }
            if c.points().len() == 2 && solve_normal_pair(c, a, b, inv_dt) {
                continue;
            }
            for i in 0..c.points().len() {
                let point = c.points()[i];
                let vn = ContactConstraint::relative_velocity(&point, a, b).dot(&c.normal);
                let impulse = point.normal_mass * (target_speed(&point, inv_dt) - vn);
                c.add_normal_impulse(i, impulse, a, b);
            }
        }
    }
    if environment.restitution {
        work.restitution_impulses = apply_restitution(params, constraints, states);
    }
    // The step is its one substep: what each point holds now is what the step applied.
    for c in constraints.iter_mut() {
        c.note_substep_impulses();
    }
    integrate_positions(drives, states, dt, SpeedCaps::new(params, dt));
    // Joints take as many position passes as velocity iterations (at least the contacts'):
    // a chain of light links holding a heavy load needs them to close its drift each step.
    let joint_passes = (params.effective_iterations() as usize).max(POSITION_ITERATIONS);
    for pass in 0..joint_passes {
        if pass < joint_passes {
            for joint in joints.iter_mut() {
                with_joint_positions(joint, states, dt);
            }
        }
        if pass < POSITION_ITERATIONS {
            correct_positions(params, constraints, states);
        }
    }
    work
}

/// Runs `f` on copies of a joint's two states, and writes back the velocities of the bodies
/// it moves.
pub(super) fn with_joint_states(
    joint: &mut JointConstraint,
    states: &mut [BodyState],
    f: impl FnOnce(&mut JointConstraint, &mut BodyState, &mut BodyState),
) {
    let (mut a, mut b) = (states[joint.a], states[joint.b]);
    f(joint, &mut a, &mut b);
    if joint.moves_a {
        (states[joint.a].v, states[joint.a].w) = (a.v, a.w);
    }
    if joint.moves_b {
        (states[joint.b].v, states[joint.b].w) = (b.v, b.w);
    }
}

/// One position pass of a joint on its two states.
fn with_joint_positions(joint: &JointConstraint, states: &mut [BodyState], dt: Real) {
    let (mut a, mut b) = (states[joint.a], states[joint.b]);
    joint.correct_positions(&mut a, &mut b, dt);
    if joint.moves_a {
        (states[joint.a].dp, states[joint.a].dq) = (a.dp, a.dq);
    }
    if joint.moves_b {
        (states[joint.b].dp, states[joint.b].dq) = (b.dp, b.dq);
    }
}

/// The slowest normal velocity a point allows: close a speculative gap exactly; an overlap is
/// the position passes' business.
#[inline]
fn target_speed(point: &ConstraintPoint, inv_dt: Real) -> Real {
    -point.separation.max(0.0) * inv_dt
}

/// Both normal impulses of a two-point manifold at once, as Box2D v2.4's block solver does:
/// the 2x2 linear complementarity problem, by trying each case of which points push. Solved
/// one after the other, the two points of a resting face fight, and the box rocks; the rocking
/// kept sequential-impulse stacks from ever sleeping. Returns false (nothing applied) when the
/// points are too alike or no case holds, and the caller solves them one by one.
fn solve_normal_pair(
    c: &mut ContactConstraint,
    a: &mut BodyState,
    b: &mut BodyState,
    inv_dt: Real,
) -> bool {
    let n = c.normal;
    let (ma, ia, mb, ib) = (c.inv_mass_a, c.inv_inertia_a, c.inv_mass_b, c.inv_inertia_b);
    let [p1, p2] = [c.points()[0], c.points()[1]];
    let (rn1a, rn1b) = (cross(p1.anchor_a, n), cross(p1.anchor_b, n));
    let (rn2a, rn2b) = (cross(p2.anchor_a, n), cross(p2.anchor_b, n));
    let k11 = ma + mb + ia * rn1a * rn1a + ib * rn1b * rn1b;
    let k22 = ma + mb + ia * rn2a * rn2a + ib * rn2b * rn2b;
    let k12 = ma + mb + ia * rn1a * rn2a + ib * rn1b * rn2b;
    let det = k11 * k22 - k12 * k12;
    // Written so a NaN also counts as ill-conditioned.
    let well_conditioned = k11 * k11 < MAX_CONDITION * det;
    if !well_conditioned {
        return false;
    }
    let old = [p1.normal_impulse, p2.normal_impulse];
    let vn1 = ContactConstraint::relative_velocity(&p1, a, b).dot(&n);
    let vn2 = ContactConstraint::relative_velocity(&p2, a, b).dot(&n);
    // b = vn - target - K·old: the velocities the impulses `x` must answer, K·x + b >= 0.
    let b1 = vn1 - target_speed(&p1, inv_dt) - (k11 * old[0] + k12 * old[1]);
    let b2 = vn2 - target_speed(&p2, inv_dt) - (k12 * old[0] + k22 * old[1]);
    let inv_det = 1.0 / det;
    let candidates = [
        // Both push: x = -K⁻¹ b.
        [
            -(k22 * b1 - k12 * b2) * inv_det,
            -(-k12 * b1 + k11 * b2) * inv_det,
        ],
        // Only the first pushes; the second separates.
        [-b1 / k11, 0.0],
        // Only the second.
        [0.0, -b2 / k22],
        // Neither.
        [0.0, 0.0],
    ];
    let Some(x) = candidates.into_iter().find(|x| {
        let vn1 = k11 * x[0] + k12 * x[1] + b1;
        let vn2 = k12 * x[0] + k22 * x[1] + b2;
        let tolerance = 1e-6 * (1.0 + b1.abs() + b2.abs());
        // Pushing points end with vn = 0 by construction; the others must be separating.
        x[0] >= 0.0 && x[1] >= 0.0 && vn1 >= -tolerance && vn2 >= -tolerance
    }) else {
        return false;
    };
    let (d1, d2) = (x[0] - old[0], x[1] - old[1]);
    let (push1, push2) = (n * d1, n * d2);
    a.v -= (push1 + push2) * ma;
    a.w -= ia * (cross(p1.anchor_a, push1) + cross(p2.anchor_a, push2));
    b.v += (push1 + push2) * mb;
    b.w += ib * (cross(p1.anchor_b, push1) + cross(p2.anchor_b, push2));
    for (point, (total, applied)) in c.points_mut().iter_mut().zip([(x[0], d1), (x[1], d2)]) {
        point.normal_impulse = total;
        point.total_normal_impulse += applied;
    }
    true
}

/// One Gauss-Seidel pass on positions: each point's overlap beyond the slop, a Baumgarte
/// fraction of it and at most [`MAX_CORRECTION`], is pushed out along the normal by moving the
/// two bodies as an impulse would (no velocity changes).
fn correct_positions(
    params: &SolverParams,
    constraints: &[ContactConstraint],
    states: &mut [BodyState],
) {
    for c in constraints {
        let (a, b) = pair_mut(states, c.a, c.b);
        for point in c.points() {
            let separation = c.current_separation(point, a, b);
            let correction =
                (params.baumgarte * (separation + LINEAR_SLOP)).clamp(-MAX_CORRECTION, 0.0);
            if correction == 0.0 {
                continue;
            }
            let (ra, rb) = (a.dq * point.anchor_a, b.dq * point.anchor_b);
            let (rna, rnb) = (cross(ra, c.normal), cross(rb, c.normal));
            let k = c.inv_mass_a
                + c.inv_mass_b
                + c.inv_inertia_a * rna * rna
                + c.inv_inertia_b * rnb * rnb;
            if k <= 0.0 {
                continue;
            }
            let push = c.normal * (-correction / k);
            a.dp -= push * c.inv_mass_a;
            a.dq = rotation(-c.inv_inertia_a * cross(ra, push)) * a.dq;
            b.dp += push * c.inv_mass_b;
            b.dq = rotation(c.inv_inertia_b * cross(rb, push)) * b.dq;
        }
    }
}
