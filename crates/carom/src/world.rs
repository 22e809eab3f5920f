//! The world: bodies, global settings, the step, and queries.

use crate::body::{Body, BodyDef, BodyHandle, BodyKind};
use crate::body_set::BodySet;
use crate::drag::DragModel;
use crate::error::{CaromError, check_finite_vec};
use crate::integrate;
use crate::math::{Real, Vec2};
use crate::ray::Ray;

/// World-wide settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// Gravitational acceleration, m/s². Default `(0, -10)`, as in Box2D.
    pub gravity: Vec2,
    /// The law that applies each body's drag coefficients. Default exponential damping.
    pub drag: DragModel,
}

impl Default for WorldSettings {
    fn default() -> Self {
        WorldSettings {
            gravity: Vec2::new(0.0, -10.0),
            drag: DragModel::default(),
        }
    }
}

/// The closest body a ray enters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldRayHit {
    /// The body hit.
    pub body: BodyHandle,
    /// The entry point, in world coordinates.
    pub point: Vec2,
    /// The body's outward unit normal there.
    pub normal: Vec2,
    /// How far along the ray, in `[0, 1]`.
    pub fraction: Real,
}

/// A physics world: create bodies in it, step it, query it.
#[derive(Debug, Clone, Default)]
pub struct World {
    bodies: BodySet,
    settings: WorldSettings,
    time: f64,
    step_count: u64,
}

impl World {
    /// An empty world with default settings (gravity `(0, -10)`).
    pub fn new() -> Self {
        World::default()
    }

    /// An empty world with the given settings.
    pub fn with_settings(settings: WorldSettings) -> Result<Self, CaromError> {
        check_finite_vec("gravity", settings.gravity)?;
        Ok(World {
            settings,
            ..World::default()
        })
    }

    /// The settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Gravity, m/s².
    pub fn gravity(&self) -> Vec2 {
        self.settings.gravity
    }

    /// Sets gravity (finite).
    pub fn set_gravity(&mut self, gravity: Vec2) -> Result<(), CaromError> {
        self.settings.gravity = check_finite_vec("gravity", gravity)?;
        Ok(())
    }

    /// Chooses the drag law.
    pub fn set_drag_model(&mut self, model: DragModel) {
        self.settings.drag = model;
    }

