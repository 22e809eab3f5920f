//! The world's side of persistent islands (see [`crate::dynamics::island`]): linking them as
//! contacts start touching, counting what may have split them, splitting one lazily when its
//! bodies want to sleep, and putting resting islands to sleep.

use crate::constants::{SLEEP_THRESHOLD, TIME_TO_SLEEP};
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::math::Real;
use crate::world::World;
use crate::world::solver_sets::SolverSet;

/// The memory islands work in, kept so a step allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct IslandScratch {
    /// The bodies of an island being split.
    members: Vec<BodyHandle>,
    /// The search's bodies still to visit.
    stack: Vec<BodyHandle>,
    /// One body's touching partners.
    pub partners: Vec<BodyHandle>,
    /// One body's joined partners.
    joined: Vec<BodyHandle>,
    /// The islands falling asleep this step.
    sleepy: Vec<u32>,
}

impl World {
    fn handle_index(&self, handle: BodyHandle) -> usize {
        self.bodies.dense_index(handle).expect("island bodies live")
    }

    /// Appends the body at `index` to island `id`'s list.
    fn append_to_island(&mut self, index: usize, id: u32) {
        let handle = self.bodies.handles()[index];
        let tail = self.islands.get(id).tail;
        self.bodies.as_mut_slice()[index].set_island(Some(id), tail, None);
        if let Some(tail) = tail {
            let tail = self.handle_index(tail);
            self.bodies.as_mut_slice()[tail].set_island_next(Some(handle));
        }
        let island = self.islands.get_mut(id);
        island.head.get_or_insert(handle);
        island.tail = Some(handle);
        island.len += 1;
    }

    /// Gives the dynamic body at `index` an island of its own, and returns its id.
    pub(crate) fn create_island_for(&mut self, index: usize) -> u32 {
        let id = self.islands.create();
        self.append_to_island(index, id);
        id
    }

    /// Gives the body at `index`, just made dynamic (and awake), an island, joined with those
    /// of the dynamic bodies it touches or is joined to, which wake: an island is awake or
    /// asleep as a whole.
    pub(crate) fn join_touching_islands(&mut self, index: usize) {
        self.create_island_for(index);
        let handle = self.bodies.handles()[index];
        let mut partners = std::mem::take(&mut self.island_scratch.partners);
        let mut joined = std::mem::take(&mut self.island_scratch.joined);
        self.contacts.touching_partners(handle, &mut partners);
        self.joint_partners(handle, &mut joined);
        partners.extend_from_slice(&joined);
        self.island_scratch.joined = joined;
        for &partner in &partners {
            let body = &self.bodies.as_slice()[self.handle_index(partner)];
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
        let body = &self.bodies.as_slice()[index];
        let Some(id) = body.island() else {
            return;
        };
        let (prev, next) = body.island_neighbours();
        self.bodies.as_mut_slice()[index].set_island(None, None, None);
        match prev {
            Some(prev) => {
                let prev = self.handle_index(prev);
                self.bodies.as_mut_slice()[prev].set_island_next(next);
            }
            None => self.islands.get_mut(id).head = next,
        }
        match next {
            Some(next) => {
                let next = self.handle_index(next);
                self.bodies.as_mut_slice()[next].set_island_prev(prev);
            }
            None => self.islands.get_mut(id).tail = prev,
        }
        let island = self.islands.get_mut(id);
        island.len -= 1;
        island.removed += 1;
        if island.len == 0 {
            self.islands.destroy(id);
        }
    }

    /// The island of a body, if it is dynamic and has one.
    fn island_of(&self, handle: BodyHandle) -> Option<u32> {
        self.bodies
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
        let (big, small) = if self.islands.get(ia).len >= self.islands.get(ib).len {
            (ia, ib)
        } else {
            (ib, ia)
        };
        let mut next = self.islands.get(small).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            body.set_island_id(Some(big));
        }
        let (small_head, small_tail, small_len, small_removed) = {
            let s = self.islands.get(small);
            (s.head, s.tail, s.len, s.removed)
        };
        let big_tail = self.islands.get(big).tail;
        if let (Some(tail), Some(head)) = (big_tail, small_head) {
            let tail_index = self.handle_index(tail);
            self.bodies.as_mut_slice()[tail_index].set_island_next(Some(head));
            let head_index = self.handle_index(head);
            self.bodies.as_mut_slice()[head_index].set_island_prev(Some(tail));
        }
        let island = self.islands.get_mut(big);
        island.tail = small_tail.or(island.tail);
        island.len += small_len;
        island.removed += small_removed;
        self.islands.destroy(small);
    }

    /// Counts a contact between two bodies that stopped touching (or was destroyed while
    /// touching) against their island: it may have come apart.
    pub(crate) fn unlink_contact(&mut self, a: BodyHandle, b: BodyHandle) {
        if let (Some(ia), Some(ib)) = (self.island_of(a), self.island_of(b))
            && ia == ib
        {
            self.islands.get_mut(ia).removed += 1;
        }
    }

