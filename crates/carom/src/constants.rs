//! The engine's tuning constants and tolerances, each named once.
//!
//! A leaf: it depends on nothing but the scalar type, so any module may use it. Only values
//! that are part of an algorithm's structure (the SIMD lane count, a tree's null index) live
//! beside their code.

use crate::math::{Real, Vec2};

// Scale of contact.

/// Penetration the solver tolerates, and the scale of "touching", in metres (Box2D's 0.5 cm).
pub const LINEAR_SLOP: Real = 0.005;

/// Shapes closer than this get speculative contact points, in metres (4 × slop, as Box2D).
pub const SPECULATIVE_DISTANCE: Real = 4.0 * LINEAR_SLOP;

/// How much moving bodies' bounding boxes are enlarged in the broadphase, in metres, so a
/// body can move a little without its tree entry changing.
pub(crate) const AABB_MARGIN: Real = 0.05;

// Contact events.

/// A pair begins to touch, for its begin event, once a point's separation is at most this, m
/// (a tenth of the slop). Not zero: a body a speculative point stopped at a surface rests
/// there to within rounding, a few micrometres to either side.
pub(crate) const TOUCH_BEGIN: Real = 0.1 * LINEAR_SLOP;

/// A touching pair stops touching, for its end event, once every point is farther apart than
/// this, m (the slop). A resting body rocks by far less, so its contact does not flicker.
pub(crate) const TOUCH_END: Real = LINEAR_SLOP;

/// The approach speed above which a push is a hit, by default, m/s (Box2D's
/// `hitEventThreshold`).
pub(crate) const HIT_EVENT_THRESHOLD: Real = 1.0;

// Shapes.

/// The largest coordinate or radius a shape may have, m (Box2D's `B2_HUGE`): beyond it an f32
/// keeps too few digits below a millimetre for contacts, and sums of sizes can overflow.
pub const MAX_SHAPE_EXTENT: Real = 1.0e5;

/// The shortest and the longest time step a world takes, s. Outside them the step's
/// reciprocals and products overflow f32 (a step of 1e-38 s, or of 1e38 s), so they are
/// refused; a game's step is thousands of times inside both.
pub const TIME_STEP_RANGE: std::ops::RangeInclusive<Real> = 1.0e-6..=10.0;

/// The farthest from the origin a body may be placed, m, along either axis, and where a force,
/// an impulse or an explosion may act: ten times the largest shape. Beyond it an f32 position resolves to no better than 6 cm, and products of
/// positions with forces and sizes can overflow.
pub const MAX_POSITION: Real = 1.0e6;

/// The fastest a body may be set moving, m/s, along either axis: across all of
/// [`MAX_POSITION`] in a second, a thousand times a rifle bullet. A step's motion, and a
/// velocity times the heaviest mass, stay well inside f32 below it; the solver's speed cap
/// (`max_linear_speed`) is held to it too.
pub const MAX_SPEED: Real = 1.0e6;

/// The fastest a body may be set spinning, rad/s: a hundred thousand turns a second. A
/// spin times the largest lever arm, and a step's turn, stay well inside f32 below it.
pub const MAX_ANGULAR_SPEED: Real = 1.0e6;

/// The strongest gravity a world may have, m/s², along either axis: a hundred thousand times
/// Earth's. A body's gravity scale is held within [`MAX_GRAVITY_SCALE`] either way. Below them a
/// step's change of velocity stays well inside f32 before the speed caps act on it.
pub const MAX_ACCELERATION: Real = 1.0e6;

/// The largest gravity scale a body may have, either way.
pub const MAX_GRAVITY_SCALE: Real = 1.0e3;

/// The least mass a dynamic body may have, kg: a grain of dust a micrometre across weighs
/// about 1e-15. Below it the inverse mass, times the impulses and lever arms the solver
/// multiplies it by, can overflow f32.
pub const MIN_BODY_MASS: Real = 1.0e-20;

