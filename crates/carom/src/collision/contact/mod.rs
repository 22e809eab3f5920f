//! Persistent contacts: one per pair of colliders whose fat boxes overlap, kept across steps.
//!
//! The broadphase creates a contact when two colliders' fat boxes begin to overlap; each step the
//! narrowphase rebuilds its manifold (carrying impulses over by feature id) and destroys it
//! once the boxes part. The solver works on every contact whose manifold has points,
//! speculative ones included (the shapes are within the speculative margin), as Box2D does;
//! those take a graph colour and link their bodies' islands.
//!
//! Events report something narrower: whether the shapes really touch. A pair begins to touch
//! when a point's separation is at most [`TOUCH_BEGIN`] (a tenth of the slop, not zero: a body
//! a speculative point stopped at a surface rests there to within rounding, micrometres to
//! either side), and stops once every point is farther apart than [`TOUCH_END`] (the slop), or
//! the contact is destroyed. The gap between the two is hysteresis: a resting body rocks by
//! far less than the slop, so its contact does not flicker between begin and end. A body that
//! only comes within the speculative margin and turns back (a speculative point stops it
//! short, as sequential impulse's restitution can) never touches. Changes of touching are
//! reported as begin and end events, readable after the step.
//!
//! This file holds the contact types and the set's fields; the set's work is split by concern:
//! ids, the lookup by pair, making and destroying contacts and their events (`set`), each
//! body's list of contacts (`adjacency`), where each contact is stored, colour by colour
//! (`parts`), and a saved world's contacts read back and checked (`saved`).

use crate::clone_in_place::clone_in_place;
use crate::collision::recycle::ManifoldFrame;
use crate::dynamics::body::BodyHandle;
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::surface::{Mixed, Mixers, mix};
use crate::geometry::query::manifold::Manifold;
use crate::graph::colors::ContactColors;
use crate::graph::layout::ContactPartition;
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, OwnsNothing, array, map_table, nothing};
use crate::math::Real;

mod adjacency;
mod parts;
#[cfg(feature = "serde")]
mod saved;
mod set;

use adjacency::{Edge, EdgeList, NO_EDGE};
use set::PairLookup;

/// A pair of colliders the narrowphase watches.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Contact {
    pub(super) collider_a: ColliderHandle,
    pub(super) collider_b: ColliderHandle,
    body_a: BodyHandle,
    body_b: BodyHandle,
    pub(super) manifold: Manifold,
    /// What the solver did at each point over the last step. Kept here, beside the manifold
    /// rather than in its points, so the narrowphase, which builds and copies manifolds, does
    /// not carry them.
    impulses: [PointImpulse; 2],
    /// The manifold has points, speculative ones included: the solver works on it (it has a
    /// colour while awake, and links its bodies' islands). Not what events report.
    pub(super) touching: bool,
    /// The shapes touch, as events report it (see the module's notes): within [`TOUCH_BEGIN`]
    /// to begin, [`TOUCH_END`] to go on.
    pub(super) in_contact: bool,
    /// A collider of the pair asks for hit events.
    hit_events: bool,
    /// A collider of the pair asks for the pre-solve hook.
    pub(super) pre_solve: bool,
    /// The colliders' surfaces mixed ([`crate::dynamics::surface`]). Kept current as a
    /// collider's change, so a step reads them without its colliders.
    #[cfg_attr(feature = "serde", serde(skip))]
    mixed: Mixed,
    /// The rolling resistance's accumulated angular impulse, kept for warm starting while
    /// the contact touches.
    pub(crate) rolling_impulse: Real,
    /// What the manifold was built against, to carry it along while the bodies barely move.
    pub(super) frame: ManifoldFrame,
    /// Its graph colour while touching in the awake set ([`NO_COLOR`] otherwise).
    color: u8,
    /// Which of its bodies the colour holds (the dynamic ones when it was coloured).
    color_holds: [bool; 2],
    /// How many contacts the set had made before it: the solvers that take contacts one by
    /// one take them in this order.
    serial: u64,
}

