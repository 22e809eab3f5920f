//! The broadphase: which pairs of bodies are close enough to need a closer look.
//!
//! A dynamic AABB tree (as in Box2D) holds one enlarged ("fat") box per body. A body that moves
//! within its fat box costs nothing; one that leaves it is re-inserted and queued, and at the
//! next pair update only queued bodies query the trees, so the cost per step follows motion,
//! not the body count. Static bodies live in a tree of their own that is never queried by
//! static bodies, so static-static pairs are never even looked at.

use crate::aabb::Aabb;
use crate::body::{BodyHandle, BodyKind};
use crate::math::{Real, Vec2};

const NULL: u32 = u32::MAX;

#[derive(Debug, Clone)]
struct TreeNode {
    aabb: Aabb,
    /// Parent node, or (for free nodes) the next free node.
    parent: u32,
    child1: u32,
    child2: u32,
    /// Leaves are 0; free nodes are -1.
    height: i32,
    /// What the leaf stands for.
    payload: u32,
}

impl TreeNode {
    #[inline]
    fn is_leaf(&self) -> bool {
        self.child1 == NULL
    }
}

/// A bounding-volume hierarchy of axis-aligned boxes, balanced by tree rotations.
///
/// Leaves are proxies: a box and a `u32` payload. Insertion descends by the surface-area
/// heuristic (perimeter in 2D), so queries cost `O(log n + hits)` on average.
#[derive(Debug, Clone)]
pub struct DynamicTree {
    nodes: Vec<TreeNode>,
    root: u32,
    free_list: u32,
    proxy_count: usize,
}

impl Default for DynamicTree {
    fn default() -> Self {
        DynamicTree {
            nodes: Vec::new(),
            root: NULL,
            free_list: NULL,
            proxy_count: 0,
        }
    }
}

impl DynamicTree {
    /// An empty tree.
    pub fn new() -> Self {
        Self::default()
    }

    fn allocate_node(&mut self) -> u32 {
        let fresh = TreeNode {
            aabb: Aabb::new(Vec2::zeros(), Vec2::zeros()),
            parent: NULL,
            child1: NULL,
            child2: NULL,
            height: 0,
            payload: NULL,
        };
        if self.free_list == NULL {
            self.nodes.push(fresh);
            (self.nodes.len() - 1) as u32
        } else {
            let id = self.free_list;
            self.free_list = self.nodes[id as usize].parent;
            self.nodes[id as usize] = fresh;
            id
        }
    }

    fn free_node(&mut self, id: u32) {
        let node = &mut self.nodes[id as usize];
        node.parent = self.free_list;
        node.height = -1;
        self.free_list = id;
    }

    /// Adds a leaf with the given box and payload; returns its proxy id.
    pub fn create_proxy(&mut self, aabb: Aabb, payload: u32) -> u32 {
        let id = self.allocate_node();
        let node = &mut self.nodes[id as usize];
        node.aabb = aabb;
        node.payload = payload;
        self.insert_leaf(id);
        self.proxy_count += 1;
        id
    }

    /// Removes a leaf.
    pub fn destroy_proxy(&mut self, proxy: u32) {
        debug_assert!(self.nodes[proxy as usize].is_leaf());
        self.remove_leaf(proxy);
        self.free_node(proxy);
        self.proxy_count -= 1;
    }

    /// Gives a leaf a new box (re-inserting it where it now belongs).
    pub fn move_proxy(&mut self, proxy: u32, aabb: Aabb) {
        self.remove_leaf(proxy);
        self.nodes[proxy as usize].aabb = aabb;
        self.insert_leaf(proxy);
    }

    /// The box stored for a leaf.
    #[inline]
    pub fn fat_aabb(&self, proxy: u32) -> Aabb {
        self.nodes[proxy as usize].aabb
    }

    /// The payload stored for a leaf.
    #[inline]
    pub fn payload(&self, proxy: u32) -> u32 {
        self.nodes[proxy as usize].payload
    }

    /// How many leaves the tree holds.
    pub fn proxy_count(&self) -> usize {
        self.proxy_count
    }

    /// The height of the tree (0 for a single leaf, -1 when empty).
    pub fn height(&self) -> i32 {
        if self.root == NULL {
            -1
        } else {
            self.nodes[self.root as usize].height
        }
    }

