//! A kinematic mover's two questions to the world: which planes it touches where it stands
//! ([`World::collide_mover`]), and how far it can go along a line before it touches more
//! ([`World::cast_mover`]). With [`solve_planes`](crate::solve_planes) between them they
//! make Box2D's mover loop: collide, solve, cast, move, and again from where it stopped.
//!
//! A mover is a capsule in world coordinates, not a body: the world does not see it, and it
//! sees what a [`QueryFilter`] lets it (sensors never, since they are not in the broadphase).
//! Chains' links are one-sided for it as for every query: a link is solid only for a mover
//! whose core is wholly in front of it, so a mover jumps up through a chain from below and
//! lands on it from above.
//!
//! Two choices differ from Box2D's. A plane's point is in world coordinates (Box2D's is in
//! the obstacle's body frame). And a mover whose core has entered an obstacle's still gets its
//! plane, from the exact separation, so that it is pushed out; Box2D drops such planes.

use crate::collision::query_filter::QueryFilter;
use crate::constants::{
    LINEAR_SLOP, MAX_POSITION, MAX_TIME_OF_IMPACT_ITERATIONS, SHAPE_CAST_TOLERANCE,
};
use crate::dynamics::body::BodyHandle;
use crate::dynamics::collider::ColliderHandle;
use crate::geometry::capsule::Capsule;
use crate::geometry::query::collide::collide;
use crate::geometry::query::distance::{closest_points, separation, with_core};
use crate::geometry::segment::closest_on_segment;
use crate::geometry::shape::{Shape, WorldShape};
use crate::math::{Real, Vec2, is_finite_vec};
use crate::world::World;

use super::planes::CollisionPlane;

/// A plane a mover touches: the obstacle's side of it, and which collider it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoverPlane {
    /// The body touched.
    pub body: BodyHandle,
    /// Its collider.
    pub collider: ColliderHandle,
    /// Unit normal out of the collider toward the mover.
    pub normal: Vec2,
    /// How far the mover overlaps the collider, m (0 touching, [`crate::LINEAR_SLOP`] at
    /// rest against it).
    pub depth: Real,
    /// Where they touch, on the collider's surface, in world coordinates: the middle of the
    /// patch where a side lies on a face.
    pub point: Vec2,
    /// The ends of that patch (both `point` where they touch at a point).
    patch: [Vec2; 2],
}

impl MoverPlane {
    /// The plane as the solver takes it: rigid, clipping velocity.
    pub fn rigid(&self) -> CollisionPlane {
        CollisionPlane::rigid(self.normal, self.depth)
    }

    /// The point of the contact patch nearest `target`: where a push through a body's
    /// centre of mass lands when the patch spans it, so that pushing a box by its side does
    /// not spin it.
    pub(crate) fn patch_point_nearest(&self, target: Vec2) -> Vec2 {
        closest_on_segment(target, self.patch[0], self.patch[1]).0
    }
}

impl World {
    /// Every collider the capsule `mover` (in world coordinates) overlaps or touches and
    /// that `filter` sees, with its plane, in handle order. A mover that is not a sound
    /// capsule (see [`Capsule::validate`], about its middle) or whose middle lies beyond
    /// [`crate::MAX_POSITION`] touches nothing.
    pub fn collide_mover(&self, mover: &Capsule, filter: QueryFilter) -> Vec<MoverPlane> {
        let mut planes = Vec::new();
        self.collide_mover_into(mover, filter, &mut planes);
        planes
    }

    /// [`World::collide_mover`] into `planes` (cleared first), reusing its storage.
    pub(crate) fn collide_mover_into(
        &self,
        mover: &Capsule,
        filter: QueryFilter,
        planes: &mut Vec<MoverPlane>,
    ) {
        planes.clear();
        let Some(shape) = placed(mover) else {
            return;
        };
        self.broadphase().query(&shape.aabb(), |handle| {
            let Some(collider) = self.collider(handle) else {
                return;
            };
            let other = collider.world_shape();
            if !filter.sees(&collider.filter(), collider.body()) || is_behind(other, mover) {
                return;
            }
            let s = separation(&shape, other);
            if s.separation > 0.0 {
                return;
            }
            let patch = touching_patch(&shape, other, -s.normal);
            planes.push(MoverPlane {
                body: collider.body(),
                collider: handle,
                normal: -s.normal,
                depth: -s.separation,
                point: 0.5 * (patch[0] + patch[1]),
                patch,
            });
        });
        planes.sort_unstable_by_key(|plane| plane.collider.index());
    }

