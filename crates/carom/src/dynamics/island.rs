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

use crate::dynamics::body::BodyHandle;

/// One island's record.
#[derive(Debug, Clone, Default)]
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
    pub rest: f32,
    pub rest_step: u64,
    /// Still in use (a freed record waits to be reused).
    pub live: bool,
}

/// Every island's record, by island id.
#[derive(Debug, Clone, Default)]
pub(crate) struct Islands {
    records: Vec<Island>,
    free: Vec<u32>,
}

impl Islands {
    /// A new empty island; returns its id.
    pub fn create(&mut self) -> u32 {
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
    pub fn destroy(&mut self, id: u32) {
        self.records[id as usize].live = false;
        self.free.push(id);
    }

    /// An island's record.
    #[inline]
    pub fn get(&self, id: u32) -> &Island {
        &self.records[id as usize]
    }

    /// An island's record, mutably.
    #[inline]
    pub fn get_mut(&mut self, id: u32) -> &mut Island {
        &mut self.records[id as usize]
    }

    /// The ids of the live islands, for tests.
    #[cfg(test)]
    pub fn live_ids(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.records.len() as u32).filter(|&id| self.records[id as usize].live)
    }
}
