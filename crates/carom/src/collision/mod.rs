//! Collision: which pairs are near (broadphase), how far apart two shapes are (distance),
//! where they touch (manifolds, with chains' smooth segments apart), which pairs may collide at
//! all (filters), the persistent contacts that carry it from step to step and the stage that
//! updates them each step (narrowphase), the user's pre-solve say over them, the hits they
//! report, sensors, shape casts, and continuous collision for fast bodies.

pub(crate) mod broadphase;
pub(crate) mod chain_segment;
pub(crate) mod contact;
pub(crate) mod continuous;
pub(crate) mod distance;
pub(crate) mod dynamic_tree;
pub(crate) mod filter;
pub(crate) mod hits;
pub(crate) mod look_ahead;
pub(crate) mod manifold;
pub(crate) mod narrowphase;
pub(crate) mod pre_solve;
pub(crate) mod query_filter;
pub(crate) mod recycle;
pub(crate) mod sensor;
pub(crate) mod shape_cast;
