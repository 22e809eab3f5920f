//! `carom record` and `carom replay`: a scene run headless and written out as a recording
//! ([`carom_scene::Recording`]), and a recording played back and checked step by step. The web
//! build plays recordings back the same way, so a run recorded on one replays on the other.

use crate::files;
use carom_scene::{Parting, Recording, SceneError, SceneWorld};
use std::path::Path;

/// Opens the scene file `path` for a recorded run: the file is read once, and the scene is
/// built from the text the recording keeps.
///
/// # Errors
/// A scene that does not read, parse or build, named as loading it names it.
pub fn open(path: &Path) -> Result<(SceneWorld, Recording), String> {
    let file = path.display().to_string();
    let text = files::read_to_string(path).map_err(|source| {
        SceneError::Io {
            file: file.clone(),
            source,
        }
        .to_string()
    })?;
    let recording = Recording::new(&file, &text);
    let scene = recording.start().map_err(|e| e.to_string())?;
    Ok((scene, recording))
}

/// Runs the scene in `scene` headless for `steps` steps, with no input, and records it.
///
/// # Errors
/// A scene that does not read, parse or build, or a step that fails.
pub fn record(scene: &Path, steps: u64) -> Result<Recording, String> {
    let (mut world, mut recording) = open(scene)?;
    for _ in 0..steps {
        world.step().map_err(|e| e.to_string())?;
        recording.step(&world.world);
    }
    Ok(recording)
}

/// What a replay found.
#[derive(Debug, Clone, PartialEq)]
pub struct Replayed {
    /// The recorded scene's file name.
    pub name: String,
    /// Steps recorded.
    pub steps: u64,
    /// Inputs recorded.
    pub inputs: usize,
    /// The first step whose hash differs, if one does.
    pub parting: Option<Parting>,
}

/// Plays back the recording `text` (from the file `file`) and checks every step's hash.
///
/// # Errors
/// Text that is not a recording, a scene that does not build, or a step that fails.
pub fn replay(text: &str, file: &str) -> Result<Replayed, String> {
    let recording = Recording::parse(text, file).map_err(|e| e.to_string())?;
    let parting = recording.replay().map_err(|e| e.to_string())?;
    Ok(Replayed {
        name: recording.name.clone(),
        steps: recording.steps(),
        inputs: recording.inputs.len(),
        parting,
    })
}

impl Replayed {
    /// One line for a person: every step matched, or where the replay parted.
    pub fn summary(&self) -> String {
        match self.parting {
            None => format!(
                "{}: {} steps and {} inputs replayed; every step ends in the recorded hash",
                self.name, self.steps, self.inputs
            ),
            Some(parting) => format!(
                "{}: step {} of {} ends in hash {:016x}, recorded as {:016x}: the replay parts \
                 from the recording there",
                self.name, parting.step, self.steps, parting.replayed, parting.recorded
            ),
        }
    }

    /// One JSON object: `{"scene": …, "steps": …, "inputs": …, "parted_at": step or null}`.
    pub fn to_json(&self) -> String {
        let parted = self
            .parting
            .map_or_else(|| "null".to_string(), |p| p.step.to_string());
        format!(
            "{{\"scene\": {:?}, \"steps\": {}, \"inputs\": {}, \"parted_at\": {parted}}}",
            self.name, self.steps, self.inputs
        )
    }
}
