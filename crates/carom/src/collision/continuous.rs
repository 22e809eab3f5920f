//! Continuous collision: fast bodies do not tunnel through thin ones.
//!
//! After the solve, a dynamic body that moved more than half its smallest extent this step is
//! swept from where it started to where it ended. Conservative advancement finds the first
//! time its shape comes within the linear slop of a static body: with `d` the exact distance
//! and `bound` the fastest the two can close that distance, advancing by `d / bound` can never
//! step past a contact. The body is left at that time of impact with its velocity; the next
//! step's speculative contact stops it.
//!
//! Bullets are swept after the other fast bodies have been put back, against every body, and
//! a moving one is swept too: its path over the step, not only where it ended, so a bullet
//! cannot start the sweep already past a wall that came towards it. A bullet that hits a
//! moving body is carried with it to where that body ended, keeping the place on its face
//! where it hit. (Sweeping against where the other body ended, as Box2D does, lets a wall
//! coming at a bullet, or one the solver pushed on, pass the bullet through itself.)
//!
//! With direct joints, a body put back takes the bodies hinged to it back to the same time
//! (along their own paths), so its hinges stay closed: put back alone, a ragdoll's limb would
//! part from its body by as far as the rest went on.
//!
//! The sweep is the second line. The first is in the contacts: with this effect on, a pair's
//! face points are kept as far apart as the pair can close in a step (see
//! [`crate::geometry::query::manifold::Margins`]) and moving bodies' broadphase boxes cover where they are going,
//! so a body meeting a face, static or moving, at any speed has its contact before it gets
//! there and the solver stops it at the surface.

use crate::capacity::room;
use crate::collision::broadphase::BroadPhase;
use crate::constants::{
    LINK_SKIM_FRACTION, MAX_TIME_OF_IMPACT_ITERATIONS, SWEEPS_PER_TASK, TASKS_PER_THREAD,
};
use crate::dynamics::body::{Body, BodyHandle, BodyKind, Pose};
use crate::dynamics::collider::{Collider, ColliderHandle, place_colliders};
use crate::geometry::aabb::Aabb;
use crate::geometry::query::distance::separation;
use crate::geometry::shape::WorldShape;
use crate::handle_map::HandleMap;
use crate::joint::store::JointStore;
use crate::math::{Isometry, Real, Rot, Vec2, angle_of, rotation};
use crate::parallel::worth_sharing;
use rayon::prelude::*;
use std::collections::TryReserveError;
use std::ops::Range;

/// How far any point of `body` can have moved since `from`: at least the sweep's reach
/// (translation plus turn times reach), without the arctangent the turn costs.
fn motion_bound(from: Pose, body: &Body) -> Real {
    let relative = body.rotation() * from.rotation.inverse();
    (body.center_of_mass() - from.center).norm() + turn_bound(relative) * body.reach()
}

/// At least the angle of `relative`, in magnitude: a turn of at most a quarter is at most its
/// sine times a quarter turn (Jordan's inequality), with a little to spare for rounding; any
/// larger turn counts as half a turn.
fn turn_bound(relative: Rot) -> Real {
    if relative.re >= 0.0 {
        relative.im.abs() * (1.001 * crate::math::consts::FRAC_PI_2)
    } else {
        crate::math::consts::PI
    }
}

/// A straight sweep of the centre of mass, and a steady turn about it, over the step, `t`
/// in `[0, 1]`.
#[derive(Debug, Clone, Copy)]
struct Sweep {
    start: Vec2,
    translation: Vec2,
    start_rotation: Rot,
    turn: Real,
    /// The centre of mass in the body's frame.
    local_center: Vec2,
}

impl Sweep {
    fn new(from: Pose, body: &Body) -> Self {
        Sweep {
            start: from.center,
            translation: body.center_of_mass() - from.center,
            start_rotation: from.rotation,
            turn: angle_of(&(body.rotation() * from.rotation.inverse())),
            local_center: body.local_center(),
        }
    }

