//! What two shapes do to each other, with no world around them: how far apart they are
//! (`distance`), where they touch (`collide`, which builds a pair's `manifold`, chains' smooth
//! segments in `chain_segment`) and when one moving shape first touches another
//! (`shape_cast`).

pub(crate) mod chain_segment;
pub(crate) mod collide;
pub(crate) mod distance;
pub(crate) mod manifold;
pub(crate) mod shape_cast;
