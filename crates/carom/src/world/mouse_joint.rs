//! A soft spring that drags a point of a body toward a target: how a user grabs and throws.
//!
//! The joint is a damped spring on the grabbed point, tuned by frequency and damping ratio
//! against the mass the point feels (so a long plank grabbed at its tip behaves like a small
//! box grabbed at its centre), with its force capped. It acts through forces added before a
//! step, so the body still collides on the way and a wall stops it: the grab never teleports
//! anything. Letting go leaves the body with the velocity it had: a throw.

use crate::dynamics::body::BodyHandle;
use crate::error::CaromError;
use crate::math::{Real, Vec2};
use crate::world::World;

/// A spring from a point fixed in a body to a target point in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MouseJoint {
    body: BodyHandle,
    local_anchor: Vec2,
    target: Vec2,
    /// Spring frequency, Hz: how quickly the point catches up with the target.
    pub hertz: Real,
    /// 1 is critically damped; below overshoots.
    pub damping_ratio: Real,
    /// The force cap, as an acceleration of the body's whole mass, m/s². It bounds how hard a
    /// dragged body presses into what is in its way.
    pub max_acceleration: Real,
    /// Spin damping while held, 1/s, so a body hangs from the cursor instead of whirling.
    pub angular_damping: Real,
}

impl MouseJoint {
    /// Grabs `body` at `world_point` (usually where the user clicked). `None` for bodies that
    /// do not respond to forces (static or kinematic) or a stale handle.
    pub fn new(world: &World, body: BodyHandle, world_point: Vec2) -> Option<Self> {
        let grabbed = world.body(body).filter(|b| b.is_dynamic())?;
        Some(MouseJoint {
            body,
            local_anchor: grabbed.local_point(world_point),
            target: world_point,
            hertz: 5.0,
            damping_ratio: 0.7,
            max_acceleration: 200.0,
            angular_damping: 2.0,
        })
    }

    /// The body held.
    pub fn body(&self) -> BodyHandle {
        self.body
    }

    /// Where the spring pulls to.
    pub fn target(&self) -> Vec2 {
        self.target
    }

    /// Moves the target (the cursor moved).
    pub fn set_target(&mut self, target: Vec2) -> Result<(), CaromError> {
        self.target = crate::error::check_finite_vec("mouse joint target", target)?;
        Ok(())
    }

    /// The grabbed point, in the body's own frame.
    pub fn local_anchor(&self) -> Vec2 {
        self.local_anchor
    }

    /// The grabbed point in the world now, if the body still exists.
    pub fn anchor(&self, world: &World) -> Option<Vec2> {
        world
            .body(self.body)
            .map(|b| b.world_point(self.local_anchor))
    }

    /// Adds this step's spring force and spin damping to the body; call before each step.
    /// Returns the force applied (zero if the body is gone).
    pub fn apply(&self, world: &mut World) -> Result<Vec2, CaromError> {
        let Some(mut body) = world.body_mut(self.body) else {
            return Ok(Vec2::zeros());
        };
        let anchor = body.world_point(self.local_anchor);
        let arm = anchor - body.center_of_mass();
        // The mass the point feels, taken at its lightest (pushing across the arm), so the
        // spring is never stiffer than intended and stays stable at any step.
        let inv_mass = body.inv_mass() + body.inv_inertia() * arm.norm_squared();
        if inv_mass <= 0.0 {
            return Ok(Vec2::zeros());
        }
        let effective_mass = 1.0 / inv_mass;
        let omega = 2.0 * std::f32::consts::PI * self.hertz;
        let stiffness = effective_mass * omega * omega;
        let damping = 2.0 * effective_mass * self.damping_ratio * omega;
        let mut force = (self.target - anchor) * stiffness - body.velocity_at(anchor) * damping;
        let max_force = self.max_acceleration * body.mass();
        let magnitude = force.norm();
        if magnitude > max_force {
            force *= max_force / magnitude;
        }
        body.apply_force(force, anchor)?;
        // Damp the swing about the grabbed point, where the body turns while held.
        let inertia_about_anchor = body.inertia() + body.mass() * arm.norm_squared();
        let spin = body.angular_velocity();
        body.apply_torque(-inertia_about_anchor * self.angular_damping * spin)?;
        Ok(force)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDef, Shape, WorldSettings, vec2};

    fn world_without_gravity() -> World {
        World::with_settings(WorldSettings {
            gravity: Vec2::zeros(),
            ..WorldSettings::default()
        })
        .unwrap()
    }

    #[test]
    fn the_grabbed_point_follows_the_target_and_settles_on_it() {
        let mut world = world_without_gravity();
        let plank = world
            .add_body(BodyDef::dynamic(Shape::rect(2.0, 0.1)))
            .unwrap();
        // Grab the plank at its tip, pull the tip 3 m up and right.
        let mut joint = MouseJoint::new(&world, plank, vec2(2.0, 0.0)).unwrap();
        joint.set_target(vec2(4.0, 2.0)).unwrap();
        for _ in 0..180 {
            joint.apply(&mut world).unwrap();
            world.step(1.0 / 60.0).unwrap();
        }
        let anchor = joint.anchor(&world).unwrap();
        assert!((anchor - joint.target()).norm() < 0.01, "tip at {anchor:?}");
        let body = world.body(plank).unwrap();
        assert!(
            body.linear_velocity().norm() < 0.05,
            "{:?} {}",
            body.linear_velocity(),
            body.angular_velocity()
        );
    }

    #[test]
    fn a_wall_stops_a_dragged_body() {
        let mut world = world_without_gravity();
        world
            .add_body(BodyDef::static_body(Shape::rect(0.1, 5.0)).position(vec2(2.0, 0.0)))
            .unwrap();
        let crate_box = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)))
            .unwrap();
        let mut joint = MouseJoint::new(&world, crate_box, vec2(0.0, 0.0)).unwrap();
        joint.set_target(vec2(10.0, 0.0)).unwrap();
        for _ in 0..120 {
            let force = joint.apply(&mut world).unwrap();
            assert!(
                force.norm() <= joint.max_acceleration * 1.0 + 1e-3,
                "{force:?}"
            );
            world.step(1.0 / 60.0).unwrap();
        }
        // The box (half-width 0.5) presses on the wall's face at x = 1.9, a few mm deep at most.
        let x = world.body(crate_box).unwrap().position().x;
        assert!(x < 1.4 + 0.02 && x > 1.3, "box centre at {x}");
    }

    #[test]
    fn only_dynamic_bodies_can_be_grabbed() {
        let mut world = world_without_gravity();
        let wall = world
            .add_body(BodyDef::static_body(Shape::rect(1.0, 1.0)))
            .unwrap();
        assert!(MouseJoint::new(&world, wall, vec2(0.0, 0.0)).is_none());
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(5.0, 0.0)))
            .unwrap();
        let mut joint = MouseJoint::new(&world, ball, vec2(5.0, 0.0)).unwrap();
        assert!(joint.set_target(vec2(Real::NAN, 0.0)).is_err());
        world.remove_body(ball).unwrap();
        assert_eq!(joint.apply(&mut world).unwrap(), Vec2::zeros());
        assert!(joint.anchor(&world).is_none());
    }
}
