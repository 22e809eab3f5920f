//! The plane solver at the heart of a kinematic mover: given where a mover wants to go and
//! the planes of what it touches, the nearest displacement that leaves no plane overlapped,
//! and the velocity with its part into those planes removed.
//!
//! Box2D's `b2SolvePlanes` and `b2ClipVector`: projected Gauss-Seidel on the displacement,
//! each plane's push accumulated and kept between 0 (a plane pushes, never pulls) and its
//! limit (a soft obstacle, another character say, pushes only so far in one solve).

use crate::constants::{LINEAR_SLOP, MAX_PLANE_ITERATIONS, MAX_POSITION, PLANE_UNIT_TOLERANCE};
use crate::math::{Real, Vec2};

/// A plane a mover must not cross, in the mover's displacement: a displacement `delta`
/// satisfies it when `normal · delta >= offset`. Collected by [`crate::World::collide_mover`]
/// (as [`MoverPlane`](crate::MoverPlane)s) and solved by [`solve_planes`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionPlane {
    /// Unit normal, pointing out of the obstacle toward the mover.
    pub normal: Vec2,
    /// How far the mover overlaps the obstacle where it was collided, in metres: the
    /// displacement must carry it at least this far along `normal`. Negative when apart.
    pub offset: Real,
    /// The most this plane may push in one solve, in metres, not negative; [`Real::INFINITY`]
    /// for a rigid obstacle.
    pub push_limit: Real,
    /// Whether [`clip_velocity`] removes velocity into this plane. Off for soft obstacles, whose
    /// push should not stop the mover.
    pub clip_velocity: bool,
    /// How far this plane pushed in the last [`solve_planes`]: its output.
    pub push: Real,
}

impl CollisionPlane {
    /// A rigid plane that clips velocity.
    pub fn rigid(normal: Vec2, offset: Real) -> Self {
        CollisionPlane {
            normal,
            offset,
            push_limit: Real::INFINITY,
            clip_velocity: true,
            push: 0.0,
        }
    }

    /// A soft plane: pushes at most `push_limit` metres a solve and leaves velocity alone.
    pub fn soft(normal: Vec2, offset: Real, push_limit: Real) -> Self {
        CollisionPlane {
            push_limit,
            clip_velocity: false,
            ..CollisionPlane::rigid(normal, offset)
        }
    }
}

/// What [`solve_planes`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneSolution {
    /// The displacement: the target moved out of every plane (to within
    /// [`crate::LINEAR_SLOP`] of overlap, where a mover rests).
    pub delta: Vec2,
    /// Sweeps over the planes it took.
    pub iterations: usize,
    /// False when the pushes still changed by more than [`crate::LINEAR_SLOP`] after the last
    /// sweep (a narrow wedge): `delta` is then the best found, and a cast along it stays safe.
    pub converged: bool,
}

/// The displacement nearest `target` that satisfies every plane, each plane's `push` set to
/// how far it pushed. A mover rests [`crate::LINEAR_SLOP`] into what it touches, as contacts
/// do, so that touching surfaces stay in its planes from one move to the next. A plane that
/// cannot push (a normal that is not a unit, an offset that is not finite or lies beyond
/// [`crate::MAX_POSITION`], a push limit below zero or NaN) is passed over, its `push` left
/// at 0.
pub fn solve_planes(target: Vec2, planes: &mut [CollisionPlane]) -> PlaneSolution {
    solve_planes_along(target, planes, |plane| plane.normal)
}

