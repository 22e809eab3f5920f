//! Graph colouring of the contact constraints: within one colour no two constraints share a
//! body the solver moves, so a colour's constraints can be solved in any order, four at a time
//! in SIMD lanes (or on several threads) with the same result as one by one.

use super::ContactConstraint;
use crate::constants::COLOR_COUNT;

/// The constraints (indices into the solver's array) of each colour, and those that found no
/// colour free, solved one by one after the colours.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactGraph {
    /// Per colour, its constraints; some colours may be empty.
    pub colors: Vec<Vec<usize>>,
    pub overflow: Vec<usize>,
    /// Per body, the colours it is in (kept to reuse the memory).
    used: Vec<u32>,
}

impl ContactGraph {
    /// Colours `constraints` greedily in order: each takes the first colour that neither of its
    /// moving bodies has yet. Static and kinematic bodies (no inverse mass, never changed by an
    /// impulse) may appear in any number of constraints of a colour. `body_count` bounds the
    /// constraints' dense body indices.
    /// The graph's memory is reused from step to step.
    pub fn build(&mut self, constraints: &[ContactConstraint], body_count: usize) {
        let used = &mut self.used;
        used.clear();
        used.resize(body_count, 0);
        self.colors.resize_with(COLOR_COUNT, Vec::new);
        self.colors.iter_mut().for_each(Vec::clear);
        self.overflow.clear();
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
                continue;
            }
            if moves_a {
                used[c.a] |= 1 << free;
            }
            if moves_b {
                used[c.b] |= 1 << free;
            }
            self.colors[free].push(index);
        }
    }

    /// No colours: every constraint is solved one by one, in order.
    pub fn leave_uncolored(&mut self, constraint_count: usize) {
        self.colors.iter_mut().for_each(Vec::clear);
        self.overflow.clear();
        self.overflow.extend(0..constraint_count);
    }
}
