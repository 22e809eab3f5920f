//! Joint trees solved exactly: the point constraints of hinged bodies (revolute joints) in
//! one linear solve per pass, where Gauss-Seidel moves at most a light body's share of the
//! momentum per pass and lets a heavy load stretch a light chain.
//!
//! The system is `A x = r`, with `A = J M⁻¹ Jᵀ` over the joints' 2-row point constraints and
//! `r` their velocity error (plus the soft bias in the biased pass). Where the joints form a
//! tree over the moving bodies, eliminating the joints leaf first fills in nothing: a joint
//! whose one body has no other joint left couples only the joints at its other body (the
//! pivot), so its elimination is a rank-2 update of that body's effective inverse mass, a
//! symmetric 3x3 matrix (`W`, the articulated inverse mass in constraint space; Baraff 1996,
//! "Linear-time dynamics using Lagrange multipliers", solves the same tree by its augmented
//! matrix). Factoring and solving together cost a few dozen flops a joint, in one sweep leaf
//! first and one back.
//!
//! The soft step's impulse is then Box2D's, with the matrix in place of the scalar mass:
//! `Δλ = -mass_scale · A⁻¹ r - impulse_scale · λ`. At the end of each substep the same
//! factorisation closes the drift in position ([`JointTrees::project`]), which the soft bias
//! would otherwise leave to the next substep.
//!
//! A hinge's limits are a third row of its joint, on the angle, while a stop holds: the
//! hinge is then a weld, and the tree stays exact. A stop may only push, so which stops
//! hold is found by trying (an active set): a stop that would pull is let go, one the
//! solution would turn past is taken in, and the tree solved again, a few rounds at most.
//!
//! A joint that closes a loop cannot be eliminated without fill-in: it stays with the other
//! joints, solved iteratively, and a component with many loops (a net) stays iterative whole.
//!
//! The tree owns its joints' point and limit impulses for the step: it warm starts them and hands them
//! back for the next step and for the reactions.

mod algebra;
mod plan;

use super::{SharedStates, block_range};
use crate::constants::{MAX_BLOCKS, TREE_LIMIT_ROUNDS, TREE_PROJECTION_GIVE};
use crate::math::{Real, Vec2, cross, rotation};
use crate::solver::body_state::BodyState;
use crate::solver::joints::{HingeLimit, JointConstraint, JointFrame, JointPass};
use algebra::{Sym3, Vec3, columns, dot, inverse22, inverse33, on_rows, subtract_outer, sym_mul};
use std::ops::Range;

/// A joint's rows at one of its bodies: the point's two and the limit's (zero when no stop
/// holds), each over the body's `(vx, vy, w)`.
type Rows = [Vec3; 3];

/// A hinge's limits as the tree holds them.
#[derive(Debug, Clone, Copy)]
struct TreeLimit {
    limit: HingeLimit,
    /// The stop this pass: `1` the lower, `-1` the upper. The row is `stop · (wB - wA)`.
    stop: Real,
    /// The limits are so close that the hinge is held at one angle, a two-sided row.
    locked: bool,
    /// The stop holds in this round's system.
    active: bool,
    /// This pass's slack (positive: the stop not yet reached), and its bias, mass scale and
    /// impulse scale.
    slack: Real,
    scales: (Real, Real, Real),
}

impl TreeLimit {
    /// The slack at `angle` from the stop nearest it, which becomes the stop.
    fn aim(&mut self, angle: Real) -> Real {
        let l = self.limit.limits;
        if self.locked {
            self.stop = 1.0;
            return angle - angle.clamp(l.lower, l.upper);
        }
        self.stop = if angle - l.lower <= l.upper - angle {
            1.0
        } else {
            -1.0
        };
        if self.stop > 0.0 {
            angle - l.lower
        } else {
            l.upper - angle
        }
    }

    /// The limit row's sign at the bodies, `0` when no stop holds.
    fn turn(this: &Option<Self>) -> Real {
        this.filter(|l| l.active).map_or(0.0, |l| l.stop)
    }
}

