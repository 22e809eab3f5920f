//! Air drag: how moving bodies slow down on their own.

use crate::math::{Real, Vec2, clamp_magnitude};

/// Which law slows bodies down, using each body's linear and angular drag coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum DragModel {
    /// Exponential damping, `v *= 1 / (1 + dt c)`: unconditionally stable for any step and
    /// coefficient, and the same law Box2D uses. The default.
    #[default]
    Exponential,
    /// The tutorial's drag: the velocity loses `clamp_magnitude(v, 1) · c · dt` each step, a
    /// constant deceleration above 1 m/s and a proportional one below. It never reverses the
    /// velocity, even for steps longer than `1 / c`.
    Tutorial,
}

impl DragModel {
    /// The linear velocity after one step of drag.
    #[inline]
    pub fn apply_linear(self, velocity: Vec2, coefficient: Real, dt: Real) -> Vec2 {
        match self {
            DragModel::Exponential => velocity * (1.0 / (1.0 + dt * coefficient)),
            DragModel::Tutorial => {
                let loss = clamp_magnitude(velocity, 1.0) * (coefficient * dt);
                // Shedding more speed than there is means stopping, not going backwards.
                if loss.norm_squared() >= velocity.norm_squared() {
                    Vec2::zeros()
                } else {
                    velocity - loss
                }
            }
        }
    }

    /// The angular velocity after one step of drag.
    #[inline]
    pub fn apply_angular(self, velocity: Real, coefficient: Real, dt: Real) -> Real {
        match self {
            DragModel::Exponential => velocity * (1.0 / (1.0 + dt * coefficient)),
            DragModel::Tutorial => {
                let loss = velocity.clamp(-1.0, 1.0) * (coefficient * dt);
                if loss.abs() >= velocity.abs() {
                    0.0
                } else {
                    velocity - loss
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn tutorial_drag_is_constant_above_one_and_never_reverses() {
        let v = DragModel::Tutorial.apply_linear(vec2(10.0, 0.0), 2.0, 0.1);
        assert!((v - vec2(9.8, 0.0)).norm() < 1e-6);
        let slow = DragModel::Tutorial.apply_linear(vec2(0.5, 0.0), 2.0, 0.1);
        assert!((slow - vec2(0.4, 0.0)).norm() < 1e-6);
        assert_eq!(
            DragModel::Tutorial.apply_linear(vec2(0.5, 0.0), 100.0, 0.1),
            Vec2::zeros()
        );
        assert!((DragModel::Tutorial.apply_angular(-3.0, 1.0, 0.5) + 2.5).abs() < 1e-6);
        assert_eq!(DragModel::Tutorial.apply_angular(0.1, 50.0, 0.1), 0.0);
    }

    #[test]
    fn exponential_damping_is_stable_for_huge_coefficients() {
        let v = DragModel::Exponential.apply_linear(vec2(4.0, -2.0), 1.0e6, 1.0);
        assert!(v.norm() < 1e-5 && v.x > 0.0);
        let w = DragModel::Exponential.apply_angular(2.0, 1.0, 1.0);
        assert_eq!(w, 1.0);
    }
}