    /// The centre of mass and the rotation at `t`.
    fn pose_at(&self, t: Real) -> (Vec2, Rot) {
        (
            self.start + self.translation * t,
            rotation(self.turn * t) * self.start_rotation,
        )
    }

    /// The body's transform (of its origin) at `t`.
    fn at(&self, t: Real) -> Isometry {
        let (center, rotation) = self.pose_at(t);
        Isometry::from_parts((center - rotation * self.local_center).into(), rotation)
    }
}

/// The first time in `(0, 1)` at which two shapes would pass into each other, by conservative
/// advancement: with `separation_at(t)` their signed gap at `t` (negative when overlapping) and
/// `bound` the fastest they can close it per unit of sweep time, advancing by the gap over
/// `bound` can never step past the goal.
///
/// Shapes that start clear of each other are stopped when they come within `target`. A shape
/// already touching at the start (a fast box sliding on the floor it rests on, a plank landing
/// on one end) is the solver's business, but the solver may not stop all of it in one step:
/// it may go on as long as no point sinks more than [`sink_allowance`] deeper than it started
/// (`min_extent` is the swept shape's). Stopping it at the first touch instead would freeze a
/// sliding body where it started, every step; sweeping only a core around its centre (Box2D's
/// fallback) lets a spinning plank's far end swing through a thin floor.
fn time_of_impact(
    bound: Real,
    min_extent: Real,
    target: Real,
    mut separation_at: impl FnMut(Real) -> Real,
) -> Option<Real> {
    if bound <= 0.0 {
        return None;
    }
    let tolerance = 0.25 * target;
    let start = separation_at(0.0);
    let goal = if start >= target + tolerance {
        target
    } else {
        start.min(target) - sink_allowance(min_extent, target)
    };
    let mut t: Real = 0.0;
    let mut distance = start;
    for _ in 0..MAX_TIME_OF_IMPACT_ITERATIONS {
        if distance < goal + tolerance {
            return Some(t);
        }
        t += (distance - goal) / bound;
        if t >= 1.0 {
            return None;
        }
        distance = separation_at(t);
    }
    // Still approaching after many small advances: stop here, short of the goal.
    Some(t)
}

/// [`time_of_impact`] of `collider` on `sweep` with `other`, a shape that stays where it is.
fn impact_with_still(
    collider: &Collider,
    sweep: &Sweep,
    other: &WorldShape,
    target: Real,
    placed: &mut WorldShape,
) -> Option<Real> {
    let bound =
        sweep.translation.norm() + sweep.turn.abs() * collider.reach_from(sweep.local_center);
    time_of_impact(bound, collider.shape().min_extent(), target, |t| {
        collider.place_shape(placed, &sweep.at(t));
        separation(other, placed).separation
    })
}

/// [`time_of_impact`] of `collider` on `sweep` with `other` on `other_sweep`: both move, and
/// the gap closes no faster than their centres close plus how fast each turns its reach.
fn impact_with_moving(
    (collider, sweep): (&Collider, &Sweep),
    (other, other_sweep): (&Collider, &Sweep),
    target: Real,
    (placed, placed_other): (&mut WorldShape, &mut WorldShape),
) -> Option<Real> {
    let bound = (sweep.translation - other_sweep.translation).norm()
        + sweep.turn.abs() * collider.reach_from(sweep.local_center)
        + other_sweep.turn.abs() * other.reach_from(other_sweep.local_center);
    time_of_impact(bound, collider.shape().min_extent(), target, |t| {
        collider.place_shape(placed, &sweep.at(t));
        other.place_shape(placed_other, &other_sweep.at(t));
        separation(placed_other, placed).separation
    })
}

/// How much deeper than it started a shape that already touches another may sink within one
/// step: a quarter of its smallest extent, and never less than twice the contact target.
fn sink_allowance(min_extent: Real, target: Real) -> Real {
    (0.25 * min_extent).max(2.0 * target)
}

