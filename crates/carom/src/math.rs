//! Scalar and vector types, and the few 2D products nalgebra does not name.

/// The floating-point type of the engine: `f32`, or `f64` with the `f64` feature
/// (bodies far from the origin keep their precision; every step costs more). The contact
/// solver's SIMD lanes are `f32` in both: what they solve is relative to the bodies.
#[cfg(not(feature = "f64"))]
pub type Real = f32;
/// The floating-point type of the engine: `f32`, or `f64` with the `f64` feature
/// (bodies far from the origin keep their precision; every step costs more). The contact
/// solver's SIMD lanes are `f32` in both: what they solve is relative to the bodies.
#[cfg(feature = "f64")]
pub type Real = f64;

/// π and its kin in [`Real`]'s precision.
#[cfg(not(feature = "f64"))]
pub use std::f32::consts;
/// π and its kin in [`Real`]'s precision.
#[cfg(feature = "f64")]
pub use std::f64::consts;

/// A 2D vector or point.
pub type Vec2 = nalgebra::Vector2<Real>;

/// A rotation in the plane (a unit complex number: `cos + i sin`).
pub type Rot = nalgebra::UnitComplex<Real>;

/// A rigid transform: rotation followed by translation.
pub type Isometry = nalgebra::Isometry2<Real>;

/// A 3x3 homogeneous matrix, as renderers want it.
pub type Mat3 = nalgebra::Matrix3<Real>;

/// Builds a vector from its components.
#[inline]
pub fn vec2(x: Real, y: Real) -> Vec2 {
    Vec2::new(x, y)
}

/// The 2D cross product `a.x * b.y - a.y * b.x` (the z of the 3D cross product).
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> Real {
    a.x * b.y - a.y * b.x
}

/// The cross product of a scalar (a vector along z) with a vector: `s × v = (-s v.y, s v.x)`.
///
/// Used for the velocity of a point on a spinning body: `v + ω × r`.
#[inline]
pub(crate) fn cross_sv(s: Real, v: Vec2) -> Vec2 {
    Vec2::new(-s * v.y, s * v.x)
}

/// The clockwise perpendicular `(v.y, -v.x)`: the outward normal of a counter-clockwise edge.
#[inline]
pub(crate) fn perp_cw(v: Vec2) -> Vec2 {
    Vec2::new(v.y, -v.x)
}

/// True when both components are finite (neither NaN nor infinite).
#[inline]
pub(crate) fn is_finite_vec(v: Vec2) -> bool {
    v.x.is_finite() && v.y.is_finite()
}

/// Shortens `v` to at most `max_len`, keeping its direction.
#[inline]
pub(crate) fn clamp_magnitude(v: Vec2, max_len: Real) -> Vec2 {
    let len_sq = v.norm_squared();
    if len_sq <= max_len * max_len {
        v
    } else if len_sq.is_finite() {
        v * (max_len / len_sq.sqrt())
    } else {
        // Too long to square (a force too large for a tiny mass), or infinite: its direction
        // from the components scaled by the largest, an infinite one alone if any.
        let infinite = |x: Real| if x.is_infinite() { x.signum() } else { 0.0 };
        let big = v.x.abs().max(v.y.abs());
        let direction = if big.is_finite() {
            v / big
        } else {
            Vec2::new(infinite(v.x), infinite(v.y))
        };
        direction * (max_len / direction.norm())
    }
}

/// `angle` brought into `[-π, π]` by whole turns.
#[inline]
pub(crate) fn unwind_angle(angle: Real) -> Real {
    use consts::{PI, TAU};
    if (-PI..=PI).contains(&angle) {
        angle
    } else {
        angle - TAU * ((angle + PI) / TAU).floor()
    }
}

// Sines, cosines and arctangents are carom's own (the `libm` crate's ports of musl's), not
// the platform's C library's: glibc, other C libraries and a browser's WebAssembly round a
// few results differently in the last bit, and one bit grows into a different simulation.
// With these a world steps to the same bits on every platform.

/// The rotation by `angle` radians, computed the same on every platform.
#[inline]
pub fn rotation(angle: Real) -> Rot {
    let (sin, cos) = sin_cos(angle);
    Rot::from_cos_sin_unchecked(cos, sin)
}

