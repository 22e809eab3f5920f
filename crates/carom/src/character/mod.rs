//! Characters: the kinematic mover's parts (planes, their solver, the world's mover queries)
//! and a character controller built on them.

pub(crate) mod controller;
pub(crate) mod mover;
pub(crate) mod planes;
