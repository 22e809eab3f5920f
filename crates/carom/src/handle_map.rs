//! Items stored contiguously, addressed by generational handles: bodies, colliders.
//!
//! Items live in one dense `Vec` so the hot loops walk memory in order; a slot table maps each
//! handle to its item's current place. Removal swaps the last item into the hole. A removed
//! handle never answers again: its slot comes back with a new generation, and a slot whose
//! generation would wrap is retired.

use crate::capacity::room;
use crate::clone_in_place::clone_in_place;
use crate::error::CaromError;
use crate::heap_bytes::{HeapBytes, OwnsNothing, array};
use std::collections::TryReserveError;

/// A generational handle: a slot index and the generation the slot had when it was issued.
pub(crate) trait Handle: Copy + Eq {
    /// What the handles are for, for error messages ("body").
    const WHAT: &'static str;
    /// The handle of `index` at `generation`.
    fn from_parts(index: u32, generation: u32) -> Self;
    /// The slot index.
    fn index(self) -> u32;
    /// The slot's generation when this handle was issued.
    fn generation(self) -> u32;
}

/// Declares a public generational handle type: its parts, their accessors, and [`Handle`].
macro_rules! generational_handle {
    ($(#[$doc:meta])* $name:ident, $what:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
        pub struct $name {
            index: u32,
            generation: u32,
        }

        impl $name {
            /// A handle from its parts, for tools that store handles elsewhere. A world only
            /// answers to handles it issued.
            pub fn from_raw_parts(index: u32, generation: u32) -> Self {
                $name { index, generation }
            }

            /// The slot index (reused after removal, with a new generation).
            #[inline]
            pub fn index(&self) -> u32 {
                self.index
            }

            /// The generation of the slot this handle was issued for.
            #[inline]
            pub fn generation(&self) -> u32 {
                self.generation
            }
        }

        impl $crate::handle_map::Handle for $name {
            const WHAT: &'static str = $what;
            fn from_parts(index: u32, generation: u32) -> Self {
                $name { index, generation }
            }
            fn index(self) -> u32 {
                self.index
            }
            fn generation(self) -> u32 {
                self.generation
            }
        }
    };
}
pub(crate) use generational_handle;

#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Slot {
    generation: u32,
    /// Index into `items`, or `None` while the slot is free.
    dense: Option<u32>,
}

/// Items of type `T` behind handles of type `H`.
#[derive(Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct HandleMap<H, T> {
    items: Vec<T>,
    /// The handle of each item, in the same order.
    handles: Vec<H>,
    slots: Vec<Slot>,
    free_slots: Vec<u32>,
}

clone_in_place!(HandleMap<H, T> { items, handles, slots, free_slots });

impl<H: OwnsNothing, T> HandleMap<H, T> {
    /// The heap its arrays hold, bytes, `items` counting the array of items (with what each
    /// owns, if any).
    pub(crate) fn heap_bytes_with(&self, items: fn(&Vec<T>) -> usize) -> usize {
        let HandleMap {
            items: item_array,
            handles,
            slots,
            free_slots,
        } = self;
        items(item_array) + array(handles) + array(slots) + array(free_slots)
    }
}

impl<H: OwnsNothing, T: HeapBytes> HeapBytes for HandleMap<H, T> {
    fn heap_bytes(&self) -> usize {
        self.heap_bytes_with(Vec::heap_bytes)
    }
}

impl<H, T> Default for HandleMap<H, T> {
    fn default() -> Self {
        HandleMap {
            items: Vec::new(),
            handles: Vec::new(),
            slots: Vec::new(),
            free_slots: Vec::new(),
        }
    }
}

impl<H: Handle, T> HandleMap<H, T> {
    /// Makes room for `count` items in all (and as many slots, and freed slots).
    pub(crate) fn reserve(&mut self, count: usize) -> Result<(), TryReserveError> {
        room(&mut self.items, count)?;
        room(&mut self.handles, count)?;
        room(&mut self.slots, count)?;
        room(&mut self.free_slots, count)
    }

