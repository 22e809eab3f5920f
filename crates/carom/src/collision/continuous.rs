//! Continuous collision: fast bodies do not tunnel through thin ones.
//!
//! After the solve, a dynamic body that moved more than half its smallest extent this step is
//! swept from where it started to where it ended. Conservative advancement finds the first
//! time its shape comes within the linear slop of a static body (or, for bullets, of any
//! other body): with `d` the exact distance and `bound` the fastest any point of the body can
//! close that distance, advancing by `d / bound` can never step past a contact. The body is
//! left at that time of impact with its velocity; the next step's speculative contact stops it.
//!
//! The sweep is the second line. The first is in the contacts: with this effect on, a pair's
//! face points are kept as far apart as the pair can close in a step (see
//! [`crate::collision::manifold::Margins`]) and moving bodies' broadphase boxes cover where they are going,
//! so a body meeting a face, static or moving, at any speed has its contact before it gets
//! there and the solver stops it at the surface.

use crate::collision::broadphase::BroadPhase;
use crate::collision::distance::separation;
use crate::constants::{
    FAST_FRACTION, LINK_SKIM_FRACTION, MAX_TIME_OF_IMPACT_ITERATIONS, SWEEPS_PER_TASK,
    TASKS_PER_THREAD,
};
use crate::dynamics::body::{Body, BodyHandle, BodyKind, Pose};
use crate::dynamics::collider::{Collider, ColliderHandle, place_colliders};
use crate::geometry::shape::WorldShape;
use crate::handle_map::HandleMap;
use crate::joint::store::JointStore;
use crate::math::{Isometry, Real, Rot, Vec2, angle_of, rotation};
use crate::parallel::worth_sharing;
use rayon::prelude::*;
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
        relative.im.abs() * (1.001 * std::f32::consts::FRAC_PI_2)
    } else {
        std::f32::consts::PI
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

/// The first time in `(0, 1)` at which `shape` on `sweep` would pass into `other`, by
/// conservative advancement: with `distance` the signed gap (negative when overlapping) and
/// `bound` the fastest any point of the shape can close it, advancing by `distance / bound`
/// can never step past the goal.
///
/// A shape that starts clear of `other` is stopped when it comes within `target` of it. A shape
/// already touching at the start (a fast box sliding on the floor it rests on, a plank landing
/// on one end) is the solver's business, but the solver may not stop all of it in one step:
/// it may go on as long as no point sinks more than [`sink_allowance`] deeper than it started.
/// Stopping it at the first touch instead would freeze a sliding body where it started, every
/// step; sweeping only a core around its centre (Box2D's fallback) lets a spinning plank's far
/// end swing through a thin floor.
fn time_of_impact(
    collider: &Collider,
    sweep: &Sweep,
    other: &WorldShape,
    target: Real,
    placed: &mut WorldShape,
) -> Option<Real> {
    let radius = collider.reach_from(sweep.local_center);
    // The fastest any point of the shape moves, per unit of sweep time.
    let bound = sweep.translation.norm() + sweep.turn.abs() * radius;
    if bound <= 0.0 {
        return None;
    }
    let tolerance = 0.25 * target;
    collider.place_shape(placed, &sweep.at(0.0));
    let start = separation(other, placed).separation;
    let goal = if start >= target + tolerance {
        target
    } else {
        start.min(target) - sink_allowance(collider.shape().min_extent(), target)
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
        collider.place_shape(placed, &sweep.at(t));
        distance = separation(other, placed).separation;
    }
    // Still approaching after many small advances: stop here, short of the goal.
    Some(t)
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
/// `scratch` keeps its memory from step to step.
///
/// The fast bodies are picked in order, swept on as many threads as rayon gives (each sweep
/// reads the world as the solver left it, and nothing is moved until all are done), then put
/// back in order: the same bits on any number of threads.
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
) -> (usize, usize) {
    let ContinuousScratch {
        fast,
        impacts,
        swept,
    } = scratch;
    fast.clear();
    let all = bodies.as_slice();
    for (index, body) in awake.clone().zip(&all[awake]) {
        if body.kind() != BodyKind::Dynamic {
            continue;
        }
        let slow = FAST_FRACTION * body.min_extent();
        if motion_bound(body.start_pose(), body) <= slow {
            continue;
        }
        let sweep = Sweep::new(body.start_pose(), body);
        let reach = sweep.translation.norm() + sweep.turn.abs() * body.reach();
        if reach > slow {
            fast.push((index, sweep));
        }
    }
    impacts.clear();
    impacts.resize(fast.len(), None);
    {
        let world = SweptWorld {
            bodies: all,
            colliders,
            broadphase,
            joints,
            target,
            hooked,
        };
        let sweep_run = |fast: &[(usize, Sweep)],
                         impacts: &mut [Option<(Vec2, Rot)>],
                         shapes: &mut [Option<WorldShape>; 3]| {
            for (&(index, sweep), impact) in fast.iter().zip(impacts.iter_mut()) {
                *impact = world.first_impact(index, &sweep, shapes);
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
        } else if !fast.is_empty() {
            if swept.is_empty() {
                swept.push(Default::default());
            }
            sweep_run(fast, impacts, &mut swept[0]);
        }
    }
    let moved = bodies.as_mut_slice();
    let mut count = 0;
    for (&(index, _), impact) in fast.iter().zip(impacts.iter()) {
        if let &Some((center, rotation)) = impact {
            let body = &mut moved[index];
            body.move_to_time_of_impact(center, rotation);
            place_colliders(body, colliders);
            count += 1;
        }
    }
    (count, fast.len())
}

/// What a sweep reads of the world: all of it as the solver left it.
struct SweptWorld<'a> {
    bodies: &'a [Body],
    colliders: &'a HandleMap<ColliderHandle, Collider>,
    broadphase: &'a BroadPhase,
    joints: &'a JointStore,
    /// The gap a time of impact leaves, m.
    target: Real,
    /// The world has a pre-solve hook.
    hooked: bool,
}

impl SweptWorld<'_> {
    /// Where the body at storage index `index`, moving along `sweep`, first meets a collider
    /// it may not pass through (its centre of mass and rotation then), if before the end of
    /// the step; `shapes` are scratch.
    fn first_impact(
        &self,
        index: usize,
        sweep: &Sweep,
        shapes: &mut [Option<WorldShape>; 3],
    ) -> Option<(Vec2, Rot)> {
        let body = &self.bodies[index];
        let mut first: Option<Real> = None;
        for collider in body
            .colliders()
            .iter()
            .filter_map(|&c| self.colliders.get(c))
        {
            let placed = placed_shape(shapes, collider);
            collider.place_shape(placed, &sweep.at(0.0));
            let path = placed.aabb().union(&collider.aabb());
            let mut visit = |handle| {
                let Some(other) = self.colliders.get(handle) else {
                    return;
                };
                let other_body = &self.bodies[other.body_index()];
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
                    return;
                }
                let placed = placed_shape(shapes, collider);
                if let Some(t) =
                    time_of_impact(collider, sweep, other.world_shape(), self.target, placed)
                    && first.is_none_or(|f| t < f)
                {
                    first = Some(t);
                }
            };
            // Only a bullet stops at moving bodies: the others need only the static tree.
            if body.is_bullet() {
                self.broadphase.query(&path, &mut visit);
            } else {
                self.broadphase.query_static(&path, &mut visit);
            }
        }
        first.filter(|&t| t < 1.0).map(|t| sweep.pose_at(t))
    }
}

/// The scratch shape a sweep of `collider` places along its path: one per kind of world
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

/// What continuous collision works in, kept so a step allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContinuousScratch {
    /// The fast bodies of this step: storage index and sweep.
    fast: Vec<(usize, Sweep)>,
    /// Where each fast body is put back, if it is.
    impacts: Vec<Option<(Vec2, Rot)>>,
    /// Scratch shapes, one set per task: a sweep places its shape along its path in them.
    swept: Vec<[Option<WorldShape>; 3]>,
}

impl ContinuousScratch {
    /// The storage indices of the bodies the last [`solve_continuous`] put back.
    pub(crate) fn moved(&self) -> impl Iterator<Item = usize> + '_ {
        self.fast
            .iter()
            .zip(&self.impacts)
            .filter(|(_, impact)| impact.is_some())
            .map(|(&(index, _), _)| index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_turn_bound_is_never_below_the_turn() {
        let steps = 100_000;
        for i in 0..=steps {
            let angle =
                -std::f32::consts::PI + 2.0 * std::f32::consts::PI * i as Real / steps as Real;
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
