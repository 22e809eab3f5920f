//! Soft step's contact solve several constraints at a time: the contacts of one graph colour
//! (no shared moving body) are prepared straight into bundles of [`Lanes::WIDTH`] constraints,
//! stored as structures of arrays, and solved with SIMD lanes, the bodies gathered into lanes
//! by transposes and their velocities scattered back in place. Eight lanes where the CPU has
//! AVX, four elsewhere. The arithmetic per lane is the scalar solver's ([`super::soft_step`])
//! operation for operation, summed in the same order, so a lane gives the scalar result bit for
//! bit at either width (tested); only the order of constraints differs (colour by colour).
//!
//! [`WideContacts::execute`] runs a step's stages (soft step lists them) over the bundles, the
//! overflow's constraints and the bodies, on all threads.

#[cfg(target_arch = "x86_64")]
use super::avx_lanes::{self, Avx8};
use super::body_state::{SpeedCaps, integrate_position, integrate_velocity};
use super::contact_constraint::{BodyMass, ConstraintPoint, ContactConstraint, SolverBody};
use super::contact_graph::ContactGraph;
use super::joints::{JointColors, JointConstraint, JointPass};
use super::lanes::{Kernel, Lanes};
use super::shared_states::SharedStates;
use super::soft_step::{Bias, apply_restitution, solve_one, warm_start_one};
use super::stages::{block_count, block_range, run_stages};
use super::{BodyState, Environment, Softness, SolverParams};
use crate::collision::contact::{BodyIndices, Contact, PointImpulse};
use crate::constants::{
    COLOR_COUNT, ITEMS_PER_TASK, JOINT_COLOR_COUNT, MAX_BLOCKS, MIN_BLOCK, MIN_BODY_BLOCK,
    MIN_JOINT_BLOCK, MIN_SHARED,
};
use crate::dynamics::body::Body;
use crate::math::Real;
use crate::parallel::{for_each_chunk_with, worth_sharing};
use crate::stats::Work;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use wide::f32x4;

/// How many constraints the solver takes at a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Width {
    /// `wide`'s four lanes, on every CPU.
    Four,
    /// AVX's eight lanes (x86-64 CPUs with AVX).
    #[cfg(target_arch = "x86_64")]
    Eight,
}

impl Width {
    /// The widest this CPU runs.
    pub fn widest() -> Width {
        #[cfg(target_arch = "x86_64")]
        if avx_lanes::detected() {
            return Width::Eight;
        }
        Width::Four
    }
}

/// One contact point of a bundle's constraints.
#[derive(Debug, Clone, Copy)]
struct WidePoint<L> {
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
    max_normal_impulse: L,
    relative_velocity: L,
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
            field.lanes_mut()[lane] = value;
        }
    }
}

/// [`Lanes::WIDTH`] constraints; lanes past the colour's end are empty (zero masses, no
/// impulse, the spare state for both bodies).
#[derive(Debug, Clone, Copy)]
struct Bundle<L: Lanes> {
    /// Each lane's contact, an index into the awake contacts (`u32::MAX` when empty).
    contacts: L::Indices,
    /// Body states (the spare state for a static body or an empty lane).
    a: L::Indices,
    b: L::Indices,
    /// One bit per lane: whether A (B) takes impulses (a dynamic body). Only those velocities
    /// are written back, as Box2D skips static ones, so a static or kinematic body's velocity
    /// is never touched (nor shared between threads' caches) whatever the lanes computed.
    writes_a: u32,
    writes_b: u32,
    /// Manifold points in all lanes (for the step's statistics).
    point_count: u32,
    inv_mass_a: L,
    inv_inertia_a: L,
    inv_mass_b: L,
    inv_inertia_b: L,
    normal_x: L,
    normal_y: L,
    friction: L,
    restitution: L,
    /// Soft step's coefficients per lane (stiffer against static bodies).
    bias_rate: L,
    mass_scale: L,
    impulse_scale: L,
    points: [WidePoint<L>; 2],
}

