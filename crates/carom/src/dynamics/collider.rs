//! Colliders: the shapes a body is made of, each placed in the body's frame with its own
//! material.
//!
//! A body has one or more colliders. Each holds a [`Shape`] (centred on its own centroid), where
//! it sits in the body's frame (an offset and an angle), and its material: density (its share
//! of the body's mass), friction and restitution. Collision works collider by collider: the
//! broadphase holds one box per collider and contacts join pairs of colliders; the body's
//! mass, centre of mass and inertia are summed over its colliders.

use crate::clone_in_place::clone_in_place;
use crate::constants::{CONTACTS_PER_TASK, ITEMS_PER_TASK};
use crate::dynamics::body::{Body, BodyHandle};
use crate::dynamics::filter::CollisionFilter;
use crate::dynamics::surface::Surface;
use crate::error::{CaromError, check_finite, check_finite_vec};
use crate::geometry::aabb::Aabb;
use crate::geometry::checks::check_extent;
use crate::geometry::mass::MassProperties;
use crate::geometry::ray::{Ray, RayHit};
use crate::geometry::shape::{Shape, WorldShape};
use crate::handle_map::{HandleMap, generational_handle};
use crate::heap_bytes::HeapBytes;
use crate::math::{Isometry, Real, Vec2};
use crate::parallel::{for_each_mut, map_zip_mut_into};
use std::ops::Range;

generational_handle!(
    /// A stable reference to a collider in a [`crate::World`]; generational, as [`BodyHandle`].
    ColliderHandle,
    "collider"
);

/// Everything needed to attach a collider to a body; build one with [`ColliderDef::new`] and
/// the chained setters. Values are checked when it is added to a world.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ColliderDef {
    /// The shape, centred on its own centroid.
    pub shape: Shape,
    /// Where the shape's centre sits in the body's frame.
    #[cfg_attr(feature = "serde", serde(default))]
    pub offset: Vec2,
    /// How the shape is turned in the body's frame, radians.
    #[cfg_attr(feature = "serde", serde(default))]
    pub angle: Real,
    /// Mass per unit area, kg/m² (zero adds no mass). A dynamic body needs some mass.
    #[cfg_attr(feature = "serde", serde(default = "one"))]
    pub density: Real,
    /// Coulomb friction coefficient (0 is ice).
    #[cfg_attr(feature = "serde", serde(default = "default_friction"))]
    pub friction: Real,
    /// Bounciness: 0 does not bounce, 1 bounces back at the speed it came.
    #[cfg_attr(feature = "serde", serde(default))]
    pub restitution: Real,
    /// Resistance to rolling (see [`Surface::rolling_resistance`]). Default 0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub rolling_resistance: Real,
    /// How fast the surface moves along itself, m/s (see [`Surface::tangent_speed`]): a
    /// conveyor belt. Default 0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub tangent_speed: Real,
    /// The game's material id, for the world's mixers (see [`Surface::material`]). Default 0.
    #[cfg_attr(feature = "serde", serde(default))]
    pub material: u64,
    /// What it collides with. Default: everything.
    #[cfg_attr(feature = "serde", serde(default))]
    pub filter: CollisionFilter,
    /// Report hard hits on it as [`crate::HitEvent`]s (its contacts approaching faster than
    /// [`crate::WorldSettings::hit_event_threshold`]). Default off: a world where no collider
    /// asks does no work for them.
    #[cfg_attr(feature = "serde", serde(default))]
    pub hit_events: bool,
    /// A sensor: it reports what overlaps it ([`crate::SensorEvent`]) and never collides.
    /// It still adds its density's mass to its body. Queries, ray casts and picking do not
    /// see it. Default off.
    #[cfg_attr(feature = "serde", serde(default))]
    pub sensor: bool,
    /// Its contacts are shown to the world's pre-solve hook ([`crate::World::set_pre_solve`])
    /// each step before they are solved, and the hook may disable them. Default off.
    #[cfg_attr(feature = "serde", serde(default))]
    pub pre_solve: bool,
}

