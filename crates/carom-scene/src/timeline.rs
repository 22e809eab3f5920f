//! A run that can be gone back through, step by step: the [`Recording`] of every input and
//! step, and keyframes (the scene's whole state every so many steps) to start from.
//!
//! Going to an earlier step restores the keyframe at or before it and plays the recorded
//! inputs forward from there, so the scene is at exactly the bits it had the first time.
//! Playing on from an earlier step goes on through the recorded run, until the user does
//! something new: the run then branches, and what came after that step is forgotten.
//!
//! Keyframes are bounded by a memory budget. Past it the oldest are thinned, more of them the
//! further back they lie and the less work replaying their stretch of the run takes (a pile
//! asleep replays almost for free; its collapse does not), so the recent past stays a few
//! steps away and the whole run stays reachable.

use crate::recording::{Hand, Input, Recording};
use crate::scene_world::SceneWorld;
use crate::snapshot::SceneSnapshot;
use carom::CaromError;
use std::mem::size_of;

/// Steps between keyframes, before any are thinned: a third of a second at 60 Hz.
pub const KEYFRAME_EVERY: u64 = 20;

/// The keyframes' memory budget, bytes, before older ones are thinned. The timeline holds one
/// keyframe's worth more: the last one thinned, whose memory the next one reuses.
pub const KEYFRAME_BUDGET: usize = 192 << 20;

/// The scene's state at one step, before the inputs applied at that step.
#[derive(Debug)]
struct Keyframe {
    step: u64,
    scene: SceneSnapshot,
    hand: Hand,
    bytes: usize,
}

/// Whether an input changed the course of the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Course {
    /// The scene was at the end of its run: the input is the run's newest.
    Live,
    /// The scene was at an earlier step: the run branched there, and what the old run did
    /// after it is forgotten.
    Branched {
        /// The step the new branch starts from.
        at: u64,
        /// Steps of the old run forgotten.
        forgotten: u64,
    },
}

/// Why a timeline could not move.
#[derive(Debug, Clone, PartialEq)]
pub enum TimelineError {
    /// The world refused the step.
    Step(CaromError),
    /// An input could not be applied (a setting out of range), named.
    Input(String),
    /// A replayed step did not end in the state the run recorded. It cannot happen while a
    /// step gives the same bits each time; it is reported rather than hidden if it does.
    Diverged {
        /// The step (counted from 1) whose hash differs.
        step: u64,
    },
}

impl std::fmt::Display for TimelineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TimelineError::Step(e) => e.fmt(f),
            TimelineError::Input(reason) => f.write_str(reason),
            TimelineError::Diverged { step } => write!(
                f,
                "replaying the run, step {step} did not end where it did the first time"
            ),
        }
    }
}

impl std::error::Error for TimelineError {}

impl From<CaromError> for TimelineError {
    fn from(e: CaromError) -> Self {
        TimelineError::Step(e)
    }
}

/// A run and its keyframes; see the module's documentation. The timeline owns the [`Hand`]
/// that applies inputs, because going back in time puts the hand back too.
#[derive(Debug)]
pub struct Timeline {
    recording: Recording,
    hand: Hand,
    keyframes: Vec<Keyframe>,
    /// Steps the scene has taken: at most the recording's.
    at: u64,
    /// The work of replaying the run's steps, summed: `work[k]` is that of its first `k`
    /// steps, a step's work the bodies awake and the friction impulses it solved, plus one.
    work: Vec<u64>,
    every: u64,
    budget: usize,
    /// A thinned keyframe's snapshot, whose memory the next keyframe reuses.
    spare: Option<SceneSnapshot>,
}

impl Timeline {
    /// A timeline of `scene` as it is now, the start of `recording` (its scene's text and
    /// name; a recording's steps and inputs are dropped, since this run starts here), with a
    /// keyframe every [`KEYFRAME_EVERY`] steps within [`KEYFRAME_BUDGET`].
    pub fn new(recording: Recording, scene: &SceneWorld) -> Timeline {
        Timeline::with_keyframes(recording, scene, KEYFRAME_EVERY, KEYFRAME_BUDGET)
    }

