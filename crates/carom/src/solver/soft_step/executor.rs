//! The stage executor: runs a step's stage list (soft step plans it) over the bundles, the
//! overflow's constraints, the joints and the bodies, on as many threads as rayon gives, in
//! one parallel region. Each stage's blocks are lent to whichever thread claims them, and
//! [`super::scheduler`] puts a barrier between stages.

use super::Bias;
use super::inputs::PassBias;
use super::joint_trees::{JointTrees, TreeBlock};
use super::kernels::Bundle;
use super::lanes::{Kernel, Lanes};
use super::scalar::{apply_restitution, solve_one, warm_start_one};
use super::scheduler::{block_count, block_range, run_stages};
use super::shared_states::SharedStates;
use super::shock_propagation::ShockPropagation;
use crate::constants::{
    COLOR_COUNT, JOINT_COLOR_COUNT, MAX_BLOCKS, MIN_BLOCK, MIN_BODY_BLOCK, MIN_JOINT_BLOCK,
    MIN_SHARED,
};
use crate::graph::joints::JointColors;
use crate::math::Real;
use crate::solver::body_state::BodyState;
use crate::solver::body_state::{Drive, SpeedCaps, integrate_position, integrate_velocity};
use crate::solver::contact_constraint::ContactConstraint;
use crate::solver::context::Environment;
use crate::solver::joints::{JointConstraint, JointPass};
use crate::solver::params::SolverParams;
use crate::stats::Work;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// One pass over constraints.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Pass {
    WarmStart,
    /// A solve, biased or relaxing, with friction or not.
    Solve(PassBias, bool),
    /// Restitution, above this approach speed.
    Restitution(Real),
}

/// One stage of a step's solve, as [`WideContacts::execute`] runs it.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Stage {
    /// Forces, gravity and drag into the awake bodies' velocities.
    IntegrateVelocities,
    /// The velocities into the motion since the step began.
    IntegratePositions,
    /// A pass over the bundles of a colour (an index below [`WideContacts::color_count`]).
    Color(usize, Pass),
    /// The pass over the overflow's constraints, one by one.
    Overflow(Pass),
    /// A pass over the joints of a joint colour (the last is their overflow, one block).
    Joints(usize, Pass),
    /// The joint trees' exact solve (blocks of whole trees).
    JointTrees(Pass),
    /// Shock propagation's contacts between levels, from the ground up (one block).
    Shock(Pass),
}

/// What the stages read besides the states and constraints.
pub(crate) struct StageInputs<'a> {
    /// What integration reads of the awake bodies (their states come first).
    pub drives: &'a [Drive],
    pub environment: Environment,
    /// The substep, and the speed caps.
    pub h: Real,
    pub caps: SpeedCaps,
    /// Soft step's biases (the overflow's solve), and the settings (its restitution).
    pub bias: &'a Bias,
    pub params: &'a SolverParams,
}

/// A block of a colour's bundles, lent to whichever thread claims it.
type LentBlock<'a, L> = Option<Mutex<&'a mut [Bundle<L>]>>;