/// [`solve_planes`] with each plane pushing along `along(plane)` (a unit vector on the
/// plane's side) instead of its normal: a character's ground pushes it straight up, so that
/// standing on a slope does not slide it down, and a slope too steep to climb pushes it
/// straight back, so that walking into it does not lift it. A plane's push is then measured
/// along that direction.
pub(crate) fn solve_planes_along(
    target: Vec2,
    planes: &mut [CollisionPlane],
    along: impl Fn(&CollisionPlane) -> Vec2,
) -> PlaneSolution {
    for plane in planes.iter_mut() {
        plane.push = 0.0;
    }
    let mut delta = target;
    for sweep in 1..=MAX_PLANE_ITERATIONS {
        let mut moved = 0.0;
        for plane in planes.iter_mut() {
            let direction = along(plane);
            // How fast pushing along `direction` leaves the plane; the callers keep it
            // positive (at least the cosine of the steepest slope a character climbs).
            let rate = plane.normal.dot(&direction);
            let separation = plane.normal.dot(&delta) - plane.offset + LINEAR_SLOP;
            // A plane that cannot push (no direction, a normal that is not a unit, an offset
            // beyond where anything can be, numbers that are not finite, a limit below zero
            // or not a number) pushes nothing, rather than panic or spread NaN.
            let unit = (plane.normal.norm_squared() - 1.0).abs() <= PLANE_UNIT_TOLERANCE;
            if !(rate > 0.0
                && unit
                && plane.offset.abs() <= MAX_POSITION
                && separation.is_finite()
                && plane.push_limit >= 0.0)
            {
                continue;
            }
            let accumulated = plane.push;
            plane.push = (accumulated - separation / rate).clamp(0.0, plane.push_limit);
            let push = plane.push - accumulated;
            delta += direction * push;
            moved += push.abs();
        }
        if moved < LINEAR_SLOP {
            return PlaneSolution {
                delta,
                iterations: sweep,
                converged: true,
            };
        }
    }
    PlaneSolution {
        delta,
        iterations: MAX_PLANE_ITERATIONS,
        converged: false,
    }
}

/// `velocity` without its part into the planes that pushed in the last [`solve_planes`] and
/// clip velocity: a mover stopped by a wall stops gaining speed into it, and one on a slope
/// keeps only the speed along it.
pub fn clip_velocity(velocity: Vec2, planes: &[CollisionPlane]) -> Vec2 {
    planes
        .iter()
        .filter(|plane| plane.push > 0.0 && plane.clip_velocity)
        .fold(velocity, |v, plane| {
            v - plane.normal * v.dot(&plane.normal).min(0.0)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn a_floor_and_a_wall_stop_a_move_into_their_corner() {
        let mut planes = [
            CollisionPlane::rigid(vec2(0.0, 1.0), 0.1),
            CollisionPlane::rigid(vec2(-1.0, 0.0), 0.0),
        ];
        let solution = solve_planes(vec2(1.0, -1.0), &mut planes);
        assert!(solution.converged);
        // Out of the floor's 0.1 of overlap and up to the wall, each to a slop's overlap.
        assert!((solution.delta - vec2(LINEAR_SLOP, 0.1 - LINEAR_SLOP)).norm() < 1e-6);
        assert!((planes[0].push - (1.1 - LINEAR_SLOP)).abs() < 1e-6);
        assert!((planes[1].push - (1.0 - LINEAR_SLOP)).abs() < 1e-6);
        assert_eq!(clip_velocity(vec2(5.0, -3.0), &planes), vec2(0.0, 0.0));
        assert_eq!(clip_velocity(vec2(-5.0, 3.0), &planes), vec2(-5.0, 3.0));
    }

    #[test]
    fn planes_push_but_never_pull() {
        let mut planes = [CollisionPlane::rigid(vec2(0.0, 1.0), 0.0)];
        let solution = solve_planes(vec2(0.3, 2.0), &mut planes);
        assert_eq!(solution.delta, vec2(0.3, 2.0));
        assert_eq!(planes[0].push, 0.0);
        assert_eq!(clip_velocity(vec2(0.0, -4.0), &planes), vec2(0.0, -4.0));
    }

    #[test]
    fn a_soft_plane_pushes_only_to_its_limit_and_keeps_velocity() {
        let mut planes = [CollisionPlane::soft(vec2(-1.0, 0.0), 0.5, 0.025)];
        let solution = solve_planes(Vec2::zeros(), &mut planes);
        assert!((solution.delta - vec2(-0.025, 0.0)).norm() < 1e-7);
        assert_eq!(planes[0].push, 0.025);
        assert_eq!(clip_velocity(vec2(3.0, 0.0), &planes), vec2(3.0, 0.0));
    }

    #[test]
    fn a_slope_turns_a_fall_into_a_slide_along_it() {
        let normal = vec2(-1.0, 1.0).normalize();
        let mut planes = [CollisionPlane::rigid(normal, 0.0)];
        let solution = solve_planes(vec2(0.0, -1.0), &mut planes);
        // Along the slope, not into it.
        assert!((normal.dot(&solution.delta) + LINEAR_SLOP).abs() < 1e-6);
        let slid = clip_velocity(vec2(0.0, -1.0), &planes);
        assert!(slid.dot(&normal).abs() < 1e-6);
        assert!((slid - vec2(-0.5, -0.5)).norm() < 1e-6);
    }
}