    /// The handle the next insertion will get.
    pub(crate) fn next_handle(&self) -> H {
        match self.free_slots.last() {
            Some(&index) => H::from_parts(index, self.slots[index as usize].generation),
            None => H::from_parts(self.slots.len() as u32, 0),
        }
    }

    /// Stores an item made for the handle [`HandleMap::next_handle`] gave; returns the handle.
    pub(crate) fn insert(&mut self, item: T) -> H {
        let handle = self.next_handle();
        if handle.index() as usize == self.slots.len() {
            self.slots.push(Slot {
                generation: 0,
                dense: None,
            });
        } else {
            self.free_slots.pop();
        }
        self.slots[handle.index() as usize].dense = Some(self.items.len() as u32);
        self.items.push(item);
        self.handles.push(handle);
        handle
    }

    /// Removes an item and returns it; its handle never refers to anything again. The last
    /// item moves into its place (see [`HandleMap::dense_index`]).
    pub(crate) fn remove(&mut self, handle: H) -> Option<T> {
        let dense = self.dense_index(handle)?;
        let slot = &mut self.slots[handle.index() as usize];
        slot.dense = None;
        if let Some(next) = slot.generation.checked_add(1) {
            slot.generation = next;
            self.free_slots.push(handle.index());
        }
        let item = self.items.swap_remove(dense);
        self.handles.swap_remove(dense);
        if let Some(&moved) = self.handles.get(dense) {
            self.slots[moved.index() as usize].dense = Some(dense as u32);
        }
        Some(item)
    }

    /// Swaps the places of two items in the dense array; their handles follow them.
    pub(crate) fn swap(&mut self, i: usize, j: usize) {
        if i == j {
            return;
        }
        self.items.swap(i, j);
        self.handles.swap(i, j);
        for k in [i, j] {
            let slot = self.handles[k].index() as usize;
            self.slots[slot].dense = Some(k as u32);
        }
    }

    /// Where the handle's item sits in the dense array, if the handle is live.
    #[inline]
    pub(crate) fn dense_index(&self, handle: H) -> Option<usize> {
        self.slots
            .get(handle.index() as usize)
            .filter(|slot| slot.generation == handle.generation())
            .and_then(|slot| slot.dense)
            .map(|dense| dense as usize)
    }

    /// The dense index, or the error that names a stale handle.
    pub(crate) fn checked_index(&self, handle: H) -> Result<usize, CaromError> {
        self.dense_index(handle).ok_or(CaromError::StaleHandle {
            what: H::WHAT,
            index: handle.index(),
            generation: handle.generation(),
        })
    }

    /// True when the handle refers to a live item.
    pub(crate) fn contains(&self, handle: H) -> bool {
        self.dense_index(handle).is_some()
    }

    /// The item, if the handle is live.
    #[inline]
    pub(crate) fn get(&self, handle: H) -> Option<&T> {
        self.dense_index(handle).map(|i| &self.items[i])
    }

    /// The item, mutably, if the handle is live.
    #[inline]
    pub(crate) fn get_mut(&mut self, handle: H) -> Option<&mut T> {
        self.dense_index(handle).map(|i| &mut self.items[i])
    }

    /// Every item, in storage order.
    #[inline]
    pub(crate) fn as_slice(&self) -> &[T] {
        &self.items
    }

    /// Every item, mutably, in storage order.
    #[inline]
    pub(crate) fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.items
    }

    /// Every item in handle order (by slot index: creation order, except that a slot freed by
    /// a removal is reused), which, unlike storage order, does not change as items move.
    pub(crate) fn iter_by_handle(&self) -> ByHandle<'_, T> {
        ByHandle {
            slots: self.slots.iter(),
            items: &self.items,
            remaining: self.items.len(),
        }
    }

    /// Every item's handle, in storage order.
    pub(crate) fn handles(&self) -> &[H] {
        &self.handles
    }

    /// Every item's handle and every item, which may be changed, in storage order.
    pub(crate) fn handles_and_slice_mut(&mut self) -> (&[H], &mut [T]) {
        (&self.handles, &mut self.items)
    }

    /// How many items there are.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }

    /// How many slots there are, free or not: every handle's index is below it.
    #[inline]
    pub(crate) fn slot_count(&self) -> usize {
        self.slots.len()
    }
}