/// Four or eight bodies' states in lanes.
#[derive(Debug, Clone, Copy)]
struct WideBody<L> {
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

/// The bundles of one width.
#[derive(Debug, Clone)]
enum Bundles {
    Four(Vec<Bundle<f32x4>>),
    #[cfg(target_arch = "x86_64")]
    Eight(Vec<Bundle<Avx8>>),
}

/// Evaluates `$body` with `$bundles` bound to the bundles of whichever width they are.
macro_rules! with_bundles {
    ($bundles:expr, |$b:ident| $body:expr) => {
        match $bundles {
            Bundles::Four($b) => $body,
            #[cfg(target_arch = "x86_64")]
            Bundles::Eight($b) => $body,
        }
    };
}

/// The coloured constraints of a step in bundles, colour by colour, and the contacts left
/// over for the scalar solver.
#[derive(Debug, Clone)]
pub(crate) struct WideContacts {
    bundles: Bundles,
    /// Each colour's bundles, as a range of the bundles.
    colors: Vec<Range<usize>>,
    /// Per bundle, its contacts: a range of the solve order.
    slots: Vec<Range<usize>>,
    /// Awake contacts (indices) solved one by one after the colours: those no colour was free
    /// for.
    pub overflow: Vec<usize>,
    /// Some bundle's contact has restitution (else the restitution pass has nothing to do).
    bouncy: bool,
}

impl Default for WideContacts {
    fn default() -> Self {
        WideContacts::new(Width::widest())
    }
}

/// How a pass treats overlap: soft step's biased solve or its relaxation.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PassBias {
    pub use_bias: bool,
    pub inv_h: Real,
    pub max_push_speed: Real,
    /// The substep's last pass: each point's accumulated normal impulse is then what the
    /// substep applied, and the largest is kept for the user.
    pub substep_end: bool,
}

/// What preparing the constraints reads.
pub(crate) struct BundleInputs<'a> {
    /// Where the awake set's bodies are among all bodies (dense indices).
    pub awake: Range<usize>,
    /// The awake bodies' states and masses, then the spare state's (a static body's).
    pub states: &'a [BodyState],
    pub masses: &'a [BodyMass],
    /// The awake contacts, and where each one's bodies are among all bodies.
    pub contacts: &'a [Contact],
    pub body_indices: &'a [BodyIndices],
    /// The solve order (contact indices) and its colours.
    pub order: &'a [usize],
    pub graph: &'a ContactGraph,
    /// Softness against moving and static partners.
    pub soft: Softness,
    pub static_soft: Softness,
    /// Start from last step's impulses (else from zero).
    pub warm_starting: bool,
}

impl BundleInputs<'_> {
    /// A contact's body at dense index `index`, as the solver takes it: its state, or the
    /// spare state (past the awake ones) if it is not in the awake set.
    fn solver_body(&self, index: usize) -> SolverBody {
        let awake = self.awake.contains(&index);
        let index = if awake {
            index - self.awake.start
        } else {
            self.awake.len()
        };
        let state = &self.states[index];
        SolverBody {
            index,
            mass: self.masses[index],
            v: state.v,
            w: state.w,
            awake,
        }
    }

    /// Contact `index` prepared as a constraint.
    pub fn constraint(&self, index: usize) -> ContactConstraint {
        let contact = &self.contacts[index];
        let material = (contact.friction(), contact.restitution());
        let [a, b] = self.body_indices[index].map(|i| self.solver_body(i as usize));
        let mut constraint = ContactConstraint::new(index, contact.manifold(), material, a, b);
        if !self.warm_starting {
            for point in constraint.points_mut() {
                point.normal_impulse = 0.0;
                point.tangent_impulse = 0.0;
            }
        }
        constraint
    }
}

impl WideContacts {
    /// No bundles yet, of `width` (four lanes if the CPU lacks AVX for eight).
    pub fn new(width: Width) -> Self {
        let bundles = match width {
            Width::Four => Bundles::Four(Vec::new()),
            // An `Avx8` may only exist on a CPU with AVX.
            #[cfg(target_arch = "x86_64")]
            Width::Eight if avx_lanes::detected() => Bundles::Eight(Vec::new()),
            #[cfg(target_arch = "x86_64")]
            Width::Eight => Bundles::Four(Vec::new()),
        };
        WideContacts {
            bundles,
            colors: Vec::new(),
            slots: Vec::new(),
            overflow: Vec::new(),
            bouncy: false,
        }
    }