    /// Calls `visit(proxy)` for every leaf whose box overlaps `aabb`.
    pub fn query(&self, aabb: &Aabb, mut visit: impl FnMut(u32)) {
        if self.root == NULL {
            return;
        }
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(self.root);
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            if !node.aabb.overlaps(aabb) {
                continue;
            }
            if node.is_leaf() {
                visit(id);
            } else {
                stack.push(node.child1);
                stack.push(node.child2);
            }
        }
    }

    /// Walks the leaves whose boxes the segment `origin + t * translation`, `t` in
    /// `[0, max_fraction]`, passes through. `visit(proxy, max_fraction)` returns the new
    /// maximum fraction (for closest-hit casts, the hit's fraction clips the rest of the walk).
    pub fn ray_cast(
        &self,
        origin: Vec2,
        translation: Vec2,
        mut max_fraction: Real,
        mut visit: impl FnMut(u32, Real) -> Real,
    ) {
        if self.root == NULL {
            return;
        }
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(self.root);
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            if node
                .aabb
                .ray_interval(origin, translation, max_fraction)
                .is_none()
            {
                continue;
            }
            if node.is_leaf() {
                max_fraction = visit(id, max_fraction).min(max_fraction);
                if max_fraction <= 0.0 {
                    return;
                }
            } else {
                stack.push(node.child1);
                stack.push(node.child2);
            }
        }
    }

    fn insert_leaf(&mut self, leaf: u32) {
        if self.root == NULL {
            self.root = leaf;
            self.nodes[leaf as usize].parent = NULL;
            return;
        }
        // Descend to the sibling that makes the tree's total perimeter grow least.
        let leaf_aabb = self.nodes[leaf as usize].aabb;
        let mut index = self.root;
        while !self.nodes[index as usize].is_leaf() {
            let node = &self.nodes[index as usize];
            let (child1, child2) = (node.child1, node.child2);
            let perimeter = node.aabb.perimeter();
            let combined = node.aabb.union(&leaf_aabb).perimeter();
            // Cost of a new parent for this node and the leaf, and the cost pushed down to
            // every ancestor below this one if we descend further.
            let cost_here = 2.0 * combined;
            let inheritance = 2.0 * (combined - perimeter);
            let descend_cost = |child: u32| {
                let c = &self.nodes[child as usize];
                let grown = c.aabb.union(&leaf_aabb).perimeter();
                if c.is_leaf() {
                    grown + inheritance
                } else {
                    grown - c.aabb.perimeter() + inheritance
                }
            };
            let (cost1, cost2) = (descend_cost(child1), descend_cost(child2));
            if cost_here < cost1 && cost_here < cost2 {
                break;
            }
            index = if cost1 < cost2 { child1 } else { child2 };
        }
        let sibling = index;

        let old_parent = self.nodes[sibling as usize].parent;
        let new_parent = self.allocate_node();
        {
            let sibling_node = &self.nodes[sibling as usize];
            let (aabb, height) = (sibling_node.aabb.union(&leaf_aabb), sibling_node.height + 1);
            let parent = &mut self.nodes[new_parent as usize];
            parent.parent = old_parent;
            parent.aabb = aabb;
            parent.height = height;
            parent.child1 = sibling;
            parent.child2 = leaf;
        }
        if old_parent == NULL {
            self.root = new_parent;
        } else {
            self.replace_child(old_parent, sibling, new_parent);
        }
        self.nodes[sibling as usize].parent = new_parent;
        self.nodes[leaf as usize].parent = new_parent;
        self.refit_upwards(new_parent);
    }

    fn remove_leaf(&mut self, leaf: u32) {
        if leaf == self.root {
            self.root = NULL;
            return;
        }
        let parent = self.nodes[leaf as usize].parent;
        let grandparent = self.nodes[parent as usize].parent;
        let sibling = if self.nodes[parent as usize].child1 == leaf {
            self.nodes[parent as usize].child2
        } else {
            self.nodes[parent as usize].child1
        };
        self.free_node(parent);
        if grandparent == NULL {
            self.root = sibling;
            self.nodes[sibling as usize].parent = NULL;
        } else {
            self.replace_child(grandparent, parent, sibling);
            self.nodes[sibling as usize].parent = grandparent;
            self.refit_upwards(grandparent);
        }
    }

    fn replace_child(&mut self, parent: u32, old: u32, new: u32) {
        let p = &mut self.nodes[parent as usize];
        if p.child1 == old {
            p.child1 = new;
        } else {
            p.child2 = new;
        }
    }

    /// Rebalances and refits boxes and heights from `index` to the root.
    fn refit_upwards(&mut self, mut index: u32) {
        while index != NULL {
            index = self.balance(index);
            let node = &self.nodes[index as usize];
            let (c1, c2) = (
                &self.nodes[node.child1 as usize],
                &self.nodes[node.child2 as usize],
            );
            let (height, aabb) = (1 + c1.height.max(c2.height), c1.aabb.union(&c2.aabb));
            let node = &mut self.nodes[index as usize];
            node.height = height;
            node.aabb = aabb;
            index = node.parent;
        }
    }

    /// If `a`'s subtrees differ in height by more than one, rotates the taller child up and
    /// returns the new root of this subtree.
    fn balance(&mut self, a: u32) -> u32 {
        let node_a = &self.nodes[a as usize];
        if node_a.is_leaf() || node_a.height < 2 {
            return a;
        }
        let (b, c) = (node_a.child1, node_a.child2);
        let skew = self.nodes[c as usize].height - self.nodes[b as usize].height;
        if skew > 1 {
            self.rotate_up(a, c, b, true)
        } else if skew < -1 {
            self.rotate_up(a, b, c, false)
        } else {
            a
        }
    }

    /// Rotates `up` (a child of `a`) into `a`'s place. `a` keeps `stay` (its other child) and
    /// takes the shorter of `up`'s children; `up` keeps the taller one. `up_is_child2` says
    /// which slot of `a` `up` occupied, which is the slot its adopted grandchild fills.
    fn rotate_up(&mut self, a: u32, up: u32, stay: u32, up_is_child2: bool) -> u32 {
        let (f, g) = (
            self.nodes[up as usize].child1,
            self.nodes[up as usize].child2,
        );
        let a_parent = self.nodes[a as usize].parent;

        self.nodes[up as usize].child1 = a;
        self.nodes[up as usize].parent = a_parent;
        self.nodes[a as usize].parent = up;
        if a_parent == NULL {
            self.root = up;
        } else {
            self.replace_child(a_parent, a, up);
        }

        let (keep, give) = if self.nodes[f as usize].height > self.nodes[g as usize].height {
            (f, g)
        } else {
            (g, f)
        };
        self.nodes[up as usize].child2 = keep;
        if up_is_child2 {
            self.nodes[a as usize].child2 = give;
        } else {
            self.nodes[a as usize].child1 = give;
        }
        self.nodes[give as usize].parent = a;

        let (stay_node, give_node) = (&self.nodes[stay as usize], &self.nodes[give as usize]);
        let a_aabb = stay_node.aabb.union(&give_node.aabb);
        let a_height = 1 + stay_node.height.max(give_node.height);
        let keep_node = &self.nodes[keep as usize];
        let up_aabb = a_aabb.union(&keep_node.aabb);
        let up_height = 1 + a_height.max(keep_node.height);
        self.nodes[a as usize].aabb = a_aabb;
        self.nodes[a as usize].height = a_height;
        self.nodes[up as usize].aabb = up_aabb;
        self.nodes[up as usize].height = up_height;
        up
    }

    /// Checks every structural invariant: parent links, heights, boxes containing their
    /// children, balance, and the leaf count. For tests.
    pub fn validate(&self) -> Result<(), String> {
        if self.root == NULL {
            return if self.proxy_count == 0 {
                Ok(())
            } else {
                Err("empty tree with proxies".into())
            };
        }
        if self.nodes[self.root as usize].parent != NULL {
            return Err("root has a parent".into());
        }
        let mut leaves = 0;
        let mut stack = vec![self.root];
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            if node.is_leaf() {
                leaves += 1;
                if node.height != 0 {
                    return Err(format!("leaf {id} has height {}", node.height));
                }
                continue;
            }
            let (c1, c2) = (
                &self.nodes[node.child1 as usize],
                &self.nodes[node.child2 as usize],
            );
            if c1.parent != id || c2.parent != id {
                return Err(format!("children of {id} do not point back"));
            }
            if node.height != 1 + c1.height.max(c2.height) {
                return Err(format!("node {id} has a stale height"));
            }
            if (c1.height - c2.height).abs() > 1 {
                return Err(format!("node {id} is unbalanced"));
            }
            if !node.aabb.contains(&c1.aabb) || !node.aabb.contains(&c2.aabb) {
                return Err(format!("node {id} does not contain its children"));
            }
            stack.push(node.child1);
            stack.push(node.child2);
        }
        if leaves != self.proxy_count {
            return Err(format!("{leaves} leaves but {} proxies", self.proxy_count));
        }
        Ok(())
    }
}

