//! The `Spawn` event: copies of a generator's bodies and joints made and remade in turn at the
//! places of a grid, and the same turns written out ahead ([`SpawnSchedule`]) so that another
//! engine can make and remove the same bodies before the same steps.

use crate::generate::{Batch, add_bodies};
use crate::pending_joint::Target;
use carom::{BodyHandle, JointHandle, Real, Vec2, World, vec2};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// How far short of a whole step a turn's time may fall and still count as that step's: the
/// times are sums of decimal seconds, and a turn due at 8 steps must not wait for the ninth.
const STEP_TOLERANCE: f64 = 1e-6;

/// A spawn event: its grid of places, what it makes at each, and how far it has got.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct Spawn {
    /// When turn 0 comes, s.
    at: f64,
    /// Time between turns, s.
    every: f64,
    /// What the first place moves a copy by, m.
    origin: Vec2,
    columns: u32,
    rows: u32,
    spacing: Vec2,
    /// What a copy is, where the generator puts it.
    template: Batch,
    /// The collision group after which the copies that keep apart take theirs: place `p`'s
    /// `k`-th takes `-(1 + first_group + p apart + k)`, the same at every remaking.
    first_group: i32,
    /// The next turn.
    turn: u64,
    /// What each place holds (column by column, each column's rows in order).
    places: Vec<Option<Made>>,
}

/// The bodies and joints of one copy, as made.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Made {
    /// Its bodies, in the order the generator lists them.
    pub bodies: Vec<BodyHandle>,
    /// Its joints, in the order the generator lists them.
    pub joints: Vec<JointHandle>,
}

impl Spawn {
    /// A spawn event making `template` at the places of a grid; checks the values and makes
    /// one copy in a world of its own with `world`'s settings, so that a copy that cannot be
    /// made is refused when the scene is built rather than skipped when it runs.
    pub fn new(
        (at, every): (Real, Real),
        origin: Vec2,
        (columns, rows): (u32, u32),
        spacing: Vec2,
        template: Batch,
        first_group: i32,
        world: &World,
    ) -> Result<Self, String> {
        if !(at.is_finite() && at >= 0.0) {
            return Err(format!("`at` must be a time ≥ 0, got {at}"));
        }
        if !(every.is_finite() && every > 0.0) {
            return Err(format!("`every` must be positive, got {every}"));
        }
        if columns == 0 || rows == 0 {
            return Err(format!(
                "it needs at least one column and one row, got {columns} x {rows}"
            ));
        }
        if !(origin.iter().chain(spacing.iter()).all(|x| x.is_finite())) {
            return Err("origin and spacing must be finite".into());
        }
        if template.defs.is_empty() {
            return Err("`of` makes no bodies".into());
        }
        if let Some(name) = template
            .joints
            .iter()
            .flat_map(|j| &j.bodies)
            .find_map(|t| match t {
                Target::Named(name) => Some(name),
                Target::Local(_) => None,
            })
        {
            return Err(format!(
                "a copy's joints must join its own bodies, and one names {name:?}"
            ));
        }
        let places = columns as usize * rows as usize;
        let spawn = Spawn {
            at: at as f64,
            every: every as f64,
            origin,
            columns,
            rows,
            spacing,
            template,
            first_group,
            turn: 0,
            places: vec![None; places],
        };
        let mut trial = World::with_settings(*world.settings()).map_err(|e| e.to_string())?;
        spawn
            .make(0, &mut trial, &mut HashMap::new())
            .map_err(|e| format!("a copy cannot be made: {e}"))?;
        Ok(spawn)
    }

    /// How many collision groups its copies that keep apart take, all places together.
    pub fn groups(template: &Batch, columns: u32, rows: u32) -> i32 {
        let places = columns.saturating_mul(rows).min(i32::MAX as u32) as i32;
        places.saturating_mul(template.copies_apart() as i32)
    }

    /// The step before which turn `turn` comes, at `dt` seconds a step.
    fn step_of(&self, turn: u64, dt: Real) -> u64 {
        let time = self.at + turn as f64 * self.every;
        (time / dt as f64 - STEP_TOLERANCE).ceil().max(0.0) as u64
    }

    /// What a copy at the place in `column` and `row` is moved by.
    fn shift(&self, column: u32, row: u32) -> Vec2 {
        self.origin
            + vec2(
                column as Real * self.spacing.x,
                row as Real * self.spacing.y,
            )
    }

    /// Makes the copy of place `index` in `world`: the template's bodies moved by the place's
    /// shift, then its joints.
    fn make(
        &self,
        index: usize,
        world: &mut World,
        colors: &mut HashMap<BodyHandle, (f32, f32, f32)>,
    ) -> Result<Made, String> {
        let (column, row) = (index as u32 / self.rows, index as u32 % self.rows);
        let shift = self.shift(column, row);
        let template = &self.template;
        let defs = template.defs.iter().cloned().map(|mut def| {
            def.position += shift;
            def
        });
        let first_group = self.first_group + index as i32 * template.copies_apart() as i32;
        let parts = (&template.colors[..], &template.apart[..]);
        let bodies =
            add_bodies(world, defs, parts, first_group, colors).map_err(|e| e.to_string())?;
        let mut joints = Vec::with_capacity(template.joints.len());
        let no_names = HashMap::new();
        for joint in &template.joints {
            let def = joint.shifted(shift, 0).def(&bodies, &no_names)?;
            joints.push(world.add_joint(def).map_err(|e| e.to_string())?);
        }
        Ok(Made { bodies, joints })
    }