    /// How many constraints a bundle holds.
    pub fn width(&self) -> usize {
        with_bundles!(&self.bundles, |bundles| lanes_of(bundles))
    }

    /// Forgets the bundles (a step that solves no colour).
    pub fn clear(&mut self) {
        with_bundles!(&mut self.bundles, |bundles| bundles.clear());
        self.colors.clear();
        self.slots.clear();
        self.overflow.clear();
        self.bouncy = false;
    }

    /// Prepares the coloured contacts into bundles (on all threads), reusing last step's
    /// memory, and lists the overflow's contacts.
    pub fn prepare(&mut self, inputs: &BundleInputs) {
        let width = self.width();
        self.slots.clear();
        self.colors.clear();
        self.colors.reserve(COLOR_COUNT);
        for members in inputs.graph.colors() {
            if members.is_empty() {
                continue;
            }
            let start = self.slots.len();
            self.slots.extend(
                members
                    .clone()
                    .step_by(width)
                    .map(|from| from..(from + width).min(members.end)),
            );
            self.colors.push(start..self.slots.len());
        }
        let spare = inputs.awake.len() as u32;
        let softness = [inputs.soft, inputs.static_soft];
        let slots = &self.slots;
        self.bouncy = with_bundles!(&mut self.bundles, |bundles| {
            prepare_bundles(bundles, slots, inputs, softness, spare);
            let zero = Lanes::splat(0.0);
            bundles.iter().any(|b| b.restitution.gt(zero).bits() != 0)
        });
        self.overflow.clear();
        self.overflow
            .extend(inputs.graph.overflow.iter().map(|&at| inputs.order[at]));
    }

    /// Manifold points in the bundles.
    pub fn point_count(&self) -> usize {
        with_bundles!(&self.bundles, |bundles| bundles
            .iter()
            .map(|b| b.point_count as usize)
            .sum())
    }

    /// True when some bundle's contact has restitution.
    pub fn bouncy(&self) -> bool {
        self.bouncy
    }

    /// How many colours have bundles ([`Stage::Color`] takes an index below it).
    pub fn color_count(&self) -> usize {
        self.colors.len()
    }

    /// Runs `plan`, stage after stage, on as many threads as rayon gives (in one parallel
    /// region) when there is enough to share: the stages over the bundles, the overflow's
    /// constraints one by one, and the integration of the awake bodies (`inputs.bodies`, whose
    /// states come first in `states`). Returns the work integration did and how many
    /// restitution impulses were computed.
    #[allow(unsafe_code)]
    pub fn execute(
        &mut self,
        plan: &[Stage],
        states: &mut [BodyState],
        overflow: &mut [ContactConstraint],
        joints: (&mut [JointConstraint], &JointColors),
        inputs: &StageInputs,
    ) -> (Work, usize) {
        let all = 0..states.len();
        // SAFETY: the stages run one after another (`run_stages`). Within a colour's stage the
        // bundles write no state that another bundle of the colour reads or writes (checked
        // as the order was built, `solver::ColorCheck`), nor do a joint colour's joints (the
        // joint colouring only puts a joint in a colour none of whose joints moves its
        // bodies); integration's blocks borrow disjoint runs of states, and the overflow's
        // stage is one block, alone (`range_mut` below).
        let states = unsafe { SharedStates::new(states) };
        let colors = &self.colors;
        with_bundles!(&mut self.bundles, |bundles| {
            execute_stages(
                bundles, colors, plan, &states, all, overflow, joints, inputs,
            )
        })
    }

    /// Copies the impulses back into the contacts' manifolds, for the next step's warm start
    /// (on all threads when there are enough).
    pub fn store(&self, contacts: &mut [Contact]) {
        self.store_in_tasks_of(contacts, ITEMS_PER_TASK / self.width());
    }