/// The least rotational inertia a dynamic body may have, kg·m², if it has any, whether its
/// rotation is fixed or not (so that freeing it cannot fail): the inverse inertia times a
/// lever arm of [`MAX_SHAPE_EXTENT`] squared must stay well inside f32 (1e28 × 1e10 = 1e38).
pub const MIN_BODY_INERTIA: Real = 1.0e-28;

/// The greatest mass a dynamic body may have, kg: a planet is about 1e25. Above it the mass
/// times the speeds, gravity and lever arms the solver multiplies it by nears f32's overflow.
pub const MAX_BODY_MASS: Real = 1.0e30;

/// The greatest rotational inertia a dynamic body may have, kg·m²: [`MAX_BODY_MASS`] at a
/// lever arm of a kilometre. Above it the inertia times the spins the solver multiplies it by
/// nears f32's overflow.
pub const MAX_BODY_INERTIA: Real = 1.0e36;

/// The most sides [`crate::Polygon::regular`] makes: each contact with a polygon walks its
/// sides, so past this a circle is the shape to use, and a number read from a file cannot
/// ask for gigabytes.
pub const MAX_REGULAR_SIDES: usize = 1 << 16;

/// The greatest friction, restitution or rolling resistance a surface may have (a mixer's
/// answer is held to it too): rubber's friction is about 1, and a thousand times the solver's
/// largest impulses still stays well inside f32.
pub const MAX_SURFACE_COEFFICIENT: Real = 1000.0;

/// The fastest a surface may move along itself, m/s, either way: past any conveyor, and the
/// two surfaces' sum times a body's mass stays well inside f32.
pub const MAX_TANGENT_SPEED: Real = 1.0e4;

/// The stiffest spring (Hz) and the heaviest damping (ratio) a joint or the solver takes: a
/// step resolves nothing stiffer than a quarter of its substep rate, so a megahertz is rigid
/// already, while above it a spring's softness terms, `(2π f h)²` at the longest step,
/// overflow f32.
pub const MAX_SPRING: Real = 1.0e6;

/// The longest a joint's length, limit, translation or offset may be, m: farther than any two
/// bodies can be placed apart. A joint's angles (limits, targets, offsets) are held within a
/// turn either way. Past them a joint's error, times the rates the solver multiplies it by,
/// nears f32's overflow.
pub const MAX_JOINT_LENGTH: Real = 1.0e7;

/// How far outside a shape's boundary a point may lie and still count as inside, in metres.
///
/// Points exactly on an edge are inside; this absorbs the rounding of moving a point into the
/// shape's local frame, so a point on the boundary does not flicker in and out.
pub(crate) const CONTAINMENT_TOLERANCE: Real = 1.0e-5;

/// Points of a polygon closer than this (relative to the polygon's size) are the same point.
pub(crate) const WELD_TOLERANCE: Real = 1.0e-5;

/// A polygon vertex whose turn has a sine below this is collinear with its neighbours.
pub(crate) const COLLINEAR_SINE: f64 = 1.0e-6;

// Narrowphase.

/// The direction used when two circle centres coincide: pushing B up, by convention.
pub const COINCIDENT_NORMAL: Vec2 = Vec2::new(0.0, 1.0);

/// Once a contact has a reference face, the other shape's best face must beat it by this much
/// to take over, so nearly equal faces do not take turns from one step to the next (Box2D's
/// 0.1 × slop).
pub(crate) const REFERENCE_TOLERANCE: Real = 0.1 * LINEAR_SLOP;

/// How far outside the reference polygon a clipped point may lie and still count: rounding,
/// not geometry, at the scale of the slop.
pub const SPURIOUS_TOLERANCE: Real = 0.1 * LINEAR_SLOP;

// Chains (Box2D's tolerances for smooth collision).

/// How sharply a chain must turn at a vertex for the vertex to count as convex, as the sine of
/// the turn: flatter joins count as concave, where normals snap to the link's own.
pub(crate) const CHAIN_CONVEX_SINE: Real = 0.01;

