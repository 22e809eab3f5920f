//! The components of a collider: its shape, material and filter. A [`Collider`] on an entity
//! with a [`crate::RigidBody`] belongs to that body; on a child of one, to the parent, placed
//! at the child's `Transform`; on an entity with neither, to a static body the plugin gives it.

use crate::convert::to_carom;
use bevy::ecs::component::Component;
use bevy::math::Vec2;
use carom::{CaromError, ChainDef, ColliderDef, ColliderHandle, Real, Shape};

/// A collider's shape: any of carom's shapes, or a chain of segments (terrain). Sizes are
/// full widths and heights, in metres.
#[derive(Component, Debug, Clone, PartialEq)]
pub struct Collider(pub(crate) ColliderShape);

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ColliderShape {
    /// One carom collider.
    Shape(Shape),
    /// One carom collider for each link.
    Chain(ChainDef),
}

impl Collider {
    /// A disc of `radius`.
    pub fn circle(radius: f32) -> Self {
        Collider(ColliderShape::Shape(Shape::circle(radius as Real)))
    }

    /// A box `width` by `height`, centred on the entity.
    pub fn rectangle(width: f32, height: f32) -> Self {
        let (hw, hh) = (0.5 * width as Real, 0.5 * height as Real);
        Collider(ColliderShape::Shape(Shape::rect(hw, hh)))
    }

    /// A box `width` by `height` with corners rounded to `radius` (outside the box).
    pub fn rounded_rectangle(width: f32, height: f32, radius: f32) -> Self {
        let (hw, hh) = (0.5 * width as Real, 0.5 * height as Real);
        Collider(ColliderShape::Shape(Shape::rounded_rect(
            hw,
            hh,
            radius as Real,
        )))
    }

    /// A stadium: the segment from `a` to `b` grown by `radius`.
    pub fn capsule(a: Vec2, b: Vec2, radius: f32) -> Self {
        Collider(ColliderShape::Shape(Shape::capsule(
            to_carom(a),
            to_carom(b),
            radius as Real,
        )))
    }

    /// A line segment from `a` to `b`, with no inside: for static geometry.
    pub fn segment(a: Vec2, b: Vec2) -> Self {
        Collider(ColliderShape::Shape(Shape::segment(
            to_carom(a),
            to_carom(b),
        )))
    }

    /// The convex polygon through `points` (at most carom's polygon limit, counter-clockwise
    /// or not).
    ///
    /// # Errors
    /// Too few or too many points, or points on a line.
    pub fn polygon(points: &[Vec2]) -> Result<Self, CaromError> {
        let points: Vec<_> = points.iter().map(|&p| to_carom(p)).collect();
        Ok(Collider(ColliderShape::Shape(Shape::polygon(&points)?)))
    }

    /// A regular polygon of `sides` around a circle of `radius`.
    ///
    /// # Errors
    /// Fewer than three sides, or more than a polygon holds.
    pub fn regular_polygon(sides: usize, radius: f32) -> Result<Self, CaromError> {
        Ok(Collider(ColliderShape::Shape(Shape::regular(
            sides,
            radius as Real,
        )?)))
    }

    /// An open chain of segments through `points`: smooth terrain that bodies slide along
    /// without catching on the joints between links.
    pub fn chain(points: &[Vec2]) -> Self {
        Self::from_chain(ChainDef::open(
            points.iter().map(|&p| to_carom(p)).collect::<Vec<_>>(),
        ))
    }

    /// A closed loop of segments through `points`.
    pub fn closed_chain(points: &[Vec2]) -> Self {
        Self::from_chain(ChainDef::closed(
            points.iter().map(|&p| to_carom(p)).collect::<Vec<_>>(),
        ))
    }

    /// A collider of any carom shape.
    pub fn from_shape(shape: Shape) -> Self {
        Collider(ColliderShape::Shape(shape))
    }

    /// A chain with carom's full description (ghost points, a surface for each link, a
    /// filter). The chain's own surfaces and filter are used, not the entity's
    /// [`ColliderMaterial`] and [`CollisionFilter`].
    pub fn from_chain(chain: ChainDef) -> Self {
        Collider(ColliderShape::Chain(chain))
    }

    /// The shape, unless the collider is a chain.
    pub fn shape(&self) -> Option<&Shape> {
        match &self.0 {
            ColliderShape::Shape(shape) => Some(shape),
            ColliderShape::Chain(_) => None,
        }
    }

