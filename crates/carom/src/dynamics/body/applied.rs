//! What a user applies to a body from outside: forces and torques, which last until the end
//! of the next step, and impulses, which change its velocities at once. A point they act at
//! lies within [`crate::MAX_POSITION`], as a body's position does. A value that would
//! leave the body's figures not finite, or an impulse that would leave it faster than
//! [`crate::MAX_SPEED`] or [`crate::MAX_ANGULAR_SPEED`], is refused, and the body is left as it was.

use super::Body;
use super::checks::{check_position, check_spin, check_velocity};
use crate::error::{CaromError, check_finite, check_finite_vec};
use crate::math::{Real, Vec2, cross, is_finite_vec};

impl Body {
    /// Adds a force at a world point: it also adds the torque `r × F`, with `r` from the
    /// centre of mass. Forces last until the end of the next step. Only dynamic bodies feel it.
    pub(crate) fn apply_force(&mut self, force: Vec2, world_point: Vec2) -> Result<(), CaromError> {
        check_finite_vec("force", force)?;
        check_position("force application point", world_point)?;
        let torque = cross(world_point - self.center, force);
        self.accumulate(
            "force",
            force.norm(),
            self.force + force,
            self.torque + torque,
        )
    }

    /// Adds a force through the centre of mass (no torque).
    pub(crate) fn apply_force_at_center(&mut self, force: Vec2) -> Result<(), CaromError> {
        check_finite_vec("force", force)?;
        self.accumulate("force", force.norm(), self.force + force, self.torque)
    }

    /// Adds a torque, N·m, counter-clockwise.
    pub(crate) fn apply_torque(&mut self, torque: Real) -> Result<(), CaromError> {
        check_finite("torque", torque)?;
        self.accumulate("torque", torque, self.force, self.torque + torque)
    }

    /// Applies an impulse at a world point: it changes the velocities at once,
    /// `Δv = J / m`, `Δω = (r × J) / I`.
    pub(crate) fn apply_impulse(
        &mut self,
        impulse: Vec2,
        world_point: Vec2,
    ) -> Result<(), CaromError> {
        check_finite_vec("impulse", impulse)?;
        check_position("impulse application point", world_point)?;
        let v = self.linear_velocity + impulse * self.mass.inv_mass;
        let w = self.angular_velocity
            + self.mass.inv_inertia * cross(world_point - self.center, impulse);
        self.kick("impulse", impulse.norm(), v, w)
    }

    /// Applies an impulse through the centre of mass.
    pub(crate) fn apply_impulse_at_center(&mut self, impulse: Vec2) -> Result<(), CaromError> {
        check_finite_vec("impulse", impulse)?;
        let v = self.linear_velocity + impulse * self.mass.inv_mass;
        self.kick("impulse", impulse.norm(), v, self.angular_velocity)
    }

    /// Applies an angular impulse, N·m·s.
    pub(crate) fn apply_angular_impulse(&mut self, impulse: Real) -> Result<(), CaromError> {
        check_finite("angular impulse", impulse)?;
        let w = self.angular_velocity + self.mass.inv_inertia * impulse;
        self.kick("angular impulse", impulse, self.linear_velocity, w)
    }

    /// A dynamic body's accumulated `force` and `torque` become these totals, which a force or
    /// torque `name` of size `value` made, and it wakes; other kinds feel no force.
    fn accumulate(
        &mut self,
        name: &'static str,
        value: Real,
        force: Vec2,
        torque: Real,
    ) -> Result<(), CaromError> {
        if self.is_dynamic() {
            check_sums(name, value, force, torque)?;
            (self.force, self.torque) = (force, torque);
            self.wake_up();
        }
        Ok(())
    }

    /// The body's velocities become `v` and `w`, which an impulse `name` of size `value` gave
    /// it, and it wakes.
    fn kick(
        &mut self,
        name: &'static str,
        value: Real,
        v: Vec2,
        w: Real,
    ) -> Result<(), CaromError> {
        check_sums(name, value, v, w)?;
        // The speeds a body may be given at all: past them a step's motion overflows. The
        // error names the impulse, not the velocity it would give.
        if check_velocity(name, v).is_err() || check_spin(name, w).is_err() {
            return Err(CaromError::OutOfRange {
                name,
                expected: "small enough that the body's velocities stay within 1e6 m/s and \
                           1e6 rad/s either way",
                value,
            });
        }
        self.wake_up();
        (self.linear_velocity, self.angular_velocity) = (v, w);
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
    if is_finite_vec(v) && w.is_finite() {
        return Ok(());
    }
    Err(CaromError::OutOfRange {
        name,
        expected: "small enough for the body's sums and velocities to stay finite",
        value,
    })
}
