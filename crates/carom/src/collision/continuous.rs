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
use crate::collision::narrowphase::separation;
use crate::constants::{FAST_FRACTION, MAX_TIME_OF_IMPACT_ITERATIONS};
use crate::dynamics::body::{Body, BodyKind};
use crate::geometry::shape::{Shape, WorldShape};
use crate::math::{Isometry, Real, Rot, Vec2};

/// Where a body was at the start of the step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pose {
    pub position: Vec2,
    pub rotation: Rot,
}

impl Pose {
    pub fn of(body: &Body) -> Self {
        Pose {
            position: body.position(),
            rotation: body.rotation(),
        }
    }
}

/// A straight sweep in position and angle over the step, `t` in `[0, 1]`.
#[derive(Debug, Clone, Copy)]
struct Sweep {
    start: Vec2,
    translation: Vec2,
    start_rotation: Rot,
    turn: Real,
}

impl Sweep {
    fn new(from: Pose, body: &Body) -> Self {
        Sweep {
            start: from.position,
            translation: body.position() - from.position,
            start_rotation: from.rotation,
            turn: (body.rotation() * from.rotation.inverse()).angle(),
        }
    }

    fn at(&self, t: Real) -> Isometry {
        Isometry::from_parts(
            (self.start + self.translation * t).into(),
            Rot::new(self.turn * t) * self.start_rotation,
        )
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
fn time_of_impact(shape: &Shape, sweep: &Sweep, other: &WorldShape, target: Real) -> Option<Real> {
    let radius = shape.max_extent();
    // The fastest any point of the shape moves, per unit of sweep time.
    let bound = sweep.translation.norm() + sweep.turn.abs() * radius;
    if bound <= 0.0 {
        return None;
    }
    let tolerance = 0.25 * target;
    let mut placed = WorldShape::new(shape, &sweep.at(0.0));
    let start = separation(other, &placed).separation;
    let goal = if start >= target + tolerance {
        target
    } else {
        start.min(target) - sink_allowance(shape, target)
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
        placed.update(shape, &sweep.at(t));
        distance = separation(other, &placed).separation;
    }
    // Still approaching after many small advances: stop here, short of the goal.
    Some(t)
}

/// How much deeper than it started a shape that already touches another may sink within one
/// step: a quarter of its smallest extent, and never less than twice the contact target.
fn sink_allowance(shape: &Shape, target: Real) -> Real {
    (0.25 * shape.min_extent()).max(2.0 * target)
}

/// Sweeps every fast body and moves the ones that would have tunnelled back to their time of
/// impact. `starts` holds each body's pose at the start of the step, in storage order.
/// Returns the number of impacts and the number of bodies swept.
pub(crate) fn solve_continuous(
    bodies: &mut [Body],
    starts: &[Pose],
    broadphase: &BroadPhase,
    dense_index: impl Fn(crate::BodyHandle) -> Option<usize>,
    target: Real,
) -> (usize, usize) {
    let mut impacts: Vec<(usize, Isometry)> = Vec::new();
    let mut sweeps = 0;
    for (index, body) in bodies.iter().enumerate() {
        if body.kind() != BodyKind::Dynamic {
            continue;
        }
        let sweep = Sweep::new(starts[index], body);
        let reach = sweep.translation.norm() + sweep.turn.abs() * body.shape().max_extent();
        if reach <= FAST_FRACTION * body.shape().min_extent() {
            continue;
        }
        sweeps += 1;
        let start_box = WorldShape::new(body.shape(), &sweep.at(0.0)).aabb();
        let swept = start_box.union(&body.aabb());
        let mut first: Option<Real> = None;
        broadphase.query(&swept, |handle| {
            let Some(other_index) = dense_index(handle) else {
                return;
            };
            let other = &bodies[other_index];
            let eligible =
                other_index != index && (other.kind() == BodyKind::Static || body.is_bullet());
            if !eligible {
                return;
            }
            if let Some(t) = time_of_impact(body.shape(), &sweep, other.world_shape(), target)
                && first.is_none_or(|f| t < f)
            {
                first = Some(t);
            }
        });
        if let Some(t) = first.filter(|&t| t < 1.0) {
            impacts.push((index, sweep.at(t)));
        }
    }
    for &(index, pose) in &impacts {
        bodies[index].move_to_time_of_impact(pose);
    }
    (impacts.len(), sweeps)
}
