//! Geometry: shapes and their mass, bounding boxes, rays and segments, what two shapes do to
//! each other (`query`), and the tree of boxes that finds which shapes are near.

pub(crate) mod aabb;
pub(crate) mod capsule;
pub(crate) mod checks;
pub(crate) mod circle;
pub(crate) mod dynamic_tree;
pub(crate) mod look_ahead;
pub(crate) mod mass;
pub(crate) mod points;
pub(crate) mod polygon;
pub(crate) mod query;
pub(crate) mod ray;
pub(crate) mod segment;
pub(crate) mod shape;
