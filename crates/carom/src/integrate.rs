//! Semi-implicit (symplectic) Euler: velocities from forces first, then positions from the
//! new velocities. This order keeps orbits and oscillators from gaining energy.

use crate::body::{Body, BodyKind};
use crate::drag::DragModel;
use crate::math::{Real, Vec2};

/// Velocity half of the step: gravity and accumulated forces, then drag. Clears the forces.
pub(crate) fn integrate_velocities(
    bodies: &mut [Body],
    gravity: Vec2,
    drag: Option<DragModel>,
    dt: Real,
) {
    for body in bodies.iter_mut().filter(|b| b.kind() == BodyKind::Dynamic) {
        let acceleration = gravity * body.gravity_scale() + body.force() * body.inv_mass();
        let angular_acceleration = body.torque() * body.inv_inertia();
        let (linear_damping, angular_damping) = (body.linear_damping(), body.angular_damping());
        let (v, w) = body.velocities_mut();
        *v += acceleration * dt;
        *w += angular_acceleration * dt;
        if let Some(model) = drag {
            *v = model.apply_linear(*v, linear_damping, dt);
            *w = model.apply_angular(*w, angular_damping, dt);
        }
        body.clear_forces();
    }
}

/// Position half of the step: every moving body advances by its (new) velocity, and its
/// world shape is re-placed once for the queries and collisions that follow.
pub(crate) fn integrate_positions(bodies: &mut [Body], dt: Real) {
    for body in bodies.iter_mut().filter(|b| b.kind() != BodyKind::Static) {
        body.advance(dt);
        body.sync_world_shape();
    }
}
