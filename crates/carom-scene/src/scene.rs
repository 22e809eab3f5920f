//! The scene format: what a RON file in `demos/` holds. Every field but `name` has a default.

use carom::{BodyKind, CollisionFilter, Motor, Real, Spring, World, WorldSettings};

use carom::draw::DrawFlags;
use serde::{Deserialize, Serialize};

/// The version of the scene format this crate reads and writes. It changes when a file
/// written for one version would read differently, or not at all, in another; a saved state
/// in a scene has its own version as well (carom's save format).
pub const SCENE_FORMAT: u32 = 2;

fn this_format() -> u32 {
    SCENE_FORMAT
}

/// Reads a scene's format, refusing any but [`SCENE_FORMAT`].
fn read_format<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    let format = u32::deserialize(deserializer)?;
    if format == SCENE_FORMAT {
        Ok(format)
    } else {
        Err(serde::de::Error::custom(format!(
            "the scene is in scene format {format}, and this carom-scene ({}) reads scene \
             format {SCENE_FORMAT} only",
            env!("CARGO_PKG_VERSION")
        )))
    }
}

/// A 2D vector written `(x, y)`.
pub type Pair = (Real, Real);

/// One scene: a world to build, how to look at it, and what happens over time.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The version of the scene format the file is written in ([`SCENE_FORMAT`] if it does
    /// not say). A file in another version is refused with both versions named, as soon as
    /// this field is read: write it first. Every file this crate writes does.
    #[serde(default = "this_format", deserialize_with = "read_format")]
    pub format: u32,
    /// Short name, shown in menus.
    pub name: String,
    /// What the scene shows and what to try.
    #[serde(default)]
    pub description: String,
    /// Where the camera starts. Without one, the view frames the scene's bodies
    /// ([`Camera::framing`]).
    #[serde(default, with = "present", skip_serializing_if = "Option::is_none")]
    pub camera: Option<Camera>,
    /// The world's settings, every field of [`carom::WorldSettings`] and each optional: gravity,
    /// the solver and its tuning (`solver: (kind: sequential_impulse, substeps: 8, ..)`), the
    /// effects simulated (anything not named is not computed; default all), margins, contact
    /// recycling and the hit-event threshold.
    #[serde(default)]
    pub world: WorldSettings,
    /// Seconds per step. Default 1/60.
    #[serde(default = "default_time_step")]
    pub time_step: Real,
    /// Bodies listed one by one.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// Bodies made in bulk.
    #[serde(default)]
    pub generators: Vec<Generator>,
    /// Joints between named bodies.
    #[serde(default)]
    pub joints: Vec<JointSpec>,
    /// Things that happen at given times.
    #[serde(default)]
    pub events: Vec<EventSpec>,
    /// A character the keyboard walks and jumps.
    #[serde(default)]
    pub player: Option<PlayerSpec>,
    /// What the demo and snapshots draw at first. Default: shapes, sleeping bodies dimmed.
    #[serde(default = "default_draw")]
    pub draw: DrawFlags,
    /// How `carom bench` measures this scene's error against the exact answer. Default: no
    /// exact answer; the bench reports the deepest overlap.
    #[serde(default)]
    pub accuracy: Option<Accuracy>,
    /// A running scene saved whole (see [`crate::SavedState`]): the scene opens on it as it
    /// was, and its `world`, `effects`, `bodies`, `generators`, `joints` and `events` are not
    /// built again. Written by [`crate::SceneWorld::save`]; not meant to be written by hand.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state: Option<crate::SavedState>,
}