// Plain values: every field is `Copy` (one that is not fails to compile in the pattern below,
// which moves each out of a borrowed contact), so an array of contacts is its capacity alone.
impl OwnsNothing for Contact {}
const _: fn(&Contact) -> Contact = |contact| Contact { ..*contact };

impl Contact {
    /// Takes its material from its colliders (both live).
    fn mix(&mut self, colliders: &HandleMap<ColliderHandle, Collider>, mixers: &Mixers) {
        if let (Some(a), Some(b)) = (
            colliders.get(self.collider_a),
            colliders.get(self.collider_b),
        ) {
            self.mixed = mix(a, b, mixers);
            if self.mixed.rolling_resistance == 0.0 {
                self.rolling_impulse = 0.0;
            }
        }
    }

    /// The first collider (the manifold normal points away from it).
    pub fn collider_a(&self) -> ColliderHandle {
        self.collider_a
    }

    /// The second collider.
    pub fn collider_b(&self) -> ColliderHandle {
        self.collider_b
    }

    /// The first collider's body.
    pub fn body_a(&self) -> BodyHandle {
        self.body_a
    }

    /// The second collider's body.
    pub fn body_b(&self) -> BodyHandle {
        self.body_b
    }

    /// Which colliders and bodies the contact joins.
    pub fn pair(&self) -> ContactPair {
        ContactPair {
            collider_a: self.collider_a,
            collider_b: self.collider_b,
            body_a: self.body_a,
            body_b: self.body_b,
        }
    }

    /// Friction coefficient of the pair: the geometric mean of the colliders', or the
    /// world's friction mixer's answer.
    pub fn friction(&self) -> Real {
        self.mixed.friction
    }

    /// Restitution of the pair: the larger of the colliders', or the world's restitution
    /// mixer's answer.
    pub fn restitution(&self) -> Real {
        self.mixed.restitution
    }

    /// The pair's rolling resistance: the larger of the colliders' times the larger rolling
    /// radius, m (see [`crate::Surface::rolling_resistance`]).
    pub fn rolling_resistance(&self) -> Real {
        self.mixed.rolling_resistance
    }

    /// The colliders' tangent speeds added, m/s (see [`crate::Surface::tangent_speed`]).
    pub fn tangent_speed(&self) -> Real {
        self.mixed.tangent_speed
    }

    /// Where the bodies touch, as of the last step.
    pub fn manifold(&self) -> &Manifold {
        &self.manifold
    }

    /// What the solver did at each point of the manifold over the last step it solved the
    /// contact, point by point (as many as the manifold has).
    pub fn point_impulses(&self) -> &[PointImpulse] {
        &self.impulses[..self.manifold.points().len()]
    }

    /// The normal impulse the last step applied over all the points, N·s (their
    /// [`PointImpulse::total_normal_impulse`]): divided by the step, the force pressing the
    /// colliders apart.
    pub fn total_normal_impulse(&self) -> Real {
        self.point_impulses()
            .iter()
            .map(|p| p.total_normal_impulse)
            .sum()
    }

    /// The manifold and what the solver did at its points, for the solver to store impulses
    /// in.
    pub(crate) fn manifold_and_impulses_mut(&mut self) -> (&mut Manifold, &mut [PointImpulse; 2]) {
        (&mut self.manifold, &mut self.impulses)
    }

    /// True while the shapes touch, as begin and end events report it: since a point came
    /// within a tenth of the slop (0.5 mm), until every point is more than the slop apart. A
    /// contact with only speculative points does not touch, though the solver works on it
    /// (its manifold has points).
    pub fn is_touching(&self) -> bool {
        self.in_contact
    }

    /// True while the manifold has points, speculative ones included: the solver works on it.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn is_solved(&self) -> bool {
        self.touching
    }

    /// True when a collider of the pair asks for hit events.
    pub(crate) fn reports_hits(&self) -> bool {
        self.hit_events
    }

    /// How many contacts its set had made before it, for the solvers that take contacts one
    /// by one, oldest first.
    pub(crate) fn serial(&self) -> u64 {
        self.serial
    }

    /// Its colour and which bodies the colour holds, for tests.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn color(&self) -> (u8, [bool; 2]) {
        (self.color, self.color_holds)
    }
}

