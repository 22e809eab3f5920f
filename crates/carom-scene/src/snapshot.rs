//! A running scene's state kept in memory, to go back to: the world's
//! [`Snapshot`](carom::Snapshot) and what the scene adds to it (its timed events, its player,
//! the colours of the bodies it made).

use crate::events::Events;
use crate::player::Player;
use crate::scene_world::SceneWorld;
use carom::{BodyHandle, Snapshot};
use std::collections::HashMap;

/// A scene's whole state at one step: [`SceneWorld::restore`] puts it back, and the scene then
/// steps on to exactly the bits it stepped to the first time, its timed events included.
#[derive(Debug, Clone, Default)]
pub struct SceneSnapshot {
    world: Snapshot,
    events: Events,
    player: Option<Player>,
    colors: HashMap<BodyHandle, (f32, f32, f32)>,
}

impl SceneSnapshot {
    /// The world's part.
    pub fn world(&self) -> &Snapshot {
        &self.world
    }

    /// About the heap memory the snapshot holds, bytes: the world's
    /// ([`Snapshot::heap_bytes`]) and the scene's arrays beside it.
    pub fn heap_bytes(&self) -> usize {
        let SceneSnapshot {
            world,
            events,
            player,
            colors,
        } = self;
        let colors = colors.capacity() * (size_of::<(BodyHandle, (f32, f32, f32))>() + 1);
        let player = player.as_ref().map_or(0, Player::heap_bytes);
        world.heap_bytes() + events.heap_bytes() + colors + player
    }
}

impl SceneWorld {
    /// The scene's state now, to [`restore`](SceneWorld::restore) later.
    pub fn snapshot(&self) -> SceneSnapshot {
        SceneSnapshot {
            world: self.world.snapshot(),
            events: self.events.clone(),
            player: self.player.clone(),
            colors: self.colors.clone(),
        }
    }

    /// Takes the scene's state now into `snapshot`, reusing its memory.
    pub fn snapshot_into(&self, snapshot: &mut SceneSnapshot) {
        self.world.snapshot_into(&mut snapshot.world);
        snapshot.events.clone_from(&self.events);
        snapshot.player.clone_from(&self.player);
        snapshot.colors.clone_from(&self.colors);
    }

    /// Puts the scene back in the state `snapshot` holds: the world (see
    /// [`World::restore`](carom::World::restore)), the timed events, the player and the
    /// colours. The time step, names, camera and drawing choices are the scene's own and stay.
    pub fn restore(&mut self, snapshot: &SceneSnapshot) {
        self.world.restore(&snapshot.world);
        self.events.clone_from(&snapshot.events);
        self.player.clone_from(&snapshot.player);
        self.colors.clone_from(&snapshot.colors);
    }
}
