//! One solver step over the awake set, the same three calls for every solver: prepare (copy
//! the awake bodies into states, order the contacts, prepare them and the joints as
//! constraints), solve (the chosen solver), and store (impulses back into contacts and joints
//! for the next warm start, states back into bodies through the speed caps).

use super::body_state::{BodyState, Drive, SpeedCaps};
use super::classic::{push_out, sequential_impulse, tutorial_impulse};
use super::contact_constraint::BodyMass;
use super::context::{AwakeJoint, AwakeSet, Environment, SolverContext, StepReport};
use super::joints::{JointBody, JointConstraint};
use super::params::{SolverKind, SolverParams};
use super::soft_step::{self, Bias, BundleInputs};
use super::workspace::Workspace;
use crate::constants::ITEMS_PER_TASK;
use crate::dynamics::body::Body;
use crate::graph::joints::JointStates;
use crate::graph::order::{ColorCheck, order_constraints};
use crate::joint::{Joint, JointKind};
use crate::math::Real;
use crate::parallel::{for_each_with, map_into};
use crate::stats::{Instant, Work};
use std::ops::Range;

/// Runs one step of the chosen solver over the awake set.
pub(crate) fn step(
    params: &SolverParams,
    environment: Environment,
    mut set: AwakeSet,
    dt: Real,
    workspace: &mut Workspace,
) -> StepReport {
    debug_assert!(
        set.contacts
            .iter()
            .zip(set.body_indices)
            .all(|(c, &[a, b])| {
                let is = |index: u32, body| {
                    let body_at = set.bodies.get(index as usize);
                    body_at.is_some_and(|x| x.handle() == body)
                };
                is(a, c.body_a()) && is(b, c.body_b())
            }),
        "every awake contact's bodies are where the narrowphase found them"
    );
    let started = Instant::now();
    let plan = prepare(params, environment, &set, dt, workspace);
    let prepare = started.elapsed();
    let work = solve(params, environment, dt, &plan, workspace);
    let storing = Instant::now();
    let (points, joints) = store(params, &mut set, dt, &plan, workspace);
    StepReport {
        joints,
        points,
        work,
        prepare,
        store: storing.elapsed(),
    }
}

/// What preparing decided for the rest of the step.
struct Plan {
    kind: SolverKind,
    /// Soft step's softness, which its bundles were prepared with.
    bias: Bias,
    /// The (sub)step the joints were prepared for.
    h: Real,
}

/// Copies the awake bodies into states, orders the touching contacts and prepares them (soft
/// step's coloured ones straight into SIMD bundles, the rest one by one), then the joints.
fn prepare(
    params: &SolverParams,
    environment: Environment,
    set: &AwakeSet,
    dt: Real,
    workspace: &mut Workspace,
) -> Plan {
    let AwakeSet {
        bodies,
        awake,
        contacts,
        body_indices,
        colors,
        joints,
        awake_joints,
    } = set;
    let Workspace {
        states,
        masses,
        drives,
        constraints,
        graph,
        wide,
        order,
        claims,
        demoted,
        joints: joint_constraints,
        joint_colors,
        joint_trees,
        shock,
        ..
    } = workspace;
    // Soft step solves colour by colour; the classic solvers, and soft step without colours,
    // one by one in contact order.
    let kind = params.effective_kind();
    let colored = kind == SolverKind::SoftStep && params.graph_coloring;
    // The awake bodies as the solver sees them, and a spare state past them: static bodies'
    // (at rest, immovable), and empty SIMD lanes'.
    let awake_bodies = &bodies[awake.clone()];
    map_into(awake_bodies, states, ITEMS_PER_TASK, BodyState::from_body);
    states.push(BodyState::spare());
    map_into(awake_bodies, masses, ITEMS_PER_TASK, BodyMass::of);
    masses.push(BodyMass::default());
    map_into(awake_bodies, drives, ITEMS_PER_TASK, Drive::of);
    let check = ColorCheck {
        moves: |i: usize| masses[i].dynamic,
        awake: awake.clone(),
        body_indices,
        claims,
    };
    order_constraints(
        |i| contacts[i].serial(),
        colors,
        colored.then_some(check),
        order,
        graph,
        demoted,
    );
    let bias = Bias::new(params, dt / params.substeps.max(1) as Real);
    let inputs = BundleInputs {
        awake: awake.clone(),
        states,
        masses,
        contacts,
        body_indices,
        order,
        graph,
        soft: bias.soft,
        static_soft: bias.static_soft,
        warm_starting: params.warm_starting,
    };
    if kind == SolverKind::SoftStep && params.shock_propagation {
        let up = environment.gravity.filter(|g| g.norm() > 0.0);
        shock.plan(&inputs, up.map(|g| -g.normalize()));
    } else {
        shock.clear();
    }
    let one_by_one: &[usize] = if colored {
        wide.prepare(&inputs);
        &wide.overflow
    } else {
        wide.clear();
        order
    };
    map_into(one_by_one, constraints, ITEMS_PER_TASK, |&i| {
        inputs.constraint(i)
    });
    // The joints, prepared for the step's substeps (soft step) or the whole step.
    let h = if kind.has_substeps() {
        dt / params.substeps.max(1) as Real
    } else {
        dt
    };
    let joint_inputs = JointInputs {
        bodies,
        awake: awake.clone(),
        joints,
        awake_joints,
    };
    joint_colors.order(
        awake_joints.len(),
        |i| joint_inputs.states(i),
        colored,
        states.len(),
    );
    map_into(
        &joint_colors.order,
        joint_constraints,
        ITEMS_PER_TASK,
        |&i| joint_inputs.prepare(i, h, params.warm_starting),
    );
    if kind == SolverKind::SoftStep && params.direct_joints {
        joint_trees.plan(joint_constraints, states.len());
    } else {
        joint_trees.clear();
    }
    Plan { kind, bias, h }
}