/// One joint of the tree, in elimination order, with what a pass needs of it.
#[derive(Debug, Clone, Copy)]
struct TreeJoint {
    /// Its index among the step's joint constraints.
    constraint: usize,
    /// Its anchors and its bodies' masses.
    point: JointFrame,
    /// Its limits, if it has them.
    limit: Option<TreeLimit>,
    /// Its bodies' states, and whether each takes impulses.
    a: usize,
    b: usize,
    moves_a: bool,
    moves_b: bool,
    /// Whether the pivot (the body whose other joints it couples) is B; else A.
    pivot_b: bool,
    /// Which tree it belongs to (a component of the hinges, numbered from 0), and its
    /// moving bodies' places among the tree's ([`Tree::bodies`]).
    tree: u32,
    slot_a: u32,
    slot_b: u32,
    /// Its own effective inverse mass, on the point's rows (averaged over the two) and on
    /// the angle's, which the projection's give is in proportion to.
    own: [Real; 2],
    /// The accumulated impulses: the point's on B (A takes its opposite), and the stop's.
    impulse: Vec3,
    /// This pass: the anchors, `D⁻¹`, `W Gᵀ` at the pivot (three columns), the solve's
    /// intermediate `z` and then its solution, and the round's change of impulse.
    ra: Vec2,
    rb: Vec2,
    inverse: Sym3,
    spread: Rows,
    z: Vec3,
    change: Vec3,
}

impl TreeJoint {
    /// Applies impulse `p` (the point's and the stop's) to the bodies' velocities.
    fn push(&self, a: &mut BodyState, b: &mut BodyState, p: Vec3) {
        self.point
            .push(a, b, self.ra, self.rb, Vec2::new(p[0], p[1]));
        let turn = TreeJoint::stop(self) * p[2];
        let (_, ia, _, ib) = self.point.inverse_masses();
        a.w -= ia * turn;
        b.w += ib * turn;
    }

    /// The stop's sign, whether it holds or not (its impulse is zero when it does not).
    fn stop(&self) -> Real {
        self.limit.map_or(0.0, |l| l.stop)
    }

    /// Moves the bodies as impulse `p` would in a unit of time, their velocities left alone.
    fn shift(&self, a: &mut BodyState, b: &mut BodyState, p: Vec3) {
        let linear = Vec2::new(p[0], p[1]);
        let turn = self.stop() * p[2];
        let (ma, ia, mb, ib) = self.point.inverse_masses();
        a.dp -= linear * ma;
        a.dq = rotation(-ia * (cross(self.ra, linear) + turn)) * a.dq;
        b.dp += linear * mb;
        b.dq = rotation(ib * (cross(self.rb, linear) + turn)) * b.dq;
    }

    /// The rows' velocity error: the point's, and the stop's.
    fn velocity(&self, a: &BodyState, b: &BodyState) -> Vec3 {
        let point = JointFrame::velocity(a, b, self.ra, self.rb);
        [point.x, point.y, self.stop() * (b.w - a.w)]
    }
}

/// One tree: its joints and its moving bodies, as ranges of [`JointTrees`]' lists.
#[derive(Debug, Clone)]
struct Tree {
    joints: Range<usize>,
    bodies: Range<usize>,
}

/// The joint trees of a step: which joints, in what order, and the pass's scratch.
#[derive(Debug, Clone, Default)]
pub(crate) struct JointTrees {
    /// Every tree's joints, tree after tree, each tree's leaf first.
    joints: Vec<TreeJoint>,
    trees: Vec<Tree>,
    /// Every tree's moving bodies (their states), tree after tree.
    bodies: Vec<usize>,
    /// Per body of the trees, as `bodies`: the effective inverse mass, the sweeps'
    /// accumulated vectors, and a round's change of spin.
    inverse_mass: Vec<Sym3>,
    accumulated: Vec<Vec3>,
    spin: Vec<Real>,
    /// Planning scratch: joints left per state, the joints at each state (in CSR), the
    /// joints in elimination order.
    left: Vec<u32>,
    starts: Vec<u32>,
    fill: Vec<u32>,
    at_body: Vec<u32>,
    queue: Vec<u32>,
    removed: Vec<bool>,
    ordered: Vec<TreeJoint>,
    /// Per constraint: a hinge of a component solved directly.
    accepted: Vec<bool>,
    /// Per state: its component's representative (union-find), then the component's tree
    /// joints and loop joints.
    parent: Vec<u32>,
    tree_count: Vec<u32>,
    loop_count: Vec<u32>,
}

