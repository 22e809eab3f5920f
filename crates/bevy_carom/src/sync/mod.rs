//! Keeping the carom world in step with the entities: making, changing and removing its
//! bodies, colliders and joints as the game spawns, edits and despawns them.

pub(crate) mod create;
pub(crate) mod remove;
pub(crate) mod update;
