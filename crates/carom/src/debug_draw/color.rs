//! Colours, and the palette the world is drawn in.

/// A colour with straight (not premultiplied) alpha, components in `0..=1`, sRGB-encoded as
/// colours are usually written down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Color {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
    /// Opacity.
    pub a: f32,
}

impl Color {
    /// An opaque colour.
    pub const fn rgb(r: f32, g: f32, b: f32) -> Self {
        Color { r, g, b, a: 1.0 }
    }

    /// The same colour with opacity `a`.
    pub const fn with_alpha(self, a: f32) -> Self {
        Color { a, ..self }
    }

    /// Blended toward `other` by `t` (0 keeps this colour, 1 gives `other`).
    pub fn mix(self, other: Color, t: f32) -> Self {
        let lerp = |x: f32, y: f32| x + (y - x) * t;
        Color {
            r: lerp(self.r, other.r),
            g: lerp(self.g, other.g),
            b: lerp(self.b, other.b),
            a: lerp(self.a, other.a),
        }
    }

    /// The components as an array, red first.
    pub const fn to_array(self) -> [f32; 4] {
        [self.r, self.g, self.b, self.a]
    }

    /// The background the demo and the snapshots clear to.
    pub const BACKGROUND: Color = Color::rgb(0.09, 0.10, 0.12);
}

/// The house colours: kinds, contacts and overlays.
pub(crate) mod palette {
    use super::Color;

    /// Static bodies.
    pub(crate) const STATIC: Color = Color::rgb(0.42, 0.52, 0.45);
    /// Kinematic bodies.
    pub(crate) const KINEMATIC: Color = Color::rgb(0.45, 0.55, 0.85);
    /// Dynamic bodies take one of these, by handle, so neighbours differ.
    pub(crate) const DYNAMIC: [Color; 6] = [
        Color::rgb(0.90, 0.62, 0.35),
        Color::rgb(0.55, 0.78, 0.45),
        Color::rgb(0.40, 0.70, 0.85),
        Color::rgb(0.85, 0.50, 0.55),
        Color::rgb(0.80, 0.75, 0.40),
        Color::rgb(0.65, 0.55, 0.85),
    ];
    /// What sleeping bodies fade toward.
    pub(crate) const ASLEEP: Color = Color::rgb(0.35, 0.35, 0.38);
    /// Contact points.
    pub(crate) const CONTACT_POINT: Color = Color::rgb(1.0, 0.85, 0.2);
    /// Contact normals.
    pub(crate) const CONTACT_NORMAL: Color = Color::rgb(0.95, 0.95, 0.95);
    /// Reference edges.
    pub(crate) const REFERENCE_EDGE: Color = Color::rgb(0.95, 0.25, 0.2);
    /// Incident edges.
    pub(crate) const INCIDENT_EDGE: Color = Color::rgb(0.25, 0.55, 1.0);
    /// Edge normals.
    pub(crate) const EDGE_NORMAL: Color = Color::rgb(0.3, 0.9, 0.9);
    /// Bounding boxes.
    pub(crate) const AABB: Color = Color::rgb(0.85, 0.4, 0.85);
    /// Velocities.
    pub(crate) const VELOCITY: Color = Color::rgb(0.4, 1.0, 0.4);
    /// Centres of mass.
    pub(crate) const CENTER_OF_MASS: Color = Color::rgb(0.95, 0.95, 0.95);
    /// Joints' links: from each body's centre of mass to its anchor, and between anchors.
    pub(crate) const JOINT: Color = Color::rgb(0.55, 0.85, 0.80);
    /// Joints' anchors.
    pub(crate) const JOINT_ANCHOR: Color = Color::rgb(1.0, 1.0, 1.0);
    /// Prismatic and wheel joints' axes.
    pub(crate) const JOINT_AXIS: Color = Color::rgb(0.6, 0.6, 0.65);
    /// Lower limits: a revolute joint's least angle, the least length or translation.
    pub(crate) const JOINT_LOWER_LIMIT: Color = Color::rgb(0.45, 0.9, 0.45);
    /// Upper limits: a revolute joint's greatest angle, the greatest length or translation.
    pub(crate) const JOINT_UPPER_LIMIT: Color = Color::rgb(0.95, 0.35, 0.3);
    /// Joints' reaction forces.
    pub(crate) const JOINT_FORCE: Color = Color::rgb(1.0, 0.55, 0.15);
}
