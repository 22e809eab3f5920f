//! Asking the world what is where: colliders whose boxes overlap a box, and colliders a shape
//! overlaps, each through the broadphase and filtered as collisions are.

use crate::collision::filter::CollisionFilter;
use crate::collision::narrowphase::separation;
use crate::dynamics::collider::ColliderHandle;
use crate::geometry::aabb::Aabb;
use crate::geometry::shape::WorldShape;
use crate::world::World;

impl World {
    /// Every collider whose box overlaps `aabb` (touching counts) and that `filter` would
    /// collide with (as two colliders' filters decide; [`CollisionFilter::DEFAULT`] takes
    /// every collider), in handle order. Boxes are as of the last step or edit.
    pub fn query_aabb(&self, aabb: &Aabb, filter: CollisionFilter) -> Vec<ColliderHandle> {
        let mut found = Vec::new();
        self.broadphase.query(aabb, |handle| {
            if let Some(collider) = self.colliders.get(handle)
                && filter.collides_with(&collider.filter())
                && collider.aabb().overlaps(aabb)
            {
                found.push(handle);
            }
        });
        found.sort_unstable_by_key(|h| h.index());
        found
    }

    /// Every collider `shape` (placed in the world) overlaps or touches, exactly, that
    /// `filter` would collide with, in handle order.
    pub fn query_shape(&self, shape: &WorldShape, filter: CollisionFilter) -> Vec<ColliderHandle> {
        let mut found = self.query_aabb(&shape.aabb(), filter);
        found.retain(|&handle| {
            let collider = self.colliders.get(handle).expect("just found");
            separation(shape, collider.world_shape()).separation <= 0.0
        });
        found
    }
}
