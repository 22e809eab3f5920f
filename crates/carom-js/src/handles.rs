//! The handles JavaScript holds: `Body`, `Collider`, `Joint`. Each names its world by key and
//! itself by carom's generational handle, and checks both on every call: a handle whose world
//! was freed, or whose object was removed, answers with an error that says which.

use crate::convert::{array_of, error, finite, object, vec2, vec2_out};
use crate::defs::{body_kind, body_kind_name, collision_filter};
use crate::registry::{self, WorldKey};
use carom::{BodyHandle, BodyMut, CaromError, ColliderHandle, JointHandle, Shape, World};
use js_sys::{Array, Function, Reflect};
use wasm_bindgen::prelude::*;

/// Which kind of handle a hidden key is.
#[derive(Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub(crate) enum Tag {
    Body = 1,
    Collider = 2,
    Joint = 3,
}

/// A handle's hidden key: its world's parts, its tag, its own parts.
fn key(world: WorldKey, tag: Tag, index: u32, generation: u32) -> Vec<u32> {
    let [w, g] = world.parts();
    vec![w, g, tag as u32, index, generation]
}

/// The world and parts of a handle found inside an options object (`excludeBody`), where the
/// binding cannot check the class itself.
pub(crate) fn key_of(
    value: &JsValue,
    tag: Tag,
    what: &str,
) -> Result<(WorldKey, u32, u32), JsError> {
    let expected = match tag {
        Tag::Body => "a Body",
        Tag::Collider => "a Collider",
        Tag::Joint => "a Joint",
    };
    let wrong = || error(what, format!("expected {expected}"));
    let method = Reflect::get(value, &JsValue::from_str("__caromKey"))
        .ok()
        .and_then(|m| m.dyn_into::<Function>().ok())
        .ok_or_else(wrong)?;
    let parts: Vec<u32> = method
        .call0(value)
        .ok()
        .map(|parts| {
            Array::from(&parts)
                .iter()
                .filter_map(|p| p.as_f64())
                .map(|p| p as u32)
                .collect()
        })
        .ok_or_else(wrong)?;
    match parts[..] {
        [w, g, t, index, generation] if t == tag as u32 => {
            Ok((WorldKey::from_parts([w, g]), index, generation))
        }
        _ => Err(wrong()),
    }
}

/// An error from carom, as a JavaScript one.
pub(crate) fn carom_error(e: CaromError) -> JsError {
    JsError::new(&e.to_string())
}

/// What every handle has: its `id`, `isValid()`, `equals()`, and the hidden key by which one
/// passed inside an options object is read.
macro_rules! handle_basics {
    ($handle:ident, $what:literal, $tag:expr) => {
        #[wasm_bindgen]
        impl $handle {
            #[doc = concat!("Its index in its world: unique among the world's ", $what, "s while")]
            #[doc = concat!("it lives (a ", $what, " added after it is removed may get it).")]
            #[wasm_bindgen(getter)]
            pub fn id(&self) -> u32 {
                self.handle.index()
            }

            /// Whether it is still in its world: not removed, its world not freed.
            #[wasm_bindgen(js_name = isValid)]
            pub fn is_valid(&self) -> bool {
                self.read(|_, _| ()).is_ok()
            }

            #[doc = concat!("Whether `other` is the same ", $what, " (two handles to one ", $what)]
            #[doc = "are different objects)."]
            pub fn equals(&self, other: &$handle) -> bool {
                self.world == other.world && self.handle == other.handle
            }

            /// Its hidden key, read when it is passed inside an options object (`excludeBody`).
            #[wasm_bindgen(js_name = __caromKey, skip_typescript)]
            pub fn carom_key(&self) -> Vec<u32> {
                key(
                    self.world,
                    $tag,
                    self.handle.index(),
                    self.handle.generation(),
                )
            }
        }
    };
}

