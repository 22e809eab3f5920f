//! A running scene saved whole, to open again as it was: the world with every contact,
//! impulse and island (carom's saved world), the names and colours of its bodies, and how far
//! its timed events have got.

use crate::error::SceneError;
use crate::events::Events;
use crate::player::{Player, SavedPlayer};
use crate::scene::Scene;
use crate::scene_world::SceneWorld;
use carom::{BodyHandle, World};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// A scene's state at one moment, kept in its file's `state` field. A scene that has one
/// opens on it instead of building its bodies again.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedState {
    world: World,
    names: BTreeMap<String, BodyHandle>,
    colors: Vec<(BodyHandle, (f32, f32, f32))>,
    events: Events,
    /// The player's motion, if the scene has one.
    #[serde(default)]
    player: Option<SavedPlayer>,
}

impl SceneWorld {
    /// `scene` (the one this was built from) with this moment's state in it: written out
    /// ([`write()`]) and opened again, it goes on exactly as this one would. The pre-solve rule
    /// of one-way platforms is set again on opening, as for any scene.
    pub fn save(&self, scene: &Scene) -> Scene {
        let mut colors: Vec<_> = self.colors.iter().map(|(&h, &c)| (h, c)).collect();
        colors.sort_by_key(|&(handle, _)| handle);
        Scene {
            state: Some(SavedState {
                world: self.world.clone(),
                names: self.names.iter().map(|(n, &h)| (n.clone(), h)).collect(),
                colors,
                events: self.events.clone(),
                player: self.player.as_ref().map(Player::saved),
            }),
            ..scene.clone()
        }
    }
}

impl SavedState {
    /// The world, its names and colours and its events, checked against each other.
    pub(crate) fn parts(&self) -> Result<Parts, String> {
        let world = self.world.clone();
        let names: HashMap<String, BodyHandle> = self.names.clone().into_iter().collect();
        let colors: HashMap<BodyHandle, (f32, f32, f32)> = self.colors.iter().copied().collect();
        let handles = names.values().chain(colors.keys());
        if let Some(gone) = handles
            .chain(&self.events.bodies())
            .find(|&&h| world.body(h).is_none())
        {
            return Err(format!(
                "it names body {} of the saved world, which has none such",
                gone.index()
            ));
        }
        Ok(Parts {
            world,
            names,
            colors,
            events: self.events.clone(),
            player: self.player,
        })
    }
}

/// A saved state taken apart to build a [`SceneWorld`] from.
pub(crate) struct Parts {
    pub world: World,
    pub names: HashMap<String, BodyHandle>,
    pub colors: HashMap<BodyHandle, (f32, f32, f32)>,
    pub events: Events,
    pub player: Option<SavedPlayer>,
}

/// A scene as scene-file text (RON): the hand-written part laid out for reading, a saved
/// state compactly. `file` names it in the error.
pub fn to_text(scene: &Scene, file: &str) -> Result<String, SceneError> {
    let config = ron::ser::PrettyConfig::new().depth_limit(3);
    let text = ron::ser::to_string_pretty(scene, config).map_err(|e| SceneError::Write {
        file: file.to_string(),
        reason: e.to_string(),
    })?;
    Ok(text + "\n")
}

/// Writes a scene to `path` in the scene format ([`to_text`]).
pub fn write(scene: &Scene, path: &Path) -> Result<(), SceneError> {
    let file = path.display().to_string();
    let text = to_text(scene, &file)?;
    std::fs::write(path, text).map_err(|e| SceneError::Write {
        file,
        reason: e.to_string(),
    })
}
