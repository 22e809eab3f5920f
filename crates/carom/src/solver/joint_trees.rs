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
//! A joint that closes a loop cannot be eliminated without fill-in: it stays with the other
//! joints, solved iteratively, and a component with many loops (a net) stays iterative whole.
//!
//! The tree owns its joints' point impulses for the step: it warm starts them and hands them
//! back for the next step and for the reactions.

use super::BodyState;
use super::joints::{JointConstraint, JointFrame, JointPass};
use crate::constants::{MAX_LOOPS_PER_JOINTS, TREE_PROJECTION_GIVE};
use crate::math::{Real, Vec2};

/// A symmetric 3x3 matrix over a body's `(vx, vy, w)`: `[xx, xy, xw, yy, yw, ww]`.
type Sym3 = [Real; 6];

/// A 3-vector over a body's `(vx, vy, w)`.
type Vec3 = [Real; 3];

/// One joint of the tree, in elimination order, with what a pass needs of it.
#[derive(Debug, Clone, Copy)]
struct TreeJoint {
    /// Its index among the step's joint constraints.
    constraint: usize,
    /// Its anchors and its bodies' masses.
    point: JointFrame,
    /// Its bodies' states, and whether each takes impulses.
    a: usize,
    b: usize,
    moves_a: bool,
    moves_b: bool,
    /// Whether the pivot (the body whose other joints it couples) is B; else A.
    pivot_b: bool,
    /// The accumulated point impulse, on B (A takes its opposite).
    impulse: Vec2,
    /// This pass: the anchors, `D⁻¹` (as `[d11, d12, d22]`), `W Gᵀ` at the pivot (two
    /// columns), and the solve's intermediate `z`.
    ra: Vec2,
    rb: Vec2,
    inverse: [Real; 3],
    spread: [Vec3; 2],
    z: Vec2,
}

/// The joint trees of a step: which joints, in what order, and the pass's scratch.
#[derive(Debug, Clone, Default)]
pub(crate) struct JointTrees {
    joints: Vec<TreeJoint>,
    /// The moving bodies of the trees, whose scratch a pass resets.
    bodies: Vec<usize>,
    /// Per state: the effective inverse mass, and the sweeps' accumulated vectors.
    inverse_mass: Vec<Sym3>,
    accumulated: Vec<Vec3>,
    /// Planning scratch: joints left per state, the joints at each state (in CSR).
    left: Vec<u32>,
    starts: Vec<u32>,
    fill: Vec<u32>,
    at_body: Vec<u32>,
    queue: Vec<u32>,
    removed: Vec<bool>,
    /// Per constraint: a hinge of a component solved directly.
    accepted: Vec<bool>,
    /// Per state: its component's representative (union-find), then the component's tree
    /// joints and loop joints.
    parent: Vec<u32>,
    tree_count: Vec<u32>,
    loop_count: Vec<u32>,
}

impl JointTrees {
    /// No trees this step.
    pub fn clear(&mut self) {
        self.joints.clear();
        self.bodies.clear();
    }

