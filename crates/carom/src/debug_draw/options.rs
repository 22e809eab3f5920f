//! What to draw: [`DrawFlags`] and [`DrawOptions`].

use crate::math::Real;

/// Which parts of the world [`crate::World::debug_draw`] describes. Combine with `|`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DrawFlags(u32);

impl DrawFlags {
    /// Nothing.
    pub const NONE: DrawFlags = DrawFlags(0);
    /// Bodies' shapes, filled and outlined; circles with a radius line to show their turn.
    pub const SHAPES: DrawFlags = DrawFlags(1);
    /// Each polygon edge's outward normal, from the edge's middle.
    pub const EDGE_NORMALS: DrawFlags = DrawFlags(1 << 1);
    /// Bodies' bounding boxes.
    pub const AABBS: DrawFlags = DrawFlags(1 << 2);
    /// Contact points of touching pairs.
    pub const CONTACT_POINTS: DrawFlags = DrawFlags(1 << 3);
    /// Contact normals, from each contact point.
    pub const CONTACT_NORMALS: DrawFlags = DrawFlags(1 << 4);
    /// The reference (red) and incident (blue) edges of polygon contacts.
    pub const CONTACT_EDGES: DrawFlags = DrawFlags(1 << 5);
    /// Centres of mass.
    pub const CENTERS_OF_MASS: DrawFlags = DrawFlags(1 << 6);
    /// Linear velocities, as arrows from the centre of mass.
    pub const VELOCITIES: DrawFlags = DrawFlags(1 << 7);
    /// Sleeping bodies dimmed.
    pub const SLEEPING: DrawFlags = DrawFlags(1 << 8);
    /// Joints: anchors, the lines joining them to their bodies' centres, axes and limits.
    /// Mouse joints are left to whoever drives them (the demo draws its grab); filter joints
    /// have nothing to show.
    pub const JOINTS: DrawFlags = DrawFlags(1 << 9);
    /// Each joint's reaction force on body B in the last step, as an arrow from B's anchor.
    pub const JOINT_FORCES: DrawFlags = DrawFlags(1 << 10);

    /// Every flag, each with its name as scenes and the command line spell it. New flags go
    /// at the end: serde writes a flag as its index here.
    pub const NAMED: [(&'static str, DrawFlags); 11] = [
        ("shapes", DrawFlags::SHAPES),
        ("edge_normals", DrawFlags::EDGE_NORMALS),
        ("aabbs", DrawFlags::AABBS),
        ("contact_points", DrawFlags::CONTACT_POINTS),
        ("contact_normals", DrawFlags::CONTACT_NORMALS),
        ("contact_edges", DrawFlags::CONTACT_EDGES),
        ("centers_of_mass", DrawFlags::CENTERS_OF_MASS),
        ("velocities", DrawFlags::VELOCITIES),
        ("sleeping", DrawFlags::SLEEPING),
        ("joints", DrawFlags::JOINTS),
        ("joint_forces", DrawFlags::JOINT_FORCES),
    ];

    /// Everything.
    pub const ALL: DrawFlags = DrawFlags((1 << 11) - 1);

    /// The flag called `name` (see [`DrawFlags::NAMED`]).
    pub fn from_name(name: &str) -> Option<DrawFlags> {
        DrawFlags::NAMED
            .iter()
            .find(|(known, _)| *known == name)
            .map(|(_, flag)| *flag)
    }

    /// True if every flag of `other` is set here.
    pub const fn contains(self, other: DrawFlags) -> bool {
        self.0 & other.0 == other.0
    }

    /// True if any flag of `other` is set.
    pub(super) const fn intersects(self, other: DrawFlags) -> bool {
        self.0 & other.0 != 0
    }

    /// Sets or clears the flags of `other`.
    pub fn set(&mut self, other: DrawFlags, on: bool) {
        if on {
            self.0 |= other.0;
        } else {
            self.0 &= !other.0;
        }
    }
}

impl Default for DrawFlags {
    /// Shapes, with sleeping bodies dimmed, and joints (which Box2D also draws by default:
    /// without them a jointed body looks like it floats).
    fn default() -> Self {
        DrawFlags::SHAPES | DrawFlags::SLEEPING | DrawFlags::JOINTS
    }
}

impl std::ops::BitOr for DrawFlags {
    type Output = DrawFlags;
    fn bitor(self, other: DrawFlags) -> DrawFlags {
        DrawFlags(self.0 | other.0)
    }
}

/// What to draw and at what scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawOptions {
    /// Which parts to describe.
    pub flags: DrawFlags,
    /// Length of contact and edge normal arrows, m.
    pub normal_length: Real,
    /// Velocity arrows are the distance covered in this many seconds.
    pub velocity_scale: Real,
    /// Size of joint markings, m: a revolute joint's limit lines are this long, an axis
    /// without limits reaches this far either side of its anchor, and a limit's tick is 0.4
    /// of it across.
    pub joint_size: Real,
    /// Reaction force arrows are this many metres per newton, capped at 2 m so a joint under
    /// a heavy load still fits the view. At 0.01 m/N a 1 kg body hanging under 10 m/s²
    /// gravity shows a 0.1 m arrow.
    pub force_scale: Real,
}

impl Default for DrawOptions {
    fn default() -> Self {
        DrawOptions {
            flags: DrawFlags::default(),
            normal_length: 0.5,
            velocity_scale: 0.1,
            joint_size: 0.5,
            force_scale: 0.01,
        }
    }
}

/// Draw flags are written as the list of layers on, each a bare name.
#[cfg(feature = "serde")]
mod written {
    use super::DrawFlags;
    use serde::de::{self, Deserializer, SeqAccess, Visitor};
    use serde::ser::{SerializeSeq, Serializer};
    use serde::{Deserialize, Serialize};
    use std::fmt;

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
                            let names: Vec<&str> =
                                DrawFlags::NAMED.iter().map(|(n, _)| *n).collect();
                            E::custom(format!(
                                "unknown draw layer `{name}`, expected one of {names:?}"
                            ))
                        })
                }
            }
            deserializer.deserialize_identifier(Name)
        }
    }
}
