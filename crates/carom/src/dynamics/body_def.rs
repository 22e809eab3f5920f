//! What a body is created from: [`BodyDef`], its kind, placement, velocity, colliders and
//! the material they share ([`ColliderSettings`]), checked when the body is added to a world.

use crate::dynamics::body::BodyKind;
use crate::dynamics::chain::ChainDef;
use crate::dynamics::collider::ColliderDef;
use crate::dynamics::filter::CollisionFilter;
use crate::dynamics::surface::Surface;
use crate::error::CaromError;
use crate::geometry::shape::Shape;
use crate::math::{Real, Vec2};

/// Everything needed to create a body; build one with [`BodyDef::dynamic`],
/// [`BodyDef::static_body`] or [`BodyDef::kinematic`] and the chained setters.
///
/// The setters give the same body in any order. Those of the material ([`BodyDef::density`],
/// [`BodyDef::friction`], [`BodyDef::surface`], [`BodyDef::filter`], ...) set it for every
/// collider of the body, those added with [`BodyDef::collider`] before and after alike
/// ([`BodyDef::every_collider`] keeps them); to give colliders different materials, set them
/// on each [`ColliderDef`] and not on the body.
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
    /// The material set on the body, which every collider takes, whenever it was added.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "ColliderSettings::is_empty")
    )]
    pub every_collider: ColliderSettings,
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
    /// Its contacts look a step ahead even in a world that does not
    /// ([`crate::WorldSettings::look_ahead`]): an impact of it at any speed is stopped at the
    /// surface, where a world without look-ahead lets a fast body sink in for a step. With
    /// continuous collision only. Default false: as the world does.
    #[cfg_attr(feature = "serde", serde(default))]
    pub look_ahead: bool,
    /// A dynamic body that never turns, whatever pushes it (Box2D's angular motion lock): a
    /// character standing upright. Default false.
    #[cfg_attr(feature = "serde", serde(default))]
    pub fixed_rotation: bool,
}

/// What a body sets for every one of its colliders: each setting given replaces the colliders'
/// own; those left `None` leave them as they are.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct ColliderSettings {
    /// [`ColliderDef::density`].
    pub density: Option<Real>,
    /// [`ColliderDef::friction`].
    pub friction: Option<Real>,
    /// [`ColliderDef::restitution`].
    pub restitution: Option<Real>,
    /// [`ColliderDef::rolling_resistance`].
    pub rolling_resistance: Option<Real>,
    /// [`ColliderDef::tangent_speed`].
    pub tangent_speed: Option<Real>,
    /// [`ColliderDef::material`].
    pub material: Option<u64>,
    /// [`ColliderDef::filter`].
    pub filter: Option<CollisionFilter>,
    /// [`ColliderDef::hit_events`].
    pub hit_events: Option<bool>,
    /// [`ColliderDef::sensor`].
    pub sensor: Option<bool>,
    /// [`ColliderDef::pre_solve`].
    pub pre_solve: Option<bool>,
}

impl ColliderSettings {
    /// Whether it sets nothing.
    pub fn is_empty(&self) -> bool {
        *self == ColliderSettings::default()
    }

    /// Gives `collider` every setting this has.
    pub fn apply(&self, collider: &mut ColliderDef) {
        fn set<T: Copy>(given: Option<T>, field: &mut T) {
            if let Some(value) = given {
                *field = value;
            }
        }
        set(self.density, &mut collider.density);
        set(self.friction, &mut collider.friction);
        set(self.restitution, &mut collider.restitution);
        set(self.rolling_resistance, &mut collider.rolling_resistance);
        set(self.tangent_speed, &mut collider.tangent_speed);
        set(self.material, &mut collider.material);
        set(self.filter, &mut collider.filter);
        set(self.hit_events, &mut collider.hit_events);
        set(self.sensor, &mut collider.sensor);
        set(self.pre_solve, &mut collider.pre_solve);
    }
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
            every_collider: ColliderSettings::default(),
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
            look_ahead: false,
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

