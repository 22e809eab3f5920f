//! Explosions: an impulse pushing dynamic bodies away from a point, as Box2D's
//! `b2World_Explode`.
//!
//! Each collider near enough is pushed along the line from the centre to its nearest point
//! (from the centre to its centroid when the centre is inside it), at that point, by the
//! impulse per metre times the width it shows the blast (its extent across that line): a
//! wide crate takes more than a pebble at the same distance. Full strength within the radius,
//! fading linearly to nothing over the falloff beyond it. A body of several colliders takes
//! each one's push; sensors take none (Box2D pushes a sensor's shape too).

use crate::dynamics::body::{BodyHandle, BodyKind, check_position};
use crate::error::{CaromError, check_finite, check_finite_not_negative};
use crate::geometry::aabb::Aabb;
use crate::geometry::mass::polygon_centroid;
use crate::geometry::query::distance::{closest_points, with_core};
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2, perp_cw, vec2};
use crate::world::World;

/// An explosion for [`World::explode`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplosionDef {
    /// The centre, in world coordinates, within [`crate::MAX_POSITION`] of the origin.
    pub center: Vec2,
    /// Within this distance of the centre a collider takes the full impulse, m.
    pub radius: Real,
    /// Beyond the radius the impulse fades linearly to nothing over this distance, m.
    pub falloff: Real,
    /// Impulse per metre of a collider's width facing the centre, N·s/m; negative pulls in.
    pub impulse_per_length: Real,
    /// The collision categories it pushes (a collider whose category shares a bit with it).
    pub mask: u64,
}

impl ExplosionDef {
    /// An explosion at `center` pushing every category at full strength within `radius`,
    /// with no falloff.
    pub fn new(center: Vec2, radius: Real, impulse_per_length: Real) -> Self {
        ExplosionDef {
            center,
            radius,
            falloff: 0.0,
            impulse_per_length,
            mask: u64::MAX,
        }
    }

    /// Fades the impulse linearly to nothing over `falloff` metres beyond the radius.
    pub fn falloff(mut self, falloff: Real) -> Self {
        self.falloff = falloff;
        self
    }

    /// Pushes only colliders whose category shares a bit with `mask`.
    pub fn mask(mut self, mask: u64) -> Self {
        self.mask = mask;
        self
    }

    fn validate(&self) -> Result<(), CaromError> {
        check_position("explosion centre", self.center)?;
        check_finite("explosion impulse per length", self.impulse_per_length)?;
        check_finite_not_negative("explosion radius", self.radius)?;
        check_finite_not_negative("explosion falloff", self.falloff)?;
        Ok(())
    }
}

impl World {
    /// Pushes the dynamic bodies near `explosion`'s centre away from it (see the module
    /// documentation), waking the ones asleep. Returns how many colliders it pushed.
    ///
    /// # Errors
    /// A value of `explosion` out of its range, or a push that would carry a body's speed
    /// past what a float holds; the bodies then keep the speeds they had.
    pub fn explode(&mut self, explosion: &ExplosionDef) -> Result<usize, CaromError> {
        explosion.validate()?;
        let reach = explosion.radius + explosion.falloff;
        let extent = vec2(reach, reach);
        let around = Aabb::new(explosion.center - extent, explosion.center + extent);
        // The broadphase itself, not a filtered query: what a collider's own mask lets it
        // collide with does not shield it from a blast.
        let mut near = Vec::new();
        self.state
            .broadphase
            .query(&around, |handle| near.push(handle));
        near.sort_unstable_by_key(|h| h.index());
        let mut pushes: Vec<(BodyHandle, Vec2, Vec2)> = Vec::new();
        for handle in near {
            let Some(collider) = self.state.colliders.get(handle) else {
                continue;
            };
            let dynamic = self
                .state
                .bodies
                .get(collider.body())
                .is_some_and(|b| b.kind() == BodyKind::Dynamic);
            if !dynamic || collider.filter().category & explosion.mask == 0 {
                continue;
            }
            let shape = collider.world_shape();
            let (distance, point) = nearest(shape, explosion.center);
            if distance > reach {
                continue;
            }
            let away = point - explosion.center;
            let direction = if away.norm_squared() > 100.0 * Real::EPSILON * Real::EPSILON {
                away.normalize()
            } else {
                vec2(1.0, 0.0)
            };
            let scale = if distance > explosion.radius && explosion.falloff > 0.0 {
                ((reach - distance) / explosion.falloff).clamp(0.0, 1.0)
            } else {
                1.0
            };
            let width = projected_width(shape, perp_cw(direction));
            let impulse = direction * (explosion.impulse_per_length * width * scale);
            pushes.push((collider.body(), impulse, point));
        }
        // A push refused part way (one that would carry a light body's speed past f32) puts
        // back the speeds the earlier ones gave, so a refused explosion pushes nothing.
        let before: Vec<(BodyHandle, Vec2, Real)> = pushes
            .iter()
            .filter_map(|&(handle, ..)| {
                let body = self.state.bodies.get(handle)?;
                Some((handle, body.linear_velocity(), body.angular_velocity()))
            })
            .collect();
        for &(body, impulse, point) in &pushes {
            let pushed = match self.body_mut(body) {
                Some(mut body) => body.apply_impulse(impulse, point),
                None => Ok(()),
            };
            if let Err(refused) = pushed {
                for &(handle, linear, angular) in &before {
                    if let Some(mut body) = self.body_mut(handle) {
                        body.set_linear_velocity(linear)?;
                        body.set_angular_velocity(angular)?;
                    }
                }
                return Err(refused);
            }
        }
        Ok(pushes.len())
    }
}

/// The distance from `point` to `shape` (0 inside it) and where the push lands: the nearest
/// point of its surface, or its centroid when `point` is inside.
fn nearest(shape: &WorldShape, point: Vec2) -> (Real, Vec2) {
    let (core_distance, core_point, inside_core) = with_core(shape, |vertices, normals, _| {
        let near = closest_points(vertices, &[point]);
        let inside = vertices.len() >= 3
            && vertices
                .iter()
                .zip(normals)
                .all(|(v, n)| n.dot(&(point - v)) <= 0.0);
        (near.distance, near.point_a, inside)
    });
    let radius = shape.radius();
    if inside_core || core_distance <= radius {
        return (0.0, centroid(shape));
    }
    let out = (point - core_point) / core_distance;
    (core_distance - radius, core_point + out * radius)
}

/// The centre of a shape's area (of a segment's length).
fn centroid(shape: &WorldShape) -> Vec2 {
    with_core(shape, |vertices, _, _| {
        polygon_centroid(vertices)
            .unwrap_or_else(|| vertices.iter().sum::<Vec2>() / vertices.len() as Real)
    })
}

/// How wide `shape` is along `line` (a unit vector): what it shows a blast from across it.
fn projected_width(shape: &WorldShape, line: Vec2) -> Real {
    with_core(shape, |vertices, _, radius| {
        let (lo, hi) = vertices
            .iter()
            .map(|v| v.dot(&line))
            .fold((Real::INFINITY, Real::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
        hi - lo + 2.0 * radius
    })
}
