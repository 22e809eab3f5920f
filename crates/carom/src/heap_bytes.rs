//! How much heap memory a value holds, for [`crate::Snapshot::heap_bytes`]: the capacity of
//! every array it owns times its element's size, and what each element owns in turn.
//!
//! Each type a snapshot holds counts its own fields, beside its definition, naming every one
//! in a pattern without `..` (working memory, which a snapshot does not carry, as `_`), so a
//! field added later fails to compile until it is counted.

use std::collections::HashMap;
use std::mem::size_of;

/// A value that owns heap memory (or holds values that do).
pub(crate) trait HeapBytes {
    /// The heap memory it holds, bytes: not its own size, which is wherever it is.
    fn heap_bytes(&self) -> usize;
}

/// A value that owns no heap memory: every `Copy` type, and types of plain values that are
/// not `Copy` themselves (a contact, a joint), which check beside their definition that every
/// field is `Copy`. An array of them is its capacity alone, counted without a walk.
pub(crate) trait OwnsNothing {}

impl<T: Copy> OwnsNothing for T {}

/// What a value that owns no heap memory holds there: nothing (the bound checks that it owns
/// none).
pub(crate) fn nothing<T: OwnsNothing>(_: &T) -> usize {
    0
}

/// The heap an array of values that own nothing holds: its capacity's worth of them.
pub(crate) fn array<T: OwnsNothing>(items: &Vec<T>) -> usize {
    items.capacity() * size_of::<T>()
}

/// The heap a hash map's table holds, estimated from its layout in hashbrown: a key, a value
/// and one control byte per entry of its capacity. A little under what it allocated, as the
/// table keeps about an eighth of its buckets spare (and entries removed count against the
/// capacity until it rehashes). What its keys and values own is not counted.
pub(crate) fn map_table<K, V, S>(map: &HashMap<K, V, S>) -> usize {
    map.capacity() * (size_of::<(K, V)>() + 1)
}

impl<T: HeapBytes> HeapBytes for Vec<T> {
    fn heap_bytes(&self) -> usize {
        self.capacity() * size_of::<T>() + self.iter().map(T::heap_bytes).sum::<usize>()
    }
}

impl<T: HeapBytes, const N: usize> HeapBytes for [T; N] {
    fn heap_bytes(&self) -> usize {
        self.iter().map(T::heap_bytes).sum()
    }
}
