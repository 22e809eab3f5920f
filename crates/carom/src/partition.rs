//! One dense array kept in consecutive parts, so each part is a slice: the solver sets of
//! bodies, colliders and contacts, and the touching contacts' graph colours (see
//! `solver_set` and `graph::layout`).
//!
//! An item changes part by trading places with the first or last item of each part it crosses,
//! so a move costs one swap per non-empty part crossed, whatever the size of the array. New
//! items are pushed onto the array's end, into the last part, and removed from there.

use std::ops::Range;

/// Where the parts of one array end: part `p` is `[ends[p - 1], ends[p])` (from 0 for the
/// first), and the last part, `CUTS`, runs from `ends[CUTS - 1]` to the array's end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Partition<const CUTS: usize> {
    ends: [usize; CUTS],
}

impl<const CUTS: usize> Default for Partition<CUTS> {
    fn default() -> Self {
        Partition { ends: [0; CUTS] }
    }
}

impl<const CUTS: usize> Partition<CUTS> {
    /// Where each part but the last ends.
    #[cfg(feature = "serde")]
    pub(crate) fn ends(&self) -> &[usize] {
        &self.ends
    }

    /// The partition whose parts end at `ends`: `CUTS` of them, in order.
    #[cfg(feature = "serde")]
    pub(crate) fn from_ends(ends: &[usize]) -> Option<Self> {
        let ends: [usize; CUTS] = ends.try_into().ok()?;
        ends.is_sorted().then_some(Partition { ends })
    }

    /// The part of the item at `index`.
    #[inline]
    pub(crate) fn part_of(&self, index: usize) -> usize {
        self.ends.partition_point(|&end| end <= index)
    }

    /// Where part `part` begins.
    #[inline]
    pub(crate) fn start(&self, part: usize) -> usize {
        if part == 0 { 0 } else { self.ends[part - 1] }
    }

    /// The indices of part `part`, which must not be the last (whose end is the array's).
    #[inline]
    pub(crate) fn range(&self, part: usize) -> Range<usize> {
        self.start(part)..self.ends[part]
    }

    /// Moves the item at `index` into part `to` by swapping it across each boundary on the way
    /// (`swap(i, j)` swaps two items of the array); returns its new index. Only the items at
    /// the boundaries it crosses move.
    pub(crate) fn move_item(
        &mut self,
        mut index: usize,
        to: usize,
        mut swap: impl FnMut(usize, usize),
    ) -> usize {
        let mut part = self.part_of(index);
        while part < to {
            // Down: trade places with the last of this part, which then ends before it.
            let last = self.ends[part] - 1;
            if index != last {
                swap(index, last);
            }
            self.ends[part] -= 1;
            index = last;
            part += 1;
        }
        while part > to {
            // Up: trade places with the first of this part, which then begins after it.
            let first = self.ends[part - 1];
            if index != first {
                swap(index, first);
            }
            self.ends[part - 1] += 1;
            index = first;
            part -= 1;
        }
        index
    }

    /// [`Partition::move_item`], told to the caller as one move along a path: `shift(from,
    /// path)` must put the item at `from` at the path's last position, and the item at each
    /// position of the path at the one before it (the first at `from`), which is where the
    /// swaps would leave them. Each item moves once, instead of twice in each swap; returns the
    /// item's new index.
    pub(crate) fn move_item_along(
        &mut self,
        index: usize,
        to: usize,
        shift: impl FnOnce(usize, &[usize]),
    ) -> usize {
        let mut path = [0; CUTS];
        let mut len = 0;
        let end = self.move_item(index, to, |_, j| {
            path[len] = j;
            len += 1;
        });
        if len > 0 {
            shift(index, &path[..len]);
        }
        end
    }
}

/// Moves `items` as [`Partition::move_item_along`] asks: the item at `from` to the path's end,
/// each other item on the path one place back along it.
pub(crate) fn shift_along<T: Clone>(items: &mut [T], from: usize, path: &[usize]) {
    let moving = items[from].clone();
    let mut hole = from;
    for &next in path {
        items[hole] = items[next].clone();
        hole = next;
    }
    items[hole] = moving;
}

/// A partition is written as its ends, and checked when read.
#[cfg(feature = "serde")]
mod written {
    use super::Partition;
    use serde::de::{self, Deserializer};
    use serde::ser::Serializer;
    use serde::{Deserialize, Serialize};

    impl<const CUTS: usize> Serialize for Partition<CUTS> {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            self.ends().serialize(serializer)
        }
    }

    impl<'de, const CUTS: usize> Deserialize<'de> for Partition<CUTS> {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            let ends = Vec::<usize>::deserialize(deserializer)?;
            Partition::from_ends(&ends).ok_or_else(|| {
                de::Error::custom(format!(
                    "a partition needs {CUTS} ends in increasing order, got {ends:?}"
                ))
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Items labelled by their part, moved around at random among five parts: the parts stay
    /// contiguous, each item lands in the part asked for, and nothing is lost.
    #[test]
    fn moves_keep_the_parts_contiguous() {
        const PARTS: usize = 5;
        let mut items: Vec<(u32, usize)> = Vec::new();
        let mut partition = Partition::<{ PARTS - 1 }>::default();
        let mut seed: u32 = 12345;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            seed >> 8
        };
        for label in 0..300 {
            // New items arrive at the end (the last part), then go where they belong.
            let to = next() as usize % PARTS;
            items.push((label, PARTS - 1));
            let at = partition.move_item(items.len() - 1, to, |i, j| items.swap(i, j));
            items[at].1 = to;
            // Some item changes part, and now and then the last item leaves.
            let pick = next() as usize % items.len();
            let to = next() as usize % PARTS;
            let at = partition.move_item(pick, to, |i, j| items.swap(i, j));
            items[at].1 = to;
            if next() % 7 == 0 {
                let pick = next() as usize % items.len();
                let at = partition.move_item(pick, PARTS - 1, |i, j| items.swap(i, j));
                items.swap_remove(at);
            }
            for (i, &(_, part)) in items.iter().enumerate() {
                assert_eq!(partition.part_of(i), part, "item {i} after {label} inserts");
            }
            for part in 0..PARTS - 1 {
                let range = partition.range(part);
                assert!(items[range].iter().all(|&(_, p)| p == part));
            }
        }
        let mut labels: Vec<u32> = items.iter().map(|&(l, _)| l).collect();
        labels.sort_unstable();
        labels.dedup();
        assert_eq!(labels.len(), items.len());
    }

    /// Moving along a path leaves every item where the swaps leave it.
    #[test]
    fn a_move_along_the_path_matches_the_swaps() {
        const PARTS: usize = 5;
        let mut seed: u32 = 777;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            seed >> 8
        };
        let mut swapped: Vec<u32> = Vec::new();
        let mut shifted: Vec<u32> = Vec::new();
        let (mut by_swaps, mut by_path) = (
            Partition::<{ PARTS - 1 }>::default(),
            Partition::<{ PARTS - 1 }>::default(),
        );
        for label in 0..400 {
            swapped.push(label);
            shifted.push(label);
            let last = swapped.len() - 1;
            let (index, to) = if next() % 3 == 0 {
                (last, next() as usize % PARTS)
            } else {
                (next() as usize % swapped.len(), next() as usize % PARTS)
            };
            let a = by_swaps.move_item(index, to, |i, j| swapped.swap(i, j));
            let b = by_path.move_item_along(index, to, |from, path| {
                shift_along(&mut shifted, from, path)
            });
            assert_eq!(a, b);
            assert_eq!(by_swaps, by_path);
            assert_eq!(swapped, shifted, "after {label}");
        }
    }
}
