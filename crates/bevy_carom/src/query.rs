//! [`CaromQuery`]: the world's ray casts, shape casts and overlap tests, answered in entities.

use crate::collider::Collider;
use crate::convert::{to_bevy, to_carom};
use crate::world::CaromWorld;
use bevy::ecs::entity::Entity;
use bevy::ecs::system::{Res, SystemParam};
use bevy::math::Vec2;
use carom::{Aabb, CastHit, Ray, Real, WorldShape};

/// Which colliders a query sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QueryFilter {
    /// The categories of colliders seen ([`crate::CollisionFilter::category`]); every one by
    /// default.
    pub mask: u64,
    /// What the query is, for colliders that choose what finds them: when not 0, only
    /// colliders whose mask shares a bit with it are seen. 0 by default.
    pub category: u64,
    /// A body entity whose colliders are not seen (the caster's own); none by default.
    pub exclude: Option<Entity>,
}

impl Default for QueryFilter {
    fn default() -> Self {
        QueryFilter {
            mask: u64::MAX,
            category: 0,
            exclude: None,
        }
    }
}

impl QueryFilter {
    /// Sees every collider but those of `body`.
    pub fn excluding(body: Entity) -> Self {
        QueryFilter {
            exclude: Some(body),
            ..QueryFilter::default()
        }
    }
}

/// Where a ray or a cast shape met a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QueryHit {
    /// The collider's entity.
    pub collider: Entity,
    /// Its body's entity.
    pub body: Entity,
    /// Where they met, in the world.
    pub point: Vec2,
    /// The collider's outward unit normal there.
    pub normal: Vec2,
    /// How far along the ray or cast, `0..=1`; 0 for a shape that already overlaps.
    pub fraction: f32,
}

/// A system parameter for the world's queries:
///
/// ```no_run
/// # use bevy::prelude::*;
/// # use bevy_carom::{CaromQuery, QueryFilter};
/// fn look_down(query: CaromQuery) {
///     if let Some(hit) = query.cast_ray(Vec2::new(0.0, 10.0), Vec2::new(0.0, -20.0), QueryFilter::default()) {
///         println!("ground at {} ({:?})", hit.point, hit.body);
///     }
/// }
/// ```
#[derive(SystemParam)]
pub struct CaromQuery<'w> {
    world: Res<'w, CaromWorld>,
}

impl CaromQuery<'_> {
    fn filter(&self, filter: QueryFilter) -> carom::QueryFilter {
        carom::QueryFilter {
            mask: filter.mask,
            category: filter.category,
            exclude_body: filter.exclude.and_then(|e| self.world.entity_body(e)),
        }
    }

    fn hit(&self, hit: CastHit) -> Option<QueryHit> {
        Some(QueryHit {
            collider: self.world.collider_entity(hit.collider)?,
            body: self.world.body_entity(hit.body)?,
            point: to_bevy(hit.point),
            normal: to_bevy(hit.normal),
            fraction: hit.fraction as f32,
        })
    }

    fn placed(shape: &Collider, position: Vec2, angle: f32) -> Option<WorldShape> {
        Some(WorldShape::at(
            shape.shape()?,
            to_carom(position),
            angle as Real,
        ))
    }

    /// The first collider the ray from `origin` along `translation` meets.
    pub fn cast_ray(
        &self,
        origin: Vec2,
        translation: Vec2,
        filter: QueryFilter,
    ) -> Option<QueryHit> {
        let ray = Ray::new(to_carom(origin), to_carom(translation));
        self.hit(self.world.world.cast_ray(&ray, self.filter(filter))?)
    }

    /// Every collider the ray meets, nearest first.
    pub fn cast_ray_all(
        &self,
        origin: Vec2,
        translation: Vec2,
        filter: QueryFilter,
    ) -> Vec<QueryHit> {
        let ray = Ray::new(to_carom(origin), to_carom(translation));
        let mut hits: Vec<_> = (self.world.world.cast_ray_all(&ray, self.filter(filter)))
            .into_iter()
            .filter_map(|h| self.hit(h))
            .collect();
        hits.sort_by(|a, b| a.fraction.total_cmp(&b.fraction));
        hits
    }

    /// The first collider `shape`, at `position` and `angle`, meets moving along
    /// `translation`. A chain is not a shape that can be cast: `None`.
    pub fn cast_shape(
        &self,
        shape: &Collider,
        position: Vec2,
        angle: f32,
        translation: Vec2,
        filter: QueryFilter,
    ) -> Option<QueryHit> {
        let placed = Self::placed(shape, position, angle)?;
        let hit =
            (self.world.world).cast_shape(&placed, to_carom(translation), self.filter(filter))?;
        self.hit(hit)
    }

    /// The collider entities whose bounding boxes overlap the box from `min` to `max`, each
    /// once.
    pub fn overlap_aabb(&self, min: Vec2, max: Vec2, filter: QueryFilter) -> Vec<Entity> {
        let aabb = Aabb::new(to_carom(min), to_carom(max));
        self.entities(self.world.world.query_aabb(&aabb, self.filter(filter)))
    }

    /// The collider entities `shape`, at `position` and `angle`, overlaps, each once.
    pub fn overlap_shape(
        &self,
        shape: &Collider,
        position: Vec2,
        angle: f32,
        filter: QueryFilter,
    ) -> Vec<Entity> {
        let Some(placed) = Self::placed(shape, position, angle) else {
            return Vec::new();
        };
        self.entities(self.world.world.query_shape(&placed, self.filter(filter)))
    }

    /// The body entity under `point` (a dynamic one before a kinematic, before a static).
    pub fn body_at(&self, point: Vec2) -> Option<Entity> {
        self.world
            .body_entity(self.world.world.body_at(to_carom(point))?)
    }

    fn entities(&self, colliders: Vec<carom::ColliderHandle>) -> Vec<Entity> {
        let mut entities: Vec<_> = colliders
            .into_iter()
            .filter_map(|c| self.world.collider_entity(c))
            .collect();
        // A chain's links are one entity.
        entities.sort_unstable();
        entities.dedup();
        entities
    }
}
