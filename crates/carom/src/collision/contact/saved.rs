//! A contact set as a saved world holds it: by index, with the lookup giving each pair's index
//! and each body's list its pairs, and each contact's id with the unused ids in the order
//! they are given out again (contacts are filed by id, so a restored world must keep them).
//! Reading refuses ids that are not each used once, and lists that do not hold each contact
//! exactly once in each of its bodies' lists.

use super::adjacency::{EdgeList, NO_EDGE, edge, edge_id};
use super::set::{PairLookup, pair_key};
use super::{BodyIndices, Contact, ContactEvent, ContactSet, NO_ID, Slot};
use crate::dynamics::body::{Body, BodyHandle};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::surface::Mixers;
use crate::error::CaromError;
use crate::graph::colors::ContactColors;
use crate::graph::colors::NO_COLOR;
use crate::graph::layout::ContactPartition;
use crate::handle_map::HandleMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The saved form, borrowed from a set to write it.
#[derive(Serialize)]
#[serde(rename = "ContactSet")]
struct SavedRef<'a> {
    contacts: &'a [Contact],
    parts: &'a ContactPartition,
    asleep_touching: usize,
    colors: &'a ContactColors,
    began: &'a [(BodyHandle, BodyHandle)],
    ended: &'a [(BodyHandle, BodyHandle)],
    /// Each pair and the index of its contact, sorted by pair.
    lookup: Vec<(u64, usize)>,
    /// Each body's contacts as pairs, in the list's order.
    edges: Vec<Vec<u64>>,
    events: &'a [ContactEvent],
    pending: &'a [ContactEvent],
    body_indices: &'a [BodyIndices],
    made: u64,
    /// Each contact's id, by index.
    ids: &'a [u32],
    /// The unused ids, the next to be given out first.
    free: Vec<u32>,
}

/// The saved form, as read.
#[derive(Deserialize)]
#[serde(rename = "ContactSet")]
struct Saved {
    contacts: Vec<Contact>,
    parts: ContactPartition,
    asleep_touching: usize,
    colors: ContactColors,
    began: Vec<(BodyHandle, BodyHandle)>,
    ended: Vec<(BodyHandle, BodyHandle)>,
    lookup: Vec<(u64, usize)>,
    edges: Vec<Vec<u64>>,
    events: Vec<ContactEvent>,
    pending: Vec<ContactEvent>,
    body_indices: Vec<BodyIndices>,
    made: u64,
    ids: Vec<u32>,
    free: Vec<u32>,
}

impl Serialize for ContactSet {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let keys_of = |list: &EdgeList| {
            let mut keys = Vec::new();
            let mut edge = list.first;
            while edge != NO_EDGE {
                let contact = &self.contacts[self.index_of(edge_id(edge))];
                keys.push(pair_key(contact.collider_a, contact.collider_b));
                edge = self.next(edge);
            }
            keys
        };
        let mut lookup: Vec<(u64, usize)> = self
            .lookup
            .iter()
            .map(|(&key, &id)| (key, self.index_of(id)))
            .collect();
        lookup.sort_unstable_by_key(|&(key, _)| key);
        let free = self.free_ids().collect();
        SavedRef {
            contacts: &self.contacts,
            parts: &self.parts,
            asleep_touching: self.asleep_touching,
            colors: &self.colors,
            began: &self.began,
            ended: &self.ended,
            lookup,
            edges: self.edges.iter().map(keys_of).collect(),
            events: &self.events,
            pending: &self.pending,
            body_indices: &self.body_indices,
            made: self.made,
            ids: &self.ids,
            free,
        }
        .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for ContactSet {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let saved = Saved::deserialize(deserializer)?;
        ContactSet::from_saved(saved).map_err(serde::de::Error::custom)
    }
}

