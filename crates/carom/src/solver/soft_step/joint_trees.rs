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

use super::{SharedStates, block_range};
use crate::constants::{
    LOCKED_HINGE_RANGE, MAX_BLOCKS, MAX_LOOPS_PER_JOINTS, TREE_LIMIT_ROUNDS, TREE_PROJECTION_GIVE,
};
use crate::math::{Real, Vec2, cross, rotation};
use crate::solver::body_state::BodyState;
use crate::solver::joints::{HingeLimit, JointConstraint, JointFrame, JointPass};
use std::ops::Range;

/// A symmetric 3x3 matrix over a body's `(vx, vy, w)`: `[xx, xy, xw, yy, yw, ww]`.
type Sym3 = [Real; 6];

/// A 3-vector over a body's `(vx, vy, w)`, or over a joint's rows.
type Vec3 = [Real; 3];

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
    /// Hinge `c`, constraint `index`, as the tree takes it, its impulses carried over; `None`
    /// if it has no hinge point. `pivot_b`: its second body is the pivot its first is
    /// eliminated into.
    fn of(index: usize, c: &JointConstraint, pivot_b: bool) -> Option<TreeJoint> {
        let point = c.hinge_point()?;
        let limit = c.hinge_limit().map(|limit| {
            let l = limit.limits;
            let mut tree = TreeLimit {
                limit,
                stop: 1.0,
                locked: l.upper - l.lower < LOCKED_HINGE_RANGE,
                active: false,
                slack: 0.0,
                scales: (0.0, 1.0, 0.0),
            };
            tree.aim(limit.angle(&BodyState::spare(), &BodyState::spare()));
            tree
        });
        let i = &c.impulses;
        let held = match limit {
            Some(l) if l.locked => i.lower - i.upper,
            Some(l) if l.stop > 0.0 => i.lower,
            Some(_) => i.upper,
            None => 0.0,
        };
        let (ma, ia, mb, ib) = point.inverse_masses();
        // The anchors' lengths do not change as the bodies turn.
        let (ra, rb) = point.anchors(&BodyState::spare(), &BodyState::spare());
        let own = [
            ma + mb + 0.5 * (ia * ra.norm_squared() + ib * rb.norm_squared()),
            ia + ib,
        ];
        Some(TreeJoint {
            constraint: index,
            point,
            limit,
            tree: 0,
            slot_a: 0,
            slot_b: 0,
            own,
            a: c.a,
            b: c.b,
            moves_a: c.moves_a,
            moves_b: c.moves_b,
            pivot_b,
            impulse: [i.linear.x, i.linear.y, held],
            ra: Vec2::zeros(),
            rb: Vec2::zeros(),
            inverse: [0.0; 6],
            spread: [[0.0; 3]; 3],
            z: [0.0; 3],
            change: [0.0; 3],
        })
    }

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

    /// Orders the revolute joints among `constraints` leaf first over `states` states, marks
    /// them as the tree's (their own solve then leaves the point to it), and leaves the
    /// joints that close loops to the iterative solve. Allocates only as the world grows.
    pub(crate) fn plan(&mut self, constraints: &mut [JointConstraint], states: usize) {
        self.joints.clear();
        self.trees.clear();
        self.bodies.clear();
        let count = self.accept(constraints, states);
        if count == 0 {
            return;
        }
        self.list_at_bodies(constraints, states);
        self.order_leaf_first(constraints, count);
        for tree in &self.joints {
            constraints[tree.constraint].leave_point_to_tree();
        }
        self.group_by_tree();
    }

    /// Finds which moving bodies the hinges connect and marks, in `accepted`, the hinges the
    /// trees may take: those of components with few loops. Counts each moving state's accepted
    /// joints in `left` and returns how many there are.
    fn accept(&mut self, constraints: &[JointConstraint], states: usize) -> usize {
        let hinge = |c: &JointConstraint| c.hinge_point().is_some() && (c.moves_a || c.moves_b);
        // Which moving bodies the hinges connect, and which hinges close a loop among them.
        self.parent.clear();
        self.parent.extend(0..states as u32 + 1);
        self.accepted.clear();
        self.accepted.resize(constraints.len(), false);
        for (index, c) in constraints.iter().enumerate() {
            if hinge(c) && c.moves_a && c.moves_b {
                let (ra, rb) = (root(&mut self.parent, c.a), root(&mut self.parent, c.b));
                // The smaller index leads, so the components do not depend on joint order.
                let (low, high) = (ra.min(rb), ra.max(rb));
                self.parent[high] = low as u32;
                // Marked for now: closes a loop.
                self.accepted[index] = ra == rb;
            }
        }
        // Each state's representative, one hop away ([`JointTrees::groups`]).
        for state in 0..=states {
            self.parent[state] = root(&mut self.parent, state) as u32;
        }
        self.tree_count.clear();
        self.tree_count.resize(states + 1, 0);
        self.loop_count.clear();
        self.loop_count.resize(states + 1, 0);
        for (index, c) in constraints.iter().enumerate().filter(|(_, c)| hinge(c)) {
            let component = component_of(&mut self.parent, c);
            if self.accepted[index] {
                self.loop_count[component] += 1;
            } else {
                self.tree_count[component] += 1;
            }
        }
        // A component with many loops (a net, a grid) would have its iterative loop hinges
        // undo the exact tree each pass: it stays iterative whole, at iterative cost.
        let (most_loops, per_tree) = MAX_LOOPS_PER_JOINTS;
        self.left.clear();
        self.left.resize(states + 1, 0);
        let mut count = 0usize;
        for (index, c) in constraints.iter().enumerate() {
            // Each state's parent is its component's root now.
            let accepted = hinge(c) && {
                let component = component_of(&mut self.parent, c);
                self.loop_count[component] * per_tree <= self.tree_count[component] * most_loops
            };
            self.accepted[index] = accepted;
            if accepted {
                count += 1;
                for (moves, state) in [(c.moves_a, c.a), (c.moves_b, c.b)] {
                    if moves {
                        self.left[state] += 1;
                    }
                }
            }
        }
        count
    }

    /// Lists the accepted joints at each moving state, in constraint order (`starts` and
    /// `at_body`).
    fn list_at_bodies(&mut self, constraints: &[JointConstraint], states: usize) {
        self.starts.clear();
        self.starts.push(0);
        for state in 0..states {
            let next = self.starts[state] + self.left[state];
            self.starts.push(next);
        }
        self.at_body.clear();
        self.at_body.resize(self.starts[states] as usize, u32::MAX);
        self.fill.clear();
        self.fill.extend_from_slice(&self.starts[..states]);
        for (index, c) in constraints.iter().enumerate() {
            if !self.accepted[index] {
                continue;
            }
            for (moves, state) in [(c.moves_a, c.a), (c.moves_b, c.b)] {
                if moves {
                    self.at_body[self.fill[state] as usize] = index as u32;
                    self.fill[state] += 1;
                }
            }
        }
    }

    /// Takes the `count` accepted joints leaf first into `joints`: a joint is ready when one
    /// of its bodies has no other joint left, and that side is eliminated into the other.
    /// When only loops are left, the first joint left closes one and goes to the iterative
    /// solve.
    fn order_leaf_first(&mut self, constraints: &[JointConstraint], count: usize) {
        self.removed.clear();
        self.removed.resize(constraints.len(), false);
        let leaf = |left: &[u32], moves: bool, state: usize| !moves || left[state] <= 1;
        self.queue.clear();
        for (index, c) in constraints.iter().enumerate() {
            if self.accepted[index]
                && (leaf(&self.left, c.moves_a, c.a) || leaf(&self.left, c.moves_b, c.b))
            {
                self.queue.push(index as u32);
            }
        }
        let (mut head, mut next_loop) = (0usize, 0usize);
        let mut placed = 0usize;
        while placed < count {
            let index = if head < self.queue.len() {
                head += 1;
                self.queue[head - 1] as usize
            } else {
                while self.removed[next_loop] || !self.accepted[next_loop] {
                    next_loop += 1;
                }
                let index = next_loop;
                self.remove(constraints, index);
                placed += 1;
                continue;
            };
            if self.removed[index] {
                continue;
            }
            let c = &constraints[index];
            let ready_a = leaf(&self.left, c.moves_a, c.a);
            let ready_b = leaf(&self.left, c.moves_b, c.b);
            if !(ready_a || ready_b) {
                continue;
            }
            // The leaf side is eliminated into the pivot.
            let Some(joint) = TreeJoint::of(index, c, ready_a) else {
                continue;
            };
            self.joints.push(joint);
            self.remove(constraints, index);
            placed += 1;
        }
    }

    /// Puts the planned joints tree after tree, each tree's in its order (which eliminates
    /// it leaf first on its own), numbers each tree's moving bodies, and sizes the scratch.
    fn group_by_tree(&mut self) {
        // Each tree numbered in the order its first joint comes, and its joints counted.
        self.left.fill(u32::MAX);
        self.starts.clear();
        self.starts.push(0);
        for joint in &mut self.joints {
            let root = self.parent[if joint.moves_a { joint.a } else { joint.b }] as usize;
            if self.left[root] == u32::MAX {
                self.left[root] = self.starts.len() as u32 - 1;
                self.starts.push(0);
            }
            joint.tree = self.left[root];
            self.starts[joint.tree as usize + 1] += 1;
        }
        for tree in 1..self.starts.len() {
            self.starts[tree] += self.starts[tree - 1];
        }
        self.ordered.clear();
        self.ordered.extend_from_slice(&self.joints);
        self.fill.clear();
        self.fill.extend_from_slice(&self.starts);
        for joint in &self.ordered {
            let place = &mut self.fill[joint.tree as usize];
            self.joints[*place as usize] = *joint;
            *place += 1;
        }
        // Each tree's moving bodies, once each, in the order its joints come.
        self.left.fill(u32::MAX);
        for tree in 0..self.starts.len() - 1 {
            let joints = self.starts[tree] as usize..self.starts[tree + 1] as usize;
            let first = self.bodies.len();
            for joint in &mut self.joints[joints.clone()] {
                for (moves, state, slot) in [
                    (joint.moves_a, joint.a, &mut joint.slot_a),
                    (joint.moves_b, joint.b, &mut joint.slot_b),
                ] {
                    if moves {
                        if self.left[state] == u32::MAX {
                            self.left[state] = (self.bodies.len() - first) as u32;
                            self.bodies.push(state);
                        }
                        *slot = self.left[state];
                    }
                }
            }
            self.trees.push(Tree {
                joints,
                bodies: first..self.bodies.len(),
            });
        }
        let bodies = self.bodies.len();
        if self.inverse_mass.len() < bodies {
            self.inverse_mass.resize(bodies, [0.0; 6]);
            self.accumulated.resize(bodies, [0.0; 3]);
            self.spin.resize(bodies, 0.0);
        }
    }

    /// Takes joint `index` out of the graph, readying the joints it leaves alone at a body.
    fn remove(&mut self, constraints: &[JointConstraint], index: usize) {
        self.removed[index] = true;
        let c = &constraints[index];
        for (moves, state) in [(c.moves_a, c.a), (c.moves_b, c.b)] {
            if !moves {
                continue;
            }
            self.left[state] -= 1;
            if self.left[state] == 1 {
                let joints =
                    &self.at_body[self.starts[state] as usize..self.starts[state + 1] as usize];
                if let Some(&last) = joints.iter().find(|&&j| !self.removed[j as usize]) {
                    self.queue.push(last);
                }
            }
        }
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

/// The representative of `state`'s component, compressing the path to it.
fn root(parent: &mut [u32], state: usize) -> usize {
    let mut at = state;
    while parent[at] as usize != at {
        let up = parent[at] as usize;
        parent[at] = parent[up];
        at = up;
    }
    at
}

/// The component of a joint's moving bodies.
fn component_of(parent: &mut [u32], c: &JointConstraint) -> usize {
    root(parent, if c.moves_a { c.a } else { c.b })
}

/// Writes a joint's bodies' velocities back (those that move).
fn set_velocities(states: &SharedStates, tree: &TreeJoint, a: &BodyState, b: &BodyState) {
    for (moves, index, state) in [(tree.moves_a, tree.a, a), (tree.moves_b, tree.b, b)] {
        if moves {
            states.set_velocity(index, state);
        }
    }
}

/// `W Gᵀ` for a joint's rows at a body with anchor `r` and effective inverse mass `W`, less
/// their sign: the rows are `[1, 0, -r.y]`, `[0, 1, r.x]` and `[0, 0, turn]` (the last only
/// when `N` is 3, else zero) over the body's `(vx, vy, w)`.
#[inline]
fn columns<const N: usize>(w: &Sym3, r: Vec2, turn: Real) -> [Vec3; 3] {
    let [xx, xy, xw, yy, yw, ww] = *w;
    let turned = if N == 3 {
        [turn * xw, turn * yw, turn * ww]
    } else {
        [0.0; 3]
    };
    [
        [xx - r.y * xw, xy - r.y * yw, xw - r.y * ww],
        [xy + r.x * xw, yy + r.x * yw, yw + r.x * ww],
        turned,
    ]
}

/// `G c` for a joint's rows at a body (as [`columns`], less their sign): what vector `c`
/// over the body's `(vx, vy, w)` is on each row.
#[inline]
fn on_rows<const N: usize>(r: Vec2, turn: Real, c: Vec3) -> Vec3 {
    [
        c[0] - r.y * c[2],
        c[1] + r.x * c[2],
        if N == 3 { turn * c[2] } else { 0.0 },
    ]
}

fn dot(a: Vec3, b: Vec3) -> Real {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `m v` for the symmetric `m`, of which only the first `N` rows and columns are read (the
/// rest of the result is zero).
#[inline]
fn sym_mul<const N: usize>(m: &Sym3, v: Vec3) -> Vec3 {
    let [xx, xy, xw, yy, yw, ww] = *m;
    if N == 3 {
        [
            xx * v[0] + xy * v[1] + xw * v[2],
            xy * v[0] + yy * v[1] + yw * v[2],
            xw * v[0] + yw * v[1] + ww * v[2],
        ]
    } else {
        [xx * v[0] + xy * v[1], xy * v[0] + yy * v[1], 0.0]
    }
}

/// Where entry `(i, j)` of a symmetric 3x3 matrix is kept in a [`Sym3`].
const SYM: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];

/// `w -= C D⁻¹ Cᵀ` for the 3xN `C` given by its columns and the symmetric `D⁻¹` (its first
/// `N` rows and columns).
fn subtract_outer<const N: usize>(w: &mut Sym3, c: &[Vec3; N], inverse: &Sym3) {
    // Row i of C D⁻¹.
    let mut e = [[0.0; N]; 3];
    for (i, row) in e.iter_mut().enumerate() {
        for (l, entry) in row.iter_mut().enumerate() {
            for (k, column) in c.iter().enumerate() {
                *entry += column[i] * inverse[SYM[k][l]];
            }
        }
    }
    for i in 0..3 {
        for j in i..3 {
            let mut outer = 0.0;
            for (l, column) in c.iter().enumerate() {
                outer += e[i][l] * column[j];
            }
            w[SYM[i][j]] -= outer;
        }
    }
}

/// The inverse of the symmetric `[[d11, d12], [d12, d22]]`, regularised so that a joint
/// made redundant by others (two pins on one body) takes no impulse rather than an infinite
/// one.
fn inverse22([d11, d12, d22]: [Real; 3]) -> [Real; 3] {
    let trace = d11 + d22;
    let det = d11 * d22 - d12 * d12;
    let (d11, d22, det) = if det > 1e-6 * trace * trace {
        (d11, d22, det)
    } else {
        let eps = 1e-3 * trace;
        let (d11, d22) = (d11 + eps, d22 + eps);
        (d11, d22, d11 * d22 - d12 * d12)
    };
    if det > 0.0 && det.is_finite() {
        [d22 / det, -d12 / det, d11 / det]
    } else {
        [0.0; 3]
    }
}

/// The inverse of the symmetric `d`, regularised as [`inverse22`] is (relative to each
/// diagonal entry, since the rows mix lengths and angles).
fn inverse33(d: Sym3) -> Sym3 {
    let det =
        |[a, b, c, e, f, i]: Sym3| a * (e * i - f * f) - b * (b * i - f * c) + c * (b * f - e * c);
    let scale = d[0] * d[3] * d[5];
    let d = if det(d) > 1e-6 * scale {
        d
    } else {
        let grow = 1.0 + 1e-3;
        [d[0] * grow, d[1], d[2], d[3] * grow, d[4], d[5] * grow]
    };
    let det = det(d);
    if !(det > 0.0 && det.is_finite()) {
        return [0.0; 6];
    }
    let [a, b, c, e, f, i] = d;
    let inv = 1.0 / det;
    [
        (e * i - f * f) * inv,
        (c * f - b * i) * inv,
        (b * f - c * e) * inv,
        (a * i - c * c) * inv,
        (b * c - a * f) * inv,
        (a * e - b * b) * inv,
    ]
}
