//! The pairs of overlapping leaves of which at least one moved, found by walking the tree
//! against itself (and against a second tree) rather than by one query from the root for each
//! leaf that moved. Neighbouring leaves share the walk down to their common ancestor, so in a
//! step where most leaves move the walk tests a few pairs of nodes per leaf, where a query per
//! leaf tests every node on the way down to it and around it. The leaves that moved are marked
//! first, with their ancestors ([`DynamicTree::mark_moved`]), and the walk passes by every
//! subtree that holds none of them.

use super::{DynamicTree, NULL, WalkStack};

/// A piece of the walk. The whole walk is `Within(root)` and, for the second tree,
/// `Against(root, its root)`; [`DynamicTree::split_walk`] cuts it into more pieces so threads
/// can share it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Walk {
    /// Pairs of leaves both under this node.
    Within(u32),
    /// Pairs of a leaf under the first node and a leaf under the second, in this tree.
    Between(u32, u32),
    /// Pairs of a leaf under a node of this tree and a leaf under a node of the second tree.
    Against(u32, u32),
}

impl DynamicTree {
    /// Marks `leaf` and its ancestors for the pair walk.
    pub(crate) fn mark_moved(&mut self, leaf: u32) {
        let mut index = leaf;
        while index != NULL && !self.nodes[index as usize].moved {
            self.nodes[index as usize].moved = true;
            index = self.nodes[index as usize].parent;
        }
    }

    /// Takes back [`DynamicTree::mark_moved`]: once every marked leaf is unmarked, no node is.
    /// Each walk up stops at the first node already unmarked, whose ancestors an earlier walk
    /// unmarked.
    pub(crate) fn unmark_moved(&mut self, leaf: u32) {
        let mut index = leaf;
        while index != NULL && self.nodes[index as usize].moved {
            self.nodes[index as usize].moved = false;
            index = self.nodes[index as usize].parent;
        }
    }

    /// The whole walk for pairs of overlapping leaves with at least one marked leaf, in this
    /// tree and between this tree's marked leaves and `other`'s leaves, cut into at least
    /// `pieces` pieces where the trees allow, into `out`. Which pieces does not change which
    /// pairs the walk meets.
    pub(crate) fn split_walk(&self, other: &DynamicTree, pieces: usize, out: &mut Vec<Walk>) {
        out.clear();
        if self.root == NULL || !self.nodes[self.root as usize].moved {
            return;
        }
        out.push(Walk::Within(self.root));
        if other.root != NULL
            && self.nodes[self.root as usize]
                .aabb
                .overlaps(&other.nodes[other.root as usize].aabb)
        {
            out.push(Walk::Against(self.root, other.root));
        }
        // Breadth first, so the pieces are of like size: each pass cuts every piece once.
        let mut cut = true;
        while cut && out.len() < pieces {
            cut = false;
            let (mut i, mut end) = (0, out.len());
            while i < end && out.len() < pieces {
                let piece = out[i];
                if self.leaf_pair(other, piece).is_some() {
                    i += 1;
                    continue;
                }
                let mark = out.len();
                self.split(other, piece, |more| out.push(more));
                if out.len() > mark {
                    // The first smaller piece takes this one's place.
                    out[i] = out.swap_remove(mark);
                    cut = true;
                    i += 1;
                } else {
                    // No pair under it: gone, and the last piece takes its place.
                    out.swap_remove(i);
                    end = end.min(out.len());
                }
            }
        }
    }

    /// Calls `visit(leaf, other_leaf)` for each pair of overlapping leaves in `piece` (one
    /// that [`DynamicTree::split_walk`] made): `other_leaf` is a leaf of `other` for a piece
    /// [`Walk::Against`], else of this tree.
    pub(crate) fn walk(&self, other: &DynamicTree, piece: Walk, mut visit: impl FnMut(u32, u32)) {
        let mut stack = WalkStack::<Walk, 256>::new(Walk::Within(NULL));
        stack.push(piece);
        while let Some(piece) = stack.pop() {
            match self.leaf_pair(other, piece) {
                Some((a, b)) => visit(a, b),
                None => self.split(other, piece, |more| stack.push(more)),
            }
        }
    }

