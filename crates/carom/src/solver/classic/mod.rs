//! The classic solvers, from the tutorial's to Box2D v2.4's: each takes the touching
//! contacts one by one in contact order, over the whole step (no substeps).
//!
//! - [`push_out`]: overlapping bodies moved apart, approaching velocity removed; no impulses.
//! - [`tutorial_impulse`]: the tutorial's per-point impulses with a Baumgarte bias.
//! - [`sequential_impulse`]: accumulated, clamped, warm-started impulses with joints, and
//!   position passes after the bodies move (Catto 2006, Box2D v2.4).

pub(crate) mod push_out;
pub(crate) mod sequential_impulse;
pub(crate) mod tutorial_impulse;