/// The default friction coefficient.
pub(crate) const DEFAULT_FRICTION: Real = 0.6;

/// 1, the default density and gravity scale (for serde's defaults).
#[cfg(feature = "serde")]
pub(crate) fn one() -> Real {
    1.0
}

/// [`DEFAULT_FRICTION`], for serde's defaults.
#[cfg(feature = "serde")]
fn default_friction() -> Real {
    DEFAULT_FRICTION
}

impl ColliderDef {
    /// A collider with default material (density 1, friction 0.6, no restitution) at the
    /// body's origin.
    pub fn new(shape: Shape) -> Self {
        ColliderDef {
            shape,
            offset: Vec2::zeros(),
            angle: 0.0,
            density: 1.0,
            friction: DEFAULT_FRICTION,
            restitution: 0.0,
            rolling_resistance: 0.0,
            tangent_speed: 0.0,
            material: 0,
            filter: CollisionFilter::DEFAULT,
            hit_events: false,
            sensor: false,
            pre_solve: false,
        }
    }

    /// Places the shape's centre at `offset` in the body's frame.
    pub fn offset(mut self, offset: Vec2) -> Self {
        self.offset = offset;
        self
    }

    /// Turns the shape by `angle` radians in the body's frame.
    pub fn angle(mut self, angle: Real) -> Self {
        self.angle = angle;
        self
    }

    /// Sets the density.
    pub fn density(mut self, density: Real) -> Self {
        self.density = density;
        self
    }

    /// Sets the friction coefficient.
    pub fn friction(mut self, friction: Real) -> Self {
        self.friction = friction;
        self
    }

    /// Sets the restitution.
    pub fn restitution(mut self, restitution: Real) -> Self {
        self.restitution = restitution;
        self
    }

    /// Sets its whole surface: friction, restitution, rolling resistance, tangent speed and
    /// material id.
    pub fn surface(mut self, surface: Surface) -> Self {
        self.friction = surface.friction;
        self.restitution = surface.restitution;
        self.rolling_resistance = surface.rolling_resistance;
        self.tangent_speed = surface.tangent_speed;
        self.material = surface.material;
        self
    }

    /// Its surface, as [`ColliderDef::surface`] sets it.
    pub(crate) fn as_surface(&self) -> Surface {
        Surface {
            friction: self.friction,
            restitution: self.restitution,
            rolling_resistance: self.rolling_resistance,
            tangent_speed: self.tangent_speed,
            material: self.material,
        }
    }

    /// Sets what it collides with.
    pub fn filter(mut self, filter: CollisionFilter) -> Self {
        self.filter = filter;
        self
    }

    /// Asks for hit events on it (see [`ColliderDef::hit_events`]).
    pub fn hit_events(mut self, on: bool) -> Self {
        self.hit_events = on;
        self
    }

    /// Makes it a sensor, or not (see [`ColliderDef::sensor`]).
    pub fn sensor(mut self, on: bool) -> Self {
        self.sensor = on;
        self
    }

    /// Shows its contacts to the pre-solve hook, or not (see [`ColliderDef::pre_solve`]).
    pub fn pre_solve(mut self, on: bool) -> Self {
        self.pre_solve = on;
        self
    }

    /// Checks every value.
    ///
    /// # Errors
    /// A bad shape, a non-finite placement, a density that is not finite or is negative, or
    /// a surface [`Surface::validate`] refuses.
    pub fn validate(&self) -> Result<(), CaromError> {
        self.shape.validate()?;
        check_finite_vec("collider offset", self.offset)?;
        // An offset is part of the body's shape: held to the same size as a shape's points.
        check_extent("collider offset", self.offset.x)?;
        check_extent("collider offset", self.offset.y)?;
        check_finite("collider angle", self.angle)?;
        check_non_negative("density", self.density)?;
        self.as_surface().validate()
    }
}