    /// [`WideContacts::store`] in tasks of at least `per_task` bundles.
    pub(super) fn store_in_tasks_of(&self, contacts: &mut [Contact], per_task: usize) {
        let colors = &self.colors;
        with_bundles!(&self.bundles, |bundles| store_bundles(
            bundles, colors, contacts, per_task
        ));
    }
}

#[cfg(test)]
impl WideContacts {
    /// Runs one pass over every colour (on the current rayon pool), as a step's stages do.
    fn run_pass(&mut self, states: &mut [BodyState], pass: Pass) -> usize {
        let plan: Vec<Stage> = (0..self.color_count())
            .map(|color| Stage::Color(color, pass))
            .collect();
        let params = SolverParams::default();
        let bias = Bias::new(&params, 1.0 / 240.0);
        let inputs = StageInputs {
            bodies: &[],
            environment: Environment {
                gravity: None,
                drag: None,
                friction: true,
                restitution: true,
            },
            h: 1.0 / 240.0,
            caps: SpeedCaps::new(&params, 1.0 / 60.0),
            bias: &bias,
            params: &params,
        };
        let joints = (&mut [][..], &JointColors::default());
        self.execute(&plan, states, &mut [], joints, &inputs).1
    }

    /// Applies the accumulated impulses (warm start).
    pub fn warm_start(&mut self, states: &mut [BodyState]) {
        self.run_pass(states, Pass::WarmStart);
    }

    /// One pass: non-penetration (soft-biased or relaxed), then friction if asked.
    pub fn solve(&mut self, states: &mut [BodyState], pass: PassBias, friction: bool) {
        self.run_pass(states, Pass::Solve(pass, friction));
    }

    /// Bounces; returns how many impulses were computed.
    pub fn restitution(&mut self, states: &mut [BodyState], threshold: Real) -> usize {
        self.run_pass(states, Pass::Restitution(threshold))
    }

    /// Each contact's points' normal, tangent and total normal impulses.
    pub fn impulses(&self) -> std::collections::HashMap<usize, [(Real, Real, Real); 2]> {
        let mut out = std::collections::HashMap::new();
        with_bundles!(&self.bundles, |bundles| {
            for bundle in bundles {
                for (lane, &contact) in bundle.contacts.as_ref().iter().enumerate() {
                    let points = bundle.points.map(|p| {
                        (
                            p.normal_impulse.lane(lane),
                            p.tangent_impulse.lane(lane),
                            p.total_normal_impulse.lane(lane),
                        )
                    });
                    out.insert(contact as usize, points);
                }
            }
        });
        out
    }

    /// Sets a point's accumulated normal impulse in contact `contact`'s lane.
    pub fn set_normal_impulse(&mut self, contact: usize, point: usize, value: Real) {
        with_bundles!(&mut self.bundles, |bundles| {
            if let Some((bundle, lane)) = lane_of(bundles, contact) {
                let field = &mut bundle.points[point].normal_impulse;
                *field = with_lane(*field, lane, value);
            }
        });
    }

    /// Sets contact `contact`'s restitution.
    pub fn set_restitution(&mut self, contact: usize, value: Real) {
        with_bundles!(&mut self.bundles, |bundles| {
            if let Some((bundle, lane)) = lane_of(bundles, contact) {
                bundle.restitution = with_lane(bundle.restitution, lane, value);
            }
        });
    }

    /// Sets a point's approach speed at the start of the step in contact `contact`'s lane.
    pub fn set_relative_velocity(&mut self, contact: usize, point: usize, value: Real) {
        with_bundles!(&mut self.bundles, |bundles| {
            if let Some((bundle, lane)) = lane_of(bundles, contact) {
                let field = &mut bundle.points[point].relative_velocity;
                *field = with_lane(*field, lane, value);
            }
        });
    }
}

/// The bundle and lane holding contact `contact`.
#[cfg(test)]
fn lane_of<L: Lanes>(bundles: &mut [Bundle<L>], contact: usize) -> Option<(&mut Bundle<L>, usize)> {
    bundles.iter_mut().find_map(|bundle| {
        let lane = bundle
            .contacts
            .as_ref()
            .iter()
            .position(|&c| c as usize == contact)?;
        Some((bundle, lane))
    })
}