    /// Adds a body; its definition is checked first.
    ///
    /// # Errors
    /// Non-finite placement or velocity, a non-positive density for a dynamic body, or a
    /// negative friction, restitution or drag coefficient.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyHandle, CaromError> {
        self.bodies.insert(def)
    }

    /// Removes a body and returns it.
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<Body, CaromError> {
        self.bodies.remove(handle)
    }

    /// The body behind a handle, unless it was removed.
    pub fn body(&self, handle: BodyHandle) -> Option<&Body> {
        self.bodies.get(handle)
    }

    /// The body behind a handle, mutably, unless it was removed.
    pub fn body_mut(&mut self, handle: BodyHandle) -> Option<&mut Body> {
        self.bodies.get_mut(handle)
    }

    /// True when the handle refers to a body of this world.
    pub fn contains(&self, handle: BodyHandle) -> bool {
        self.bodies.contains(handle)
    }

    /// Every body, in storage order (which is also draw order: later is on top).
    pub fn bodies(&self) -> impl ExactSizeIterator<Item = &Body> {
        self.bodies.as_slice().iter()
    }

    /// Every body, mutably.
    pub fn bodies_mut(&mut self) -> impl ExactSizeIterator<Item = &mut Body> {
        self.bodies.as_mut_slice().iter_mut()
    }

    /// How many bodies there are.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Simulated time so far, in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// How many steps were taken.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    /// Advances the world by `dt` seconds.
    ///
    /// The stages, in order: integrate forces (gravity, applied forces, drag) into velocities,
    /// then integrate velocities into positions. Collision stages slot in between as they land.
    ///
    /// # Errors
    /// A time step that is not finite and positive; the world is left untouched.
    pub fn step(&mut self, dt: Real) -> Result<(), CaromError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(CaromError::OutOfRange {
                name: "time step",
                expected: "finite and positive",
                value: dt,
            });
        }
        let bodies = self.bodies.as_mut_slice();
        integrate::integrate_velocities(
            bodies,
            self.settings.gravity,
            Some(self.settings.drag),
            dt,
        );
        integrate::integrate_positions(bodies, dt);
        self.time += dt as f64;
        self.step_count += 1;
        Ok(())
    }

    /// The body under a world point, for grabbing with the mouse.
    ///
    /// Dynamic bodies win over kinematic ones and those over static ones; among equals the one
    /// latest in storage order (drawn on top) wins.
    pub fn body_at(&self, point: Vec2) -> Option<BodyHandle> {
        let rank = |kind: BodyKind| match kind {
            BodyKind::Static => 0,
            BodyKind::Kinematic => 1,
            BodyKind::Dynamic => 2,
        };
        self.bodies()
            .filter(|body| body.contains_point(point))
            .max_by_key(|body| rank(body.kind()))
            .map(Body::handle)
    }

    /// Every body containing the point.
    pub fn bodies_at(&self, point: Vec2) -> impl Iterator<Item = BodyHandle> + '_ {
        self.bodies()
            .filter(move |body| body.contains_point(point))
            .map(Body::handle)
    }

    /// The first body the ray enters, if any.
    pub fn cast_ray(&self, ray: &Ray) -> Option<WorldRayHit> {
        if !(crate::math::is_finite_vec(ray.origin) && crate::math::is_finite_vec(ray.translation))
        {
            return None;
        }
        let mut best: Option<WorldRayHit> = None;
        for body in self.bodies() {
            let reach = best.map_or(1.0, |hit| hit.fraction);
            if body
                .aabb()
                .ray_interval(ray.origin, ray.translation, reach)
                .is_none()
            {
                continue;
            }
            let inverse = body.rotation().inverse();
            let local = Ray::new(body.local_point(ray.origin), inverse * ray.translation);
            if let Some(hit) = body.shape().ray_cast_local(&local)
                && best.is_none_or(|b| hit.fraction < b.fraction)
            {
                best = Some(WorldRayHit {
                    body: body.handle(),
                    point: ray.at(hit.fraction),
                    normal: body.rotation() * hit.normal,
                    fraction: hit.fraction,
                });
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;
    use crate::shape::Shape;

    #[test]
    fn bad_time_steps_are_refused() {
        let mut world = World::new();
        for dt in [0.0, -1.0, Real::NAN, Real::INFINITY] {
            assert!(world.step(dt).is_err());
        }
        assert_eq!(world.step_count(), 0);
    }

    #[test]
    fn static_bodies_do_not_fall_and_kinematic_ones_keep_their_velocity() {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5).unwrap()))
            .unwrap();
        let platform = world
            .add_body(
                BodyDef::kinematic(Shape::rect(1.0, 0.1).unwrap())
                    .linear_velocity(vec2(1.0, 0.0))
                    .angular_velocity(0.5),
            )
            .unwrap();
        for _ in 0..60 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert_eq!(world.body(ground).unwrap().position(), Vec2::zeros());
        let p = world.body(platform).unwrap();
        assert!((p.position() - vec2(1.0, 0.0)).norm() < 1e-4);
        assert_eq!(p.linear_velocity(), vec2(1.0, 0.0));
        assert!((p.angle() - 0.5).abs() < 1e-4);
    }

    #[test]
    fn body_at_prefers_dynamic_and_topmost() {
        let mut world = World::new();
        let floor = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 5.0).unwrap()))
            .unwrap();
        let low = world
            .add_body(BodyDef::dynamic(Shape::circle(1.0).unwrap()))
            .unwrap();
        let high = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5).unwrap()))
            .unwrap();
        assert_eq!(world.body_at(vec2(0.0, 0.0)), Some(high));
        assert_eq!(world.body_at(vec2(0.8, 0.0)), Some(low));
        assert_eq!(world.body_at(vec2(3.0, 3.0)), Some(floor));
        assert_eq!(world.body_at(vec2(30.0, 3.0)), None);
        assert_eq!(world.bodies_at(vec2(0.0, 0.0)).count(), 3);
    }

    #[test]
    fn cast_ray_finds_the_closest_body() {
        let mut world = World::new();
        let near = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5).unwrap()).position(vec2(2.0, 0.0)))
            .unwrap();
        let far = world
            .add_body(
                BodyDef::dynamic(Shape::circle(0.5).unwrap())
                    .position(vec2(5.0, 0.0))
                    .angle(1.0),
            )
            .unwrap();
        let hit = world
            .cast_ray(&Ray::new(vec2(0.0, 0.0), vec2(10.0, 0.0)))
            .unwrap();
        assert_eq!(hit.body, near);
        assert!((hit.point - vec2(1.5, 0.0)).norm() < 1e-6);
        assert!((hit.normal - vec2(-1.0, 0.0)).norm() < 1e-6);
        assert!((hit.fraction - 0.15).abs() < 1e-6);
        world.remove_body(near).unwrap();
        let hit = world
            .cast_ray(&Ray::new(vec2(0.0, 0.0), vec2(10.0, 0.0)))
            .unwrap();
        assert_eq!(hit.body, far);
        assert!((hit.point - vec2(4.5, 0.0)).norm() < 1e-5);
        assert!(
            world
                .cast_ray(&Ray::new(vec2(0.0, 3.0), vec2(10.0, 0.0)))
                .is_none()
        );
        assert!(
            world
                .cast_ray(&Ray::new(vec2(Real::NAN, 0.0), vec2(1.0, 0.0)))
                .is_none()
        );
    }
}