/// Checks that a coefficient is finite and not negative.
pub(crate) fn check_non_negative(name: &'static str, value: Real) -> Result<Real, CaromError> {
    check_finite(name, value)?;
    if value < 0.0 {
        return Err(CaromError::OutOfRange {
            name,
            expected: "zero or positive",
            value,
        });
    }
    Ok(value)
}

/// A shape attached to a body: its geometry, placement in the body's frame and material, and
/// where it is in the world as of the last step or edit.
#[derive(Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Collider {
    body: BodyHandle,
    /// Where the body sits in the world's body storage, kept current by the world, so the hot
    /// loops reach the body without a handle lookup.
    body_index: u32,
    #[cfg_attr(
        feature = "serde",
        serde(with = "crate::geometry::shape::saved::exact_shape")
    )]
    shape: Shape,
    /// Placement in the body's frame; `None` at the origin, unturned (the common case, which
    /// then costs no transform product).
    local: Option<Isometry>,
    density: Real,
    surface: Surface,
    filter: CollisionFilter,
    hit_events: bool,
    sensor: bool,
    pre_solve: bool,
    world_shape: WorldShape,
    aabb: Aabb,
}

clone_in_place!(Collider {
    body,
    body_index,
    shape,
    local,
    density,
    surface,
    filter,
    hit_events,
    sensor,
    pre_solve,
    world_shape,
    aabb,
});

// Its shape, in its own frame and placed in the world (a polygon of many points holds them
// on the heap); the rest is plain values.
impl HeapBytes for Collider {
    fn heap_bytes(&self) -> usize {
        let Collider {
            body: _,
            body_index: _,
            shape,
            local: _,
            density: _,
            surface: _,
            filter: _,
            hit_events: _,
            sensor: _,
            pre_solve: _,
            world_shape,
            aabb: _,
        } = self;
        shape.heap_bytes() + world_shape.heap_bytes()
    }
}

impl Collider {
    /// A collider of `body` (placed by `body_transform`) from a checked definition.
    pub(crate) fn new(
        body: BodyHandle,
        body_index: usize,
        def: ColliderDef,
        body_transform: &Isometry,
    ) -> Self {
        let local = (def.offset != Vec2::zeros() || def.angle != 0.0)
            .then(|| Isometry::new(def.offset, def.angle));
        let world_shape = WorldShape::new(&def.shape, body_transform);
        let surface = def.as_surface();
        let mut collider = Collider {
            body,
            body_index: body_index as u32,
            shape: def.shape,
            local,
            density: def.density,
            surface,
            filter: def.filter,
            hit_events: def.hit_events,
            sensor: def.sensor,
            pre_solve: def.pre_solve,
            aabb: world_shape.aabb(),
            world_shape,
        };
        collider.place(body_transform);
        collider
    }

    /// The body it belongs to.
    #[inline]
    pub fn body(&self) -> BodyHandle {
        self.body
    }

    /// Where its body sits in the world's body storage.
    #[inline]
    pub(crate) fn body_index(&self) -> usize {
        self.body_index as usize
    }

    /// Notes that its body moved in the world's storage.
    pub(crate) fn set_body_index(&mut self, index: usize) {
        self.body_index = index as u32;
    }

    /// The shape, in its own frame.
    #[inline]
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// Where the shape sits in the body's frame.
    pub fn local_transform(&self) -> Isometry {
        self.local.unwrap_or_else(Isometry::identity)
    }

    /// Mass per unit area, kg/m².
    #[inline]
    pub fn density(&self) -> Real {
        self.density
    }

    /// Coulomb friction coefficient.
    #[inline]
    pub fn friction(&self) -> Real {
        self.surface.friction
    }

    /// Restitution.
    #[inline]
    pub fn restitution(&self) -> Real {
        self.surface.restitution
    }