/// Sweeps every fast body of the awake set (`bodies[awake]`) and moves the ones that would
/// have tunnelled back to their time of impact, from their poses at the start of the step
/// ([`Body::start_pose`]). With `hooked` (the world has a pre-solve hook), pairs
/// that asked for the hook are left to it and their contacts. Returns the number of impacts
/// and the number of bodies swept. A sweep stops only at colliders its collider may collide
/// with: their collision filters agree and no joint (`joints`) keeps the two bodies apart.
/// `scratch` keeps its memory from step to step. With `groups` (each awake body's group of
/// hinged bodies, by its index in the awake set), a group is put back together to its first
/// impact ([`rewind_groups`]).
///
/// The other fast bodies are swept first, then the bullets against the world those left. In
/// each pass the fast bodies are picked in order, swept on as many threads as rayon gives (each
/// sweep reads the world as the pass found it, and nothing is moved until all are done), then
/// put back in order: the same bits on any number of threads.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_continuous(
    bodies: &mut HandleMap<BodyHandle, Body>,
    awake: Range<usize>,
    colliders: &mut HandleMap<ColliderHandle, Collider>,
    scratch: &mut ContinuousScratch,
    broadphase: &BroadPhase,
    joints: &JointStore,
    target: Real,
    hooked: bool,
    groups: Option<&[u32]>,
) -> (usize, usize) {
    let ContinuousScratch {
        fast,
        impacts,
        swept,
        paths,
        earliest,
        rewound,
    } = scratch;
    rewound.clear();
    fast.clear();
    let all = bodies.as_slice();
    let mut bullets = 0;
    for (index, body) in awake.clone().zip(&all[awake.clone()]) {
        if body.kind() != BodyKind::Dynamic {
            continue;
        }
        let slow = body.sweep_threshold() * body.min_extent();
        if motion_bound(body.start_pose(), body) <= slow {
            continue;
        }
        let sweep = Sweep::new(body.start_pose(), body);
        let reach = sweep.translation.norm() + sweep.turn.abs() * body.reach();
        if reach > slow {
            fast.push((index, sweep));
            bullets += usize::from(body.is_bullet());
        }
    }
    // The bullets last, each group in storage order.
    let others = fast.len() - bullets;
    if bullets > 0 {
        fast.sort_by_key(|&(index, _)| all[index].is_bullet());
    }
    impacts.clear();
    impacts.resize(fast.len(), None);
    let mut count = 0;
    for pass in [0..others, others..fast.len()] {
        if pass.is_empty() {
            continue;
        }
        // Where each fast body went this step, as the pass finds it, for the bullets to find
        // the moving bodies the broadphase does not hold where they were.
        paths.clear();
        if pass.start == others {
            let all = bodies.as_slice();
            paths.extend(fast.iter().map(|&(index, _)| swept_box(&all[index])));
        }
        let world = SweptWorld {
            bodies: bodies.as_slice(),
            awake: awake.clone(),
            colliders,
            broadphase,
            joints,
            target,
            hooked,
            fast,
            paths,
        };
        world.sweep_all(&pass, &mut impacts[pass.clone()], swept);
        if let (Some(groups), 0) = (groups, pass.start) {
            let jointed = Jointed {
                groups,
                awake: awake.clone(),
                earliest: &mut *earliest,
            };
            count += rewind_groups(
                bodies,
                colliders,
                jointed,
                &fast[pass.clone()],
                impacts,
                rewound,
            );
        }
        let moved = bodies.as_mut_slice();
        for (&(index, _), impact) in fast[pass.clone()].iter().zip(&impacts[pass]) {
            if let &Some((_, center, rotation)) = impact {
                let body = &mut moved[index];
                body.move_to_time_of_impact(center, rotation);
                place_colliders(body, colliders);
                count += 1;
            }
        }
    }
    (count, fast.len())
}

/// What [`rewind_groups`] reads of the hinged groups.
struct Jointed<'a> {
    /// Each awake body's group, by its index in the awake set.
    groups: &'a [u32],
    awake: Range<usize>,
    /// Scratch: each group put back, with its first impact.
    earliest: &'a mut Vec<(u32, Real)>,
}

