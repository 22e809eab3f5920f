//! A shape as scenes and saved worlds write it: its outline in the coordinates it was given
//! in, checked again when read; and, for a saved world's colliders, bit for bit.

use super::{ChainSegment, Polygon, Shape};
use crate::math::{Real, Vec2};
use serde::de::{self, Deserializer};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

/// A shape as it is written: a circle's radius, a convex polygon's outline in the coordinates
/// it was given in (read back, it is centred on its centroid again) and its rounding, a
/// capsule's centres and radius, a segment's ends, a chain link's four points.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Shape", rename_all = "snake_case", deny_unknown_fields)]
enum ShapeData {
    Circle {
        radius: Real,
    },
    Capsule {
        center1: Vec2,
        center2: Vec2,
        radius: Real,
    },
    Polygon {
        points: Vec<Vec2>,
        #[serde(default)]
        radius: Real,
        /// Given, `points` are the vertices around the centroid, counter-clockwise, and this
        /// is where the centroid was: they are kept exactly as written (a saved world's form).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        centroid: Option<Vec2>,
    },
    Segment {
        point1: Vec2,
        point2: Vec2,
    },
    ChainSegment {
        ghost1: Vec2,
        point1: Vec2,
        point2: Vec2,
        ghost2: Vec2,
    },
}

impl Serialize for Shape {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Shape::Circle(c) => ShapeData::Circle { radius: c.radius() },
            Shape::Capsule(c) => ShapeData::Capsule {
                center1: c.center1(),
                center2: c.center2(),
                radius: c.radius(),
            },
            Shape::Polygon(p) => ShapeData::Polygon {
                points: p
                    .vertices()
                    .iter()
                    .map(|v| v + p.source_centroid())
                    .collect(),
                radius: p.radius(),
                centroid: None,
            },
            Shape::Segment(s) => ShapeData::Segment {
                point1: s.point1(),
                point2: s.point2(),
            },
            Shape::ChainSegment(s) => ShapeData::ChainSegment {
                ghost1: s.ghost1(),
                point1: s.point1(),
                point2: s.point2(),
                ghost2: s.ghost2(),
            },
        }
        .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Shape {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let shape = match ShapeData::deserialize(deserializer)? {
            ShapeData::Circle { radius } => Shape::circle(radius),
            ShapeData::Capsule {
                center1,
                center2,
                radius,
            } => Shape::capsule(center1, center2, radius),
            ShapeData::Polygon {
                points,
                radius,
                centroid: None,
            } => Shape::Polygon(
                Polygon::new(&points)
                    .map_err(de::Error::custom)?
                    .rounded(radius),
            ),
            ShapeData::Polygon {
                points,
                radius,
                centroid: Some(centroid),
            } => Shape::Polygon(
                Polygon::from_centred(points, centroid)
                    .map_err(de::Error::custom)?
                    .rounded(radius),
            ),
            ShapeData::Segment { point1, point2 } => Shape::segment(point1, point2),
            ShapeData::ChainSegment {
                ghost1,
                point1,
                point2,
                ghost2,
            } => Shape::ChainSegment(ChainSegment::new(ghost1, point1, point2, ghost2)),
        };
        shape.validate().map_err(de::Error::custom)?;
        Ok(shape)
    }
}

/// A collider's shape in a saved world, bit for bit: a polygon is written as its vertices
/// around its centroid with where that centroid was, where the outline of [`Shape`]'s own form
/// would be centred again and could round differently. Read back, the vertices are checked as
/// any polygon's are.
pub(crate) mod exact_shape {
    use super::{Shape, ShapeData};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub(crate) fn serialize<S: Serializer>(
        shape: &Shape,
        serializer: S,
    ) -> Result<S::Ok, S::Error> {
        match shape {
            Shape::Polygon(p) => ShapeData::Polygon {
                points: p.vertices().to_vec(),
                radius: p.radius(),
                centroid: Some(p.source_centroid()),
            }
            .serialize(serializer),
            other => other.serialize(serializer),
        }
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Shape, D::Error> {
        Shape::deserialize(deserializer)
    }
}
