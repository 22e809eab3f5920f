//! Scenes as data for carom: RON files in `demos/` describe a world (settings, effects,
//! bodies, generators) and what happens in it over time. Loading lives here so the physics core
//! stays free of file formats.
//!
//! A scene file is read as untrusted: any text gives a scene or an error, never a panic, and
//! building refuses a scene that asks its generators for more bodies or joints than its
//! [`Limits`] (half a million each unless raised with [`build_with_limits`]) before it makes
//! anything.
//!
//! ```
//! let scene = carom_scene::parse(r#"(
//!     name: "drop",
//!     bodies: [
//!         (kind: static, shape: Box(width: 20.0, height: 1.0), position: (0.0, -0.5)),
//!         (name: Some("ball"), shape: Circle(radius: 0.5), position: (0.0, 5.0)),
//!     ],
//! )"#, "drop.ron")?;
//! let mut built = carom_scene::build(&scene, "drop.ron")?;
//! for _ in 0..60 {
//!     built.step()?;
//! }
//! let ball = built.world.body(built.names["ball"]).unwrap();
//! assert!(ball.position().y < 5.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// A panic that a caller's input can reach is a bug. Each `expect`, `unreachable!` and
// `panic!` left in the library says, in the `allow` beside it, why no input reaches it.
#![cfg_attr(
    not(test),
    warn(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::unreachable,
        clippy::todo,
        clippy::unimplemented
    )
)]
// Times widen to `f64` for the world's clock; in the double-precision build those casts are
// no-ops.
#![cfg_attr(feature = "f64", allow(clippy::unnecessary_cast))]

mod build;
mod defs;
mod error;
mod events;
mod generate;
mod limits;
mod load;
mod one_way;
mod pending_joint;
mod player;
mod recording;
mod saved;
pub mod scene;
mod scene_world;
mod snapshot;
mod spawn;
mod timeline;

pub use build::{build, build_with_limits};
pub use error::SceneError;
pub use limits::Limits;
pub use load::{parse, read};
pub use player::{Player, PlayerInput};
pub use recording::{GRAB_ACCELERATION, Hand, Input, Parting, RECORDING_FORMAT, Recording, Timed};
pub use saved::{SavedState, to_text, write};
pub use scene::{Accuracy, Camera, KeyChange, PlayerKey, SCENE_FORMAT, Scene};
pub use scene_world::SceneWorld;
pub use snapshot::SceneSnapshot;
pub use spawn::{Made, SpawnChange, SpawnSchedule};
pub use timeline::{Course, KEYFRAME_BUDGET, KEYFRAME_EVERY, Timeline, TimelineError};

/// Reads, parses and builds a scene file, within the default [`Limits`].
pub fn load(path: &std::path::Path) -> Result<SceneWorld, SceneError> {
    let scene = read(path)?;
    build(&scene, &path.display().to_string())
}
