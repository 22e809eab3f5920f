//! The scene format: what a RON file in `demos/` holds. Every field but `name` has a default.

use carom::{BodyKind, DrawFlags, Effects, SolverKind};
use serde::{Deserialize, Serialize};

/// A 2D vector written `(x, y)`.
pub type Pair = (f32, f32);

/// One scene: a world to build, how to look at it, and what happens over time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name, shown in menus.
    pub name: String,
    /// What the scene shows and what to try.
    #[serde(default)]
    pub description: String,
    /// Where the camera starts.
    #[serde(default)]
    pub camera: Camera,
    /// World settings.
    #[serde(default)]
    pub world: WorldSpec,
    /// The effects simulated; anything not named is not computed. Default: all.
    #[serde(default = "all_effects")]
    pub effects: Effects,
    /// Bodies listed one by one.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// Bodies made in bulk.
    #[serde(default)]
    pub generators: Vec<Generator>,
    /// Things that happen at given times.
    #[serde(default)]
    pub events: Vec<EventSpec>,
    /// What the demo and snapshots draw at first. Default: shapes, sleeping bodies dimmed.
    #[serde(default = "default_draw")]
    pub draw: DrawFlags,
    /// How `carom bench` measures this scene's error against the exact answer. Default: no
    /// exact answer; the bench reports the deepest overlap.
    #[serde(default)]
    pub accuracy: Option<Accuracy>,
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
        seconds: f32,
    },
    /// No gravity, no friction, restitution 1: momentum and kinetic energy must stay what they
    /// were once the scene's events at time 0 have fired. The error is the larger relative
    /// change of the two after `seconds`.
    Conservation {
        /// How long to run, s.
        seconds: f32,
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
        friction: f32,
        /// How long each trial runs, s.
        seconds: f32,
    },
}

/// Bodies are dynamic unless a scene says otherwise.
fn dynamic() -> BodyKind {
    BodyKind::Dynamic
}

fn default_draw() -> DrawFlags {
    DrawFlags::SHAPES | DrawFlags::SLEEPING
}

fn all_effects() -> Effects {
    Effects::ALL
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

impl Default for Camera {
    fn default() -> Self {
        Camera {
            center: (0.0, 5.0),
            zoom: 30.0,
        }
    }
}

/// World settings; unset solver fields take the solver's defaults.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldSpec {
    /// Gravity, m/s².
    pub gravity: Pair,
    /// Seconds per step.
    pub time_step: f32,
    /// The contact solver.
    pub solver: SolverKind,
    /// Velocity iterations.
    pub iterations: Option<u32>,
    /// Substeps (soft step).
    pub substeps: Option<u32>,
    /// Warm starting.
    pub warm_starting: Option<bool>,
    /// Contact stiffness, Hz (soft step).
    pub contact_hertz: Option<f32>,
    /// Contact damping ratio (soft step).
    pub damping_ratio: Option<f32>,
    /// Fastest push-out, m/s (soft step).
    pub max_push_speed: Option<f32>,
}

impl Default for WorldSpec {
    fn default() -> Self {
        WorldSpec {
            gravity: (0.0, -10.0),
            time_step: 1.0 / 60.0,
            solver: SolverKind::default(),
            iterations: None,
            substeps: None,
            warm_starting: None,
            contact_hertz: None,
            damping_ratio: None,
            max_push_speed: None,
        }
    }
}

/// A shape, in the body's frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ShapeSpec {
    /// A circle.
    Circle {
        /// Radius, m.
        radius: f32,
    },
    /// An axis-aligned box (before the body's angle).
    Box {
        /// Full width, m.
        width: f32,
        /// Full height, m.
        height: f32,
    },
    /// A regular polygon with a flat bottom.
    Regular {
        /// Number of sides.
        sides: u32,
        /// Distance from centre to corners, m.
        radius: f32,
    },
    /// A convex polygon, its points in order (either winding); it is recentred on its centroid.
    Polygon {
        /// The corners.
        points: Vec<Pair>,
    },
    /// The convex hull of any points.
    Hull {
        /// The points.
        points: Vec<Pair>,
    },
}

/// Material and look shared by generated bodies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    /// kg/m².
    pub density: f32,
    /// Coulomb coefficient.
    pub friction: f32,
    /// Bounciness.
    pub restitution: f32,
    /// Linear and angular drag coefficients.
    pub damping: Pair,
    /// RGB in 0..1, for drawing.
    pub color: Option<(f32, f32, f32)>,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            density: 1.0,
            friction: 0.6,
            restitution: 0.0,
            damping: (0.0, 0.0),
            color: None,
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
    pub angle: f32,
    /// Starting velocity, m/s.
    #[serde(default)]
    pub linear_velocity: Pair,
    /// Starting spin, rad/s.
    #[serde(default)]
    pub angular_velocity: f32,
    /// Density, friction, restitution, drag, colour.
    #[serde(default)]
    pub material: Material,
    /// Swept against moving bodies too.
    #[serde(default)]
    pub bullet: bool,
    /// Starts awake; a dynamic body that starts asleep waits, unsolved, until something
    /// touches it.
    #[serde(default = "yes")]
    pub awake: bool,
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
    pub angle: f32,
    /// kg/m²; the body's if not given.
    #[serde(default)]
    pub density: Option<f32>,
    /// Coulomb coefficient; the body's if not given.
    #[serde(default)]
    pub friction: Option<f32>,
    /// Bounciness; the body's if not given.
    #[serde(default)]
    pub restitution: Option<f32>,
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
        size: f32,
        /// Horizontal shift of every other box, m (Box2D offsets rows by ±0.01).
        #[serde(default)]
        offset: f32,
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
        size: f32,
        /// Only this many rows from the bottom (the rest left to other bodies). Default all.
        #[serde(default)]
        rows: Option<u32>,
        /// Fraction of a box by which neighbours start overlapping (Box2D's overlap recovery
        /// uses 0.25). Default 0: touching.
        #[serde(default)]
        overlap: f32,
        /// Their material.
        #[serde(default)]
        material: Material,
    },
    /// `columns × rows` copies of a shape, the first centred on `origin`.
    Grid {
        /// Centre of the first (bottom-left) body.
        origin: Pair,
        /// Bodies per row.
        columns: u32,
        /// Rows.
        rows: u32,
        /// Distance between neighbours' centres, m.
        spacing: Pair,
        /// The shape of each.
        shape: ShapeSpec,
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
    /// Four static walls of a box-shaped room centred on `center`.
    Room {
        /// Centre of the room.
        center: Pair,
        /// Inside width, m.
        width: f32,
        /// Inside height, m.
        height: f32,
        /// Wall thickness, m.
        #[serde(default = "one")]
        thickness: f32,
        /// The walls' material.
        #[serde(default)]
        material: Material,
    },
}

fn one() -> f32 {
    1.0
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
        at: f32,
        /// Which body (its `name`).
        body: String,
        /// Its new velocity, m/s.
        velocity: Pair,
        /// Its new spin, rad/s.
        #[serde(default)]
        angular_velocity: f32,
    },
    /// Every `every` seconds, the named body goes back to where and how it started.
    Respawn {
        /// Period, s.
        every: f32,
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
        angular_velocity: f32,
    },
}