/// How far past a convex neighbour's normal a contact normal may lean and still be a link's
/// own, as a sine: beyond it, the neighbour handles the contact.
pub(crate) const CHAIN_NORMAL_SINE: Real = 0.01;

// Contact recycling.

/// Under soft step, a kept manifold's pair may have moved relative to each other by no more
/// than this at the farthest point of a turning body, m (less for small bodies, see
/// [`RECYCLE_SIZE_FRACTION`]): Box2D's 10 × slop. A pair that was not touching may move no more
/// than the speculative distance, so that it cannot miss becoming speculative.
pub(crate) const RECYCLE_DISTANCE: Real = 10.0 * LINEAR_SLOP;

/// [`RECYCLE_DISTANCE`] under the classic solvers. Sequential impulse settles a 20 m box on
/// two small triangles too slowly for the stability suite's bar at Box2D's distance (1.1 m/s
/// after 4 s, where it needs less than 1), and once pressed a thin sliver through the floor
/// in a random pile; 2 × slop keeps both as they were.
pub(crate) const RECYCLE_DISTANCE_CLASSIC: Real = 2.0 * LINEAR_SLOP;

/// A body that moves farther in a step than its fat box's margin pairs only with what it can
/// reach at its relative velocity (`geometry::look_ahead`); it stops doing so once it moves
/// less than this fraction of the margin, so a body near that speed does not make and drop its
/// pairs every other step.
pub(crate) const RUNNER_STOP_FRACTION: Real = 0.5;

/// A small body may move no more than this fraction of its smallest extent (its inradius) before
/// its manifolds are built again: 5 cm is a tenth of a 1 m box's half-width but all of a
/// 10 cm plank's, whose contacts change a good deal over it.
pub(crate) const RECYCLE_SIZE_FRACTION: Real = 0.25;

/// Neither body may have turned more than this since the manifold was built (the cosine of
/// the turn, Box2D's 0.98: about 11°), so the held normal and anchors stay close to the truth.
pub(crate) const RECYCLE_COS_ANGLE: Real = 0.98;

// Continuous collision.

/// A body that moves more than this fraction of its smallest extent in a step is swept by
/// continuous collision: the default of each body's own [`crate::BodyDef::sweep_threshold`]
/// (Box2D's safety factor).
pub const SWEEP_THRESHOLD: Real = 0.5;

/// A fast body whose centre moves along a chain's link, closing on it by less than this
/// fraction of its smallest extent and ending farther than that in front of it, is not swept
/// against the link (Box2D's core fraction): it cannot pass through, and its contact with the
/// link keeps it out, so a body sliding fast along a chain costs no sweeps.
pub(crate) const LINK_SKIM_FRACTION: Real = 0.25;

/// The most conservative-advancement iterations per pair (Box2D uses 20 for its root finder).
pub(crate) const MAX_TIME_OF_IMPACT_ITERATIONS: usize = 30;

/// A shape cast stops when the gap is this small, m (Box2D's quarter of the slop).
pub const SHAPE_CAST_TOLERANCE: Real = 0.25 * LINEAR_SLOP;

// Characters.

/// The most sweeps of the plane solver over a mover's planes (Box2D's 20).
pub(crate) const MAX_PLANE_ITERATIONS: usize = 20;

/// How far from 1 a collision plane's normal's squared length may be and still count as a
/// unit: normalising leaves it within a few parts in ten million; a plane whose normal is
/// further off pushes nothing.
pub(crate) const PLANE_UNIT_TOLERANCE: Real = 1.0e-3;

/// The most rounds of collide, solve and cast in one character move (Box2D's sample uses 5).
pub(crate) const MAX_CHARACTER_ITERATIONS: usize = 5;

/// A round of a character's move that goes less than this ends the move, m.
pub(crate) const CHARACTER_MOVE_TOLERANCE: Real = 0.1 * LINEAR_SLOP;

/// How far below a character the ground it stands on may be, m: it rests a slop into the
/// ground, and a cast may leave it a little short.
pub(crate) const CHARACTER_GROUND_PROBE: Real = 2.0 * LINEAR_SLOP;

