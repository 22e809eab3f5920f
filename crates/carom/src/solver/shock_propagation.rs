//! Shock propagation (Guendelman, Bridson and Fedkiw 2003, "Nonconvex rigid bodies with
//! stacking"): a heavy body resting on light ones is held by them as if they were the ground.
//!
//! Gauss-Seidel moves at most the light body's share of the momentum through a contact per
//! pass, so a 400 kg box landing on a 0.5 kg triangle pushes the triangle into the ground for
//! hundreds of passes before it stops; and a soft contact's stiffness is relative to its
//! effective mass, the triangle's, so even at rest the box sinks into it. Shock propagation
//! levels the bodies by how many supports lie between them and the ground (a support: a
//! contact whose normal is within 60° of straight up), and after each pass over the contacts
//! solves every support between two levels once more, from the ground up, with the lower body
//! immovable: the upper body then stops on the lower as on the ground, with its own mass in the
//! contact's stiffness, and is held there by friction within `μ ×` that push.
//!
//! Only the upper body moves, so the pass takes momentum out and must never put any in: the
//! lower body's motion counts only where it lets the upper body slow down (moving away along
//! the normal, or along the tangent the way the upper body slides, slower), never where it
//! would throw or drag the upper body (as the lower one's push-out from below would).
//!
//! The lower body does not feel the pass, so the weight above reaches the ground through the
//! ordinary passes only, as far as Gauss-Seidel has converged: the ground under a light body
//! reports less than the load it bears. Bodies not resting on static or kinematic ones, and
//! contacts within a level, are left to the ordinary passes; without gravity nothing rests on
//! anything.

use super::BodyState;
use super::contact_constraint::{pair_mut, separation_now};
use super::soft_step::scalar::point_bias;
use super::soft_step::{Bias, BundleInputs};
use crate::collision::contact::Contact;
use crate::constants::SUPPORT_COSINE;
use crate::math::{Real, Vec2, cross, cross_sv, perp_cw};

/// A level not (yet) reached from the ground.
const UNREACHED: u32 = u32::MAX;

/// The step's supports between levels, and the search that levels the bodies.
#[derive(Debug, Clone, Default)]
pub(crate) struct ShockPropagation {
    /// Each state's level: 0 for bodies that do not move, `n + 1` for a body resting on one
    /// of level `n`.
    level: Vec<u32>,
    /// The support graph over the states, as adjacency lists: the bodies state `i` supports
    /// are `neighbours[first[i]..first[i + 1]]`.
    first: Vec<u32>,
    neighbours: Vec<u32>,
    /// The breadth-first search's queue.
    queue: Vec<u32>,
    /// The step's supports of moving bodies as (lower state, upper state, contact index),
    /// in solve order.
    found: Vec<[u32; 3]>,
    /// The supports between levels as (lower level, contact index), lowest first.
    order: Vec<(u32, u32)>,
    /// Those supports prepared, in that order.
    supports: Vec<Support>,
}

/// A support between levels: a contact whose lower body counts as immovable, so its impulses
/// move the upper body only.
#[derive(Debug, Clone, Copy)]
struct Support {
    contact_index: usize,
    /// The bodies' states, A and B as in the contact.
    a: usize,
    b: usize,
    /// Whether the upper body is B (else A).
    upper_b: bool,
    /// The upper body's inverse mass and inertia.
    inv_mass: Real,
    inv_inertia: Real,
    /// Unit normal from A to B.
    normal: Vec2,
    friction: Real,
    tangent_speed: Real,
    points: [SupportPoint; 2],
    point_count: usize,
}

/// One point of a support.
#[derive(Debug, Clone, Copy, Default)]
struct SupportPoint {
    anchor_a: Vec2,
    anchor_b: Vec2,
    /// As [`super::contact_constraint::ConstraintPoint::base_separation`].
    base_separation: Real,
    /// `1 / k` along the normal and the tangent, of the upper body alone.
    normal_mass: Real,
    tangent_mass: Real,
    /// The accumulated impulses (the normal one kept across steps, friction within the step).
    normal_impulse: Real,
    tangent_impulse: Real,
    /// The normal impulse applied over the step, warm start included.
    total_normal_impulse: Real,
}

impl Support {
    fn points(&self) -> &[SupportPoint] {
        &self.points[..self.point_count]
    }

    /// Applies `p`, along A to B, to the upper body alone at a point.
    fn push(&self, point: &SupportPoint, p: Vec2, a: &mut BodyState, b: &mut BodyState) {
        let (upper, anchor, p) = if self.upper_b {
            (b, point.anchor_b, p)
        } else {
            (a, point.anchor_a, -p)
        };
        upper.v += p * self.inv_mass;
        upper.w += self.inv_inertia * cross(anchor, p);
    }