/// A run of whole trees, with their joints and their bodies' scratch, lent to one thread
/// for a pass ([`JointTrees::blocks`]).
pub(crate) struct TreeBlock<'a> {
    trees: &'a [Tree],
    joints: &'a mut [TreeJoint],
    inverse_mass: &'a mut [Sym3],
    accumulated: &'a mut [Vec3],
    spin: &'a mut [Real],
}

impl TreeBlock<'_> {
    /// Applies the accumulated impulses (the warm start), or forgets them where the speed
    /// caps cut a body's velocities, as the other joints do.
    pub(crate) fn warm_start(&mut self, states: &SharedStates) {
        for tree in self.joints.iter_mut() {
            let (mut a, mut b) = (states.get(tree.a), states.get(tree.b));
            if a.held != 0 || b.held != 0 {
                tree.impulse = [0.0; 3];
                continue;
            }
            (tree.ra, tree.rb) = tree.point.anchors(&a, &b);
            tree.push(&mut a, &mut b, tree.impulse);
            set_velocities(states, tree, &a, &b);
        }
    }

    /// One pass: the velocity error of every joint of the block's trees (with the pass's
    /// bias) solved away at once, with the stops that hold.
    pub(crate) fn solve(&mut self, states: &SharedStates, pass: &JointPass) {
        self.each_tree(|tree| tree.solve(states, pass));
    }

    /// Closes the trees' drift in position (one Newton step on the anchors' separations and
    /// the passed stops, the bodies moved as the same impulses would move them in a unit of
    /// time), leaving their velocities alone: the end of a substep, where the soft bias would
    /// otherwise leave what nonlinear motion opened for the next one. Called right after the
    /// relaxation's [`TreeBlock::solve`], whose stops it takes as they were aimed.
    pub(crate) fn project(&mut self, states: &SharedStates) {
        self.each_tree(|tree| tree.project(states));
    }

    /// Runs `work` on each tree, with its joints and its bodies' scratch.
    fn each_tree(&mut self, mut work: impl FnMut(&mut TreeWork)) {
        let Some(first) = self.trees.first() else {
            return;
        };
        let (joint0, body0) = (first.joints.start, first.bodies.start);
        for tree in self.trees {
            let joints = tree.joints.start - joint0..tree.joints.end - joint0;
            let bodies = tree.bodies.start - body0..tree.bodies.end - body0;
            work(&mut TreeWork {
                joints: &mut self.joints[joints],
                inverse_mass: &mut self.inverse_mass[bodies.clone()],
                accumulated: &mut self.accumulated[bodies.clone()],
                spin: &mut self.spin[bodies],
            });
        }
    }
}

/// One tree's joints and its bodies' scratch, which a pass works through alone.
struct TreeWork<'a> {
    joints: &'a mut [TreeJoint],
    inverse_mass: &'a mut [Sym3],
    accumulated: &'a mut [Vec3],
    spin: &'a mut [Real],
}

impl JointTrees {
    /// No trees this step.
    pub(crate) fn clear(&mut self) {
        self.joints.clear();
        self.trees.clear();
        self.bodies.clear();
        self.parent.clear();
    }

    /// Each state's group of bodies joined by hinges (its representative), if there are
    /// trees this step.
    pub(crate) fn groups(&self) -> Option<&[u32]> {
        (!self.joints.is_empty()).then_some(&self.parent[..])
    }

