//! Solver sets, as in Box2D v3: bodies are stored by what the step does with them, so the step
//! walks only what moves.
//!
//! Bodies live in one dense array in three contiguous sets: static bodies first, then the
//! awake set (dynamic and kinematic bodies the step moves), then the sleeping bodies. A
//! body's colliders are stored in the same three sets in the colliders' array, and contacts in
//! two: awake (a body of the pair is awake, kept colour by colour, see
//! `graph::layout`) and asleep. Joints are stored in three sets as Box2D keeps them: static
//! (no dynamic body: nothing to solve), awake (a dynamic body is awake) and asleep (their
//! island sleeps; a kinematic or static partner does not keep a joint awake). Each stage of a
//! step takes the awake set as one slice; a static or sleeping body, or a joint that is not
//! awake, is never visited.
//!
//! Falling asleep moves an island's bodies (and their colliders, contacts and joints) out of
//! the awake set; waking moves them back (see `world::islands`). Each move is a swap at a set
//! boundary, so it costs the island's own bodies, contacts and joints, whatever the size of
//! the world. The awake joints are solved in storage order: the order they were added while no
//! island sleeps, and otherwise shuffled by the swaps (the same way on every run). The joints'
//! array keeps its awake set first, before the static one, so that joints never solved do not
//! shuffle it either.

#[cfg(feature = "serde")]
use crate::error::CaromError;
use crate::partition::Partition;
use std::ops::Range;

/// Which set an item is stored in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum SolverSet {
    /// Static bodies and their colliders: never visited by a step.
    Static = 0,
    /// What the step moves, and the contacts it solves.
    Awake = 1,
    /// Sleeping islands: never visited until woken.
    Asleep = 2,
}

/// Where the sets of one dense array begin and end: static, then awake, then asleep.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct SetBounds(Partition<2>);

impl SetBounds {
    /// The set of the item at `index`.
    #[inline]
    pub(crate) fn set_of(&self, index: usize) -> SolverSet {
        match self.0.part_of(index) {
            0 => SolverSet::Static,
            1 => SolverSet::Awake,
            _ => SolverSet::Asleep,
        }
    }

    /// The dense indices of the awake set.
    #[inline]
    pub(crate) fn awake(&self) -> Range<usize> {
        self.0.range(SolverSet::Awake as usize)
    }

    /// Where the sleeping set begins (everything past it sleeps).
    #[inline]
    pub(crate) fn asleep_start(&self) -> usize {
        self.0.start(SolverSet::Asleep as usize)
    }

    /// Moves the item at `index` into set `to` by swapping it across each boundary on the way
    /// (`swap(i, j)` swaps two items of the array); returns its new index.
    pub(crate) fn move_item(
        &mut self,
        index: usize,
        to: SolverSet,
        swap: impl FnMut(usize, usize),
    ) -> usize {
        self.0.move_item(index, to as usize, swap)
    }
}

/// Where the joint sets of the joints' dense array begin and end: awake, then static, then
/// asleep. Unlike bodies', the static set follows the awake one, so a joint that is never
/// solved, added or moved there, leaves the order of the solved ones alone.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointSetBounds(Partition<2>);

impl JointSetBounds {
    /// The part of the array each set is kept in.
    fn part(set: SolverSet) -> usize {
        match set {
            SolverSet::Awake => 0,
            SolverSet::Static => 1,
            SolverSet::Asleep => 2,
        }
    }

    /// The set of the joint at `index`.
    #[cfg(any(test, feature = "serde"))]
    pub(crate) fn set_of(&self, index: usize) -> SolverSet {
        match self.0.part_of(index) {
            0 => SolverSet::Awake,
            1 => SolverSet::Static,
            _ => SolverSet::Asleep,
        }
    }

    /// The dense indices of the awake set.
    #[inline]
    pub(crate) fn awake(&self) -> Range<usize> {
        self.0.range(Self::part(SolverSet::Awake))
    }

    /// Moves the joint at `index` into set `to` by swapping it across each boundary on the
    /// way (`swap(i, j)` swaps two joints of the array); returns its new index.
    pub(crate) fn move_item(
        &mut self,
        index: usize,
        to: SolverSet,
        swap: impl FnMut(usize, usize),
    ) -> usize {
        self.0.move_item(index, Self::part(to), swap)
    }

    /// Checks bounds read from a saved world against the joints they divide.
    #[cfg(feature = "serde")]
    pub(crate) fn check_saved(&self, len: usize) -> Result<(), CaromError> {
        if self.0.start(Self::part(SolverSet::Asleep)) > len {
            return Err(CaromError::bad_save(format!(
                "the joint sets reach past the {len} joints"
            )));
        }
        Ok(())
    }
}

#[cfg(feature = "serde")]
impl SetBounds {
    /// Checks bounds read from a saved world against the array they divide.
    pub(crate) fn check_saved(&self, what: &str, len: usize) -> Result<(), CaromError> {
        if self.asleep_start() > len {
            return Err(CaromError::bad_save(format!(
                "the {what} sets reach past the {len} {what}s"
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Items labelled by their set, moved around at random: the sets stay contiguous, each
    /// item lands in the set asked for, and nothing is lost.
    #[test]
    fn moves_keep_the_sets_contiguous() {
        let mut items: Vec<(u32, SolverSet)> = Vec::new();
        let mut bounds = SetBounds::default();
        let sets = [SolverSet::Static, SolverSet::Awake, SolverSet::Asleep];
        let mut seed: u32 = 12345;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            seed >> 8
        };
        for label in 0..200 {
            // New items arrive at the end (asleep), then go where they belong.
            let to = sets[next() as usize % 3];
            items.push((label, SolverSet::Asleep));
            let at = bounds.move_item(items.len() - 1, to, |i, j| items.swap(i, j));
            items[at].1 = to;
            // And some item changes set.
            let pick = next() as usize % items.len();
            let to = sets[next() as usize % 3];
            let at = bounds.move_item(pick, to, |i, j| items.swap(i, j));
            items[at].1 = to;
            for (i, &(_, set)) in items.iter().enumerate() {
                assert_eq!(bounds.set_of(i), set, "item {i} after {label} inserts");
            }
        }
        let mut labels: Vec<u32> = items.iter().map(|&(l, _)| l).collect();
        labels.sort_unstable();
        assert_eq!(labels, (0..200).collect::<Vec<_>>());
    }
}
