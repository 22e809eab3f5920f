//! Box2D v3's soft step: substeps with soft contacts, relaxation and a restitution pass.
//!
//! Per substep: integrate velocities, warm start, solve with a soft-constraint bias (a stiff,
//! heavily damped spring pulls overlap out at a bounded speed), integrate positions, then
//! relax (solve again without bias, so the push-out leaves no energy behind). Anchors stay
//! fixed for the step; each point's separation is updated from the bodies' motion. Joints are
//! solved the same way, after the contacts in each pass ([`super::joints`]); with the
//! options on, so are shock propagation's supports ([`shock_propagation`]) and the
//! joint trees ([`joint_trees`]).
//!
//! This file plans a step's stages; the rest of the folder runs them:
//! - `inputs`: what the contact passes read, and how a pass treats overlap;
//! - `bundles`: the coloured contacts in SIMD bundles, prepared and stored;
//! - `kernels`: one bundle's passes, four or eight lanes at a time;
//! - `scalar`: the same passes one constraint at a time, for the overflow;
//! - `executor`: the stages run over bundles, overflow, joints and bodies on all threads;
//! - `scheduler`: blocks of a stage handed to threads, with a barrier between stages;
//! - `shared_states`: the body states the threads write in place (with the solver's
//!   `unsafe` code, here and in `lanes::avx`, saying why it is sound);
//! - `joint_trees`: direct joints, each tree of hinges planned and solved exactly;
//! - `shock_propagation`: shock propagation's levels and supports, planned each step;
//! - `shock_bundles`: shock propagation's supports, a level's round at a time in SIMD lanes;
//! - `lanes`: the SIMD lanes, `wide`'s four or AVX's eight.

mod bundles;
mod executor;
mod inputs;
mod joint_trees;
mod kernels;
mod lanes;
pub(crate) mod scalar;
mod scheduler;
mod shared_states;
mod shock_bundles;
mod shock_propagation;
#[cfg(test)]
mod tests;

pub(crate) use bundles::WideContacts;
pub(crate) use executor::Stage;
pub(crate) use inputs::BundleInputs;
pub(crate) use joint_trees::JointTrees;
pub(crate) use scheduler::block_range;
pub(crate) use shared_states::SharedStates;
pub(crate) use shock_bundles::{
    PassInputs as ShockPassInputs, ShockBundles, test_hooks as shock_test_hooks,
};
pub(crate) use shock_propagation::ShockPropagation;

use super::body_state::BodyState;
use super::body_state::SpeedCaps;
use super::contact_constraint::ContactConstraint;
use super::context::{Environment, SolverContext};
use super::joints::JointConstraint;
use super::params::{Softness, SolverParams};
use crate::constants::{COLOR_COUNT, JOINT_COLOR_COUNT};
use crate::graph::joints::JointColors;
use crate::math::Real;
use crate::stats::Work;
use executor::{Pass, StageInputs};
use inputs::PassBias;

/// One step in Box2D's stage order: per substep, integrate velocities, warm start, solve
/// (biased), integrate positions, relax (unbiased); then restitution. Each contact pass runs
/// colour by colour over `wide`'s SIMD bundles, already prepared, then over `constraints`,
/// the overflow's, one by one. The stage list is built here and run by
/// [`WideContacts::execute`] on as many threads as rayon gives, in one parallel region.
/// `bias` is for the step's substeps (the bundles were prepared with its softness).
pub(super) fn solve(
    context: &SolverContext,
    states: &mut [BodyState],
    (constraints, shock): (&mut [ContactConstraint], &mut ShockPropagation),
    (joints, joint_colors, trees): (&mut [JointConstraint], &JointColors, &mut JointTrees),
    wide: &mut WideContacts,
    plan: &mut Vec<Stage>,
    bias: &Bias,
) -> Work {
    let SolverContext {
        params,
        environment,
        drives,
        dt,
    } = *context;
    let substeps = params.substeps.max(1);
    let h = dt / substeps as Real;
    let bias_friction = environment.friction && params.friction_in_bias_pass;
    let bouncy = wide.bouncy() || constraints.iter().any(|c| c.restitution > 0.0);
    let shape = ContactStages {
        colors: wide.color_count(),
        overflow: !constraints.is_empty(),
        shock: !shock.is_empty(),
        bouncy,
    };
    plan_stages(
        plan,
        params,
        environment,
        bias,
        (joint_colors, !trees.is_empty()),
        shape,
    );
    let inputs = StageInputs {
        drives,
        environment,
        h,
        caps: SpeedCaps::new(params, dt),
        bias,
        params,
    };
    let (mut work, bounces) = wide.execute(
        plan,
        states,
        (constraints, shock),
        (joints, joint_colors, &mut *trees),
        &inputs,
    );
    trees.finish(joints);
    let points = wide.point_count() + constraints.iter().map(|c| c.points().len()).sum::<usize>();
    let friction_passes = u32::from(bias_friction) + u32::from(environment.friction);
    work.friction_impulses =
        points * (friction_passes * params.effective_iterations() * substeps) as usize;
    work.restitution_impulses = bounces;
    work
}

/// Which contact stages a step has: its colours, whether the overflow has constraints,
/// whether shock propagation has contacts to solve, and whether any contact bounces.
struct ContactStages {
    colors: usize,
    overflow: bool,
    shock: bool,
    bouncy: bool,
}