    /// Whether there is anything to solve.
    pub(crate) fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// How many joints the trees have.
    pub(crate) fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The trees cut into at most `count` runs of whole trees, of about as many joints
    /// each, for threads to solve apart: the trees share no moving body, so each run's
    /// results are the same whoever solves it, and whichever run goes first.
    pub(crate) fn blocks(&mut self, count: usize) -> [Option<TreeBlock<'_>>; MAX_BLOCKS] {
        let mut blocks = std::array::from_fn(|_| None);
        let count = count.clamp(1, MAX_BLOCKS);
        let total = self.joints.len();
        let mut joints = &mut self.joints[..];
        let bodies = self.bodies.len();
        let mut inverse_mass = &mut self.inverse_mass[..bodies];
        let mut accumulated = &mut self.accumulated[..bodies];
        let mut spin = &mut self.spin[..bodies];
        let (mut first, mut made) = (0, 0);
        for block in 0..count {
            // The trees that start before this block's share of the joints ends.
            let end = block_range(total, count, block).end;
            let mut last = first;
            while last < self.trees.len() && (self.trees[last].joints.start < end) {
                last += 1;
            }
            if block + 1 == count {
                last = self.trees.len();
            }
            if last == first {
                continue;
            }
            let trees = &self.trees[first..last];
            let joint_count = trees[trees.len() - 1].joints.end - trees[0].joints.start;
            let body_count = trees[trees.len() - 1].bodies.end - trees[0].bodies.start;
            let (these, rest) = std::mem::take(&mut joints).split_at_mut(joint_count);
            joints = rest;
            let (w, rest) = std::mem::take(&mut inverse_mass).split_at_mut(body_count);
            inverse_mass = rest;
            let (q, rest) = std::mem::take(&mut accumulated).split_at_mut(body_count);
            accumulated = rest;
            let (turns, rest) = std::mem::take(&mut spin).split_at_mut(body_count);
            spin = rest;
            blocks[made] = Some(TreeBlock {
                trees,
                joints: these,
                inverse_mass: w,
                accumulated: q,
                spin: turns,
            });
            made += 1;
            first = last;
        }
        blocks
    }

    /// Hands the accumulated point and stop impulses back to their joints.
    pub(crate) fn finish(&self, constraints: &mut [JointConstraint]) {
        for tree in &self.joints {
            let c = &mut constraints[tree.constraint];
            c.impulses.linear = Vec2::new(tree.impulse[0], tree.impulse[1]);
            if let Some(limit) = tree.limit {
                let held = tree.impulse[2];
                (c.impulses.lower, c.impulses.upper) = if limit.locked {
                    (held.max(0.0), (-held).max(0.0))
                } else if limit.stop > 0.0 {
                    (held, 0.0)
                } else {
                    (0.0, held)
                };
            }
        }
    }
}