/// An error a scene can be measured by, each against an exact or ideal answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Accuracy {
    /// The bodies start exactly at rest (touching, no overlap), so the exact answer is that
    /// nothing moves: the error is how far the named bodies (default: the highest dynamic body)
    /// are from where they started after `seconds`, sinking and drifting together.
    Rest {
        /// Bodies measured (their `name`s); empty means the highest dynamic body.
        #[serde(default)]
        bodies: Vec<String>,
        /// How long to run, s.
        seconds: Real,
    },
    /// No gravity, no friction, restitution 1: momentum and kinetic energy must stay what they
    /// were once the scene's events at time 0 have fired. The error is the larger relative
    /// change of the two after `seconds`.
    Conservation {
        /// How long to run, s.
        seconds: Real,
    },
    /// A box on a slope with friction coefficient `friction` (the mixed one) starts to slide
    /// when the slope is steeper than atan(μ). The bench tilts gravity instead of the slope,
    /// finds the tilt at which the named body starts to slide (it moves more than 5 mm in
    /// `seconds`) by bisection, and adds the body's own starting angle (it sits square on its
    /// slope). The error is that angle less atan(μ), in degrees.
    SlideAngle {
        /// The body on the slope (its `name`).
        body: String,
        /// The friction coefficient between it and the slope.
        friction: Real,
        /// How long each trial runs, s.
        seconds: Real,
    },
    /// A body swinging on a joint (a pendulum) should swing with the period `expected`. The
    /// bench records the body's x less its pivot's (its first joint's anchor on the other
    /// body) every step for `seconds`, and takes the mean time between upward zero crossings.
    /// The error is |measured − expected| / expected, in %.
    Period {
        /// The swinging body (its `name`); it must have a joint.
        body: String,
        /// The exact period, s.
        expected: Real,
        /// How long to run, s (a few periods at least: fewer than three crossings is an
        /// infinite error).
        seconds: Real,
    },
    /// A body hanging from `anchor` by a chain of joints should stay `length` from it: the
    /// error is the worst, over `seconds`, of |distance − length| / length, in %, where the
    /// distance is from `anchor` to the body's first joint's anchor on the body.
    Stretch {
        /// The hanging body (its `name`); it must have a joint.
        body: String,
        /// The fixed point it hangs from, m.
        anchor: Pair,
        /// Its joint anchor's exact distance from `anchor`, m.
        length: Real,
        /// How long to run, s.
        seconds: Real,
    },
    /// A structure of joints spanning a fixed length (a bridge between two posts) can only
    /// sag by stretching its joints: the error is the worst, over `seconds`, of the sum of
    /// every joint's anchor separation, in % of `length`.
    Gaps {
        /// The length the joints span, m.
        length: Real,
        /// How long to run, s.
        seconds: Real,
    },
    /// Hinges should hold together and turn no further than their limits (a pile of
    /// ragdolls). Two errors: the worst, over `seconds`, of any hinge's anchor separation (m)
    /// and of how far any hinge has turned past its limits (degrees).
    Hinges {
        /// How long to run, s.
        seconds: Real,
    },
    /// Light bodies under heavy ones should not be pushed into the ground: the error is how
    /// far, at worst over `seconds`, any dynamic body's lowest point gets below `ground`.
    Sink {
        /// The height of the ground's top, m.
        ground: Real,
        /// How long to run, s.
        seconds: Real,
    },
}

/// Bodies are dynamic unless a scene says otherwise.
fn dynamic() -> BodyKind {
    BodyKind::Dynamic
}

fn default_draw() -> DrawFlags {
    DrawFlags::SHAPES | DrawFlags::SLEEPING
}

fn default_time_step() -> Real {
    1.0 / 60.0
}

/// Where the camera looks and how close.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    /// The world point at the centre of the view, m.
    pub center: Pair,
    /// Pixels per metre in a 1280 x 720 view. Other views scale it so that they show at least
    /// what that view shows: by their height, or by their width when they are narrower.
    pub zoom: f32,
}

impl Camera {
    /// The view size, in pixels, at which `zoom` is exact.
    pub const REFERENCE_VIEW: (f32, f32) = (1280.0, 720.0);

    /// Pixels per metre in a `width` x `height` pixel view.
    pub fn zoom_for_view(&self, width: u32, height: u32) -> f32 {
        self.zoom * Camera::view_scale(width, height)
    }

    /// How much larger than the reference view a `width` x `height` view is, as far as
    /// fitting the reference view's contents goes.
    pub fn view_scale(width: u32, height: u32) -> f32 {
        let (reference_width, reference_height) = Camera::REFERENCE_VIEW;
        (height.max(1) as f32 / reference_height).min(width.max(1) as f32 / reference_width)
    }
}