    /// The velocities of A and B at a point along `direction`, the lower body's kept only
    /// where it lets the upper body slow down: for the normal, the lower body moving away
    /// from the upper; for the tangent, the lower body sliding the same way, slower.
    fn velocities(
        &self,
        point: &SupportPoint,
        direction: Vec2,
        along_normal: bool,
        a: &BodyState,
        b: &BodyState,
    ) -> (Real, Real) {
        let va = (a.v + cross_sv(a.w, point.anchor_a)).dot(&direction);
        let vb = (b.v + cross_sv(b.w, point.anchor_b)).dot(&direction);
        let (upper, lower) = if self.upper_b { (vb, va) } else { (va, vb) };
        let lower = if along_normal {
            // B lies along the normal from A: away is down for A, up for B.
            if self.upper_b {
                lower.min(0.0)
            } else {
                lower.max(0.0)
            }
        } else if upper >= 0.0 {
            lower.clamp(0.0, upper)
        } else {
            lower.clamp(upper, 0.0)
        };
        if self.upper_b {
            (lower, upper)
        } else {
            (upper, lower)
        }
    }
}

impl ShockPropagation {
    /// Nothing to solve.
    pub fn clear(&mut self) {
        self.supports.clear();
    }

    /// Whether there is anything to solve.
    pub fn is_empty(&self) -> bool {
        self.supports.is_empty()
    }

    /// Levels the bodies from the ground up over the supports (those of `inputs`' touching
    /// contacts whose normals are within 60° of `up`) and prepares the supports between
    /// levels, lowest first (ties in contact order, so the same on every thread count).
    /// Nothing without `up` (no gravity). Allocates only as the world grows.
    pub fn plan(&mut self, inputs: &BundleInputs, up: Option<Vec2>) {
        self.supports.clear();
        let Some(up) = up else {
            return;
        };
        let count = inputs.masses.len();
        let moves = |state: usize| inputs.masses[state].dynamic;
        // Each support of a moving body as (lower, upper): its normal, from A to B, points up
        // or down.
        self.found.clear();
        for &i in inputs.order {
            let [a, b] = inputs.body_indices[i].map(|index| inputs.state(index as usize));
            let rise = inputs.contacts[i].manifold().normal.dot(&up);
            let support = if rise >= SUPPORT_COSINE {
                (a, b)
            } else if rise <= -SUPPORT_COSINE {
                (b, a)
            } else {
                continue;
            };
            if moves(support.1) {
                self.found
                    .push([support.0 as u32, support.1 as u32, i as u32]);
            }
        }
        // Moving bodies resting on ones that do not move start the search at level 1; the
        // graph leads from each moving body to the moving bodies it supports.
        self.level.clear();
        self.level.extend(
            inputs
                .masses
                .iter()
                .map(|m| if m.dynamic { UNREACHED } else { 0 }),
        );
        self.first.clear();
        self.first.resize(count + 1, 0);
        self.queue.clear();
        for &[lower, upper, _] in &self.found {
            let (lower, upper) = (lower as usize, upper as usize);
            if moves(lower) {
                self.first[lower] += 1;
            } else if self.level[upper] == UNREACHED {
                self.level[upper] = 1;
                self.queue.push(upper as u32);
            }
        }
        // Counts into ends, then filled back to starts.
        for i in 1..=count {
            self.first[i] += self.first[i - 1];
        }
        self.neighbours.clear();
        self.neighbours.resize(self.first[count] as usize, 0);
        for &[lower, upper, _] in &self.found {
            let lower = lower as usize;
            if moves(lower) {
                self.first[lower] -= 1;
                self.neighbours[self.first[lower] as usize] = upper;
            }
        }
        let mut next = 0;
        while let Some(&body) = self.queue.get(next) {
            next += 1;
            let body = body as usize;
            let up = self.level[body] + 1;
            let range = self.first[body] as usize..self.first[body + 1] as usize;
            for &other in &self.neighbours[range] {
                if self.level[other as usize] == UNREACHED {
                    self.level[other as usize] = up;
                    self.queue.push(other);
                }
            }
        }
        // Every support from a lower level to a higher one, lowest first.
        self.order.clear();
        for &[lower, upper, i] in &self.found {
            let (below, above) = (self.level[lower as usize], self.level[upper as usize]);
            if moves(lower as usize) && above != UNREACHED && below < above {
                self.order.push((below, i));
            }
        }
        self.order.sort_unstable();
        for &(_, i) in &self.order {
            let i = i as usize;
            let [a, b] = inputs.body_indices[i].map(|index| inputs.state(index as usize));
            let upper_b = self.level[b] > self.level[a];
            let mass = inputs.masses[if upper_b { b } else { a }];
            let contact = &inputs.contacts[i];
            let manifold = contact.manifold();
            let normal = manifold.normal;
            let tangent = perp_cw(normal);
            let mut support = Support {
                contact_index: i,
                a,
                b,
                upper_b,
                inv_mass: mass.inv_mass,
                inv_inertia: mass.inv_inertia,
                normal,
                friction: contact.friction(),
                tangent_speed: contact.tangent_speed(),
                points: [SupportPoint::default(); 2],
                point_count: manifold.points().len(),
            };
            for (point, mp) in support.points.iter_mut().zip(manifold.points()) {
                let (ra, rb) = (mp.anchor_a, mp.anchor_b);
                let r = if upper_b { rb } else { ra };
                let k = |d: Vec2| mass.inv_mass + mass.inv_inertia * cross(r, d).powi(2);
                let inverse = |k: Real| if k > 0.0 { 1.0 / k } else { 0.0 };
                *point = SupportPoint {
                    anchor_a: ra,
                    anchor_b: rb,
                    base_separation: mp.separation - normal.dot(&(rb - ra)),
                    normal_mass: inverse(k(normal)),
                    tangent_mass: inverse(k(tangent)),
                    normal_impulse: if inputs.warm_starting {
                        mp.shock_impulse
                    } else {
                        0.0
                    },
                    tangent_impulse: 0.0,
                    total_normal_impulse: 0.0,
                };
            }
            self.supports.push(support);
        }
    }