/// Puts every body of a hinged group back to the group's first impact this step, each along
/// its own path: `fast` (the non-bullets, in storage order) and their `impacts` are changed
/// to it, and the other bodies of the group, not fast themselves, are moved (and listed in
/// `rewound`). Bullets are left to their own pass. Returns how many bodies were moved.
fn rewind_groups(
    bodies: &mut HandleMap<BodyHandle, Body>,
    colliders: &mut HandleMap<ColliderHandle, Collider>,
    jointed: Jointed,
    fast: &[(usize, Sweep)],
    impacts: &mut [Option<(Real, Vec2, Rot)>],
    rewound: &mut Vec<usize>,
) -> usize {
    let Jointed {
        groups,
        awake,
        earliest,
    } = jointed;
    // A body the solve did not see (none should be) is in no group.
    let group = |index: usize| groups.get(index - awake.start).copied();
    earliest.clear();
    for (&(index, _), impact) in fast.iter().zip(impacts.iter()) {
        if let (Some((t, ..)), Some(group)) = (impact, group(index)) {
            earliest.push((group, *t));
        }
    }
    if earliest.is_empty() {
        return 0;
    }
    earliest.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    earliest.dedup_by_key(|&mut (group, _)| group);
    let first = |index: usize| {
        let g = group(index)?;
        earliest
            .binary_search_by_key(&g, |&(group, _)| group)
            .ok()
            .map(|at| earliest[at].1)
    };
    // The fast bodies: to the group's impact if it is earlier than their own.
    for (&(index, sweep), impact) in fast.iter().zip(impacts.iter_mut()) {
        if let Some(t) = first(index)
            && impact.is_none_or(|(own, ..)| t < own)
        {
            let (center, rotation) = sweep.pose_at(t);
            *impact = Some((t, center, rotation));
        }
    }
    // The others of each group.
    let moved = bodies.as_mut_slice();
    for index in awake.clone() {
        let body = &mut moved[index];
        if body.kind() != BodyKind::Dynamic
            || body.is_bullet()
            || fast.binary_search_by_key(&index, |&(fast, _)| fast).is_ok()
        {
            continue;
        }
        if let Some(t) = first(index) {
            let (center, rotation) = Sweep::new(body.start_pose(), body).pose_at(t);
            body.move_to_time_of_impact(center, rotation);
            place_colliders(body, colliders);
            rewound.push(index);
        }
    }
    rewound.len()
}

/// A box around everywhere `body` went this step: its reach around its centre's path.
fn swept_box(body: &Body) -> Aabb {
    let reach = Vec2::repeat(body.reach());
    let (from, to) = (body.start_pose().center, body.center_of_mass());
    Aabb::new(from.inf(&to) - reach, from.sup(&to) + reach)
}

/// What a sweep reads of the world: all of it as the pass found it.
struct SweptWorld<'a> {
    bodies: &'a [Body],
    /// The storage indices of the awake bodies: only these moved this step.
    awake: Range<usize>,
    colliders: &'a HandleMap<ColliderHandle, Collider>,
    broadphase: &'a BroadPhase,
    joints: &'a JointStore,
    /// The gap a time of impact leaves, m.
    target: Real,
    /// The world has a pre-solve hook.
    hooked: bool,
    /// Every fast body of the step (storage index, sweep).
    fast: &'a [(usize, Sweep)],
    /// For the bullets' pass, [`swept_box`] of each of `fast`; empty in the first pass.
    paths: &'a [Aabb],
}

/// When a sweep stops, and the moving body it met, if it did: that body's storage index and
/// path.
type Impact = (Real, Option<(usize, Sweep)>);

