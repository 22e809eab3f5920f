//! A whole world as it is saved and read back (feature `serde`): bodies, colliders, joints,
//! contacts with their warm-start impulses and graph colours, islands, the broadphase's trees
//! and the settings, so a restored world steps on exactly as the saved one would have.
//!
//! What a step only works in (its scratch memory, the solver's workspace, the last step's
//! statistics) is not saved, nor is the pre-solve hook, which is code: set it again after
//! restoring. A saved world is checked as it is read, since the file may have been edited:
//! what does not hold together is a [`CaromError::BadSave`], not a panic in a later step.

use crate::dynamics::body::BodyKind;
use crate::dynamics::collider::Collider;
use crate::error::CaromError;
use crate::solver_set::SolverSet;
use crate::world::state::WorldState;
use crate::world::{World, check_settings};
use serde::{Deserialize, Serialize};

/// The version of the saved form; a world saved in another is refused. Format 2: the solver's
/// `iterations` became optional and joints are stored in solver sets. Format 3: the
/// broadphase keeps which proxies moved apart from the proxies. Format 4: contacts keep their
/// ids (contacts are filed by id). Format 5: the contact array's parts are laid out anew
/// (`graph::layout`). Format 6: colliders keep a whole surface (rolling resistance, tangent
/// speed, material id) and contacts their rolling impulse. Format 7: Box2D 3.2's motor joint
/// (a velocity part and a spring part), the mover and pogo joints and their impulses, and
/// bodies that never turn. Format 8: what outlives a step is written as one `state`, after
/// the format.
const SAVE_FORMAT: u32 = 8;

/// What a saved world holds: its save format, then every field of [`World`] that outlives a
/// step.
#[derive(Serialize, Deserialize)]
#[serde(rename = "World", deny_unknown_fields)]
pub(crate) struct SavedWorld {
    /// Written first and checked as soon as it is read, so a world saved by another version
    /// is refused for that, with both versions named, before any field that version changed
    /// can fail to read.
    #[serde(deserialize_with = "this_format")]
    format: u32,
    state: WorldState,
}

impl From<World> for SavedWorld {
    fn from(world: World) -> Self {
        SavedWorld {
            format: SAVE_FORMAT,
            state: world.state,
        }
    }
}

impl TryFrom<SavedWorld> for World {
    type Error = CaromError;

    fn try_from(saved: SavedWorld) -> Result<Self, CaromError> {
        // The format was checked as it was read (`this_format`).
        let mut state = saved.state;
        check_settings(&state.settings)?;
        state.hit_event_colliders = state
            .colliders
            .as_slice()
            .iter()
            .filter(|c| c.hit_events())
            .count();
        let mut world = World {
            state,
            ..World::default()
        };
        world.check_saved()?;
        let state = &mut world.state;
        state.contacts.mix_saved(&state.colliders);
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

impl World {
    /// Checks that what was read holds together: every handle and index points at something
    /// that exists, the parts of each array fit in it, and every number is finite.
    pub(crate) fn check_saved(&self) -> Result<(), CaromError> {
        self.state.bodies.check_saved()?;
        self.state.colliders.check_saved()?;
        if !self.state.time.is_finite() {
            return Err(CaromError::bad_save("the time is not finite"));
        }
        for (index, body) in self.state.bodies.as_slice().iter().enumerate() {
            body.check_saved(self.state.bodies.handles()[index])?;
            for &collider in body.colliders() {
                let owner = self.state.colliders.get(collider).map(Collider::body);
                if owner != Some(body.handle()) {
                    return Err(CaromError::bad_save(format!(
                        "body {index} lists a collider that is not its own"
                    )));
                }
            }
        }
        let attached: usize = self
            .state
            .bodies
            .as_slice()
            .iter()
            .map(|b| b.colliders().len())
            .sum();
        if attached != self.state.colliders.len() {
            return Err(CaromError::bad_save(
                "a collider is not attached to its body",
            ));
        }
        for (index, collider) in self.state.colliders.as_slice().iter().enumerate() {
            if self.state.bodies.dense_index(collider.body()) != Some(collider.body_index()) {
                return Err(CaromError::bad_save(format!(
                    "collider {index} does not know where its body is"
                )));
            }
            let body = &self.state.bodies.as_slice()[collider.body_index()];
            collider
                .check_saved(&body.transform())
                .map_err(|e| CaromError::bad_save(format!("collider {index}: {e}")))?;
        }
        for (index, body) in self.state.bodies.as_slice().iter().enumerate() {
            let colliders = body
                .colliders()
                .iter()
                .filter_map(|&c| self.state.colliders.get(c));
            if !body.mass_matches(colliders) {
                return Err(CaromError::bad_save(format!(
                    "body {index}'s mass is not its colliders'"
                )));
            }
        }
        self.state
            .body_sets
            .check_saved("body", self.state.bodies.len())?;
        self.state
            .collider_sets
            .check_saved("collider", self.state.colliders.len())?;
        self.check_saved_sets()?;
        self.state.islands.check_saved(&self.state.bodies)?;
        self.state.joints.check_saved(&self.state.bodies)?;
        for (index, joint) in self.state.joints.as_slice().iter().enumerate() {
            if self.state.joints.set_of(index) != self.joint_set_for(joint) {
                return Err(CaromError::bad_save(format!(
                    "joint {index} is stored in the wrong set"
                )));
            }
        }
        self.state
            .broadphase
            .check_saved(&self.state.colliders, &self.state.bodies)?;
        self.state
            .contacts
            .check_saved(&self.state.colliders, &self.state.bodies)?;
        self.state.sensors.check_saved(&self.state.colliders)?;
        Ok(())
    }

    /// Every body is in the set its kind and sleep say, and every collider in its body's.
    fn check_saved_sets(&self) -> Result<(), CaromError> {
        for (index, body) in self.state.bodies.as_slice().iter().enumerate() {
            let set = if body.kind() == BodyKind::Static {
                SolverSet::Static
            } else if body.is_sleeping() {
                SolverSet::Asleep
            } else {
                SolverSet::Awake
            };
            if self.state.body_sets.set_of(index) != set {
                return Err(CaromError::bad_save(format!(
                    "body {index} is stored in the wrong set"
                )));
            }
        }
        for (index, collider) in self.state.colliders.as_slice().iter().enumerate() {
            if self.state.collider_sets.set_of(index)
                != self.state.body_sets.set_of(collider.body_index())
            {
                return Err(CaromError::bad_save(format!(
                    "collider {index} is stored apart from its body"
                )));
            }
        }
        Ok(())
    }
}
