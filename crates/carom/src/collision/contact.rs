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

use crate::clone_in_place::clone_in_place;
use crate::collision::recycle::ManifoldFrame;
use crate::constants::CONTACTS_PER_TASK;
#[cfg(feature = "serde")]
use crate::dynamics::body::Body;
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::surface::{Mixed, Mixers, mix};
use crate::geometry::query::manifold::Manifold;
use crate::graph::colors::{ColorBody, ContactColors, NO_COLOR};
use crate::graph::layout::{
    ASLEEP, ColorRanges, ContactPartition, NOT_TOUCHING, color_part, color_ranges,
};
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, OwnsNothing, array, map_table, nothing};
use crate::math::Real;
use crate::parallel::for_each_with;
use crate::partition::shift_along;
use crate::solver_set::SolverSet;
use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::hash::{BuildHasherDefault, Hasher};

#[cfg(feature = "serde")]
mod saved;

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

/// A cheap hasher for pair keys (two slot indices packed in a `u64`), which need no
/// protection against adversarial input.
#[derive(Default)]
pub(super) struct PairHasher(u64);

impl Hasher for PairHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ b as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        }
    }
    fn write_u64(&mut self, key: u64) {
        self.0 = (key ^ (key >> 29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
}

pub(super) fn pair_key(a: ColliderHandle, b: ColliderHandle) -> u64 {
    let (low, high) = if a.index() < b.index() {
        (a, b)
    } else {
        (b, a)
    };
    (low.index() as u64) << 32 | high.index() as u64
}

/// The contacts of a world, stored contiguously in parts (see `graph::layout`):
/// the awake ones (a body of the pair is awake) colour by colour, then the sleeping ones;
/// with a lookup by pair and each body's list.
///
/// Each contact also has an id, kept from its creation to its destruction (Box2D's contact
/// id), which the lookup and the bodies' lists hold: moving a contact between parts only
/// tells its id where it went, and walking a body's contacts hashes nothing.
#[derive(Debug, Default)]
pub struct ContactSet {
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
    lookup: HashMap<u64, u32, BuildHasherDefault<PairHasher>>,
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

/// One of a body's contacts: its id, and which of the contact's bodies the body is (the low
/// bit: 0 for the first).
type Edge = u32;

/// No edge: the end of a list.
const NO_EDGE: Edge = u32::MAX;

/// The first and last of a body's edges ([`NO_EDGE`] when it has none).
#[derive(Debug, Clone, Copy)]
struct EdgeList {
    first: Edge,
    last: Edge,
}

impl EdgeList {
    const EMPTY: EdgeList = EdgeList {
        first: NO_EDGE,
        last: NO_EDGE,
    };
}

fn edge(id: u32, side: usize) -> Edge {
    id << 1 | side as u32
}

fn edge_id(edge: Edge) -> u32 {
    edge >> 1
}

fn edge_side(edge: Edge) -> usize {
    (edge & 1) as usize
}

/// The bodies of the contacts that started touching, and of those that stopped.
pub(crate) type TouchChanges = (Vec<(BodyHandle, BodyHandle)>, Vec<(BodyHandle, BodyHandle)>);

clone_in_place!(ContactSet {
    contacts, parts, asleep_touching, colors, began, ended, lookup, ids, slots, free, edges,
    events, pending, body_indices, made, mixers,
} keep { doomed });

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
            + map_table(lookup)
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

impl ContactSet {
    /// True when the pair of colliders in slots `low < high` already has a contact.
    pub fn contains(&self, low: u32, high: u32) -> bool {
        self.lookup
            .contains_key(&((low as u64) << 32 | high as u64))
    }

    /// Starts watching a pair of colliders (of two bodies), in the awake set if `awake` (a
    /// body of the pair is awake). It does not touch yet, so it has no colour.
    pub(crate) fn add(
        &mut self,
        a: (ColliderHandle, &Collider),
        b: (ColliderHandle, &Collider),
        awake: bool,
    ) {
        let id = match self.lookup.entry(pair_key(a.0, b.0)) {
            Entry::Occupied(_) => return,
            Entry::Vacant(vacant) => {
                let id = if let Some(id) = self.free {
                    self.free = self.slots[id as usize].next_unused();
                    id
                } else {
                    self.slots.push(Slot::unused(NO_ID));
                    (self.slots.len() - 1) as u32
                };
                *vacant.insert(id)
            }
        };
        let contact = Contact {
            collider_a: a.0,
            collider_b: b.0,
            body_a: a.1.body(),
            body_b: b.1.body(),
            manifold: Manifold::default(),
            impulses: [PointImpulse::default(); 2],
            touching: false,
            in_contact: false,
            hit_events: a.1.hit_events() || b.1.hit_events(),
            pre_solve: a.1.pre_solve() || b.1.pre_solve(),
            mixed: mix(a.1, b.1, &self.mixers),
            rolling_impulse: 0.0,
            frame: ManifoldFrame::default(),
            color: NO_COLOR,
            color_holds: [false; 2],
            serial: self.made,
        };
        self.slots[id as usize] = Slot::of(self.contacts.len() as u32, &contact);
        for (side, body) in [contact.body_a, contact.body_b].into_iter().enumerate() {
            self.append(body.index() as usize, edge(id, side));
        }
        self.ids.push(id);
        self.contacts.push(contact);
        self.body_indices.push(NO_BODIES);
        self.made += 1;
        // New contacts arrive in the sleeping part, the last.
        if awake {
            // Not touching yet: no colour, so no kinds needed.
            let last = self.contacts.len() - 1;
            self.move_to(last, SolverSet::Awake, &|_| BodyKind::Static);
        }
    }

    /// Moves the contact at `from` along `path`, and the contacts on it one place back, with
    /// what is kept beside them (see [`crate::partition::Partition::move_item_along`]); their
    /// ids learn where they went.
    fn shift(&mut self, from: usize, path: &[usize]) {
        shift_along(&mut self.contacts, from, path);
        shift_along(&mut self.body_indices, from, path);
        shift_along(&mut self.ids, from, path);
        for &index in std::iter::once(&from).chain(path) {
            self.slots[self.ids[index] as usize].index = index as u32;
        }
    }

    /// The links of `edge`: the edges before and after it in its body's list.
    #[inline]
    fn links(&mut self, edge: Edge) -> &mut [Edge; 2] {
        &mut self.slots[edge_id(edge) as usize].links[edge_side(edge)]
    }

    /// The edge after `edge` in its body's list.
    #[inline]
    fn next(&self, edge: Edge) -> Edge {
        self.slots[edge_id(edge) as usize].links[edge_side(edge)][1]
    }

    /// The first of the edges of the body of slot index `body`.
    fn first_edge(&self, body: usize) -> Edge {
        self.edges.get(body).map_or(NO_EDGE, |list| list.first)
    }

    /// Appends `edge` to the list of the body of slot index `body`.
    fn append(&mut self, body: usize, edge: Edge) {
        if self.edges.len() <= body {
            self.edges.resize(body + 1, EdgeList::EMPTY);
        }
        let last = self.edges[body].last;
        *self.links(edge) = [last, NO_EDGE];
        if last == NO_EDGE {
            self.edges[body].first = edge;
        } else {
            self.links(last)[1] = edge;
        }
        self.edges[body].last = edge;
    }

    /// Takes `edge` out of the list of the body of slot index `body`, the last edge taking
    /// its place, as a vector's swap removal would leave it.
    fn unlink(&mut self, body: usize, edge: Edge) {
        let last = self.edges[body].last;
        let before_last = self.links(last)[0];
        if before_last == NO_EDGE {
            self.edges[body].first = NO_EDGE;
        } else {
            self.links(before_last)[1] = NO_EDGE;
        }
        self.edges[body].last = before_last;
        if last == edge {
            return;
        }
        let [before, after] = *self.links(edge);
        *self.links(last) = [before, after];
        if before == NO_EDGE {
            self.edges[body].first = last;
        } else {
            self.links(before)[1] = last;
        }
        if after == NO_EDGE {
            self.edges[body].last = last;
        } else {
            self.links(after)[0] = last;
        }
    }

    /// The index of the live contact of id `id`.
    #[inline]
    pub(super) fn index_of(&self, id: u32) -> usize {
        self.slots[id as usize].index as usize
    }

    /// Says whether the contact at `index` touches (its manifold has points).
    pub(super) fn set_touching(&mut self, index: usize, touching: bool) {
        self.contacts[index].touching = touching;
        let id = self.ids[index];
        self.slots[id as usize].touching = touching;
    }

    /// The id of the contact at `index`, which it keeps wherever it moves until destroyed.
    #[inline]
    pub(super) fn id_at(&self, index: usize) -> u32 {
        self.ids[index]
    }

    /// Moves the contact at `index` into part `to`; returns its new index.
    fn move_part(&mut self, index: usize, to: usize) -> usize {
        let mut parts = self.parts;
        let index = parts.move_item_along(index, to, |from, path| self.shift(from, path));
        self.parts = parts;
        index
    }

    /// The set of the contact at `index`.
    fn set_of(&self, index: usize) -> SolverSet {
        if index < self.parts.start(ASLEEP) {
            SolverSet::Awake
        } else {
            SolverSet::Asleep
        }
    }

    /// Gives the awake touching contact at `index` a colour and moves it into the colour's
    /// part; returns its new index.
    pub(super) fn paint(&mut self, index: usize, kinds: &impl Fn(BodyHandle) -> BodyKind) -> usize {
        let contact = &self.contacts[index];
        debug_assert!(contact.touching && contact.color == NO_COLOR);
        let side = |body: BodyHandle| ColorBody {
            slot: body.index(),
            dynamic: kinds(body) == BodyKind::Dynamic,
        };
        let (a, b) = (side(contact.body_a), side(contact.body_b));
        let color = self.colors.add(a, b);
        let contact = &mut self.contacts[index];
        contact.color = color;
        contact.color_holds = [a.dynamic, b.dynamic];
        self.move_part(index, color_part(color))
    }

    /// Takes the contact at `index` out of its colour, if it has one, freeing there the
    /// bodies it held (whatever their kind is now), into the awake part that does not touch;
    /// returns its new index.
    pub(super) fn unpaint(&mut self, index: usize) -> usize {
        let contact = &mut self.contacts[index];
        if contact.color == NO_COLOR {
            return index;
        }
        let color = contact.color;
        contact.color = NO_COLOR;
        let side = |body: BodyHandle, held: bool| ColorBody {
            slot: body.index(),
            dynamic: held,
        };
        let [held_a, held_b] = contact.color_holds;
        let (a, b) = (side(contact.body_a, held_a), side(contact.body_b, held_b));
        self.colors.remove(color, a, b);
        self.move_part(index, NOT_TOUCHING)
    }

    /// Moves the contact at `index` into `set`; returns its new index. A touching contact
    /// takes a colour in the awake set and gives it back in the sleeping one.
    fn move_to(
        &mut self,
        index: usize,
        set: SolverSet,
        kinds: &impl Fn(BodyHandle) -> BodyKind,
    ) -> usize {
        if self.set_of(index) == set {
            return index;
        }
        let touching = self.contacts[index].touching;
        if set == SolverSet::Asleep {
            self.asleep_touching += usize::from(touching);
            let index = self.unpaint(index);
            self.move_part(index, ASLEEP)
        } else {
            self.asleep_touching -= usize::from(touching);
            let index = self.move_part(index, NOT_TOUCHING);
            if touching {
                self.paint(index, kinds)
            } else {
                index
            }
        }
    }

    /// Files each contact of `body` in the awake set if one of its bodies is awake, else in
    /// the sleeping set; `bodies` tells each body's set and kind.
    pub(crate) fn refile(
        &mut self,
        body: BodyHandle,
        bodies: impl Fn(BodyHandle) -> (SolverSet, BodyKind),
    ) {
        let kinds = |b: BodyHandle| bodies(b).1;
        let awake = |b: BodyHandle| bodies(b).0 == SolverSet::Awake;
        self.for_each_of(body, |set, index| {
            let contact = &set.contacts[index];
            let to = if awake(contact.body_a) || awake(contact.body_b) {
                SolverSet::Awake
            } else {
                SolverSet::Asleep
            };
            set.move_to(index, to, &kinds);
        });
    }

    /// Colours each of a body's awake touching contacts again, after its kind changed (a body
    /// that became static frees its colours, one that became dynamic takes its own).
    pub(crate) fn repaint(&mut self, body: BodyHandle, kinds: impl Fn(BodyHandle) -> BodyKind) {
        self.for_each_of(body, |set, index| {
            if set.contacts[index].color != NO_COLOR {
                let index = set.unpaint(index);
                set.paint(index, &kinds);
            }
        });
    }

    /// Mixes again the friction and restitution of each contact of `body`, whose collider's
    /// material changed.
    pub(crate) fn remix(
        &mut self,
        body: BodyHandle,
        colliders: &HandleMap<ColliderHandle, Collider>,
    ) {
        let mixers = self.mixers;
        self.for_each_of(body, |set, index| {
            set.contacts[index].mix(colliders, &mixers);
        });
    }

    /// Takes new mixers and mixes every contact again with them.
    pub(crate) fn set_mixers(
        &mut self,
        mixers: Mixers,
        colliders: &HandleMap<ColliderHandle, Collider>,
    ) {
        self.mixers = mixers;
        for contact in &mut self.contacts {
            contact.mix(colliders, &mixers);
        }
    }

    /// The world's mixers.
    pub(crate) fn mixers(&self) -> Mixers {
        self.mixers
    }

    /// Calls `visit(self, index)` for each contact of `body`, at its index now. The visit may
    /// move contacts between parts (their edges stay as they are): the next edge is read
    /// before it.
    fn for_each_of(&mut self, body: BodyHandle, mut visit: impl FnMut(&mut Self, usize)) {
        let mut edge = self.first_edge(body.index() as usize);
        while edge != NO_EDGE {
            let index = self.index_of(edge_id(edge));
            edge = self.next(edge);
            visit(self, index);
        }
    }

    /// The other body of every touching contact of `body`.
    pub(crate) fn touching_partners(&self, body: BodyHandle, into: &mut Vec<BodyHandle>) {
        into.clear();
        let mut edge = self.first_edge(body.index() as usize);
        while edge != NO_EDGE {
            let slot = &self.slots[edge_id(edge) as usize];
            let side = edge_side(edge);
            edge = slot.links[side][1];
            if slot.touching {
                into.push(slot.bodies[1 - side]);
            }
        }
    }

    /// Drops the contact at `index`, ending it if it touched.
    pub(super) fn destroy(&mut self, index: usize, events_now: bool) {
        // From the sleeping part, the last, a removal moves only another sleeper.
        let index = self.move_to(index, SolverSet::Asleep, &|_| BodyKind::Static);
        let contact = self.contacts.swap_remove(index);
        self.body_indices.swap_remove(index);
        let id = self.ids.swap_remove(index);
        if let Some(&moved) = self.ids.get(index) {
            self.slots[moved as usize].index = index as u32;
        }
        if contact.touching {
            self.asleep_touching -= 1;
            self.ended.push((contact.body_a, contact.body_b));
        }
        self.lookup
            .remove(&pair_key(contact.collider_a, contact.collider_b));
        for (side, body) in [contact.body_a, contact.body_b].into_iter().enumerate() {
            self.unlink(body.index() as usize, edge(id, side));
        }
        self.slots[id as usize] = Slot::unused(self.free.unwrap_or(NO_ID));
        self.free = Some(id);
        if contact.in_contact {
            let event = ContactEvent::End(contact.pair());
            if events_now {
                self.events.push(event);
            } else {
                self.pending.push(event);
            }
        }
    }

    /// Drops every contact of a collider (of `body`) that is being removed.
    pub(crate) fn remove_collider(&mut self, body: BodyHandle, handle: ColliderHandle) {
        self.destroy_where(body, |c| c.collider_a == handle || c.collider_b == handle);
    }

    /// Drops every contact of a body that is being removed.
    pub(crate) fn remove_body(&mut self, handle: BodyHandle) {
        self.destroy_where(handle, |_| true);
    }

    /// Drops the contacts of `body` that `doomed` picks (their filters no longer allow them).
    pub(crate) fn remove_where(&mut self, body: BodyHandle, doomed: impl Fn(&Contact) -> bool) {
        self.destroy_where(body, doomed);
    }

    /// Drops every contact between two bodies (a joint now keeps them apart).
    pub(crate) fn remove_between(&mut self, a: BodyHandle, b: BodyHandle) {
        self.destroy_where(a, |c| c.body_a() == b || c.body_b() == b);
    }

    /// Drops the contacts of `body` that `doomed` picks.
    fn destroy_where(&mut self, body: BodyHandle, doomed: impl Fn(&Contact) -> bool) {
        // By id, as each removal moves other contacts and edges.
        let mut ids = std::mem::take(&mut self.doomed);
        ids.clear();
        let mut edge = self.first_edge(body.index() as usize);
        while edge != NO_EDGE {
            let id = edge_id(edge);
            if doomed(&self.contacts[self.index_of(id)]) {
                ids.push(id);
            }
            edge = self.next(edge);
        }
        for &id in &ids {
            self.destroy(self.index_of(id), false);
        }
        self.doomed = ids;
    }

    /// Forgets last step's events; those raised since (by removals) become this step's.
    pub(crate) fn begin_step(&mut self) {
        self.events.clear();
        self.events.append(&mut self.pending);
    }

    /// Every contact.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &Contact> {
        self.contacts.iter()
    }

    /// The indices of the awake contacts (a body of the pair is awake): the first ones.
    pub(super) fn awake_range(&self) -> std::ops::Range<usize> {
        0..self.parts.start(ASLEEP)
    }

    /// How many contacts are in the awake set.
    pub(crate) fn awake_len(&self) -> usize {
        self.awake_range().end
    }

    /// The part of the contact at `index`, for tests of the layout.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn part_of(&self, index: usize) -> usize {
        self.parts.part_of(index)
    }

    /// How many sleeping contacts touch, as counted while filing them.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn asleep_touching(&self) -> usize {
        self.asleep_touching
    }

    /// The awake contacts (a body of the pair is awake): the ones a step visits.
    #[cfg(test)]
    pub(crate) fn awake(&self) -> &[Contact] {
        &self.contacts[self.awake_range()]
    }

    /// Finds where the awake contacts' bodies are among all bodies (`dense_index`), on all
    /// threads: once a step, after the narrowphase and the wakes and links it caused, when
    /// no body changes set again before the solver reads them.
    pub(crate) fn find_body_indices(&mut self, dense_index: impl Fn(BodyHandle) -> usize + Sync) {
        let awake = self.awake_range();
        let (contacts, indices) = (&self.contacts[awake.clone()], &mut self.body_indices[awake]);
        for_each_with(contacts, indices, CONTACTS_PER_TASK, |contact, indices| {
            *indices = body_indices_of(contact, &dense_index);
        });
    }

    /// Takes the bodies of the contacts that started and stopped touching since the last call;
    /// give the lists back (emptied) with [`ContactSet::give_back_touch_changes`] to keep their
    /// memory.
    pub(crate) fn take_touch_changes(&mut self) -> TouchChanges {
        (
            std::mem::take(&mut self.began),
            std::mem::take(&mut self.ended),
        )
    }

    /// Returns the lists [`ContactSet::take_touch_changes`] lent.
    pub(crate) fn give_back_touch_changes(
        &mut self,
        began: Vec<(BodyHandle, BodyHandle)>,
        ended: Vec<(BodyHandle, BodyHandle)>,
    ) {
        (self.began, self.ended) = (began, ended);
    }

    /// Where each colour's contacts (then the overflow's) are among the awake contacts.
    pub(crate) fn color_ranges(&self) -> ColorRanges {
        color_ranges(&self.parts)
    }

    /// The awake contacts and where their bodies are (current from the narrowphase until the
    /// step ends).
    pub(crate) fn awake_and_bodies(&self) -> (&[Contact], &[BodyIndices]) {
        let awake = self.awake_range();
        (&self.contacts[awake.clone()], &self.body_indices[awake])
    }

    /// The awake contacts, mutably, for the solver, where their bodies are, and where each
    /// colour's contacts are among them.
    pub(crate) fn awake_mut_and_colors(&mut self) -> (&mut [Contact], &[BodyIndices], ColorRanges) {
        let awake = self.awake_range();
        let colors = self.color_ranges();
        (
            &mut self.contacts[awake.clone()],
            &self.body_indices[awake],
            colors,
        )
    }

    /// The unused ids, the next to be given out first.
    #[cfg(any(test, feature = "serde"))]
    fn free_ids(&self) -> impl Iterator<Item = u32> + '_ {
        std::iter::successors(self.free, |&id| self.slots[id as usize].next_unused())
    }

    /// Checks the ids: each contact's id finds it and its pair finds the id, the unused ids
    /// are the free ones, and each body's list holds exactly its contacts, each where its id
    /// says.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn check_ids(&self) {
        assert_eq!(self.ids.len(), self.contacts.len());
        assert_eq!(self.lookup.len(), self.contacts.len());
        for (index, (contact, &id)) in self.contacts.iter().zip(&self.ids).enumerate() {
            assert_eq!(self.index_of(id), index, "contact {index}'s id");
            let key = pair_key(contact.collider_a, contact.collider_b);
            assert_eq!(self.lookup.get(&key), Some(&id), "contact {index}'s pair");
            let slot = &self.slots[id as usize];
            assert_eq!(
                slot.bodies,
                [contact.body_a, contact.body_b],
                "contact {index}'s bodies"
            );
            assert_eq!(
                slot.touching, contact.touching,
                "contact {index}'s touching"
            );
        }
        // Each list, walked forwards, links back and holds only its body's live contacts.
        let mut listed = vec![[false; 2]; self.slots.len()];
        for (body, list) in self.edges.iter().enumerate() {
            let (mut before, mut edge) = (NO_EDGE, list.first);
            while edge != NO_EDGE {
                let (id, side) = (edge_id(edge), edge_side(edge));
                let slot = &self.slots[id as usize];
                assert_ne!(slot.index, FREE, "body {body} lists an unused id");
                let contact = &self.contacts[slot.index as usize];
                let of = [contact.body_a, contact.body_b][side];
                assert_eq!(
                    of.index() as usize,
                    body,
                    "body {body} lists another's contact"
                );
                assert!(!listed[id as usize][side], "body {body}'s list loops");
                listed[id as usize][side] = true;
                assert_eq!(slot.links[side][0], before, "body {body}'s list links back");
                (before, edge) = (edge, slot.links[side][1]);
            }
            assert_eq!(list.last, before, "body {body}'s last edge");
        }
        let mut free = Vec::new();
        for id in self.free_ids() {
            assert!(free.len() < self.slots.len(), "the free ids loop");
            free.push(id);
        }
        free.sort_unstable();
        let unused: Vec<u32> = (0..self.slots.len() as u32)
            .filter(|&id| self.slots[id as usize].index == FREE)
            .collect();
        assert_eq!(unused, free, "the free ids are the unused ones");
        let listed = listed.iter().flatten().filter(|&&listed| listed).count();
        assert_eq!(
            listed,
            2 * self.contacts.len(),
            "the bodies list every contact"
        );
    }

    /// The graph colours of the awake touching contacts.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn colors(&self) -> &ContactColors {
        &self.colors
    }

    /// How many contacts touch: the awake ones coloured, the sleeping ones remembered.
    pub(crate) fn touching_count(&self) -> usize {
        self.awake_range().len() - self.parts.range(NOT_TOUCHING).len() + self.asleep_touching
    }

    /// How many contacts there are.
    pub fn len(&self) -> usize {
        self.contacts.len()
    }

    /// The begin and end events of the last step, in the order they happened.
    pub fn events(&self) -> &[ContactEvent] {
        &self.events
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

#[cfg(feature = "serde")]
impl ContactSet {
    /// Gives each contact of a saved world, once checked, what it keeps from its colliders
    /// (its mixed surfaces), so it steps as the world it was saved from.
    pub(crate) fn mix_saved(&mut self, colliders: &HandleMap<ColliderHandle, Collider>) {
        let mixers = self.mixers;
        for contact in &mut self.contacts {
            contact.mix(colliders, &mixers);
        }
    }

    /// Checks contacts read from a saved world: each is between live colliders of its bodies,
    /// with at most two finite points and a colour that exists, and the lookups find them.
    pub(crate) fn check_saved(
        &self,
        colliders: &HandleMap<ColliderHandle, Collider>,
        bodies: &HandleMap<BodyHandle, Body>,
    ) -> Result<(), String> {
        use crate::constants::COLOR_COUNT;
        let count = self.contacts.len();
        if self.body_indices.len() != count
            || self.parts.ends().last().is_some_and(|&end| end > count)
        {
            return Err("the contact array's parts do not fit it".into());
        }
        if self.asleep_touching > count {
            return Err("more sleeping contacts touch than there are".into());
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            let owner = |c: ColliderHandle| colliders.get(c).map(Collider::body);
            if owner(contact.collider_a) != Some(contact.body_a)
                || owner(contact.collider_b) != Some(contact.body_b)
            {
                return Err(format!(
                    "contact {i} is not between live colliders of its bodies"
                ));
            }
            let m = &contact.manifold;
            let finite = m.is_sound()
                && m.normal.iter().all(|x| x.is_finite())
                && m.points().iter().all(|p| {
                    [p.point, p.anchor_a, p.anchor_b]
                        .iter()
                        .flat_map(|v| v.iter())
                        .all(|x| x.is_finite())
                        && [
                            p.separation,
                            p.normal_impulse,
                            p.tangent_impulse,
                            p.shock_impulse,
                        ]
                        .iter()
                        .all(|x| x.is_finite())
                })
                && contact.rolling_impulse.is_finite();
            let colored = (contact.color as usize) < COLOR_COUNT
                || contact.color == crate::graph::colors::OVERFLOW
                || contact.color == NO_COLOR;
            if !finite || !colored {
                return Err(format!("contact {i} has a bad manifold or colour"));
            }
            if self
                .lookup
                .get(&pair_key(contact.collider_a, contact.collider_b))
                != Some(&self.ids[i])
            {
                return Err(format!("contact {i} is not found by its pair"));
            }
        }
        if self.lookup.len() != count {
            return Err("the contact lookup holds pairs with no contact".into());
        }
        let live = |(a, b): &(BodyHandle, BodyHandle)| bodies.contains(*a) && bodies.contains(*b);
        if !self.began.iter().chain(&self.ended).all(live) {
            return Err("a contact change names a body that does not exist".into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Contacts between random bodies made and destroyed at random: each body's linked list
    /// holds its edges in the order a vector with swap removal would, the order partners are
    /// walked in, which the islands (and so every result) depend on.
    #[test]
    fn edge_lists_keep_the_order_of_swap_removal() {
        const BODIES: usize = 5;
        let mut set = ContactSet::default();
        let mut model: Vec<Vec<Edge>> = vec![Vec::new(); BODIES];
        let mut live: Vec<(u32, [usize; 2])> = Vec::new();
        let mut seed: u32 = 99;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as usize
        };
        for id in 0..500u32 {
            set.slots.push(Slot {
                index: id,
                ..Slot::unused(NO_ID)
            });
            let a = next() % BODIES;
            let bodies = [a, (a + 1 + next() % (BODIES - 1)) % BODIES];
            for (side, body) in bodies.into_iter().enumerate() {
                set.append(body, edge(id, side));
                model[body].push(edge(id, side));
            }
            live.push((id, bodies));
            while next() % 5 < 2 && !live.is_empty() {
                let (gone, bodies) = live.swap_remove(next() % live.len());
                for (side, body) in bodies.into_iter().enumerate() {
                    set.unlink(body, edge(gone, side));
                    let at = model[body].iter().position(|&e| e == edge(gone, side));
                    model[body].swap_remove(at.unwrap());
                }
            }
            for (body, expected) in model.iter().enumerate() {
                let mut walked = Vec::new();
                let mut edge = set.first_edge(body);
                while edge != NO_EDGE {
                    walked.push(edge);
                    edge = set.next(edge);
                }
                assert_eq!(&walked, expected, "body {body} after contact {id}");
                assert_eq!(set.edges[body].last, *expected.last().unwrap_or(&NO_EDGE));
            }
        }
        assert!(live.len() > 20, "{} contacts live at the end", live.len());
    }
}
