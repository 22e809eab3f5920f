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
//!
//! The pass goes level by level. Within a level the supports of different upper bodies
//! commute (each moves only its own upper body and reads a lower one that this level does not
//! move), so a level's rounds (the first support of each upper body, then the second, ...)
//! are solved in SIMD bundles ([`super::ShockBundles`]) with the bits of the
//! one-at-a-time solve here, which a round of one takes.

use super::scalar::point_bias;
use super::{
    Bias, BundleInputs, SharedStates, ShockBundles, ShockPassInputs, shock_test_hooks as test_hooks,
};
use crate::collision::contact::Contact;
use crate::constants::MIN_WIDE_ROUND;
use crate::constants::SUPPORT_COSINE;
use crate::math::{Real, Vec2, cross, cross_sv, perp_cw};
use crate::solver::body_state::BodyState;
use crate::solver::contact_constraint::separation_now;
use std::ops::Range;

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
    /// Each support's (lower level, round, index): the `k`-th support of an upper body in a
    /// level is in the level's round `k`; sorted, the order the bundles take them in.
    rounds: Vec<(u32, u32, u32)>,
    /// Per state, its supports so far in the current level: (level, count).
    seen: Vec<(u32, u32)>,
    /// The supports' indices in solve order (level by level, round by round).
    lanes: Vec<u32>,
    /// That order in runs, each solved in SIMD bundles or one support at a time.
    runs: Vec<Run>,
    /// The bundles of the wide runs.
    wide: ShockBundles,
}

/// A run of the solve order.
#[derive(Debug, Clone)]
enum Run {
    /// Bundles (a range of them) of one level's round.
    Wide(Range<usize>),
    /// Supports one at a time (a range of [`ShockPropagation::lanes`]): a round too small
    /// to fill a bundle's lanes.
    Single(Range<usize>),
}

/// A support between levels: a contact whose lower body counts as immovable, so its impulses
/// move the upper body only.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Support {
    contact_index: usize,
    /// The bodies' states, A and B as in the contact.
    pub a: usize,
    pub b: usize,
    /// Whether the upper body is B (else A).
    pub upper_b: bool,
    /// The upper body's inverse mass and inertia.
    pub inv_mass: Real,
    pub inv_inertia: Real,
    /// Unit normal from A to B.
    pub normal: Vec2,
    pub friction: Real,
    pub tangent_speed: Real,
    points: [SupportPoint; 2],
    pub point_count: usize,
}

/// One point of a support.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SupportPoint {
    pub anchor_a: Vec2,
    pub anchor_b: Vec2,
    /// As [`super::contact_constraint::ConstraintPoint::base_separation`].
    pub base_separation: Real,
    /// `1 / k` along the normal and the tangent, of the upper body alone.
    pub normal_mass: Real,
    pub tangent_mass: Real,
    /// The accumulated impulses (the normal one kept across steps, friction within the step).
    pub normal_impulse: Real,
    pub tangent_impulse: Real,
    /// The normal impulse applied over the step, warm start included.
    pub total_normal_impulse: Real,
}

impl Support {
    /// The support at contact `i` of `inputs`, its upper body the one of higher `level`,
    /// its points' masses and warm-start impulses prepared.
    fn of(inputs: &BundleInputs, i: usize, level: &[u32]) -> Self {
        let [a, b] = inputs.body_indices[i].map(|index| inputs.state(index as usize));
        let upper_b = level[b] > level[a];
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
        support
    }

    pub(crate) fn points(&self) -> &[SupportPoint] {
        &self.points[..self.point_count]
    }

    pub(crate) fn points_mut(&mut self) -> &mut [SupportPoint] {
        &mut self.points[..self.point_count]
    }

    /// The upper body's state.
    fn upper(&self) -> usize {
        if self.upper_b { self.b } else { self.a }
    }

