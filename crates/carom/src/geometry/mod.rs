//! Geometry: shapes and their mass, bounding boxes, rays and segments.

pub(crate) mod aabb;
pub(crate) mod mass;
pub(crate) mod ray;
pub(crate) mod shape;
