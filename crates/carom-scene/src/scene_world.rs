//! A scene built into a world, and what it adds to each step: events and the player.

use crate::events::Events;
use crate::player::Player;
use crate::scene::{Accuracy, Camera};
use crate::spawn::SpawnSchedule;
use carom::draw::{Color, DebugDraw, DrawFlags, DrawOptions};
use carom::{BodyHandle, CaromError, Real, World};
use std::collections::HashMap;

/// A scene built into a world, with what the scene adds on top: its time step, the names and
/// colours of its bodies, and its timed events.
#[derive(Debug)]
pub struct SceneWorld {
    /// The world.
    pub world: World,
    /// Seconds per step.
    pub time_step: Real,
    /// Bodies by the names the scene gave them.
    pub names: HashMap<String, BodyHandle>,
    /// Colours the scene asked for.
    pub colors: HashMap<BodyHandle, (f32, f32, f32)>,
    /// Where the scene's camera starts: its own, or one that frames its bodies.
    pub camera: Camera,
    /// What the scene asks to be drawn.
    pub draw: DrawFlags,
    /// How `carom bench` measures the scene's error, its body names checked.
    pub accuracy: Option<Accuracy>,
    /// The character the keyboard walks, if the scene has one: set its
    /// [`Player::input`] before each step.
    pub player: Option<Player>,
    pub(crate) events: Events,
}

impl SceneWorld {
    /// Fires the events due, moves the player, and advances the world by one time step.
    pub fn step(&mut self) -> Result<(), CaromError> {
        self.events
            .fire(&mut self.world, &mut self.colors, self.time_step);
        if let Some(player) = &mut self.player {
            player.step(&mut self.world, self.time_step)?;
        }
        self.world.step(self.time_step)
    }

    /// Fires the events due now without stepping (harmless: [`SceneWorld::step`] fires each
    /// event once), so the state at time 0 includes the launches at time 0.
    pub fn fire_events(&mut self) {
        self.events
            .fire(&mut self.world, &mut self.colors, self.time_step);
    }

    /// What the scene's spawn events will make and remove over the next `steps` steps,
    /// written out for another engine to do the same before the same steps (a benchmark's
    /// peers, say); see [`SpawnSchedule`].
    ///
    /// # Errors
    /// A spawn event that has made copies already: schedule a scene before its first step.
    pub fn spawn_schedule(&self, steps: u64) -> Result<SpawnSchedule, String> {
        let (spawns, others) = self.events.spawns();
        let now = self.world.step_count();
        SpawnSchedule::new(
            &spawns,
            self.world.settings(),
            (now, steps),
            self.time_step,
            others,
        )
    }

    /// Describes the world to `out` as `options` select, in the scene's colours.
    pub fn debug_draw(&self, options: &DrawOptions, out: &mut impl DebugDraw) {
        self.world.debug_draw(
            options,
            |body| {
                self.colors
                    .get(&body.handle())
                    .map(|&(r, g, b)| Color::rgb(r, g, b))
            },
            out,
        );
        if let Some(player) = &self.player {
            player.draw(out);
        }
    }
}
