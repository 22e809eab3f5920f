//! A run recorded, to play back exactly: the scene as its file read when the run began, every
//! input applied to it with the step it came before (grabs, drags, throws, the player's keys,
//! solver and effect changes), and the world's state hash after every step.
//!
//! A step gives the same bits on every machine carom is tested on, so a replay ends each step
//! in the hash recorded, natively or in a browser, whichever of them recorded it. A replay that
//! does not names the first step whose hash differs: the step where the two runs parted.

use crate::build::build;
use crate::error::SceneError;
use crate::load::parse;
use crate::player::PlayerInput;
use crate::scene_world::SceneWorld;
use carom::{BodyHandle, Effect, JointDef, JointHandle, Real, SolverParams, World, vec2};
use serde::{Deserialize, Serialize};

/// The version of the recording's form; a recording in another is refused.
pub const RECORDING_FORMAT: u32 = 1;

/// How hard the cursor's spring may pull a grabbed body, as an acceleration of its mass, m/s²
/// (Box2D's samples pull with 1000 times the body's mass).
pub const GRAB_ACCELERATION: Real = 1000.0;

/// What a user does to a running scene.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Input {
    /// Grab the dynamic body under this world point, there, with the cursor's spring (nothing
    /// happens over empty space or a body that is not dynamic). A grab lets go of the last one.
    Grab {
        /// Where, m.
        point: (Real, Real),
    },
    /// Move the grabbed body's spring to this world point.
    Drag {
        /// Where, m.
        point: (Real, Real),
    },
    /// Let go of the grabbed body: it keeps the velocity it has (a throw).
    LetGo,
    /// The keys the scene's player holds from now on.
    Keys {
        /// Walk left.
        left: bool,
        /// Walk right.
        right: bool,
        /// Jump.
        jump: bool,
    },
    /// The player plays the scene's recorded play from now on.
    PlayRecordedKeys,
    /// The solver's settings from now on.
    Solver(SolverParams),
    /// An effect switched on or off.
    Effect {
        /// Which.
        effect: Effect,
        /// On or off.
        on: bool,
    },
}

impl Input {
    /// The keys held as an input.
    pub fn keys(keys: PlayerInput) -> Input {
        Input::Keys {
            left: keys.left,
            right: keys.right,
            jump: keys.jump,
        }
    }
}

/// An input and the step it came before: the number of steps taken since the recording began.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Timed {
    /// Steps taken before the input.
    pub step: u64,
    /// The input.
    pub input: Input,
}

/// What the user's hand holds of a scene: the body it grabbed, and the spring that pulls it.
/// Both the demo and a replay apply inputs through one, so both do the same thing.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Hand {
    grab: Option<(JointHandle, BodyHandle)>,
}

impl Hand {
    /// Applies `input` to `scene`.
    ///
    /// # Errors
    /// A setting out of range, named; the scene is then left as it was.
    pub fn apply(&mut self, scene: &mut SceneWorld, input: &Input) -> Result<(), String> {
        let world = &mut scene.world;
        match *input {
            Input::Grab { point: (x, y) } => {
                self.let_go(world);
                let point = vec2(x, y);
                let Some(body) = world.body_at(point) else {
                    return Ok(());
                };
                let Some(mass) = world
                    .body(body)
                    .filter(|b| b.is_dynamic())
                    .map(|b| b.mass())
                else {
                    return Ok(());
                };
                let def = JointDef::mouse(body, point, GRAB_ACCELERATION * mass);
                self.grab = world.add_joint(def).ok().map(|joint| (joint, body));
            }
            Input::Drag { point: (x, y) } => {
                if let Some(mut joint) = self.grab.and_then(|(joint, _)| world.joint_mut(joint)) {
                    joint
                        .set_mouse_target(vec2(x, y))
                        .map_err(|e| e.to_string())?;
                }
            }
            Input::LetGo => self.let_go(world),
            Input::Keys { left, right, jump } => {
                if let Some(player) = &mut scene.player {
                    player.input = PlayerInput { left, right, jump };
                }
            }
            Input::PlayRecordedKeys => {
                if let Some(player) = &mut scene.player {
                    player.replay();
                }
            }
            Input::Solver(params) => world
                .update_settings(|s| s.solver = params)
                .map_err(|e| e.to_string())?,
            Input::Effect { effect, on } => world
                .update_settings(|s| s.effects.set(effect, on))
                .map_err(|e| e.to_string())?,
        }
        Ok(())
    }

    /// The body held and its spring, if any.
    pub fn grabbed(&self) -> Option<(JointHandle, BodyHandle)> {
        self.grab
    }

    /// After a step: forgets the grab if its spring is gone (the body was removed, or the
    /// joint broke).
    pub fn after_step(&mut self, world: &World) {
        if self
            .grab
            .is_some_and(|(joint, _)| world.joint(joint).is_none())
        {
            self.grab = None;
        }
    }