    /// The two leaves `piece` is, if it is a pair of leaves.
    #[inline]
    fn leaf_pair(&self, other: &DynamicTree, piece: Walk) -> Option<(u32, u32)> {
        let (a, b, b_nodes) = match piece {
            Walk::Within(_) => return None,
            Walk::Between(a, b) => (a, b, &self.nodes),
            Walk::Against(a, b) => (a, b, &other.nodes),
        };
        (self.nodes[a as usize].is_leaf() && b_nodes[b as usize].is_leaf()).then_some((a, b))
    }

    /// Passes to `push` the smaller pieces of `piece` (not a pair of leaves) that may hold
    /// a pair: those with a marked node whose boxes overlap. Each piece is checked before it
    /// is pushed, so a piece that leads nowhere costs no push and pop.
    #[inline]
    fn split(&self, other: &DynamicTree, piece: Walk, mut push: impl FnMut(Walk)) {
        let nodes = &self.nodes;
        match piece {
            Walk::Within(id) => {
                let node = &nodes[id as usize];
                if node.is_leaf() {
                    return;
                }
                let (c1, c2) = (node.child1, node.child2);
                let (n1, n2) = (&nodes[c1 as usize], &nodes[c2 as usize]);
                if n1.moved {
                    push(Walk::Within(c1));
                }
                if n2.moved {
                    push(Walk::Within(c2));
                }
                if (n1.moved || n2.moved) && n1.aabb.overlaps(&n2.aabb) {
                    push(Walk::Between(c1, c2));
                }
            }
            Walk::Between(a, b) => {
                let (na, nb) = (&nodes[a as usize], &nodes[b as usize]);
                if goes_down_first(na, nb) {
                    for c in [na.child1, na.child2] {
                        let nc = &nodes[c as usize];
                        if (nc.moved || nb.moved) && nc.aabb.overlaps(&nb.aabb) {
                            push(Walk::Between(c, b));
                        }
                    }
                } else {
                    for c in [nb.child1, nb.child2] {
                        let nc = &nodes[c as usize];
                        if (na.moved || nc.moved) && na.aabb.overlaps(&nc.aabb) {
                            push(Walk::Between(a, c));
                        }
                    }
                }
            }
            Walk::Against(a, b) => {
                let (na, nb) = (&nodes[a as usize], &other.nodes[b as usize]);
                if goes_down_first(na, nb) {
                    for c in [na.child1, na.child2] {
                        let nc = &nodes[c as usize];
                        if nc.moved && nc.aabb.overlaps(&nb.aabb) {
                            push(Walk::Against(c, b));
                        }
                    }
                } else {
                    for c in [nb.child1, nb.child2] {
                        if na.aabb.overlaps(&other.nodes[c as usize].aabb) {
                            push(Walk::Against(a, c));
                        }
                    }
                }
            }
        }
    }
}

