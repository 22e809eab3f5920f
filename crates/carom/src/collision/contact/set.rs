//! The set's bookkeeping: each contact's id (kept from its creation to its destruction),
//! the lookup by pair of colliders, making and destroying contacts, their mixed surfaces, and
//! the begin and end events.

use super::adjacency::{NO_EDGE, edge, edge_id};
use super::{
    Contact, ContactEvent, ContactSet, NO_BODIES, NO_ID, PointImpulse, Slot, TouchChanges,
};
use crate::capacity::room;
use crate::collision::recycle::ManifoldFrame;
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::surface::{Mixers, mix};
use crate::geometry::query::manifold::Manifold;
use crate::graph::colors::NO_COLOR;
use crate::handle_map::HandleMap;
use crate::solver_set::SolverSet;
use std::collections::hash_map::Entry;
use std::collections::{HashMap, TryReserveError};
use std::hash::{BuildHasherDefault, Hasher};
use std::ops::{Deref, DerefMut};
#[cfg(any(test, all(feature = "testing", feature = "serde")))]
use {
    super::{FREE, adjacency::edge_side},
    crate::graph::colors::ContactColors,
};

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

/// Each pair's contact id, by pair key. Its `clone_from` (a world restored from a snapshot)
/// keeps a larger table than the source's, filling it again, rather than shrinking it to the
/// source's size: a rollback loop that restores a world taken with fewer contacts then steps
/// without growing the table again. Nothing walks the map in a step, so the order its entries
/// land in changes no result.
#[derive(Debug, Default)]
pub(super) struct PairLookup(pub(super) HashMap<u64, u32, BuildHasherDefault<PairHasher>>);

impl PairLookup {
    /// An empty map with room for `capacity` pairs (for a saved world's contacts).
    #[cfg(feature = "serde")]
    pub(super) fn with_capacity(capacity: usize) -> Self {
        PairLookup(HashMap::with_capacity_and_hasher(
            capacity,
            Default::default(),
        ))
    }
}

impl Clone for PairLookup {
    fn clone(&self) -> Self {
        PairLookup(self.0.clone())
    }

    fn clone_from(&mut self, source: &Self) {
        if self.0.capacity() > source.0.capacity() {
            self.0.clear();
            self.0.extend(source.0.iter().map(|(&key, &id)| (key, id)));
        } else {
            self.0.clone_from(&source.0);
        }
    }
}

impl Deref for PairLookup {
    type Target = HashMap<u64, u32, BuildHasherDefault<PairHasher>>;
    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl DerefMut for PairLookup {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.0
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

impl ContactSet {
    /// True when the pair of colliders in slots `low < high` already has a contact.
    pub(crate) fn contains(&self, low: u32, high: u32) -> bool {
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

    /// The index of the live contact of id `id`.
    #[inline]
    pub(in crate::collision) fn index_of(&self, id: u32) -> usize {
        self.slots[id as usize].index as usize
    }

    /// Says whether the contact at `index` touches (its manifold has points).
    pub(in crate::collision) fn set_touching(&mut self, index: usize, touching: bool) {
        self.contacts[index].touching = touching;
        let id = self.ids[index];
        self.slots[id as usize].touching = touching;
    }

    /// The id of the contact at `index`, which it keeps wherever it moves until destroyed.
    #[inline]
    pub(in crate::collision) fn id_at(&self, index: usize) -> u32 {
        self.ids[index]
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

    /// Drops the contact at `index`, ending it if it touched.
    pub(in crate::collision) fn destroy(&mut self, index: usize, events_now: bool) {
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
    pub(super) fn destroy_where(&mut self, body: BodyHandle, doomed: impl Fn(&Contact) -> bool) {
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
    pub(crate) fn iter(&self) -> impl ExactSizeIterator<Item = &Contact> {
        self.contacts.iter()
    }

    /// The awake contacts (a body of the pair is awake): the ones a step visits.
    #[cfg(test)]
    pub(crate) fn awake(&self) -> &[Contact] {
        &self.contacts[self.awake_range()]
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

    /// The unused ids, the next to be given out first.
    #[cfg(any(test, feature = "serde"))]
    pub(super) fn free_ids(&self) -> impl Iterator<Item = u32> + '_ {
        std::iter::successors(self.free, |&id| self.slots[id as usize].next_unused())
    }

    /// Makes room in the graph colours for the body slots below `slots`
    /// ([`crate::graph::colors::ContactColors::cover`]).
    pub(crate) fn cover_bodies(&mut self, slots: usize) {
        self.colors.cover(slots);
    }

    /// The graph colours of the awake touching contacts.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn colors(&self) -> &ContactColors {
        &self.colors
    }

    /// Makes room for `contacts` contacts in all, among as many bodies as `bodies` (slots):
    /// the contacts, their ids and lookup, their bodies' lists, and the lists of a step's
    /// touch changes and events (a step changes each contact's touching once at most).
    pub(crate) fn reserve(
        &mut self,
        contacts: usize,
        bodies: usize,
    ) -> Result<(), TryReserveError> {
        room(&mut self.contacts, contacts)?;
        room(&mut self.ids, contacts)?;
        room(&mut self.slots, contacts)?;
        room(&mut self.body_indices, contacts)?;
        let more = contacts.saturating_sub(self.lookup.len());
        self.lookup.try_reserve(more)?;
        room(&mut self.edges, bodies)?;
        self.colors.reserve(bodies)?;
        room(&mut self.began, contacts)?;
        room(&mut self.ended, contacts)?;
        room(&mut self.events, contacts)?;
        room(&mut self.doomed, contacts)
    }

    /// How many contacts there are.
    pub(crate) fn len(&self) -> usize {
        self.contacts.len()
    }

    /// The begin and end events of the last step, in the order they happened.
    pub(crate) fn events(&self) -> &[ContactEvent] {
        &self.events
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
}