/// `lanes` with lane `lane` set to `value`.
#[cfg(test)]
fn with_lane<L: Lanes>(lanes: L, lane: usize, value: Real) -> L {
    let mut values = [0.0; 8];
    lanes.write_to(&mut values);
    values[lane] = value;
    L::from_slice(&values)
}

/// The width of a slice of bundles.
fn lanes_of<L: Lanes>(_: &[Bundle<L>]) -> usize {
    L::WIDTH
}

/// Prepares one bundle per slot, in place (on all threads).
fn prepare_bundles<L: Lanes>(
    bundles: &mut Vec<Bundle<L>>,
    slots: &[Range<usize>],
    inputs: &BundleInputs,
    softness: [Softness; 2],
    spare: u32,
) {
    bundles.resize_with(slots.len(), Bundle::empty);
    for_each_chunk_with(
        slots,
        bundles,
        ITEMS_PER_TASK / L::WIDTH,
        |slots, bundles| {
            L::run(Prepare {
                slots,
                bundles,
                inputs,
                softness,
                spare,
            })
        },
    );
}

/// Prepares bundles from their slots.
struct Prepare<'a, L: Lanes> {
    slots: &'a [Range<usize>],
    bundles: &'a mut [Bundle<L>],
    inputs: &'a BundleInputs<'a>,
    softness: [Softness; 2],
    spare: u32,
}

impl<L: Lanes> Kernel for Prepare<'_, L> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        for (slot, bundle) in self.slots.iter().zip(self.bundles) {
            let members = &self.inputs.order[slot.clone()];
            bundle.prepare(self.inputs, members, self.softness, self.spare);
        }
    }
}

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
}