/// What the solver did at one contact point over a step: Box2D's `totalNormalImpulse`,
/// `maxNormalImpulse` and `normalVelocity`. Force is impulse over time: divide by the step
/// (or, for the most in a substep, by the substep).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointImpulse {
    /// The normal impulse applied here over the step, N·s: every substep's share, warm start
    /// and relaxation included, and the restitution pass. Zero where the solver pushed nothing
    /// (a speculative point never reached) and under push-out, which has no impulses.
    pub total_normal_impulse: Real,
    /// The most normal impulse applied here in one substep, N·s (the whole step for the
    /// solvers without substeps).
    pub max_normal_impulse: Real,
    /// Velocity of B relative to A along the normal here as the step began, m/s (negative
    /// while they approach): how hard a hit was.
    pub normal_velocity: Real,
}

/// Which colliders, of which bodies, a contact event is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactPair {
    /// First collider of the pair.
    pub collider_a: ColliderHandle,
    /// Second collider of the pair.
    pub collider_b: ColliderHandle,
    /// The first collider's body.
    pub body_a: BodyHandle,
    /// The second collider's body.
    pub body_b: BodyHandle,
}

/// A change in whether two colliders touch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ContactEvent {
    /// The colliders began to touch: a point came within a tenth of the slop (0.5 mm), not
    /// merely within the speculative margin (see [`Contact::is_touching`]).
    Begin(ContactPair),
    /// The colliders stopped touching: every point is more than the slop (5 mm) apart, or
    /// one of them, or its body, was removed.
    End(ContactPair),
}

impl ContactEvent {
    /// The pair the event is about.
    pub fn pair(&self) -> ContactPair {
        match *self {
            ContactEvent::Begin(pair) | ContactEvent::End(pair) => pair,
        }
    }
}

/// The contacts of a world, stored contiguously in parts (see `graph::layout`):
/// the awake ones (a body of the pair is awake) colour by colour, then the sleeping ones;
/// with a lookup by pair and each body's list.
///
/// Each contact also has an id, kept from its creation to its destruction (Box2D's contact
/// id), which the lookup and the bodies' lists hold: moving a contact between parts only
/// tells its id where it went, and walking a body's contacts hashes nothing.
#[derive(Debug, Default)]
pub(crate) struct ContactSet {
    pub(super) contacts: Vec<Contact>,
    /// Where each part of `contacts` begins and ends.
    parts: ContactPartition,
    /// How many sleeping contacts touch (they cannot change while asleep).
    asleep_touching: usize,
    /// The graph colours of the awake touching contacts.
    colors: ContactColors,
    /// The bodies of contacts that started touching, and of those that stopped (or were
    /// destroyed while touching), since the world last took them (to link islands).
    pub(super) began: Vec<(BodyHandle, BodyHandle)>,
    pub(super) ended: Vec<(BodyHandle, BodyHandle)>,
    /// Each pair's contact id: written only as contacts are made and destroyed.
    lookup: PairLookup,
    /// Each contact's id, by index (moved with the contacts).
    ids: Vec<u32>,
    /// Where each id's contact is, in the array and in its bodies' lists.
    slots: Vec<Slot>,
    /// The first id of destroyed contacts to give out again: each unused slot names the next
    /// ([`NO_ID`] for none), so freeing allocates nothing.
    free: Option<u32>,
    /// Each body's contacts, by the body's slot index: the ends of a list of [`Edge`]s linked
    /// through the slots, in the order they were made, a removal moving the last into its
    /// place. Removing a body or a collider visits its own contacts only, walks visit partners
    /// in this order, and a body's first contact allocates nothing.
    edges: Vec<EdgeList>,
    pub(super) events: Vec<ContactEvent>,
    /// Events raised between steps (removing a body), reported after the next step.
    pending: Vec<ContactEvent>,
    /// Where each contact's bodies are among all bodies (dense indices), beside the contacts
    /// so the solver reads them from a compact array (Box2D caches them in its contacts):
    /// found by the narrowphase, current for the awake contacts until the step ends.
    body_indices: Vec<BodyIndices>,
    /// How many contacts have been made.
    made: u64,
    /// The ids a removal destroys, kept to spare an allocation.
    doomed: Vec<u32>,
    /// The world's friction and restitution mixers (code: not saved).
    mixers: Mixers,
}

