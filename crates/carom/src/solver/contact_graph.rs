//! Graph colouring of the contact constraints: within one colour no two constraints share a
//! body the solver moves, so a colour's constraints can be solved in any order, four at a time
//! in SIMD lanes (or on several threads) with the same result as one by one.

use super::ContactConstraint;
use crate::constants::COLOR_COUNT;

/// The constraints (indices into the solver's array) of each colour, and those that found no
/// colour free, solved one by one after the colours. All in flat arrays that keep their
/// memory, so a step that uses a colour for the first time allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactGraph {
    /// Every coloured constraint, colour after colour.
    members: Vec<usize>,
    /// Where each colour's constraints end in `members` (colour `c` starts where `c - 1` ends).
    ends: [usize; COLOR_COUNT],
    pub overflow: Vec<usize>,
    /// Per constraint, its colour (`NO_COLOR` for the overflow).
    color_of: Vec<u8>,
    /// Per body, the colours it is in (kept to reuse the memory).
    used: Vec<u32>,
}

/// The colour of a constraint left to the overflow.
const NO_COLOR: u8 = u8::MAX;

impl ContactGraph {
    /// Colours `constraints` greedily in order: each takes the first colour that neither of its
    /// moving bodies has yet. Static and kinematic bodies (no inverse mass, never changed by an
    /// impulse) may appear in any number of constraints of a colour. `body_count` bounds the
    /// constraints' body indices.
    /// The graph's memory is reused from step to step.
    pub fn build(&mut self, constraints: &[ContactConstraint], body_count: usize) {
        let used = &mut self.used;
        used.clear();
        used.resize(body_count, 0);
        self.color_of.clear();
        self.overflow.clear();
        let mut counts = [0usize; COLOR_COUNT];
        for (index, c) in constraints.iter().enumerate() {
            let (moves_a, moves_b) = (c.dynamic_a, c.dynamic_b);
            let mut taken =
                if moves_a { used[c.a] } else { 0 } | if moves_b { used[c.b] } else { 0 };
            if !(moves_a && moves_b) {
                // As Box2D: no contact with a static body in colour 0, so the first colour
                // solved is all dynamic pairs and the ground's contacts come after.
                taken |= 1;
            }
            let free = (!taken).trailing_zeros() as usize;
            if free >= COLOR_COUNT {
                self.overflow.push(index);
                self.color_of.push(NO_COLOR);
                continue;
            }
            if moves_a {
                used[c.a] |= 1 << free;
            }
            if moves_b {
                used[c.b] |= 1 << free;
            }
            counts[free] += 1;
            self.color_of.push(free as u8);
        }
        // Each colour's place in the flat array, then its members in constraint order.
        let mut next = [0usize; COLOR_COUNT];
        let mut end = 0;
        for color in 0..COLOR_COUNT {
            next[color] = end;
            end += counts[color];
            self.ends[color] = end;
        }
        self.members.clear();
        self.members.resize(end, 0);
        for (index, &color) in self.color_of.iter().enumerate() {
            if color != NO_COLOR {
                self.members[next[color as usize]] = index;
                next[color as usize] += 1;
            }
        }
    }

    /// No colours: every constraint is solved one by one, in order.
    pub fn leave_uncolored(&mut self, constraint_count: usize) {
        self.members.clear();
        self.ends = [0; COLOR_COUNT];
        self.overflow.clear();
        self.overflow.extend(0..constraint_count);
    }

    /// Each colour's constraints, in colour order (some may be empty).
    pub fn colors(&self) -> impl Iterator<Item = &[usize]> {
        (0..COLOR_COUNT).map(|color| self.color(color))
    }

    /// One colour's constraints.
    pub fn color(&self, color: usize) -> &[usize] {
        let start = if color == 0 { 0 } else { self.ends[color - 1] };
        &self.members[start..self.ends[color]]
    }
}