/// True when a pair of bodies of these kinds can ever produce a contact response: at least
/// one of them must be dynamic.
#[inline]
pub fn kinds_can_collide(a: BodyKind, b: BodyKind) -> bool {
    a == BodyKind::Dynamic || b == BodyKind::Dynamic
}

const STATIC_TREE: usize = 0;
const MOVING_TREE: usize = 1;

#[derive(Debug, Clone, Copy)]
struct Proxy {
    handle: BodyHandle,
    kind: BodyKind,
    node: u32,
    queued: bool,
}

impl Proxy {
    fn tree(&self) -> usize {
        tree_for(self.kind)
    }
}

fn tree_for(kind: BodyKind) -> usize {
    if kind == BodyKind::Static {
        STATIC_TREE
    } else {
        MOVING_TREE
    }
}

/// The broadphase of a world: one proxy per body, keyed by the body's handle.
#[derive(Debug, Clone, Default)]
pub struct BroadPhase {
    trees: [DynamicTree; 2],
    /// Indexed by body slot index.
    proxies: Vec<Option<Proxy>>,
    /// Slots whose fat box changed since the last pair update.
    move_buffer: Vec<u32>,
}

impl BroadPhase {
    /// An empty broadphase.
    pub fn new() -> Self {
        Self::default()
    }