/// [`WideContacts::execute`] for bundles of one width.
#[allow(clippy::too_many_arguments)]
pub(super) fn execute_stages<L: Lanes>(
    bundles: &mut [Bundle<L>],
    colors: &[Range<usize>],
    plan: &[Stage],
    states: &SharedStates,
    all_states: Range<usize>,
    (overflow, shock): (&mut [ContactConstraint], &mut ShockPropagation),
    (joints, joint_colors, trees): (&mut [JointConstraint], &JointColors, &mut JointTrees),
    inputs: &StageInputs,
) -> (Work, usize) {
    let threads = rayon::current_num_threads();
    // A joint costs about what a bundle does.
    let shared = threads > 1 && bundles.len() + joints.len() >= MIN_SHARED;
    let joint_blocks = lend_joint_blocks(joints, joint_colors, shared, threads);
    let joint_block_counts = joint_blocks
        .each_ref()
        .map(|blocks| blocks.iter().filter(|b| b.is_some()).count());
    let joint_passes =
        [true, false].map(|use_bias| JointPass::soft(inputs.params, inputs.h, use_bias));
    // Every colour cut into blocks, each behind a lock that is never contended (a block is
    // claimed once a stage), which is how a block is lent mutably to whichever thread claims
    // it; the colour's stages all cut it the same way.
    let mut blocks: [[LentBlock<L>; MAX_BLOCKS]; COLOR_COUNT] =
        std::array::from_fn(|_| std::array::from_fn(|_| None));
    let mut color_blocks = [0; COLOR_COUNT];
    let mut rest = bundles;
    for (color, range) in colors.iter().enumerate() {
        let (mut of_color, after) = rest.split_at_mut(range.len());
        rest = after;
        let count = if shared {
            block_count(range.len(), MIN_BLOCK, threads)
        } else {
            1
        };
        for (block, slot) in blocks[color].iter_mut().take(count).enumerate() {
            let size = block_range(range.len(), count, block).len();
            let (this, more) = of_color.split_at_mut(size);
            of_color = more;
            *slot = Some(Mutex::new(this));
        }
        color_blocks[color] = count;
    }
    let bodies = inputs.drives.len();
    let body_blocks = if shared {
        block_count(bodies, MIN_BODY_BLOCK, threads)
    } else {
        1
    };
    // Whole trees per block: the trees share no moving body, so a block writes only its own
    // trees' states, and reads besides only bodies that no joint moves.
    let tree_count = if shared {
        block_count(trees.joint_count(), MIN_JOINT_BLOCK, threads)
    } else {
        1
    };
    let tree_blocks = trees.blocks(tree_count).map(|block| block.map(Mutex::new));
    let tree_block_count = tree_blocks.iter().filter(|b| b.is_some()).count();
    let lent = LentStages {
        states,
        all_states,
        inputs,
        body_blocks,
        color_blocks: blocks,
        overflow: Mutex::new(overflow),
        shock: Mutex::new(shock),
        joint_blocks,
        joint_passes,
        tree_blocks,
        work: Mutex::new(Work::default()),
        bounces: AtomicUsize::new(0),
    };
    let stage_blocks = |stage: usize| match plan[stage] {
        Stage::IntegrateVelocities | Stage::IntegratePositions => body_blocks,
        Stage::Color(color, _) => color_blocks[color],
        Stage::Overflow(_) | Stage::Shock(_) => 1,
        Stage::JointTrees(_) => tree_block_count,
        Stage::Joints(color, _) => joint_block_counts[color],
    };
    run_stages(plan.len(), stage_blocks, shared, |stage, block| {
        lent.run(plan[stage], block)
    });
    (*lock(&lent.work), lent.bounces.into_inner())
}

