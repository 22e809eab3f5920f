//! What the demo's timeline holds and costs over a long run (`carom-bench timeline`): a scene
//! played for many steps with its keyframes kept as the demo keeps them, the memory they take
//! as the run grows, and the time to go back to steps across the run.

use carom_scene::{SceneWorld, Timeline, TimelineError};
use std::time::{Duration, Instant};

/// The timeline at one moment of the run.
#[derive(Debug, Clone, Copy)]
pub struct Growth {
    /// Steps played.
    pub steps: u64,
    /// Keyframes kept.
    pub keyframes: usize,
    /// What the timeline counts of itself ([`Timeline::bytes`]).
    pub bytes: usize,
}

/// Going to one step of the run, from its end.
#[derive(Debug, Clone, Copy)]
pub struct Seek {
    /// The step gone to.
    pub to: u64,
    /// Steps replayed from the keyframe before it.
    pub replayed: u64,
    /// How long it took.
    pub time: Duration,
}

/// Plays `scene` for `steps` steps on `timeline`, noting its growth every `every` steps and
/// after the last.
///
/// # Errors
/// A step that fails.
pub fn play(
    scene: &mut SceneWorld,
    timeline: &mut Timeline,
    steps: u64,
    every: u64,
) -> Result<Vec<Growth>, TimelineError> {
    let mut growth = Vec::new();
    for step in 1..=steps {
        timeline.step(scene)?;
        if step % every.max(1) == 0 || step == steps {
            growth.push(Growth {
                steps: step,
                keyframes: timeline.keyframe_count(),
                bytes: timeline.bytes(),
            });
        }
    }
    Ok(growth)
}

/// Goes from the run's end to each of `targets` and back to the end, timing each way there.
///
/// # Errors
/// A step that fails, or a replayed step that ends elsewhere than it did.
pub fn seeks(
    scene: &mut SceneWorld,
    timeline: &mut Timeline,
    targets: &[u64],
) -> Result<Vec<Seek>, TimelineError> {
    let end = timeline.end();
    let mut seeks = Vec::new();
    for &to in targets {
        let from = timeline.keyframe_steps().filter(|&k| k <= to).last();
        let start = Instant::now();
        timeline.go_to(scene, to)?;
        seeks.push(Seek {
            to,
            replayed: to - from.unwrap_or(0),
            time: start.elapsed(),
        });
        timeline.go_to(scene, end)?;
    }
    Ok(seeks)
}