    /// Adds another collider; it takes the material set on the body (see
    /// [`BodyDef::every_collider`]).
    pub fn collider(mut self, mut collider: ColliderDef) -> Self {
        self.every_collider.apply(&mut collider);
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

    /// Sets the linear velocity, within [`crate::MAX_SPEED`] on each axis (checked when the
    /// body is added).
    pub fn linear_velocity(mut self, velocity: Vec2) -> Self {
        self.linear_velocity = velocity;
        self
    }

    /// Sets the angular velocity, within [`crate::MAX_ANGULAR_SPEED`] (checked when the body
    /// is added).
    pub fn angular_velocity(mut self, velocity: Real) -> Self {
        self.angular_velocity = velocity;
        self
    }

    /// Sets `settings` for every collider, those added before and after.
    fn for_every_collider(mut self, settings: impl FnOnce(&mut ColliderSettings)) -> Self {
        settings(&mut self.every_collider);
        for collider in &mut self.colliders {
            self.every_collider.apply(collider);
        }
        self
    }

    /// Sets the density of every collider.
    pub fn density(self, density: Real) -> Self {
        self.for_every_collider(|every| every.density = Some(density))
    }

    /// Sets the friction coefficient of every collider.
    pub fn friction(self, friction: Real) -> Self {
        self.for_every_collider(|every| every.friction = Some(friction))
    }

    /// Sets the restitution of every collider.
    pub fn restitution(self, restitution: Real) -> Self {
        self.for_every_collider(|every| every.restitution = Some(restitution))
    }

    /// Sets the whole surface of every collider (see [`Surface`]).
    pub fn surface(self, surface: Surface) -> Self {
        self.for_every_collider(|every| {
            every.friction = Some(surface.friction);
            every.restitution = Some(surface.restitution);
            every.rolling_resistance = Some(surface.rolling_resistance);
            every.tangent_speed = Some(surface.tangent_speed);
            every.material = Some(surface.material);
        })
    }

    /// Sets what every collider collides with.
    pub fn filter(self, filter: CollisionFilter) -> Self {
        self.for_every_collider(|every| every.filter = Some(filter))
    }

    /// Asks for hit events on every collider, or not (see [`ColliderDef::hit_events`]).
    pub fn hit_events(self, on: bool) -> Self {
        self.for_every_collider(|every| every.hit_events = Some(on))
    }

    /// Makes every collider a sensor, or not (see [`ColliderDef::sensor`]).
    pub fn sensor(self, on: bool) -> Self {
        self.for_every_collider(|every| every.sensor = Some(on))
    }

    /// Shows the contacts of every collider to the pre-solve hook, or not (see
    /// [`ColliderDef::pre_solve`]).
    pub fn pre_solve(self, on: bool) -> Self {
        self.for_every_collider(|every| every.pre_solve = Some(on))
    }

    /// Sets the gravity scale, within [`crate::MAX_GRAVITY_SCALE`] either way (checked when
    /// the body is added).
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

    /// Makes its contacts look a step ahead even in a world that does not (see
    /// [`BodyDef::look_ahead`]).
    pub fn look_ahead(mut self, look_ahead: bool) -> Self {
        self.look_ahead = look_ahead;
        self
    }

    /// Keeps a dynamic body from turning (see [`BodyDef::fixed_rotation`]).
    pub fn fixed_rotation(mut self, fixed: bool) -> Self {
        self.fixed_rotation = fixed;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    fn wheel() -> ColliderDef {
        ColliderDef::new(Shape::circle(0.3))
            .offset(vec2(1.0, 0.0))
            .density(9.0)
            .restitution(0.7)
    }

    #[test]
    fn the_setters_give_the_same_body_in_any_order() {
        let surface = Surface {
            friction: 0.1,
            rolling_resistance: 0.05,
            ..Surface::default()
        };
        let filter = CollisionFilter {
            group: -3,
            ..CollisionFilter::default()
        };
        let first = BodyDef::dynamic(Shape::rect(1.0, 0.5))
            .density(2.0)
            .surface(surface)
            .filter(filter)
            .sensor(true)
            .collider(wheel())
            .position(vec2(1.0, 2.0));
        let last = BodyDef::dynamic(Shape::rect(1.0, 0.5))
            .position(vec2(1.0, 2.0))
            .collider(wheel())
            .sensor(true)
            .filter(filter)
            .surface(surface)
            .density(2.0);
        assert_eq!(first, last);
        for collider in &first.colliders {
            assert_eq!(collider.density, 2.0);
            assert_eq!(collider.friction, 0.1);
            assert_eq!(collider.rolling_resistance, 0.05);
            assert_eq!(collider.filter.group, -3);
            assert!(collider.sensor);
        }
        // What the body leaves unset stays each collider's own.
        assert_eq!(first.colliders[1].offset, vec2(1.0, 0.0));
        assert_eq!(first.colliders[0].restitution, 0.0);
        assert_eq!(
            first.colliders[1].restitution, 0.0,
            "the surface sets restitution"
        );
        let alone = BodyDef::dynamic(Shape::rect(1.0, 0.5)).collider(wheel());
        assert_eq!(alone.colliders[1].density, 9.0);
        assert_eq!(alone.colliders[1].restitution, 0.7);
        assert!(alone.every_collider.is_empty());
    }

    #[test]
    fn a_collider_pushed_directly_takes_the_body_s_material_when_added() {
        let mut def = BodyDef::dynamic(Shape::rect(0.5, 0.5)).density(4.0);
        def.colliders.push(wheel());
        let mut world = crate::World::new();
        let handle = world.add_body(def).expect("a valid body");
        let body = world.body(handle).expect("added");
        for &collider in body.colliders() {
            let collider = world.collider(collider).expect("attached");
            assert_eq!(collider.density(), 4.0);
        }
    }
}
