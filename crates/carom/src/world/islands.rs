//! The world's side of persistent islands (see [`crate::dynamics::island`]): linking them as
//! contacts start touching, counting what may have split them. Splitting one is
//! [`super::island_split`]; putting resting islands to sleep is [`super::sleep`].

use crate::capacity::room;
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::world::World;
use std::collections::TryReserveError;

/// The memory islands work in, kept so a step allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct IslandScratch {
    /// The bodies of an island being split, in its list's order.
    pub(super) members: Vec<BodyHandle>,
    /// Where each body is among `members`, by its slot index (stale entries are told apart
    /// by `members` not holding the body there).
    pub(super) local: Vec<u32>,
    /// Each member's parent in the union-find, by place among `members`.
    pub(super) parents: Vec<u32>,
    /// The island each group's root goes to, by place among `members`.
    pub(super) groups: Vec<u32>,
    /// One body's touching partners.
    pub partners: Vec<BodyHandle>,
    /// One body's joined partners.
    pub(super) joined: Vec<BodyHandle>,
    /// The islands falling asleep this step.
    pub(super) sleepy: Vec<u32>,
}

impl IslandScratch {
    /// Makes room for an island of `bodies` bodies to split, and as many to fall asleep.
    pub(crate) fn reserve(&mut self, bodies: usize) -> Result<(), TryReserveError> {
        room(&mut self.members, bodies)?;
        room(&mut self.local, bodies)?;
        room(&mut self.parents, bodies)?;
        room(&mut self.groups, bodies)?;
        room(&mut self.partners, bodies)?;
        room(&mut self.joined, bodies)?;
        room(&mut self.sleepy, bodies)
    }
}

impl World {
    #[allow(
        clippy::expect_used,
        reason = "islands list only live bodies: removing a body takes it out of its island"
    )]
    pub(super) fn handle_index(&self, handle: BodyHandle) -> usize {
        self.state
            .bodies
            .dense_index(handle)
            .expect("island bodies live")
    }

    /// Appends the body at `index` to island `id`'s list.
    pub(super) fn append_to_island(&mut self, index: usize, id: u32) {
        let handle = self.state.bodies.handles()[index];
        let tail = self.state.islands.get(id).tail;
        self.state.bodies.as_mut_slice()[index].set_island(Some(id), tail, None);
        if let Some(tail) = tail {
            let tail = self.handle_index(tail);
            self.state.bodies.as_mut_slice()[tail].set_island_next(Some(handle));
        }
        let island = self.state.islands.get_mut(id);
        island.head.get_or_insert(handle);
        island.tail = Some(handle);
        island.len += 1;
    }

    /// Gives the dynamic body at `index` an island of its own, and returns its id.
    pub(crate) fn create_island_for(&mut self, index: usize) -> u32 {
        let id = self.state.islands.create();
        self.append_to_island(index, id);
        id
    }

    /// Gives the body at `index`, just made dynamic (and awake), an island, joined with those
    /// of the dynamic bodies it touches or is joined to, which wake: an island is awake or
    /// asleep as a whole.
    pub(crate) fn join_touching_islands(&mut self, index: usize) {
        self.create_island_for(index);
        let handle = self.state.bodies.handles()[index];
        let mut partners = std::mem::take(&mut self.island_scratch.partners);
        let mut joined = std::mem::take(&mut self.island_scratch.joined);
        self.state.contacts.touching_partners(handle, &mut partners);
        self.joint_partners(handle, &mut joined);
        partners.extend_from_slice(&joined);
        self.island_scratch.joined = joined;
        for &partner in &partners {
            let body = &self.state.bodies.as_slice()[self.handle_index(partner)];
            if let (true, Some(island)) = (body.is_sleeping(), body.island()) {
                self.wake_island(island);
            }
            self.link_islands(handle, partner);
        }
        self.island_scratch.partners = partners;
    }

    /// Takes the body at `index` out of its island, if it has one (it is being removed, or is
    /// no longer dynamic). The island may have come apart; an empty one is freed.
    pub(crate) fn leave_island(&mut self, index: usize) {
        let body = &self.state.bodies.as_slice()[index];
        let Some(id) = body.island() else {
            return;
        };
        let (prev, next) = body.island_neighbours();
        self.state.bodies.as_mut_slice()[index].set_island(None, None, None);
        match prev {
            Some(prev) => {
                let prev = self.handle_index(prev);
                self.state.bodies.as_mut_slice()[prev].set_island_next(next);
            }
            None => self.state.islands.get_mut(id).head = next,
        }
        match next {
            Some(next) => {
                let next = self.handle_index(next);
                self.state.bodies.as_mut_slice()[next].set_island_prev(prev);
            }
            None => self.state.islands.get_mut(id).tail = prev,
        }
        let island = self.state.islands.get_mut(id);
        island.len -= 1;
        island.removed += 1;
        if island.len == 0 {
            self.state.islands.destroy(id);
        }
    }

    /// The island of a body, if it is dynamic and has one.
    fn island_of(&self, handle: BodyHandle) -> Option<u32> {
        self.state
            .bodies
            .get(handle)
            .filter(|body| body.kind() == BodyKind::Dynamic)
            .and_then(|body| body.island())
    }

    /// Joins the islands of two bodies whose contact started touching: the smaller island's
    /// bodies move to the larger one's list.
    pub(crate) fn link_islands(&mut self, a: BodyHandle, b: BodyHandle) {
        let (Some(ia), Some(ib)) = (self.island_of(a), self.island_of(b)) else {
            return;
        };
        if ia == ib {
            return;
        }
        let (big, small) = if self.state.islands.get(ia).len >= self.state.islands.get(ib).len {
            (ia, ib)
        } else {
            (ib, ia)
        };
        let mut next = self.state.islands.get(small).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.state.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            body.set_island_id(Some(big));
        }
        let (small_head, small_tail, small_len, small_removed) = {
            let s = self.state.islands.get(small);
            (s.head, s.tail, s.len, s.removed)
        };
        let big_tail = self.state.islands.get(big).tail;
        if let (Some(tail), Some(head)) = (big_tail, small_head) {
            let tail_index = self.handle_index(tail);
            self.state.bodies.as_mut_slice()[tail_index].set_island_next(Some(head));
            let head_index = self.handle_index(head);
            self.state.bodies.as_mut_slice()[head_index].set_island_prev(Some(tail));
        }
        let island = self.state.islands.get_mut(big);
        island.tail = small_tail.or(island.tail);
        island.len += small_len;
        island.removed += small_removed;
        self.state.islands.destroy(small);
    }

    /// Counts a contact between two bodies that stopped touching (or was destroyed while
    /// touching) against their island: it may have come apart.
    pub(crate) fn unlink_contact(&mut self, a: BodyHandle, b: BodyHandle) {
        if let (Some(ia), Some(ib)) = (self.island_of(a), self.island_of(b))
            && ia == ib
        {
            self.state.islands.get_mut(ia).removed += 1;
        }
    }

    /// Links and unlinks islands for the contacts that started or stopped touching since the
    /// last call.
    pub(crate) fn apply_touch_changes(&mut self) {
        let (mut began, mut ended) = self.state.contacts.take_touch_changes();
        for &(a, b) in &ended {
            self.unlink_contact(a, b);
        }
        for &(a, b) in &began {
            self.link_islands(a, b);
        }
        began.clear();
        ended.clear();
        self.state.contacts.give_back_touch_changes(began, ended);
    }
}
