//! The joint colouring: each step the awake joints are coloured afresh, greedily, so no two
//! joints of a colour share a body that moves, and soft step solves a colour's joints at once.
//! Unlike contacts, joints are not coloured persistently: a world has far fewer joints than
//! contacts, they are created and woken rarely, and colouring them each step costs one pass
//! over the awake joints, while a persistent colouring would have to be kept in step with
//! every joint's and body's move between solver sets.

use crate::capacity::room;
use crate::constants::JOINT_COLOR_COUNT;
use std::collections::TryReserveError;

/// The joint colouring of a step: the order the joints are prepared and solved in, colour by
/// colour, no two of a colour sharing a body that moves (the last range, the overflow's, is
/// solved alone, one by one).
#[derive(Debug, Clone, Default)]
pub(crate) struct JointColors {
    /// Per colour, then the overflow: the range of the order it holds.
    pub ranges: Vec<std::ops::Range<usize>>,
    /// The joints to solve (indices into the step's awake joints), colour by colour.
    pub order: Vec<usize>,
    /// Each awake joint's place in `order` ([`LEFT_OUT`] for one with nothing to solve): where
    /// its constraint is, so its results can be stored joint by joint.
    pub places: Vec<usize>,
    /// Per state, the colours that already hold it (a bit each).
    claims: Vec<u32>,
    /// Each joint's colour, or `u8::MAX` for one with nothing to solve.
    colors: Vec<u8>,
}

/// The place of an awake joint left out of the order (nothing to solve).
pub(crate) const LEFT_OUT: usize = usize::MAX;

/// Which states a joint touches, and whether it moves each (dynamic and awake).
pub(crate) type JointStates = [(usize, bool); 2];

impl JointColors {
    /// Makes room to colour `joints` joints among `states` states.
    pub(crate) fn reserve(&mut self, joints: usize, states: usize) -> Result<(), TryReserveError> {
        room(&mut self.ranges, JOINT_COLOR_COUNT + 1)?;
        room(&mut self.order, joints)?;
        room(&mut self.places, joints)?;
        room(&mut self.claims, states)?;
        room(&mut self.colors, joints)
    }

    /// Colours `count` joints greedily in order, each into the first colour that holds
    /// neither of the states it moves (up to [`JOINT_COLOR_COUNT`], then the overflow), or
    /// all into the overflow unless `colored`; `states(i)` says which states joint `i`
    /// touches (`None`: nothing to solve, left out). `state_count` is how many states there
    /// are. Within a colour the joints keep their order.
    pub(crate) fn order(
        &mut self,
        count: usize,
        states: impl Fn(usize) -> Option<JointStates>,
        colored: bool,
        state_count: usize,
    ) {
        let overflow = JOINT_COLOR_COUNT as u8;
        self.claims.clear();
        if colored {
            self.claims.resize(state_count, 0);
        }
        self.colors.clear();
        let mut counts = [0usize; JOINT_COLOR_COUNT + 1];
        for i in 0..count {
            let Some(touched) = states(i) else {
                self.colors.push(u8::MAX);
                continue;
            };
            let color = if colored {
                let taken = touched
                    .iter()
                    .filter(|(_, moves)| *moves)
                    .fold(0u32, |taken, &(state, _)| taken | self.claims[state]);
                let color = (!taken).trailing_zeros().min(overflow as u32) as u8;
                if color < overflow {
                    for &(state, moves) in &touched {
                        if moves {
                            self.claims[state] |= 1 << color;
                        }
                    }
                }
                color
            } else {
                overflow
            };
            counts[color as usize] += 1;
            self.colors.push(color);
        }
        self.ranges.clear();
        let mut next = [0; JOINT_COLOR_COUNT + 1];
        let mut start = 0;
        for (count, next) in counts.iter().zip(&mut next) {
            self.ranges.push(start..start + count);
            *next = start;
            start += count;
        }
        self.order.clear();
        self.order.resize(start, 0);
        self.places.clear();
        for (i, &color) in self.colors.iter().enumerate() {
            if color == u8::MAX {
                self.places.push(LEFT_OUT);
                continue;
            }
            let slot = &mut next[color as usize];
            self.order[*slot] = i;
            self.places.push(*slot);
            *slot += 1;
        }
    }
}