handle_basics!(Body, "body", Tag::Body);
handle_basics!(Collider, "collider", Tag::Collider);
handle_basics!(Joint, "joint", Tag::Joint);

/// A rigid body in a world. Get one from `World.createBody` (or a query, an event, a scene's
/// name); it stays valid until removed or until its world is freed.
#[wasm_bindgen]
#[derive(Clone, Copy)]
pub struct Body {
    pub(crate) world: WorldKey,
    pub(crate) handle: BodyHandle,
}

impl Body {
    pub(crate) fn new(world: WorldKey, handle: BodyHandle) -> Body {
        Body { world, handle }
    }

    fn read<R>(&self, f: impl FnOnce(&carom::Body, &World) -> R) -> Result<R, JsError> {
        registry::with(self.world, "this body's world", |sim| {
            let world = sim.world();
            let body = world
                .body(self.handle)
                .ok_or_else(|| JsError::new("this body was removed from its world"))?;
            Ok(f(body, world))
        })
    }

    fn write<R>(&self, f: impl FnOnce(BodyMut<'_>) -> Result<R, CaromError>) -> Result<R, JsError> {
        registry::with(self.world, "this body's world", |sim| {
            let body = sim
                .world_mut()
                .body_mut(self.handle)
                .ok_or_else(|| JsError::new("this body was removed from its world"))?;
            f(body).map_err(carom_error)
        })
    }
}

#[wasm_bindgen]
impl Body {
    /// `"dynamic"`, `"static"` or `"kinematic"`.
    #[wasm_bindgen(js_name = "type", unchecked_return_type = "BodyType")]
    pub fn kind(&self) -> Result<String, JsError> {
        self.read(|b, _| body_kind_name(b.kind()).to_string())
    }

    /// Makes it dynamic, static or kinematic.
    #[wasm_bindgen(js_name = setType)]
    pub fn set_kind(
        &self,
        #[wasm_bindgen(unchecked_param_type = "BodyType")] kind: &str,
    ) -> Result<(), JsError> {
        let kind = body_kind(kind, "body type")?;
        self.write(|mut b| b.set_kind(kind))
    }

    /// Where its origin is, m.
    #[wasm_bindgen(unchecked_return_type = "Vec2")]
    pub fn position(&self) -> Result<JsValue, JsError> {
        self.read(|b, _| vec2_out(b.position()))
    }

    /// Its rotation, radians counter-clockwise.
    pub fn angle(&self) -> Result<f64, JsError> {
        self.read(|b, _| b.angle() as f64)
    }

    /// Its centre of mass in world coordinates, m.
    #[wasm_bindgen(js_name = centerOfMass, unchecked_return_type = "Vec2")]
    pub fn center_of_mass(&self) -> Result<JsValue, JsError> {
        self.read(|b, _| vec2_out(b.center_of_mass()))
    }

    /// Its centre of mass's velocity, m/s.
    #[wasm_bindgen(js_name = linearVelocity, unchecked_return_type = "Vec2")]
    pub fn linear_velocity(&self) -> Result<JsValue, JsError> {
        self.read(|b, _| vec2_out(b.linear_velocity()))
    }

    /// Its angular velocity, rad/s counter-clockwise.
    #[wasm_bindgen(js_name = angularVelocity)]
    pub fn angular_velocity(&self) -> Result<f64, JsError> {
        self.read(|b, _| b.angular_velocity() as f64)
    }

    /// The velocity of its point at `point` (world coordinates), m/s.
    #[wasm_bindgen(js_name = velocityAt, unchecked_return_type = "Vec2")]
    pub fn velocity_at(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] point: JsValue,
    ) -> Result<JsValue, JsError> {
        let point = vec2(&point, "point")?;
        self.read(|b, _| vec2_out(b.velocity_at(point)))
    }