    fn let_go(&mut self, world: &mut World) {
        if let Some((joint, _)) = self.grab.take() {
            // Gone already if the body was removed or the joint broke.
            let _ = world.remove_joint(joint);
        }
    }
}

/// A run recorded: see the module's documentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recording {
    /// [`RECORDING_FORMAT`] when written.
    pub format: u32,
    /// The scene file's name, for messages.
    pub name: String,
    /// The scene file's text when the run began.
    pub scene: String,
    /// The inputs, in the order they were applied.
    pub inputs: Vec<Timed>,
    /// The world's state hash ([`World::state_hash`]) after each step: `hashes[k]` after step
    /// `k + 1`.
    pub hashes: Vec<u64>,
}

/// Where a replay parted from its recording.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Parting {
    /// The first step (counted from 1) whose hash differs.
    pub step: u64,
    /// The hash recorded after it.
    pub recorded: u64,
    /// The hash the replay ended it in.
    pub replayed: u64,
}

impl Recording {
    /// A recording of `scene` (the text of the file `name`) that has taken no step yet.
    pub fn new(name: &str, scene: &str) -> Recording {
        Recording {
            format: RECORDING_FORMAT,
            name: name.to_string(),
            scene: scene.to_string(),
            inputs: Vec::new(),
            hashes: Vec::new(),
        }
    }

    /// Steps recorded.
    pub fn steps(&self) -> u64 {
        self.hashes.len() as u64
    }

    /// Notes `input`, applied now, before the next step.
    pub fn input(&mut self, input: Input) {
        self.inputs.push(Timed {
            step: self.steps(),
            input,
        });
    }

    /// Notes a step taken, and the world's hash after it.
    pub fn step(&mut self, world: &World) {
        self.hashes.push(world.state_hash());
    }

    /// Forgets everything after the first `steps` steps: the run went back to that moment
    /// and goes on from there another way (the inputs applied then are kept).
    pub fn truncate(&mut self, steps: u64) {
        self.hashes.truncate(steps as usize);
        self.inputs.retain(|timed| timed.step <= steps);
    }

    /// The recording as text (RON).
    pub fn to_text(&self) -> String {
        let pretty = ron::ser::PrettyConfig::default().compact_arrays(true);
        ron::ser::to_string_pretty(self, pretty).unwrap_or_default()
    }

    /// Reads a recording; `file` names it in errors.
    ///
    /// # Errors
    /// Text that is not a recording, or one in another format.
    pub fn parse(text: &str, file: &str) -> Result<Recording, SceneError> {
        let recording: Recording = ron::from_str(text).map_err(|e| SceneError::Syntax {
            file: file.to_string(),
            line: e.span.start.line,
            column: e.span.start.col,
            message: e.code.to_string(),
        })?;
        if recording.format != RECORDING_FORMAT {
            return Err(SceneError::Invalid {
                file: file.to_string(),
                what: "the recording".into(),
                reason: format!(
                    "it is in recording format {}, and this carom reads format \
                     {RECORDING_FORMAT} only",
                    recording.format
                ),
            });
        }
        Ok(recording)
    }

    /// The scene as the run began.
    ///
    /// # Errors
    /// A scene that does not parse or build.
    pub fn start(&self) -> Result<SceneWorld, SceneError> {
        build(&parse(&self.scene, &self.name)?, &self.name)
    }

    /// Plays the run back from its start, applying each input before the step it came
    /// before, and checks the hash after every step. Stops at the first step whose hash
    /// differs and returns where; `None` when every step matched.
    ///
    /// # Errors
    /// A scene that does not build, an input that cannot be applied, or a step that fails.
    pub fn replay(&self) -> Result<Option<Parting>, SceneError> {
        let mut scene = self.start()?;
        let invalid = |what: &str, reason: String| SceneError::Invalid {
            file: self.name.clone(),
            what: what.into(),
            reason,
        };
        let mut hand = Hand::default();
        let mut inputs = self.inputs.iter().peekable();
        for (index, &recorded) in self.hashes.iter().enumerate() {
            let taken = index as u64;
            while let Some(timed) = inputs.next_if(|timed| timed.step <= taken) {
                hand.apply(&mut scene, &timed.input).map_err(|reason| {
                    invalid(&format!("the input before step {}", taken + 1), reason)
                })?;
            }
            scene
                .step()
                .map_err(|e| invalid(&format!("step {}", taken + 1), e.to_string()))?;
            hand.after_step(&scene.world);
            let replayed = scene.world.state_hash();
            if replayed != recorded {
                return Ok(Some(Parting {
                    step: taken + 1,
                    recorded,
                    replayed,
                }));
            }
        }
        Ok(None)
    }
}