    /// Applies the accumulated impulses to the upper body (and counts them as pushed this
    /// step).
    fn warm_start(&mut self, states: &SharedStates) {
        let (mut a, mut b) = (states.get(self.a), states.get(self.b));
        let tangent = perp_cw(self.normal);
        for i in 0..self.point_count {
            let point = self.points[i];
            let p = self.normal * point.normal_impulse + tangent * point.tangent_impulse;
            self.push(&point, p, &mut a, &mut b);
            self.points[i].total_normal_impulse += point.normal_impulse;
        }
        self.write(states, &a, &b);
    }

    /// Stops the upper body on the lower as a soft contact with the ground would, then (if
    /// `friction`) holds it within `μ ×` that push.
    fn solve(&mut self, states: &SharedStates, bias: &Bias, use_bias: bool, friction: bool) {
        let (mut a, mut b) = (states.get(self.a), states.get(self.b));
        let (a, b) = (&mut a, &mut b);
        for i in 0..self.point_count {
            let mut point = self.points[i];
            let (ra, rb) = (point.anchor_a, point.anchor_b);
            let s = separation_now(self.normal, point.base_separation, ra, rb, a, b);
            let (velocity_bias, mass_scale, impulse_scale) =
                point_bias(s, bias.soft, bias, use_bias);
            let (va, vb) = self.velocities(&point, self.normal, true, a, b);
            let impulse = -point.normal_mass * (mass_scale * (vb - va) + velocity_bias)
                - impulse_scale * point.normal_impulse;
            let total = (point.normal_impulse + impulse).max(0.0);
            let applied = total - point.normal_impulse;
            point.normal_impulse = total;
            point.total_normal_impulse += applied;
            self.push(&point, self.normal * applied, a, b);
            self.points[i] = point;
        }
        if friction {
            let tangent = perp_cw(self.normal);
            for i in 0..self.point_count {
                let mut point = self.points[i];
                let (va, vb) = self.velocities(&point, tangent, false, a, b);
                let vt = vb - va - self.tangent_speed;
                let limit = self.friction * point.normal_impulse;
                let total = (point.tangent_impulse - point.tangent_mass * vt).clamp(-limit, limit);
                let applied = total - point.tangent_impulse;
                point.tangent_impulse = total;
                self.push(&point, tangent * applied, a, b);
                self.points[i] = point;
            }
        }
        self.write(states, a, b);
    }

    /// Writes back the upper body's velocities.
    fn write(&self, states: &SharedStates, a: &BodyState, b: &BodyState) {
        states.set_velocity(self.upper(), if self.upper_b { b } else { a });
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
    pub(crate) fn clear(&mut self) {
        self.supports.clear();
    }

    /// Whether there is anything to solve.
    pub(crate) fn is_empty(&self) -> bool {
        self.supports.is_empty()
    }

    /// Levels the bodies from the ground up over the supports (those of `inputs`' touching
    /// contacts whose normals are within 60° of `up`) and prepares the supports between
    /// levels, lowest first (ties in contact order, so the same on every thread count).
    /// Nothing without `up` (no gravity). Allocates only as the world grows.
    pub(crate) fn plan(&mut self, inputs: &BundleInputs, up: Option<Vec2>) {
        self.supports.clear();
        let Some(up) = up else {
            return;
        };
        self.find_supports(inputs, up);
        self.level_bodies(inputs);
        self.order_supports(inputs);
        for &(_, i) in &self.order {
            let support = Support::of(inputs, i as usize, &self.level);
            self.supports.push(support);
        }
        self.pack(inputs.masses.len());
    }

    /// Each support of a moving body as (lower, upper, contact): its normal, from A to B,
    /// points up or down.
    fn find_supports(&mut self, inputs: &BundleInputs, up: Vec2) {
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
            if inputs.masses[support.1].dynamic {
                self.found
                    .push([support.0 as u32, support.1 as u32, i as u32]);
            }
        }
    }

