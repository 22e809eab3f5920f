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