    /// `local` (in the body's frame) in world coordinates.
    #[wasm_bindgen(js_name = worldPoint, unchecked_return_type = "Vec2")]
    pub fn world_point(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] local: JsValue,
    ) -> Result<JsValue, JsError> {
        let local = vec2(&local, "point")?;
        self.read(|b, _| vec2_out(b.world_point(local)))
    }

    /// `point` (world coordinates) in the body's frame.
    #[wasm_bindgen(js_name = localPoint, unchecked_return_type = "Vec2")]
    pub fn local_point(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] point: JsValue,
    ) -> Result<JsValue, JsError> {
        let point = vec2(&point, "point")?;
        self.read(|b, _| vec2_out(b.local_point(point)))
    }

    /// Its mass, kg (0 unless dynamic).
    pub fn mass(&self) -> Result<f64, JsError> {
        self.read(|b, _| b.mass() as f64)
    }

    /// Its rotational inertia about its centre of mass, kg·m².
    pub fn inertia(&self) -> Result<f64, JsError> {
        self.read(|b, _| b.inertia() as f64)
    }

    /// Its kinetic energy, J.
    #[wasm_bindgen(js_name = kineticEnergy)]
    pub fn kinetic_energy(&self) -> Result<f64, JsError> {
        self.read(|b, _| b.kinetic_energy() as f64)
    }

    /// Whether it sleeps (costs nothing until touched or woken).
    #[wasm_bindgen(js_name = isSleeping)]
    pub fn is_sleeping(&self) -> Result<bool, JsError> {
        self.read(|b, _| b.is_sleeping())
    }

    /// Its gravity scale.
    #[wasm_bindgen(js_name = gravityScale)]
    pub fn gravity_scale(&self) -> Result<f64, JsError> {
        self.read(|b, _| b.gravity_scale() as f64)
    }

    /// Its colliders.
    pub fn colliders(&self) -> Result<Vec<Collider>, JsError> {
        self.read(|b, _| {
            b.colliders()
                .iter()
                .map(|&c| Collider::new(self.world, c))
                .collect()
        })
    }

    /// The joints that hold it.
    pub fn joints(&self) -> Result<Vec<Joint>, JsError> {
        self.read(|b, world| {
            world
                .joints_of(b.handle())
                .iter()
                .map(|&j| Joint::new(self.world, j))
                .collect()
        })
    }

    /// Moves it to `position` (wakes it).
    #[wasm_bindgen(js_name = setPosition)]
    pub fn set_position(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] position: JsValue,
    ) -> Result<(), JsError> {
        let position = vec2(&position, "position")?;
        self.write(|mut b| b.set_position(position))
    }

    /// Turns it to `angle`, radians (wakes it).
    #[wasm_bindgen(js_name = setAngle)]
    pub fn set_angle(&self, angle: f64) -> Result<(), JsError> {
        let angle = finite(angle, "angle")?;
        self.write(|mut b| b.set_angle(angle))
    }

    /// Sets its linear velocity, m/s (wakes it).
    #[wasm_bindgen(js_name = setLinearVelocity)]
    pub fn set_linear_velocity(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] velocity: JsValue,
    ) -> Result<(), JsError> {
        let velocity = vec2(&velocity, "velocity")?;
        self.write(|mut b| b.set_linear_velocity(velocity))
    }

    /// Sets its angular velocity, rad/s (wakes it).
    #[wasm_bindgen(js_name = setAngularVelocity)]
    pub fn set_angular_velocity(&self, velocity: f64) -> Result<(), JsError> {
        let velocity = finite(velocity, "angular velocity")?;
        self.write(|mut b| b.set_angular_velocity(velocity))
    }

    /// Sets its gravity scale.
    #[wasm_bindgen(js_name = setGravityScale)]
    pub fn set_gravity_scale(&self, scale: f64) -> Result<(), JsError> {
        let scale = finite(scale, "gravity scale")?;
        self.write(|mut b| b.set_gravity_scale(scale))
    }

    /// Sets its linear and angular drag coefficients, 1/s.
    #[wasm_bindgen(js_name = setDamping)]
    pub fn set_damping(&self, linear: f64, angular: f64) -> Result<(), JsError> {
        let linear = finite(linear, "linear damping")?;
        let angular = finite(angular, "angular damping")?;
        self.write(|mut b| b.set_damping(linear, angular))
    }

    /// Makes it a bullet (swept against moving bodies too) or not.
    #[wasm_bindgen(js_name = setBullet)]
    pub fn set_bullet(&self, bullet: bool) -> Result<(), JsError> {
        self.write(|mut b| {
            b.set_bullet(bullet);
            Ok(())
        })
    }

    /// Stops it turning, or lets it turn again.
    #[wasm_bindgen(js_name = setFixedRotation)]
    pub fn set_fixed_rotation(&self, fixed: bool) -> Result<(), JsError> {
        self.write(|mut b| {
            b.set_fixed_rotation(fixed);
            Ok(())
        })
    }

    /// Wakes it (and its island).
    #[wasm_bindgen(js_name = wakeUp)]
    pub fn wake_up(&self) -> Result<(), JsError> {
        self.write(|mut b| {
            b.wake_up();
            Ok(())
        })
    }

    /// Pushes with `force` (N) for the next step, at `point` (world coordinates) or at the
    /// centre of mass when it is left out.
    #[wasm_bindgen(js_name = applyForce)]
    pub fn apply_force(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] force: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2 | undefined")] point: JsValue,
    ) -> Result<(), JsError> {
        let force = vec2(&force, "force")?;
        let point = (!point.is_undefined())
            .then(|| vec2(&point, "point"))
            .transpose()?;
        self.write(|mut b| match point {
            Some(point) => b.apply_force(force, point),
            None => b.apply_force_at_center(force),
        })
    }

    /// Changes its momentum by `impulse` (N·s) now, at `point` (world coordinates) or at the
    /// centre of mass when it is left out.
    #[wasm_bindgen(js_name = applyImpulse)]
    pub fn apply_impulse(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] impulse: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2 | undefined")] point: JsValue,
    ) -> Result<(), JsError> {
        let impulse = vec2(&impulse, "impulse")?;
        let point = (!point.is_undefined())
            .then(|| vec2(&point, "point"))
            .transpose()?;
        self.write(|mut b| match point {
            Some(point) => b.apply_impulse(impulse, point),
            None => b.apply_impulse_at_center(impulse),
        })
    }

    /// Turns with `torque` (N·m) for the next step.
    #[wasm_bindgen(js_name = applyTorque)]
    pub fn apply_torque(&self, torque: f64) -> Result<(), JsError> {
        let torque = finite(torque, "torque")?;
        self.write(|mut b| b.apply_torque(torque))
    }

    /// Changes its angular momentum by `impulse` (N·m·s) now.
    #[wasm_bindgen(js_name = applyAngularImpulse)]
    pub fn apply_angular_impulse(&self, impulse: f64) -> Result<(), JsError> {
        let impulse = finite(impulse, "angular impulse")?;
        self.write(|mut b| b.apply_angular_impulse(impulse))
    }
}