    /// Applies the accumulated impulses to the upper bodies (and counts the pushes as pushed
    /// this step).
    pub fn warm_start(&mut self, states: &mut [BodyState]) {
        for c in &mut self.supports {
            let (a, b) = pair_mut(states, c.a, c.b);
            let tangent = perp_cw(c.normal);
            for i in 0..c.point_count {
                let point = c.points[i];
                let p = c.normal * point.normal_impulse + tangent * point.tangent_impulse;
                c.push(&point, p, a, b);
                c.points[i].total_normal_impulse += point.normal_impulse;
            }
        }
    }

    /// One pass from the ground up, biased or relaxing: each support stops its upper body on
    /// the lower, as a soft contact with the ground would, then (if `friction`) holds it by
    /// friction within `μ ×` that push, beside the ordinary passes' friction within theirs.
    pub fn solve(&mut self, states: &mut [BodyState], bias: &Bias, use_bias: bool, friction: bool) {
        for c in &mut self.supports {
            let (a, b) = pair_mut(states, c.a, c.b);
            for i in 0..c.point_count {
                let mut point = c.points[i];
                let (ra, rb) = (point.anchor_a, point.anchor_b);
                let s = separation_now(c.normal, point.base_separation, ra, rb, a, b);
                let (velocity_bias, mass_scale, impulse_scale) =
                    point_bias(s, bias.soft, bias, use_bias);
                let (va, vb) = c.velocities(&point, c.normal, true, a, b);
                let impulse = -point.normal_mass * (mass_scale * (vb - va) + velocity_bias)
                    - impulse_scale * point.normal_impulse;
                let total = (point.normal_impulse + impulse).max(0.0);
                let applied = total - point.normal_impulse;
                point.normal_impulse = total;
                point.total_normal_impulse += applied;
                c.push(&point, c.normal * applied, a, b);
                c.points[i] = point;
            }
            if friction {
                let tangent = perp_cw(c.normal);
                for i in 0..c.point_count {
                    let mut point = c.points[i];
                    let (va, vb) = c.velocities(&point, tangent, false, a, b);
                    let vt = vb - va - c.tangent_speed;
                    let limit = c.friction * point.normal_impulse;
                    let total =
                        (point.tangent_impulse - point.tangent_mass * vt).clamp(-limit, limit);
                    let applied = total - point.tangent_impulse;
                    point.tangent_impulse = total;
                    c.push(&point, tangent * applied, a, b);
                    c.points[i] = point;
                }
            }
        }
    }

    /// Keeps the accumulated pushes in the contacts' manifolds for the next step's warm start
    /// (and forgets those of the touching contacts `order` names that are not supports between
    /// levels now), and adds what each pushed this step to its contact's reported impulse.
    pub fn store(&self, contacts: &mut [Contact], order: &[usize]) {
        for &i in order {
            let (manifold, _) = contacts[i].manifold_and_impulses_mut();
            for point in manifold.points_mut() {
                point.shock_impulse = 0.0;
            }
        }
        for c in &self.supports {
            let (manifold, reports) = contacts[c.contact_index].manifold_and_impulses_mut();
            let points = manifold.points_mut().iter_mut().zip(reports);
            for ((kept, report), point) in points.zip(c.points()) {
                kept.shock_impulse = point.normal_impulse;
                report.total_normal_impulse += point.total_normal_impulse;
            }
        }
    }
}