    /// Links and unlinks islands for the contacts that started or stopped touching since the
    /// last call.
    pub(crate) fn apply_touch_changes(&mut self) {
        let (mut began, mut ended) = self.contacts.take_touch_changes();
        for &(a, b) in &ended {
            self.unlink_contact(a, b);
        }
        for &(a, b) in &began {
            self.link_islands(a, b);
        }
        began.clear();
        ended.clear();
        self.contacts.give_back_touch_changes(began, ended);
    }

    /// Splits island `id` into the groups of its bodies that touching contacts and joints
    /// still join, by a search through each body's contacts and joints; the first group keeps
    /// the id.
    fn split_island(&mut self, id: u32) {
        let mut members = std::mem::take(&mut self.island_scratch.members);
        let mut stack = std::mem::take(&mut self.island_scratch.stack);
        let mut partners = std::mem::take(&mut self.island_scratch.partners);
        let mut joined = std::mem::take(&mut self.island_scratch.joined);
        members.clear();
        let mut next = self.islands.get(id).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            // No island: not yet reached by the search.
            body.set_island(None, None, None);
            members.push(handle);
        }
        {
            let island = self.islands.get_mut(id);
            (island.head, island.tail, island.len, island.removed) = (None, None, 0, 0);
        }
        let mut current = Some(id);
        for &seed in &members {
            let seed_index = self.handle_index(seed);
            if self.bodies.as_slice()[seed_index].island().is_some() {
                continue;
            }
            let group = current.take().unwrap_or_else(|| self.islands.create());
            self.append_to_island(seed_index, group);
            stack.clear();
            stack.push(seed);
            while let Some(handle) = stack.pop() {
                self.contacts.touching_partners(handle, &mut partners);
                self.joint_partners(handle, &mut joined);
                partners.extend_from_slice(&joined);
                for &partner in &partners {
                    let index = self.handle_index(partner);
                    let body = &self.bodies.as_slice()[index];
                    if body.kind() == BodyKind::Dynamic && body.island().is_none() {
                        self.append_to_island(index, group);
                        stack.push(partner);
                    }
                }
            }
        }
        self.island_scratch.members = members;
        self.island_scratch.stack = stack;
        self.island_scratch.partners = partners;
        self.island_scratch.joined = joined;
    }

    /// The sleep stage: advances the awake dynamic bodies' sleep timers, puts every island
    /// whose bodies have all rested long enough to sleep (if it is known to be whole), and
    /// splits the sleepiest island that may have come apart, so its resting parts can sleep
    /// at the next step. Returns how many sleep timers were advanced.
    pub(crate) fn update_sleep(&mut self, dt: Real) -> usize {
        let step = self.step_count + 1;
        let awake = self.body_sets.awake();
        let mut checked = 0;
        // The sleepiest body whose island may have come apart: (sleep time, island).
        let mut split: Option<(Real, u32)> = None;
        for index in awake.clone() {
            let body = &mut self.bodies.as_mut_slice()[index];
            if body.kind() != BodyKind::Dynamic {
                continue;
            }
            body.update_sleep_time(SLEEP_THRESHOLD, dt);
            checked += 1;
            let (time, id) = (body.sleep_time(), body.island().expect("dynamic bodies"));
            let island = self.islands.get_mut(id);
            if island.rest_step != step {
                (island.rest_step, island.rest) = (step, time);
            } else {
                island.rest = island.rest.min(time);
            }
            // Ties go to the larger island id, as in Box2D, so the choice is deterministic.
            if time >= TIME_TO_SLEEP
                && island.removed > 0
                && split.is_none_or(|(t, i)| time > t || (time == t && id > i))
            {
                split = Some((time, id));
            }
        }
        // Islands at rest fall asleep, unless they may have come apart (then they wait to be
        // split). Found by their bodies, in storage order; each is put to sleep once.
        let mut sleepy = std::mem::take(&mut self.island_scratch.sleepy);
        sleepy.clear();
        for index in awake {
            let body = &self.bodies.as_slice()[index];
            let Some(id) = body.island().filter(|_| body.kind() == BodyKind::Dynamic) else {
                continue;
            };
            let island = self.islands.get_mut(id);
            let whole = island.removed == 0 || island.len == 1;
            if island.rest_step == step && island.rest >= TIME_TO_SLEEP && whole {
                // Marked so it is listed once.
                island.rest_step = 0;
                sleepy.push(id);
            }
        }
        for &id in &sleepy {
            self.sleep_island(id);
        }
        self.island_scratch.sleepy = sleepy;
        if let Some((_, id)) = split {
            self.split_island(id);
        }
        checked
    }

    /// Puts every body of island `id` to sleep: they, their colliders and contacts leave the
    /// awake set.
    pub(crate) fn sleep_island(&mut self, id: u32) {
        let mut next = self.islands.get(id).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            body.fall_asleep();
            self.move_body(index, SolverSet::Asleep);
        }
    }

    /// Wakes every body of island `id`: they, their colliders and contacts go back to the
    /// awake set. An island already awake is left alone.
    pub(crate) fn wake_island(&mut self, id: u32) {
        let mut next = self.islands.get(id).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            if !body.is_sleeping() && self.body_sets.set_of(index) == SolverSet::Awake {
                continue;
            }
            body.wake_up();
            self.move_body(index, SolverSet::Awake);
        }
    }
}