/// One step's stages with their blocks lent out: each block behind a lock that is never
/// contended (a block is claimed once a stage), which is how it is lent mutably to whichever
/// thread claims it, and what the stages add up.
struct LentStages<'a, L: Lanes> {
    states: &'a SharedStates<'a>,
    /// Every state, the spare one included (the overflow's and the shock stage's reach).
    all_states: Range<usize>,
    inputs: &'a StageInputs<'a>,
    /// How many blocks the awake bodies are cut into.
    body_blocks: usize,
    /// Each colour's bundles, cut into blocks.
    color_blocks: [[LentBlock<'a, L>; MAX_BLOCKS]; COLOR_COUNT],
    overflow: Mutex<&'a mut [ContactConstraint]>,
    shock: Mutex<&'a mut ShockPropagation>,
    /// Each joint colour's joints, cut into blocks (the overflow's in one).
    joint_blocks: [[LentJoints<'a>; MAX_BLOCKS]; JOINT_COLOR_COUNT + 1],
    /// The joints' biased and relaxing passes.
    joint_passes: [JointPass; 2],
    /// Blocks of whole joint trees.
    tree_blocks: [Option<Mutex<TreeBlock<'a>>>; MAX_BLOCKS],
    /// The work the effects did, and how many constraints bounced.
    work: Mutex<Work>,
    bounces: AtomicUsize,
}

impl<L: Lanes> LentStages<'_, L> {
    /// Runs block `block` of `stage`.
    fn run(&self, stage: Stage, block: usize) {
        match stage {
            Stage::IntegrateVelocities | Stage::IntegratePositions => {
                self.integrate(stage, block);
            }
            Stage::Color(color, pass) => self.color(color, pass, block),
            Stage::Overflow(pass) => self.overflow(pass),
            Stage::Shock(pass) => self.shock(pass),
            Stage::Joints(color, pass) => self.joints(color, pass, block),
            Stage::JointTrees(pass) => self.joint_trees(pass, block),
        }
    }

    /// An integration stage over one block of the awake bodies.
    fn integrate(&self, stage: Stage, block: usize) {
        let drives = self.inputs.drives;
        let range = block_range(drives.len(), self.body_blocks, block);
        // SAFETY: integration's blocks are disjoint runs, and no other stage runs.
        #[allow(unsafe_code)]
        let block_states = unsafe { self.states.range_mut(range.clone()) };
        let done = integrate(stage, &drives[range], block_states, self.inputs);
        if let Some(done) = done {
            *lock(&self.work) += done;
        }
    }

    /// A pass over one block of a colour's bundles.
    fn color(&self, color: usize, pass: Pass, block: usize) {
        if let Some(block) = &self.color_blocks[color][block] {
            let mut block = lock(block);
            let count = L::run(PassBlock {
                block: &mut block,
                states: self.states,
                pass,
            });
            self.bounces.fetch_add(count, Ordering::Relaxed);
        }
    }

    /// A pass over the overflow's constraints, one by one.
    fn overflow(&self, pass: Pass) {
        let mut constraints = lock(&self.overflow);
        // SAFETY: the overflow's stage is one block, and no other stage runs.
        #[allow(unsafe_code)]
        let all = unsafe { self.states.range_mut(self.all_states.clone()) };
        let count = overflow_pass(pass, &mut constraints, all, self.inputs);
        self.bounces.fetch_add(count, Ordering::Relaxed);
    }

    /// A pass over shock propagation's supports (one block, and no other stage runs).
    fn shock(&self, pass: Pass) {
        let mut shock = lock(&self.shock);
        match pass {
            Pass::WarmStart => shock.warm_start(self.states),
            Pass::Solve(bias, friction) => {
                shock.solve(self.states, self.inputs.bias, bias.use_bias, friction)
            }
            Pass::Restitution(_) => {}
        }
    }

    /// A pass over one block of a joint colour's joints.
    fn joints(&self, color: usize, pass: Pass, block: usize) {
        if let Some(block) = &self.joint_blocks[color][block] {
            joint_pass(pass, &mut lock(block), self.states, &self.joint_passes);
        }
    }

    /// The joint trees' pass over one block of whole trees, with the projection at the end of
    /// each substep.
    fn joint_trees(&self, pass: Pass, block: usize) {
        if let Some(block) = &self.tree_blocks[block] {
            let mut trees = lock(block);
            match pass {
                Pass::WarmStart => trees.warm_start(self.states),
                Pass::Solve(bias, _) => {
                    trees.solve(self.states, &self.joint_passes[usize::from(!bias.use_bias)]);
                    if bias.substep_end {
                        trees.project(self.states);
                    }
                }
                Pass::Restitution(_) => {}
            }
        }
    }
}

/// Integration stage `stage` over a block of the awake bodies and their states: velocities
/// (returning the work the effects did) or positions.
fn integrate(
    stage: Stage,
    drives: &[Drive],
    states: &mut [BodyState],
    inputs: &StageInputs,
) -> Option<Work> {
    let (h, caps) = (inputs.h, inputs.caps);
    if let Stage::IntegratePositions = stage {
        for (drive, state) in drives.iter().zip(states) {
            integrate_position(drive, state, h, caps);
        }
        return None;
    }
    let mut done = Work::default();
    for (drive, state) in drives.iter().zip(states) {
        done += integrate_velocity(inputs.environment, drive, state, h, caps);
    }
    Some(done)
}

/// A pass over the overflow's constraints, one by one, on every state; returns how many
/// restitution impulses it computed.
fn overflow_pass(
    pass: Pass,
    constraints: &mut [ContactConstraint],
    states: &mut [BodyState],
    inputs: &StageInputs,
) -> usize {
    match pass {
        Pass::WarmStart => {
            for c in constraints.iter_mut() {
                warm_start_one(c, states);
            }
        }
        Pass::Solve(bias, friction) => {
            for c in constraints.iter_mut() {
                solve_one(c, states, inputs.bias, bias.use_bias, friction);
                if bias.substep_end {
                    c.note_substep_impulses();
                }
            }
        }
        Pass::Restitution(_) => return apply_restitution(inputs.params, constraints, states),
    }
    0
}

/// A pass over a block of one joint colour's joints (restitution has none); `passes` are the
/// joints' biased and relaxing passes.
fn joint_pass(
    pass: Pass,
    block: &mut [JointConstraint],
    states: &SharedStates,
    passes: &[JointPass; 2],
) {
    for joint in block.iter_mut() {
        let mut a = states.get(joint.a);
        let mut b = states.get(joint.b);
        match pass {
            Pass::WarmStart => joint.warm_start(&mut a, &mut b),
            Pass::Solve(bias, _) => {
                joint.solve(&mut a, &mut b, &passes[usize::from(!bias.use_bias)])
            }
            Pass::Restitution(_) => {}
        }
        if joint.moves_a {
            states.set_velocity(joint.a, &a);
        }
        if joint.moves_b {
            states.set_velocity(joint.b, &b);
        }
    }
}

/// The joints of each joint colour cut into blocks (one for the overflow, the last colour),
/// each lent to whichever thread claims it.
fn lend_joint_blocks<'a>(
    joints: &'a mut [JointConstraint],
    colors: &JointColors,
    shared: bool,
    threads: usize,
) -> [[LentJoints<'a>; MAX_BLOCKS]; JOINT_COLOR_COUNT + 1] {
    let mut lent: [[LentJoints; MAX_BLOCKS]; JOINT_COLOR_COUNT + 1] =
        std::array::from_fn(|_| std::array::from_fn(|_| None));
    let mut rest = joints;
    let overflow = colors.ranges.len().saturating_sub(1);
    for ((color, range), blocks) in colors.ranges.iter().enumerate().zip(&mut lent) {
        let (mut of_color, after) = rest.split_at_mut(range.len());
        rest = after;
        let count = if shared && color != overflow {
            block_count(range.len(), MIN_JOINT_BLOCK, threads)
        } else {
            1
        };
        if !range.is_empty() {
            for (block, slot) in blocks.iter_mut().take(count).enumerate() {
                let size = block_range(range.len(), count, block).len();
                let (this, more) = of_color.split_at_mut(size);
                of_color = more;
                *slot = Some(Mutex::new(this));
            }
        }
    }
    lent
}

/// A block of a joint colour's joints, lent to whichever thread claims it.
type LentJoints<'a> = Option<Mutex<&'a mut [JointConstraint]>>;

/// A lock taken even if a panicking thread poisoned it (the panic is passed on anyway).
fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|e| e.into_inner())
}

/// A pass over a block of bundles of one colour.
struct PassBlock<'a, L: Lanes> {
    block: &'a mut [Bundle<L>],
    states: &'a SharedStates<'a>,
    pass: Pass,
}

impl<L: Lanes> Kernel for PassBlock<'_, L> {
    /// Impulses restitution computed.
    type Output = usize;

    #[inline(always)]
    fn run(self) -> usize {
        let states = self.states;
        let mut count = 0;
        match self.pass {
            Pass::WarmStart => {
                for bundle in self.block.iter_mut() {
                    bundle.warm_start(states);
                }
            }
            Pass::Solve(bias, friction) => {
                for bundle in self.block.iter_mut() {
                    bundle.solve(states, bias, friction);
                }
            }
            Pass::Restitution(threshold) => {
                for bundle in self.block.iter_mut() {
                    count += bundle.restitution(states, threshold);
                }
            }
        }
        count
    }
}
