//! The `World` class: creating and removing bodies, colliders and joints, stepping, saving and
//! snapshots. Queries and events are in `queries.rs` and `events.rs`.

use crate::convert::{error, finite, object, vec2, vec2_out};
use crate::defs;
use crate::handles::{Body, Collider, Joint, carom_error};
use crate::registry::{self, WorldKey};
use crate::sim::Sim;
use carom::{Capacity, JointDef, World as CaromWorld};
use carom_scene::SceneSnapshot;
use wasm_bindgen::prelude::*;

/// A physics world. Create bodies in it, step it, query it; `free()` it (or let it be
/// collected) to release its memory, after which its handles answer with an error.
#[wasm_bindgen]
pub struct World {
    pub(crate) key: WorldKey,
}

impl Drop for World {
    fn drop(&mut self) {
        registry::remove(self.key);
    }
}

impl World {
    pub(crate) fn with<R>(
        &self,
        f: impl FnOnce(&mut Sim) -> Result<R, JsError>,
    ) -> Result<R, JsError> {
        registry::with(self.key, "this world", f)
    }

    /// Checks that a handle passed in belongs to this world.
    pub(crate) fn owns(&self, handle_world: WorldKey, what: &str) -> Result<(), JsError> {
        if handle_world == self.key {
            Ok(())
        } else {
            Err(JsError::new(&format!("{what} belongs to another world")))
        }
    }

    fn new_sim(sim: Sim) -> World {
        World {
            key: registry::insert(sim),
        }
    }
}

