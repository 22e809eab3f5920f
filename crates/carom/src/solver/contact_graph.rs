//! The solve order of one step's contact constraints: the colours of the persistent graph
//! colouring (see `collision::coloring`), each a range of constraints no two of which share a
//! body the solver moves, so a colour's constraints can be solved in any order, several at a
//! time in SIMD lanes (or on several threads) with the same result as one by one.

use crate::constants::COLOR_COUNT;
use std::ops::Range;

/// The constraints (indices into the solver's array) of each colour, and those that found no
/// colour free, solved one by one after the colours. The constraints are laid out colour by
/// colour, so a colour is a range of them.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactGraph {
    /// Where each colour's constraints end (colour `c` starts where `c - 1` ends).
    ends: [usize; COLOR_COUNT],
    pub overflow: Vec<usize>,
}

impl ContactGraph {
    /// The constraints are the colours' contacts in colour order, `counts[c]` of colour `c`,
    /// then `overflow` more for the overflow.
    pub fn lay_out(&mut self, counts: [usize; COLOR_COUNT], overflow: usize) {
        let mut end = 0;
        for (color, count) in counts.into_iter().enumerate() {
            end += count;
            self.ends[color] = end;
        }
        self.overflow.clear();
        self.overflow.extend(end..end + overflow);
    }

    /// No colours: every constraint is solved one by one, in order.
    pub fn leave_uncolored(&mut self, constraint_count: usize) {
        self.ends = [0; COLOR_COUNT];
        self.overflow.clear();
        self.overflow.extend(0..constraint_count);
    }

    /// Each colour's constraints, in colour order (some may be empty).
    pub fn colors(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        (0..COLOR_COUNT).map(|color| self.color(color))
    }

    /// One colour's constraints.
    pub fn color(&self, color: usize) -> Range<usize> {
        let start = if color == 0 { 0 } else { self.ends[color - 1] };
        start..self.ends[color]
    }
}