    /// [`Timeline::new`] with a keyframe every `every` steps (at least 1) and at most
    /// `budget` bytes of them (the first keyframe and the newest are always kept; the last one
    /// thinned is held for its memory's reuse beside them).
    pub fn with_keyframes(
        mut recording: Recording,
        scene: &SceneWorld,
        every: u64,
        budget: usize,
    ) -> Timeline {
        recording.truncate(0);
        recording.inputs.clear();
        let mut timeline = Timeline {
            recording,
            hand: Hand::default(),
            keyframes: Vec::new(),
            at: 0,
            work: vec![0],
            every: every.max(1),
            budget,
            spare: None,
        };
        timeline.keep_keyframe(scene);
        timeline
    }

    /// The run so far: every input and every step's hash, to the end of the newest branch.
    pub fn recording(&self) -> &Recording {
        &self.recording
    }

    /// The hand that applies inputs (the body it holds).
    pub fn hand(&self) -> &Hand {
        &self.hand
    }

    /// Steps the scene has taken: where on the timeline it is.
    pub fn at(&self) -> u64 {
        self.at
    }

    /// Steps in the run: the end of the timeline.
    pub fn end(&self) -> u64 {
        self.recording.steps()
    }

    /// Whether the scene is at the end of its run, where a step is a new one.
    pub fn is_live(&self) -> bool {
        self.at == self.end()
    }

    /// How many keyframes are kept.
    pub fn keyframe_count(&self) -> usize {
        self.keyframes.len()
    }