impl TreeWork<'_> {
    /// One pass over the tree: its stops aimed, then solved in rounds with the stops that
    /// hold until none changes (a stop that would pull is let go, one passed is taken in),
    /// and the change of impulse applied.
    fn solve(&mut self, states: &SharedStates, pass: &JointPass) {
        let s = pass.softness;
        let (mass_scale, impulse_scale) = if pass.use_bias {
            (s.mass_scale, s.impulse_scale)
        } else {
            (1.0, 0.0)
        };
        // Each limit's stop this pass, and whether it starts in the system: it pushed last
        // pass, or is passed, or would be by the velocities as they are.
        for tree in self.joints.iter_mut() {
            let Some(mut limit) = tree.limit else {
                continue;
            };
            let (mut a, mut b) = (states.get(tree.a), states.get(tree.b));
            let was = limit.stop;
            limit.slack = limit.aim(limit.limit.angle(&a, &b));
            if limit.stop != was && tree.impulse[2] != 0.0 {
                // The other stop is nearer now: the old one lets go.
                let (_, ia, _, ib) = tree.point.inverse_masses();
                let turn = -was * tree.impulse[2];
                a.w -= ia * turn;
                b.w += ib * turn;
                tree.impulse[2] = 0.0;
                set_velocities(states, tree, &a, &b);
            }
            limit.scales = if limit.locked {
                pass.rigid(limit.slack)
            } else {
                pass.limit(limit.slack)
            };
            let closing = limit.stop * (b.w - a.w) + limit.scales.0;
            limit.active =
                limit.locked || tree.impulse[2] > 0.0 || limit.slack <= 0.0 || closing < 0.0;
            tree.limit = Some(limit);
        }
        for round in 0..TREE_LIMIT_ROUNDS {
            let last = round + 1 == TREE_LIMIT_ROUNDS;
            self.exact(states, 0.0, |tree, a, b| {
                let mut error = tree.velocity(a, b);
                if pass.use_bias {
                    let drift = tree.point.separation(a, b, tree.ra, tree.rb) * s.bias_rate;
                    error[0] += drift.x;
                    error[1] += drift.y;
                }
                if let Some(limit) = tree.limit {
                    error[2] += limit.scales.0;
                }
                error
            });
            // The change of impulse; a stop that would pull lets go.
            let mut changed = false;
            for tree in self.joints.iter_mut() {
                let z = tree.z;
                let mut change = [
                    -z[0] * mass_scale - tree.impulse[0] * impulse_scale,
                    -z[1] * mass_scale - tree.impulse[1] * impulse_scale,
                    0.0,
                ];
                if let Some(limit) = tree.limit.as_mut().filter(|l| l.active) {
                    let (_, mass_scale, impulse_scale) = limit.scales;
                    change[2] = -z[2] * mass_scale - tree.impulse[2] * impulse_scale;
                    if !limit.locked && tree.impulse[2] + change[2] < 0.0 {
                        if last {
                            change[2] = -tree.impulse[2];
                        } else {
                            limit.active = false;
                            changed = true;
                        }
                    }
                }
                tree.change = change;
            }
            // A stop the solution would turn past is taken in.
            if !(last || changed) {
                changed = self.take_in_passed_stop(states);
            }
            if changed {
                self.let_go(states);
                continue;
            }
            // The stops held: the changes are final.
            for tree in self.joints.iter_mut() {
                let (mut a, mut b) = (states.get(tree.a), states.get(tree.b));
                tree.push(&mut a, &mut b, tree.change);
                for k in 0..3 {
                    tree.impulse[k] += tree.change[k];
                }
                set_velocities(states, tree, &a, &b);
            }
            break;
        }
    }

    /// Takes the impulse of every stop let go out of the bodies' velocities.
    fn let_go(&mut self, states: &SharedStates) {
        for tree in self.joints.iter_mut() {
            let Some(limit) = tree.limit else {
                continue;
            };
            if limit.active || tree.impulse[2] == 0.0 {
                continue;
            }
            let (mut a, mut b) = (states.get(tree.a), states.get(tree.b));
            tree.push(&mut a, &mut b, [0.0, 0.0, -tree.impulse[2]]);
            tree.impulse[2] = 0.0;
            set_velocities(states, tree, &a, &b);
        }
    }

    /// Takes in the first stop (leaf first) that the round's changes would turn a hinge
    /// past; returns whether there was one.
    fn take_in_passed_stop(&mut self, states: &SharedStates) -> bool {
        self.spin.fill(0.0);
        for tree in self.joints.iter() {
            let p = tree.change;
            let (_, ia, _, ib) = tree.point.inverse_masses();
            let turn = tree.stop() * p[2];
            let linear = Vec2::new(p[0], p[1]);
            if tree.moves_a {
                self.spin[tree.slot_a as usize] -= ia * (cross(tree.ra, linear) + turn);
            }
            if tree.moves_b {
                self.spin[tree.slot_b as usize] += ib * (cross(tree.rb, linear) + turn);
            }
        }
        for tree in self.joints.iter_mut() {
            let Some(limit) = tree.limit.as_mut().filter(|l| !l.active) else {
                continue;
            };
            let spin = |moves: bool, state: usize, slot: u32| {
                states.get(state).w + if moves { self.spin[slot as usize] } else { 0.0 }
            };
            let turning =
                spin(tree.moves_b, tree.b, tree.slot_b) - spin(tree.moves_a, tree.a, tree.slot_a);
            if limit.stop * turning + limit.scales.0 < 0.0 {
                limit.active = true;
                return true;
            }
        }
        false
    }

    /// Closes the tree's drift in position ([`JointTrees::project`]), in rounds as the
    /// solve's: a passed stop only pushes out.
    fn project(&mut self, states: &SharedStates) {
        // The relaxation's solve has just aimed each stop at these same positions (it moves
        // no body): its slack is the stop's now.
        for tree in self.joints.iter_mut() {
            if let Some(limit) = &mut tree.limit {
                limit.active = limit.locked || limit.slack < 0.0;
            }
        }
        for round in 0..TREE_LIMIT_ROUNDS {
            let last = round + 1 == TREE_LIMIT_ROUNDS;
            self.exact(states, TREE_PROJECTION_GIVE, |tree, a, b| {
                let drift = tree.point.separation(a, b, tree.ra, tree.rb);
                [drift.x, drift.y, tree.limit.map_or(0.0, |l| l.slack)]
            });
            let mut changed = false;
            for tree in self.joints.iter_mut() {
                tree.change = [-tree.z[0], -tree.z[1], -tree.z[2]];
                if let Some(limit) = tree.limit.as_mut().filter(|l| l.active && !l.locked)
                    && tree.change[2] < 0.0
                {
                    if last {
                        tree.change[2] = 0.0;
                    } else {
                        limit.active = false;
                        changed = true;
                    }
                }
            }
            if changed {
                continue;
            }
            for tree in self.joints.iter() {
                let (mut a, mut b) = (states.get(tree.a), states.get(tree.b));
                tree.shift(&mut a, &mut b, tree.change);
                for (moves, index, state) in [(tree.moves_a, tree.a, a), (tree.moves_b, tree.b, b)]
                {
                    if moves {
                        states.set_motion(index, &state);
                    }
                }
            }
            break;
        }
    }

    /// Solves `A x = r` over the tree, `r` each joint's `error` given the bodies' states
    /// (its anchors already in `ra`, `rb`), with the stops that hold, leaving `x` in each
    /// joint's `z`. `give` is added to each joint's own effective inverse mass, in proportion.
    fn exact(
        &mut self,
        states: &SharedStates,
        give: Real,
        error: impl Fn(&TreeJoint, &BodyState, &BodyState) -> Vec3,
    ) {
        self.accumulated.fill([0.0; 3]);
        for tree in self.joints.iter() {
            let (ma, ia, mb, ib) = tree.point.inverse_masses();
            if tree.moves_a {
                self.inverse_mass[tree.slot_a as usize] = [ma, 0.0, 0.0, ma, 0.0, ia];
            }
            if tree.moves_b {
                self.inverse_mass[tree.slot_b as usize] = [mb, 0.0, 0.0, mb, 0.0, ib];
            }
        }
        // Leaf first: factor, and carry each joint's part of the error to its pivot. A joint
        // without a stop that holds has two rows, and costs what a plain hinge does.
        for tree in self.joints.iter_mut() {
            let (a, b) = (states.get(tree.a), states.get(tree.b));
            (tree.ra, tree.rb) = tree.point.anchors(&a, &b);
            let y = error(tree, &a, &b);
            let (w, q) = (&mut *self.inverse_mass, &mut *self.accumulated);
            if TreeLimit::turn(&tree.limit) == 0.0 {
                eliminate::<2>(tree, w, q, y, give);
            } else {
                eliminate::<3>(tree, w, q, y, give);
            }
        }
        // Root first: each joint less what the joints beyond its pivot carry.
        self.accumulated.fill([0.0; 3]);
        for tree in self.joints.iter_mut().rev() {
            if TreeLimit::turn(&tree.limit) == 0.0 {
                substitute::<2>(tree, self.accumulated);
            } else {
                substitute::<3>(tree, self.accumulated);
            }
        }
    }
}