impl SweptWorld<'_> {
    /// Sweeps `fast[pass]` into `impacts`, on as many threads as rayon gives.
    fn sweep_all(
        &self,
        pass: &Range<usize>,
        impacts: &mut [Option<(Real, Vec2, Rot)>],
        swept: &mut Vec<SweepShapes>,
    ) {
        let fast = &self.fast[pass.clone()];
        let sweep_run = |fast: &[(usize, Sweep)],
                         impacts: &mut [Option<(Real, Vec2, Rot)>],
                         shapes: &mut SweepShapes| {
            for (&(index, sweep), impact) in fast.iter().zip(impacts.iter_mut()) {
                *impact = self.first_impact(index, &sweep, shapes);
            }
        };
        if worth_sharing(fast.len(), SWEEPS_PER_TASK) {
            // One set of scratch shapes per task, kept from step to step: a few tasks per
            // thread, so that the sets, once filled, serve every step after.
            let tasks = fast
                .len()
                .div_ceil(SWEEPS_PER_TASK)
                .min(TASKS_PER_THREAD * rayon::current_num_threads());
            let per_task = fast.len().div_ceil(tasks);
            if swept.len() < tasks {
                swept.resize_with(tasks, Default::default);
            }
            fast.par_chunks(per_task)
                .zip(impacts.par_chunks_mut(per_task))
                .zip(swept.par_iter_mut())
                .for_each(|((fast, impacts), shapes)| sweep_run(fast, impacts, shapes));
        } else {
            if swept.is_empty() {
                swept.push(Default::default());
            }
            sweep_run(fast, impacts, &mut swept[0]);
        }
    }

    /// Where the body at storage index `index`, moving along `sweep`, ends if it meets a
    /// collider it may not pass through before the end of the step (its centre of mass and
    /// rotation then); `shapes` are scratch.
    fn first_impact(
        &self,
        index: usize,
        sweep: &Sweep,
        shapes: &mut SweepShapes,
    ) -> Option<(Real, Vec2, Rot)> {
        let body = &self.bodies[index];
        let mut first: Option<Impact> = None;
        for collider in body
            .colliders()
            .iter()
            .filter_map(|&c| self.colliders.get(c))
        {
            let placed = placed_shape(&mut shapes.own, collider);
            collider.place_shape(placed, &sweep.at(0.0));
            let path = placed.aabb().union(&collider.aabb());
            let mut visit = |handle| {
                if let Some(impact) = self.impact(body, collider, sweep, handle, shapes)
                    && first.is_none_or(|(f, _)| impact.0 < f)
                {
                    first = Some(impact);
                }
            };
            if body.is_bullet() {
                self.broadphase.query(&path, &mut visit);
                // A moving body may have crossed the path from somewhere the broadphase,
                // which holds it where it ended, does not cover.
                for (&(other, _), other_path) in self.fast.iter().zip(self.paths) {
                    if other != index && other_path.overlaps(&path) {
                        for &handle in self.bodies[other].colliders() {
                            visit(handle);
                        }
                    }
                }
            } else {
                // Only a bullet stops at moving bodies: the others need only the static tree.
                self.broadphase.query_static(&path, &mut visit);
            }
        }
        let (t, carrier) = first.filter(|&(t, _)| t < 1.0)?;
        let (center, rotation) = sweep.pose_at(t);
        Some(match carrier {
            None => (t, center, rotation),
            Some((other, other_sweep)) => {
                // Keep the place on the other body's face where the two met, to where it ended.
                let (other_center, other_rotation) = other_sweep.pose_at(t);
                let end = &self.bodies[other];
                let turn = end.rotation() * other_rotation.inverse();
                (
                    t,
                    end.center_of_mass() + turn * (center - other_center),
                    turn * rotation,
                )
            }
        })
    }

    /// When `collider` of `body`, on `sweep`, meets the collider `handle` if it may not pass
    /// through it, and the moving body that collider is on, if it moved.
    fn impact(
        &self,
        body: &Body,
        collider: &Collider,
        sweep: &Sweep,
        handle: ColliderHandle,
        shapes: &mut SweepShapes,
    ) -> Option<Impact> {
        let other = self.colliders.get(handle)?;
        let other_index = other.body_index();
        let other_body = &self.bodies[other_index];
        // Chains are one-sided: a body may pass up through one from behind.
        let eligible = other.body() != body.handle()
            && (other_body.kind() == BodyKind::Static || body.is_bullet())
            && collider.filter().collides_with(&other.filter())
            && !self.joints.filters(body.handle(), other.body())
            && !other.world_shape().is_link_behind(sweep.start)
            && !other.world_shape().is_link_skimmed(
                sweep.start,
                sweep.start + sweep.translation,
                LINK_SKIM_FRACTION * body.min_extent(),
            )
            && !(self.hooked && (collider.pre_solve() || other.pre_solve()));
        if !eligible {
            return None;
        }
        let placed = placed_shape(&mut shapes.own, collider);
        if other_body.kind() != BodyKind::Static && self.awake.contains(&other_index) {
            let other_sweep = Sweep::new(other_body.start_pose(), other_body);
            if other_sweep.translation != Vec2::zeros() || other_sweep.turn != 0.0 {
                let placed_other = placed_shape(&mut shapes.other, other);
                let t = impact_with_moving(
                    (collider, sweep),
                    (other, &other_sweep),
                    self.target,
                    (placed, placed_other),
                )?;
                return Some((t, Some((other_index, other_sweep))));
            }
        }
        let t = impact_with_still(collider, sweep, other.world_shape(), self.target, placed)?;
        Some((t, None))
    }
}