/// A shape on a body, with its material and filter. Get one from `World.createCollider` or
/// `Body.colliders()`.
#[wasm_bindgen]
#[derive(Clone, Copy)]
pub struct Collider {
    pub(crate) world: WorldKey,
    pub(crate) handle: ColliderHandle,
}

impl Collider {
    pub(crate) fn new(world: WorldKey, handle: ColliderHandle) -> Collider {
        Collider { world, handle }
    }

    fn read<R>(&self, f: impl FnOnce(&carom::Collider, &World) -> R) -> Result<R, JsError> {
        registry::with(self.world, "this collider's world", |sim| {
            let world = sim.world();
            let collider = world
                .collider(self.handle)
                .ok_or_else(|| JsError::new("this collider was removed from its world"))?;
            Ok(f(collider, world))
        })
    }

    fn write(
        &self,
        f: impl FnOnce(&mut carom::ColliderMut<'_>) -> Result<(), CaromError>,
    ) -> Result<(), JsError> {
        registry::with(self.world, "this collider's world", |sim| {
            let mut collider = sim
                .world_mut()
                .collider_mut(self.handle)
                .ok_or_else(|| JsError::new("this collider was removed from its world"))?;
            f(&mut collider).map_err(carom_error)
        })
    }
}

#[wasm_bindgen]
impl Collider {
    /// The body it is on.
    pub fn body(&self) -> Result<Body, JsError> {
        self.read(|c, _| Body::new(self.world, c.body()))
    }