impl Camera {
    /// A camera that frames `world`'s moving bodies as they are (all its bodies if none
    /// moves), with the ground under them near the bottom of the view: the top of the highest
    /// static body below them, wherever they overlap it across.
    // Lengths are `Real`, f32 or f64 by the core's feature; the zoom is f32 either way.
    #[allow(clippy::unnecessary_cast)]
    pub fn framing(world: &World) -> Camera {
        let moving = |b: &&carom::Body| b.kind() != BodyKind::Static;
        let any_moving = world.bodies().any(|b| moving(&b));
        let Some(bodies) = world
            .bodies()
            .filter(|b| !any_moving || moving(b))
            .map(|b| b.aabb())
            .reduce(|a, b| a.union(&b))
        else {
            return Camera::default();
        };
        let ground = world
            .bodies()
            .filter(|b| b.kind() == BodyKind::Static)
            .map(|b| b.aabb())
            .filter(|s| s.min.x < bodies.max.x && s.max.x > bodies.min.x)
            .filter(|s| s.max.y <= bodies.min.y + 0.25 * (bodies.max.y - bodies.min.y))
            .map(|s| s.max.y)
            .reduce(Real::max)
            .filter(|_| any_moving)
            .map_or(bodies.min.y, |top| top.min(bodies.min.y));
        let (view_width, view_height) = Camera::REFERENCE_VIEW;
        // The ground a tenth up the view, the top a tenth down, the sides a tenth in.
        let height = ((bodies.max.y - ground) as f32 / 0.8)
            .max((bodies.max.x - bodies.min.x) as f32 / 0.8 * view_height / view_width)
            .max(FRAMING_LEAST);
        let center_x = 0.5 * (bodies.min.x + bodies.max.x);
        let center_y = ground + (0.4 * height) as Real;
        Camera {
            center: (center_x, center_y),
            zoom: view_height / height,
        }
    }
}

/// The least height, m, a framing camera shows: a lone small body is not blown up to fill
/// the view.
const FRAMING_LEAST: f32 = 4.0;

/// An `Option` written as its value when it has one and left out when not, so a file
/// writes `camera: (center: ..)`, not `camera: Some((center: ..))`.
mod present {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<T: Serialize, S: Serializer>(
        value: &Option<T>,
        serializer: S,
    ) -> Result<S::Ok, S::Error> {
        match value {
            Some(value) => value.serialize(serializer),
            None => serializer.serialize_none(),
        }
    }

    pub fn deserialize<'de, T: Deserialize<'de>, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Option<T>, D::Error> {
        T::deserialize(deserializer).map(Some)
    }
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            center: (0.0, 5.0),
            zoom: 30.0,
        }
    }
}

/// A shape, in the body's frame. Polygons may be rounded by a `radius` (default 0): grown by
/// it all round, corners becoming arcs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ShapeSpec {
    /// A circle.
    Circle {
        /// Radius, m.
        radius: Real,
    },
    /// An axis-aligned box (before the body's angle).
    Box {
        /// Full width, m.
        width: Real,
        /// Full height, m.
        height: Real,
    },
    /// An axis-aligned box with rounded corners, `width` by `height` overall: a box smaller by
    /// `radius` on every side, grown by `radius`.
    RoundedBox {
        /// Full width, m.
        width: Real,
        /// Full height, m.
        height: Real,
        /// Corner radius, m: less than half the width and half the height.
        radius: Real,
    },
    /// A capsule along x, centred: two circles' centres `length` apart, joined.
    Capsule {
        /// Distance between the centres, m.
        length: Real,
        /// Radius, m.
        radius: Real,
    },
    /// A regular polygon with a flat bottom.
    Regular {
        /// Number of sides.
        sides: u32,
        /// Distance from centre to corners, m.
        radius: Real,
        /// Rounding, m.
        #[serde(default)]
        rounding: Real,
    },
    /// A convex polygon, its points in order (either winding); it is recentred on its centroid.
    Polygon {
        /// The corners.
        points: Vec<Pair>,
        /// Rounding, m.
        #[serde(default)]
        radius: Real,
    },
    /// The convex hull of any points.
    Hull {
        /// The points.
        points: Vec<Pair>,
        /// Rounding, m.
        #[serde(default)]
        radius: Real,
    },
    /// A two-sided segment for static geometry, its ends where they are given (not
    /// recentred); it has no mass. Rounded by a `radius`, it is a capsule between those ends
    /// (Box2D's `b2Capsule`: two centres and a radius), which has mass.
    Segment {
        /// One end, m.
        from: Pair,
        /// The other end, m.
        to: Pair,
        /// Rounding, m: 0 for a bare segment.
        #[serde(default)]
        radius: Real,
    },
    /// A chain of one-sided segments for terrain, its points where they are given; it collides
    /// on its right, walking along the points (ground whose solid side is below runs right to
    /// left; a counter-clockwise loop is solid outside). One collider per link; no mass.
    Chain {
        /// The points, in order.
        points: Vec<Pair>,
        /// Whether the last point joins back to the first.
        #[serde(default)]
        closed: bool,
    },
}

