//! Where each contact is kept in the contact array: in parts by what a step does with it, so
//! the solver reads each graph colour's contacts in memory order, as Box2D v3 keeps each
//! colour's contacts in an array of their own.
//!
//! The awake contacts (a body of the pair is awake) come first, the sleeping ones last. Among
//! the awake ones, in order: the overflow, the high colours (which contacts with a static body
//! take, from the last down), the contacts that do not touch, then the low colours (which
//! contacts between dynamic bodies take, from the first up). The colours most taken sit next
//! to the part that does not touch, so a contact that starts or stops touching usually crosses
//! one or two parts (see `partition`).

use crate::constants::COLOR_COUNT;
use crate::graph::colors::OVERFLOW;
use crate::partition::Partition;
use std::ops::Range;

/// The parts of the contact array (one per colour, the overflow, the awake contacts that do
/// not touch, the sleeping ones), less one.
const CUTS: usize = COLOR_COUNT + 2;

/// The contact array's parts.
pub(crate) type ContactPartition = Partition<CUTS>;

/// The colours from this one up are kept before the part that does not touch, the lower ones
/// after it.
const FIRST_HIGH: usize = COLOR_COUNT / 2;

/// The awake contacts that do not touch (and have no colour).
pub(crate) const NOT_TOUCHING: usize = 1 + COLOR_COUNT - FIRST_HIGH;

/// The sleeping contacts, touching or not: the last part.
pub(crate) const ASLEEP: usize = CUTS;

/// The part of colour `color` (or of the overflow, [`OVERFLOW`]).
#[inline]
pub(crate) fn color_part(color: u8) -> usize {
    let color = color as usize;
    if color == OVERFLOW as usize {
        0
    } else if color >= FIRST_HIGH {
        1 + color - FIRST_HIGH
    } else {
        NOT_TOUCHING + 1 + color
    }
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
    /// contacts that do not touch; the colours most taken sit beside the latter.
    #[test]
    fn every_colour_has_its_own_awake_part() {
        let mut parts: Vec<usize> = (0..=COLOR_COUNT as u8).map(color_part).collect();
        parts.push(NOT_TOUCHING);
        parts.sort_unstable();
        assert_eq!(parts, (0..ASLEEP).collect::<Vec<_>>());
        assert_eq!(color_part(0), NOT_TOUCHING + 1);
        assert_eq!(color_part(COLOR_COUNT as u8 - 1), NOT_TOUCHING - 1);
    }
}
