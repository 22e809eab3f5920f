//! Serde for the types whose storage is not their meaning: sets of flags read and written as
//! lists of names, shapes as their outline (checked again when read).

use crate::debug_draw::DrawFlags;
use crate::geometry::shape::{ChainSegment, Polygon, Shape};
use crate::math::{Real, Vec2};
use crate::partition::Partition;
use crate::world::effects::{Effect, Effects};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};
use std::fmt;

impl Serialize for Effects {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let on: Vec<Effect> = Effect::ALL
            .into_iter()
            .filter(|&e| self.contains(e))
            .collect();
        on.serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Effects {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let list = Vec::<Effect>::deserialize(deserializer)?;
        Ok(list.into_iter().fold(Effects::NONE, Effects::with))
    }
}

impl Serialize for DrawFlags {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let on: Vec<&str> = DrawFlags::NAMED
            .iter()
            .filter(|(_, flag)| self.contains(*flag))
            .map(|(name, _)| *name)
            .collect();
        let mut seq = serializer.serialize_seq(Some(on.len()))?;
        for name in on {
            seq.serialize_element(&DrawLayer(name))?;
        }
        seq.end()
    }
}

/// One draw layer's name, written as a bare identifier (as an enum variant is).
struct DrawLayer(&'static str);

impl Serialize for DrawLayer {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let index = DrawFlags::NAMED
            .iter()
            .position(|(name, _)| *name == self.0)
            .unwrap_or(0);
        serializer.serialize_unit_variant("DrawFlags", index as u32, self.0)
    }
}

impl<'de> Deserialize<'de> for DrawFlags {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Layers;
        impl<'de> Visitor<'de> for Layers {
            type Value = DrawFlags;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a list of draw layers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<DrawFlags, A::Error> {
                let mut flags = DrawFlags::NONE;
                while let Some(LayerName(flag)) = seq.next_element()? {
                    flags = flags | flag;
                }
                Ok(flags)
            }
        }
        deserializer.deserialize_seq(Layers)
    }
}

/// A draw layer read from its name.
struct LayerName(DrawFlags);

impl<'de> Deserialize<'de> for LayerName {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Name;
        impl Visitor<'_> for Name {
            type Value = LayerName;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a draw layer name")
            }
            fn visit_str<E: de::Error>(self, name: &str) -> Result<LayerName, E> {
                DrawFlags::NAMED
                    .iter()
                    .find(|(known, _)| *known == name)
                    .map(|(_, flag)| LayerName(*flag))
                    .ok_or_else(|| {
                        let names: Vec<&str> = DrawFlags::NAMED.iter().map(|(n, _)| *n).collect();
                        E::custom(format!(
                            "unknown draw layer `{name}`, expected one of {names:?}"
                        ))
                    })
            }
        }
        deserializer.deserialize_identifier(Name)
    }
}

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

/// A hash map written as a list of `(key, value)` pairs sorted by key: the same map always
/// gives the same text, and formats whose map keys must be strings can hold it.
pub(crate) mod sorted_map {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};
    use std::collections::HashMap;
    use std::hash::{BuildHasher, Hash};

    pub fn serialize<K, V, H, S>(map: &HashMap<K, V, H>, serializer: S) -> Result<S::Ok, S::Error>
    where
        K: Serialize + Ord,
        V: Serialize,
        S: Serializer,
    {
        let mut pairs: Vec<(&K, &V)> = map.iter().collect();
        pairs.sort_by(|a, b| a.0.cmp(b.0));
        pairs.serialize(serializer)
    }

    pub fn deserialize<'de, K, V, H, D>(deserializer: D) -> Result<HashMap<K, V, H>, D::Error>
    where
        K: Deserialize<'de> + Eq + Hash,
        V: Deserialize<'de>,
        H: BuildHasher + Default,
        D: Deserializer<'de>,
    {
        let pairs = Vec::<(K, V)>::deserialize(deserializer)?;
        let count = pairs.len();
        let map: HashMap<K, V, H> = pairs.into_iter().collect();
        if map.len() != count {
            return Err(serde::de::Error::custom("a key appears twice"));
        }
        Ok(map)
    }
}

/// A collider's shape in a saved world, bit for bit: a polygon is written as its vertices
/// around its centroid with where that centroid was, where the outline of [`Shape`]'s own form
/// would be centred again and could round differently. Read back, the vertices are checked as
/// any polygon's are.
pub(crate) mod exact_shape {
    use super::ShapeData;
    use crate::geometry::shape::Shape;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(shape: &Shape, serializer: S) -> Result<S::Ok, S::Error> {
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

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Shape, D::Error> {
        Shape::deserialize(deserializer)
    }
}

impl<const CUTS: usize> Serialize for Partition<CUTS> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.ends().serialize(serializer)
    }
}

impl<'de, const CUTS: usize> Deserialize<'de> for Partition<CUTS> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let ends = Vec::<usize>::deserialize(deserializer)?;
        Partition::from_ends(&ends).ok_or_else(|| {
            de::Error::custom(format!(
                "a partition needs {CUTS} ends in increasing order, got {ends:?}"
            ))
        })
    }
}