#[wasm_bindgen]
impl World {
    /// An empty world; `settings` (all optional) changes gravity and the solver.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "WorldSettings | undefined")] settings: JsValue,
    ) -> Result<World, JsError> {
        let settings = defs::settings(&settings)?;
        let world = CaromWorld::with_settings(settings).map_err(carom_error)?;
        Ok(World::new_sim(Sim::Plain(Box::new(world))))
    }

    /// A world built from a scene in carom's RON scene format (the demo's `demos/*.ron`), with
    /// its time step, names and timed events. `file` names it in error messages.
    #[wasm_bindgen(js_name = fromScene)]
    pub fn from_scene(text: &str, file: Option<String>) -> Result<World, JsError> {
        let file = file.as_deref().unwrap_or("scene");
        let scene = carom_scene::parse(text, file).map_err(|e| JsError::new(&e.to_string()))?;
        let built = carom_scene::build(&scene, file).map_err(|e| JsError::new(&e.to_string()))?;
        Ok(World::new_sim(Sim::Scene(Box::new(built))))
    }

    /// A world saved by `save()`, exactly as it was: stepping it goes on bit for bit as the
    /// saved one would have.
    pub fn load(text: &str) -> Result<World, JsError> {
        let world: CaromWorld = ron::from_str(text).map_err(|e| error("saved world", e))?;
        Ok(World::new_sim(Sim::Plain(Box::new(world))))
    }

    /// The world saved as text (RON), to open with `World.load`. A scene's time step, names
    /// and timed events are not in it.
    pub fn save(&self) -> Result<String, JsError> {
        self.with(|sim| ron::to_string(sim.world()).map_err(|e| error("saving the world", e)))
    }

    /// How many worlds are alive (made and not yet freed or collected).
    #[wasm_bindgen(js_name = liveCount)]
    pub fn live_count() -> u32 {
        registry::live_worlds() as u32
    }

    /// Advances the world by `dt` seconds: its scene's time step, or 1/60 s, when left out.
    /// A scene's timed events fire as they fall due.
    pub fn step(&self, dt: Option<f64>) -> Result<(), JsError> {
        let dt = dt.map(|dt| finite(dt, "time step")).transpose()?;
        self.with(|sim| {
            let dt = dt.unwrap_or_else(|| sim.time_step());
            sim.step(dt).map_err(carom_error)
        })
    }

    /// The time step `step()` takes when given none, s.
    #[wasm_bindgen(js_name = timeStep)]
    pub fn time_step(&self) -> Result<f64, JsError> {
        self.with(|sim| Ok(sim.time_step() as f64))
    }

    /// Simulated time, s.
    pub fn time(&self) -> Result<f64, JsError> {
        self.with(|sim| Ok(sim.world().time()))
    }

    /// Steps taken.
    #[wasm_bindgen(js_name = stepCount)]
    pub fn step_count(&self) -> Result<f64, JsError> {
        self.with(|sim| Ok(sim.world().step_count() as f64))
    }

    /// A hash of the whole state: equal on every platform for the same world and inputs
    /// (native builds included), so two runs can be compared by it.
    #[wasm_bindgen(js_name = stateHash)]
    pub fn state_hash(&self) -> Result<u64, JsError> {
        self.with(|sim| Ok(sim.world().state_hash()))
    }

    /// Gravity, m/s².
    #[wasm_bindgen(unchecked_return_type = "Vec2")]
    pub fn gravity(&self) -> Result<JsValue, JsError> {
        self.with(|sim| Ok(vec2_out(sim.world().gravity())))
    }

    /// Changes gravity, m/s².
    #[wasm_bindgen(js_name = setGravity)]
    pub fn set_gravity(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] gravity: JsValue,
    ) -> Result<(), JsError> {
        let gravity = vec2(&gravity, "gravity")?;
        self.with(|sim| {
            sim.world_mut()
                .update_settings(|s| s.gravity = gravity)
                .map_err(carom_error)
        })
    }

    /// Wakes every body.
    #[wasm_bindgen(js_name = wakeAll)]
    pub fn wake_all(&self) -> Result<(), JsError> {
        self.with(|sim| {
            sim.world_mut().wake_all();
            Ok(())
        })
    }

    /// How many bodies it has.
    #[wasm_bindgen(js_name = bodyCount)]
    pub fn body_count(&self) -> Result<u32, JsError> {
        self.with(|sim| Ok(sim.world().body_count() as u32))
    }

    /// Its bodies, in a stable order (the order of `transforms()`).
    pub fn bodies(&self) -> Result<Vec<Body>, JsError> {
        self.with(|sim| {
            Ok(sim
                .world()
                .bodies()
                .map(|b| Body::new(self.key, b.handle()))
                .collect())
        })
    }

    /// Its joints.
    pub fn joints(&self) -> Result<Vec<Joint>, JsError> {
        self.with(|sim| {
            Ok(sim
                .world()
                .joints()
                .map(|j| Joint::new(self.key, j.handle()))
                .collect())
        })
    }

    /// Every body's `x, y, angle`, three numbers each, in the order of `bodies()`: one call
    /// for drawing a whole world.
    pub fn transforms(&self) -> Result<Vec<f32>, JsError> {
        self.with(|sim| {
            let world = sim.world();
            let mut out = Vec::with_capacity(world.body_count() * 3);
            for body in world.bodies() {
                let p = body.position();
                out.extend([p.x, p.y, body.angle()]);
            }
            Ok(out)
        })
    }

    /// The body the scene named `name`, if it is a scene's world and has one.
    #[wasm_bindgen(js_name = bodyNamed)]
    pub fn body_named(&self, name: &str) -> Result<Option<Body>, JsError> {
        self.with(|sim| {
            Ok(match sim {
                Sim::Scene(scene) => scene.names.get(name).map(|&h| Body::new(self.key, h)),
                Sim::Plain(_) => None,
            })
        })
    }

    /// Adds a body.
    #[wasm_bindgen(js_name = createBody)]
    pub fn create_body(
        &self,
        #[wasm_bindgen(unchecked_param_type = "BodyDef")] def: JsValue,
    ) -> Result<Body, JsError> {
        let def = defs::body(&def)?;
        self.with(|sim| {
            let handle = sim.world_mut().add_body(def).map_err(carom_error)?;
            Ok(Body::new(self.key, handle))
        })
    }

    /// Adds a static chain of segments (ground, a track): one body whose colliders are its
    /// links.
    #[wasm_bindgen(js_name = createChain)]
    pub fn create_chain(
        &self,
        #[wasm_bindgen(unchecked_param_type = "ChainDef")] def: JsValue,
    ) -> Result<Body, JsError> {
        let def = defs::chain(&def)?;
        self.with(|sim| {
            let handle = sim.world_mut().add_body(def).map_err(carom_error)?;
            Ok(Body::new(self.key, handle))
        })
    }

    /// Removes a body with its colliders and joints.
    #[wasm_bindgen(js_name = removeBody)]
    pub fn remove_body(&self, body: &Body) -> Result<(), JsError> {
        self.owns(body.world, "the body")?;
        self.with(|sim| {
            sim.world_mut()
                .remove_body(body.handle)
                .map(drop)
                .map_err(carom_error)
        })
    }

    /// Adds a collider to `body`.
    #[wasm_bindgen(js_name = createCollider)]
    pub fn create_collider(
        &self,
        body: &Body,
        #[wasm_bindgen(unchecked_param_type = "ColliderDef")] def: JsValue,
    ) -> Result<Collider, JsError> {
        self.owns(body.world, "the body")?;
        let def = defs::collider(&def, "collider definition")?;
        self.with(|sim| {
            let handle = sim
                .world_mut()
                .add_collider(body.handle, def)
                .map_err(carom_error)?;
            Ok(Collider::new(self.key, handle))
        })
    }

    /// Removes a collider.
    #[wasm_bindgen(js_name = removeCollider)]
    pub fn remove_collider(&self, collider: &Collider) -> Result<(), JsError> {
        self.owns(collider.world, "the collider")?;
        self.with(|sim| {
            sim.world_mut()
                .remove_collider(collider.handle)
                .map(drop)
                .map_err(carom_error)
        })
    }

    /// Joins `bodyA` and `bodyB`; `def.kind` says how, with anchors in world coordinates.
    #[wasm_bindgen(js_name = createJoint)]
    pub fn create_joint(
        &self,
        body_a: &Body,
        body_b: &Body,
        #[wasm_bindgen(unchecked_param_type = "JointDef")] def: JsValue,
    ) -> Result<Joint, JsError> {
        self.owns(body_a.world, "body A")?;
        self.owns(body_b.world, "body B")?;
        let def = defs::joint(&def, body_a.handle, body_b.handle)?;
        self.add_joint(def)
    }

    /// Pulls `body`'s point at `target` toward the target (move it with `Joint.setTarget`),
    /// with at most `maxForce` newtons: dragging with a mouse or a finger.
    #[wasm_bindgen(js_name = createMouseJoint)]
    pub fn create_mouse_joint(
        &self,
        body: &Body,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] target: JsValue,
        max_force: f64,
    ) -> Result<Joint, JsError> {
        self.owns(body.world, "the body")?;
        let target = vec2(&target, "target")?;
        let max_force = finite(max_force, "max force")?;
        self.add_joint(JointDef::mouse(body.handle, target, max_force))
    }

    /// Removes a joint.
    #[wasm_bindgen(js_name = removeJoint)]
    pub fn remove_joint(&self, joint: &Joint) -> Result<(), JsError> {
        self.owns(joint.world, "the joint")?;
        self.with(|sim| {
            sim.world_mut()
                .remove_joint(joint.handle)
                .map(drop)
                .map_err(carom_error)
        })
    }

    /// Pushes the dynamic bodies near `def.center` away from it; answers how many colliders
    /// it pushed.
    pub fn explode(
        &self,
        #[wasm_bindgen(unchecked_param_type = "ExplosionDef")] def: JsValue,
    ) -> Result<u32, JsError> {
        let def = defs::explosion(&def)?;
        self.with(|sim| {
            sim.world_mut()
                .explode(&def)
                .map(|n| n as u32)
                .map_err(carom_error)
        })
    }

    /// Makes room ahead of time for as many bodies, colliders, contacts and joints as
    /// `capacity` names, so that a world no larger than that steps without asking for memory
    /// after its first step. Room already made is kept; nothing else changes.
    pub fn reserve(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Capacity")] capacity: JsValue,
    ) -> Result<(), JsError> {
        let capacity = defs::capacity(&capacity)?;
        self.with(|sim| sim.world_mut().reserve(capacity).map_err(carom_error))
    }

    /// The most bodies, colliders, contacts and joints the world has held at once, or made
    /// room for: what to `reserve` for a run like the ones it has made.
    #[wasm_bindgen(js_name = highWater, unchecked_return_type = "Capacity")]
    pub fn high_water(&self) -> Result<JsValue, JsError> {
        self.with(|sim| {
            let Capacity {
                bodies,
                colliders,
                contacts,
                joints,
            } = sim.world().high_water();
            let count = |n: usize| JsValue::from_f64(n as f64);
            Ok(object(&[
                ("bodies", count(bodies)),
                ("colliders", count(colliders)),
                ("contacts", count(contacts)),
                ("joints", count(joints)),
            ]))
        })
    }

    /// The whole state now, to `restore` later (rollback, rewind). A scene's timed events are
    /// in it too.
    pub fn snapshot(&self) -> Result<Snapshot, JsError> {
        self.with(|sim| {
            Ok(Snapshot {
                state: match sim {
                    Sim::Plain(world) => State::World(Box::new(world.snapshot())),
                    Sim::Scene(scene) => State::Scene(Box::new(scene.snapshot())),
                },
                world: self.key,
            })
        })
    }

    /// Puts the world back as it was when `snapshot` was taken: stepping on gives the same
    /// bits as it did then. Handles to bodies made since then no longer answer.
    pub fn restore(&self, snapshot: &Snapshot) -> Result<(), JsError> {
        if snapshot.world != self.key {
            return Err(JsError::new("the snapshot was taken of another world"));
        }
        self.with(|sim| {
            match (sim, &snapshot.state) {
                (Sim::Plain(world), State::World(state)) => world.restore(state),
                (Sim::Scene(scene), State::Scene(state)) => scene.restore(state),
                _ => return Err(JsError::new("the snapshot was taken of another world")),
            }
            Ok(())
        })
    }
}

impl World {
    fn add_joint(&self, def: JointDef) -> Result<Joint, JsError> {
        self.with(|sim| {
            let handle = sim.world_mut().add_joint(def).map_err(carom_error)?;
            Ok(Joint::new(self.key, handle))
        })
    }
}

enum State {
    World(Box<carom::Snapshot>),
    Scene(Box<SceneSnapshot>),
}

/// A world's whole state at one moment (`World.snapshot()`), to put back with
/// `World.restore`. It holds its own copy: `free()` it when done.
#[wasm_bindgen]
pub struct Snapshot {
    world: WorldKey,
    state: State,
}

#[wasm_bindgen]
impl Snapshot {
    /// The step count when it was taken.
    #[wasm_bindgen(js_name = stepCount)]
    pub fn step_count(&self) -> f64 {
        match &self.state {
            State::World(s) => s.step_count() as f64,
            State::Scene(s) => s.world().step_count() as f64,
        }
    }

    /// The memory it holds, bytes.
    #[wasm_bindgen(js_name = heapBytes)]
    pub fn heap_bytes(&self) -> f64 {
        match &self.state {
            State::World(s) => s.heap_bytes() as f64,
            State::Scene(s) => s.heap_bytes() as f64,
        }
    }
}
