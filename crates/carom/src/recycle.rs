//! Contact recycling: a pair whose bodies have barely moved relative to each other since its
//! manifold was built keeps that manifold, carried along with the bodies, instead of running
//! SAT and clipping again (Box2D 3.2 and Rapier 0.36 do the same). Each point is remembered on
//! both bodies; moved with them, the two copies part or close along the normal by exactly the
//! change of separation. Resting piles then cost next to nothing in the narrowphase.

use crate::body::Body;
use crate::manifold::{ContactEdge, Manifold, PairSide};
use crate::math::{Isometry, Real, Rot, Vec2};
use crate::settings::LINEAR_SLOP;
use crate::shape::WorldShape;

/// How far B may have moved relative to A since the manifold was built, m. Small next to the
/// slop, so a recycled separation is never off by more than a fraction of what contacts allow.
pub const RECYCLE_DISTANCE: Real = 0.25 * LINEAR_SLOP;

/// How far B may have turned relative to A since the manifold was built, rad.
pub const RECYCLE_ANGLE: Real = 0.005;

/// What a manifold was built against: the bodies' relative pose, and each point on both bodies.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ManifoldFrame {
    /// False until a manifold is built (a new contact has nothing to recycle).
    valid: bool,
    /// B's translation in A's frame.
    relative_translation: Vec2,
    /// B's rotation relative to A.
    relative_rotation: Rot,
    /// The normal in A's frame.
    normal_in_a: Vec2,
    /// Per point: where it was in A's frame and in B's frame, and its separation then.
    points: [(Vec2, Vec2, Real); 2],
}

impl ManifoldFrame {
    /// Remembers `manifold`, just built for bodies at `a` and `b`.
    pub fn of(manifold: &Manifold, a: &Isometry, b: &Isometry) -> Self {
        let relative = a.inv_mul(b);
        let mut points = [(Vec2::zeros(), Vec2::zeros(), 0.0); 2];
        for (slot, point) in points.iter_mut().zip(manifold.points()) {
            let p = point.point.into();
            *slot = (
                a.inverse_transform_point(&p).coords,
                b.inverse_transform_point(&p).coords,
                point.separation,
            );
        }
        ManifoldFrame {
            valid: true,
            relative_translation: relative.translation.vector,
            relative_rotation: relative.rotation,
            normal_in_a: a.inverse_transform_vector(&manifold.normal),
            points,
        }
    }

    /// `previous` carried along with bodies `a` and `b`, if they have moved little enough
    /// relative to each other since it was built; `None` if it must be built again.
    pub fn carry(&self, previous: &Manifold, a: &Body, b: &Body) -> Option<Manifold> {
        if !self.valid {
            return None;
        }
        let (pose_a, pose_b) = (a.transform(), b.transform());
        let relative = pose_a.inv_mul(&pose_b);
        let moved = (relative.translation.vector - self.relative_translation).norm();
        // The sine and cosine of the turn since, without an arctangent.
        let turn = self.relative_rotation.rotation_to(&relative.rotation);
        if moved > RECYCLE_DISTANCE || turn.re <= 0.0 || turn.im.abs() > RECYCLE_ANGLE.sin() {
            return None;
        }
        let mut manifold = *previous;
        let normal = pose_a.transform_vector(&self.normal_in_a);
        manifold.normal = normal;
        for (point, &(on_a, on_b, separation)) in manifold.points_mut().iter_mut().zip(&self.points)
        {
            let on_a = pose_a.transform_point(&on_a.into()).coords;
            let on_b = pose_b.transform_point(&on_b.into()).coords;
            point.point = (on_a + on_b) * 0.5;
            point.separation = separation + normal.dot(&(on_b - on_a));
        }
        for edge in [&mut manifold.reference_edge, &mut manifold.incident_edge]
            .into_iter()
            .flatten()
        {
            let shape = match edge.side {
                PairSide::A => a.world_shape(),
                PairSide::B => b.world_shape(),
            };
            move_edge(edge, shape);
        }
        Some(manifold)
    }
}

/// Puts an edge's world end points where its polygon is now.
fn move_edge(edge: &mut ContactEdge, shape: &WorldShape) {
    if let WorldShape::Polygon { vertices, .. } = shape
        && edge.index < vertices.len()
    {
        edge.start = vertices[edge.index];
        edge.end = vertices[(edge.index + 1) % vertices.len()];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::BodyDef;
    use crate::manifold;
    use crate::math::vec2;
    use crate::shape::Shape;
    use crate::world::World;

    /// A box resting on a wider box, and the manifold between them.
    fn resting_pair(gap: Real) -> (World, crate::BodyHandle, crate::BodyHandle) {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5).unwrap()))
            .unwrap();
        let block = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5).unwrap()).position(vec2(0.3, 1.0 + gap)),
            )
            .unwrap();
        (world, ground, block)
    }

    #[test]
    fn a_carried_manifold_matches_a_rebuilt_one_for_small_motions() {
        let (mut world, ground, block) = resting_pair(-0.002);
        let margin = 0.02;
        let built = {
            let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
            manifold::collide(a.world_shape(), b.world_shape(), margin)
        };
        let frame = {
            let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
            ManifoldFrame::of(&built, &a.transform(), &b.transform())
        };
        // Lift the block 1 mm and turn it a little: within the recycling limits.
        {
            let body = world.body_mut(block).unwrap();
            body.set_position(vec2(0.3005, 1.0 - 0.001)).unwrap();
            body.set_angle(0.002).unwrap();
        }
        let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
        let carried = frame.carry(&built, a, b).expect("small motion recycles");
        let rebuilt = manifold::collide(a.world_shape(), b.world_shape(), margin);
        assert_eq!(carried.points().len(), rebuilt.points().len());
        for (c, r) in carried.points().iter().zip(rebuilt.points()) {
            assert!((c.separation - r.separation).abs() < 1e-4, "{c:?} vs {r:?}");
            assert!((c.point - r.point).norm() < 1e-3, "{c:?} vs {r:?}");
        }
        assert!((carried.normal - rebuilt.normal).norm() < 1e-5);
    }

    #[test]
    fn a_larger_motion_or_a_new_contact_is_built_again() {
        let (mut world, ground, block) = resting_pair(0.0);
        let built = {
            let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
            manifold::collide(a.world_shape(), b.world_shape(), 0.02)
        };
        let frame = {
            let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
            ManifoldFrame::of(&built, &a.transform(), &b.transform())
        };
        let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
        assert!(ManifoldFrame::default().carry(&built, a, b).is_none());
        world
            .body_mut(block)
            .unwrap()
            .set_position(vec2(0.3, 1.01))
            .unwrap();
        let (a, b) = (world.body(ground).unwrap(), world.body(block).unwrap());
        assert!(frame.carry(&built, a, b).is_none(), "1 cm is too far");
    }
}