    /// How far the capsule `mover` (in world coordinates) can move along `translation`,
    /// unturned, before it touches a collider `filter` sees: a fraction in `[0, 1]`, 1 when
    /// the way is clear. It stops [`crate::LINEAR_SLOP`] into what it meets, where a mover
    /// rests. A collider it already touches lets it move along its surface and one more slop
    /// into it (so that touching is not stuck); one whose core it has entered is left to
    /// [`World::collide_mover`]'s planes to push it out of. A mover or translation that is
    /// not finite does not move: 0, as does a mover [`World::collide_mover`] passes over.
    pub fn cast_mover(&self, mover: &Capsule, translation: Vec2, filter: QueryFilter) -> Real {
        let Some(shape) = placed(mover) else {
            return 0.0;
        };
        if !is_finite_vec(translation) {
            return 0.0;
        }
        let mut scratch = shape.clone();
        let mut best: Real = 1.0;
        self.broadphase()
            .box_cast(&shape.aabb(), translation, |handle, reach| {
                let Some(collider) = self.collider(handle) else {
                    return reach;
                };
                let other = collider.world_shape();
                if !filter.sees(&collider.filter(), collider.body()) || is_behind(other, mover) {
                    return reach;
                }
                if let Some(fraction) =
                    cast_against(&shape, translation, other, best.min(reach), &mut scratch)
                {
                    best = best.min(fraction);
                }
                best.min(reach)
            });
        best
    }
}

/// The capsule as a placed shape, if it is finite and sound.
fn placed(mover: &Capsule) -> Option<WorldShape> {
    // A capsule in world coordinates: about its middle, a shape a collider could have (no
    // larger, its centres apart), and its middle where a body may be placed.
    let middle = 0.5 * (mover.center1() + mover.center2());
    let local = Capsule::new(
        mover.center1() - middle,
        mover.center2() - middle,
        mover.radius(),
    );
    let near = middle.x.abs() <= MAX_POSITION && middle.y.abs() <= MAX_POSITION;
    if !near || local.validate().is_err() {
        return None;
    }
    Some(WorldShape::at(&Shape::Capsule(*mover), Vec2::zeros(), 0.0))
}

/// True when `other` is a chain's link that the mover's core is not wholly in front of.
fn is_behind(other: &WorldShape, mover: &Capsule) -> bool {
    other.is_link_behind(mover.center1()) || other.is_link_behind(mover.center2())
}

/// The fraction of `translation` at which `mover` comes [`LINEAR_SLOP`] into `other`, if
/// below `max_fraction`; see [`World::cast_mover`]. Conservative advancement on the exact
/// separation, as [`crate::geometry::query::shape_cast`] does.
fn cast_against(
    mover: &WorldShape,
    translation: Vec2,
    other: &WorldShape,
    max_fraction: Real,
    scratch: &mut WorldShape,
) -> Option<Real> {
    let mut s = separation(mover, other);
    let mut target = -LINEAR_SLOP;
    if s.separation < target + SHAPE_CAST_TOLERANCE {
        // Already touching: it may slide along and come one slop further in, unless its
        // core is (nearly) inside, where only the planes can help.
        let core_distance = s.separation + mover.radius() + other.radius();
        if core_distance <= 2.0 * LINEAR_SLOP {
            return None;
        }
        target = s.separation - LINEAR_SLOP;
    }
    let mut fraction: Real = 0.0;
    for _ in 0..MAX_TIME_OF_IMPACT_ITERATIONS {
        let closing = s.normal.dot(&translation);
        if closing <= 0.0 {
            return None;
        }
        fraction += (s.separation - target) / closing;
        if fraction >= max_fraction {
            return None;
        }
        scratch.clone_from(mover);
        scratch.translate(translation * fraction);
        s = separation(scratch, other);
        if s.separation < target + SHAPE_CAST_TOLERANCE {
            return Some(fraction);
        }
    }
    // Still closing in after many small advances (a graze): never past contact.
    Some(fraction)
}