/// Where a contact id's contact is, and what a walk through a body's contacts reads of it.
#[derive(Debug, Clone, Copy)]
struct Slot {
    /// Its index in the contact array ([`FREE`] while the id is unused).
    index: u32,
    /// The edges before and after it in the list of its first body, then of its second
    /// ([`NO_EDGE`] at an end). While the id is unused, the first names the next unused id.
    links: [[Edge; 2]; 2],
    /// Its bodies, first and second, and whether it touches: copies of the contact's, here
    /// so that finding a body's touching partners (to split or join islands) reads the
    /// slots alone, not every contact of the body.
    bodies: [BodyHandle; 2],
    touching: bool,
}

impl Slot {
    /// The slot of an unused id, `next` naming the next unused one.
    fn unused(next: u32) -> Self {
        Slot {
            index: FREE,
            links: [[next, NO_EDGE], [NO_EDGE; 2]],
            bodies: [BodyHandle::from_raw_parts(u32::MAX, 0); 2],
            touching: false,
        }
    }

    /// The unused id after this unused one, if any.
    fn next_unused(&self) -> Option<u32> {
        let next = self.links[0][0];
        (next != NO_ID).then_some(next)
    }

    /// The slot of the contact at `index` (not yet linked into its bodies' lists).
    fn of(index: u32, contact: &Contact) -> Self {
        Slot {
            index,
            links: [[NO_EDGE; 2]; 2],
            bodies: [contact.body_a, contact.body_b],
            touching: contact.touching,
        }
    }
}

/// The index of an unused id's slot.
const FREE: u32 = u32::MAX;

/// No id: the end of the list of unused ones.
const NO_ID: u32 = u32::MAX;

/// The bodies of the contacts that started touching, and of those that stopped.
pub(crate) type TouchChanges = (Vec<(BodyHandle, BodyHandle)>, Vec<(BodyHandle, BodyHandle)>);

clone_in_place!(ContactSet {
    parts, asleep_touching, colors, lookup, slots, free, edges, made, mixers,
} roomy { contacts, ids, body_indices, began, ended, events, pending } keep { doomed });

impl HeapBytes for ContactSet {
    fn heap_bytes(&self) -> usize {
        let ContactSet {
            contacts,
            parts,
            asleep_touching,
            colors,
            began,
            ended,
            lookup,
            ids,
            slots,
            free,
            edges,
            events,
            pending,
            body_indices,
            made,
            doomed: _,
            mixers,
        } = self;
        array(contacts)
            + nothing(parts)
            + nothing(asleep_touching)
            + colors.heap_bytes()
            + array(began)
            + array(ended)
            + map_table(&lookup.0)
            + array(ids)
            + array(slots)
            + nothing(free)
            + array(edges)
            + array(events)
            + array(pending)
            + array(body_indices)
            + nothing(made)
            + nothing(mixers)
    }
}

/// Where a contact's two bodies are among all bodies (dense indices).
pub(crate) type BodyIndices = [u32; 2];

/// A new contact's [`BodyIndices`], until the narrowphase finds them.
const NO_BODIES: BodyIndices = [u32::MAX; 2];

/// Where `contact`'s bodies are, by `dense_index`.
pub(crate) fn body_indices_of(
    contact: &Contact,
    dense_index: impl Fn(BodyHandle) -> usize,
) -> BodyIndices {
    [contact.body_a, contact.body_b].map(|b| dense_index(b) as u32)
}
