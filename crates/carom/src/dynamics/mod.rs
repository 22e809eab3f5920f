//! Dynamics: bodies, the colliders they are made of, drag, and the islands that sleep.

pub(crate) mod body;
pub(crate) mod collider;
pub(crate) mod drag;
pub(crate) mod island;