    /// Its whole surface: friction, restitution, rolling resistance, tangent speed and
    /// material id.
    #[inline]
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// What it collides with.
    #[inline]
    pub fn filter(&self) -> CollisionFilter {
        self.filter
    }

    /// True when hard hits on it are reported (see [`ColliderDef::hit_events`]).
    #[inline]
    pub fn hit_events(&self) -> bool {
        self.hit_events
    }

    /// True when its contacts are shown to the pre-solve hook (see [`ColliderDef::pre_solve`]).
    #[inline]
    pub fn pre_solve(&self) -> bool {
        self.pre_solve
    }

    /// True for a sensor (see [`ColliderDef::sensor`]).
    #[inline]
    pub fn is_sensor(&self) -> bool {
        self.sensor
    }

    /// Sets what it collides with; the world ends contacts it no longer allows.
    pub(crate) fn set_filter(&mut self, filter: CollisionFilter) {
        self.filter = filter;
    }

    /// The shape in world coordinates, as of the last step or edit.
    #[inline]
    pub fn world_shape(&self) -> &WorldShape {
        &self.world_shape
    }

    /// The tight world bounding box, as of the last step or edit.
    #[inline]
    pub fn aabb(&self) -> Aabb {
        self.aabb
    }

    /// Sets its surface, if [`Surface::validate`] accepts it.
    pub(crate) fn set_surface(&mut self, surface: Surface) -> Result<(), CaromError> {
        surface.validate()?;
        self.surface = surface;
        Ok(())
    }

    /// Sets the density; the world recomputes the body's mass.
    pub(crate) fn set_density(&mut self, density: Real) {
        self.density = density;
    }

    /// True when `world_point`, which is `body_point` in the body's frame, lies inside or on
    /// the shape.
    pub(crate) fn contains(&self, world_point: Vec2, body_point: Vec2) -> bool {
        if !self
            .aabb
            .fattened(crate::constants::CONTAINMENT_TOLERANCE)
            .contains_point(world_point)
        {
            return false;
        }
        let local = match &self.local {
            None => body_point,
            Some(local) => local.inverse_transform_vector(&(body_point - local.translation.vector)),
        };
        self.shape.contains_local(local)
    }

    /// A ray given in the body's frame, cast at the shape.
    pub(crate) fn ray_cast_body_frame(&self, ray: &Ray) -> Option<RayHit> {
        match &self.local {
            None => self.shape.ray_cast_local(ray),
            Some(local) => {
                let origin =
                    local.inverse_transform_vector(&(ray.origin - local.translation.vector));
                let shape_ray = Ray::new(origin, local.inverse_transform_vector(&ray.translation));
                let mut hit = self.shape.ray_cast_local(&shape_ray)?;
                hit.point = local.rotation * hit.point + local.translation.vector;
                hit.normal = local.rotation * hit.normal;
                Some(hit)
            }
        }
    }

    /// Mass, centroid (in the body's frame) and inertia about that centroid.
    pub(crate) fn mass_properties(&self) -> Result<MassProperties, CaromError> {
        if self.density == 0.0 {
            self.shape.validate()?;
            return Ok(MassProperties {
                mass: 0.0,
                center: self.local_transform().translation.vector,
                inertia: 0.0,
            });
        }
        let mut props = self.shape.mass_properties(self.density)?;
        if let Some(local) = &self.local {
            props.center = (local * nalgebra::Point2::from(props.center)).coords;
        }
        Ok(props)
    }

    /// The farthest any point of the shape lies from `center` (a point of the body's frame).
    pub(crate) fn reach_from(&self, center: Vec2) -> Real {
        let offset = self.local.map_or(Vec2::zeros(), |l| l.translation.vector);
        if offset == center {
            self.shape.max_extent()
        } else {
            (offset - center).norm() + self.shape.max_extent()
        }
    }

