//! Dynamics: bodies, the colliders they are made of, drag, and sleeping.

pub(crate) mod body;
pub(crate) mod collider;
pub(crate) mod drag;

pub(crate) mod sleep;