    /// `"circle"`, `"capsule"`, `"polygon"`, `"segment"` or `"chainSegment"`.
    #[wasm_bindgen(js_name = shapeType)]
    pub fn shape_type(&self) -> Result<String, JsError> {
        self.read(|c, _| {
            match c.shape() {
                Shape::Circle(_) => "circle",
                Shape::Capsule(_) => "capsule",
                Shape::Polygon(_) => "polygon",
                Shape::Segment(_) => "segment",
                Shape::ChainSegment(_) => "chainSegment",
            }
            .to_string()
        })
    }

    /// Whether it is a sensor.
    #[wasm_bindgen(js_name = isSensor)]
    pub fn is_sensor(&self) -> Result<bool, JsError> {
        self.read(|c, _| c.is_sensor())
    }

    /// Its friction coefficient.
    pub fn friction(&self) -> Result<f64, JsError> {
        self.read(|c, _| c.friction() as f64)
    }

    /// Its restitution.
    pub fn restitution(&self) -> Result<f64, JsError> {
        self.read(|c, _| c.restitution() as f64)
    }

    /// Its density, kg/m².
    pub fn density(&self) -> Result<f64, JsError> {
        self.read(|c, _| c.density() as f64)
    }

    /// Its box in world coordinates, `{ min, max }`.
    #[wasm_bindgen(unchecked_return_type = "Aabb")]
    pub fn aabb(&self) -> Result<JsValue, JsError> {
        self.read(|c, _| {
            let aabb = c.aabb();
            object(&[("min", vec2_out(aabb.min)), ("max", vec2_out(aabb.max))])
        })
    }

    /// Its collision filter; category and mask are bigints.
    #[wasm_bindgen(unchecked_return_type = "CollisionFilterOut")]
    pub fn filter(&self) -> Result<JsValue, JsError> {
        self.read(|c, _| {
            let filter = c.filter();
            object(&[
                ("category", js_sys::BigInt::from(filter.category).into()),
                ("mask", js_sys::BigInt::from(filter.mask).into()),
                ("group", filter.group.into()),
            ])
        })
    }

    /// What overlaps it, if it is a sensor.
    #[wasm_bindgen(js_name = sensorOverlaps)]
    pub fn sensor_overlaps(&self) -> Result<Vec<Collider>, JsError> {
        registry::with(self.world, "this collider's world", |sim| {
            let overlaps = sim
                .world()
                .sensor_overlaps(self.handle)
                .map_err(carom_error)?;
            Ok(overlaps
                .iter()
                .map(|o| Collider::new(self.world, o.visitor))
                .collect())
        })
    }

    /// Sets its friction coefficient.
    #[wasm_bindgen(js_name = setFriction)]
    pub fn set_friction(&self, friction: f64) -> Result<(), JsError> {
        let friction = finite(friction, "friction")?;
        self.write(|c| c.set_friction(friction))
    }

    /// Sets its restitution.
    #[wasm_bindgen(js_name = setRestitution)]
    pub fn set_restitution(&self, restitution: f64) -> Result<(), JsError> {
        let restitution = finite(restitution, "restitution")?;
        self.write(|c| c.set_restitution(restitution))
    }