/// Material and look shared by generated bodies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    /// kg/m².
    pub density: Real,
    /// Coulomb coefficient.
    pub friction: Real,
    /// Bounciness.
    pub restitution: Real,
    /// Resistance to rolling (carom's `Surface::rolling_resistance`).
    pub rolling_resistance: Real,
    /// How fast the surface moves along itself, m/s, clockwise around the shape: a conveyor
    /// belt (carom's `Surface::tangent_speed`).
    pub tangent_speed: Real,
    /// Linear and angular drag coefficients.
    pub damping: Pair,
    /// RGB in 0..1, for drawing.
    pub color: Option<(f32, f32, f32)>,
    /// What it collides with: `(category, mask, group)` as in carom's `CollisionFilter`.
    pub filter: CollisionFilter,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            density: 1.0,
            friction: 0.6,
            restitution: 0.0,
            rolling_resistance: 0.0,
            tangent_speed: 0.0,
            damping: (0.0, 0.0),
            color: None,
            filter: CollisionFilter::DEFAULT,
        }
    }
}

/// One body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// A name events can refer to.
    #[serde(default)]
    pub name: Option<String>,
    /// How it moves.
    #[serde(default = "dynamic")]
    pub kind: BodyKind,
    /// Its shape, at its origin. A body needs a `shape`, `colliders`, or both.
    #[serde(default)]
    pub shape: Option<ShapeSpec>,
    /// More shapes, each placed in the body's frame.
    #[serde(default)]
    pub colliders: Vec<ColliderSpec>,
    /// Where its centroid starts, m.
    #[serde(default)]
    pub position: Pair,
    /// Starting angle, rad.
    #[serde(default)]
    pub angle: Real,
    /// Starting velocity, m/s.
    #[serde(default)]
    pub linear_velocity: Pair,
    /// Starting spin, rad/s.
    #[serde(default)]
    pub angular_velocity: Real,
    /// Density, friction, restitution, drag, colour.
    #[serde(default)]
    pub material: Material,
    /// Swept against moving bodies too.
    #[serde(default)]
    pub bullet: bool,
    /// Its contacts look a step ahead even in a world that does not (`BodyDef::look_ahead`).
    #[serde(default)]
    pub look_ahead: bool,
    /// A dynamic body that never turns (a character standing upright).
    #[serde(default)]
    pub fixed_rotation: bool,
    /// Starts awake; a dynamic body that starts asleep waits, unsolved, until something
    /// touches it.
    #[serde(default = "yes")]
    pub awake: bool,
    /// Its colliders are sensors: they report what overlaps them and never collide (carom's
    /// `ColliderDef::sensor`). A collider may say otherwise.
    #[serde(default)]
    pub sensor: bool,
    /// Its colliders are one-way platforms: solid to what comes down onto their top (their
    /// up is the collider's +y, turned with it and its body), passable from below and the
    /// sides. A collider may say otherwise.
    #[serde(default)]
    pub one_way: bool,
    /// The speed of its fastest point below which it counts as resting, m/s (carom's
    /// `BodyDef::sleep_threshold`; Box2D's ragdolls use 0.1). Default 0.05.
    #[serde(default = "sleep_threshold")]
    pub sleep_threshold: Real,
}

fn sleep_threshold() -> Real {
    carom::SLEEP_THRESHOLD
}

/// One more shape of a body, placed in its frame; its material is the body's unless given.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColliderSpec {
    /// The shape.
    pub shape: ShapeSpec,
    /// Where its centroid sits in the body's frame, m.
    #[serde(default)]
    pub offset: Pair,
    /// How it is turned in the body's frame, rad.
    #[serde(default)]
    pub angle: Real,
    /// kg/m²; the body's if not given.
    #[serde(default)]
    pub density: Option<Real>,
    /// Coulomb coefficient; the body's if not given.
    #[serde(default)]
    pub friction: Option<Real>,
    /// Bounciness; the body's if not given.
    #[serde(default)]
    pub restitution: Option<Real>,
    /// What it collides with; the body's if not given.
    #[serde(default)]
    pub filter: Option<CollisionFilter>,
    /// A sensor; the body's `sensor` if not given.
    #[serde(default)]
    pub sensor: Option<bool>,
    /// A one-way platform; the body's `one_way` if not given.
    #[serde(default)]
    pub one_way: Option<bool>,
}