/// Eliminates `tree`'s `N` rows (the point's two, and its stop's if it holds) leaf first:
/// its `D⁻¹` and intermediate `z` from its error `y` less what the joints eliminated before
/// it carry (`accumulated`), then its pivot's effective inverse mass (`inverse_mass`) less
/// what it now holds, and its share of the solution carried to the pivot. `give` is added
/// to `D` in proportion to each row's own effective mass.
fn eliminate<const N: usize>(
    tree: &mut TreeJoint,
    inverse_mass: &mut [Sym3],
    accumulated: &mut [Vec3],
    mut y: Vec3,
    give: Real,
) {
    let turn = TreeLimit::turn(&tree.limit);
    let mut d = [0.0; 6];
    let mut spread = [[0.0; 3]; 3];
    for (moves, slot, r, sign, pivot) in [
        (tree.moves_a, tree.slot_a, tree.ra, -1.0, !tree.pivot_b),
        (tree.moves_b, tree.slot_b, tree.rb, 1.0, tree.pivot_b),
    ] {
        if !moves {
            continue;
        }
        let slot = slot as usize;
        // `G W Gᵀ` at the body, from `W Gᵀ` (less its sign, which the product squares).
        let [u, v, t] = columns::<N>(&inverse_mass[slot], r, turn);
        d[0] += u[0] - r.y * u[2];
        d[1] += v[0] - r.y * v[2];
        d[3] += v[1] + r.x * v[2];
        if N == 3 {
            d[2] += t[0] - r.y * t[2];
            d[4] += t[1] + r.x * t[2];
            d[5] += turn * t[2];
        }
        let q = on_rows::<N>(r, turn, accumulated[slot]);
        for k in 0..N {
            y[k] -= sign * q[k];
        }
        if pivot {
            for (signed, column) in spread.iter_mut().zip([u, v, t]) {
                for i in 0..3 {
                    signed[i] = sign * column[i];
                }
            }
        }
    }
    if give > 0.0 {
        let [linear, angular] = tree.own;
        d[0] += give * linear;
        d[3] += give * linear;
        d[5] += give * angular;
    }
    tree.inverse = if N == 3 {
        inverse33(d)
    } else {
        let [i11, i12, i22] = inverse22([d[0], d[1], d[3]]);
        [i11, i12, 0.0, i22, 0.0, 0.0]
    };
    tree.z = sym_mul::<N>(&tree.inverse, y);
    tree.spread = spread;
    let (moves, pivot) = if tree.pivot_b {
        (tree.moves_b, tree.slot_b)
    } else {
        (tree.moves_a, tree.slot_a)
    };
    if moves {
        // `W Gᵀ` at the pivot carries this joint's share of the solution there, and the
        // pivot's `W` is less what this joint now holds.
        let pivot = pivot as usize;
        let mut columns = [[0.0; 3]; N];
        columns.copy_from_slice(&spread[..N]);
        let q = &mut accumulated[pivot];
        for (column, zk) in columns.iter().zip(tree.z) {
            for i in 0..3 {
                q[i] += column[i] * zk;
            }
        }
        subtract_outer(&mut inverse_mass[pivot], &columns, &tree.inverse);
    }
}

