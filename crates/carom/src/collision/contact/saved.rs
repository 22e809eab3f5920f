//! A contact set as a saved world holds it: by index, with the lookup giving each pair's index
//! and each body's list its pairs. Contact ids are not saved (they change nothing a step
//! computes); reading gives each contact the id of its index, and refuses lists that do not
//! hold each contact exactly once in each of its bodies' lists.

use super::{
    BodyIndices, Contact, ContactEvent, ContactSet, EdgeList, NO_EDGE, PairHasher, Slot, edge,
    edge_id, pair_key,
};
use crate::dynamics::body::BodyHandle;
use crate::graph::colors::ContactColors;
use crate::graph::layout::ContactPartition;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

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
    /// The set `saved` holds, each contact with the id of its index; refused when a pair is
    /// listed twice or names no contact, or a body's lists do not hold each of its contacts
    /// once. What else must hold is checked with the rest of the world (`check_saved`).
    fn from_saved(saved: Saved) -> Result<Self, String> {
        let count = saved.contacts.len();
        let Ok(count_u32) = u32::try_from(count) else {
            return Err("too many contacts".into());
        };
        let mut lookup: HashMap<u64, u32, BuildHasherDefault<PairHasher>> =
            HashMap::with_capacity_and_hasher(saved.lookup.len(), Default::default());
        for &(key, index) in &saved.lookup {
            if index >= count {
                return Err("the contact lookup names a contact that does not exist".into());
            }
            if lookup.insert(key, index as u32).is_some() {
                return Err("a pair appears twice in the contact lookup".into());
            }
        }
        let slots = (saved.contacts.iter().zip(0..count_u32))
            .map(|(contact, index)| Slot::of(index, contact))
            .collect();
        let mut set = ContactSet {
            contacts: saved.contacts,
            parts: saved.parts,
            asleep_touching: saved.asleep_touching,
            colors: saved.colors,
            began: saved.began,
            ended: saved.ended,
            lookup,
            ids: (0..count_u32).collect(),
            slots,
            free: None,
            edges: Vec::with_capacity(saved.edges.len()),
            events: saved.events,
            pending: saved.pending,
            body_indices: saved.body_indices,
            made: saved.made,
            doomed: Vec::new(),
        };
        let mut listed = vec![[false; 2]; count];
        for (body, keys) in saved.edges.iter().enumerate() {
            for key in keys {
                let Some(&id) = set.lookup.get(key) else {
                    return Err("a body lists a contact that does not exist".into());
                };
                let contact = &set.contacts[id as usize];
                let listed = &mut listed[id as usize];
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