    /// Whether there is anything to solve.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// Orders the revolute joints among `constraints` leaf first over `states` states, marks
    /// them as the tree's (their own solve then leaves the point to it), and leaves the
    /// joints that close loops to the iterative solve. Allocates only as the world grows.
    pub fn plan(&mut self, constraints: &mut [JointConstraint], states: usize) {
        self.joints.clear();
        self.bodies.clear();
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
            // The component's root is one hop away now: the counting compressed its path.
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
        if count == 0 {
            return;
        }
        // The joints at each moving state, in constraint order.
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
        self.removed.clear();
        self.removed.resize(constraints.len(), false);
        // A joint is ready when one of its bodies has no other joint left.
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
                // Only loops are left: the first joint left closes one, and goes to the
                // iterative solve.
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
            let pivot_b = ready_a;
            let Some(point) = c.hinge_point() else {
                continue;
            };
            self.joints.push(TreeJoint {
                constraint: index,
                point,
                a: c.a,
                b: c.b,
                moves_a: c.moves_a,
                moves_b: c.moves_b,
                pivot_b,
                impulse: c.impulses.linear,
                ra: Vec2::zeros(),
                rb: Vec2::zeros(),
                inverse: [0.0; 3],
                spread: [[0.0; 3]; 2],
                z: Vec2::zeros(),
            });
            self.remove(constraints, index);
            placed += 1;
        }
        for tree in &self.joints {
            constraints[tree.constraint].leave_point_to_tree();
        }
        // The moving bodies, once each.
        for tree in &self.joints {
            for (moves, state) in [(tree.moves_a, tree.a), (tree.moves_b, tree.b)] {
                if moves && self.left[state] != u32::MAX {
                    self.left[state] = u32::MAX;
                    self.bodies.push(state);
                }
            }
        }
        if self.inverse_mass.len() < states + 1 {
            self.inverse_mass.resize(states + 1, [0.0; 6]);
            self.accumulated.resize(states + 1, [0.0; 3]);
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

    /// Applies the accumulated impulses (the warm start), or forgets them where the speed
    /// caps cut a body's velocities, as the other joints do.
    pub fn warm_start(&mut self, states: &mut [BodyState]) {
        for tree in &mut self.joints {
            let (mut a, mut b) = (states[tree.a], states[tree.b]);
            if a.held != 0 || b.held != 0 {
                tree.impulse = Vec2::zeros();
                continue;
            }
            let (ra, rb) = tree.point.anchors(&a, &b);
            tree.point.push(&mut a, &mut b, ra, rb, tree.impulse);
            set_velocities(states, tree, &a, &b);
        }
    }

    /// One pass: the velocity error of every tree joint (with the pass's bias) solved away
    /// at once.
    pub fn solve(&mut self, states: &mut [BodyState], pass: &JointPass) {
        self.exact(states, 0.0, |tree, a, b| {
            let mut error = JointFrame::velocity(a, b, tree.ra, tree.rb);
            if pass.use_bias {
                error += tree.point.separation(a, b, tree.ra, tree.rb) * pass.softness.bias_rate;
            }
            error
        });
        let s = pass.softness;
        let (mass_scale, impulse_scale) = if pass.use_bias {
            (s.mass_scale, s.impulse_scale)
        } else {
            (1.0, 0.0)
        };
        for tree in &mut self.joints {
            let impulse = -tree.z * mass_scale - tree.impulse * impulse_scale;
            tree.impulse += impulse;
            let (mut a, mut b) = (states[tree.a], states[tree.b]);
            tree.point.push(&mut a, &mut b, tree.ra, tree.rb, impulse);
            set_velocities(states, tree, &a, &b);
        }
    }

    /// Closes the trees' drift in position (one Newton step on the anchors' separations,
    /// the bodies moved as the same impulses would move them in a unit of time), leaving
    /// their velocities alone: the end of a substep, where the soft bias would otherwise
    /// leave what nonlinear motion opened for the next one.
    pub fn project(&mut self, states: &mut [BodyState]) {
        self.exact(states, TREE_PROJECTION_GIVE, |tree, a, b| {
            tree.point.separation(a, b, tree.ra, tree.rb)
        });
        for tree in &self.joints {
            let (mut a, mut b) = (states[tree.a], states[tree.b]);
            tree.point.shift(&mut a, &mut b, tree.ra, tree.rb, -tree.z);
            for (moves, index, state) in [(tree.moves_a, tree.a, a), (tree.moves_b, tree.b, b)] {
                if moves {
                    states[index].dp = state.dp;
                    states[index].dq = state.dq;
                }
            }
        }
    }

    /// Solves `A x = r` over every tree at once, `r` each joint's `error` given the bodies'
    /// states, leaving `x` in each joint's `z` and its anchors in `ra`, `rb`.
    fn exact(
        &mut self,
        states: &[BodyState],
        give: Real,
        error: impl Fn(&TreeJoint, &BodyState, &BodyState) -> Vec2,
    ) {
        for &state in &self.bodies {
            self.accumulated[state] = [0.0; 3];
        }
        for tree in &self.joints {
            let (ma, ia, mb, ib) = tree.point.inverse_masses();
            if tree.moves_a {
                self.inverse_mass[tree.a] = [ma, 0.0, 0.0, ma, 0.0, ia];
            }
            if tree.moves_b {
                self.inverse_mass[tree.b] = [mb, 0.0, 0.0, mb, 0.0, ib];
            }
        }
        // Leaf first: factor, and carry each joint's part of the error to its pivot.
        for tree in &mut self.joints {
            let (a, b) = (states[tree.a], states[tree.b]);
            let (ra, rb) = tree.point.anchors(&a, &b);
            (tree.ra, tree.rb) = (ra, rb);
            let mut y = error(tree, &a, &b);
            let mut d = [0.0; 3];
            for (moves, state, r, sign) in [
                (tree.moves_a, tree.a, ra, -1.0),
                (tree.moves_b, tree.b, rb, 1.0),
            ] {
                if moves {
                    add_sandwich(&mut d, &self.inverse_mass[state], r);
                    y -= jacobian(r, self.accumulated[state]) * sign;
                }
            }
            if give > 0.0 {
                let (ma, ia, mb, ib) = tree.point.inverse_masses();
                let own = ma + mb + 0.5 * (ia * ra.norm_squared() + ib * rb.norm_squared());
                d[0] += give * own;
                d[2] += give * own;
            }
            tree.inverse = inverse22(d);
            tree.z = mul22(tree.inverse, y);
            let (pivot, r, sign, moves) = if tree.pivot_b {
                (tree.b, rb, 1.0, tree.moves_b)
            } else {
                (tree.a, ra, -1.0, tree.moves_a)
            };
            if moves {
                // W Gᵀ at the pivot, G = sign [[1, 0, -r.y], [0, 1, r.x]]: the pivot's share
                // of this joint's solution, then W less what this joint now holds.
                let columns = spread(&self.inverse_mass[pivot], r, sign);
                tree.spread = columns;
                let q = &mut self.accumulated[pivot];
                for (column, zk) in columns.iter().zip([tree.z.x, tree.z.y]) {
                    for i in 0..3 {
                        q[i] += column[i] * zk;
                    }
                }
                subtract_outer(&mut self.inverse_mass[pivot], &columns, tree.inverse);
            } else {
                tree.spread = [[0.0; 3]; 2];
            }
        }
        // Root first: each joint less what the joints beyond its pivot carry.
        for &state in &self.bodies {
            self.accumulated[state] = [0.0; 3];
        }
        for tree in self.joints.iter_mut().rev() {
            let pivot = if tree.pivot_b { tree.b } else { tree.a };
            let t = self.accumulated[pivot];
            let carried = Vec2::new(
                tree.spread[0].iter().zip(t).map(|(c, t)| c * t).sum(),
                tree.spread[1].iter().zip(t).map(|(c, t)| c * t).sum(),
            );
            let x = tree.z - mul22(tree.inverse, carried);
            for (moves, state, r, sign) in [
                (tree.moves_a, tree.a, tree.ra, -1.0),
                (tree.moves_b, tree.b, tree.rb, 1.0),
            ] {
                if moves {
                    // Gᵀ x.
                    let t = &mut self.accumulated[state];
                    t[0] += sign * x.x;
                    t[1] += sign * x.y;
                    t[2] += sign * (-r.y * x.x + r.x * x.y);
                }
            }
            tree.z = x;
        }
    }

    /// Hands the accumulated point impulses back to their joints.
    pub fn finish(&self, constraints: &mut [JointConstraint]) {
        for tree in &self.joints {
            constraints[tree.constraint].impulses.linear = tree.impulse;
        }
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

/// Writes a joint's bodies' velocities back (those that move).
fn set_velocities(states: &mut [BodyState], tree: &TreeJoint, a: &BodyState, b: &BodyState) {
    for (moves, index, state) in [(tree.moves_a, tree.a, a), (tree.moves_b, tree.b, b)] {
        if moves {
            states[index].v = state.v;
            states[index].w = state.w;
        }
    }
}

/// `G q` for `G = [[1, 0, -r.y], [0, 1, r.x]]` (the sign left to the caller).
fn jacobian(r: Vec2, q: Vec3) -> Vec2 {
    Vec2::new(q[0] - r.y * q[2], q[1] + r.x * q[2])
}

/// `d += G W Gᵀ` for `G = ±[[1, 0, -r.y], [0, 1, r.x]]` (the sign squares away).
fn add_sandwich(d: &mut [Real; 3], w: &Sym3, r: Vec2) {
    let [xx, xy, xw, yy, yw, ww] = *w;
    // Rows of G W.
    let g0 = [xx - r.y * xw, xy - r.y * yw, xw - r.y * ww];
    let g1 = [xy + r.x * xw, yy + r.x * yw, yw + r.x * ww];
    d[0] += g0[0] - r.y * g0[2];
    d[1] += g0[1] + r.x * g0[2];
    d[2] += g1[1] + r.x * g1[2];
}

/// The two columns of `W Gᵀ` for `G = sign [[1, 0, -r.y], [0, 1, r.x]]`.
fn spread(w: &Sym3, r: Vec2, sign: Real) -> [Vec3; 2] {
    let [xx, xy, xw, yy, yw, ww] = *w;
    [
        [
            sign * (xx - r.y * xw),
            sign * (xy - r.y * yw),
            sign * (xw - r.y * ww),
        ],
        [
            sign * (xy + r.x * xw),
            sign * (yy + r.x * yw),
            sign * (yw + r.x * ww),
        ],
    ]
}

/// `w -= C D⁻¹ Cᵀ` for the 3x2 `C` given by its columns and the symmetric 2x2 `D⁻¹`.
fn subtract_outer(w: &mut Sym3, c: &[Vec3; 2], [d11, d12, d22]: [Real; 3]) {
    // C D⁻¹: 3x2.
    let e = |i: usize| [c[0][i] * d11 + c[1][i] * d12, c[0][i] * d12 + c[1][i] * d22];
    let (e0, e1, e2) = (e(0), e(1), e(2));
    let dot = |e: [Real; 2], j: usize| e[0] * c[0][j] + e[1] * c[1][j];
    w[0] -= dot(e0, 0);
    w[1] -= dot(e0, 1);
    w[2] -= dot(e0, 2);
    w[3] -= dot(e1, 1);
    w[4] -= dot(e1, 2);
    w[5] -= dot(e2, 2);
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

fn mul22([m11, m12, m22]: [Real; 3], v: Vec2) -> Vec2 {
    Vec2::new(m11 * v.x + m12 * v.y, m12 * v.x + m22 * v.y)
}