/// Bodies made in bulk.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Generator {
    /// A column of square boxes standing on `base` (the middle of the bottom box's bottom).
    Stack {
        /// Where the column stands.
        base: Pair,
        /// How many boxes.
        count: u32,
        /// Box side, m.
        #[serde(default = "one")]
        size: Real,
        /// Horizontal shift of every other box, m (Box2D offsets rows by ±0.01).
        #[serde(default)]
        offset: Real,
        /// Their material.
        #[serde(default)]
        material: Material,
    },
    /// A pyramid of square boxes: `count` in the bottom row, one fewer each row up, standing on
    /// `base` (the middle of the bottom row's bottom), touching exactly (Box2D's recipe).
    Pyramid {
        /// Where it stands.
        base: Pair,
        /// Boxes in the bottom row.
        count: u32,
        /// Box side, m.
        #[serde(default = "one")]
        size: Real,
        /// Only this many rows from the bottom (the rest left to other bodies). Default all.
        #[serde(default)]
        rows: Option<u32>,
        /// Fraction of a box by which neighbours start overlapping (Box2D's overlap recovery
        /// uses 0.25). Default 0: touching.
        #[serde(default)]
        overlap: Real,
        /// Their material.
        #[serde(default)]
        material: Material,
    },
    /// `columns × rows` copies of a shape, the first centred on `origin`, made row by row.
    Grid {
        /// Centre of the first (bottom-left) body.
        origin: Pair,
        /// Bodies per row.
        columns: u32,
        /// Rows.
        rows: u32,
        /// Distance between neighbours' centres, m.
        spacing: Pair,
        /// The shape of each. Give this or `shapes`.
        #[serde(default)]
        shape: Option<ShapeSpec>,
        /// Shapes taken in turn, in the order the bodies are made (Box2D's spinner cycles a
        /// capsule, a circle and a square). Give this or `shape`.
        #[serde(default)]
        shapes: Vec<ShapeSpec>,
        /// Only the first `count` cells, row by row, the last row left part-filled. Default
        /// all.
        #[serde(default)]
        count: Option<u32>,
        /// Their kind.
        #[serde(default = "dynamic")]
        kind: BodyKind,
        /// Their material.
        #[serde(default)]
        material: Material,
        /// Whether they start awake (dynamic ones that do not wait, unsolved, until
        /// something touches them).
        #[serde(default = "yes")]
        awake: bool,
        /// One body at the world origin holding every copy as a collider where the copy
        /// would be, instead of a body each (Box2D's rain ground: one static body of 2505
        /// boxes).
        #[serde(default)]
        compound: bool,
    },
    /// `columns × rows` copies of a shape joined into a net by revolute joints (Box2D's joint
    /// grid): each body is hinged to the one before it in its column and to the one beside it
    /// in the column before, at the midpoint between their centres, the earlier body being
    /// joint body A. Bodies are made column by column, each column from its first row, and
    /// each body's joints right after it (Box2D's order, which sets how both engines store
    /// and colour them).
    JointGrid {
        /// Centre of the first body (column 0, row 0).
        origin: Pair,
        /// Columns (bodies per row).
        columns: u32,
        /// Rows (bodies per column).
        rows: u32,
        /// From one column's centres to the next's (x) and one row's to the next's (y), m;
        /// negative goes left or down.
        spacing: Pair,
        /// The shape of each.
        shape: ShapeSpec,
        /// Their material (its filter decides whether neighbours collide where they are not
        /// joined; joined ones do not).
        #[serde(default)]
        material: Material,
        /// Cells whose bodies are static; the rest are dynamic.
        #[serde(default)]
        fixed: Vec<Cells>,
        /// The joints' settings (limits, motor as joint friction, spring). Default: none.
        #[serde(default)]
        joint: RevoluteSpec,
    },
    /// `count` copies of a shape scattered over the rectangle from `low` to `high` (its
    /// corners), at positions drawn from `seed`: the same seed, the same scatter.
    Rain {
        /// Lower-left corner of the area.
        low: Pair,
        /// Upper-right corner of the area.
        high: Pair,
        /// How many bodies.
        count: u32,
        /// The shape of each.
        shape: ShapeSpec,
        /// Seed of the scatter.
        #[serde(default)]
        seed: u64,
        /// Their material.
        #[serde(default)]
        material: Material,
    },
    /// Another generator repeated `columns × rows` times, each copy shifted by `spacing`.
    Repeat {
        /// Copies per row.
        columns: u32,
        /// Rows of copies.
        rows: u32,
        /// Shift between neighbouring copies, m.
        spacing: Pair,
        /// What is repeated.
        of: Box<Generator>,
    },
    /// A chain of `count` box links from `from` to `to`, each joined to the next by a
    /// revolute joint at their shared end; the first joined to the body named `start` at
    /// `from`, the last to the body named `end` at `to`, if given. A rope, a bridge.
    Chain {
        /// Where the first link starts (its joint with `start`).
        from: Pair,
        /// Where the last link ends (its joint with `end`).
        to: Pair,
        /// How many links.
        count: u32,
        /// Each link's thickness, m (its length is the chain's over `count`).
        #[serde(default = "tenth")]
        thickness: Real,
        /// The body the first link hangs from, by name.
        #[serde(default)]
        start: Option<String>,
        /// The body the last link holds, by name.
        #[serde(default)]
        end: Option<String>,
        /// The joints' settings (limits, motor as joint friction, spring).
        #[serde(default)]
        joint: RevoluteSpec,
        /// The links' material.
        #[serde(default)]
        material: Material,
    },
    /// Bodies and joints made together (a ragdoll, a car), so that [`Generator::Repeat`] can
    /// copy them: names are local to each copy (joints find a name in their own copy first,
    /// then among the scene's bodies).
    Group {
        /// The bodies, as in the scene's list.
        bodies: Vec<BodySpec>,
        /// Joints between them (or to the scene's named bodies).
        #[serde(default)]
        joints: Vec<JointSpec>,
        /// Whether a copy's bodies collide with each other. False gives each copy a collision
        /// group of its own (a ragdoll's limbs pass through each other but hit other
        /// ragdolls). Default true.
        #[serde(default = "yes")]
        self_collide: bool,
    },
    /// Four static walls of a box-shaped room centred on `center`.
    Room {
        /// Centre of the room.
        center: Pair,
        /// Inside width, m.
        width: Real,
        /// Inside height, m.
        height: Real,
        /// Wall thickness, m.
        #[serde(default = "one")]
        thickness: Real,
        /// The walls' material.
        #[serde(default)]
        material: Material,
    },
}

