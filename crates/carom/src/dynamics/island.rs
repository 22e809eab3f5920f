//! Persistent islands, as Box2D v3 keeps them: the groups of dynamic bodies joined by touching
//! contacts, which sleep and wake together.
//!
//! An island is a list threaded through its bodies (each knows its island and its neighbours
//! in the list) with a small record here: its ends, its size, and how many of its contacts
//! stopped touching since it was last whole. Islands are linked when a contact starts touching
//! (the smaller one's bodies join the larger), and never split then: a contact that stops
//! touching only counts against its island. An island is split (by a search through its
//! touching contacts) only when one of its bodies wants to sleep, so a step spends nothing on
//! islands but their changes. Static and kinematic bodies belong to no island, or one floor
//! would tie a whole world together (Box2D 3.2 gives kinematic bodies islands). A sleeping
//! island wakes when an awake dynamic body or a moving kinematic one touches it; a still
//! kinematic platform lets what rests on it sleep.

use crate::capacity::room;
use crate::clone_in_place::clone_in_place;
#[cfg(feature = "serde")]
use crate::dynamics::body::Body;
use crate::dynamics::body::BodyHandle;
#[cfg(feature = "serde")]
use crate::error::CaromError;
#[cfg(feature = "serde")]
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, array};
use crate::math::Real;
use std::collections::TryReserveError;

/// One island's record.
#[derive(Debug, Clone, Copy, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Island {
    /// The first and last bodies of its list.
    pub head: Option<BodyHandle>,
    pub tail: Option<BodyHandle>,
    /// How many bodies it has.
    pub len: u32,
    /// Contacts between its bodies that stopped touching (or bodies that left it) since it
    /// was last known to be connected: above zero, it may have come apart.
    pub removed: u32,
    /// The shortest time any of its awake bodies has rested, as of step `rest_step`.
    pub rest: Real,
    pub rest_step: u64,
    /// Still in use (a freed record waits to be reused).
    pub live: bool,
}

/// Every island's record, by island id.
#[derive(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Islands {
    records: Vec<Island>,
    free: Vec<u32>,
}

clone_in_place!(Islands { records, free });

impl HeapBytes for Islands {
    fn heap_bytes(&self) -> usize {
        let Islands { records, free } = self;
        array(records) + array(free)
    }
}

impl Islands {
    /// Makes room for `count` islands in all (one per dynamic body at most).
    pub(crate) fn reserve(&mut self, count: usize) -> Result<(), TryReserveError> {
        room(&mut self.records, count)?;
        room(&mut self.free, count)
    }

    /// A new empty island; returns its id.
    pub(crate) fn create(&mut self) -> u32 {
        let record = Island {
            live: true,
            ..Island::default()
        };
        match self.free.pop() {
            Some(id) => {
                self.records[id as usize] = record;
                id
            }
            None => {
                self.records.push(record);
                (self.records.len() - 1) as u32
            }
        }
    }

    /// Frees an island's record for reuse.
    pub(crate) fn destroy(&mut self, id: u32) {
        self.records[id as usize].live = false;
        self.free.push(id);
    }

    /// An island's record.
    #[inline]
    pub(crate) fn get(&self, id: u32) -> &Island {
        &self.records[id as usize]
    }

    /// An island's record, mutably.
    #[inline]
    pub(crate) fn get_mut(&mut self, id: u32) -> &mut Island {
        &mut self.records[id as usize]
    }

    /// The ids of the live islands, for tests.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn live_ids(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.records.len() as u32).filter(|&id| self.records[id as usize].live)
    }
}

#[cfg(feature = "serde")]
impl Islands {
    /// Checks islands read from a saved world: each live island's list runs through dynamic
    /// bodies of that island, from its head to its tail, as long as it says; every dynamic
    /// body is in a live island; freed records are not live.
    pub(crate) fn check_saved(
        &self,
        bodies: &HandleMap<BodyHandle, Body>,
    ) -> Result<(), CaromError> {
        for &id in &self.free {
            if self.records.get(id as usize).is_none_or(|r| r.live) {
                return Err(CaromError::bad_save(format!(
                    "island {id} is free but live, or does not exist"
                )));
            }
        }
        for (id, record) in self.records.iter().enumerate() {
            if !record.live {
                continue;
            }
            let (mut at, mut previous, mut count) = (record.head, None, 0u32);
            while let Some(handle) = at {
                let body = bodies
                    .get(handle)
                    .filter(|b| b.is_dynamic() && b.island() == Some(id as u32))
                    .ok_or_else(|| {
                        CaromError::bad_save(format!("island {id} lists a body not in it"))
                    })?;
                let (prev, next) = body.island_neighbours();
                count += 1;
                if prev != previous || count > record.len {
                    return Err(CaromError::bad_save(format!(
                        "island {id}'s list is broken"
                    )));
                }
                (previous, at) = (Some(handle), next);
            }
            if count != record.len || previous != record.tail {
                return Err(CaromError::bad_save(format!(
                    "island {id}'s list is broken"
                )));
            }
        }
        for body in bodies.as_slice() {
            let live = body
                .island()
                .is_some_and(|id| self.records.get(id as usize).is_some_and(|r| r.live));
            if body.is_dynamic() != live {
                return Err(CaromError::bad_save(format!(
                    "body {} is not in a live island, or is not dynamic",
                    body.handle().index()
                )));
            }
        }
        Ok(())
    }
}