    /// The steps of the keyframes kept, in order.
    pub fn keyframe_steps(&self) -> impl Iterator<Item = u64> + '_ {
        self.keyframes.iter().map(|k| k.step)
    }

    /// The memory the timeline holds, bytes: its keyframes (and the memory of the last one
    /// thinned, kept for the next) and its recording.
    pub fn bytes(&self) -> usize {
        let spare = self.spare.as_ref().map_or(0, SceneSnapshot::heap_bytes);
        let keyframes: usize = self.keyframes.iter().map(|k| k.bytes).sum::<usize>() + spare;
        let recording = (self.recording.hashes.capacity() + self.work.capacity())
            * size_of::<u64>()
            + self.recording.inputs.capacity() * size_of::<crate::recording::Timed>()
            + self.recording.scene.capacity();
        keyframes + recording
    }

    /// Applies `input` to `scene` and records it. At an earlier step than the run's end, the
    /// run branches there first: the old run's later steps and inputs are forgotten.
    ///
    /// # Errors
    /// A setting out of range; the scene and the run are then left as they were.
    pub fn input(&mut self, scene: &mut SceneWorld, input: Input) -> Result<Course, TimelineError> {
        let mut hand = self.hand;
        hand.apply(scene, &input).map_err(TimelineError::Input)?;
        self.hand = hand;
        let course = if self.is_live() {
            Course::Live
        } else {
            let forgotten = self.end() - self.at;
            self.recording.truncate(self.at);
            self.work.truncate(self.at as usize + 1);
            self.keyframes.retain(|k| k.step <= self.at);
            Course::Branched {
                at: self.at,
                forgotten,
            }
        };
        self.recording.input(input);
        Ok(course)
    }

    /// One step forward: at the end of the run a new step, recorded; before it, the
    /// recorded run's next step, with the inputs recorded before the step after it.
    ///
    /// # Errors
    /// A step that fails, or (never, while steps give the same bits) a replayed step that
    /// ends elsewhere than it did.
    pub fn step(&mut self, scene: &mut SceneWorld) -> Result<(), TimelineError> {
        let live = self.is_live();
        scene.step()?;
        self.hand.after_step(&scene.world);
        self.at += 1;
        if live {
            self.recording.step(&scene.world);
            let stats = scene.world.stats();
            let work = (stats.bodies - stats.sleeping_bodies + stats.work.friction_impulses) as u64;
            let before = self.work.last().copied().unwrap_or(0);
            self.work.push(before + work + 1);
            if self.at.is_multiple_of(self.every) {
                self.keep_keyframe(scene);
            }
            return Ok(());
        }
        let recorded = self.recording.hashes[(self.at - 1) as usize];
        if scene.world.state_hash() != recorded {
            return Err(TimelineError::Diverged { step: self.at });
        }
        self.apply_recorded_inputs(scene)
    }

    /// Puts the scene at step `target` of the run (at most its end): from the keyframe at
    /// or before it, or from where the scene is if that is nearer, it plays the recorded run
    /// forward.
    ///
    /// # Errors
    /// As [`Timeline::step`].
    pub fn go_to(&mut self, scene: &mut SceneWorld, target: u64) -> Result<(), TimelineError> {
        let target = self.start_toward(scene, target)?;
        while self.at < target {
            self.step(scene)?;
        }
        Ok(())
    }

    /// Takes the first move toward step `target` (clamped to the run's end, and returned):
    /// restores the keyframe at or before it unless the scene is already nearer. What is
    /// left is [`Timeline::step`] until [`Timeline::at`] is the target, which a caller with
    /// a frame budget spreads over frames.
    ///
    /// # Errors
    /// A recorded input that no longer applies (never: it applied the first time).
    pub fn start_toward(
        &mut self,
        scene: &mut SceneWorld,
        target: u64,
    ) -> Result<u64, TimelineError> {
        let target = target.min(self.end());
        let nearest = self
            .keyframes
            .iter()
            .rposition(|k| k.step <= target)
            .unwrap_or(0);
        let from = self.keyframes.get(nearest).map_or(0, |k| k.step);
        let going_back = target < self.at;
        if going_back || from > self.at {
            let keyframe = &self.keyframes[nearest];
            scene.restore(&keyframe.scene);
            self.hand = keyframe.hand;
            self.at = keyframe.step;
            // A keyframe is the state before the inputs of its step.
            self.apply_recorded_inputs(scene)?;
        }
        Ok(target)
    }

    /// Applies the inputs recorded before the step after [`Timeline::at`].
    fn apply_recorded_inputs(&mut self, scene: &mut SceneWorld) -> Result<(), TimelineError> {
        let at = self.at;
        let first = self.recording.inputs.partition_point(|t| t.step < at);
        for timed in self.recording.inputs[first..]
            .iter()
            .take_while(|t| t.step == at)
        {
            self.hand
                .apply(scene, &timed.input)
                .map_err(TimelineError::Input)?;
        }
        Ok(())
    }

    /// Keeps the scene's state now as a keyframe, then thins older ones past the budget.
    fn keep_keyframe(&mut self, scene: &SceneWorld) {
        let snapshot = match self.spare.take() {
            Some(mut spare) => {
                scene.snapshot_into(&mut spare);
                spare
            }
            None => scene.snapshot(),
        };
        let bytes = snapshot.heap_bytes() + size_of::<Keyframe>();
        self.keyframes.push(Keyframe {
            step: self.at,
            scene: snapshot,
            hand: self.hand,
            bytes,
        });
        while self.keyframes.iter().map(|k| k.bytes).sum::<usize>() > self.budget {
            let Some(index) = self.thinnest() else { break };
            self.spare = Some(self.keyframes.remove(index).scene);
        }
    }

    /// The keyframe whose loss costs least: the one whose neighbours are nearest in the work
    /// of replaying from one to the other, weighed by its age, so gaps grow with age and
    /// with quiet. Never the first or the newest.
    fn thinnest(&self) -> Option<usize> {
        let newest = self.keyframes.last()?.step;
        let slack = (self.every * THINNING_SLACK) as f64;
        let work = |step: u64| self.work.get(step as usize).copied().unwrap_or(0);
        (1..self.keyframes.len().saturating_sub(1)).min_by(|&a, &b| {
            let cost = |i: usize| {
                let (before, after) = (self.keyframes[i - 1].step, self.keyframes[i + 1].step);
                let gap = (work(after) - work(before)) as f64;
                gap / ((newest - self.keyframes[i].step) as f64 + slack)
            };
            cost(a).total_cmp(&cost(b))
        })
    }
}

/// The age, in keyframe intervals, below which keyframes are thinned about evenly: the gaps
/// grow in proportion to age only past it, so a long run's old half is not left with a
/// handful of keyframes.
const THINNING_SLACK: u64 = 30;