/// A block of a grid's cells: the columns and the rows from the first to the last given, both
/// included, counted from 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cells {
    /// First and last column.
    pub columns: (u32, u32),
    /// First and last row.
    pub rows: (u32, u32),
}

impl Cells {
    /// Whether the cell at `column`, `row` is in the block.
    pub fn contains(&self, column: u32, row: u32) -> bool {
        (self.columns.0..=self.columns.1).contains(&column)
            && (self.rows.0..=self.rows.1).contains(&row)
    }
}

fn one() -> Real {
    1.0
}

fn tenth() -> Real {
    0.1
}

/// A joint between two named bodies, its anchor given where the bodies start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// The two bodies, by name (a mouse joint names its body twice).
    pub bodies: (String, String),
    /// What it does.
    pub kind: JointKindSpec,
    /// Where it joins them, in the world where they start, m: both bodies' anchor, or body
    /// A's if `anchor_b` is given.
    #[serde(default)]
    pub anchor: Pair,
    /// Body B's anchor, if it is not `anchor` (a distance joint's other end).
    #[serde(default)]
    pub anchor_b: Option<Pair>,
    /// Whether the two bodies still collide with each other.
    #[serde(default)]
    pub collide_connected: bool,
    /// It breaks when it applies more force, N.
    #[serde(default)]
    pub break_force: Option<Real>,
    /// It breaks when it applies more torque, N·m.
    #[serde(default)]
    pub break_torque: Option<Real>,
}

/// A revolute joint's settings.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RevoluteSpec {
    /// Lowest and highest angle of B relative to A, rad (0 where they start).
    pub limits: Option<Pair>,
    /// Speed (rad/s) and most torque (N·m); speed 0 is joint friction.
    pub motor: Option<Motor>,
    /// Pulls toward `target_angle`.
    pub spring: Option<Spring>,
    /// The angle the spring pulls to, rad.
    pub target_angle: Real,
}

/// A character the keyboard walks and jumps (carom's kinematic `Character`: it climbs
/// slopes up to 45° and steps up to 0.3 m, and rides what it stands on), falling under the
/// world's gravity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlayerSpec {
    /// Where its capsule's middle starts, m.
    pub position: Pair,
    /// From its middle to its end circles' centres, m. Default 0.5.
    #[serde(default = "player_half_height")]
    pub half_height: Real,
    /// Its capsule's radius, m. Default 0.3.
    #[serde(default = "player_radius")]
    pub radius: Real,
    /// m/s. Default 4.
    #[serde(default = "walk_speed")]
    pub walk_speed: Real,
    /// Its upward speed as it jumps, m/s. Default 7.
    #[serde(default = "jump_speed")]
    pub jump_speed: Real,
    /// The x past which the level is done, m.
    #[serde(default)]
    pub goal: Option<Real>,
    /// A recorded play: the keys' changes, by step, that a host may replay
    /// ([`crate::Player::replay`]).
    #[serde(default)]
    pub replay: Vec<KeyChange>,
}