/// What the stages read besides the states and constraints.
pub(crate) struct StageInputs<'a> {
    /// The awake bodies (their states come first).
    pub bodies: &'a [Body],
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
fn execute_stages<L: Lanes>(
    bundles: &mut [Bundle<L>],
    colors: &[Range<usize>],
    plan: &[Stage],
    states: &SharedStates,
    all_states: Range<usize>,
    overflow: &mut [ContactConstraint],
    (joints, joint_colors): (&mut [JointConstraint], &JointColors),
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
    let bodies = inputs.bodies;
    let body_blocks = if shared {
        block_count(bodies.len(), MIN_BODY_BLOCK, threads)
    } else {
        1
    };
    let overflow = Mutex::new(overflow);
    let work = Mutex::new(Work::default());
    let bounces = AtomicUsize::new(0);
    let stage_blocks = |stage: usize| match plan[stage] {
        Stage::IntegrateVelocities | Stage::IntegratePositions => body_blocks,
        Stage::Color(color, _) => color_blocks[color],
        Stage::Overflow(_) => 1,
        Stage::Joints(color, _) => joint_block_counts[color],
    };
    run_stages(
        plan.len(),
        stage_blocks,
        shared,
        |stage, block| match plan[stage] {
            Stage::IntegrateVelocities => {
                let range = block_range(bodies.len(), body_blocks, block);
                // SAFETY: integration's blocks are disjoint runs, and no other stage runs.
                #[allow(unsafe_code)]
                let block_states = unsafe { states.range_mut(range.clone()) };
                let mut done = Work::default();
                for (body, state) in bodies[range].iter().zip(block_states) {
                    done +=
                        integrate_velocity(inputs.environment, body, state, inputs.h, inputs.caps);
                }
                *lock(&work) += done;
            }
            Stage::IntegratePositions => {
                let range = block_range(bodies.len(), body_blocks, block);
                // SAFETY: as above.
                #[allow(unsafe_code)]
                let block_states = unsafe { states.range_mut(range.clone()) };
                for (body, state) in bodies[range].iter().zip(block_states) {
                    integrate_position(body, state, inputs.h, inputs.caps);
                }
            }
            Stage::Color(color, pass) => {
                if let Some(block) = &blocks[color][block] {
                    let mut block = lock(block);
                    let count = L::run(PassBlock {
                        block: &mut block,
                        states,
                        pass,
                    });
                    bounces.fetch_add(count, Ordering::Relaxed);
                }
            }
            Stage::Overflow(pass) => {
                let mut constraints = lock(&overflow);
                // SAFETY: the overflow's stage is one block, and no other stage runs.
                #[allow(unsafe_code)]
                let all = unsafe { states.range_mut(all_states.clone()) };
                match pass {
                    Pass::WarmStart => {
                        for c in constraints.iter_mut() {
                            warm_start_one(c, all);
                        }
                    }
                    Pass::Solve(bias, friction) => {
                        for c in constraints.iter_mut() {
                            solve_one(c, all, inputs.bias, bias.use_bias, friction);
                            if bias.substep_end {
                                c.note_substep_impulses();
                            }
                        }
                    }
                    Pass::Restitution(_) => {
                        let count = apply_restitution(inputs.params, &mut constraints, all);
                        bounces.fetch_add(count, Ordering::Relaxed);
                    }
                }
            }
            Stage::Joints(color, pass) => {
                if let Some(block) = &joint_blocks[color][block] {
                    let mut block = lock(block);
                    for joint in block.iter_mut() {
                        let mut a = states.get(joint.a);
                        let mut b = states.get(joint.b);
                        match pass {
                            Pass::WarmStart => joint.warm_start(&mut a, &mut b),
                            Pass::Solve(bias, _) => {
                                let pass = &joint_passes[usize::from(!bias.use_bias)];
                                joint.solve(&mut a, &mut b, pass);
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
            }
        },
    );
    (*lock(&work), bounces.into_inner())
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

/// Copies every bundle's impulses into its contacts, colour by colour (`colors` are each
/// colour's bundles). A colour's bundles hold its contacts in rising order, so halves of them
/// write disjoint halves of the contacts, which threads then share.
fn store_bundles<L: Lanes>(
    bundles: &[Bundle<L>],
    colors: &[Range<usize>],
    contacts: &mut [Contact],
    per_task: usize,
) {
    for range in colors {
        let bundles = &bundles[range.clone()];
        let Some(first) = bundles.first() else {
            continue;
        };
        let start = first.first_contact();
        store_halves(bundles, &mut contacts[start..], start, per_task);
    }
}

/// Stores `bundles` into `contacts`, which begin at contact `offset`: in halves on two threads
/// while the halves are at least `per_task` bundles.
fn store_halves<L: Lanes>(
    bundles: &[Bundle<L>],
    contacts: &mut [Contact],
    offset: usize,
    per_task: usize,
) {
    if !worth_sharing(bundles.len(), per_task) {
        L::run(Store {
            bundles,
            contacts,
            offset,
        });
        return;
    }
    let (low, high) = bundles.split_at(bundles.len() / 2);
    let at = high[0].first_contact() - offset;
    debug_assert!(low.iter().all(|b| b.last_contact() < offset + at));
    let (low_contacts, high_contacts) = contacts.split_at_mut(at);
    rayon::join(
        || store_halves(low, low_contacts, offset, per_task),
        || store_halves(high, high_contacts, offset + at, per_task),
    );
}

/// Copies bundles' impulses into their contacts, which begin at contact `offset`.
struct Store<'a, L: Lanes> {
    bundles: &'a [Bundle<L>],
    contacts: &'a mut [Contact],
    offset: usize,
}

impl<L: Lanes> Kernel for Store<'_, L> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        for bundle in self.bundles {
            bundle.store(self.contacts, self.offset);
        }
    }
}

impl<L: Lanes> Bundle<L> {
    /// A bundle of empty lanes, to be prepared.
    #[inline(always)]
    fn empty() -> Self {
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
    fn prepare(
        &mut self,
        inputs: &BundleInputs,
        members: &[usize],
        softness: [Softness; 2],
        spare: u32,
    ) {
        (self.writes_a, self.writes_b, self.point_count) = (0, 0, 0);
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
            let values = [
                a.mass.inv_mass,
                a.mass.inv_inertia,
                b.mass.inv_mass,
                b.mass.inv_inertia,
                normal.x,
                normal.y,
                contact.friction(),
                contact.restitution(),
                soft.bias_rate,
                soft.mass_scale,
                soft.impulse_scale,
            ];
            for (field, value) in self.fields_mut().into_iter().zip(values) {
                field.lanes_mut()[lane] = value;
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
    fn clear_lane(&mut self, lane: usize, spare: u32) {
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
    fn fields_mut(&mut self) -> [&mut L; 11] {
        [
            &mut self.inv_mass_a,
            &mut self.inv_inertia_a,
            &mut self.inv_mass_b,
            &mut self.inv_inertia_b,
            &mut self.normal_x,
            &mut self.normal_y,
            &mut self.friction,
            &mut self.restitution,
            &mut self.bias_rate,
            &mut self.mass_scale,
            &mut self.impulse_scale,
        ]
    }

    /// Gathers both sides' bodies.
    #[inline(always)]
    fn bodies(&self, states: &SharedStates) -> (WideBody<L>, WideBody<L>) {
        (
            WideBody::gather(states, &self.a),
            WideBody::gather(states, &self.b),
        )
    }

    /// Writes back both sides' moving bodies (a colour's moving bodies are distinct, so no two
    /// written lanes share a state).
    #[inline(always)]
    fn write(&self, states: &SharedStates, a: &WideBody<L>, b: &WideBody<L>) {
        a.scatter(states, &self.a, self.writes_a);
        b.scatter(states, &self.b, self.writes_b);
    }

    /// Applies the bundle's accumulated impulses (and counts them as pushed this step).
    #[inline(always)]
    fn warm_start(&mut self, states: &SharedStates) {
        let (mut a, mut b) = self.bodies(states);
        let (tangent_x, tangent_y) = (self.normal_y, -self.normal_x);
        for j in 0..2 {
            let point = self.points[j];
            let p_x = self.normal_x * point.normal_impulse + tangent_x * point.tangent_impulse;
            let p_y = self.normal_y * point.normal_impulse + tangent_y * point.tangent_impulse;
            self.apply(&point, p_x, p_y, &mut a, &mut b);
            self.points[j].total_normal_impulse += point.normal_impulse;
        }
        self.write(states, &a, &b);
    }

    /// Solves the bundle's constraints once.
    #[inline(always)]
    fn solve(&mut self, states: &SharedStates, pass: PassBias, friction: bool) {
        let zero = L::splat(0.0);
        let one = L::splat(1.0);
        let inv_h = L::splat(pass.inv_h);
        let max_push = L::splat(-pass.max_push_speed);
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
                let vt = relative_velocity(&point, &a, &b, tangent_x, tangent_y);
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
        }
        self.write(states, &a, &b);
    }

    /// Bounces the points that approached faster than `threshold` and pushed this step;
    /// returns how many.
    #[inline(always)]
    fn restitution(&mut self, states: &SharedStates, threshold: Real) -> usize {
        let zero = L::splat(0.0);
        let bouncy = self.restitution.gt(zero);
        if bouncy.bits() == 0 {
            return 0;
        }
        let (mut a, mut b) = self.bodies(states);
        let mut bounced = 0;
        for j in 0..2 {
            let point = self.points[j];
            let slow = point.relative_velocity.gt(L::splat(-threshold));
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
    fn apply(
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
    fn first_contact(&self) -> usize {
        self.contacts.as_ref()[0] as usize
    }

    /// The last filled lane's contact.
    fn last_contact(&self) -> usize {
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
    fn store(&self, contacts: &mut [Contact], offset: usize) {
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
            let (manifold, reports) = contact.manifold_and_impulses_mut();
            let points = manifold.points_mut().iter_mut().zip(reports);
            for (j, (point, report)) in points.enumerate() {
                point.normal_impulse = impulses[j][0][lane];
                point.tangent_impulse = impulses[j][1][lane];
                *report = PointImpulse {
                    total_normal_impulse: impulses[j][2][lane],
                    max_normal_impulse: impulses[j][3][lane],
                    normal_velocity: impulses[j][4][lane],
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