// Sleeping.

/// Bodies whose fastest point moves slower than this may sleep, m/s (Box2D's 5 cm/s): the
/// default of each body's own [`crate::BodyDef::sleep_threshold`].
pub const SLEEP_THRESHOLD: Real = 0.05;

/// How long a whole island must rest before it sleeps, s (Box2D's 0.5 s).
pub const TIME_TO_SLEEP: Real = 0.5;

/// An island holding at least this share of the awake bodies (one in so many) is split by
/// reading every awake touching contact in memory order; a smaller one by walking its bodies'
/// contact lists, which costs more per contact but reads only its own.
pub(crate) const SPLIT_SCAN_SHARE: usize = 8;

// Solvers.

/// Graph colours a touching contact may take before it goes to the overflow (Box2D's 24,
/// less its overflow).
pub(crate) const COLOR_COUNT: usize = 23;

/// The colours open to contacts between two dynamic bodies (the first ones); contacts with a
/// static or kinematic body take colours from the last down (Box2D's split).
pub(crate) const DYNAMIC_COLOR_COUNT: usize = 20;

/// Sequential impulse: position passes after each step (Box2D v2.4's default).
pub(crate) const POSITION_ITERATIONS: usize = 3;

/// Sequential impulse: the most overlap one position pass removes at a point, m (Box2D v2.4's
/// `b2_maxLinearCorrection`): a deep overlap is taken apart over several steps, not flung.
pub(crate) const MAX_CORRECTION: Real = 0.2;

/// Sequential impulse: above this condition number the two points of a face are too alike to
/// solve as a block (Box2D v2.4's `k_maxConditionNumber`).
pub(crate) const MAX_CONDITION: Real = 1000.0;

/// Soft step: colours joints may take before the overflow. Joints are coloured apart from
/// contacts, in colours of their own solved after the contacts' in each pass.
pub(crate) const JOINT_COLOR_COUNT: usize = 12;

/// Joints per block, at least, when a joint colour or the joint trees are shared among
/// threads.
pub(crate) const MIN_JOINT_BLOCK: usize = 64;

/// The mouse joint's spin damping: a soft constraint toward no spin (Box2D v3.0's).
pub(crate) const MOUSE_ANGULAR_HERTZ: Real = 0.5;
pub(crate) const MOUSE_ANGULAR_DAMPING_RATIO: Real = 0.1;

/// The tutorial's impulse solver: the overlap it leaves alone, m.
pub(crate) const TUTORIAL_SLOP: Real = 0.01;

// Threads.

/// Bodies or constraints per task when the solver's per-item work is shared among threads:
/// each costs a few nanoseconds, and a fork several microseconds.
pub(crate) const ITEMS_PER_TASK: usize = 2048;

/// Contacts per task when manifolds are rebuilt on several threads (a manifold costs about
/// a tenth of a microsecond, a fork several microseconds).
pub(crate) const CONTACTS_PER_TASK: usize = 256;

/// How many contacts ahead the narrowphase asks for bodies to be fetched: far enough that
/// they arrive before they are read, near enough that they are still cached then.
pub(crate) const PREFETCH_AHEAD: usize = 8;

/// How many times [`PREFETCH_AHEAD`] ahead the narrowphase asks for the contacts themselves:
/// a contact must have arrived before its bodies can be asked for from it.
pub(crate) const CONTACTS_AHEAD: usize = 2;

/// Awake contacts below which the narrowphase asks for nothing ahead: a set this small (its
/// contacts, their bodies and fat boxes, about 0.4 MB) stays in a core's L2 cache from step
/// to step, so the hints would only add instructions.
pub(crate) const PREFETCH_MIN_CONTACTS: usize = 1024;

/// Fast bodies per task when continuous collision's sweeps are shared among threads (a sweep
/// costs a microsecond or more: a tree query and conservative advancement per shape met).
pub(crate) const SWEEPS_PER_TASK: usize = 32;