/// A key of the player's going down or up before a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyChange {
    /// The world's step count when it happens (0: before the first step).
    pub step: u64,
    /// Which.
    pub key: PlayerKey,
    /// Down (held) or up.
    pub down: bool,
}

/// The player's keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlayerKey {
    /// Walk left.
    Left,
    /// Walk right.
    Right,
    /// Jump.
    Jump,
}

fn player_half_height() -> Real {
    0.5
}

fn player_radius() -> Real {
    0.3
}

fn walk_speed() -> Real {
    4.0
}

fn jump_speed() -> Real {
    7.0
}

/// What a joint does, with its settings (as in carom's joint types).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum JointKindSpec {
    /// A rod between `anchor` and `anchor_b`; with a spring, soft, within `limits`.
    Distance {
        /// Rest length, m; default the anchors' distance at the start.
        #[serde(default)]
        length: Option<Real>,
        /// Makes it a spring (0 Hz: no spring force, a rope within `limits`).
        #[serde(default)]
        spring: Option<Spring>,
        /// Shortest and longest, m.
        #[serde(default)]
        limits: Option<Pair>,
    },
    /// A hinge at `anchor`.
    Revolute {
        /// Lowest and highest angle of B relative to A, rad (0 where they start).
        #[serde(default)]
        limits: Option<Pair>,
        /// Speed (rad/s) and most torque (N·m); speed 0 is joint friction.
        #[serde(default)]
        motor: Option<Motor>,
        /// Pulls toward `target_angle`.
        #[serde(default)]
        spring: Option<Spring>,
        /// The angle the spring pulls to, rad.
        #[serde(default)]
        target_angle: Real,
    },
    /// A slider through `anchor` along `axis`.
    Prismatic {
        /// The direction of travel, in the world at the start.
        axis: Pair,
        /// Least and most translation, m.
        #[serde(default)]
        limits: Option<Pair>,
        /// Speed (m/s) and most force (N).
        #[serde(default)]
        motor: Option<Motor>,
        /// Pulls toward `target_translation`.
        #[serde(default)]
        spring: Option<Spring>,
        /// m.
        #[serde(default)]
        target_translation: Real,
    },
    /// Glues the bodies together at `anchor`; springs make it soft.
    Weld {
        /// Soft translation.
        #[serde(default)]
        linear: Option<Spring>,
        /// Soft rotation.
        #[serde(default)]
        angular: Option<Spring>,
    },
    /// Wheel B on chassis A: a suspension along `axis` through `anchor`, a motor on its turn.
    Wheel {
        /// The suspension's direction, in the world at the start. Default up.
        #[serde(default = "up")]
        axis: Pair,
        /// The suspension. Default 4 Hz, damping ratio 0.7.
        #[serde(default = "suspension")]
        spring: Option<Spring>,
        /// Least and most travel along the axis, m.
        #[serde(default)]
        limits: Option<Pair>,
        /// Speed (rad/s) and most torque (N·m).
        #[serde(default)]
        motor: Option<Motor>,
    },
    /// Drives B relative to A (as carom's `MotorJoint`): a velocity part and a spring part
    /// toward offsets from where B starts, each doing nothing while its cap is 0.
    Motor {
        /// B's anchor's velocity relative to A's, in the world, m/s.
        #[serde(default)]
        linear_velocity: Pair,
        /// N (0: no linear velocity part).
        #[serde(default)]
        max_velocity_force: Real,
        /// B's spin relative to A's, rad/s.
        #[serde(default)]
        angular_velocity: Real,
        /// N·m (0: no angular velocity part).
        #[serde(default)]
        max_velocity_torque: Real,
        /// Where the spring pulls B's anchor from A's, in A's frame, m. Default where it starts.
        #[serde(default)]
        linear_offset: Pair,
        /// The angle the spring turns B to from A's, more than at the start, rad.
        #[serde(default)]
        angular_offset: Real,
        /// Default 4 Hz, critically damped.
        #[serde(default = "motor_spring")]
        linear_spring: Spring,
        /// N (0: no linear spring).
        #[serde(default)]
        max_spring_force: Real,
        /// Default 4 Hz, critically damped.
        #[serde(default = "motor_spring")]
        angular_spring: Spring,
        /// N·m (0: no angular spring).
        #[serde(default)]
        max_spring_torque: Real,
    },
    /// Drives B's velocity relative to A's with at most `max_force` on each world axis, not
    /// turning it (a dynamic character's legs; the bodies still collide).
    Mover {
        /// m/s, in the world.
        #[serde(default)]
        velocity: Pair,
        /// N on x and on y (0: that axis is free).
        max_force: Pair,
    },
    /// A leg holding B's `anchor_b` (the foot) `rest_length` above A's `anchor` on the
    /// ground, whose normal there is `normal` (the bodies still collide).
    Pogo {
        /// The ground's normal, in the world. Default up.
        #[serde(default = "up")]
        normal: Pair,
        /// m.
        rest_length: Real,
        /// Default 5 Hz, damping ratio 0.8.
        #[serde(default = "pogo_spring")]
        spring: Spring,
        /// The most push, N.
        max_compression: Real,
        /// The most pull, N.
        #[serde(default)]
        max_tension: Real,
    },
    /// Pulls body B's point at `anchor` toward `target` (both names the same body).
    Mouse {
        /// Where it pulls to, m.
        target: Pair,
        /// Default 5 Hz, damping ratio 0.7.
        #[serde(default = "mouse_spring")]
        spring: Spring,
        /// N.
        max_force: Real,
    },
    /// Only keeps the two bodies from colliding.
    Filter,
}