/// The stages of one step, into `plan`: each pass over the contacts' colours in turn,
/// then the contacts' overflow if it has constraints, then shock propagation's supports if it
/// has any (warm starting and solving: it has no restitution), then the joint colours that have
/// joints
/// (the last being their overflow), then the joint trees' exact solve if there are `trees`;
/// the restitution pass (contacts only) only if `bouncy`
/// (some contact has restitution: the pass does nothing for the others). Joints have the last
/// word in each pass, as contacts with the ground have among contacts: a limb struck in a pile
/// is pulled back onto its joint before the pass ends. (Box2D solves joints first; in a pile
/// of ragdolls that parts their joints about twice as far.) With joint trees, the relaxation
/// solves the joints first and the trees again after the contacts: the trees hold exactly,
/// and the drift they leave is projected away by each solve that ends a substep.
fn plan_stages(
    plan: &mut Vec<Stage>,
    params: &SolverParams,
    environment: Environment,
    bias: &Bias,
    (joint_colors, trees): (&JointColors, bool),
    contacts: ContactStages,
) {
    plan.clear();
    // Room for as many stages as these settings can plan, whatever colours the contacts and
    // joints use, so that a step that uses one more colour than any before takes nothing
    // from the heap: in each pass every joint colour and the joints' overflow, the joint
    // trees (twice in a relaxation), every contact colour, the overflow and shock
    // propagation; the passes of each substep and its two integrations; the restitution pass.
    let per_pass = JOINT_COLOR_COUNT + 3 + COLOR_COUNT + 2;
    let substeps = params.substeps.max(1) as usize;
    let passes = substeps * (1 + 2 * params.effective_iterations() as usize) + 1;
    plan.reserve(passes * per_pass + 2 * substeps);
    let pass = |plan: &mut Vec<Stage>, pass: Pass| {
        // With joint trees, the relaxation solves the joints first and the trees again last.
        // First, because the exact trees alone last would end each substep on velocities that
        // drive bodies into their contacts, which the next substep pushes back out. Last,
        // because with the contacts' word last a limb pressed at a stop kept a velocity its
        // hinge does not allow, which the projection took back out of its position every
        // substep. Either way a pile of ragdolls could stay awake for good. Each tree solve
        // that ends a substep projects its drift away: before the contacts, which see the
        // positions, and at the end.
        let joints_first = trees && matches!(pass, Pass::Solve(bias, _) if !bias.use_bias);
        let add_joints = |plan: &mut Vec<Stage>| {
            if !matches!(pass, Pass::Restitution(_)) {
                let joints = joint_colors.ranges.iter().enumerate();
                let used = joints.filter(|(_, range)| !range.is_empty());
                plan.extend(used.map(|(color, _)| Stage::Joints(color, pass)));
                if trees {
                    plan.push(Stage::JointTrees(pass));
                }
            }
        };
        if joints_first {
            add_joints(plan);
        }
        plan.extend((0..contacts.colors).map(|color| Stage::Color(color, pass)));
        if contacts.overflow {
            plan.push(Stage::Overflow(pass));
        }
        if contacts.shock && !matches!(pass, Pass::Restitution(_)) {
            plan.push(Stage::Shock(pass));
        }
        if joints_first {
            plan.push(Stage::JointTrees(pass));
        } else {
            add_joints(plan);
        }
    };
    let bias_friction = environment.friction && params.friction_in_bias_pass;
    let iterations = params.effective_iterations();
    for _ in 0..params.substeps.max(1) {
        plan.push(Stage::IntegrateVelocities);
        pass(plan, Pass::WarmStart);
        for _ in 0..iterations {
            pass(plan, Pass::Solve(bias.pass(true), bias_friction));
        }
        plan.push(Stage::IntegratePositions);
        for i in 0..iterations {
            let relax = PassBias {
                substep_end: i + 1 == iterations,
                ..bias.pass(false)
            };
            pass(plan, Pass::Solve(relax, environment.friction));
        }
    }
    if environment.restitution && contacts.bouncy {
        pass(plan, Pass::Restitution(params.restitution_threshold));
    }
}

/// How the biased pass pushes overlap out in one substep.
pub(super) struct Bias {
    /// Softness of contacts between moving bodies.
    pub soft: Softness,
    /// Softness of contacts with static bodies (stiffer).
    pub static_soft: Softness,
    /// One over the substep.
    pub inv_h: Real,
    /// The fastest push-out, m/s.
    pub max_push_speed: Real,
}

impl Bias {
    /// The biases of `params` for substeps of `h`.
    pub(crate) fn new(params: &SolverParams, h: Real) -> Self {
        let inv_h = 1.0 / h;
        // Stiffer than a quarter of the substep rate would ring.
        let hertz = params.contact_hertz.min(0.25 * inv_h);
        Bias {
            soft: Softness::new(hertz, params.damping_ratio, h),
            static_soft: Softness::new(params.static_stiffness * hertz, params.damping_ratio, h),
            inv_h,
            max_push_speed: params.max_push_speed,
        }
    }

    /// What the wide solver needs of it for one pass, biased or relaxing.
    pub(crate) fn pass(&self, use_bias: bool) -> PassBias {
        PassBias {
            use_bias,
            inv_h: self.inv_h,
            max_push_speed: self.max_push_speed,
            substep_end: false,
        }
    }
}