impl ContactSet {
    /// The set `saved` holds; refused when a pair is listed twice or names no contact, an id
    /// is used twice or not at all, or a body's lists do not hold each of its contacts once.
    /// What else must hold is checked with the rest of the world (`check_saved`).
    fn from_saved(saved: Saved) -> Result<Self, String> {
        let count = saved.contacts.len();
        if saved.ids.len() != count {
            return Err("the contacts and their ids differ in number".into());
        }
        let slot_count = count + saved.free.len();
        if u32::try_from(slot_count).is_err() {
            return Err("too many contacts".into());
        }
        let mut slots = vec![Slot::unused(NO_ID); slot_count];
        let mut used = vec![false; slot_count];
        for &id in saved.ids.iter().chain(&saved.free) {
            match used.get_mut(id as usize) {
                Some(used) if !*used => *used = true,
                _ => return Err("a contact id is used twice, or is out of range".into()),
            }
        }
        for (index, (&id, contact)) in saved.ids.iter().zip(&saved.contacts).enumerate() {
            slots[id as usize] = Slot::of(index as u32, contact);
        }
        for (i, &id) in saved.free.iter().enumerate() {
            slots[id as usize] = Slot::unused(saved.free.get(i + 1).copied().unwrap_or(NO_ID));
        }
        let mut lookup = PairLookup::with_capacity(saved.lookup.len());
        for &(key, index) in &saved.lookup {
            let Some(&id) = saved.ids.get(index) else {
                return Err("the contact lookup names a contact that does not exist".into());
            };
            if lookup.insert(key, id).is_some() {
                return Err("a pair appears twice in the contact lookup".into());
            }
        }
        let mut set = ContactSet {
            contacts: saved.contacts,
            parts: saved.parts,
            asleep_touching: saved.asleep_touching,
            colors: saved.colors,
            began: saved.began,
            ended: saved.ended,
            lookup,
            ids: saved.ids,
            slots,
            free: saved.free.first().copied(),
            edges: Vec::with_capacity(saved.edges.len()),
            events: saved.events,
            pending: saved.pending,
            body_indices: saved.body_indices,
            made: saved.made,
            doomed: Vec::new(),
            mixers: Mixers::default(),
        };
        let mut listed = vec![[false; 2]; count];
        for (body, keys) in saved.edges.iter().enumerate() {
            for key in keys {
                let Some(&id) = set.lookup.get(key) else {
                    return Err("a body lists a contact that does not exist".into());
                };
                let index = set.index_of(id);
                let contact = &set.contacts[index];
                let listed = &mut listed[index];
                // The contact's first side that is this body and not yet listed.
                let side = [contact.body_a, contact.body_b]
                    .iter()
                    .zip(*listed)
                    .position(|(b, listed)| b.index() as usize == body && !listed)
                    .ok_or("a body lists a contact that is not its own, or lists it twice")?;
                listed[side] = true;
                set.append(body, edge(id, side));
            }
        }
        if listed.iter().flatten().any(|&listed| !listed) {
            return Err("a contact is missing from its bodies' lists".into());
        }
        set.edges.resize(saved.edges.len(), EdgeList::EMPTY);
        Ok(set)
    }
}

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
    ) -> Result<(), CaromError> {
        use crate::constants::COLOR_COUNT;
        let count = self.contacts.len();
        if self.body_indices.len() != count
            || self.parts.ends().last().is_some_and(|&end| end > count)
        {
            return Err(CaromError::bad_save(
                "the contact array's parts do not fit it",
            ));
        }
        if self.asleep_touching > count {
            return Err(CaromError::bad_save(
                "more sleeping contacts touch than there are",
            ));
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            let owner = |c: ColliderHandle| colliders.get(c).map(Collider::body);
            if owner(contact.collider_a) != Some(contact.body_a)
                || owner(contact.collider_b) != Some(contact.body_b)
            {
                return Err(CaromError::bad_save(format!(
                    "contact {i} is not between live colliders of its bodies"
                )));
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
                return Err(CaromError::bad_save(format!(
                    "contact {i} has a bad manifold or colour"
                )));
            }
            if self
                .lookup
                .get(&pair_key(contact.collider_a, contact.collider_b))
                != Some(&self.ids[i])
            {
                return Err(CaromError::bad_save(format!(
                    "contact {i} is not found by its pair"
                )));
            }
        }
        if self.lookup.len() != count {
            return Err(CaromError::bad_save(
                "the contact lookup holds pairs with no contact",
            ));
        }
        let live = |(a, b): &(BodyHandle, BodyHandle)| bodies.contains(*a) && bodies.contains(*b);
        if !self.began.iter().chain(&self.ended).all(live) {
            return Err(CaromError::bad_save(
                "a contact change names a body that does not exist",
            ));
        }
        Ok(())
    }
}
