//! Soft step's contacts in SIMD bundles: the contacts of one graph colour (no shared moving
//! body) are prepared straight into bundles of [`Lanes::WIDTH`] constraints ([`super::kernels`]),
//! stored back into their contacts after the step, and solved by the stage executor
//! ([`WideContacts::execute`], [`super::executor`]). Eight lanes where the CPU has AVX, four
//! elsewhere; a lane gives the scalar path's result bit for bit at either width (tested; in
//! the double-precision build, whose lanes are single, to single precision), only the order
//! of constraints differs (colour by colour).

use super::executor::{Stage, StageInputs, execute_stages};
use super::inputs::BundleInputs;
use super::joint_trees::JointTrees;
use super::kernels::Bundle;
use super::shock_propagation::ShockPropagation;
use crate::capacity::room;
use crate::collision::contact::Contact;
use crate::constants::{COLOR_COUNT, ITEMS_PER_TASK};
use crate::graph::joints::JointColors;
use crate::parallel::{for_each_chunk_with, worth_sharing};
use crate::solver::body_state::BodyState;
use crate::solver::contact_constraint::ContactConstraint;
use crate::solver::joints::JointConstraint;
use crate::solver::params::Softness;
#[cfg(test)]
use crate::solver::soft_step::lanes::Lane;
#[cfg(target_arch = "x86_64")]
use crate::solver::soft_step::lanes::avx::{self, Avx8};
use crate::solver::soft_step::lanes::{Four, Kernel, Lanes};
use crate::solver::soft_step::shared_states::SharedStates;
use crate::stats::Work;
use std::collections::TryReserveError;
use std::ops::Range;

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
    /// The widest this CPU runs, unless the environment variable `CAROM_LANES` is `4`: then
    /// four lanes everywhere, so that a check of the same bits at both widths can run whole
    /// scenes (read once a process).
    pub(crate) fn widest() -> Width {
        static FOUR_ASKED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        let four_asked =
            *FOUR_ASKED.get_or_init(|| std::env::var("CAROM_LANES").is_ok_and(|v| v.trim() == "4"));
        #[cfg(target_arch = "x86_64")]
        if !four_asked && avx::detected() {
            return Width::Eight;
        }
        let _ = four_asked;
        Width::Four
    }
}

