//! Asking the world what is where: colliders whose boxes overlap a box, colliders a shape
//! overlaps, and colliders a ray enters, each through the broadphase and filtered as
//! collisions are. Sensors are not in the broadphase, so no query sees them (a sensor lists
//! what overlaps it itself: [`World::sensor_overlaps`]).

use crate::collision::filter::CollisionFilter;
use crate::collision::narrowphase::separation;
use crate::dynamics::collider::ColliderHandle;
use crate::geometry::aabb::Aabb;
use crate::geometry::ray::Ray;
use crate::geometry::shape::WorldShape;
use crate::math::Real;
use crate::world::{World, WorldRayHit};

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

    /// The first collider the ray enters, if any.
    pub fn cast_ray(&self, ray: &Ray) -> Option<WorldRayHit> {
        self.cast_ray_filtered(ray, CollisionFilter::DEFAULT)
    }

    /// The first collider the ray enters that `filter` would collide with, if any.
    pub fn cast_ray_filtered(&self, ray: &Ray, filter: CollisionFilter) -> Option<WorldRayHit> {
        let mut best: Option<WorldRayHit> = None;
        self.ray_hits(ray, filter, |hit, reach| {
            if hit.fraction <= reach && best.is_none_or(|b| hit.fraction < b.fraction) {
                best = Some(hit);
            }
            best.map_or(reach, |b| b.fraction)
        });
        best
    }

    /// Every collider the ray enters that `filter` would collide with, nearest first.
    pub fn cast_ray_all(&self, ray: &Ray, filter: CollisionFilter) -> Vec<WorldRayHit> {
        let mut hits = Vec::new();
        self.ray_hits(ray, filter, |hit, reach| {
            hits.push(hit);
            reach
        });
        hits.sort_by(|a, b| a.fraction.total_cmp(&b.fraction));
        hits
    }

    /// Casts the ray through the broadphase and calls `visit` with each hit on a collider
    /// `filter` allows and the reach so far; `visit` returns the new reach (a closest-hit
    /// search shortens it, an every-hit search keeps it). A ray that is not finite hits
    /// nothing.
    fn ray_hits(
        &self,
        ray: &Ray,
        filter: CollisionFilter,
        mut visit: impl FnMut(WorldRayHit, Real) -> Real,
    ) {
        if !(crate::math::is_finite_vec(ray.origin) && crate::math::is_finite_vec(ray.translation))
        {
            return;
        }
        self.broadphase
            .ray_cast(ray.origin, ray.translation, |handle, reach| {
                let Some(collider) = self.colliders.get(handle) else {
                    return reach;
                };
                let Some(body) = self.bodies.get(collider.body()) else {
                    return reach;
                };
                if !filter.collides_with(&collider.filter()) {
                    return reach;
                }
                let inverse = body.rotation().inverse();
                let local = Ray::new(body.local_point(ray.origin), inverse * ray.translation);
                let Some(hit) = collider.ray_cast_body_frame(&local) else {
                    return reach;
                };
                let hit = WorldRayHit {
                    body: body.handle(),
                    collider: handle,
                    point: ray.at(hit.fraction),
                    normal: body.rotation() * hit.normal,
                    fraction: hit.fraction,
                };
                visit(hit, reach)
            });
    }
}