/// Where `mover` touches `other`, on `other`'s surface, as the ends of a patch; `normal`
/// points from `other` to the mover. The manifold's contact points when it has any (two where
/// a side rests on a face), else the nearest points of their cores.
fn touching_patch(mover: &WorldShape, other: &WorldShape, normal: Vec2) -> [Vec2; 2] {
    let manifold = collide(mover, other, LINEAR_SLOP);
    // Each point is midway between the surfaces: half its separation from `other`'s.
    let on_other = |p: &crate::geometry::query::manifold::ManifoldPoint| {
        p.point - normal * (0.5 * p.separation)
    };
    match manifold.points() {
        [one] => return [on_other(one); 2],
        [first, second, ..] => return [on_other(first), on_other(second)],
        [] => {}
    }
    let near = with_core(mover, |a, _, _| {
        with_core(other, |b, _, _| closest_points(a, b))
    });
    let point = if (near.point_a - near.point_b).norm_squared() > LINEAR_SLOP * LINEAR_SLOP {
        near.point_b + normal * other.radius()
    } else {
        // The cores meet: the mover's core point there, pushed out along the plane.
        near.point_a + normal * other.radius()
    };
    [point; 2]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body_def::BodyDef;
    use crate::math::vec2;

    fn capsule_at(x: Real, y: Real) -> Capsule {
        Capsule::new(vec2(x, y - 0.5), vec2(x, y + 0.5), 0.3)
    }

    fn world_with_box() -> World {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(0.5, 0.5)))
            .unwrap();
        world
    }

    #[test]
    fn a_cast_stops_a_slop_into_the_face() {
        let world = world_with_box();
        let fraction = world.cast_mover(&capsule_at(-5.0, 0.0), vec2(10.0, 0.0), QueryFilter::ALL);
        // The capsule's side reaches the face at x = -0.5 from -4.7: 4.2 m, plus a slop.
        let expected = (4.2 + LINEAR_SLOP) / 10.0;
        assert!(
            (fraction - expected).abs() < 0.5 * SHAPE_CAST_TOLERANCE,
            "{fraction}"
        );
        let clear = world.cast_mover(&capsule_at(-5.0, 3.0), vec2(10.0, 0.0), QueryFilter::ALL);
        assert_eq!(clear, 1.0);
    }

    #[test]
    fn a_touching_mover_slides_along_and_stops_a_slop_further_in() {
        let world = world_with_box();
        // Resting a slop into the top face.
        let resting = capsule_at(0.0, 0.5 + 0.8 - LINEAR_SLOP);
        let along = world.cast_mover(&resting, vec2(0.2, 0.0), QueryFilter::ALL);
        assert_eq!(along, 1.0);
        let into = world.cast_mover(&resting, vec2(0.0, -1.0), QueryFilter::ALL);
        assert!((into - LINEAR_SLOP).abs() < SHAPE_CAST_TOLERANCE, "{into}");
        let planes = world.collide_mover(&resting, QueryFilter::ALL);
        assert_eq!(planes.len(), 1);
        assert!((planes[0].normal - vec2(0.0, 1.0)).norm() < 1e-6);
        assert!((planes[0].depth - LINEAR_SLOP).abs() < 1e-5);
        assert!((planes[0].point - vec2(0.0, 0.5)).norm() < 1e-5);
    }

    #[test]
    fn a_mover_inside_an_obstacle_gets_the_plane_that_pushes_it_out() {
        let world = world_with_box();
        let planes = world.collide_mover(&capsule_at(0.1, 0.2), QueryFilter::ALL);
        assert_eq!(planes.len(), 1);
        let plane = planes[0];
        assert!(plane.depth > 0.3 && plane.normal.norm() > 0.99);
        let mut solver = [plane.rigid()];
        let delta = crate::character::planes::solve_planes(Vec2::zeros(), &mut solver).delta;
        let out = capsule_at(0.1 + delta.x, 0.2 + delta.y);
        let after = world.collide_mover(&out, QueryFilter::ALL);
        assert!(
            after.iter().all(|p| p.depth <= LINEAR_SLOP + 1e-5),
            "{after:?}"
        );
    }

    #[test]
    fn chains_stop_a_mover_from_above_only() {
        let mut world = World::new();
        // A one-way ledge: solid on its right, which is up for points going left.
        let ledge = crate::ChainDef::open(vec![vec2(2.0, 0.0), vec2(-2.0, 0.0)]);
        world
            .add_body(BodyDef::static_chain(&ledge).unwrap())
            .unwrap();
        let below = capsule_at(0.0, -1.0);
        assert_eq!(
            world.cast_mover(&below, vec2(0.0, 3.0), QueryFilter::ALL),
            1.0
        );
        assert!(
            world
                .collide_mover(&capsule_at(0.0, 0.2), QueryFilter::ALL)
                .is_empty()
        );
        let above = capsule_at(0.0, 2.0);
        assert!(world.cast_mover(&above, vec2(0.0, -3.0), QueryFilter::ALL) < 0.5);
    }

    #[test]
    fn a_mover_that_is_not_finite_touches_nothing_and_does_not_move() {
        let world = world_with_box();
        let bad = Capsule::new(vec2(Real::NAN, 0.0), vec2(0.0, 1.0), 0.3);
        assert!(world.collide_mover(&bad, QueryFilter::ALL).is_empty());
        assert_eq!(
            world.cast_mover(&bad, vec2(1.0, 0.0), QueryFilter::ALL),
            0.0
        );
        let good = capsule_at(-3.0, 0.0);
        assert_eq!(
            world.cast_mover(&good, vec2(Real::INFINITY, 0.0), QueryFilter::ALL),
            0.0
        );
    }
}