    fn slot(handle: BodyHandle) -> usize {
        handle.index() as usize
    }

    fn proxy(&self, handle: BodyHandle) -> Option<&Proxy> {
        self.proxies
            .get(Self::slot(handle))
            .and_then(Option::as_ref)
            .filter(|p| p.handle == handle)
    }

    /// Adds a body with its tight box, enlarged by `margin`.
    pub fn insert(&mut self, handle: BodyHandle, kind: BodyKind, aabb: Aabb, margin: Real) {
        let slot = Self::slot(handle);
        if self.proxies.len() <= slot {
            self.proxies.resize(slot + 1, None);
        }
        debug_assert!(self.proxies[slot].is_none(), "slot already has a proxy");
        let node = self.trees[tree_for(kind)].create_proxy(aabb.fattened(margin), slot as u32);
        self.proxies[slot] = Some(Proxy {
            handle,
            kind,
            node,
            queued: false,
        });
        self.enqueue(slot);
    }

    /// Removes a body's proxy.
    pub fn remove(&mut self, handle: BodyHandle) {
        if let Some(proxy) = self.proxy(handle).copied() {
            self.trees[proxy.tree()].destroy_proxy(proxy.node);
            self.proxies[Self::slot(handle)] = None;
            // A queued slot is skipped at the next pair update.
        }
    }

    /// Follows a body that may have moved or changed kind. Its fat box is replaced only when
    /// the tight box has left it; then the body is queued to look for new pairs.
    pub fn update(&mut self, handle: BodyHandle, kind: BodyKind, aabb: Aabb, margin: Real) {
        let Some(proxy) = self.proxy(handle).copied() else {
            return;
        };
        if tree_for(kind) != proxy.tree() {
            self.remove(handle);
            self.insert(handle, kind, aabb, margin);
            return;
        }
        let slot = Self::slot(handle);
        if let Some(p) = self.proxies[slot].as_mut() {
            p.kind = kind;
        }
        let tree = &mut self.trees[proxy.tree()];
        if !tree.fat_aabb(proxy.node).contains(&aabb) {
            tree.move_proxy(proxy.node, aabb.fattened(margin));
            self.enqueue(slot);
        }
    }

    fn enqueue(&mut self, slot: usize) {
        if let Some(p) = self.proxies[slot].as_mut()
            && !p.queued
        {
            p.queued = true;
            self.move_buffer.push(slot as u32);
        }
    }

    /// The fat box of a body, if it has a proxy.
    pub fn fat_aabb(&self, handle: BodyHandle) -> Option<Aabb> {
        self.proxy(handle)
            .map(|p| self.trees[p.tree()].fat_aabb(p.node))
    }

    /// True when the fat boxes of two bodies overlap.
    pub fn fat_aabbs_overlap(&self, a: BodyHandle, b: BodyHandle) -> bool {
        match (self.fat_aabb(a), self.fat_aabb(b)) {
            (Some(a), Some(b)) => a.overlaps(&b),
            _ => false,
        }
    }

