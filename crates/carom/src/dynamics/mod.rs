//! Dynamics: bodies and their storage, drag, and sleeping.

pub(crate) mod body;
pub(crate) mod body_set;
pub(crate) mod drag;

pub(crate) mod sleep;
