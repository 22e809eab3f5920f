//! The tree's rebuild (Box2D's `b2DynamicTree_Rebuild`): the part that leaves enlarged in
//! place is built again, top down, by median splits.

use super::{DynamicTree, NULL};
use crate::capacity::room;
use crate::math::Vec2;
use std::collections::TryReserveError;

/// What [`DynamicTree::rebuild`] works in; its contents mean nothing between rebuilds.
#[derive(Debug, Clone, Default)]
pub(super) struct RebuildScratch {
    /// The subtrees to build over (leaves, and unmarked subtrees under marked nodes)...
    items: Vec<u32>,
    /// ...and the centres of their boxes, in the same order, partitioned with them.
    centers: Vec<Vec2>,
    /// The walk down the marked part; then the new inner nodes in the order they were made.
    nodes: Vec<u32>,
    /// Inner nodes still to split: the node and its range of `items`.
    splits: Vec<(u32, u32, u32)>,
}

impl DynamicTree {
    /// Makes room to hold and rebuild a tree of `proxies` leaves.
    pub(crate) fn reserve(&mut self, proxies: usize) -> Result<(), TryReserveError> {
        // A leaf for each proxy and an inner node for each but one.
        room(&mut self.nodes, proxies.saturating_mul(2))?;
        self.scratch.reserve(proxies)
    }

    /// Builds the marked part of the tree again (Box2D's `b2DynamicTree_Rebuild`): its inner
    /// nodes are freed, and the leaves and unmarked subtrees under them are joined again by a
    /// top-down median split, which leaves no node marked. `full` rebuilds the whole tree.
    /// Allocates nothing once its buffers have grown to the tree's size.
    pub fn rebuild(&mut self, full: bool) {
        // Sized first, nothing marked or not, so that the first step to enlarge anything
        // does not allocate either.
        self.scratch.clear_for(self.proxy_count);
        if self.root == NULL || !(full || self.nodes[self.root as usize].enlarged) {
            return;
        }
        let mut scratch = std::mem::take(&mut self.scratch);
        // Gather the subtrees to keep and free the inner nodes above them.
        let mut index = self.root;
        loop {
            let node = &mut self.nodes[index as usize];
            if node.is_leaf() || !(node.enlarged || full) {
                node.parent = NULL;
                scratch.items.push(index);
                scratch.centers.push(node.aabb.center());
                match scratch.nodes.pop() {
                    Some(next) => index = next,
                    None => break,
                }
            } else {
                let (child1, child2) = (node.child1, node.child2);
                scratch.nodes.push(child2);
                self.free_node(index);
                index = child1;
            }
        }
        self.root = self.build(&mut scratch);
        self.scratch = scratch;
    }

    /// Joins `scratch.items` (detached subtrees) under new inner nodes, splitting each range at
    /// the middle of its centres' extent along the longer axis (Box2D's `b2BuildTree` with
    /// `b2PartitionMid`); returns the root.
    fn build(&mut self, scratch: &mut RebuildScratch) -> u32 {
        let count = scratch.items.len();
        if count == 1 {
            return scratch.items[0];
        }
        let RebuildScratch {
            items,
            centers,
            nodes: made,
            splits,
        } = scratch;
        made.clear();
        splits.clear();
        let root = self.allocate_node();
        made.push(root);
        splits.push((root, 0, count as u32));
        while let Some((parent, start, end)) = splits.pop() {
            let (start, end) = (start as usize, end as usize);
            let split = start + partition_mid(&mut items[start..end], &mut centers[start..end]);
            let mut children = [NULL; 2];
            for (child, (lo, hi)) in children.iter_mut().zip([(start, split), (split, end)]) {
                *child = if hi - lo == 1 {
                    items[lo]
                } else {
                    let inner = self.allocate_node();
                    made.push(inner);
                    splits.push((inner, lo as u32, hi as u32));
                    inner
                };
                self.nodes[*child as usize].parent = parent;
            }
            let node = &mut self.nodes[parent as usize];
            (node.child1, node.child2) = (children[0], children[1]);
        }
        // Every inner node was made before its inner children: backwards, children come first.
        // None of them is marked: the subtrees kept under them are leaves or unmarked.
        for &inner in made.iter().rev() {
            self.refit(inner);
        }
        root
    }
}

impl RebuildScratch {
    /// Makes room to rebuild over `proxies` leaves.
    fn reserve(&mut self, proxies: usize) -> Result<(), TryReserveError> {
        room(&mut self.items, proxies)?;
        room(&mut self.centers, proxies)?;
        room(&mut self.nodes, proxies)?;
        room(&mut self.splits, proxies)
    }

    /// Empties the buffers, sized for a tree of `proxies` leaves: a rebuild gathers at most
    /// one item per leaf and makes fewer inner nodes, so only new leaves, not motion, make
    /// them grow (room for half as many again, as Box2D keeps, so a few new ones do not).
    pub(super) fn clear_for(&mut self, proxies: usize) {
        self.items.clear();
        self.centers.clear();
        self.nodes.clear();
        self.splits.clear();
        if self.items.capacity() < proxies {
            let room = proxies + proxies / 2;
            self.items.reserve(room);
            self.centers.reserve(room);
            self.nodes.reserve(room);
            self.splits.reserve(room);
        }
    }
}

/// Splits `items` in two about the middle of their `centers`' extent along its longer axis
/// (Box2D's `b2PartitionMid`: a Hoare partition, centres below the middle first); returns the
/// size of the first part, half the items when all fall on one side.
pub(super) fn partition_mid(items: &mut [u32], centers: &mut [Vec2]) -> usize {
    let count = items.len();
    if count <= 2 {
        return count / 2;
    }
    let (mut lower, mut upper) = (centers[0], centers[0]);
    for c in &centers[1..] {
        lower = lower.inf(c);
        upper = upper.sup(c);
    }
    let extent = upper - lower;
    let axis = if extent.x > extent.y { 0 } else { 1 };
    let pivot = 0.5 * (lower[axis] + upper[axis]);
    let (mut i1, mut i2) = (0, count);
    while i1 < i2 {
        while i1 < i2 && centers[i1][axis] < pivot {
            i1 += 1;
        }
        while i1 < i2 && centers[i2 - 1][axis] >= pivot {
            i2 -= 1;
        }
        if i1 < i2 {
            items.swap(i1, i2 - 1);
            centers.swap(i1, i2 - 1);
            i1 += 1;
            i2 -= 1;
        }
    }
    if 0 < i1 && i1 < count { i1 } else { count / 2 }
}