    /// Pairs whose fat boxes began to overlap because one of them moved since the last call,
    /// each ordered `(lower slot, higher slot)`, sorted, without duplicates, and only where
    /// one body is dynamic. Pairs for which `exists` answers true are left out.
    pub fn update_pairs(
        &mut self,
        mut exists: impl FnMut(BodyHandle, BodyHandle) -> bool,
    ) -> Vec<(BodyHandle, BodyHandle)> {
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for &slot in &self.move_buffer {
            let Some(proxy) = self.proxies[slot as usize] else {
                continue;
            };
            let fat = self.trees[proxy.tree()].fat_aabb(proxy.node);
            // Only dynamic bodies need the static tree; everything needs the moving one.
            let trees: &[usize] = if proxy.kind == BodyKind::Dynamic {
                &[STATIC_TREE, MOVING_TREE]
            } else {
                &[MOVING_TREE]
            };
            for &tree in trees {
                self.trees[tree].query(&fat, |node| {
                    let other_slot = self.trees[tree].payload(node);
                    if other_slot == slot {
                        return;
                    }
                    let Some(other) = self.proxies[other_slot as usize] else {
                        return;
                    };
                    if kinds_can_collide(proxy.kind, other.kind) {
                        pairs.push((slot.min(other_slot), slot.max(other_slot)));
                    }
                });
            }
        }
        for &slot in &self.move_buffer {
            if let Some(p) = self.proxies[slot as usize].as_mut() {
                p.queued = false;
            }
        }
        self.move_buffer.clear();
        pairs.sort_unstable();
        pairs.dedup();
        pairs
            .into_iter()
            .filter_map(|(a, b)| {
                let (a, b) = (
                    self.proxies[a as usize]?.handle,
                    self.proxies[b as usize]?.handle,
                );
                (!exists(a, b)).then_some((a, b))
            })
            .collect()
    }

    /// Every pair whose fat boxes overlap now, as [`BroadPhase::update_pairs`] orders them:
    /// the full answer the incremental one must agree with.
    pub fn overlapping_pairs(&self) -> Vec<(BodyHandle, BodyHandle)> {
        let mut pairs = Vec::new();
        for proxy in self.proxies.iter().flatten() {
            if proxy.kind != BodyKind::Dynamic {
                continue;
            }
            let fat = self.trees[proxy.tree()].fat_aabb(proxy.node);
            let slot = proxy.handle.index();
            for tree in &self.trees {
                tree.query(&fat, |node| {
                    let other_slot = tree.payload(node);
                    if other_slot == slot {
                        return;
                    }
                    let other =
                        self.proxies[other_slot as usize].expect("tree leaves have proxies");
                    // A dynamic-dynamic pair is seen from both sides: keep one.
                    if other.kind == BodyKind::Dynamic && other_slot < slot {
                        return;
                    }
                    let (a, b) = if slot < other_slot {
                        (proxy.handle, other.handle)
                    } else {
                        (other.handle, proxy.handle)
                    };
                    pairs.push((a, b));
                });
            }
        }
        pairs.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));
        pairs
    }

    /// Calls `visit(handle)` for every body whose fat box overlaps `aabb`.
    pub fn query(&self, aabb: &Aabb, mut visit: impl FnMut(BodyHandle)) {
        for tree in &self.trees {
            tree.query(aabb, |node| {
                if let Some(p) = self.proxies[tree.payload(node) as usize] {
                    visit(p.handle);
                }
            });
        }
    }

    /// Walks the bodies whose fat boxes the segment passes through, clipping the walk to the
    /// fraction `visit` returns (see [`DynamicTree::ray_cast`]).
    pub fn ray_cast(
        &self,
        origin: Vec2,
        translation: Vec2,
        mut visit: impl FnMut(BodyHandle, Real) -> Real,
    ) {
        let mut max_fraction = 1.0;
        for tree in &self.trees {
            tree.ray_cast(
                origin,
                translation,
                max_fraction,
                |node, current| match self.proxies[tree.payload(node) as usize] {
                    Some(p) => {
                        let clipped = visit(p.handle, current);
                        max_fraction = max_fraction.min(clipped);
                        clipped
                    }
                    None => current,
                },
            );
        }
    }

    /// The two trees, static first, for inspection and tests.
    pub fn trees(&self) -> [&DynamicTree; 2] {
        [&self.trees[STATIC_TREE], &self.trees[MOVING_TREE]]
    }
}

/// The O(n²) reference: every pair of `(handle, kind, fat box)` entries whose boxes overlap
/// and of which one is dynamic, ordered as the broadphase orders them.
pub fn brute_force_pairs(
    entries: &[(BodyHandle, BodyKind, Aabb)],
) -> Vec<(BodyHandle, BodyHandle)> {
    let mut pairs = Vec::new();
    for (i, (ha, ka, aa)) in entries.iter().enumerate() {
        for (hb, kb, ab) in &entries[i + 1..] {
            if kinds_can_collide(*ka, *kb) && aa.overlaps(ab) {
                let (a, b) = if ha.index() < hb.index() {
                    (*ha, *hb)
                } else {
                    (*hb, *ha)
                };
                pairs.push((a, b));
            }
        }
    }
    pairs.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));
    pairs
}