    /// carom's definitions of the colliders this makes, placed at `offset` and `angle` in its
    /// body.
    pub(crate) fn defs(
        &self,
        parts: &ColliderParts,
        offset: Vec2,
        angle: f32,
    ) -> Result<Vec<ColliderDef>, CaromError> {
        match &self.0 {
            ColliderShape::Shape(shape) => {
                let mut def = ColliderDef::new(shape.clone());
                def.offset = to_carom(offset);
                def.angle = angle as Real;
                parts.material.apply(&mut def);
                def.filter = parts.filter.into();
                def.sensor = parts.sensor;
                def.hit_events = parts.hit_events;
                Ok(vec![def])
            }
            ColliderShape::Chain(chain) => {
                if offset != Vec2::ZERO || angle != 0.0 {
                    // A chain's links are in its body's frame; place the chain's points there.
                    let placed = placed_chain(chain, offset, angle);
                    return placed.colliders();
                }
                chain.colliders()
            }
        }
    }
}

/// `chain` with its points turned by `angle` and moved by `offset`.
fn placed_chain(chain: &ChainDef, offset: Vec2, angle: f32) -> ChainDef {
    let rotation = carom::rotation(angle as Real);
    let offset = to_carom(offset);
    let place = |p: carom::Vec2| rotation * p + offset;
    let mut placed = chain.clone();
    for point in &mut placed.points {
        *point = place(*point);
    }
    if let Some((before, after)) = placed.ghosts {
        placed.ghosts = Some((place(before), place(after)));
    }
    placed
}

/// What a collider's definition takes from its entity's other components.
pub(crate) struct ColliderParts {
    pub material: ColliderMaterial,
    pub filter: CollisionFilter,
    pub sensor: bool,
    pub hit_events: bool,
}

/// A collider's mass and surface.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct ColliderMaterial {
    /// kg/m²; 0 for a massless collider.
    pub density: f32,
    /// Coulomb friction coefficient (0 is ice).
    pub friction: f32,
    /// Bounciness: 0 does not bounce, 1 bounces back at the speed it came.
    pub restitution: f32,
    /// Resistance to rolling (a ball on it slows as if this friction acted at its rim).
    pub rolling_resistance: f32,
    /// How fast the surface moves along itself, m/s: a conveyor belt.
    pub tangent_speed: f32,
}

impl Default for ColliderMaterial {
    fn default() -> Self {
        let def = ColliderDef::new(Shape::circle(1.0));
        ColliderMaterial {
            density: def.density as f32,
            friction: def.friction as f32,
            restitution: def.restitution as f32,
            rolling_resistance: def.rolling_resistance as f32,
            tangent_speed: def.tangent_speed as f32,
        }
    }
}

impl ColliderMaterial {
    fn apply(&self, def: &mut ColliderDef) {
        def.density = self.density as Real;
        def.friction = self.friction as Real;
        def.restitution = self.restitution as Real;
        def.rolling_resistance = self.rolling_resistance as Real;
        def.tangent_speed = self.tangent_speed as Real;
    }

    /// The material of a carom collider.
    pub(crate) fn of(collider: &carom::Collider) -> Self {
        let surface = collider.surface();
        ColliderMaterial {
            density: collider.density() as f32,
            friction: surface.friction as f32,
            restitution: surface.restitution as f32,
            rolling_resistance: surface.rolling_resistance as f32,
            tangent_speed: surface.tangent_speed as f32,
        }
    }
}

/// Which colliders meet: two do when each one's category is in the other's mask, unless they
/// share a group (positive: always meet, negative: never).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct CollisionFilter {
    /// What this collider is: usually one bit.
    pub category: u64,
    /// The categories it meets.
    pub mask: u64,
    /// Its group, 0 for none.
    pub group: i32,
}

impl Default for CollisionFilter {
    fn default() -> Self {
        carom::CollisionFilter::DEFAULT.into()
    }
}

impl From<CollisionFilter> for carom::CollisionFilter {
    fn from(f: CollisionFilter) -> Self {
        carom::CollisionFilter {
            category: f.category,
            mask: f.mask,
            group: f.group,
        }
    }
}

impl From<carom::CollisionFilter> for CollisionFilter {
    fn from(f: carom::CollisionFilter) -> Self {
        CollisionFilter {
            category: f.category,
            mask: f.mask,
            group: f.group,
        }
    }
}

/// Makes a collider a sensor: it pushes nothing and reports what enters and leaves it
/// ([`crate::SensorEntered`], [`crate::SensorExited`]).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sensor;

/// Makes a collider report hard impacts ([`crate::Hit`]): contacts that begin faster than the
/// world's hit speed.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct HitEvents;

/// The carom colliders an entity's [`Collider`] made (a chain makes one for each link), and
/// their body's entity; added by the plugin.
#[derive(Component, Debug, Clone, PartialEq, Eq)]
#[component(immutable)]
pub struct CaromCollider {
    pub(crate) handles: Vec<ColliderHandle>,
    pub(crate) body: bevy::ecs::entity::Entity,
}

impl CaromCollider {
    /// The colliders' handles in the [`crate::CaromWorld`].
    pub fn handles(&self) -> &[ColliderHandle] {
        &self.handles
    }

    /// The entity of the body they belong to.
    pub fn body(&self) -> bevy::ecs::entity::Entity {
        self.body
    }
}
