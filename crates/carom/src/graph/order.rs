//! The solve order of one step's contact constraints: the colours of the persistent graph
//! colouring (see `graph::colors`), each a range of constraints no two of which share a
//! body the solver moves, so a colour's constraints can be solved in any order, several at a
//! time in SIMD lanes (or on several threads) with the same result as one by one.

use crate::constants::COLOR_COUNT;
use crate::graph::layout::ColorRanges;
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
    pub(crate) fn lay_out(&mut self, counts: [usize; COLOR_COUNT], overflow: usize) {
        let mut end = 0;
        for (color, count) in counts.into_iter().enumerate() {
            end += count;
            self.ends[color] = end;
        }
        self.overflow.clear();
        self.overflow.extend(end..end + overflow);
    }

    /// No colours: every constraint is solved one by one, in order.
    pub(crate) fn leave_uncolored(&mut self, constraint_count: usize) {
        self.ends = [0; COLOR_COUNT];
        self.overflow.clear();
        self.overflow.extend(0..constraint_count);
    }

    /// Each colour's constraints, in colour order (some may be empty).
    pub(crate) fn colors(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        (0..COLOR_COUNT).map(|color| self.color(color))
    }

    /// One colour's constraints.
    pub(crate) fn color(&self, color: usize) -> Range<usize> {
        let start = if color == 0 { 0 } else { self.ends[color - 1] };
        start..self.ends[color]
    }
}

/// The colouring's promise, checked: no two contacts of a colour share a body the solver
/// moves (a dynamic body of the awake set). The solver's SIMD passes write bodies in place on
/// several threads on the strength of it.
pub(crate) struct ColorCheck<'a, M> {
    /// Whether the awake body at each position in the awake set moves (is dynamic).
    pub moves: M,
    /// Where the awake bodies are among all bodies.
    pub awake: Range<usize>,
    /// Where each awake contact's bodies are among all bodies.
    pub body_indices: &'a [[u32; 2]],
    /// The colour (plus one) that last claimed each awake body.
    pub claims: &'a mut Vec<u8>,
}

impl<M: Fn(usize) -> bool> ColorCheck<'_, M> {
    /// Claims contact `contact`'s moving bodies for colour `color`; false (claiming nothing)
    /// if the colour holds one already.
    fn claim(&mut self, contact: usize, color: usize) -> bool {
        let [a, b] = self.body_indices[contact].map(|i| i as usize);
        let mark = color as u8 + 1;
        let moving = |index: usize| {
            let i = index.checked_sub(self.awake.start)?;
            (self.awake.contains(&index) && (self.moves)(i)).then_some(i)
        };
        let (a, b) = (moving(a), moving(b));
        if [a, b].iter().flatten().any(|&i| self.claims[i] == mark) {
            return false;
        }
        for i in [a, b].into_iter().flatten() {
            self.claims[i] = mark;
        }
        true
    }
}

/// The order the touching contacts are solved in, into `order`: colour by colour, then the
/// overflow (`colors` are where each colour's contacts are among the awake contacts), laid out in
/// `graph`, and a contact whose colour already holds one of its moving bodies (which the
/// colouring never allows) is solved in the overflow. Without `check`, every touching contact
/// is solved one by one, oldest first by `serial` (the order sequential impulses were tuned in: a stack
/// built from the bottom is solved from the bottom).
pub(crate) fn order_constraints<M: Fn(usize) -> bool>(
    serial: impl Fn(usize) -> u64,
    colors: &ColorRanges,
    check: Option<ColorCheck<M>>,
    order: &mut Vec<usize>,
    graph: &mut ContactGraph,
    demoted: &mut Vec<usize>,
) {
    order.clear();
    let Some(mut check) = check else {
        order.extend(colors.iter().flat_map(Range::clone));
        order.sort_unstable_by_key(|&i| serial(i));
        graph.leave_uncolored(order.len());
        return;
    };
    check.claims.clear();
    check.claims.resize(check.awake.len(), 0);
    demoted.clear();
    let (ranges, overflow) = colors.split_at(COLOR_COUNT);
    let mut counts = [0; COLOR_COUNT];
    for (color, (count, range)) in counts.iter_mut().zip(ranges).enumerate() {
        let before = order.len();
        for i in range.clone() {
            if check.claim(i, color) {
                order.push(i);
            } else {
                demoted.push(i);
            }
        }
        *count = order.len() - before;
    }
    order.extend(overflow[0].clone());
    order.extend_from_slice(demoted);
    graph.lay_out(counts, overflow[0].len() + demoted.len());
}