    /// Sets its density (its body's mass follows).
    #[wasm_bindgen(js_name = setDensity)]
    pub fn set_density(&self, density: f64) -> Result<(), JsError> {
        let density = finite(density, "density")?;
        self.write(|c| c.set_density(density))
    }

    /// Sets its collision filter.
    #[wasm_bindgen(js_name = setFilter)]
    pub fn set_filter(
        &self,
        #[wasm_bindgen(unchecked_param_type = "CollisionFilter")] filter: JsValue,
    ) -> Result<(), JsError> {
        let filter = collision_filter(&filter, "filter")?;
        self.write(|c| {
            c.set_filter(filter);
            Ok(())
        })
    }
}

/// A joint between two bodies. Get one from `World.createJoint`.
#[wasm_bindgen]
#[derive(Clone, Copy)]
pub struct Joint {
    pub(crate) world: WorldKey,
    pub(crate) handle: JointHandle,
}

impl Joint {
    pub(crate) fn new(world: WorldKey, handle: JointHandle) -> Joint {
        Joint { world, handle }
    }

    fn read<R>(&self, f: impl FnOnce(&carom::Joint, &World) -> R) -> Result<R, JsError> {
        registry::with(self.world, "this joint's world", |sim| {
            let world = sim.world();
            let joint = world
                .joint(self.handle)
                .ok_or_else(|| JsError::new("this joint was removed from its world (or broke)"))?;
            Ok(f(joint, world))
        })
    }
}

#[wasm_bindgen]
impl Joint {
    /// Its kind: `"distance"`, `"revolute"`, `"prismatic"`, `"weld"`, `"wheel"`, `"motor"`,
    /// `"mover"`, `"pogo"`, `"mouse"` or `"filter"`.
    pub fn kind(&self) -> Result<String, JsError> {
        self.read(|j, _| j.kind().name().to_string())
    }

    /// Its first body.
    #[wasm_bindgen(js_name = bodyA)]
    pub fn body_a(&self) -> Result<Body, JsError> {
        self.read(|j, _| Body::new(self.world, j.bodies()[0]))
    }

    /// Its second body.
    #[wasm_bindgen(js_name = bodyB)]
    pub fn body_b(&self) -> Result<Body, JsError> {
        self.read(|j, _| Body::new(self.world, j.bodies()[1]))
    }

    /// Its anchors in world coordinates, on body A then body B.
    #[wasm_bindgen(js_name = worldAnchors, unchecked_return_type = "[Vec2, Vec2]")]
    pub fn world_anchors(&self) -> Result<JsValue, JsError> {
        self.read(|j, world| {
            let [a, b] = j.bodies();
            match (world.body(a), world.body(b)) {
                (Some(a), Some(b)) => {
                    let [p, q] = j.world_anchors(a, b);
                    array_of([vec2_out(p), vec2_out(q)]).into()
                }
                _ => JsValue::UNDEFINED,
            }
        })
    }

    /// The force it applied on body B in the last step, N.
    #[wasm_bindgen(js_name = reactionForce, unchecked_return_type = "Vec2")]
    pub fn reaction_force(&self) -> Result<JsValue, JsError> {
        self.read(|j, _| vec2_out(j.reaction_force()))
    }

    /// The torque it applied on body B in the last step, N·m.
    #[wasm_bindgen(js_name = reactionTorque)]
    pub fn reaction_torque(&self) -> Result<f64, JsError> {
        self.read(|j, _| j.reaction_torque() as f64)
    }

    /// Moves a mouse joint's target (where it pulls its body), m.
    #[wasm_bindgen(js_name = setTarget)]
    pub fn set_target(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] target: JsValue,
    ) -> Result<(), JsError> {
        let target = vec2(&target, "target")?;
        registry::with(self.world, "this joint's world", |sim| {
            let mut joint = sim
                .world_mut()
                .joint_mut(self.handle)
                .ok_or_else(|| JsError::new("this joint was removed from its world (or broke)"))?;
            joint.set_mouse_target(target).map_err(carom_error)
        })
    }
}
