//! A whole world as it is saved and read back (feature `serde`): bodies, colliders, joints,
//! contacts with their warm-start impulses and graph colours, islands, the broadphase's trees
//! and the settings, so a restored world steps on exactly as the saved one would have.
//!
//! What a step only works in (its scratch memory, the solver's workspace, the last step's
//! statistics) is not saved, nor is the pre-solve hook, which is code: set it again after
//! restoring. A saved world is checked as it is read, since the file may have been edited:
//! what does not hold together is a [`CaromError::BadSave`], not a panic in a later step.

use crate::collision::broadphase::BroadPhase;
use crate::collision::contact::ContactSet;
use crate::collision::hits::HitEvent;
use crate::collision::sensor::Sensors;
use crate::dynamics::body::{Body, BodyHandle, BodyKind};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::island::Islands;
use crate::error::CaromError;
use crate::handle_map::HandleMap;
use crate::joint::store::JointStore;
use crate::solver_set::{SetBounds, SolverSet};
use crate::world::settings::WorldSettings;
use crate::world::{World, check_settings};
use serde::{Deserialize, Serialize};

/// The version of the saved form; a world saved in another is refused. Format 2: the solver's
/// `iterations` became optional and joints are stored in solver sets. Format 3: the
/// broadphase keeps which proxies moved apart from the proxies. Format 4: contacts keep their
/// ids (contacts are filed by id). Format 5: the contact array's parts are laid out anew
/// (`graph::layout`). Format 6: colliders keep a whole surface (rolling resistance, tangent
/// speed, material id) and contacts their rolling impulse. Format 7: Box2D 3.2's motor joint
/// (a velocity part and a spring part), the mover and pogo joints and their impulses, and
/// bodies that never turn.
const SAVE_FORMAT: u32 = 7;

/// What a saved world holds: every field of [`World`] that outlives a step.
#[derive(Serialize, Deserialize)]
#[serde(rename = "World", deny_unknown_fields)]
pub(crate) struct SavedWorld {
    /// Written first and checked as soon as it is read, so a world saved by another version
    /// is refused for that, with both versions named, before any field that version changed
    /// can fail to read.
    #[serde(deserialize_with = "this_format")]
    format: u32,
    settings: WorldSettings,
    time: f64,
    step_count: u64,
    bodies: HandleMap<BodyHandle, Body>,
    colliders: HandleMap<ColliderHandle, Collider>,
    joints: JointStore,
    islands: Islands,
    body_sets: SetBounds,
    collider_sets: SetBounds,
    broadphase: BroadPhase,
    contacts: ContactSet,
    sensors: Sensors,
    hit_events: Vec<HitEvent>,
}

impl From<World> for SavedWorld {
    fn from(world: World) -> Self {
        SavedWorld {
            format: SAVE_FORMAT,
            settings: world.settings,
            time: world.time,
            step_count: world.step_count,
            bodies: world.bodies,
            colliders: world.colliders,
            joints: world.joints,
            islands: world.islands,
            body_sets: world.body_sets,
            collider_sets: world.collider_sets,
            broadphase: world.broadphase,
            contacts: world.contacts,
            sensors: world.sensors,
            hit_events: world.hit_events,
        }
    }
}

impl TryFrom<SavedWorld> for World {
    type Error = CaromError;

    fn try_from(saved: SavedWorld) -> Result<Self, CaromError> {
        // The format was checked as it was read (`this_format`).
        check_settings(&saved.settings)?;
        let mut world = World {
            hit_event_colliders: saved
                .colliders
                .as_slice()
                .iter()
                .filter(|c| c.hit_events())
                .count(),
            settings: saved.settings,
            time: saved.time,
            step_count: saved.step_count,
            bodies: saved.bodies,
            colliders: saved.colliders,
            joints: saved.joints,
            islands: saved.islands,
            body_sets: saved.body_sets,
            collider_sets: saved.collider_sets,
            broadphase: saved.broadphase,
            contacts: saved.contacts,
            sensors: saved.sensors,
            hit_events: saved.hit_events,
            ..World::default()
        };
        world.check_saved().map_err(bad)?;
        world.contacts.mix_saved(&world.colliders);
        Ok(world)
    }
}