    /// Each body's level, breadth first over the supports: moving bodies resting on ones
    /// that do not move are level 1; bodies that do not move are level 0, and moving bodies
    /// that nothing still holds up stay unreached.
    fn level_bodies(&mut self, inputs: &BundleInputs) {
        let count = inputs.masses.len();
        let moves = |state: usize| inputs.masses[state].dynamic;
        // The search starts at level 1; the graph leads from each moving body to the moving
        // bodies it supports.
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
    }

    /// Every support from a lower level to a higher one, lowest first.
    fn order_supports(&mut self, inputs: &BundleInputs) {
        self.order.clear();
        for &[lower, upper, i] in &self.found {
            let (below, above) = (self.level[lower as usize], self.level[upper as usize]);
            if inputs.masses[lower as usize].dynamic && above != UNREACHED && below < above {
                self.order.push((below, i));
            }
        }
        self.order.sort_unstable();
    }

    /// Puts the supports into bundles, level by level and round by round (`count` states,
    /// the last the spare one, which empty lanes name).
    fn pack(&mut self, count: usize) {
        self.seen.clear();
        self.seen.resize(count, (UNREACHED, 0));
        self.rounds.clear();
        for (index, (&(level, _), support)) in self.order.iter().zip(&self.supports).enumerate() {
            let upper = if support.upper_b {
                support.b
            } else {
                support.a
            };
            let seen = &mut self.seen[upper];
            if seen.0 != level {
                *seen = (level, 0);
            }
            self.rounds.push((level, seen.1, index as u32));
            seen.1 += 1;
        }
        self.rounds.sort_unstable();
        self.lanes.clear();
        self.lanes
            .extend(self.rounds.iter().map(|&(_, _, index)| index));
        self.runs.clear();
        self.wide.clear();
        let spare = count as u32 - 1;
        let mut start = 0;
        for group in self.rounds.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let range = start..start + group.len();
            start = range.end;
            let run = if group.len() >= MIN_WIDE_ROUND && !test_hooks::ONE_AT_A_TIME.get() {
                let members = &self.lanes[range];
                Run::Wide(self.wide.push(&self.supports, members, spare))
            } else {
                Run::Single(range)
            };
            // Neighbouring single runs are one.
            match (self.runs.last_mut(), run) {
                (Some(Run::Single(last)), Run::Single(next)) => last.end = next.end,
                (_, run) => self.runs.push(run),
            }
        }
    }

    /// Applies the accumulated impulses to the upper bodies (and counts the pushes as pushed
    /// this step).
    pub(crate) fn warm_start(&mut self, states: &SharedStates) {
        for run in &self.runs {
            match run {
                Run::Wide(range) => self.wide.warm_start(states, range.clone()),
                Run::Single(range) => {
                    for &i in &self.lanes[range.clone()] {
                        self.supports[i as usize].warm_start(states);
                    }
                }
            }
        }
    }

    /// One pass from the ground up, biased or relaxing: each support stops its upper body on
    /// the lower, as a soft contact with the ground would, then (if `friction`) holds it by
    /// friction within `μ ×` that push, beside the ordinary passes' friction within theirs.
    pub(crate) fn solve(
        &mut self,
        states: &SharedStates,
        bias: &Bias,
        use_bias: bool,
        friction: bool,
    ) {
        let inputs = ShockPassInputs {
            use_bias,
            friction,
            inv_h: bias.inv_h,
            max_push_speed: bias.max_push_speed,
            bias_rate: bias.soft.bias_rate,
            mass_scale: bias.soft.mass_scale,
            impulse_scale: bias.soft.impulse_scale,
        };
        for run in &self.runs {
            match run {
                Run::Wide(range) => self.wide.solve(states, range.clone(), inputs),
                Run::Single(range) => {
                    for &i in &self.lanes[range.clone()] {
                        self.supports[i as usize].solve(states, bias, use_bias, friction);
                    }
                }
            }
        }
    }

    /// Keeps the accumulated pushes in the contacts' manifolds for the next step's warm start
    /// (and forgets those of the touching contacts `order` names that are not supports between
    /// levels now), and adds what each pushed this step to its contact's reported impulse.
    pub(crate) fn store(&mut self, contacts: &mut [Contact], order: &[usize]) {
        self.wide.unpack(&mut self.supports);
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

#[cfg(test)]
mod tests {
    use super::test_hooks::{BUNDLES_MADE, FOUR_LANES, ONE_AT_A_TIME};
    use crate::dynamics::body_def::BodyDef;
    use crate::geometry::shape::Shape;
    use crate::math::{Real, vec2};
    use crate::solver::soft_step::lanes::Lane;
    use crate::world::World;

    /// The bits of every body after two seconds of three pyramids of boxes under heavy tops,
    /// with shock propagation, built and stepped on this thread as the hooks say.
    fn pyramids_with_shock(four_lanes: bool, one_at_a_time: bool) -> Vec<Real> {
        FOUR_LANES.set(four_lanes);
        ONE_AT_A_TIME.set(one_at_a_time);
        let mut world = World::new();
        world
            .update_settings(|s| {
                s.solver.shock_propagation = true;
                s.solver.substeps = 4;
            })
            .unwrap();
        let ground = BodyDef::static_body(Shape::rect(40.0, 0.5)).position(vec2(0.0, -0.5));
        world.add_body(ground).unwrap();
        for (pyramid, density) in [(-12.0, 50.0), (0.0, 100.0), (12.0, 200.0)] {
            let base = 7;
            for row in 0..base {
                for i in 0..base - row {
                    let x = pyramid + (i as Real - (base - row - 1) as Real * 0.5) * 1.02;
                    let y = 0.5 + row as Real;
                    let tilt = 0.01 * ((row + i) % 3) as Real;
                    let body = BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(x, y))
                        .angle(tilt);
                    world.add_body(body).unwrap();
                }
            }
            let top = BodyDef::dynamic(Shape::rect(0.5, 0.5))
                .position(vec2(pyramid, base as Real + 0.5))
                .density(density);
            world.add_body(top).unwrap();
        }
        for _ in 0..120 {
            world.step(1.0 / 60.0).unwrap();
        }
        let state = world
            .bodies()
            .flat_map(|b| {
                let (p, v) = (b.position(), b.linear_velocity());
                [p.x, p.y, b.angle(), v.x, v.y, b.angular_velocity()]
            })
            .collect();
        FOUR_LANES.set(false);
        ONE_AT_A_TIME.set(false);
        state
    }

    /// Whether two states are the same bits.
    fn same_bits(a: &[Real], b: &[Real]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    #[test]
    fn bundles_give_the_bits_of_one_support_at_a_time_at_either_width() {
        BUNDLES_MADE.set(0);
        let wide = pyramids_with_shock(false, false);
        assert!(
            BUNDLES_MADE.get() > 0,
            "the pyramids' rounds are solved in bundles"
        );
        let made = BUNDLES_MADE.get();
        let four = pyramids_with_shock(true, false);
        assert!(BUNDLES_MADE.get() > made);
        let made = BUNDLES_MADE.get();
        let single = pyramids_with_shock(false, true);
        assert_eq!(BUNDLES_MADE.get(), made, "no bundles one at a time");
        assert!(same_bits(&wide, &four), "eight lanes against four");
        // One at a time is the same bits; in the double-precision build, whose lanes are
        // single, two seconds of stacking stay within millimetres (and mm/s) of it.
        let worst = (wide.iter().zip(&single))
            .map(|(&w, &s)| (w - s).abs())
            .fold(0.0, Real::max);
        let agree = if size_of::<Lane>() == size_of::<Real>() {
            same_bits(&wide, &single)
        } else {
            worst < 5e-3
        };
        assert!(
            wide.len() == single.len() && agree,
            "bundles against one at a time: {worst}"
        );
    }
}
