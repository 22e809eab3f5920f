//! A world's state kept in memory, to go back to: rewinding, replaying from a keyframe,
//! rolling back a prediction.
//!
//! A snapshot holds what a saved world holds (every field of [`World`] that outlives a step),
//! copied rather than serialised, so taking one and restoring it cost about as much as copying
//! the world's arrays. Restoring copies into the world's own arrays and taking a snapshot into
//! an old one reuses its arrays (with the world's room for the lists whose length changes
//! from step to step), so a rollback loop that keeps a ring of snapshots allocates only while
//! the world grows.

use crate::heap_bytes::HeapBytes;
use crate::world::World;
use crate::world::state::WorldState;

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
    state: WorldState,
}

impl Snapshot {
    /// How many steps the world had taken when the snapshot was taken.
    pub fn step_count(&self) -> u64 {
        self.state.step_count
    }

    /// The world's simulated time when the snapshot was taken, s.
    pub fn time(&self) -> f64 {
        self.state.time
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
        self.state.heap_bytes()
    }
}

impl World {
    /// The world's state now, to [`restore`](World::restore) later. A new snapshot holds
    /// only what the world holds, its arrays no longer than the world's lists.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            state: self.state.clone(),
        }
    }

    /// Takes the world's state now into `snapshot`, replacing what it held and reusing its
    /// memory: a snapshot taken again of a world of the same size allocates nothing. The
    /// lists whose length changes from step to step (contacts, events) are copied with the
    /// room the world has for them, so a ring of snapshots taken into again and again, as a
    /// rollback loop keeps, allocates only when the world's own lists grow.
    pub fn snapshot_into(&self, snapshot: &mut Snapshot) {
        snapshot.state.copy_from(&self.state);
    }

    /// Puts the world back in the state `snapshot` holds: every body, collider, joint, contact
    /// and setting as they were, the step count and time too. Stepping on from there gives
    /// the same bits as it did from the snapshot's moment. A handle made since then names
    /// nothing now, or what is made again in its place; the pre-solve hook stays as it is.
    /// The world's memory is reused, so restoring into a world as large allocates nothing.
    pub fn restore(&mut self, snapshot: &Snapshot) {
        self.state.copy_from(&snapshot.state);
    }
}

// Names every field of `World`, so a field added later fails to compile here until it is
// sorted: state that outlives a step belongs in `WorldState`, which a snapshot copies and a
// saved world saves; the rest is what a step only works in, or code.
const _: fn(&World) = |world| {
    let World {
        // Copied.
        state: _,
        // Working memory, and the last step's figures.
        island_scratch: _,
        stats: _,
        solver_workspace: _,
        scratch: _,
        // What the world's memory has held: restoring a smaller world keeps the memory.
        high_water: _,
        // Code: the world keeps its own.
        pre_solve: _,
    } = world;
};