/// The items of a [`HandleMap`] in handle order.
#[derive(Debug, Clone)]
pub(crate) struct ByHandle<'a, T> {
    slots: std::slice::Iter<'a, Slot>,
    items: &'a [T],
    remaining: usize,
}

impl<'a, T> Iterator for ByHandle<'a, T> {
    type Item = &'a T;

    fn next(&mut self) -> Option<&'a T> {
        let dense = self.slots.by_ref().find_map(|slot| slot.dense)?;
        self.remaining -= 1;
        Some(&self.items[dense as usize])
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.remaining, Some(self.remaining))
    }
}

impl<T> ExactSizeIterator for ByHandle<'_, T> {}

#[cfg(feature = "serde")]
impl<H: Handle, T> HandleMap<H, T> {
    /// Checks a map read from a saved world: every handle's slot points back at it, and every
    /// free slot is free, once.
    pub(crate) fn check_saved(&self) -> Result<(), CaromError> {
        let what = H::WHAT;
        if self.handles.len() != self.items.len() {
            return Err(CaromError::bad_save(format!(
                "{what}: {} handles for {} items",
                self.handles.len(),
                self.items.len()
            )));
        }
        for (dense, handle) in self.handles.iter().enumerate() {
            if self.dense_index(*handle) != Some(dense) {
                return Err(CaromError::bad_save(format!(
                    "{what}: the slot of item {dense} does not point at it"
                )));
            }
        }
        let occupied = self
            .slots
            .iter()
            .filter(|slot| slot.dense.is_some())
            .count();
        if occupied != self.items.len() {
            return Err(CaromError::bad_save(format!(
                "{what}: {occupied} slots in use for {} items",
                self.items.len()
            )));
        }
        let mut listed = vec![false; self.slots.len()];
        for &free in &self.free_slots {
            let free_slot = self
                .slots
                .get(free as usize)
                .is_some_and(|s| s.dense.is_none());
            let first = listed
                .get_mut(free as usize)
                .is_some_and(|listed| !std::mem::replace(listed, true));
            if !(free_slot && first) {
                return Err(CaromError::bad_save(format!(
                    "{what}: free slot {free} is not free, or listed twice"
                )));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    struct Key(u32, u32);

    impl Handle for Key {
        const WHAT: &'static str = "key";
        fn from_parts(index: u32, generation: u32) -> Self {
            Key(index, generation)
        }
        fn index(self) -> u32 {
            self.0
        }
        fn generation(self) -> u32 {
            self.1
        }
    }

    #[test]
    fn removed_handles_never_alias() {
        let mut map: HandleMap<Key, f32> = HandleMap::default();
        let a = map.insert(1.0);
        let b = map.insert(2.0);
        let c = map.insert(3.0);
        assert_eq!(map.remove(a), Some(1.0));
        // `c` was swapped into `a`'s place and is still found.
        assert_eq!(map.get(c), Some(&3.0));
        let d = map.insert(4.0);
        assert_eq!(d.index(), a.index(), "the slot is reused");
        assert_ne!(d, a, "with a new generation");
        assert!(map.get(a).is_none());
        assert!(map.remove(a).is_none());
        assert!(matches!(
            map.checked_index(a),
            Err(CaromError::StaleHandle { .. })
        ));
        assert_eq!(map.get(d), Some(&4.0));
        assert_eq!(map.get(b), Some(&2.0));
        assert_eq!(map.len(), 3);
        for (&handle, item) in map.handles().iter().zip(map.as_slice()) {
            assert_eq!(map.get(handle), Some(item));
        }
    }

    #[test]
    fn exhausted_slots_are_retired() {
        let mut map: HandleMap<Key, f32> = HandleMap::default();
        let a = map.insert(0.0);
        map.slots[0].generation = u32::MAX;
        map.remove(Key(a.0, u32::MAX)).unwrap();
        let b = map.insert(1.0);
        assert_ne!(b.index(), a.index());
    }
}
