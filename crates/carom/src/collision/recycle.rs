//! Contact recycling: a pair whose bodies have barely moved relative to each other since its
//! manifold was built keeps that manifold instead of running SAT and clipping again (Box2D 3.2
//! and Rapier 0.36 do the same). As Box2D does, the kept manifold holds its normal and its
//! points' anchors (the lever arms from each centre of mass) where they were, and only the
//! separations follow the bodies: each point, carried on A and on B by the bodies' motion since,
//! parts or closes along the normal by exactly the change of separation, the same update the
//! soft step makes within a step. Frozen anchors matter: re-measured every step from bodies
//! that rock by fractions of a millimetre, the lever arms of a tall column's contacts shift
//! back and forth and feed the rocking until the column falls. Resting piles also cost next
//! to nothing in the narrowphase.

use crate::constants::{RECYCLE_COS_ANGLE, RECYCLE_SIZE_FRACTION, SPECULATIVE_DISTANCE};
use crate::dynamics::body::{Body, BodyKind};
use crate::dynamics::collider::Collider;
use crate::geometry::query::manifold::Manifold;
use crate::math::{Real, Rot, Vec2};

/// What a manifold was built against: the bodies' poses and each point's separation then.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ManifoldFrame {
    /// False until a manifold is built (a new contact has nothing to recycle).
    valid: bool,
    /// A's rotation when the manifold was built.
    rotation_a: Rot,
    /// B's rotation when the manifold was built.
    rotation_b: Rot,
    /// B's translation in A's frame.
    relative_translation: Vec2,
    /// B's rotation relative to A.
    relative_rotation: Rot,
    /// Each point's separation when built.
    base_separations: [Real; 2],
    /// Each collider's smallest extent (its shape's inradius), kept here so carrying reads
    /// nothing of the colliders.
    min_extents: [Real; 2],
}

impl ManifoldFrame {
    /// Remembers `manifold`, just built (anchors set) for bodies `a` and `b` and their colliders,
    /// in place of the contact's `previous` frame. A collider's shape never changes, so its
    /// extent is taken from `previous` when that holds it: a manifold built again then reads
    /// nothing of its colliders but their placed shapes.
    pub(crate) fn of(
        manifold: &Manifold,
        (a, collider_a): (&Body, &Collider),
        (b, collider_b): (&Body, &Collider),
        previous: &ManifoldFrame,
    ) -> Self {
        let relative = a.transform().inv_mul(&b.transform());
        let mut base_separations = [0.0; 2];
        for (slot, point) in base_separations.iter_mut().zip(manifold.points()) {
            *slot = point.separation;
        }
        ManifoldFrame {
            valid: true,
            rotation_a: a.rotation(),
            rotation_b: b.rotation(),
            relative_translation: relative.translation.vector,
            relative_rotation: relative.rotation,
            base_separations,
            min_extents: if previous.valid {
                previous.min_extents
            } else {
                [collider_a, collider_b].map(|c| c.shape().min_extent())
            },
        }
    }

