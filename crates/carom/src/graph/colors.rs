//! Persistent graph colouring of the touching contacts, as Box2D v3 keeps it: within one
//! colour no two contacts share a dynamic body, so a colour's contacts can be solved in any
//! order, several at a time in SIMD lanes or on several threads, with the same result as one by
//! one.
//!
//! A contact takes a colour when it starts touching in the awake set and gives it back when it
//! stops touching, falls asleep or is destroyed, so a step spends nothing on colouring. Contacts
//! between two dynamic bodies take the lowest colour free for both, among the first
//! [`DYNAMIC_COLOR_COUNT`]; a contact with a static or kinematic body takes the highest colour
//! free for its dynamic body, never colour 0. Colours are solved in order, so the contacts that
//! hold bodies up against the ground are solved last in each pass and have the last word.
//! A contact that finds no colour free goes to the overflow, solved one by one after the colours.

use crate::capacity::room;
use crate::clone_in_place::clone_in_place;
use crate::constants::{COLOR_COUNT, DYNAMIC_COLOR_COUNT};
use crate::heap_bytes::{HeapBytes, array};
use std::collections::TryReserveError;

/// The colour of a contact that has none (not touching, or asleep).
pub(crate) const NO_COLOR: u8 = u8::MAX;

/// The colour of the overflow: contacts solved one by one.
pub(crate) const OVERFLOW: u8 = COLOR_COUNT as u8;

/// One bit per body slot.
#[derive(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct BodyBits(Vec<u64>);

impl Clone for BodyBits {
    fn clone(&self) -> Self {
        BodyBits(self.0.clone())
    }

    fn clone_from(&mut self, source: &Self) {
        self.0.clone_from(&source.0);
    }
}

impl HeapBytes for BodyBits {
    fn heap_bytes(&self) -> usize {
        let BodyBits(words) = self;
        array(words)
    }
}

impl BodyBits {
    fn get(&self, slot: u32) -> bool {
        self.0
            .get(slot as usize / 64)
            .is_some_and(|word| word >> (slot % 64) & 1 == 1)
    }

    fn set(&mut self, slot: u32) {
        let word = slot as usize / 64;
        if self.0.len() <= word {
            self.0.resize(word + 1, 0);
        }
        self.0[word] |= 1 << (slot % 64);
    }

    /// Room for every slot below `slots`, so that setting one allocates nothing.
    fn cover(&mut self, slots: usize) {
        let words = slots.div_ceil(64);
        if self.0.len() < words {
            self.0.resize(words, 0);
        }
    }

    fn clear(&mut self, slot: u32) {
        if let Some(word) = self.0.get_mut(slot as usize / 64) {
            *word &= !(1 << (slot % 64));
        }
    }
}

/// One body of a contact as colouring sees it: its slot index, and whether it is dynamic
/// (only dynamic bodies take impulses, so only they may not appear twice in a colour).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ColorBody {
    pub slot: u32,
    pub dynamic: bool,
}

/// Which dynamic bodies each colour holds. Each colour's contacts are a part of the contact
/// array (see `graph::layout`).
#[derive(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactColors {
    bodies: [BodyBits; COLOR_COUNT],
}

clone_in_place!(ContactColors { bodies });

impl HeapBytes for ContactColors {
    fn heap_bytes(&self) -> usize {
        let ContactColors { bodies } = self;
        bodies.heap_bytes()
    }
}

impl ContactColors {
    /// Gives a contact between `a` and `b` a colour, which then holds their dynamic bodies
    /// ([`OVERFLOW`] if none is free).
    pub(crate) fn add(&mut self, a: ColorBody, b: ColorBody) -> u8 {
        let color = self.pick(a, b);
        if color != OVERFLOW {
            for body in [a, b].iter().filter(|body| body.dynamic) {
                self.bodies[color as usize].set(body.slot);
            }
        }
        color
    }