    /// The places of turn `turn`'s column, in order.
    fn places_of(&self, turn: u64) -> impl Iterator<Item = usize> + use<> {
        let column = (turn % self.columns as u64) as u32;
        let rows = self.rows;
        (0..rows).map(move |row| (column * rows + row) as usize)
    }

    /// Takes every turn due before the world's next step: each place of the turn's column
    /// loses its copy (bodies and joints) and gets a new one. A copy that cannot be made (its
    /// first one was, when the scene was built) is skipped.
    pub fn fire(
        &mut self,
        world: &mut World,
        colors: &mut HashMap<BodyHandle, (f32, f32, f32)>,
        dt: Real,
    ) {
        while world.step_count() >= self.step_of(self.turn, dt) {
            for index in self.places_of(self.turn) {
                if let Some(old) = self.places[index].take() {
                    for body in old.bodies {
                        // Its joints go with it; a body already removed by hand is skipped.
                        let _ = world.remove_body(body);
                        colors.remove(&body);
                    }
                }
                self.places[index] = self.make(index, world, colors).ok();
            }
            self.turn += 1;
        }
    }
}

/// What a scene's spawn events will do over a run, written out ahead for another engine to do
/// the same before the same steps (see [`crate::SceneWorld::spawn_schedule`]).
#[derive(Debug)]
pub struct SpawnSchedule {
    /// Every copy the events make in the run, each made as the scene makes it, in a world of
    /// their own (never stepped, with the scene's settings): read a copy's bodies and joints
    /// here to make them elsewhere.
    pub world: World,
    /// The copies, in the order they are made: their bodies and joints in [`Self::world`].
    pub copies: Vec<Made>,
    /// What happens, in order: before step `step` (0 is the first step from when the
    /// schedule was made), a copy is removed or made.
    pub changes: Vec<SpawnChange>,
    /// The scene's events other than spawns ("launch", "respawn", "spin", "shuttle"), which a schedule
    /// does not carry: a run elsewhere that follows only the schedule leaves them out.
    pub other_events: Vec<&'static str>,
}

/// One thing a spawn event does before a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpawnChange {
    /// Copy `copy` of [`SpawnSchedule::copies`] is made before step `step`.
    Add {
        /// The step it comes before, from 0.
        step: u64,
        /// Its index in [`SpawnSchedule::copies`].
        copy: usize,
    },
    /// Copy `copy`'s bodies (and with them its joints) are removed before step `step`.
    Remove {
        /// The step it comes before, from 0.
        step: u64,
        /// Its index in [`SpawnSchedule::copies`].
        copy: usize,
    },
}

impl SpawnChange {
    /// The step it comes before.
    pub fn step(&self) -> u64 {
        match *self {
            SpawnChange::Add { step, .. } | SpawnChange::Remove { step, .. } => step,
        }
    }
}

impl SpawnSchedule {
    /// The turns `spawns` take over the `steps` steps from `now` (the world's step count),
    /// in the order the scene takes them: step by step, each event's due turns in the
    /// order of the scene's events.
    ///
    /// # Errors
    /// A spawn event that has already made copies (those would be in the scene's world, not
    /// the schedule's), or a world that cannot be made with `settings`.
    pub(crate) fn new(
        spawns: &[&Spawn],
        settings: &carom::WorldSettings,
        (now, steps): (u64, u64),
        dt: Real,
        other_events: Vec<&'static str>,
    ) -> Result<Self, String> {
        if spawns.iter().any(|s| s.places.iter().any(Option::is_some)) {
            return Err("a spawn event has made copies already: schedule it from the start".into());
        }
        let mut world = World::with_settings(*settings).map_err(|e| e.to_string())?;
        let mut copies = Vec::new();
        let mut changes = Vec::new();
        let mut turns: Vec<u64> = spawns.iter().map(|s| s.turn).collect();
        // What each event's places hold, as indices into `copies`.
        let mut held: Vec<Vec<Option<usize>>> =
            spawns.iter().map(|s| vec![None; s.places.len()]).collect();
        let mut colors = HashMap::new();
        for step in now..now + steps {
            for (k, spawn) in spawns.iter().enumerate() {
                while step >= spawn.step_of(turns[k], dt) {
                    let relative = step - now;
                    for index in spawn.places_of(turns[k]) {
                        if let Some(copy) = held[k][index].take() {
                            changes.push(SpawnChange::Remove {
                                step: relative,
                                copy,
                            });
                        }
                        if let Ok(made) = spawn.make(index, &mut world, &mut colors) {
                            held[k][index] = Some(copies.len());
                            changes.push(SpawnChange::Add {
                                step: relative,
                                copy: copies.len(),
                            });
                            copies.push(made);
                        }
                    }
                    turns[k] += 1;
                }
            }
        }
        Ok(SpawnSchedule {
            world,
            copies,
            changes,
            other_events,
        })
    }
}