/// The bundles of one width.
#[derive(Debug, Clone)]
enum Bundles {
    Four(Vec<Bundle<Four>>),
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

impl WideContacts {
    /// No bundles yet, of `width` (four lanes if the CPU lacks AVX for eight).
    pub(crate) fn new(width: Width) -> Self {
        let bundles = match width {
            Width::Four => Bundles::Four(Vec::new()),
            // An `Avx8` may only exist on a CPU with AVX.
            #[cfg(target_arch = "x86_64")]
            Width::Eight if avx::detected() => Bundles::Eight(Vec::new()),
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

    /// Makes room for `contacts` coloured contacts: their bundles (each colour's last one
    /// part full), their slots and the overflow's list.
    pub(crate) fn reserve(&mut self, contacts: usize) -> Result<(), TryReserveError> {
        let bundles = contacts.div_ceil(self.width()).saturating_add(COLOR_COUNT);
        with_bundles!(&mut self.bundles, |list| room(list, bundles))?;
        room(&mut self.colors, COLOR_COUNT)?;
        room(&mut self.slots, bundles)?;
        room(&mut self.overflow, contacts)
    }

    /// How many constraints a bundle holds.
    pub(crate) fn width(&self) -> usize {
        with_bundles!(&self.bundles, |bundles| lanes_of(bundles))
    }

    /// Forgets the bundles (a step that solves no colour).
    pub(crate) fn clear(&mut self) {
        with_bundles!(&mut self.bundles, |bundles| bundles.clear());
        self.colors.clear();
        self.slots.clear();
        self.overflow.clear();
        self.bouncy = false;
    }

    /// Prepares the coloured contacts into bundles (on all threads), reusing last step's
    /// memory, and lists the overflow's contacts.
    pub(crate) fn prepare(&mut self, inputs: &BundleInputs) {
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
    pub(crate) fn point_count(&self) -> usize {
        with_bundles!(&self.bundles, |bundles| bundles
            .iter()
            .map(|b| b.point_count as usize)
            .sum())
    }

    /// True when some bundle's contact has restitution.
    pub(crate) fn bouncy(&self) -> bool {
        self.bouncy
    }

    /// How many colours have bundles ([`Stage::Color`] takes an index below it).
    pub(crate) fn color_count(&self) -> usize {
        self.colors.len()
    }

    /// Runs `plan`, stage after stage, on as many threads as rayon gives (in one parallel
    /// region) when there is enough to share: the stages over the bundles, the overflow's
    /// constraints one by one, and the integration of the awake bodies (`inputs.drives`, whose
    /// states come first in `states`). Returns the work integration did and how many
    /// restitution impulses were computed.
    #[allow(unsafe_code)]
    pub(crate) fn execute(
        &mut self,
        plan: &[Stage],
        states: &mut [BodyState],
        overflow: (&mut [ContactConstraint], &mut ShockPropagation),
        joints: (&mut [JointConstraint], &JointColors, &mut JointTrees),
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
    pub(crate) fn store(&self, contacts: &mut [Contact]) {
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
use super::inputs::PassBias;
#[cfg(test)]
use super::{Bias, executor::Pass};
#[cfg(test)]
use crate::math::Real;
#[cfg(test)]
use crate::solver::body_state::SpeedCaps;
#[cfg(test)]
use crate::solver::context::Environment;
#[cfg(test)]
use crate::solver::params::SolverParams;

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
            drives: &[],
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
        let mut trees = JointTrees::default();
        let joints = (&mut [][..], &JointColors::default(), &mut trees);
        let mut shock = ShockPropagation::default();
        self.execute(&plan, states, (&mut [], &mut shock), joints, &inputs)
            .1
    }

    /// Applies the accumulated impulses (warm start).
    pub(crate) fn warm_start(&mut self, states: &mut [BodyState]) {
        self.run_pass(states, Pass::WarmStart);
    }

    /// One pass: non-penetration (soft-biased or relaxed), then friction if asked.
    pub(crate) fn solve(&mut self, states: &mut [BodyState], pass: PassBias, friction: bool) {
        self.run_pass(states, Pass::Solve(pass, friction));
    }

    /// Bounces; returns how many impulses were computed.
    pub(crate) fn restitution(&mut self, states: &mut [BodyState], threshold: Real) -> usize {
        self.run_pass(states, Pass::Restitution(threshold))
    }

    /// Each contact's points' normal, tangent and total normal impulses.
    pub(crate) fn impulses(&self) -> std::collections::HashMap<usize, [(Real, Real, Real); 2]> {
        let mut out = std::collections::HashMap::new();
        with_bundles!(&self.bundles, |bundles| {
            for bundle in bundles {
                for (lane, &contact) in bundle.contacts.as_ref().iter().enumerate() {
                    let points = bundle.points.map(|p| {
                        (
                            p.normal_impulse.lane(lane) as Real,
                            p.tangent_impulse.lane(lane) as Real,
                            p.total_normal_impulse.lane(lane) as Real,
                        )
                    });
                    out.insert(contact as usize, points);
                }
            }
        });
        out
    }

    /// Sets a point's accumulated normal impulse in contact `contact`'s lane.
    pub(crate) fn set_normal_impulse(&mut self, contact: usize, point: usize, value: Real) {
        with_bundles!(&mut self.bundles, |bundles| {
            if let Some((bundle, lane)) = lane_of(bundles, contact) {
                let field = &mut bundle.points[point].normal_impulse;
                *field = with_lane(*field, lane, value);
            }
        });
    }

    /// Sets contact `contact`'s restitution.
    pub(crate) fn set_restitution(&mut self, contact: usize, value: Real) {
        with_bundles!(&mut self.bundles, |bundles| {
            if let Some((bundle, lane)) = lane_of(bundles, contact) {
                bundle.restitution = with_lane(bundle.restitution, lane, value);
            }
        });
    }

    /// Sets a point's approach speed at the start of the step in contact `contact`'s lane.
    pub(crate) fn set_relative_velocity(&mut self, contact: usize, point: usize, value: Real) {
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
    values[lane] = value as Lane;
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

/// Copies every bundle's impulses into its contacts, colour by colour (`colors` are each
/// colour's bundles). A colour's bundles hold its contacts in rising order, so halves of them
/// write disjoint halves of the contacts, which threads then share.
fn store_bundles<L: Lanes>(
    bundles: &[Bundle<L>],
    colors: &[Range<usize>],
    contacts: &mut [Contact],
    per_task: usize,
) {
    // Each colour's contacts lie side by side in the contact array, but the colours are not
    // in colour order there: sorted by where they begin, any run of them covers contacts
    // below the next one's, so runs of colours can be stored on different threads.
    let mut runs: [(usize, Range<usize>); COLOR_COUNT] = std::array::from_fn(|_| (0, 0..0));
    let mut count = 0;
    for range in colors {
        if let Some(first) = bundles[range.clone()].first() {
            runs[count] = (first.first_contact(), range.clone());
            count += 1;
        }
    }
    let runs = &mut runs[..count];
    runs.sort_unstable_by_key(|run| run.0);
    let Some(&(start, _)) = runs.first() else {
        return;
    };
    store_colors(bundles, runs, &mut contacts[start..], start, per_task);
}

/// Stores the bundles of colours `runs` (each its first contact and its bundles, sorted by
/// the first) into `contacts`, which begin at contact `offset`: the colours in two halves on
/// two threads while both have work enough, and the halves of one colour likewise.
fn store_colors<L: Lanes>(
    bundles: &[Bundle<L>],
    runs: &[(usize, Range<usize>)],
    contacts: &mut [Contact],
    offset: usize,
    per_task: usize,
) {
    let total: usize = runs.iter().map(|(_, range)| range.len()).sum();
    if runs.len() == 1 || !worth_sharing(total, per_task) {
        // One colour (which store_halves may still split), or too little to share.
        for (start, range) in runs {
            let contacts = &mut contacts[start - offset..];
            store_halves(&bundles[range.clone()], contacts, *start, per_task);
        }
        return;
    }
    // Split where the bundles before are nearest half of them.
    let mut before = 0;
    let middle = runs
        .iter()
        .position(|(_, range)| {
            before += range.len();
            2 * before >= total
        })
        .map_or(1, |last| (last + 1).clamp(1, runs.len() - 1));
    let (low, high) = runs.split_at(middle);
    let at = high[0].0;
    let (low_contacts, high_contacts) = contacts.split_at_mut(at - offset);
    rayon::join(
        || store_colors(bundles, low, low_contacts, offset, per_task),
        || store_colors(bundles, high, high_contacts, at, per_task),
    );
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
