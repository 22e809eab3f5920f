//! Dynamics: bodies, the colliders they are made of (chains among them), drag, and the
//! islands that sleep.

pub(crate) mod body;
pub(crate) mod body_def;
pub(crate) mod chain;
pub(crate) mod collider;
pub(crate) mod drag;
pub(crate) mod island;
pub(crate) mod surface;
