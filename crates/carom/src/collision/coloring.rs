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

use crate::constants::{COLOR_COUNT, DYNAMIC_COLOR_COUNT};

/// The colour of a contact that has none (not touching, or asleep).
pub(crate) const NO_COLOR: u8 = u8::MAX;

/// The colour of the overflow: contacts solved one by one.
pub(crate) const OVERFLOW: u8 = COLOR_COUNT as u8;

/// One bit per body slot.
#[derive(Debug, Clone, Default)]
struct BodyBits(Vec<u64>);

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

/// The colours and their contacts.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactColors {
    /// Per colour, the dynamic bodies it holds.
    bodies: [BodyBits; COLOR_COUNT],
    /// Per colour, then the overflow, its contacts (indices into the contact array).
    members: [Vec<u32>; COLOR_COUNT + 1],
}

impl ContactColors {
    /// Gives contact `index`, between `a` and `b`, a colour; returns the colour and the
    /// contact's place in it.
    pub fn add(&mut self, index: u32, a: ColorBody, b: ColorBody) -> (u8, u32) {
        let color = self.pick(a, b);
        if color != OVERFLOW {
            for body in [a, b].iter().filter(|body| body.dynamic) {
                self.bodies[color as usize].set(body.slot);
            }
        }
        let members = &mut self.members[color as usize];
        members.push(index);
        (color, (members.len() - 1) as u32)
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

    /// Takes a contact out of its colour (`color`, at `place`), freeing its bodies there.
    /// Returns the contact that moved into its place, if one did (its place is now `place`).
    pub fn remove(&mut self, color: u8, place: u32, a: ColorBody, b: ColorBody) -> Option<u32> {
        if color != OVERFLOW {
            for body in [a, b].iter().filter(|body| body.dynamic) {
                self.bodies[color as usize].clear(body.slot);
            }
        }
        let members = &mut self.members[color as usize];
        members.swap_remove(place as usize);
        members.get(place as usize).copied()
    }

    /// Records that the contact at `place` in `color` now sits at `index` in the contact array.
    pub fn relocate(&mut self, color: u8, place: u32, index: u32) {
        self.members[color as usize][place as usize] = index;
    }

    /// Each colour's contacts, in colour order, then the overflow's.
    pub fn lists(&self) -> &[Vec<u32>; COLOR_COUNT + 1] {
        &self.members
    }

    /// True when `slot`'s bit is set in `color`, for tests of the colouring.
    #[cfg(test)]
    pub fn holds(&self, color: u8, slot: u32) -> bool {
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
        assert_eq!(colors.add(0, dynamic(1), dynamic(2)), (0, 0));
        assert_eq!(colors.add(1, dynamic(2), dynamic(3)), (1, 0));
        assert_eq!(colors.add(2, dynamic(3), dynamic(4)), (0, 1));
        let top = (COLOR_COUNT - 1) as u8;
        assert_eq!(colors.add(3, fixed(0), dynamic(1)), (top, 0));
        assert_eq!(colors.add(4, dynamic(2), fixed(0)), (top, 1));
        assert_eq!(colors.add(5, fixed(0), dynamic(1)), (top - 1, 0));
        // The ground is not held by any colour.
        assert!(!colors.holds(top, 0));
        // Contact 0 leaves colour 0; contact 2 moves into its place.
        assert_eq!(colors.remove(0, 0, dynamic(1), dynamic(2)), Some(2));
        assert_eq!(colors.lists()[0], vec![2]);
        assert!(!colors.holds(0, 1) && colors.holds(0, 3));
        assert_eq!(colors.add(6, dynamic(1), dynamic(2)), (0, 1));
    }

    /// A body in more contacts than there are colours sends the rest to the overflow.
    #[test]
    fn a_crowded_body_overflows() {
        let mut colors = ContactColors::default();
        for other in 0..DYNAMIC_COLOR_COUNT as u32 {
            let (color, _) = colors.add(other, dynamic(0), dynamic(100 + other));
            assert_eq!(color as u32, other);
        }
        assert_eq!(colors.add(99, dynamic(0), dynamic(500)).0, OVERFLOW);
        // Static contacts of the same body still find the colours kept for them.
        assert_eq!(
            colors.add(98, dynamic(0), fixed(7)).0,
            (COLOR_COUNT - 1) as u8
        );
    }
}