/// The angle of `rotation` in `[-π, π]`, computed the same on every platform.
#[inline]
pub fn angle_of(rotation: &Rot) -> Real {
    atan2(rotation.im, rotation.re)
}

/// Sine and cosine of `x`, computed the same on every platform. In single precision, one
/// argument reduction serves both: `libm::sincosf` gives, bit for bit, what `sinf` and `cosf`
/// give apart, on every `f32` (all 2^32 checked).
#[inline]
pub(crate) fn sin_cos(x: Real) -> (Real, Real) {
    #[cfg(not(feature = "f64"))]
    return libm::sincosf(x);
    #[cfg(feature = "f64")]
    return sin_cos_f64(x);
}

/// `atan2(y, x)`, computed the same on every platform.
#[inline]
pub fn atan2(y: Real, x: Real) -> Real {
    #[cfg(not(feature = "f64"))]
    return libm::atan2f(y, x);
    #[cfg(feature = "f64")]
    return atan2_f64(y, x);
}

/// Sine and cosine of `x` in double precision, computed the same on every platform.
#[inline]
pub(crate) fn sin_cos_f64(x: f64) -> (f64, f64) {
    (libm::sin(x), libm::cos(x))
}

/// `atan2(y, x)` in double precision, computed the same on every platform.
#[inline]
pub(crate) fn atan2_f64(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every step's rotations go through `sin_cos`: its one argument reduction must give what
    /// `sinf` and `cosf` give apart, or the bits of every turning body would move. A million
    /// inputs spread over every exponent, both signs (all 2^32 agree, checked once outside
    /// the suite).
    #[cfg(not(feature = "f64"))]
    #[test]
    fn sin_cos_is_sinf_and_cosf_bit_for_bit() {
        let mut bits: u32 = 0x9E37_79B9;
        for _ in 0..1_000_000 {
            bits = bits.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let x = f32::from_bits(bits);
            if !x.is_finite() {
                continue;
            }
            let (sin, cos) = sin_cos(x);
            assert_eq!(sin.to_bits(), libm::sinf(x).to_bits(), "sin {x:e}");
            assert_eq!(cos.to_bits(), libm::cosf(x).to_bits(), "cos {x:e}");
        }
    }

    #[test]
    fn rotations_from_and_to_angles_agree_with_the_standard_library() {
        for i in -40..=40 {
            let angle = i as Real * 0.1;
            let ours = rotation(angle);
            let std = Rot::new(angle);
            assert!((ours.re - std.re).abs() <= 1e-7 && (ours.im - std.im).abs() <= 1e-7);
            let back = angle_of(&ours);
            assert!((back - unwind_angle(angle)).abs() < 1e-5, "{angle}: {back}");
        }
    }

    #[test]
    fn perpendiculars_and_crosses_agree() {
        let a = vec2(2.0, 1.0);
        let b = vec2(-0.5, 3.0);
        assert_eq!(cross(a, b), 6.5);
        // The clockwise perpendicular of a CCW edge points to its right, i.e. outward.
        assert_eq!(perp_cw(vec2(1.0, 0.0)), vec2(0.0, -1.0));
        assert_eq!(cross_sv(2.0, vec2(1.0, 0.0)), vec2(0.0, 2.0));
    }

    #[test]
    fn clamp_magnitude_holds_vectors_too_long_to_square() {
        let held = clamp_magnitude(vec2(Real::MAX, -Real::MAX), 4.0);
        assert!(
            (held - vec2(2.0, -2.0) * consts::SQRT_2).norm() < 1e-5,
            "{held:?}"
        );
        let held = clamp_magnitude(vec2(Real::INFINITY, 3.0), 4.0);
        assert_eq!(held, vec2(4.0, 0.0));
        let held = clamp_magnitude(vec2(Real::NEG_INFINITY, Real::INFINITY), 4.0);
        assert!(
            (held - vec2(-2.0, 2.0) * consts::SQRT_2).norm() < 1e-5,
            "{held:?}"
        );
    }

    #[test]
    fn clamp_magnitude_keeps_short_vectors() {
        assert_eq!(clamp_magnitude(vec2(0.3, 0.4), 1.0), vec2(0.3, 0.4));
        let long = clamp_magnitude(vec2(3.0, 4.0), 1.0);
        assert!((long.norm() - 1.0).abs() < 1e-6);
        assert!((long - vec2(0.6, 0.8)).norm() < 1e-6);
    }
}
