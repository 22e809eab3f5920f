//! Geometry: shapes and their mass, bounding boxes, rays and segments.

pub(crate) mod aabb;
pub(crate) mod capsule;
pub(crate) mod checks;
pub(crate) mod circle;
pub(crate) mod mass;
pub(crate) mod points;
pub(crate) mod polygon;
pub(crate) mod ray;
pub(crate) mod segment;
pub(crate) mod shape;
