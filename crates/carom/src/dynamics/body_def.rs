//! What a body is created from: [`BodyDef`], its kind, placement, velocity, colliders and
//! the material they share, checked when the body is added to a world.

use crate::dynamics::body::BodyKind;
use crate::dynamics::chain::ChainDef;
use crate::dynamics::collider::ColliderDef;
use crate::error::CaromError;
use crate::geometry::shape::Shape;
use crate::math::{Real, Vec2};

/// Everything needed to create a body; build one with [`BodyDef::dynamic`],
/// [`BodyDef::static_body`] or [`BodyDef::kinematic`] and the chained setters.
///
/// Values are checked when the body is added to a world.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct BodyDef {
    /// How the body moves.
    pub kind: BodyKind,
    /// What it is made of: one collider or more, each a shape with its placement and material.
    pub colliders: Vec<ColliderDef>,
    /// World position of the body's origin.
    #[cfg_attr(feature = "serde", serde(default))]
    pub position: Vec2,
    /// Rotation in radians, counter-clockwise.
    #[cfg_attr(feature = "serde", serde(default))]
    pub angle: Real,
    /// Linear velocity in m/s.
    #[cfg_attr(feature = "serde", serde(default))]
    pub linear_velocity: Vec2,
    /// Angular velocity in rad/s, counter-clockwise.
    #[cfg_attr(feature = "serde", serde(default))]
    pub angular_velocity: Real,
    /// Multiplies the world's gravity for this body.
    #[cfg_attr(feature = "serde", serde(default = "crate::dynamics::collider::one"))]
    pub gravity_scale: Real,
    /// Linear drag coefficient, 1/s.
    #[cfg_attr(feature = "serde", serde(default))]
    pub linear_damping: Real,
    /// Angular drag coefficient, 1/s.
    #[cfg_attr(feature = "serde", serde(default))]
    pub angular_damping: Real,
    /// Fast body that must not pass through other moving bodies either.
    #[cfg_attr(feature = "serde", serde(default))]
    pub bullet: bool,
    /// Free for the user (an id into game data, a colour...).
    #[cfg_attr(feature = "serde", serde(default))]
    pub user_tag: u64,
    /// Whether a dynamic body starts awake. One that starts asleep (at rest, in an island of
    /// its own) costs nothing per step until a moving body touches it or it is woken, even in
    /// a world that does not put bodies to sleep: a pile placed at rest stays out of the solver
    /// until something hits it. Ignored for static and kinematic bodies.
    #[cfg_attr(feature = "serde", serde(default = "crate::dynamics::body_def::yes"))]
    pub awake: bool,
    /// The speed of its fastest point below which a dynamic body counts as resting, m/s:
    /// its island sleeps once every body in it has rested for [`crate::TIME_TO_SLEEP`].
    /// Default [`crate::SLEEP_THRESHOLD`] (Box2D's `sleepThreshold`, also per body).
    #[cfg_attr(
        feature = "serde",
        serde(default = "crate::dynamics::body_def::sleep_threshold")
    )]
    pub sleep_threshold: Real,
    /// How far a dynamic body must move in a step, as a fraction of its smallest extent, to
    /// be swept by continuous collision (Box2D's safety factor, also per body). Lower sweeps
    /// more bodies, sooner; [`Real::INFINITY`] never sweeps this one. Default
    /// [`crate::SWEEP_THRESHOLD`].
    #[cfg_attr(
        feature = "serde",
        serde(default = "crate::dynamics::body_def::sweep_threshold")
    )]
    pub sweep_threshold: Real,
    /// A dynamic body that never turns, whatever pushes it (Box2D's angular motion lock): a
    /// character standing upright. Default false.
    #[cfg_attr(feature = "serde", serde(default))]
    pub fixed_rotation: bool,
}

/// [`crate::SLEEP_THRESHOLD`], the default of [`BodyDef::sleep_threshold`] in saved
/// definitions.
#[cfg(feature = "serde")]
pub(crate) fn sleep_threshold() -> Real {
    crate::constants::SLEEP_THRESHOLD
}

/// [`crate::SWEEP_THRESHOLD`], the default of [`BodyDef::sweep_threshold`] in saved
/// definitions.
#[cfg(feature = "serde")]
pub(crate) fn sweep_threshold() -> Real {
    crate::constants::SWEEP_THRESHOLD
}

/// `true`, the default of [`BodyDef::awake`] in saved definitions.
#[cfg(feature = "serde")]
fn yes() -> bool {
    true
}

impl BodyDef {
    /// A body of the given kind made of one shape at its origin, with default material
    /// (density 1, friction 0.6, no restitution), no drag, at the world origin at rest.
    pub fn new(kind: BodyKind, shape: Shape) -> Self {
        BodyDef {
            kind,
            colliders: vec![ColliderDef::new(shape)],
            position: Vec2::zeros(),
            angle: 0.0,
            linear_velocity: Vec2::zeros(),
            angular_velocity: 0.0,
            gravity_scale: 1.0,
            linear_damping: 0.0,
            angular_damping: 0.0,
            bullet: false,
            user_tag: 0,
            awake: true,
            sleep_threshold: crate::constants::SLEEP_THRESHOLD,
            sweep_threshold: crate::constants::SWEEP_THRESHOLD,
            fixed_rotation: false,
        }
    }

