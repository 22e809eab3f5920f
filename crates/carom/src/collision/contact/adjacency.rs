//! Each body's contacts, as a list linked through the contacts' slots: walking a body's
//! contacts hashes nothing, a removal visits the body's own contacts only, and the lists keep
//! the order a vector with swap removal would, which the islands (and so every result) depend
//! on.

use super::ContactSet;
use crate::dynamics::body::BodyHandle;

/// One of a body's contacts: its id, and which of the contact's bodies the body is (the low
/// bit: 0 for the first).
pub(super) type Edge = u32;

/// No edge: the end of a list.
pub(super) const NO_EDGE: Edge = u32::MAX;

/// The first and last of a body's edges ([`NO_EDGE`] when it has none).
#[derive(Debug, Clone, Copy)]
pub(super) struct EdgeList {
    pub(super) first: Edge,
    pub(super) last: Edge,
}

impl EdgeList {
    pub(super) const EMPTY: EdgeList = EdgeList {
        first: NO_EDGE,
        last: NO_EDGE,
    };
}

pub(super) fn edge(id: u32, side: usize) -> Edge {
    id << 1 | side as u32
}

pub(super) fn edge_id(edge: Edge) -> u32 {
    edge >> 1
}

pub(super) fn edge_side(edge: Edge) -> usize {
    (edge & 1) as usize
}

impl ContactSet {
    /// The links of `edge`: the edges before and after it in its body's list.
    #[inline]
    pub(super) fn links(&mut self, edge: Edge) -> &mut [Edge; 2] {
        &mut self.slots[edge_id(edge) as usize].links[edge_side(edge)]
    }

    /// The edge after `edge` in its body's list.
    #[inline]
    pub(super) fn next(&self, edge: Edge) -> Edge {
        self.slots[edge_id(edge) as usize].links[edge_side(edge)][1]
    }

    /// The first of the edges of the body of slot index `body`.
    pub(super) fn first_edge(&self, body: usize) -> Edge {
        self.edges.get(body).map_or(NO_EDGE, |list| list.first)
    }

    /// Appends `edge` to the list of the body of slot index `body`.
    pub(super) fn append(&mut self, body: usize, edge: Edge) {
        if self.edges.len() <= body {
            self.edges.resize(body + 1, EdgeList::EMPTY);
        }
        let last = self.edges[body].last;
        *self.links(edge) = [last, NO_EDGE];
        if last == NO_EDGE {
            self.edges[body].first = edge;
        } else {
            self.links(last)[1] = edge;
        }
        self.edges[body].last = edge;
    }

    /// Takes `edge` out of the list of the body of slot index `body`, the last edge taking
    /// its place, as a vector's swap removal would leave it.
    pub(super) fn unlink(&mut self, body: usize, edge: Edge) {
        let last = self.edges[body].last;
        let before_last = self.links(last)[0];
        if before_last == NO_EDGE {
            self.edges[body].first = NO_EDGE;
        } else {
            self.links(before_last)[1] = NO_EDGE;
        }
        self.edges[body].last = before_last;
        if last == edge {
            return;
        }
        let [before, after] = *self.links(edge);
        *self.links(last) = [before, after];
        if before == NO_EDGE {
            self.edges[body].first = last;
        } else {
            self.links(before)[1] = last;
        }
        if after == NO_EDGE {
            self.edges[body].last = last;
        } else {
            self.links(after)[0] = last;
        }
    }

    /// Calls `visit(self, index)` for each contact of `body`, at its index now. The visit may
    /// move contacts between parts (their edges stay as they are): the next edge is read
    /// before it.
    pub(super) fn for_each_of(
        &mut self,
        body: BodyHandle,
        mut visit: impl FnMut(&mut Self, usize),
    ) {
        let mut edge = self.first_edge(body.index() as usize);
        while edge != NO_EDGE {
            let index = self.index_of(edge_id(edge));
            edge = self.next(edge);
            visit(self, index);
        }
    }

    /// The other body of every touching contact of `body`.
    pub(crate) fn touching_partners(&self, body: BodyHandle, into: &mut Vec<BodyHandle>) {
        into.clear();
        let mut edge = self.first_edge(body.index() as usize);
        while edge != NO_EDGE {
            let slot = &self.slots[edge_id(edge) as usize];
            let side = edge_side(edge);
            edge = slot.links[side][1];
            if slot.touching {
                into.push(slot.bodies[1 - side]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::contact::{NO_ID, Slot};

    /// Contacts between random bodies made and destroyed at random: each body's linked list
    /// holds its edges in the order a vector with swap removal would, the order partners are
    /// walked in, which the islands (and so every result) depend on.
    #[test]
    fn edge_lists_keep_the_order_of_swap_removal() {
        const BODIES: usize = 5;
        let mut set = ContactSet::default();
        let mut model: Vec<Vec<Edge>> = vec![Vec::new(); BODIES];
        let mut live: Vec<(u32, [usize; 2])> = Vec::new();
        let mut seed: u32 = 99;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as usize
        };
        for id in 0..500u32 {
            set.slots.push(Slot {
                index: id,
                ..Slot::unused(NO_ID)
            });
            let a = next() % BODIES;
            let bodies = [a, (a + 1 + next() % (BODIES - 1)) % BODIES];
            for (side, body) in bodies.into_iter().enumerate() {
                set.append(body, edge(id, side));
                model[body].push(edge(id, side));
            }
            live.push((id, bodies));
            while next() % 5 < 2 && !live.is_empty() {
                let (gone, bodies) = live.swap_remove(next() % live.len());
                for (side, body) in bodies.into_iter().enumerate() {
                    set.unlink(body, edge(gone, side));
                    let at = model[body].iter().position(|&e| e == edge(gone, side));
                    model[body].swap_remove(at.unwrap());
                }
            }
            for (body, expected) in model.iter().enumerate() {
                let mut walked = Vec::new();
                let mut edge = set.first_edge(body);
                while edge != NO_EDGE {
                    walked.push(edge);
                    edge = set.next(edge);
                }
                assert_eq!(&walked, expected, "body {body} after contact {id}");
                assert_eq!(set.edges[body].last, *expected.last().unwrap_or(&NO_EDGE));
            }
        }
        assert!(live.len() > 20, "{} contacts live at the end", live.len());
    }
}