/// Runs the chosen solver on the prepared states and constraints.
fn solve(
    params: &SolverParams,
    environment: Environment,
    dt: Real,
    plan: &Plan,
    workspace: &mut Workspace,
) -> Work {
    let Workspace {
        states,
        drives,
        constraints,
        wide,
        plan: stages,
        joints,
        joint_colors,
        joint_trees,
        shock,
        ..
    } = workspace;
    let context = SolverContext {
        params,
        environment,
        drives,
        dt,
    };
    // Push-out and the tutorial's impulses predate joints: they leave them out.
    match plan.kind {
        SolverKind::PushOut => push_out::solve(&context, states, constraints),
        SolverKind::TutorialImpulse => tutorial_impulse::solve(&context, states, constraints),
        SolverKind::SequentialImpulse => {
            sequential_impulse::solve(&context, states, constraints, joints)
        }
        SolverKind::SoftStep => soft_step::solve(
            &context,
            states,
            (constraints, shock),
            (joints, joint_colors, joint_trees),
            wide,
            stages,
            &plan.bias,
        ),
    }
}

/// Stores the impulses in the joints and contacts they came from, for the next step's warm
/// start, and writes the states back into the bodies through the speed caps; returns how many
/// contact points and joints were solved.
fn store(
    params: &SolverParams,
    set: &mut AwakeSet,
    dt: Real,
    plan: &Plan,
    workspace: &mut Workspace,
) -> (usize, usize) {
    let Workspace {
        states,
        constraints,
        wide,
        joints: joint_constraints,
        joint_colors,
        shock,
        order,
        ..
    } = workspace;
    let solved_joints = matches!(
        plan.kind,
        SolverKind::SequentialImpulse | SolverKind::SoftStep
    );
    let caps = SpeedCaps::new(params, dt);
    if solved_joints {
        // Joint by joint through the awake joints, which sit side by side in the store, each
        // finding its constraint by its place in the order: on all threads.
        let first = set.awake_joints.first().map_or(0, |j| j.index as usize);
        debug_assert!(
            (set.awake_joints.iter().enumerate()).all(|(i, j)| j.index as usize == first + i),
            "the awake joints sit side by side"
        );
        let awake = &mut set.joints[first..first + set.awake_joints.len()];
        let places = &joint_colors.places;
        let constraints = &joint_constraints[..];
        let inv_h = 1.0 / plan.h;
        for_each_with(places, awake, ITEMS_PER_TASK, |&place, joint| {
            let Some(c) = constraints.get(place) else {
                return;
            };
            joint.impulses = c.impulses_to_keep(states, caps);
            let (force, torque) = c.reaction(inv_h);
            joint.set_reaction(force, torque);
        });
    }
    wide.store(set.contacts);
    for constraint in constraints.iter() {
        constraint.store_impulses(&mut set.contacts[constraint.contact_index]);
    }
    if params.shock_propagation && plan.kind == SolverKind::SoftStep {
        shock.store(set.contacts, order);
    }
    let bodies = &mut set.bodies[set.awake.clone()];
    for_each_with(states, bodies, ITEMS_PER_TASK, |state, body| {
        state.write_back(body, caps)
    });
    let points: usize = constraints.iter().map(|c| c.points().len()).sum();
    let joints = if solved_joints {
        joint_constraints.len()
    } else {
        0
    };
    (points + wide.point_count(), joints)
}

/// What preparing the step's joints reads.
struct JointInputs<'a> {
    /// Every body; the awake ones are `bodies[awake]`, whose states come first, then the
    /// spare state (a body outside the awake set).
    bodies: &'a [Body],
    awake: Range<usize>,
    joints: &'a [Joint],
    awake_joints: &'a [AwakeJoint],
}

impl JointInputs<'_> {
    /// A joint's body at dense index `index`, as the solver takes it.
    fn side(&self, index: u32) -> JointBody<'_> {
        let index = index as usize;
        let body = &self.bodies[index];
        let is_awake = self.awake.contains(&index);
        JointBody {
            body,
            state: if is_awake {
                index - self.awake.start
            } else {
                self.awake.len()
            },
            moves: is_awake && body.is_dynamic(),
        }
    }

    /// The states awake joint `i` touches and which it moves; `None` for a filter joint,
    /// which has nothing to solve. A mouse joint moves only its one body.
    fn states(&self, i: usize) -> Option<JointStates> {
        let AwakeJoint { index, bodies } = self.awake_joints[i];
        let kind = self.joints[index as usize].kind();
        if matches!(kind, JointKind::Filter) {
            return None;
        }
        let [a, b] = bodies.map(|body| self.side(body));
        if matches!(kind, JointKind::Mouse(_)) {
            return Some([(b.state, false), (b.state, b.moves)]);
        }
        Some([(a.state, a.moves), (b.state, b.moves)])
    }

    /// Awake joint `i` prepared for (sub)steps of `h`.
    fn prepare(&self, i: usize, h: Real, warm_starting: bool) -> JointConstraint {
        let AwakeJoint { index, bodies } = self.awake_joints[i];
        let joint = &self.joints[index as usize];
        let [a, b] = bodies.map(|body| self.side(body));
        JointConstraint::prepare(joint, a, b, h, warm_starting)
    }
}