    /// Carries `manifold` along with bodies `a` and `b`, in place, if they have moved less than
    /// `distance` relative to each other since it was built (less for small bodies, and the
    /// speculative distance for a pair apart); false (leaving it as it was) if it must be
    /// built again.
    #[inline]
    pub(crate) fn carry(
        &self,
        manifold: &mut Manifold,
        a: &Body,
        b: &Body,
        distance: Real,
    ) -> bool {
        if !self.valid {
            return false;
        }
        let (rotation_a, rotation_b) = (a.rotation(), b.rotation());
        let turn_a = self.rotation_a.rotation_to(&rotation_a);
        let turn_b = self.rotation_b.rotation_to(&rotation_b);
        if turn_a.re.min(turn_b.re) <= RECYCLE_COS_ANGLE {
            return false;
        }
        let relative = a.transform().inv_mul(&b.transform());
        let moved = (relative.translation.vector - self.relative_translation).norm();
        // The sine of the relative turn since, times the farthest a point of a moving body
        // sits from its centre: how far a turn can have carried a point (conservative
        // advancement's bound; a static body does not turn).
        let relative_turn = self.relative_rotation.rotation_to(&relative.rotation);
        let moving = |body: &Body| body.kind() != BodyKind::Static;
        let extent = |body: &Body| if moving(body) { body.reach() } else { 0.0 };
        let reach = moved + extent(a).max(extent(b)) * relative_turn.im.abs();
        let smallest = [a, b]
            .into_iter()
            .zip(self.min_extents)
            .filter(|(body, _)| moving(body))
            .map(|(_, extent)| extent)
            .fold(Real::INFINITY, Real::min);
        let mut tolerance = distance.min(RECYCLE_SIZE_FRACTION * smallest);
        if manifold.is_empty() {
            tolerance = tolerance.min(SPECULATIVE_DISTANCE);
        }
        if reach >= tolerance {
            return false;
        }
        let normal = manifold.normal;
        let (center_a, center_b) = (a.center_of_mass(), b.center_of_mass());
        for (point, &base) in manifold.points_mut().iter_mut().zip(&self.base_separations) {
            let on_a = center_a + turn_a * point.anchor_a;
            let on_b = center_b + turn_b * point.anchor_b;
            point.separation = base + normal.dot(&(on_b - on_a));
            point.point = (on_a + on_b) * 0.5;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::{RECYCLE_DISTANCE, RECYCLE_DISTANCE_CLASSIC};
    use crate::dynamics::body_def::BodyDef;
    use crate::geometry::query::collide;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;
    use crate::world::World;

    /// A 1 m box resting on a wider box, `gap` above it.
    fn resting_pair(gap: Real) -> (World, crate::BodyHandle, crate::BodyHandle) {
        resting_on_ground(Shape::rect(0.5, 0.5), 1.0 + gap)
    }

    /// `shape` on a body at `(0.3, height)` over a static box whose top is at 0.5 m.
    fn resting_on_ground(
        shape: Shape,
        height: Real,
    ) -> (World, crate::BodyHandle, crate::BodyHandle) {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
            .unwrap();
        let body = world
            .add_body(BodyDef::dynamic(shape).position(vec2(0.3, height)))
            .unwrap();
        (world, ground, body)
    }

    /// A body and its (only) collider.
    fn parts(world: &World, body: crate::BodyHandle) -> (&Body, &Collider) {
        let body = world.body(body).unwrap();
        (body, world.collider(body.colliders()[0]).unwrap())
    }

    /// The manifold between the two, built as the world builds it, and its frame.
    fn built(
        world: &World,
        a: crate::BodyHandle,
        b: crate::BodyHandle,
    ) -> (Manifold, ManifoldFrame) {
        let ((a, ca), (b, cb)) = (parts(world, a), parts(world, b));
        let mut built = collide::collide(ca.world_shape(), cb.world_shape(), SPECULATIVE_DISTANCE);
        built.set_anchors(a.center_of_mass(), b.center_of_mass());
        let frame = ManifoldFrame::of(&built, (a, ca), (b, cb), &ManifoldFrame::default());
        (built, frame)
    }

    #[test]
    fn a_rebuilt_frame_keeps_the_extents_it_would_compute() {
        let (world, ground, block) = resting_pair(0.0);
        let (built, first) = built(&world, ground, block);
        let ((a, ca), (b, cb)) = (parts(&world, ground), parts(&world, block));
        let again = ManifoldFrame::of(&built, (a, ca), (b, cb), &first);
        assert_eq!(again, first);
        assert_eq!(first.min_extents, [ca, cb].map(|c| c.shape().min_extent()));
        assert!(first.min_extents.iter().all(|&extent| extent > 0.0));
    }

    #[test]
    fn a_carried_manifold_matches_a_rebuilt_one_for_small_motions() {
        let (mut world, ground, block) = resting_pair(-0.002);
        let (built, frame) = built(&world, ground, block);
        // Lift the block 1 mm, shift it 0.5 mm and turn it a little: within the limits.
        {
            let mut body = world.body_mut(block).unwrap();
            body.set_position(vec2(0.3005, 1.0 - 0.001)).unwrap();
            body.set_angle(0.002).unwrap();
        }
        let (a, b) = (parts(&world, ground), parts(&world, block));
        let mut carried = built;
        let recycled = frame.carry(&mut carried, a.0, b.0, RECYCLE_DISTANCE_CLASSIC);
        assert!(recycled, "small motion recycles");
        let rebuilt = collide::collide(a.1.world_shape(), b.1.world_shape(), SPECULATIVE_DISTANCE);
        assert_eq!(carried.points().len(), rebuilt.points().len());
        for (c, r) in carried.points().iter().zip(rebuilt.points()) {
            assert!((c.separation - r.separation).abs() < 1e-4, "{c:?} vs {r:?}");
            assert!((c.point - r.point).norm() < 1e-3, "{c:?} vs {r:?}");
        }
        assert!((carried.normal - rebuilt.normal).norm() < 1e-5);
        // The lever arms and the normal are held as built; only the separations follow.
        for (c, b) in carried.points().iter().zip(built.points()) {
            assert_eq!((c.anchor_a, c.anchor_b), (b.anchor_a, b.anchor_b));
        }
        assert_eq!(carried.normal, built.normal);
    }

    #[test]
    fn a_larger_motion_or_a_new_contact_is_built_again() {
        let (mut world, ground, block) = resting_pair(0.0);
        let (built, frame) = built(&world, ground, block);
        let (a, b) = (parts(&world, ground), parts(&world, block));
        let never = ManifoldFrame::default().carry(&mut built.clone(), a.0, b.0, RECYCLE_DISTANCE);
        assert!(!never, "a new contact has nothing to carry");
        let mut moved_within = |distance, position, angle| {
            let mut body = world.body_mut(block).unwrap();
            body.set_position(position).unwrap();
            body.set_angle(angle).unwrap();
            let (a, b) = (parts(&world, ground), parts(&world, block));
            let mut carried = built;
            let recycled = frame.carry(&mut carried, a.0, b.0, distance);
            if !recycled {
                assert_eq!(carried, built, "left as it was");
            }
            recycled
        };
        let mut moved = |position, angle| moved_within(RECYCLE_DISTANCE_CLASSIC, position, angle);
        assert!(moved(vec2(0.3, 1.008), 0.0), "8 mm is within 2 slop");
        assert!(!moved(vec2(0.3, 1.012), 0.0), "12 mm is too far");
        // A turn of 0.01 rad carries the block's corners 7 mm: within.
        assert!(moved(vec2(0.3, 1.0), 0.01));
        // 0.02 rad carries them 14 mm: too far, though the centre stayed.
        assert!(!moved(vec2(0.3, 1.0), 0.02));
        // Soft step's distance, Box2D's 10 slop (5 cm), under the block's size cap (a quarter
        // of its 0.5 m inradius): 4 cm is within, 6 cm too far.
        let mut moved = |position, angle| moved_within(RECYCLE_DISTANCE, position, angle);
        assert!(moved(vec2(0.3, 1.04), 0.0));
        assert!(!moved(vec2(0.3, 1.06), 0.0));
    }

    #[test]
    fn a_pair_apart_recycles_only_within_the_speculative_distance() {
        let (mut world, ground, block) = resting_pair(0.05);
        let (built, frame) = built(&world, ground, block);
        assert!(built.is_empty());
        let mut closer = |by: Real| {
            world
                .body_mut(block)
                .unwrap()
                .set_position(vec2(0.3, 1.05 - by))
                .unwrap();
            let (a, b) = (parts(&world, ground), parts(&world, block));
            frame.carry(&mut built.clone(), a.0, b.0, RECYCLE_DISTANCE)
        };
        // 8 mm closer, still 4 cm apart: nothing can have come within the margin.
        assert!(closer(0.008));
        // 2.5 cm closer, which is more than the 2 cm margin: built again.
        assert!(!closer(0.025));
    }

    #[test]
    fn a_small_body_may_move_a_quarter_of_its_inradius() {
        // A plank 4 cm thick: its inradius is 2 cm, so it may move 5 mm, not soft step's 5 cm.
        let (mut world, ground, plank) = resting_on_ground(Shape::rect(0.5, 0.02), 0.52);
        let (built, frame) = built(&world, ground, plank);
        assert!(!built.is_empty());
        let mut slid = |by: Real| {
            world
                .body_mut(plank)
                .unwrap()
                .set_position(vec2(0.3 + by, 0.52))
                .unwrap();
            let (a, b) = (parts(&world, ground), parts(&world, plank));
            frame.carry(&mut built.clone(), a.0, b.0, RECYCLE_DISTANCE)
        };
        assert!(slid(0.004), "4 mm is within a quarter of 2 cm");
        assert!(!slid(0.006), "6 mm is too far");
    }

    #[test]
    fn a_circle_pair_is_carried_as_a_polygon_pair_is() {
        let (mut world, ground, ball) = resting_on_ground(Shape::circle(0.5), 1.0 - 0.002);
        let (built, frame) = built(&world, ground, ball);
        // Lift the ball 1 mm, shift it 0.5 mm and turn it a little: within the limits.
        {
            let mut body = world.body_mut(ball).unwrap();
            body.set_position(vec2(0.3005, 1.0 - 0.001)).unwrap();
            body.set_angle(0.002).unwrap();
        }
        let (a, b) = (parts(&world, ground), parts(&world, ball));
        let mut carried = built;
        assert!(frame.carry(&mut carried, a.0, b.0, RECYCLE_DISTANCE));
        let rebuilt = collide::collide(a.1.world_shape(), b.1.world_shape(), SPECULATIVE_DISTANCE);
        assert_eq!(carried.points().len(), rebuilt.points().len());
        for (c, r) in carried.points().iter().zip(rebuilt.points()) {
            assert!((c.separation - r.separation).abs() < 1e-4, "{c:?} vs {r:?}");
            assert!((c.point - r.point).norm() < 1e-3, "{c:?} vs {r:?}");
        }
        assert_eq!(carried.normal, built.normal);
    }
}