fn motor_spring() -> Spring {
    Spring::new(4.0, 1.0)
}

fn pogo_spring() -> Spring {
    Spring::new(5.0, 0.8)
}

fn up() -> Pair {
    (0.0, 1.0)
}

fn suspension() -> Option<Spring> {
    Some(Spring::new(4.0, 0.7))
}

fn mouse_spring() -> Spring {
    Spring::new(5.0, 0.7)
}

fn yes() -> bool {
    true
}

/// Something that happens during the run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum EventSpec {
    /// At `at` seconds, the named body gets this velocity.
    Launch {
        /// When, s.
        at: Real,
        /// Which body (its `name`).
        body: String,
        /// Its new velocity, m/s.
        velocity: Pair,
        /// Its new spin, rad/s.
        #[serde(default)]
        angular_velocity: Real,
    },
    /// Every `every` seconds, the named body goes back to where and how it started.
    Respawn {
        /// Period, s.
        every: Real,
        /// Which body (its `name`).
        body: String,
    },
    /// From the start, the named kinematic bodies turn together about `pivot` as one
    /// rigid frame (a drum, a tumbler): each keeps its offset from the pivot.
    Spin {
        /// Which bodies (their `name`s); each must be kinematic.
        bodies: Vec<String>,
        /// The centre of the turn, m.
        pivot: Pair,
        /// Turn rate, rad/s (positive is counter-clockwise).
        angular_velocity: Real,
    },
    /// From the start, the named kinematic bodies go `offset` from where they start and back
    /// every `period` seconds, easing in and out (a lift, a moving platform).
    Shuttle {
        /// Which bodies (their `name`s); each must be kinematic.
        bodies: Vec<String>,
        /// How far they go, m.
        offset: Pair,
        /// Time there and back, s.
        period: Real,
    },
    /// Copies of a generator's bodies and joints made and remade in turn at the places of a
    /// `columns × rows` grid (Box2D's rain of ragdolls). Turn `n` comes at `at + n every`
    /// seconds, before the first step that starts then or later: it takes column `n` mod
    /// `columns` and, row by row from the first, removes the copy made at that place the
    /// last time round (its bodies, with their joints) and makes a new one there. A copy is
    /// what `of` makes, moved by its place: `origin` for the first, `spacing` on from one
    /// column or row to the next. A copy's joints join its own bodies.
    Spawn {
        /// When the first turn comes, s.
        #[serde(default)]
        at: Real,
        /// Time from one turn to the next, s.
        every: Real,
        /// Where the first place is: what `of` makes there is moved by this, m.
        #[serde(default)]
        origin: Pair,
        /// Columns of places, one taken each turn.
        columns: u32,
        /// Places in a column, each filled at its column's turn.
        #[serde(default = "one_place")]
        rows: u32,
        /// From one column's places to the next's (x) and one row's to the next's (y), m.
        #[serde(default)]
        spacing: Pair,
        /// What is made at each place.
        of: Box<Generator>,
    },
}

fn one_place() -> u32 {
    1
}