    /// Re-places the world shape and box for a body at `body_transform`.
    pub(crate) fn place(&mut self, body_transform: &Isometry) {
        match &self.local {
            None => self.world_shape.update(&self.shape, body_transform),
            Some(local) => self
                .world_shape
                .update(&self.shape, &(body_transform * local)),
        }
        self.aabb = self.world_shape.aabb();
    }

    /// Places the shape into `world_shape` (reusing its memory) for a body at `body_transform`.
    pub(crate) fn place_shape(&self, world_shape: &mut WorldShape, body_transform: &Isometry) {
        match &self.local {
            None => world_shape.update(&self.shape, body_transform),
            Some(local) => world_shape.update(&self.shape, &(body_transform * local)),
        }
    }
}

/// Places `body`'s colliders where it is, and its box around them all. Every move of a body
/// ends here or in [`place_awake_colliders`], which does the same for the whole awake set.
pub(crate) fn place_colliders(
    body: &mut Body,
    colliders: &mut HandleMap<ColliderHandle, Collider>,
) {
    let transform = body.transform();
    for &handle in body.colliders() {
        if let Some(collider) = colliders.get_mut(handle) {
            collider.place(&transform);
        }
    }
    body.set_aabb(colliders_aabb(body, colliders));
}

/// [`place_colliders`] for every body of the awake set (`awake_bodies`, whose colliders are
/// `awake_colliders`), on all threads: the colliders first, then each body's box. `out`
/// becomes `after` of every awake collider just placed (with its handle and body), in
/// collider order, so what a later stage needs of each is found while it is at hand.
pub(crate) fn place_awake_colliders<T: Send>(
    bodies: &mut HandleMap<BodyHandle, Body>,
    awake_bodies: Range<usize>,
    colliders: &mut HandleMap<ColliderHandle, Collider>,
    awake_colliders: Range<usize>,
    out: &mut Vec<T>,
    after: impl Fn(ColliderHandle, &Collider, &Body) -> T + Sync + Send,
) {
    let all = bodies.as_slice();
    let (handles, placed) = colliders.handles_and_slice_mut();
    map_zip_mut_into(
        &handles[awake_colliders.clone()],
        &mut placed[awake_colliders],
        out,
        CONTACTS_PER_TASK,
        |&handle, collider| {
            let body = &all[collider.body_index()];
            collider.place(&body.transform());
            after(handle, collider, body)
        },
    );
    let colliders = &*colliders;
    for_each_mut(
        &mut bodies.as_mut_slice()[awake_bodies],
        ITEMS_PER_TASK,
        |body| body.set_aabb(colliders_aabb(body, colliders)),
    );
}

/// The box around all of `body`'s colliders, as placed.
fn colliders_aabb(body: &Body, colliders: &HandleMap<ColliderHandle, Collider>) -> Aabb {
    let mut boxes = body
        .colliders()
        .iter()
        .filter_map(|&handle| colliders.get(handle))
        .map(Collider::aabb);
    let first = boxes
        .next()
        .unwrap_or_else(|| Aabb::new(body.position(), body.position()));
    boxes.fold(first, |all, aabb| all.union(&aabb))
}

#[cfg(feature = "serde")]
impl Collider {
    /// Checks a collider read from a saved world (its shape was checked as it was read): its
    /// material and placement are finite, and its placed shape and box are, bit for bit, its
    /// shape placed where its body is (`body_transform`).
    pub(crate) fn check_saved(&self, body_transform: &Isometry) -> Result<(), CaromError> {
        check_non_negative("density", self.density)?;
        self.surface.validate()?;
        if let Some(local) = &self.local {
            check_finite_vec("collider offset", local.translation.vector)?;
            check_finite("collider angle", local.rotation.angle())?;
        }
        let mut placed = WorldShape::new(&self.shape, &Isometry::identity());
        self.place_shape(&mut placed, body_transform);
        if placed != self.world_shape || placed.aabb() != self.aabb {
            return Err(CaromError::bad_save("a collider is not where its body is"));
        }
        Ok(())
    }
}
