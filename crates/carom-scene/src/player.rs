//! The scene's player: a kinematic character ([`carom::Character`]) that the host walks and
//! jumps each step, as a game drives one: a walking speed from the keys held, the world's
//! gravity added to its own vertical speed, the move, then its velocity clipped by what it
//! touched.

use crate::scene::{KeyChange, PlayerKey, PlayerSpec};
use carom::draw::{Color, DebugDraw};
use carom::{CaromError, Character, CharacterDef, CharacterState, Effect, Real, Vec2, World, vec2};
use serde::{Deserialize, Serialize};

/// The keys held this step.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PlayerInput {
    /// Walk left.
    pub left: bool,
    /// Walk right.
    pub right: bool,
    /// Jump, if standing on something.
    pub jump: bool,
}

/// The scene's player, moved by [`crate::SceneWorld::step`] before the world steps.
#[derive(Debug, Clone)]
pub struct Player {
    character: Character,
    velocity: Vec2,
    walk_speed: Real,
    jump_speed: Real,
    goal: Option<Real>,
    /// Whether the jump key has jumped since it went down: holding it jumps once.
    jump_spent: bool,
    /// The scene's recorded play, and whether it is being played.
    recorded: Vec<KeyChange>,
    replaying: bool,
    /// The keys held; the host sets them before each step.
    pub input: PlayerInput,
}

/// What a saved scene keeps of its player: where it is, what it stands on, how it moves.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SavedPlayer {
    state: CharacterState,
    velocity: Vec2,
    #[serde(default)]
    jump_spent: bool,
}

impl Player {
    /// About the heap memory the player holds, bytes: its recorded play.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.recorded.capacity() * size_of::<KeyChange>()
    }

    /// The player `spec` describes, standing nowhere yet.
    pub(crate) fn new(spec: &PlayerSpec) -> Result<Self, String> {
        let finite = [spec.walk_speed, spec.jump_speed]
            .iter()
            .all(|x| x.is_finite());
        if !finite || spec.walk_speed < 0.0 || spec.jump_speed < 0.0 {
            return Err("walk_speed and jump_speed must be finite and not negative".into());
        }
        if spec.goal.is_some_and(|x| !x.is_finite()) {
            return Err("goal must be finite".into());
        }
        let def = CharacterDef::capsule(spec.half_height, spec.radius)
            .position(vec2(spec.position.0, spec.position.1));
        let character = Character::new(def).map_err(|e| e.to_string())?;
        Ok(Player {
            character,
            velocity: Vec2::zeros(),
            walk_speed: spec.walk_speed,
            jump_speed: spec.jump_speed,
            goal: spec.goal,
            jump_spent: false,
            recorded: spec.replay.clone(),
            replaying: false,
            input: PlayerInput::default(),
        })
    }

    /// Plays the scene's recorded play from here: its key changes take the keys over at
    /// their steps (the world's step count), whatever the host sets.
    pub fn replay(&mut self) {
        self.replaying = true;
    }

    /// Whether it plays the scene's recorded play.
    pub fn is_replaying(&self) -> bool {
        self.replaying
    }

    /// One step of `dt`: walk, jump, fall, move, clip.
    pub(crate) fn step(&mut self, world: &mut World, dt: Real) -> Result<(), CaromError> {
        if self.replaying {
            let now = world.step_count();
            for change in self.recorded.iter().filter(|c| c.step == now) {
                let key = match change.key {
                    PlayerKey::Left => &mut self.input.left,
                    PlayerKey::Right => &mut self.input.right,
                    PlayerKey::Jump => &mut self.input.jump,
                };
                *key = change.down;
            }
        }
        let walk = match (self.input.left, self.input.right) {
            (true, false) => -self.walk_speed,
            (false, true) => self.walk_speed,
            _ => 0.0,
        };
        let grounded = self.character.is_grounded();
        // Walking steers in the air too; standing still stops only on the ground.
        if grounded || walk != 0.0 {
            self.velocity.x = walk;
        }
        // A jump per press, as games have it: holding the key down does not bounce.
        if !self.input.jump {
            self.jump_spent = false;
        } else if grounded && !self.jump_spent {
            self.velocity.y = self.jump_speed;
            self.jump_spent = true;
        }
        let settings = world.settings();
        if settings.effects.contains(Effect::Gravity) {
            self.velocity += settings.gravity * dt;
        }
        world.move_character(&mut self.character, self.velocity * dt, dt)?;
        self.velocity = self.character.clip_velocity(self.velocity);
        Ok(())
    }

    /// Its character: where it is, what it stands on and touches.
    pub fn character(&self) -> &Character {
        &self.character
    }

    /// Its velocity, m/s.
    pub fn velocity(&self) -> Vec2 {
        self.velocity
    }

    /// Whether it is past the level's goal (never, for a scene without one).
    pub fn finished(&self) -> bool {
        self.goal
            .is_some_and(|goal| self.character.position().x >= goal)
    }

    /// Draws its capsule: an outline of two half circles joined, filled.
    pub(crate) fn draw(&self, out: &mut impl DebugDraw) {
        const HALF_TURN: usize = 8;
        let capsule = self.character.capsule();
        let (bottom, top, radius) = (capsule.center1(), capsule.center2(), capsule.radius());
        let axis = (top - bottom).try_normalize(1e-9).unwrap_or(vec2(0.0, 1.0));
        let side = vec2(axis.y, -axis.x);
        let mut outline = Vec::with_capacity(2 * HALF_TURN + 2);
        for (centre, start) in [(top, side), (bottom, -side)] {
            for i in 0..=HALF_TURN {
                let turn = carom::rotation(carom::consts::PI * i as Real / HALF_TURN as Real);
                outline.push(centre + turn * start * radius);
            }
        }
        let fill = Color::rgb(0.95, 0.55, 0.2);
        out.polygon(&outline, fill.with_alpha(0.8), fill);
    }

    pub(crate) fn saved(&self) -> SavedPlayer {
        SavedPlayer {
            state: self.character.state(),
            velocity: self.velocity,
            jump_spent: self.jump_spent,
        }
    }

    pub(crate) fn restore(&mut self, saved: SavedPlayer) -> Result<(), String> {
        if !(saved.velocity.x.is_finite() && saved.velocity.y.is_finite()) {
            return Err("the player's velocity is not finite".into());
        }
        self.character
            .restore(saved.state)
            .map_err(|e| e.to_string())?;
        self.velocity = saved.velocity;
        self.jump_spent = saved.jump_spent;
        Ok(())
    }
}
