//! A world's state kept in memory, to go back to: rewinding, replaying from a keyframe,
//! rolling back a prediction.
//!
//! A snapshot holds what a saved world holds (every field of [`World`] that outlives a step),
//! copied rather than serialised, so taking one and restoring it cost about as much as copying
//! the world's arrays. Restoring copies into the world's own arrays and taking a snapshot into
//! an old one reuses its arrays, so a rollback loop that keeps a ring of snapshots allocates
//! only while the world grows.

use crate::collision::broadphase::BroadPhase;
use crate::collision::contact::ContactSet;
use crate::collision::hits::HitEvent;
use crate::collision::sensor::Sensors;
use crate::constants::COPY_ITEMS_PER_THREAD;
use crate::dynamics::body::{Body, BodyHandle};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::island::Islands;
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, array, nothing};
use crate::joint::store::JointStore;
use crate::parallel::worth_sharing;
use crate::solver_set::SetBounds;
use crate::world::World;
use crate::world::settings::WorldSettings;

/// A world's whole state at one moment, in memory: bodies, colliders, joints, contacts with
/// their warm-start impulses, islands, sleep, the broadphase and the settings.
///
/// [`World::restore`] puts it back, and the world then steps on to exactly the bits it stepped
/// to the first time. The pre-solve hook is code and is not part of a snapshot: a restored
/// world keeps the hook it has.
///
/// ```
/// use carom::{BodyDef, Shape, World, vec2};
///
/// let mut world = World::new();
/// let ball = world.add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 4.0)))?;
/// let start = world.snapshot();
/// for _ in 0..30 {
///     world.step(1.0 / 60.0)?;
/// }
/// let first = world.body(ball).unwrap().position();
/// world.restore(&start);
/// for _ in 0..30 {
///     world.step(1.0 / 60.0)?;
/// }
/// assert_eq!(world.body(ball).unwrap().position(), first);
/// # Ok::<(), carom::CaromError>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct Snapshot {
    settings: WorldSettings,
    time: f64,
    step_count: u64,
    bodies: HandleMap<BodyHandle, Body>,
    colliders: HandleMap<ColliderHandle, Collider>,
    joints: JointStore,
    islands: Islands,
    body_sets: SetBounds,
    collider_sets: SetBounds,
    broadphase: BroadPhase,
    contacts: ContactSet,
    sensors: Sensors,
    hit_events: Vec<HitEvent>,
    hit_event_colliders: usize,
}

impl Snapshot {
    /// How many steps the world had taken when the snapshot was taken.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    /// The world's simulated time when the snapshot was taken, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The heap memory the snapshot holds, bytes: the capacity of every array it owns (bodies,
    /// colliders, joints, contacts, islands, the broadphase's trees, sensors, events) times
    /// its element's size, what each element owns in turn (a body's list of colliders, a
    /// polygon's points when it has more than it holds inline, a sensor's overlaps), and its
    /// hash maps' tables (estimated as a key, a value and one control byte per entry of their
    /// capacity). For showing memory and bounding it, such as a timeline's keyframes: it
    /// walks the bodies, colliders and sensors, not the contacts, so it takes microseconds for
    /// a thousand bodies.
    ///
    /// The `Snapshot` value itself (`size_of::<Snapshot>()`, wherever it is kept) is not
    /// counted.
    pub fn heap_bytes(&self) -> usize {
        let Snapshot {
            settings,
            time,
            step_count,
            bodies,
            colliders,
            joints,
            islands,
            body_sets,
            collider_sets,
            broadphase,
            contacts,
            sensors,
            hit_events,
            hit_event_colliders,
        } = self;
        nothing(settings)
            + nothing(time)
            + nothing(step_count)
            + bodies.heap_bytes()
            + colliders.heap_bytes()
            + joints.heap_bytes()
            + islands.heap_bytes()
            + nothing(body_sets)
            + nothing(collider_sets)
            + broadphase.heap_bytes()
            + contacts.heap_bytes()
            + sensors.heap_bytes()
            + array(hit_events)
            + nothing(hit_event_colliders)
    }
}

/// Clones every part of a world's state from `$from` into `$into` (a world or a snapshot, which
/// name their parts alike), each into its old memory.
macro_rules! copy_state {
    ($into:expr, $from:expr) => {{
        let (into, from) = ($into, $from);
        into.settings.clone_from(&from.settings);
        into.time = from.time;
        into.step_count = from.step_count;
        into.hit_event_colliders = from.hit_event_colliders;
        into.hit_events.clone_from(&from.hit_events);
        into.joints.clone_from(&from.joints);
        into.islands.clone_from(&from.islands);
        into.body_sets.clone_from(&from.body_sets);
        into.collider_sets.clone_from(&from.collider_sets);
        into.sensors.clone_from(&from.sensors);
        let mut contacts = || into.contacts.clone_from(&from.contacts);
        let mut bodies = || {
            into.bodies.clone_from(&from.bodies);
            into.colliders.clone_from(&from.colliders);
            into.broadphase.clone_from(&from.broadphase);
        };
        // The copy is bound by memory traffic, which a second core adds to.
        if worth_sharing(
            from.contacts.len() + from.bodies.len(),
            COPY_ITEMS_PER_THREAD,
        ) {
            rayon::join(contacts, bodies);
        } else {
            contacts();
            bodies();
        }
    }};
}

impl World {
    /// The world's state now, to [`restore`](World::restore) later.
    pub fn snapshot(&self) -> Snapshot {
        let mut snapshot = Snapshot::default();
        self.snapshot_into(&mut snapshot);
        snapshot
    }

    /// Takes the world's state now into `snapshot`, replacing what it held and reusing its
    /// memory: a snapshot taken again of a world of the same size allocates nothing.
    pub fn snapshot_into(&self, snapshot: &mut Snapshot) {
        copy_state!(snapshot, self);
    }

    /// Puts the world back in the state `snapshot` holds: every body, collider, joint, contact
    /// and setting as they were, the step count and time too. Stepping on from there gives
    /// the same bits as it did from the snapshot's moment. A handle made since then names
    /// nothing now, or what is made again in its place; the pre-solve hook stays as it is.
    /// The world's memory is reused, so restoring into a world as large allocates nothing.
    pub fn restore(&mut self, snapshot: &Snapshot) {
        copy_state!(self, snapshot);
    }
}

// Names every field of `World`, so a field added later fails to compile here until it is
// sorted: state that outlives a step, which `copy_state!` copies (and a saved world saves), or
// what a step only works in, or code.
const _: fn(&World) = |world| {
    let World {
        // Copied.
        bodies: _,
        colliders: _,
        joints: _,
        islands: _,
        body_sets: _,
        collider_sets: _,
        broadphase: _,
        contacts: _,
        settings: _,
        time: _,
        step_count: _,
        hit_event_colliders: _,
        hit_events: _,
        sensors: _,
        // Working memory, and the last step's figures.
        island_scratch: _,
        stats: _,
        solver_workspace: _,
        scratch: _,
        // Code: the world keeps its own.
        pre_solve: _,
    } = world;
};
