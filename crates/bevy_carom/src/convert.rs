//! Between Bevy's maths (glam, `f32`, 3D transforms) and carom's (nalgebra, `Real`, 2D poses).

use bevy::math::{Quat, Rot2, Vec2};
use bevy::transform::components::Transform;
use carom::Real;

/// carom's vector as Bevy's.
pub(crate) fn to_bevy(v: carom::Vec2) -> Vec2 {
    Vec2::new(v.x as f32, v.y as f32)
}

/// Bevy's vector as carom's.
pub(crate) fn to_carom(v: Vec2) -> carom::Vec2 {
    carom::vec2(v.x as Real, v.y as Real)
}

/// The rotation about z of a 2D transform, radians.
pub(crate) fn angle_of(transform: &Transform) -> f32 {
    Pose::of_transform(transform).angle()
}

/// A 2D pose: position and rotation. Kept as the rotation's cosine and sine, as carom keeps
/// it, so that writing a body's pose back takes no trigonometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pose {
    pub position: Vec2,
    pub rotation: Rot2,
}

impl Default for Pose {
    fn default() -> Self {
        Pose {
            position: Vec2::ZERO,
            rotation: Rot2::IDENTITY,
        }
    }
}

impl Pose {
    pub fn of_transform(transform: &Transform) -> Pose {
        // A rotation about z alone is (0, 0, sin(a/2), cos(a/2)); a tilt out of the plane is
        // ignored, as the body lives in it.
        let (z, w) = (transform.rotation.z, transform.rotation.w);
        let norm = z * z + w * w;
        let rotation = if norm > 0.0 {
            Rot2::from_sin_cos(2.0 * w * z / norm, (w * w - z * z) / norm)
        } else {
            Rot2::IDENTITY
        };
        Pose {
            position: transform.translation.truncate(),
            rotation,
        }
    }

    pub fn of_body(body: &carom::Body) -> Pose {
        let rotation = body.rotation();
        Pose {
            position: to_bevy(body.position()),
            rotation: Rot2::from_sin_cos(rotation.im as f32, rotation.re as f32),
        }
    }

    /// The angle, radians.
    pub fn angle(self) -> f32 {
        self.rotation.as_radians()
    }

    /// `transform` placed at this pose, keeping its depth and scale.
    pub fn apply_to(self, transform: &mut Transform) {
        transform.translation = self.position.extend(transform.translation.z);
        // The half angle's cosine and sine from the angle's, each from the larger of the two
        // half-angle formulas, so that neither divides by a small number.
        let (c, s) = (self.rotation.cos, self.rotation.sin);
        let (z, w) = if c >= 0.0 {
            let w = (0.5 * (1.0 + c)).sqrt();
            (s / (2.0 * w), w)
        } else {
            let z = (0.5 * (1.0 - c)).sqrt().copysign(s);
            (z, s / (2.0 * z))
        };
        transform.rotation = Quat::from_xyzw(0.0, 0.0, z, w);
    }

    /// The pose a fraction `t` of the way from `self` to `to`.
    pub fn lerp(self, to: Pose, t: f32) -> Pose {
        Pose {
            position: self.position.lerp(to.position, t),
            rotation: self.rotation.nlerp(to.rotation, t),
        }
    }
}