/// Whether to go down from the first of two nodes (not both leaves): the inner one, or of two
/// inner nodes the larger, so the two sides of a piece stay of like size.
#[inline]
fn goes_down_first(a: &super::TreeNode, b: &super::TreeNode) -> bool {
    match (a.is_leaf(), b.is_leaf()) {
        (false, true) => true,
        (true, false) => false,
        _ => a.aabb.perimeter() >= b.aabb.perimeter(),
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{Lcg, random_box};
    use super::*;
    use crate::geometry::aabb::Aabb;
    use crate::math::Real;

    /// A tree of `count` random leaves (payloads 0 to count - 1), some enlarged in place and
    /// not rebuilt, as the pair walk meets it in a step.
    fn random_tree(rng: &mut Lcg, count: u32, extent: Real) -> (DynamicTree, Vec<(u32, Aabb)>) {
        let mut tree = DynamicTree::default();
        let mut leaves: Vec<(u32, Aabb)> = (0..count)
            .map(|payload| {
                let aabb = random_box(rng, extent);
                (tree.create_proxy(aabb, payload), aabb)
            })
            .collect();
        for (leaf, aabb) in leaves.iter_mut() {
            if rng.next() >= 0.3 {
                continue;
            }
            let step = random_box(rng, 0.0);
            let grown = aabb.union(&Aabb::new(
                step.min + aabb.center(),
                step.max + aabb.center(),
            ));
            tree.enlarge_proxy(*leaf, grown);
            *aabb = grown;
        }
        (tree, leaves)
    }

    type Pairs = Vec<(u32, u32)>;

    /// Every pair of overlapping leaves the walk must meet: within `leaves` with at least one
    /// marked, and of a marked one with one of `others`, as payload pairs, sorted.
    fn brute_force(
        leaves: &[(u32, Aabb)],
        marked: &[bool],
        others: &[(u32, Aabb)],
        tree: &DynamicTree,
        other: &DynamicTree,
    ) -> (Pairs, Pairs) {
        let payload = |t: &DynamicTree, node: u32| t.payload(node);
        let mut within = Vec::new();
        for (i, (a, box_a)) in leaves.iter().enumerate() {
            for (j, (b, box_b)) in leaves.iter().enumerate().skip(i + 1) {
                if (marked[i] || marked[j]) && box_a.overlaps(box_b) {
                    let (p, q) = (payload(tree, *a), payload(tree, *b));
                    within.push((p.min(q), p.max(q)));
                }
            }
        }
        let mut against = Vec::new();
        for (i, (a, box_a)) in leaves.iter().enumerate() {
            for (b, box_b) in others {
                if marked[i] && box_a.overlaps(box_b) {
                    against.push((payload(tree, *a), payload(other, *b)));
                }
            }
        }
        within.sort_unstable();
        against.sort_unstable();
        (within, against)
    }

    #[test]
    fn the_walk_meets_exactly_the_overlapping_pairs_with_a_moved_leaf() {
        let mut rng = Lcg(17);
        let (mut tree, leaves) = random_tree(&mut rng, 600, 15.0);
        let (other, others) = random_tree(&mut rng, 150, 15.0);
        for share in [0.05, 0.3, 1.0] {
            let marked: Vec<bool> = leaves.iter().map(|_| rng.next() < share).collect();
            for (&(leaf, _), _) in leaves.iter().zip(&marked).filter(|(_, m)| **m) {
                tree.mark_moved(leaf);
            }
            let expected = brute_force(&leaves, &marked, &others, &tree, &other);
            assert!(
                expected.0.len() > 5 && expected.1.len() > 5,
                "the test needs pairs"
            );
            // However the walk is cut into pieces, it meets each pair once.
            for wanted in [1, 5, 32, 1000] {
                let mut pieces = Vec::new();
                tree.split_walk(&other, wanted, &mut pieces);
                if share == 1.0 && wanted == 32 {
                    assert!(pieces.len() >= wanted, "{} pieces", pieces.len());
                }
                let (mut within, mut against) = (Vec::new(), Vec::new());
                for piece in &pieces {
                    let is_against = matches!(piece, Walk::Against(..));
                    tree.walk(&other, *piece, |a, b| {
                        if is_against {
                            against.push((tree.payload(a), other.payload(b)));
                        } else {
                            let (p, q) = (tree.payload(a), tree.payload(b));
                            within.push((p.min(q), p.max(q)));
                        }
                    });
                }
                within.sort_unstable();
                against.sort_unstable();
                assert_eq!(
                    (within, against),
                    expected,
                    "share {share}, {wanted} pieces"
                );
            }
            for (&(leaf, _), _) in leaves.iter().zip(&marked).filter(|(_, m)| **m) {
                tree.unmark_moved(leaf);
            }
            // Unmarking leaves no node marked (validate checks every node).
            tree.validate().unwrap();
        }
    }
}
