//! Collision, the world's stages: which pairs are near (broadphase), the persistent contacts
//! that carry a pair from step to step and the stage that updates them each step
//! (narrowphase, recycling manifolds that still hold), the user's pre-solve say over them, the
//! hits they report, sensors, and continuous collision for fast bodies. The pairwise geometry
//! they call (distances, manifolds, casts, the box tree) is `geometry::query` and
//! `geometry::dynamic_tree`, a layer down.

pub(crate) mod broadphase;
pub(crate) mod contact;
pub(crate) mod continuous;
pub(crate) mod hits;
pub(crate) mod narrowphase;
pub(crate) mod pre_solve;
pub(crate) mod query_filter;
pub(crate) mod recycle;
pub(crate) mod sensor;
