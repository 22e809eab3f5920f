//! Dynamics: bodies, the colliders they are made of (chains among them), which colliders may
//! collide (filters), their surfaces and how two surfaces mix, drag, and the islands that sleep.

pub(crate) mod body;
pub(crate) mod body_def;
pub(crate) mod chain;
pub(crate) mod collider;
pub(crate) mod drag;
pub(crate) mod filter;
pub(crate) mod island;
pub(crate) mod surface;
