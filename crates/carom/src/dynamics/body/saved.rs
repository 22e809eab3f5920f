//! Checks on a body read from a saved world: it must hold together as a body built through
//! the API would, or the whole save is refused.

use super::{Body, BodyHandle, BodyKind};
use crate::dynamics::collider::Collider;
use crate::error::CaromError;

impl Body {
    /// True when the body's mass, centre of mass and reach are, bit for bit, what its
    /// colliders give: a saved body's are checked so.
    pub(crate) fn mass_matches<'c>(
        &self,
        colliders: impl Iterator<Item = &'c Collider> + Clone,
    ) -> bool {
        let mut rebuilt = self.clone();
        rebuilt.rebuild_mass(colliders).is_ok()
            && rebuilt.mass == self.mass
            && rebuilt.local_center == self.local_center
            && rebuilt.reach == self.reach
            && rebuilt.min_extent == self.min_extent
    }

    /// Checks a body read from a saved world: its handle, finite values, damping and a sleep
    /// threshold not negative, a unit rotation, and a mass that fits its kind.
    pub(crate) fn check_saved(&self, handle: BodyHandle) -> Result<(), CaromError> {
        if self.handle != handle {
            return Err(CaromError::bad_save("a body's handle is not its slot's"));
        }
        if self.colliders.is_empty() {
            return Err(CaromError::bad_save("a body has no collider"));
        }
        let vectors = [
            ("position", self.position),
            ("centre of mass", self.center),
            ("local centre of mass", self.local_center),
            ("linear velocity", self.linear_velocity),
            ("force", self.force),
            ("box", self.aabb.min),
            ("box", self.aabb.max),
        ];
        let scalars = [
            ("angular velocity", self.angular_velocity),
            ("torque", self.torque),
            ("reach", self.reach),
            ("least extent", self.min_extent),
            ("gravity scale", self.gravity_scale),
            ("linear damping", self.linear_damping),
            ("angular damping", self.angular_damping),
            ("last motion", self.last_motion),
            ("sleep time", self.sleep_time),
            ("sleep threshold", self.sleep_threshold),
            ("mass", self.mass.mass),
            ("inverse mass", self.mass.inv_mass),
            ("inertia", self.mass.inertia),
            ("inverse inertia", self.mass.inv_inertia),
        ];
        let not_finite = vectors
            .iter()
            .flat_map(|(name, v)| v.iter().map(move |x| (name, x)))
            .chain(scalars.iter().map(|(name, x)| (name, x)))
            .find(|(_, x)| !x.is_finite());
        if let Some((name, value)) = not_finite {
            return Err(CaromError::bad_save(format!(
                "body {}'s {name} is not finite ({value})",
                handle.index()
            )));
        }
        // What the setters refuse: negative damping would speed a body up each step (and at
        // -1/h divide by zero), a negative sleep threshold keep it awake for good.
        if [
            self.linear_damping,
            self.angular_damping,
            self.sleep_threshold,
        ]
        .iter()
        .any(|&x| x < 0.0)
        {
            return Err(CaromError::bad_save(format!(
                "body {} has a damping or sleep threshold that is negative",
                handle.index()
            )));
        }
        if super::check_sweep_threshold(self.sweep_threshold).is_err() {
            return Err(CaromError::bad_save(format!(
                "body {} has a sweep threshold that is negative or not a number",
                handle.index()
            )));
        }
        if (self.rotation.norm() - 1.0).abs() > 1e-3 {
            return Err(CaromError::bad_save(format!(
                "body {} has a rotation that is not a unit",
                handle.index()
            )));
        }
        let m = &self.mass;
        let fits = if self.kind == BodyKind::Dynamic {
            m.inv_mass > 0.0 && m.inv_inertia >= 0.0
        } else {
            m.inv_mass == 0.0 && m.inv_inertia == 0.0
        };
        if !fits || m.mass < 0.0 || m.inertia < 0.0 {
            return Err(CaromError::bad_save(format!(
                "body {} has a mass that does not fit its kind",
                handle.index()
            )));
        }
        Ok(())
    }
}
