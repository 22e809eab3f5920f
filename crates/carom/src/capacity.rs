//! How many bodies, colliders, contacts and joints a world makes room for, and the helper that
//! makes room in a buffer without aborting when the heap runs out.

use std::collections::TryReserveError;

/// How many of each part a world makes room for ([`World::reserve`]), or the most it has
/// held at once ([`World::high_water`]).
///
/// A step takes memory from the heap only to grow a buffer past the largest it has held;
/// room reserved for as many bodies, colliders, contacts and joints as a world will hold lets
/// every step of it run without. A game that must not allocate while it plays (a console
/// title, a server with a frame budget) runs its level once, reads [`World::high_water`],
/// and reserves that when it loads the level.
///
/// [`World::reserve`]: crate::World::reserve
/// [`World::high_water`]: crate::World::high_water
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Capacity {
    /// Bodies of every kind.
    pub bodies: usize,
    /// Colliders, sensors included.
    pub colliders: usize,
    /// Contacts: pairs of colliders whose enlarged boxes overlap, touching or not.
    pub contacts: usize,
    /// Joints.
    pub joints: usize,
}

impl Capacity {
    /// The larger of each count.
    pub fn max(self, other: Capacity) -> Capacity {
        Capacity {
            bodies: self.bodies.max(other.bodies),
            colliders: self.colliders.max(other.colliders),
            contacts: self.contacts.max(other.contacts),
            joints: self.joints.max(other.joints),
        }
    }
}

/// Makes room in `buffer` for `count` items in all.
pub(crate) fn room<T>(buffer: &mut Vec<T>, count: usize) -> Result<(), TryReserveError> {
    buffer.try_reserve(count.saturating_sub(buffer.len()))
}
