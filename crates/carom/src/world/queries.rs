//! Asking the world what is where: bodies under a point, colliders whose boxes overlap a box,
//! colliders a shape overlaps, colliders a ray enters and colliders a shape moved along a line
//! meets, each through the broadphase and each but the point queries taking a
//! [`QueryFilter`]. Sensors are not in the broadphase,
//! so no query sees them (a sensor lists what overlaps it itself:
//! [`World::sensor_overlaps`]). Chains are one-sided here too: a ray or a cast shape starting
//! behind a chain's link passes through it.

use crate::collision::query_filter::QueryFilter;
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::dynamics::collider::ColliderHandle;
use crate::geometry::aabb::Aabb;
use crate::geometry::query::distance::separation;
use crate::geometry::query::shape_cast::cast_shape;
use crate::geometry::ray::Ray;
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2, is_finite_vec};
use crate::world::{CastHit, World};

impl World {
    /// Every collider whose box overlaps `aabb` (touching counts) and that `filter` sees
    /// ([`QueryFilter::ALL`] sees every collider), in handle order. Boxes are as of the last step or edit.
    pub fn query_aabb(&self, aabb: &Aabb, filter: QueryFilter) -> Vec<ColliderHandle> {
        let mut found = Vec::new();
        self.state.broadphase.query(aabb, |handle| {
            if let Some(collider) = self.state.colliders.get(handle)
                && filter.sees(&collider.filter(), collider.body())
                && collider.aabb().overlaps(aabb)
            {
                found.push(handle);
            }
        });
        found.sort_unstable_by_key(|h| h.index());
        found
    }