/// At most this many tasks per thread when continuous collision's sweeps are shared: enough
/// to even out sweeps of unequal cost, few enough that each task's scratch shapes, once
/// grown, serve every step after.
pub(crate) const TASKS_PER_THREAD: usize = 4;

/// Moved colliders per task when the broadphase's pair queries are shared among threads (a
/// query walks the trees in about a microsecond); with fewer than two tasks' worth, neither
/// the queries nor the pair walk are shared.
pub(crate) const MOVES_PER_TASK: usize = 64;

/// Sensors per task when their overlap queries are shared among threads (a query and a few
/// exact overlap tests cost about a microsecond, a fork several).
pub(crate) const SENSORS_PER_TASK: usize = 32;

/// Contacts and bodies, together, per thread before a snapshot or a restore is copied on two
/// threads (the contacts on one, the rest on the other): below it, a fork costs more than the
/// second core's share of the copy gains.
pub(crate) const COPY_ITEMS_PER_THREAD: usize = 1000;

/// Blocks a stage (a colour's bundles, the bodies) is cut into, at most, when soft step's
/// stages are shared among threads.
pub(crate) const MAX_BLOCKS: usize = 8;

/// Items per block, at least: a block's work must dwarf the cost of claiming it.
pub(crate) const MIN_BLOCK: usize = 16;

/// Bundles (of four or eight contacts) a step must have for soft step to share its stages
/// among threads: a bundle takes some tens of nanoseconds a pass, and starting the threads on
/// a step's stages some microseconds, with a short wait between stages.
pub(crate) const MIN_SHARED: usize = 256;

/// Bodies per block, at least, when integration is shared among threads.
pub(crate) const MIN_BODY_BLOCK: usize = 256;

/// Pieces the broadphase's pair walk is cut into when threads share it: enough to even out
/// pieces of unequal size among the threads.
pub(crate) const WALK_PIECES: usize = 128;

/// The broadphase walks its moving tree against itself for new pairs once at least this
/// fraction of the tree's leaves moved in a step (neighbours then share the walk down); when
/// fewer moved, each queries the trees from the root.
pub(crate) const WALK_MOVED_FRACTION: Real = 0.25;

/// Direct joints: at most this many loop-closing hinges per this many tree hinges in a
/// component solved directly. A few loops (a ragdoll holding a bar) are closed iteratively; a
/// net is not treated as a tree, since its iterative loops would undo the exact tree each pass.
pub(crate) const MAX_LOOPS_PER_JOINTS: (u32, u32) = (1, 8);

/// Direct joints: the compliance added to each hinge's own effective mass when the drift is
/// projected away at the end of a substep, as a fraction of it. It bounds the correction
/// where the hinges' directions line up (a taut bridge cannot stretch along itself, and an
/// exact projection there would throw its planks); a hundredth leaves the rest of the drift
/// closed to a percent.
pub(crate) const TREE_PROJECTION_GIVE: Real = 0.01;

/// Direct joints: the most times a pass solves the trees to find which hinge limits hold (a
/// stop that would pull is let go, one passed is taken in). Most passes need one; the last
/// round clamps what is still wrong.
pub(crate) const TREE_LIMIT_ROUNDS: usize = 4;

/// Direct joints: a hinge whose limits are closer than this (2°) is held at one angle within
/// them, a two-sided row, rather than by one stop at a time.
pub(crate) const LOCKED_HINGE_RANGE: Real = 0.035;

/// Shock propagation: a contact supports its upper body when its normal is within this cosine
/// of straight up (against gravity), 60°: a pile's slanted contacts carry load, a wall's or a
/// neighbour's side does not, and without gravity nothing is held.
pub(crate) const SUPPORT_COSINE: Real = 0.5;

/// Shock propagation: a level's round of at least this many supports (each of a different
/// upper body) is solved in SIMD bundles; a smaller one, a column's single support, costs
/// less one at a time than a bundle of empty lanes.
pub(crate) const MIN_WIDE_ROUND: usize = 2;