    /// A dynamic body.
    pub fn dynamic(shape: Shape) -> Self {
        Self::new(BodyKind::Dynamic, shape)
    }

    /// A static body.
    pub fn static_body(shape: Shape) -> Self {
        Self::new(BodyKind::Static, shape)
    }

    /// A kinematic body.
    pub fn kinematic(shape: Shape) -> Self {
        Self::new(BodyKind::Kinematic, shape)
    }

    /// A static body made of a chain's links; see [`ChainDef`].
    ///
    /// # Errors
    /// A chain [`ChainDef::segments`] refuses.
    pub fn static_chain(chain: &ChainDef) -> Result<Self, CaromError> {
        let mut def = Self::static_body(Shape::circle(1.0));
        def.colliders = chain.colliders()?;
        Ok(def)
    }

    /// Adds another collider.
    pub fn collider(mut self, collider: ColliderDef) -> Self {
        self.colliders.push(collider);
        self
    }

    /// Sets the position of the body's origin.
    pub fn position(mut self, position: Vec2) -> Self {
        self.position = position;
        self
    }

    /// Sets the angle in radians.
    pub fn angle(mut self, angle: Real) -> Self {
        self.angle = angle;
        self
    }

    /// Sets the linear velocity.
    pub fn linear_velocity(mut self, velocity: Vec2) -> Self {
        self.linear_velocity = velocity;
        self
    }

    /// Sets the angular velocity.
    pub fn angular_velocity(mut self, velocity: Real) -> Self {
        self.angular_velocity = velocity;
        self
    }

    /// Sets the density of every collider so far.
    pub fn density(mut self, density: Real) -> Self {
        for collider in &mut self.colliders {
            collider.density = density;
        }
        self
    }

    /// Sets the friction coefficient of every collider so far.
    pub fn friction(mut self, friction: Real) -> Self {
        for collider in &mut self.colliders {
            collider.friction = friction;
        }
        self
    }

    /// Sets the restitution of every collider so far.
    pub fn restitution(mut self, restitution: Real) -> Self {
        for collider in &mut self.colliders {
            collider.restitution = restitution;
        }
        self
    }

    /// Sets the whole surface of every collider so far (see [`crate::Surface`]).
    pub fn surface(mut self, surface: crate::Surface) -> Self {
        self.colliders = self
            .colliders
            .into_iter()
            .map(|collider| collider.surface(surface))
            .collect();
        self
    }

    /// Sets what every collider collides with.
    pub fn filter(mut self, filter: crate::CollisionFilter) -> Self {
        for collider in &mut self.colliders {
            collider.filter = filter;
        }
        self
    }

    /// Asks for hit events on every collider so far (see [`ColliderDef::hit_events`]).
    pub fn hit_events(mut self, on: bool) -> Self {
        for collider in &mut self.colliders {
            collider.hit_events = on;
        }
        self
    }

    /// Makes every collider so far a sensor, or not (see [`ColliderDef::sensor`]).
    pub fn sensor(mut self, on: bool) -> Self {
        for collider in &mut self.colliders {
            collider.sensor = on;
        }
        self
    }

    /// Shows the contacts of every collider so far to the pre-solve hook, or not (see
    /// [`ColliderDef::pre_solve`]).
    pub fn pre_solve(mut self, on: bool) -> Self {
        for collider in &mut self.colliders {
            collider.pre_solve = on;
        }
        self
    }

    /// Sets the gravity scale.
    pub fn gravity_scale(mut self, scale: Real) -> Self {
        self.gravity_scale = scale;
        self
    }

    /// Sets the linear and angular drag coefficients.
    pub fn damping(mut self, linear: Real, angular: Real) -> Self {
        self.linear_damping = linear;
        self.angular_damping = angular;
        self
    }

    /// Marks the body as a bullet.
    pub fn bullet(mut self, bullet: bool) -> Self {
        self.bullet = bullet;
        self
    }

    /// Sets whether a dynamic body starts awake (see [`BodyDef::awake`]).
    pub fn awake(mut self, awake: bool) -> Self {
        self.awake = awake;
        self
    }

    /// Sets the user tag.
    pub fn user_tag(mut self, tag: u64) -> Self {
        self.user_tag = tag;
        self
    }

    /// Sets the speed below which the body counts as resting (see
    /// [`BodyDef::sleep_threshold`]).
    pub fn sleep_threshold(mut self, threshold: Real) -> Self {
        self.sleep_threshold = threshold;
        self
    }

    /// Sets the fraction of its smallest extent it must move in a step to be swept (see
    /// [`BodyDef::sweep_threshold`]).
    pub fn sweep_threshold(mut self, fraction: Real) -> Self {
        self.sweep_threshold = fraction;
        self
    }

    /// Keeps a dynamic body from turning (see [`BodyDef::fixed_rotation`]).
    pub fn fixed_rotation(mut self, fixed: bool) -> Self {
        self.fixed_rotation = fixed;
        self
    }
}
