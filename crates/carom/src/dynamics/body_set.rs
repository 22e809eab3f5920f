//! Bodies stored contiguously, addressed by generational handles.
//!
//! Bodies live in one dense `Vec` so the hot loops walk memory in order; a slot table maps
//! each handle to its body's current place. Removal swaps the last body into the hole.

use crate::dynamics::body::{Body, BodyDef, BodyHandle};
use crate::error::CaromError;

#[derive(Debug, Clone, Copy)]
struct Slot {
    generation: u32,
    /// Index into `bodies`, or `None` while the slot is free.
    dense: Option<u32>,
}

/// The bodies of a world.
#[derive(Debug, Clone, Default)]
pub struct BodySet {
    bodies: Vec<Body>,
    slots: Vec<Slot>,
    free_slots: Vec<u32>,
}

impl BodySet {
    /// Validates `def` and stores the new body.
    pub fn insert(&mut self, def: BodyDef) -> Result<BodyHandle, CaromError> {
        let handle = match self.free_slots.last() {
            Some(&index) => BodyHandle {
                index,
                generation: self.slots[index as usize].generation,
            },
            None => BodyHandle {
                index: self.slots.len() as u32,
                generation: 0,
            },
        };
        let body = Body::new(handle, def)?;
        if handle.index as usize == self.slots.len() {
            self.slots.push(Slot {
                generation: 0,
                dense: None,
            });
        } else {
            self.free_slots.pop();
        }
        self.slots[handle.index as usize].dense = Some(self.bodies.len() as u32);
        self.bodies.push(body);
        Ok(handle)
    }

    /// Removes a body and returns it; its handle never refers to anything again.
    pub fn remove(&mut self, handle: BodyHandle) -> Result<Body, CaromError> {
        let dense = self.dense_index(handle)?;
        let slot = &mut self.slots[handle.index as usize];
        slot.dense = None;
        // A slot whose generation would wrap is retired, so old handles can never alias.
        if let Some(next) = slot.generation.checked_add(1) {
            slot.generation = next;
            self.free_slots.push(handle.index);
        }
        let body = self.bodies.swap_remove(dense);
        if let Some(moved) = self.bodies.get(dense) {
            self.slots[moved.handle().index as usize].dense = Some(dense as u32);
        }
        Ok(body)
    }

    /// Where the handle's body sits in the dense array.
    pub fn dense_index(&self, handle: BodyHandle) -> Result<usize, CaromError> {
        self.slots
            .get(handle.index as usize)
            .filter(|slot| slot.generation == handle.generation)
            .and_then(|slot| slot.dense)
            .map(|dense| dense as usize)
            .ok_or(CaromError::StaleHandle {
                index: handle.index,
                generation: handle.generation,
            })
    }

    /// How many slots exist (live or free).
    pub fn slot_count(&self) -> usize {
        self.slots.len()
    }

    /// The dense index of the body in a slot, if the slot is live (generation not checked).
    pub fn dense_index_of_slot(&self, slot: usize) -> Option<usize> {
        self.slots
            .get(slot)
            .and_then(|s| s.dense)
            .map(|d| d as usize)
    }

    /// True when the handle refers to a live body.
    pub fn contains(&self, handle: BodyHandle) -> bool {
        self.dense_index(handle).is_ok()
    }

    /// The body, if the handle is live.
    pub fn get(&self, handle: BodyHandle) -> Option<&Body> {
        self.dense_index(handle).ok().map(|i| &self.bodies[i])
    }

    /// The body, mutably, if the handle is live.
    pub fn get_mut(&mut self, handle: BodyHandle) -> Option<&mut Body> {
        self.dense_index(handle).ok().map(|i| &mut self.bodies[i])
    }

    /// Every body, in storage order.
    #[inline]
    pub fn as_slice(&self) -> &[Body] {
        &self.bodies
    }

    /// Every body, mutably, in storage order.
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [Body] {
        &mut self.bodies
    }

    /// How many bodies there are.
    #[inline]
    pub fn len(&self) -> usize {
        self.bodies.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    fn ball_at(x: f32) -> BodyDef {
        BodyDef::dynamic(Shape::circle(0.5)).position(vec2(x, 0.0))
    }

    #[test]
    fn removed_handles_never_alias() {
        let mut set = BodySet::default();
        let a = set.insert(ball_at(1.0)).unwrap();
        let b = set.insert(ball_at(2.0)).unwrap();
        let c = set.insert(ball_at(3.0)).unwrap();
        assert_eq!(set.remove(a).unwrap().position(), vec2(1.0, 0.0));
        // `c` was swapped into `a`'s place and is still found.
        assert_eq!(set.get(c).unwrap().position(), vec2(3.0, 0.0));
        let d = set.insert(ball_at(4.0)).unwrap();
        assert_eq!(d.index(), a.index(), "the slot is reused");
        assert_ne!(d, a, "with a new generation");
        assert!(set.get(a).is_none());
        assert!(matches!(set.remove(a), Err(CaromError::StaleHandle { .. })));
        assert_eq!(set.get(d).unwrap().position(), vec2(4.0, 0.0));
        assert_eq!(set.get(b).unwrap().position(), vec2(2.0, 0.0));
        assert_eq!(set.len(), 3);
        for body in set.as_slice() {
            assert_eq!(set.get(body.handle()).unwrap().position(), body.position());
        }
    }

    #[test]
    fn a_rejected_body_takes_no_slot() {
        let mut set = BodySet::default();
        assert!(set.insert(ball_at(f32::NAN)).is_err());
        assert_eq!(set.len(), 0);
        let a = set.insert(ball_at(0.0)).unwrap();
        assert_eq!((a.index(), a.generation()), (0, 0));
    }

    #[test]
    fn exhausted_slots_are_retired() {
        let mut set = BodySet::default();
        let a = set.insert(ball_at(0.0)).unwrap();
        set.slots[0].generation = u32::MAX;
        let worn = BodyHandle {
            index: a.index,
            generation: u32::MAX,
        };
        set.remove(worn).unwrap();
        let b = set.insert(ball_at(1.0)).unwrap();
        assert_ne!(b.index(), a.index());
    }
}