/// Solves for `tree`'s `N` rows root first: its `z` less what the joints beyond its pivot
/// carry (`accumulated`), then its bodies' share of the solution added to `accumulated`.
fn substitute<const N: usize>(tree: &mut TreeJoint, accumulated: &mut [Vec3]) {
    let pivot = if tree.pivot_b {
        tree.slot_b
    } else {
        tree.slot_a
    } as usize;
    let t = accumulated[pivot];
    let mut carried = [0.0; 3];
    for (carried, column) in carried.iter_mut().zip(&tree.spread[..N]) {
        *carried = dot(*column, t);
    }
    let solved = sym_mul::<N>(&tree.inverse, carried);
    let x = [
        tree.z[0] - solved[0],
        tree.z[1] - solved[1],
        tree.z[2] - solved[2],
    ];
    let turn = TreeLimit::turn(&tree.limit);
    for (moves, slot, r, sign) in [
        (tree.moves_a, tree.slot_a, tree.ra, -1.0),
        (tree.moves_b, tree.slot_b, tree.rb, 1.0),
    ] {
        if moves {
            // `Gᵀ x`.
            let t = &mut accumulated[slot as usize];
            t[0] += sign * x[0];
            t[1] += sign * x[1];
            t[2] += -sign * r.y * x[0];
            t[2] += sign * r.x * x[1];
            if N == 3 {
                t[2] += sign * turn * x[2];
            }
        }
    }
    tree.z = x;
}

/// Writes a joint's bodies' velocities back (those that move).
fn set_velocities(states: &SharedStates, tree: &TreeJoint, a: &BodyState, b: &BodyState) {
    for (moves, index, state) in [(tree.moves_a, tree.a, a), (tree.moves_b, tree.b, b)] {
        if moves {
            states.set_velocity(index, state);
        }
    }
}
