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

/// A bounding-volume hierarchy of axis-aligned boxes.
///
/// Leaves are proxies: a box and a `u32` payload. Quality is kept by the surface-area heuristic
/// (perimeter in 2D) as in Box2D v3: a leaf goes under the sibling that adds the least total
/// perimeter (a branch-and-bound search, ties broken by distance), and on the way back up
/// nodes are rotated whenever swapping a child with a grandchild shrinks the tree, so queries
/// cost `O(log n + hits)` on average.
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

    /// The sum of internal nodes' perimeters over the root's: the tree's quality, lower is
    /// better (queries visit fewer nodes). 0 for a tree of at most one leaf.
    pub fn area_ratio(&self) -> Real {
        if self.root == NULL {
            return 0.0;
        }
        let internal: Real = self
            .nodes
            .iter()
            .enumerate()
            .filter(|(id, n)| n.height > 0 && *id as u32 != self.root)
            .map(|(_, n)| n.aabb.perimeter())
            .sum();
        internal / self.nodes[self.root as usize].aabb.perimeter()
    }

    /// Calls `visit(proxy)` for every leaf whose box overlaps `aabb`.
    pub fn query(&self, aabb: &Aabb, mut visit: impl FnMut(u32)) {
        if self.root == NULL {
            return;
        }
        let mut stack = NodeStack::default();
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
        let mut stack = NodeStack::default();
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
        let leaf_aabb = self.nodes[leaf as usize].aabb;
        let sibling = self.find_best_sibling(&leaf_aabb);

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

    /// The node under which a new leaf with box `leaf` adds the least total perimeter: the
    /// cost of a new parent there plus the growth of every ancestor. Branch and bound: a
    /// subtree is entered only while its lower bound can still beat the best found.
    fn find_best_sibling(&self, leaf: &Aabb) -> u32 {
        let leaf_perimeter = leaf.perimeter();
        let leaf_center = leaf.center();
        let root = &self.nodes[self.root as usize];
        let mut index = self.root;
        let mut area = root.aabb.perimeter();
        let mut direct_cost = root.aabb.union(leaf).perimeter();
        let mut inherited_cost: Real = 0.0;
        let (mut best_sibling, mut best_cost) = (self.root, direct_cost);
        while !self.nodes[index as usize].is_leaf() {
            let node = &self.nodes[index as usize];
            let cost = direct_cost + inherited_cost;
            if cost < best_cost {
                best_sibling = index;
                best_cost = cost;
            }
            // Every node below pays for this node's growth.
            inherited_cost += direct_cost - area;

            let mut lower = [Real::INFINITY; 2];
            let mut child_area = [0.0; 2];
            let mut child_direct = [0.0; 2];
            let mut is_leaf = [false; 2];
            for (k, &child) in [node.child1, node.child2].iter().enumerate() {
                let c = &self.nodes[child as usize];
                child_direct[k] = c.aabb.union(leaf).perimeter();
                is_leaf[k] = c.is_leaf();
                if is_leaf[k] {
                    let cost = child_direct[k] + inherited_cost;
                    if cost < best_cost {
                        best_sibling = child;
                        best_cost = cost;
                    }
                } else {
                    child_area[k] = c.aabb.perimeter();
                    lower[k] = inherited_cost
                        + child_direct[k]
                        + (leaf_perimeter - child_area[k]).min(0.0);
                }
            }
            if (is_leaf[0] && is_leaf[1]) || (best_cost <= lower[0] && best_cost <= lower[1]) {
                break;
            }
            if lower[0] == lower[1] && !is_leaf[0] {
                // Both children already hold the leaf's box: go to the nearer one.
                let (c1, c2) = (
                    &self.nodes[node.child1 as usize],
                    &self.nodes[node.child2 as usize],
                );
                lower[0] = (c1.aabb.center() - leaf_center).norm_squared();
                lower[1] = (c2.aabb.center() - leaf_center).norm_squared();
            }
            let k = if lower[0] < lower[1] && !is_leaf[0] {
                0
            } else {
                1
            };
            index = if k == 0 { node.child1 } else { node.child2 };
            area = child_area[k];
            direct_cost = child_direct[k];
        }
        best_sibling
    }

    /// Refits boxes and heights from `index` to the root, rotating where that shrinks the tree.
    fn refit_upwards(&mut self, mut index: u32) {
        while index != NULL {
            let node = &self.nodes[index as usize];
            let (c1, c2) = (
                &self.nodes[node.child1 as usize],
                &self.nodes[node.child2 as usize],
            );
            let (height, aabb) = (1 + c1.height.max(c2.height), c1.aabb.union(&c2.aabb));
            let node = &mut self.nodes[index as usize];
            node.height = height;
            node.aabb = aabb;
            self.rotate(index);
            index = self.nodes[index as usize].parent;
        }
    }

    fn aabb(&self, id: u32) -> Aabb {
        self.nodes[id as usize].aabb
    }

    fn node_height(&self, id: u32) -> i32 {
        self.nodes[id as usize].height
    }

    /// Points `child`'s parent link at `parent`.
    fn adopt(&mut self, parent: u32, child: u32) {
        self.nodes[child as usize].parent = parent;
    }

    /// Makes `parent`'s box and height those of its children.
    fn refit(&mut self, parent: u32) {
        let (c1, c2) = (
            self.nodes[parent as usize].child1,
            self.nodes[parent as usize].child2,
        );
        let aabb = self.aabb(c1).union(&self.aabb(c2));
        let height = 1 + self.node_height(c1).max(self.node_height(c2));
        let node = &mut self.nodes[parent as usize];
        node.aabb = aabb;
        node.height = height;
    }

    /// Swaps a child of `a` with a grandchild, or two grandchildren, when that lowers the sum
    /// of the perimeters of `a`'s two children (`a`'s own box holds the same leaves either way).
    fn rotate(&mut self, a: u32) {
        if self.nodes[a as usize].height < 2 {
            return;
        }
        let (b, c) = (self.nodes[a as usize].child1, self.nodes[a as usize].child2);
        let (b_leaf, c_leaf) = (
            self.nodes[b as usize].is_leaf(),
            self.nodes[c as usize].is_leaf(),
        );
        // Each option: (cost, swap `x` in node `x_parent` with `y` in node `y_parent`).
        let mut best: (Real, Option<(u32, u32)>) = (0.0, None);
        let mut consider = |cost: Real, base: Real, x: u32, y: u32| {
            if cost < base && best.1.is_none_or(|_| cost < best.0) {
                best = (cost, Some((x, y)));
            }
        };
        let union_perimeter = |t: &Self, x: u32, y: u32| t.aabb(x).union(&t.aabb(y)).perimeter();
        let area = |t: &Self, x: u32| {
            if t.nodes[x as usize].is_leaf() {
                0.0
            } else {
                t.aabb(x).perimeter()
            }
        };
        // Either way the cost compared is the perimeter of B plus that of C (leaves count 0).
        let base = area(self, b) + area(self, c);
        // Lift a child of `other` in exchange for `down`, its sibling under `a`.
        let mut lifts = |t: &Self, down: u32, other: u32| {
            let (f, g) = (
                t.nodes[other as usize].child1,
                t.nodes[other as usize].child2,
            );
            consider(area(t, down) + union_perimeter(t, down, g), base, down, f);
            consider(area(t, down) + union_perimeter(t, down, f), base, down, g);
        };
        if !c_leaf {
            lifts(self, b, c);
        }
        if !b_leaf {
            lifts(self, c, b);
        }
        if !b_leaf && !c_leaf {
            // Exchange grandchildren across.
            let (d, e) = (self.nodes[b as usize].child1, self.nodes[b as usize].child2);
            let (f, g) = (self.nodes[c as usize].child1, self.nodes[c as usize].child2);
            consider(
                union_perimeter(self, f, e) + union_perimeter(self, d, g),
                base,
                d,
                f,
            );
            consider(
                union_perimeter(self, g, e) + union_perimeter(self, f, d),
                base,
                d,
                g,
            );
        }
        let Some((x, y)) = best.1 else {
            return;
        };
        // Swap the two subtrees `x` and `y` between their parents, then refit bottom-up.
        let (px, py) = (self.nodes[x as usize].parent, self.nodes[y as usize].parent);
        self.replace_child(px, x, y);
        self.replace_child(py, y, x);
        self.adopt(py, x);
        self.adopt(px, y);
        // The deeper of the two parents first, then the other, then `a`.
        for parent in [px, py] {
            if parent != a {
                self.refit(parent);
            }
        }
        self.refit(a);
    }

    /// Checks every structural invariant: parent links, heights, boxes containing their
    /// children, and the leaf count. For tests.
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
    /// Candidate pairs of slots found by the last pair update (kept to reuse the memory).
    candidates: Vec<(u32, u32)>,
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
        let left_fat_box = !tree.fat_aabb(proxy.node).contains(&aabb);
        if left_fat_box {
            tree.move_proxy(proxy.node, aabb.fattened(margin));
        }
        // A new kind can pair with bodies the old one ignored (kinematic turned dynamic).
        if left_fat_box || kind != proxy.kind {
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
        exists: impl FnMut(BodyHandle, BodyHandle) -> bool,
    ) -> Vec<(BodyHandle, BodyHandle)> {
        let mut pairs = Vec::new();
        self.update_pairs_into(exists, &mut pairs);
        pairs
    }

    /// [`BroadPhase::update_pairs`] into `out` (cleared first), allocating nothing once the
    /// buffers have grown.
    pub fn update_pairs_into(
        &mut self,
        mut exists: impl FnMut(BodyHandle, BodyHandle) -> bool,
        out: &mut Vec<(BodyHandle, BodyHandle)>,
    ) {
        let mut pairs = std::mem::take(&mut self.candidates);
        pairs.clear();
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
        out.clear();
        out.extend(pairs.iter().filter_map(|&(a, b)| {
            let (a, b) = (
                self.proxies[a as usize]?.handle,
                self.proxies[b as usize]?.handle,
            );
            (!exists(a, b)).then_some((a, b))
        }));
        self.candidates = pairs;
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

/// The nodes still to visit in a tree walk: on the stack for any tree of sane height, so a
/// query allocates nothing; a spill vector only for pathologically deep trees.
struct NodeStack {
    inline: [u32; 128],
    len: usize,
    spill: Vec<u32>,
}

impl Default for NodeStack {
    fn default() -> Self {
        NodeStack {
            inline: [0; 128],
            len: 0,
            spill: Vec::new(),
        }
    }
}

impl NodeStack {
    #[inline]
    fn push(&mut self, node: u32) {
        if self.len < self.inline.len() {
            self.inline[self.len] = node;
            self.len += 1;
        } else {
            self.spill.push(node);
        }
    }

    /// The last pushed node (the spill holds the newest once the array is full).
    #[inline]
    fn pop(&mut self) -> Option<u32> {
        if let Some(node) = self.spill.pop() {
            return Some(node);
        }
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        Some(self.inline[self.len])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    /// A tiny deterministic generator for the randomised tests.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> Real {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (self.0 >> 40) as Real / (1u64 << 24) as Real
        }
        fn range(&mut self, lo: Real, hi: Real) -> Real {
            lo + (hi - lo) * self.next()
        }
    }

    fn random_box(rng: &mut Lcg, extent: Real) -> Aabb {
        let c = vec2(rng.range(-extent, extent), rng.range(-extent, extent));
        let h = vec2(rng.range(0.05, 1.0), rng.range(0.05, 1.0));
        Aabb::new(c - h, c + h)
    }

    fn handle(index: u32) -> BodyHandle {
        BodyHandle {
            index,
            generation: 0,
        }
    }

    #[test]
    fn tree_stays_valid_and_balanced_under_churn() {
        let mut rng = Lcg(1);
        let mut tree = DynamicTree::new();
        let mut live: Vec<(u32, Aabb)> = Vec::new();
        for round in 0..3000 {
            let choice = rng.next();
            if live.is_empty() || choice < 0.5 {
                let aabb = random_box(&mut rng, 50.0);
                live.push((tree.create_proxy(aabb, round), aabb));
            } else if choice < 0.8 {
                let i = (rng.next() * live.len() as Real) as usize % live.len();
                let aabb = random_box(&mut rng, 50.0);
                tree.move_proxy(live[i].0, aabb);
                live[i].1 = aabb;
            } else {
                let i = (rng.next() * live.len() as Real) as usize % live.len();
                tree.destroy_proxy(live.swap_remove(i).0);
            }
            if round % 100 == 0 {
                tree.validate().unwrap();
            }
        }
        tree.validate().unwrap();
        assert_eq!(tree.proxy_count(), live.len());
        // Rotations keep the height logarithmic.
        let bound = 2.0 * (live.len() as Real).log2() + 2.0;
        assert!((tree.height() as Real) <= bound, "height {}", tree.height());
        // Queries find exactly the overlapping leaves.
        for _ in 0..50 {
            let probe = random_box(&mut rng, 50.0);
            let mut found = Vec::new();
            tree.query(&probe, |p| found.push(p));
            found.sort_unstable();
            let mut expected: Vec<u32> = live
                .iter()
                .filter(|(_, a)| a.overlaps(&probe))
                .map(|(p, _)| *p)
                .collect();
            expected.sort_unstable();
            assert_eq!(found, expected);
        }
    }

    #[test]
    fn tree_ray_cast_visits_every_box_on_the_segment() {
        let mut rng = Lcg(5);
        let mut tree = DynamicTree::new();
        let boxes: Vec<Aabb> = (0..500).map(|_| random_box(&mut rng, 30.0)).collect();
        for (i, b) in boxes.iter().enumerate() {
            tree.create_proxy(*b, i as u32);
        }
        let (origin, translation) = (vec2(-40.0, -3.0), vec2(80.0, 7.0));
        let mut visited = Vec::new();
        tree.ray_cast(origin, translation, 1.0, |p, max| {
            visited.push(tree.payload(p));
            max
        });
        visited.sort_unstable();
        let expected: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| {
                boxes[i as usize]
                    .ray_interval(origin, translation, 1.0)
                    .is_some()
            })
            .collect();
        assert_eq!(visited, expected);
        assert!(!expected.is_empty());
    }

    #[test]
    fn incremental_pairs_match_brute_force_as_bodies_move() {
        let mut rng = Lcg(9);
        let mut broadphase = BroadPhase::new();
        let kinds = [
            BodyKind::Static,
            BodyKind::Kinematic,
            BodyKind::Dynamic,
            BodyKind::Dynamic,
        ];
        let mut bodies: Vec<(BodyHandle, BodyKind, Aabb)> = (0..2000)
            .map(|i| {
                let kind = kinds[i % kinds.len()];
                (handle(i as u32), kind, random_box(&mut rng, 60.0))
            })
            .collect();
        let margin = 0.1;
        for (h, kind, aabb) in &bodies {
            broadphase.insert(*h, *kind, *aabb, margin);
        }
        // The pairs a world would hold: created by `update_pairs`, dropped when fat boxes part.
        let mut held: Vec<(BodyHandle, BodyHandle)> = Vec::new();
        for round in 0..6 {
            let new = broadphase.update_pairs(|a, b| held.contains(&(a, b)));
            let mut sorted_new = new.clone();
            sorted_new.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));
            assert_eq!(new, sorted_new, "pairs come out in a deterministic order");
            held.extend(new);
            held.retain(|&(a, b)| broadphase.fat_aabbs_overlap(a, b));
            held.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));

            let fat: Vec<(BodyHandle, BodyKind, Aabb)> = bodies
                .iter()
                .map(|(h, k, _)| (*h, *k, broadphase.fat_aabb(*h).unwrap()))
                .collect();
            let expected = brute_force_pairs(&fat);
            assert_eq!(held, expected, "round {round}");
            assert_eq!(broadphase.overlapping_pairs(), expected, "round {round}");
            assert!(expected.len() > 100, "the test world must have pairs");
            assert!(held.iter().all(|(a, b)| a.index() < b.index()));

            // Move the non-static bodies: small drifts and a few long jumps.
            for (h, kind, aabb) in bodies.iter_mut() {
                if *kind == BodyKind::Static {
                    continue;
                }
                let jump = if rng.next() < 0.05 { 20.0 } else { 0.3 };
                let d = vec2(rng.range(-jump, jump), rng.range(-jump, jump));
                *aabb = Aabb::new(aabb.min + d, aabb.max + d);
                broadphase.update(*h, *kind, *aabb, margin);
            }
        }
        for tree in broadphase.trees() {
            tree.validate().unwrap();
        }
    }

    #[test]
    fn static_pairs_are_never_reported_and_kind_changes_move_trees() {
        let mut broadphase = BroadPhase::new();
        let unit = Aabb::new(vec2(0.0, 0.0), vec2(1.0, 1.0));
        broadphase.insert(handle(0), BodyKind::Static, unit, 0.0);
        broadphase.insert(handle(1), BodyKind::Static, unit, 0.0);
        broadphase.insert(handle(2), BodyKind::Kinematic, unit, 0.0);
        assert!(broadphase.update_pairs(|_, _| false).is_empty());
        // A body that becomes dynamic pairs with everything it overlaps.
        broadphase.update(handle(2), BodyKind::Dynamic, unit, 0.0);
        assert_eq!(
            broadphase.update_pairs(|_, _| false),
            vec![(handle(0), handle(2)), (handle(1), handle(2))]
        );
        assert_eq!(broadphase.trees()[STATIC_TREE].proxy_count(), 2);
        assert_eq!(broadphase.trees()[MOVING_TREE].proxy_count(), 1);
        broadphase.remove(handle(0));
        assert_eq!(broadphase.overlapping_pairs(), vec![(handle(1), handle(2))]);
        assert!(broadphase.fat_aabb(handle(0)).is_none());
    }
}