/// The scratch shape a sweep places `collider` in along its path: one per kind of world
/// shape, so sweeping a circle after a polygon does not give up the polygon's storage.
fn placed_shape<'a>(
    shapes: &'a mut [Option<WorldShape>; 3],
    collider: &Collider,
) -> &'a mut WorldShape {
    let kind = match collider.world_shape() {
        WorldShape::Circle { .. } => 0,
        WorldShape::Polygon { .. } => 1,
        WorldShape::ChainSegment { .. } => 2,
    };
    shapes[kind].get_or_insert_with(|| collider.world_shape().clone())
}

/// The scratch shapes of one task of sweeps: the swept body's, and the moving body's it is
/// swept against.
#[derive(Debug, Clone, Default)]
struct SweepShapes {
    own: [Option<WorldShape>; 3],
    other: [Option<WorldShape>; 3],
}

/// What continuous collision works in, kept so a step allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContinuousScratch {
    /// The fast bodies of this step: storage index and sweep; the bullets last.
    fast: Vec<(usize, Sweep)>,
    /// Where each fast body is put back, if it is: when, and its centre and rotation then.
    impacts: Vec<Option<(Real, Vec2, Rot)>>,
    /// Scratch shapes, one set per task.
    swept: Vec<SweepShapes>,
    /// Where each fast body went, for the bullets' pass ([`swept_box`]).
    paths: Vec<Aabb>,
    /// The groups of hinged bodies put back, each with its first impact ([`rewind_groups`]).
    earliest: Vec<(u32, Real)>,
    /// The bodies put back with their group that were not fast themselves.
    rewound: Vec<usize>,
}

impl ContinuousScratch {
    /// Makes room for `bodies` fast bodies swept in a step.
    pub(crate) fn reserve(&mut self, bodies: usize) -> Result<(), TryReserveError> {
        room(&mut self.fast, bodies)?;
        room(&mut self.impacts, bodies)?;
        room(&mut self.swept, bodies)?;
        room(&mut self.paths, bodies)?;
        room(&mut self.earliest, bodies)?;
        room(&mut self.rewound, bodies)
    }

    /// The storage indices of the bodies the last [`solve_continuous`] put back.
    pub(crate) fn moved(&self) -> impl Iterator<Item = usize> + '_ {
        self.fast
            .iter()
            .zip(&self.impacts)
            .filter(|(_, impact)| impact.is_some())
            .map(|(&(index, _), _)| index)
            .chain(self.rewound.iter().copied())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_turn_bound_is_never_below_the_turn() {
        let steps = 100_000;
        for i in 0..=steps {
            let angle = -crate::math::consts::PI
                + 2.0 * crate::math::consts::PI * i as Real / steps as Real;
            let relative = Rot::new(angle);
            let turn = relative.angle().abs();
            assert!(
                turn_bound(relative) >= turn,
                "angle {angle}: {} < {turn}",
                turn_bound(relative)
            );
        }
        // Not so loose that every body is swept: a small turn's bound is small.
        assert!(turn_bound(Rot::new(0.01)) < 0.02);
    }
}
