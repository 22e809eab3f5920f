//! The world's joints: stored contiguously behind handles in solver sets (awake, static,
//! asleep, see `solver_set`), with each body's list of joints (for removing a body,
//! linking islands, moving a body's joints between sets and filtering pairs).

use super::{Joint, JointEvent, JointHandle};
use crate::capacity::room;
use crate::clone_in_place::copy_with_room;
use crate::dynamics::body::BodyHandle;
#[cfg(feature = "serde")]
use crate::error::CaromError;
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, array, map_table, nothing};
use crate::solver_set::{JointSetBounds, SolverSet};
use std::collections::{HashMap, TryReserveError};
use std::ops::Range;

/// Every joint of a world.
#[derive(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointStore {
    /// Stored in solver sets: those the step solves, then joints with no dynamic body, then
    /// those of sleeping islands.
    joints: HandleMap<JointHandle, Joint>,
    sets: JointSetBounds,
    /// Each body's joints, in the order they were added.
    #[cfg_attr(feature = "serde", serde(with = "crate::sorted_map"))]
    by_body: HashMap<BodyHandle, Vec<JointHandle>>,
    /// Joints that keep their bodies from colliding: how many join each pair of bodies (the
    /// lower handle first).
    #[cfg_attr(feature = "serde", serde(with = "crate::sorted_map"))]
    filters: HashMap<(BodyHandle, BodyHandle), u32>,
    /// What happened to joints in the last step.
    pub events: Vec<JointEvent>,
}

/// The pair key of two bodies, in a fixed order.
fn pair(a: BodyHandle, b: BodyHandle) -> (BodyHandle, BodyHandle) {
    if a <= b { (a, b) } else { (b, a) }
}

impl Clone for JointStore {
    fn clone(&self) -> Self {
        let JointStore {
            joints,
            sets,
            by_body,
            filters,
            events,
        } = self;
        JointStore {
            joints: joints.clone(),
            sets: *sets,
            by_body: by_body.clone(),
            filters: filters.clone(),
            events: events.clone(),
        }
    }

    /// Each body's list is cloned into its old one: a map's own `clone_from` clones every
    /// list anew.
    fn clone_from(&mut self, source: &Self) {
        let JointStore {
            joints,
            sets,
            by_body,
            filters,
            events,
        } = self;
        joints.clone_from(&source.joints);
        *sets = source.sets;
        by_body.retain(|body, _| source.by_body.contains_key(body));
        for (body, list) in &source.by_body {
            by_body.entry(*body).or_default().clone_from(list);
        }
        filters.clone_from(&source.filters);
        // A list a step refills: copied with its room (see `clone_in_place`).
        copy_with_room(events, &source.events);
    }
}

impl HeapBytes for JointStore {
    fn heap_bytes(&self) -> usize {
        let JointStore {
            joints,
            sets,
            by_body,
            filters,
            events,
        } = self;
        let lists: usize = by_body.values().map(array).sum();
        joints.heap_bytes_with(array)
            + nothing(sets)
            + map_table(by_body)
            + lists
            + map_table(filters)
            + array(events)
    }
}

impl JointStore {
    /// The handle the next joint will get.
    pub(crate) fn next_handle(&self) -> JointHandle {
        self.joints.next_handle()
    }

    /// Stores a joint (made for [`JointStore::next_handle`]) in set `set`.
    pub(crate) fn insert(&mut self, joint: Joint, set: SolverSet) -> JointHandle {
        let [a, b] = joint.bodies();
        let filters = !joint.collide_connected() && a != b;
        let handle = self.joints.insert(joint);
        // Stored last, in the sleeping set; then moved into its own.
        self.move_to(self.joints.len() - 1, set);
        self.by_body.entry(a).or_default().push(handle);
        if b != a {
            self.by_body.entry(b).or_default().push(handle);
        }
        if filters {
            *self.filters.entry(pair(a, b)).or_default() += 1;
        }
        handle
    }

    /// Removes a joint.
    pub(crate) fn remove(&mut self, handle: JointHandle) -> Option<Joint> {
        // To the end of the sleeping set, the last of the array: the removal then moves only
        // another sleeper into its place, and every set stays contiguous.
        let index = self.joints.dense_index(handle)?;
        self.move_to(index, SolverSet::Asleep);
        let joint = self.joints.remove(handle)?;
        let [a, b] = joint.bodies();
        for body in [a, b] {
            if let Some(list) = self.by_body.get_mut(&body) {
                list.retain(|&h| h != handle);
                if list.is_empty() {
                    self.by_body.remove(&body);
                }
            }
        }
        if !joint.collide_connected() && a != b {
            let key = pair(a, b);
            if let Some(count) = self.filters.get_mut(&key) {
                *count -= 1;
                if *count == 0 {
                    self.filters.remove(&key);
                }
            }
        }
        Some(joint)
    }

    pub(crate) fn get(&self, handle: JointHandle) -> Option<&Joint> {
        self.joints.get(handle)
    }

    pub(crate) fn get_mut(&mut self, handle: JointHandle) -> Option<&mut Joint> {
        self.joints.get_mut(handle)
    }

    /// Moves the joint at dense `index` into set `to` by swaps at the set boundaries; returns
    /// its new index.
    fn move_to(&mut self, index: usize, to: SolverSet) -> usize {
        let joints = &mut self.joints;
        self.sets.move_item(index, to, |i, j| joints.swap(i, j))
    }