    /// Every collider `shape` (placed in the world) overlaps or touches, exactly, that
    /// `filter` sees, in handle order. A shape that is not finite meets nothing.
    #[allow(
        clippy::expect_used,
        reason = "the broadphase answers only with live colliders"
    )]
    pub fn query_shape(&self, shape: &WorldShape, filter: QueryFilter) -> Vec<ColliderHandle> {
        if !shape.is_finite() {
            return Vec::new();
        }
        let mut found = self.query_aabb(&shape.aabb(), filter);
        found.retain(|&handle| {
            let collider = self.state.colliders.get(handle).expect("just found");
            separation(shape, collider.world_shape()).separation <= 0.0
        });
        found
    }

    /// The first collider the ray enters that `filter` sees, if any.
    pub fn cast_ray(&self, ray: &Ray, filter: QueryFilter) -> Option<CastHit> {
        let mut best: Option<CastHit> = None;
        self.ray_hits(ray, filter, |hit, reach| {
            if hit.fraction <= reach && best.is_none_or(|b| hit.fraction < b.fraction) {
                best = Some(hit);
            }
            best.map_or(reach, |b| b.fraction)
        });
        best
    }

    /// Every collider the ray enters that `filter` sees, nearest first.
    pub fn cast_ray_all(&self, ray: &Ray, filter: QueryFilter) -> Vec<CastHit> {
        let mut hits = Vec::new();
        self.ray_hits(ray, filter, |hit, reach| {
            hits.push(hit);
            reach
        });
        hits.sort_by(|a, b| a.fraction.total_cmp(&b.fraction));
        hits
    }

    /// Where `shape`, moved along `translation` without turning, first meets a collider that
    /// `filter` sees, if it does: the fraction of the translation it can move
    /// before touching (stopping within [`crate::SHAPE_CAST_TOLERANCE`] short of it), the
    /// point it touches and the collider's normal there. A shape that already overlaps a
    /// collider hits it at fraction 0. A shape or translation that is not finite meets
    /// nothing.
    pub fn cast_shape(
        &self,
        shape: &WorldShape,
        translation: Vec2,
        filter: QueryFilter,
    ) -> Option<CastHit> {
        let mut best: Option<CastHit> = None;
        self.shape_hits(shape, translation, filter, |hit, reach| {
            if best.is_none_or(|b| hit.fraction < b.fraction) {
                best = Some(hit);
            }
            best.map_or(reach, |b| b.fraction)
        });
        best
    }

    /// Every collider that `shape`, moved along `translation`, meets and that `filter` would
    /// collide with (each once, where it first meets it), nearest first; see
    /// [`World::cast_shape`].
    pub fn cast_shape_all(
        &self,
        shape: &WorldShape,
        translation: Vec2,
        filter: QueryFilter,
    ) -> Vec<CastHit> {
        let mut hits = Vec::new();
        self.shape_hits(shape, translation, filter, |hit, reach| {
            hits.push(hit);
            reach
        });
        hits.sort_by(|a, b| a.fraction.total_cmp(&b.fraction));
        hits
    }

    /// Sweeps `shape`'s box through the broadphase and calls `visit` with each hit on a
    /// collider `filter` allows and the reach so far, as [`World::ray_hits`] does.
    fn shape_hits(
        &self,
        shape: &WorldShape,
        translation: Vec2,
        filter: QueryFilter,
        mut visit: impl FnMut(CastHit, Real) -> Real,
    ) {
        let aabb = shape.aabb();
        let finite = [aabb.min, aabb.max, translation]
            .into_iter()
            .all(is_finite_vec);
        if !(shape.is_finite() && finite) {
            return;
        }
        let start = aabb.center();
        let mut scratch = shape.clone();
        self.state
            .broadphase
            .box_cast(&aabb, translation, |handle, reach| {
                let Some(collider) = self.state.colliders.get(handle) else {
                    return reach;
                };
                let other = collider.world_shape();
                if !filter.sees(&collider.filter(), collider.body()) || other.is_link_behind(start)
                {
                    return reach;
                }
                let Some(hit) = cast_shape(shape, translation, other, reach, &mut scratch) else {
                    return reach;
                };
                let hit = CastHit {
                    body: collider.body(),
                    collider: handle,
                    point: hit.point,
                    normal: hit.normal,
                    fraction: hit.fraction,
                };
                visit(hit, reach)
            });
    }

    /// Casts the ray through the broadphase and calls `visit` with each hit on a collider
    /// `filter` allows and the reach so far; `visit` returns the new reach (a closest-hit
    /// search shortens it, an every-hit search keeps it). A ray that is not finite hits
    /// nothing.
    fn ray_hits(
        &self,
        ray: &Ray,
        filter: QueryFilter,
        mut visit: impl FnMut(CastHit, Real) -> Real,
    ) {
        if !(is_finite_vec(ray.origin) && is_finite_vec(ray.translation)) {
            return;
        }
        self.state
            .broadphase
            .ray_cast(ray.origin, ray.translation, |handle, reach| {
                let Some(collider) = self.state.colliders.get(handle) else {
                    return reach;
                };
                let Some(body) = self.state.bodies.get(collider.body()) else {
                    return reach;
                };
                if !filter.sees(&collider.filter(), collider.body()) {
                    return reach;
                }
                let inverse = body.rotation().inverse();
                let local = Ray::new(body.local_point(ray.origin), inverse * ray.translation);
                let Some(hit) = collider.ray_cast_body_frame(&local) else {
                    return reach;
                };
                let hit = CastHit {
                    body: body.handle(),
                    collider: handle,
                    point: ray.at(hit.fraction),
                    normal: body.rotation() * hit.normal,
                    fraction: hit.fraction,
                };
                visit(hit, reach)
            });
    }

    /// The body under a world point, for grabbing with the mouse.
    ///
    /// Dynamic bodies win over kinematic ones and those over static ones; among equals the one
    /// latest in handle order (drawn on top) wins.
    pub fn body_at(&self, point: Vec2) -> Option<BodyHandle> {
        let rank = |kind: BodyKind| match kind {
            BodyKind::Static => 0,
            BodyKind::Kinematic => 1,
            BodyKind::Dynamic => 2,
        };
        self.bodies_at(point)
            .into_iter()
            .filter_map(|h| Some((self.state.bodies.get(h)?.kind(), h)))
            .max_by_key(|&(kind, h)| (rank(kind), h.index()))
            .map(|(_, h)| h)
    }

    /// Every body with a collider containing the point, in handle order.
    pub fn bodies_at(&self, point: Vec2) -> Vec<BodyHandle> {
        let probe = Aabb::new(point, point);
        let mut found = Vec::new();
        self.state.broadphase.query(&probe, |handle| {
            let Some(collider) = self.state.colliders.get(handle) else {
                return;
            };
            let Some(body) = self.state.bodies.get(collider.body()) else {
                return;
            };
            if collider.contains(point, body.local_point(point)) {
                found.push(collider.body());
            }
        });
        found.sort_unstable_by_key(|h| h.index());
        found.dedup();
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body_def::BodyDef;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    #[test]
    fn body_at_prefers_dynamic_and_topmost() {
        let mut world = World::new();
        let floor = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 5.0)))
            .unwrap();
        let low = world
            .add_body(BodyDef::dynamic(Shape::circle(1.0)))
            .unwrap();
        let high = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)))
            .unwrap();
        assert_eq!(world.body_at(vec2(0.0, 0.0)), Some(high));
        assert_eq!(world.body_at(vec2(0.8, 0.0)), Some(low));
        assert_eq!(world.body_at(vec2(3.0, 3.0)), Some(floor));
        assert_eq!(world.body_at(vec2(30.0, 3.0)), None);
        assert_eq!(world.bodies_at(vec2(0.0, 0.0)), vec![floor, low, high]);
    }

    #[test]
    fn queries_see_bodies_moved_since_the_last_step() {
        let mut world = World::new();
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)))
            .unwrap();
        world
            .body_mut(ball)
            .unwrap()
            .set_position(vec2(20.0, 0.0))
            .unwrap();
        assert_eq!(world.body_at(vec2(20.0, 0.2)), Some(ball));
        assert_eq!(world.body_at(vec2(0.0, 0.0)), None);
        let hit = world
            .cast_ray(
                &Ray::new(vec2(10.0, 0.0), vec2(20.0, 0.0)),
                QueryFilter::ALL,
            )
            .unwrap();
        assert_eq!(hit.body, ball);
        world.step(1.0 / 60.0).unwrap();
        assert!(world.body_at(vec2(20.0, 0.0)).is_some());
        assert!(
            world
                .broadphase()
                .fat_aabb(world.body(ball).unwrap().colliders()[0])
                .unwrap()
                .contains_point(vec2(20.0, 0.0))
        );
    }

    #[test]
    fn cast_ray_finds_the_closest_body() {
        let mut world = World::new();
        let near = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(2.0, 0.0)))
            .unwrap();
        let far = world
            .add_body(
                BodyDef::dynamic(Shape::circle(0.5))
                    .position(vec2(5.0, 0.0))
                    .angle(1.0),
            )
            .unwrap();
        let hit = world
            .cast_ray(&Ray::new(vec2(0.0, 0.0), vec2(10.0, 0.0)), QueryFilter::ALL)
            .unwrap();
        assert_eq!(hit.body, near);
        assert!((hit.point - vec2(1.5, 0.0)).norm() < 1e-6);
        assert!((hit.normal - vec2(-1.0, 0.0)).norm() < 1e-6);
        assert!((hit.fraction - 0.15).abs() < 1e-6);
        world.remove_body(near).unwrap();
        let hit = world
            .cast_ray(&Ray::new(vec2(0.0, 0.0), vec2(10.0, 0.0)), QueryFilter::ALL)
            .unwrap();
        assert_eq!(hit.body, far);
        assert!((hit.point - vec2(4.5, 0.0)).norm() < 1e-5);
        assert!(
            world
                .cast_ray(&Ray::new(vec2(0.0, 3.0), vec2(10.0, 0.0)), QueryFilter::ALL)
                .is_none()
        );
        assert!(
            world
                .cast_ray(
                    &Ray::new(vec2(Real::NAN, 0.0), vec2(1.0, 0.0)),
                    QueryFilter::ALL
                )
                .is_none()
        );
    }
}
