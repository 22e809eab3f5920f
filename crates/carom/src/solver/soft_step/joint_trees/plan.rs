//! A step's joint trees planned: which hinges the trees take (not those of components with
//! many loops), and the leaf-first order that eliminates each tree with no fill-in.

use super::{JointTrees, Tree, TreeJoint, TreeLimit};
use crate::constants::{LOCKED_HINGE_RANGE, MAX_LOOPS_PER_JOINTS};
use crate::math::Vec2;
use crate::solver::body_state::BodyState;
use crate::solver::joints::JointConstraint;

impl JointTrees {
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
