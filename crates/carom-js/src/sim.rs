//! What a JS `World` owns: a plain world, or a world built from a scene with what the scene
//! adds (its time step, names and timed events).

use carom::{CaromError, Real, World};
use carom_scene::SceneWorld;

/// The default time step of a plain world, seconds: 60 steps a second.
pub(crate) const DEFAULT_TIME_STEP: Real = 1.0 / 60.0;

pub(crate) enum Sim {
    Plain(Box<World>),
    Scene(Box<SceneWorld>),
}

impl Sim {
    pub(crate) fn world(&self) -> &World {
        match self {
            Sim::Plain(world) => world,
            Sim::Scene(scene) => &scene.world,
        }
    }

    pub(crate) fn world_mut(&mut self) -> &mut World {
        match self {
            Sim::Plain(world) => world,
            Sim::Scene(scene) => &mut scene.world,
        }
    }

    /// The step a call without one takes: the scene's, or 1/60 s.
    pub(crate) fn time_step(&self) -> Real {
        match self {
            Sim::Plain(_) => DEFAULT_TIME_STEP,
            Sim::Scene(scene) => scene.time_step,
        }
    }

    /// One step of `dt` seconds; a scene's timed events fire first, as in `carom run`, and
    /// its character (if any) stands still.
    pub(crate) fn step(&mut self, dt: Real) -> Result<(), CaromError> {
        match self {
            Sim::Plain(world) => world.step(dt),
            Sim::Scene(scene) if dt == scene.time_step => scene.step(),
            Sim::Scene(scene) => {
                scene.fire_events();
                scene.world.step(dt)
            }
        }
    }
}