/// Reads a saved world's format, refusing any but [`SAVE_FORMAT`].
fn this_format<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    let format = u32::deserialize(deserializer)?;
    if format == SAVE_FORMAT {
        Ok(format)
    } else {
        Err(serde::de::Error::custom(format_mismatch(format)))
    }
}

/// Why a world saved in `format` is refused.
fn format_mismatch(format: u32) -> String {
    format!(
        "the world was saved in save format {format}, and this carom ({}) reads save format \
         {SAVE_FORMAT} only",
        env!("CARGO_PKG_VERSION")
    )
}

fn bad(reason: String) -> CaromError {
    CaromError::BadSave { reason }
}

impl World {
    /// Checks that what was read holds together: every handle and index points at something
    /// that exists, the parts of each array fit in it, and every number is finite.
    pub(crate) fn check_saved(&self) -> Result<(), String> {
        self.bodies.check_saved()?;
        self.colliders.check_saved()?;
        if !self.time.is_finite() {
            return Err("the time is not finite".into());
        }
        for (index, body) in self.bodies.as_slice().iter().enumerate() {
            body.check_saved(self.bodies.handles()[index])?;
            for &collider in body.colliders() {
                let owner = self.colliders.get(collider).map(Collider::body);
                if owner != Some(body.handle()) {
                    return Err(format!("body {index} lists a collider that is not its own"));
                }
            }
        }
        let attached: usize = self
            .bodies
            .as_slice()
            .iter()
            .map(|b| b.colliders().len())
            .sum();
        if attached != self.colliders.len() {
            return Err("a collider is not attached to its body".into());
        }
        for (index, collider) in self.colliders.as_slice().iter().enumerate() {
            if self.bodies.dense_index(collider.body()) != Some(collider.body_index()) {
                return Err(format!("collider {index} does not know where its body is"));
            }
            let body = &self.bodies.as_slice()[collider.body_index()];
            collider
                .check_saved(&body.transform())
                .map_err(|e| format!("collider {index}: {e}"))?;
        }
        for (index, body) in self.bodies.as_slice().iter().enumerate() {
            let colliders = body
                .colliders()
                .iter()
                .filter_map(|&c| self.colliders.get(c));
            if !body.mass_matches(colliders) {
                return Err(format!("body {index}'s mass is not its colliders'"));
            }
        }
        self.body_sets.check_saved("body", self.bodies.len())?;
        self.collider_sets
            .check_saved("collider", self.colliders.len())?;
        self.check_saved_sets()?;
        self.islands.check_saved(&self.bodies)?;
        self.joints.check_saved(&self.bodies)?;
        for (index, joint) in self.joints.as_slice().iter().enumerate() {
            if self.joints.set_of(index) != self.joint_set_for(joint) {
                return Err(format!("joint {index} is stored in the wrong set"));
            }
        }
        self.broadphase.check_saved(&self.colliders, &self.bodies)?;
        self.contacts.check_saved(&self.colliders, &self.bodies)?;
        self.sensors.check_saved(&self.colliders)?;
        Ok(())
    }

    /// Every body is in the set its kind and sleep say, and every collider in its body's.
    fn check_saved_sets(&self) -> Result<(), String> {
        for (index, body) in self.bodies.as_slice().iter().enumerate() {
            let set = if body.kind() == BodyKind::Static {
                SolverSet::Static
            } else if body.is_sleeping() {
                SolverSet::Asleep
            } else {
                SolverSet::Awake
            };
            if self.body_sets.set_of(index) != set {
                return Err(format!("body {index} is stored in the wrong set"));
            }
        }
        for (index, collider) in self.colliders.as_slice().iter().enumerate() {
            if self.collider_sets.set_of(index) != self.body_sets.set_of(collider.body_index()) {
                return Err(format!("collider {index} is stored apart from its body"));
            }
        }
        Ok(())
    }
}
