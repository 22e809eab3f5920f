//! Where each contact is kept in the contact array: in parts by what a step does with it, so
//! the solver reads each graph colour's contacts in memory order, as Box2D v3 keeps each
//! colour's contacts in an array of their own.
//!
//! A contact that changes part crosses every non-empty part between (see `partition`), so the
//! parts a contact moves between most often sit side by side. In order: the overflow, the
//! colours, the awake contacts that do not touch, then the sleeping ones. A new contact
//! arrives in the sleeping part, the last, and one being destroyed leaves from it, so most
//! contacts made and destroyed cross one boundary. The colours are ordered by how often they
//! are taken, the most taken next to the part that does not touch: contacts between dynamic
//! bodies take the lowest colour free, from the first up, and contacts with a static or
//! kinematic body the highest, from the last down, so the two orders alternate (colour 0, the
//! last colour, colour 1, the one before the last, ...) going away from it.

use crate::constants::COLOR_COUNT;
use crate::graph::colors::OVERFLOW;
use crate::partition::Partition;
use std::ops::Range;

/// The parts of the contact array (the overflow, one per colour, the awake contacts that do
/// not touch, the sleeping ones), less one.
const CUTS: usize = COLOR_COUNT + 2;

/// The contact array's parts.
pub(crate) type ContactPartition = Partition<CUTS>;

/// The awake contacts that do not touch (and have no colour): after the overflow and the
/// colours.
pub(crate) const NOT_TOUCHING: usize = 1 + COLOR_COUNT;

/// The sleeping contacts, touching or not: the last part.
pub(crate) const ASLEEP: usize = CUTS;

/// Each colour's part, then the overflow's (the first).
const COLOR_PARTS: [usize; COLOR_COUNT + 1] = color_parts();

/// Lays the colours out going away from the part that does not touch, taking in turn the
/// lowest colour not yet placed and the highest.
const fn color_parts() -> [usize; COLOR_COUNT + 1] {
    let mut parts = [0; COLOR_COUNT + 1];
    // Colours still to place: low..high (high exclusive).
    let (mut low, mut high) = (0, COLOR_COUNT);
    let mut part = NOT_TOUCHING - 1;
    while low < high {
        if (NOT_TOUCHING - part) % 2 == 1 {
            parts[low] = part;
            low += 1;
        } else {
            high -= 1;
            parts[high] = part;
        }
        part -= 1;
    }
    parts[OVERFLOW as usize] = 0;
    parts
}

/// The part of colour `color` (or of the overflow, [`OVERFLOW`]).
#[inline]
pub(crate) fn color_part(color: u8) -> usize {
    COLOR_PARTS[color as usize]
}

/// Each colour's contacts, then the overflow's, as ranges of the contact array.
pub(crate) type ColorRanges = [Range<usize>; COLOR_COUNT + 1];

/// The colours' ranges in `parts`.
pub(crate) fn color_ranges(parts: &ContactPartition) -> ColorRanges {
    std::array::from_fn(|color| parts.range(color_part(color as u8)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every colour and the overflow have a part of their own, awake, apart from the
    /// contacts that do not touch; the colours most taken sit beside the latter, in turn from
    /// each end, and the sleeping part beside it on its other side.
    #[test]
    fn every_colour_has_its_own_awake_part() {
        let mut parts: Vec<usize> = (0..=COLOR_COUNT as u8).map(color_part).collect();
        parts.push(NOT_TOUCHING);
        parts.sort_unstable();
        assert_eq!(parts, (0..ASLEEP).collect::<Vec<_>>());
        assert_eq!(ASLEEP, NOT_TOUCHING + 1);
        let last = COLOR_COUNT as u8 - 1;
        let nearest = [0, last, 1, last - 1, 2].map(color_part);
        assert_eq!(nearest, std::array::from_fn(|i| NOT_TOUCHING - 1 - i));
        assert_eq!(color_part(OVERFLOW), 0);
    }
}
