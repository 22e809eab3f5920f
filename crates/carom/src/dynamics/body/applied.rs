//! What a user applies to a body from outside: forces and torques, which last until the end
//! of the next step, and impulses, which change its velocities at once. A value that would
//! leave the body's figures not finite is refused, and the body is left as it was.

use super::Body;
use crate::error::{CaromError, check_finite, check_finite_vec};
use crate::math::{Real, Vec2, cross};

impl Body {
    /// Adds a force at a world point: it also adds the torque `r × F`, with `r` from the
    /// centre of mass. Forces last until the end of the next step. Only dynamic bodies feel it.
    pub(crate) fn apply_force(&mut self, force: Vec2, world_point: Vec2) -> Result<(), CaromError> {
        check_finite_vec("force", force)?;
        check_finite_vec("force application point", world_point)?;
        if self.is_dynamic() {
            let (sum, torque) = (
                self.force + force,
                self.torque + cross(world_point - self.center, force),
            );
            check_sums("force", force.norm(), sum, torque)?;
            (self.force, self.torque) = (sum, torque);
            self.wake_up();
        }
        Ok(())
    }

    /// Adds a force through the centre of mass (no torque).
    pub(crate) fn apply_force_at_center(&mut self, force: Vec2) -> Result<(), CaromError> {
        check_finite_vec("force", force)?;
        if self.is_dynamic() {
            let sum = self.force + force;
            check_sums("force", force.norm(), sum, self.torque)?;
            self.force = sum;
            self.wake_up();
        }
        Ok(())
    }

    /// Adds a torque, N·m, counter-clockwise.
    pub(crate) fn apply_torque(&mut self, torque: Real) -> Result<(), CaromError> {
        check_finite("torque", torque)?;
        if self.is_dynamic() {
            let sum = self.torque + torque;
            check_sums("torque", torque, self.force, sum)?;
            self.torque = sum;
            self.wake_up();
        }
        Ok(())
    }

    /// Applies an impulse at a world point: it changes the velocities at once,
    /// `Δv = J / m`, `Δω = (r × J) / I`.
    pub(crate) fn apply_impulse(
        &mut self,
        impulse: Vec2,
        world_point: Vec2,
    ) -> Result<(), CaromError> {
        check_finite_vec("impulse", impulse)?;
        check_finite_vec("impulse application point", world_point)?;
        let v = self.linear_velocity + impulse * self.mass.inv_mass;
        let w = self.angular_velocity
            + self.mass.inv_inertia * cross(world_point - self.center, impulse);
        check_sums("impulse", impulse.norm(), v, w)?;
        self.wake_up();
        (self.linear_velocity, self.angular_velocity) = (v, w);
        Ok(())
    }

    /// Applies an impulse through the centre of mass.
    pub(crate) fn apply_impulse_at_center(&mut self, impulse: Vec2) -> Result<(), CaromError> {
        check_finite_vec("impulse", impulse)?;
        let v = self.linear_velocity + impulse * self.mass.inv_mass;
        check_sums("impulse", impulse.norm(), v, self.angular_velocity)?;
        self.wake_up();
        self.linear_velocity = v;
        Ok(())
    }

    /// Applies an angular impulse, N·m·s.
    pub(crate) fn apply_angular_impulse(&mut self, impulse: Real) -> Result<(), CaromError> {
        check_finite("angular impulse", impulse)?;
        let w = self.angular_velocity + self.mass.inv_inertia * impulse;
        check_sums("angular impulse", impulse, self.linear_velocity, w)?;
        self.wake_up();
        self.angular_velocity = w;
        Ok(())
    }

    /// Forgets the accumulated force and torque.
    #[inline]
    pub(crate) fn clear_forces(&mut self) {
        self.force = Vec2::zeros();
        self.torque = 0.0;
    }
}

/// Refuses a force, torque or impulse (`name`, of size `value`) that would leave what it adds
/// to (the body's accumulated force and torque, or its velocities) not finite: a value too
/// large for the body's mass, or for what was applied before it.
fn check_sums(name: &'static str, value: Real, v: Vec2, w: Real) -> Result<(), CaromError> {
    if v.x.is_finite() && v.y.is_finite() && w.is_finite() {
        return Ok(());
    }
    Err(CaromError::OutOfRange {
        name,
        expected: "small enough for the body's sums and velocities to stay finite",
        value,
    })
}
