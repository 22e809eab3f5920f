//! What a collider's surface is like, and how two surfaces mix where they touch.
//!
//! Friction mixes as the geometric mean and restitution as the larger, unless the world has a
//! mixer of its own ([`crate::World::set_friction_mixer`]), which sees both surfaces'
//! [`Surface::material`] ids. Rolling resistance mixes as the larger times the larger rolling
//! radius (a circle's or capsule's radius, a rounded polygon's rounding; sharp shapes do not
//! roll), as Box2D does: it is a torque of at most `resistance × radius × normal force`
//! against the bodies' relative spin. Tangent speeds add: each surface moves along itself at
//! its speed, clockwise around its shape (a belt's top, facing up, carries what lies on it
//! toward +x), and friction drives what touches it to match.

use crate::constants::{MAX_SURFACE_COEFFICIENT, MAX_TANGENT_SPEED};
use crate::dynamics::collider::{Collider, DEFAULT_FRICTION};
use crate::error::{CaromError, check_within};
use crate::math::Real;

/// A surface's material: how it grips, bounces, resists rolling and moves along itself, and
/// an id of the game's own for its mixers. [`Surface::default`] is friction 0.6 and nothing
/// else.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Surface {
    /// Coulomb friction coefficient (0 is ice).
    pub friction: Real,
    /// Bounciness: 0 does not bounce, 1 bounces back at the speed it came.
    pub restitution: Real,
    /// Resistance to rolling, usually in `[0, 1]`: a ball rolling on it slows as if friction
    /// of this coefficient acted at its rim, and rests on a slope up to `atan` of it.
    pub rolling_resistance: Real,
    /// How fast the surface moves along itself, m/s, clockwise around its shape: a conveyor
    /// belt's speed.
    pub tangent_speed: Real,
    /// The game's id for the material, passed to the world's mixers. Not used otherwise.
    pub material: u64,
}

impl Default for Surface {
    fn default() -> Self {
        Surface {
            friction: DEFAULT_FRICTION,
            restitution: 0.0,
            rolling_resistance: 0.0,
            tangent_speed: 0.0,
            material: 0,
        }
    }
}

impl Surface {
    /// Checks every value: friction, restitution and rolling resistance from 0 to 1000, the
    /// tangent speed within 10 km/s either way.
    ///
    /// # Errors
    /// The first value that is not so.
    pub fn validate(&self) -> Result<(), CaromError> {
        let coefficients = [
            ("friction", self.friction),
            ("restitution", self.restitution),
            ("rolling resistance", self.rolling_resistance),
        ];
        for (name, value) in coefficients {
            check_within(name, value, 0.0..=MAX_SURFACE_COEFFICIENT, "from 0 to 1000")?;
        }
        let speeds = -MAX_TANGENT_SPEED..=MAX_TANGENT_SPEED;
        let either_way = "within 10 km/s (1e4 m/s) either way";
        check_within("tangent speed", self.tangent_speed, speeds, either_way)?;
        Ok(())
    }
}

/// A pair's mixed material, as its contact keeps it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Mixed {
    pub friction: Real,
    pub restitution: Real,
    /// The larger rolling resistance times the larger rolling radius, m.
    pub rolling_resistance: Real,
    pub tangent_speed: Real,
}

/// A world's rule for mixing two surfaces' friction or restitution where they touch: it is
/// given each surface's value and material id (`a`'s value, `a`'s id, `b`'s value, `b`'s
/// id) and answers the pair's. A plain function, so that it cannot reach into the world; an
/// answer that is negative or not a number counts as 0, and one above 1000 as 1000.
pub type MaterialMixer = fn(Real, u64, Real, u64) -> Real;

/// The world's mixers; `None` mixes as this module says by default.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Mixers {
    pub friction: Option<MaterialMixer>,
    pub restitution: Option<MaterialMixer>,
}

/// Two colliders' surfaces mixed for their contact.
pub(crate) fn mix(a: &Collider, b: &Collider, mixers: &Mixers) -> Mixed {
    let (sa, sb) = (a.surface(), b.surface());
    let friction = match mixers.friction {
        Some(mixer) => mixer(sa.friction, sa.material, sb.friction, sb.material),
        None => (sa.friction * sb.friction).sqrt(),
    };
    let restitution = match mixers.restitution {
        Some(mixer) => mixer(sa.restitution, sa.material, sb.restitution, sb.material),
        None => sa.restitution.max(sb.restitution),
    };
    let rolling = sa.rolling_resistance.max(sb.rolling_resistance);
    Mixed {
        // A mixer's answer is the game's: held to what a surface may have.
        friction: sanitized(friction),
        restitution: sanitized(restitution),
        // The rolling radius is how far the shape reaches beyond its core: a circle's or a
        // capsule's radius, a rounded polygon's rounding, 0 for sharp shapes.
        rolling_resistance: if rolling > 0.0 {
            rolling * a.world_shape().radius().max(b.world_shape().radius())
        } else {
            0.0
        },
        tangent_speed: sa.tangent_speed + sb.tangent_speed,
    }
}

/// A mixer's answer made safe for the solver: held to what a surface may have.
fn sanitized(value: Real) -> Real {
    if value.is_finite() && value > 0.0 {
        value.min(MAX_SURFACE_COEFFICIENT)
    } else {
        0.0
    }
}