    /// Moves a joint into set `to` (a no-op when it is there already).
    #[allow(
        clippy::expect_used,
        reason = "only joints the store lists are refiled, and a listed joint is live"
    )]
    pub(crate) fn refile(&mut self, handle: JointHandle, to: SolverSet) {
        let index = self.joints.dense_index(handle).expect("listed joints live");
        self.move_to(index, to);
    }

    /// The dense indices of the joints a step solves.
    pub(crate) fn awake(&self) -> Range<usize> {
        self.sets.awake()
    }

    /// The set of the joint at dense `index`.
    #[cfg(any(test, feature = "serde"))]
    pub(crate) fn set_of(&self, index: usize) -> SolverSet {
        self.sets.set_of(index)
    }

    /// Every joint, in storage order: set by set.
    pub(crate) fn as_slice(&self) -> &[Joint] {
        self.joints.as_slice()
    }

    pub(crate) fn as_mut_slice(&mut self) -> &mut [Joint] {
        self.joints.as_mut_slice()
    }

    /// Every joint in handle order.
    pub(crate) fn iter_by_handle(&self) -> impl ExactSizeIterator<Item = &Joint> {
        self.joints.iter_by_handle()
    }

    pub(crate) fn len(&self) -> usize {
        self.joints.len()
    }

    /// Makes room for `count` joints in all, the bodies they join and the pairs they keep
    /// apart, and for as many break events in a step.
    pub(crate) fn reserve(&mut self, count: usize) -> Result<(), TryReserveError> {
        self.joints.reserve(count)?;
        let bodies = count.saturating_mul(2).saturating_sub(self.by_body.len());
        self.by_body.try_reserve(bodies)?;
        let pairs = count.saturating_sub(self.filters.len());
        self.filters.try_reserve(pairs)?;
        room(&mut self.events, count)
    }

    /// A body's joints.
    pub(crate) fn of_body(&self, body: BodyHandle) -> &[JointHandle] {
        self.by_body.get(&body).map_or(&[], Vec::as_slice)
    }

    /// True when a joint keeps `a` and `b` from colliding.
    pub(crate) fn filters(&self, a: BodyHandle, b: BodyHandle) -> bool {
        !self.filters.is_empty() && self.filters.contains_key(&pair(a, b))
    }

    /// The bodies joined to `body`, into `out` (cleared first; a body joined twice is listed
    /// twice).
    #[allow(
        clippy::expect_used,
        reason = "a body's joint list holds only live joints: removing a joint unlists it"
    )]
    pub(crate) fn partners(&self, body: BodyHandle, out: &mut Vec<BodyHandle>) {
        out.clear();
        for &handle in self.of_body(body) {
            let [a, b] = self
                .joints
                .get(handle)
                .expect("listed joints live")
                .bodies();
            let other = if a == body { b } else { a };
            if other != body {
                out.push(other);
            }
        }
    }
}

#[cfg(feature = "serde")]
impl JointStore {
    /// Checks joints read from a saved world: each joins live bodies with sound settings, and
    /// the lists by body and the pair filters are the ones its joints make.
    pub(crate) fn check_saved(
        &self,
        bodies: &HandleMap<BodyHandle, crate::dynamics::body::Body>,
    ) -> Result<(), CaromError> {
        self.joints.check_saved()?;
        self.sets.check_saved(self.joints.len())?;
        let mut expected = JointStore::default();
        for (joint, &handle) in self.joints.as_slice().iter().zip(self.joints.handles()) {
            let i = handle.index();
            if joint.handle() != handle || !joint.bodies().iter().all(|&b| bodies.contains(b)) {
                return Err(CaromError::bad_save(format!(
                    "joint {i} does not join live bodies"
                )));
            }
            joint
                .check_saved()
                .map_err(|e| CaromError::bad_save(format!("joint {i}: {e}")))?;
            let [a, b] = joint.bodies();
            let listed = |body| {
                self.by_body
                    .get(&body)
                    .is_some_and(|list| list.contains(&handle))
            };
            if !listed(a) || !listed(b) {
                return Err(CaromError::bad_save(format!(
                    "joint {i} is missing from its bodies' lists"
                )));
            }
            if joint.collide_connected() || a == b {
                continue;
            }
            *expected.filters.entry(pair(a, b)).or_default() += 1;
        }
        if expected.filters != self.filters {
            return Err(CaromError::bad_save(
                "the joints' collision filters are not the joints'",
            ));
        }
        for (body, joints) in &self.by_body {
            let joined = |j: &JointHandle| {
                self.joints
                    .get(*j)
                    .is_some_and(|j| j.bodies().contains(body))
            };
            if !joints.iter().all(joined) {
                return Err(CaromError::bad_save(
                    "a body lists a joint that does not join it",
                ));
            }
        }
        let listed: usize = self.by_body.values().map(Vec::len).sum();
        let ends: usize = self
            .joints
            .as_slice()
            .iter()
            .map(|j| if j.bodies()[0] == j.bodies()[1] { 1 } else { 2 })
            .sum();
        if listed != ends {
            return Err(CaromError::bad_save(
                "the joints by body are not the joints",
            ));
        }
        Ok(())
    }
}