    /// Makes room in every colour for the body slots below `slots`: a world's slots grow only
    /// as bodies are added, so with room made as a step begins, colouring the contacts that
    /// start touching in it allocates nothing.
    pub(crate) fn cover(&mut self, slots: usize) {
        for bits in &mut self.bodies {
            bits.cover(slots);
        }
    }

    /// Makes room in every colour for `slots` body slots, so that bodies added later do not
    /// make a step grow a colour.
    pub(crate) fn reserve(&mut self, slots: usize) -> Result<(), TryReserveError> {
        for BodyBits(words) in &mut self.bodies {
            room(words, slots.div_ceil(64))?;
        }
        Ok(())
    }

    /// The colour a contact between `a` and `b` takes.
    fn pick(&self, a: ColorBody, b: ColorBody) -> u8 {
        let free = |color: usize, body: ColorBody| !self.bodies[color].get(body.slot);
        let found = match (a.dynamic, b.dynamic) {
            (true, true) => (0..DYNAMIC_COLOR_COUNT).find(|&c| free(c, a) && free(c, b)),
            (true, false) => (1..COLOR_COUNT).rev().find(|&c| free(c, a)),
            (false, true) => (1..COLOR_COUNT).rev().find(|&c| free(c, b)),
            (false, false) => None,
        };
        found.map_or(OVERFLOW, |color| color as u8)
    }

    /// Takes a contact between `a` and `b` out of `color`, freeing its bodies there.
    pub(crate) fn remove(&mut self, color: u8, a: ColorBody, b: ColorBody) {
        if color != OVERFLOW {
            for body in [a, b].iter().filter(|body| body.dynamic) {
                self.bodies[color as usize].clear(body.slot);
            }
        }
    }

    /// True when `slot`'s bit is set in `color`, for tests of the colouring.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn holds(&self, color: u8, slot: u32) -> bool {
        self.bodies[color as usize].get(slot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dynamic(slot: u32) -> ColorBody {
        ColorBody {
            slot,
            dynamic: true,
        }
    }

    fn fixed(slot: u32) -> ColorBody {
        ColorBody {
            slot,
            dynamic: false,
        }
    }

    /// A chain of dynamic bodies alternates two colours from the bottom; contacts with the
    /// ground take the highest colours; removing frees the colour for the next contact.
    #[test]
    fn contacts_take_free_colours_and_give_them_back() {
        let mut colors = ContactColors::default();
        assert_eq!(colors.add(dynamic(1), dynamic(2)), 0);
        assert_eq!(colors.add(dynamic(2), dynamic(3)), 1);
        assert_eq!(colors.add(dynamic(3), dynamic(4)), 0);
        let top = (COLOR_COUNT - 1) as u8;
        assert_eq!(colors.add(fixed(0), dynamic(1)), top);
        assert_eq!(colors.add(dynamic(2), fixed(0)), top);
        assert_eq!(colors.add(fixed(0), dynamic(1)), top - 1);
        // The ground is not held by any colour.
        assert!(!colors.holds(top, 0));
        // The first contact leaves colour 0, which then takes it again.
        colors.remove(0, dynamic(1), dynamic(2));
        assert!(!colors.holds(0, 1) && colors.holds(0, 3));
        assert_eq!(colors.add(dynamic(1), dynamic(2)), 0);
    }

    /// A body in more contacts than there are colours sends the rest to the overflow.
    #[test]
    fn a_crowded_body_overflows() {
        let mut colors = ContactColors::default();
        for other in 0..DYNAMIC_COLOR_COUNT as u32 {
            let color = colors.add(dynamic(0), dynamic(100 + other));
            assert_eq!(color as u32, other);
        }
        assert_eq!(colors.add(dynamic(0), dynamic(500)), OVERFLOW);
        // Static contacts of the same body still find the colours kept for them.
        assert_eq!(colors.add(dynamic(0), fixed(7)), (COLOR_COUNT - 1) as u8);
    }
}
