//! A dynamic AABB tree (as in Box2D v3): a bounding-volume hierarchy of fat boxes with `u32`
//! payloads, kept balanced by the surface-area heuristic and tree rotations where leaves go in,
//! and by a median-split rebuild of the part that leaves enlarged in place.

use crate::clone_in_place::clone_in_place;
use crate::geometry::aabb::Aabb;
use crate::heap_bytes::{HeapBytes, OwnsNothing, array, nothing};
use crate::math::{Real, Vec2};

mod overlaps;
mod rebuild;
pub(crate) use overlaps::Walk;
use rebuild::RebuildScratch;
#[cfg(test)]
use rebuild::partition_mid;

const NULL: u32 = u32::MAX;

/// A node of the tree: 32 bytes, aligned to 32, so a walk reads each node from one cache line.
#[derive(Debug, Clone)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "NodeRecord", into = "NodeRecord")
)]
#[repr(C, align(32))]
struct TreeNode {
    aabb: Aabb,
    /// Parent node, or (for free nodes) the next free node.
    parent: u32,
    /// The first child; `NULL` for a leaf.
    child1: u32,
    /// The second child, or for a leaf what it stands for (its payload).
    child2: u32,
    /// Leaves are 0; free nodes are -1 (see [`height_over`]).
    height: i16,
    /// An inner node whose box grew in place since the last rebuild, or that holds one: the
    /// part [`DynamicTree::rebuild`] builds again. Every ancestor of a marked node is marked;
    /// leaves never are.
    enlarged: bool,
    /// A leaf that moved since the last pair update, or an inner node that holds one: only
    /// while the pair walk runs (see [`overlaps`]); at any other time no node is marked.
    moved: bool,
}

// Plain values: every field is `Copy` (one that is not fails to compile in the pattern below,
// which moves each out of a borrowed node), so an array of nodes is its capacity alone.
impl OwnsNothing for TreeNode {}
const _: fn(&TreeNode) -> TreeNode = |node| TreeNode { ..*node };

// Queries walk the nodes: one per half cache line (in single precision).
#[cfg(not(feature = "f64"))]
const _: () = assert!(std::mem::size_of::<TreeNode>() == 32);

/// A node as a saved world holds it: a leaf's payload in a field of its own, so saved worlds
/// read the same as when nodes kept it apart.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "TreeNode")]
struct NodeRecord {
    aabb: Aabb,
    parent: u32,
    child1: u32,
    child2: u32,
    height: i16,
    payload: u32,
    #[serde(default)]
    enlarged: bool,
}

#[cfg(feature = "serde")]
impl From<TreeNode> for NodeRecord {
    fn from(node: TreeNode) -> Self {
        let leaf = node.is_leaf();
        NodeRecord {
            aabb: node.aabb,
            parent: node.parent,
            child1: node.child1,
            child2: if leaf { NULL } else { node.child2 },
            height: node.height,
            payload: if leaf { node.child2 } else { NULL },
            enlarged: node.enlarged,
        }
    }
}

#[cfg(feature = "serde")]
impl TryFrom<NodeRecord> for TreeNode {
    type Error = &'static str;

    fn try_from(record: NodeRecord) -> Result<Self, Self::Error> {
        let leaf = record.child1 == NULL;
        if leaf && record.child2 != NULL {
            return Err("a tree node has a second child but no first");
        }
        Ok(TreeNode {
            aabb: record.aabb,
            parent: record.parent,
            child1: record.child1,
            child2: if leaf { record.payload } else { record.child2 },
            height: record.height,
            enlarged: record.enlarged,
            moved: false,
        })
    }
}

/// The height of an inner node over children of these heights. Saturating: a pathological
/// tree (thousands of nested boxes make a chain) keeps a valid, if capped, height.
#[inline]
fn height_over(a: i16, b: i16) -> i16 {
    a.max(b).saturating_add(1)
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
///
/// Leaves that move every step take the cheaper way, also Box2D v3's:
/// [`DynamicTree::enlarge_proxy`] gives a leaf its new box in place and grows and marks its
/// ancestors, and [`DynamicTree::rebuild`] then builds the marked part again, top down.
#[derive(Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DynamicTree {
    nodes: Vec<TreeNode>,
    root: u32,
    free_list: u32,
    proxy_count: usize,
    /// The rebuild's working memory, kept so a rebuild allocates nothing once it has grown.
    #[cfg_attr(feature = "serde", serde(skip))]
    scratch: RebuildScratch,
}

clone_in_place!(DynamicTree { nodes, root, free_list, proxy_count } keep { scratch });

impl HeapBytes for DynamicTree {
    fn heap_bytes(&self) -> usize {
        let DynamicTree {
            nodes,
            root,
            free_list,
            proxy_count,
            scratch: _,
        } = self;
        array(nodes) + nothing(root) + nothing(free_list) + nothing(proxy_count)
    }
}

impl Default for DynamicTree {
    fn default() -> Self {
        DynamicTree {
            nodes: Vec::new(),
            root: NULL,
            free_list: NULL,
            proxy_count: 0,
            scratch: RebuildScratch::default(),
        }
    }
}

impl DynamicTree {
    /// An empty tree.
    #[cfg(any(test, feature = "testing"))]
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
            enlarged: false,
            moved: false,
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
        node.enlarged = false;
        self.free_list = id;
    }

    /// Adds a leaf with the given box and payload; returns its proxy id.
    pub fn create_proxy(&mut self, aabb: Aabb, payload: u32) -> u32 {
        let id = self.allocate_node();
        let node = &mut self.nodes[id as usize];
        node.aabb = aabb;
        node.child2 = payload;
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

    /// Gives a leaf a new box where it is (Box2D's `b2DynamicTree_EnlargeProxy`): its
    /// ancestors grow until one already holds the box, and all of them up to the first one
    /// already marked are marked for the next [`DynamicTree::rebuild`]. The tree stays valid,
    /// only looser until that rebuild; a moving leaf costs the walk up its path, not a search
    /// and rotations.
    pub fn enlarge_proxy(&mut self, proxy: u32, aabb: Aabb) {
        debug_assert!(self.nodes[proxy as usize].is_leaf());
        self.nodes[proxy as usize].aabb = aabb;
        let mut index = self.nodes[proxy as usize].parent;
        while index != NULL {
            let node = &mut self.nodes[index as usize];
            let grown = node.aabb.union(&aabb);
            let changed = grown != node.aabb;
            node.aabb = grown;
            node.enlarged = true;
            index = node.parent;
            if !changed {
                // Every ancestor above already holds this one's box.
                break;
            }
        }
        // Above a marked node every ancestor is marked already.
        while index != NULL && !self.nodes[index as usize].enlarged {
            self.nodes[index as usize].enlarged = true;
            index = self.nodes[index as usize].parent;
        }
    }

    /// The box stored for a leaf, for tests.
    #[cfg(test)]
    pub fn fat_aabb(&self, proxy: u32) -> Aabb {
        self.nodes[proxy as usize].aabb
    }

    /// The payload stored for a leaf.
    #[inline]
    pub fn payload(&self, proxy: u32) -> u32 {
        self.nodes[proxy as usize].child2
    }

    /// How many leaves the tree holds.
    pub fn proxy_count(&self) -> usize {
        self.proxy_count
    }

    /// The height of the tree (0 for a single leaf, -1 when empty).
    #[cfg(any(test, feature = "testing"))]
    pub fn height(&self) -> i32 {
        if self.root == NULL {
            -1
        } else {
            i32::from(self.nodes[self.root as usize].height)
        }
    }

    /// The sum of internal nodes' perimeters over the root's: the tree's quality, lower is
    /// better (queries visit fewer nodes). 0 for a tree of at most one leaf.
    #[cfg(any(test, feature = "testing"))]
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
        if !self.nodes[self.root as usize].aabb.overlaps(aabb) {
            return;
        }
        // Only nodes whose boxes overlap go on the stack: each child is tested as its parent
        // is taken off, so a child that misses costs no push and pop.
        let mut stack = NodeStack::new(NULL);
        stack.push(self.root);
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            if node.is_leaf() {
                visit(id);
                continue;
            }
            for child in [node.child1, node.child2] {
                if self.nodes[child as usize].aabb.overlaps(aabb) {
                    stack.push(child);
                }
            }
        }
    }

    /// Walks the leaves whose boxes `swept`, moved by `t * translation` for `t` in
    /// `[0, max_fraction]`, meets on the way: each node's box is grown by the swept box's half
    /// extents, so that the segment its centre sweeps decides (a ray is a box of no size).
    /// `visit(proxy, max_fraction)` returns the new maximum fraction (for closest-hit casts,
    /// the hit's fraction clips the rest of the walk).
    pub fn box_cast(
        &self,
        swept: &Aabb,
        translation: Vec2,
        mut max_fraction: Real,
        mut visit: impl FnMut(u32, Real) -> Real,
    ) {
        if self.root == NULL {
            return;
        }
        let (origin, half) = (swept.center(), swept.half_extents());
        let mut stack = NodeStack::new(NULL);
        stack.push(self.root);
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            let grown = Aabb::new(node.aabb.min - half, node.aabb.max + half);
            if grown
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
            self.shrink_upwards(grandparent);
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
            self.refit(index);
            self.rotate(index);
            index = self.nodes[index as usize].parent;
        }
    }

    /// Refits the ancestors of a removed leaf, from `index` up, until one keeps its box and
    /// height (then so do all above it). No rotations, as Box2D v3 removes: the tree is
    /// rebalanced where leaves go in, and a removal then costs a few nodes, not the path to the
    /// root. Marks stay as they are: the sibling that took the parent's place was marked only
    /// if the parent, and so its new parent, was.
    fn shrink_upwards(&mut self, mut index: u32) {
        while index != NULL {
            let (height, aabb) = self.children_fit(index);
            let node = &mut self.nodes[index as usize];
            if node.height == height && node.aabb == aabb {
                return;
            }
            node.height = height;
            node.aabb = aabb;
            index = node.parent;
        }
    }

    /// The height and box an inner node takes from its children.
    fn children_fit(&self, index: u32) -> (i16, Aabb) {
        let node = &self.nodes[index as usize];
        let (c1, c2) = (
            &self.nodes[node.child1 as usize],
            &self.nodes[node.child2 as usize],
        );
        (height_over(c1.height, c2.height), c1.aabb.union(&c2.aabb))
    }

    fn aabb(&self, id: u32) -> Aabb {
        self.nodes[id as usize].aabb
    }

    /// Points `child`'s parent link at `parent`.
    fn adopt(&mut self, parent: u32, child: u32) {
        self.nodes[child as usize].parent = parent;
    }

    /// Makes `parent`'s box and height those of its children, and marks it if one of them is
    /// marked (a subtree moved under it by an insertion or a rotation brings its marks along).
    fn refit(&mut self, parent: u32) {
        let (height, aabb) = self.children_fit(parent);
        let node = &self.nodes[parent as usize];
        let marked =
            self.nodes[node.child1 as usize].enlarged || self.nodes[node.child2 as usize].enlarged;
        let node = &mut self.nodes[parent as usize];
        node.aabb = aabb;
        node.height = height;
        node.enlarged |= marked;
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

    /// Checks every structural invariant: links in range and pointing back, heights, boxes
    /// containing their children, marks (on inner nodes only, and on every ancestor of a
    /// marked node), the leaf count, and the free list. For tests, and for
    /// reading a saved tree, so it never indexes out of range or loops.
    #[cfg(any(test, feature = "testing", feature = "serde"))]
    pub fn validate(&self) -> Result<(), String> {
        let node = |id: u32| {
            self.nodes
                .get(id as usize)
                .ok_or_else(|| format!("node {id} is out of range"))
        };
        let mut seen = vec![false; self.nodes.len()];
        let mut visit = |id: u32| -> Result<(), String> {
            let seen = seen
                .get_mut(id as usize)
                .ok_or_else(|| format!("node {id} is out of range"))?;
            if std::mem::replace(seen, true) {
                return Err(format!("node {id} is reached twice"));
            }
            Ok(())
        };
        let mut leaves = 0;
        if self.root != NULL {
            if node(self.root)?.parent != NULL {
                return Err("root has a parent".into());
            }
            let mut stack = vec![self.root];
            while let Some(id) = stack.pop() {
                visit(id)?;
                let n = node(id)?;
                if !(n.aabb.min.iter().chain(n.aabb.max.iter())).all(|x| x.is_finite()) {
                    return Err(format!("node {id} has a box that is not finite"));
                }
                if n.moved {
                    return Err(format!("node {id} is still marked moved"));
                }
                if n.is_leaf() {
                    leaves += 1;
                    if n.height != 0 {
                        return Err(format!("leaf {id} has height {}", n.height));
                    }
                    if n.enlarged {
                        return Err(format!("leaf {id} is marked enlarged"));
                    }
                    continue;
                }
                let (c1, c2) = (node(n.child1)?, node(n.child2)?);
                if c1.parent != id || c2.parent != id {
                    return Err(format!("children of {id} do not point back"));
                }
                if n.height != height_over(c1.height, c2.height) {
                    return Err(format!("node {id} has a stale height"));
                }
                if (c1.enlarged || c2.enlarged) && !n.enlarged {
                    return Err(format!(
                        "node {id} holds an enlarged node but is not marked"
                    ));
                }
                if !n.aabb.contains(&c1.aabb) || !n.aabb.contains(&c2.aabb) {
                    return Err(format!("node {id} does not contain its children"));
                }
                stack.push(n.child1);
                stack.push(n.child2);
            }
        }
        if leaves != self.proxy_count {
            return Err(format!("{leaves} leaves but {} proxies", self.proxy_count));
        }
        let mut free = self.free_list;
        while free != NULL {
            visit(free)?;
            free = node(free)?.parent;
        }
        Ok(())
    }

    /// The payload of leaf `node`, if it is one.
    #[cfg(feature = "serde")]
    pub fn leaf_payload(&self, node: u32) -> Option<u32> {
        let n = self.nodes.get(node as usize)?;
        (n.is_leaf() && n.height == 0).then_some(n.child2)
    }
}

/// What is still to visit in a tree walk (nodes, or pairs of them): on the stack for any tree
/// of sane height, so a walk allocates nothing; a spill vector only for pathologically deep
/// trees.
struct WalkStack<T, const N: usize> {
    inline: [T; N],
    len: usize,
    spill: Vec<T>,
}

/// The nodes still to visit in a query.
type NodeStack = WalkStack<u32, 128>;

impl<T: Copy, const N: usize> WalkStack<T, N> {
    /// An empty stack (`fill` fills the unused places).
    fn new(fill: T) -> Self {
        WalkStack {
            inline: [fill; N],
            len: 0,
            spill: Vec::new(),
        }
    }

    #[inline]
    fn push(&mut self, item: T) {
        if self.len < N {
            self.inline[self.len] = item;
            self.len += 1;
        } else {
            self.spill.push(item);
        }
    }

    /// The last pushed item (the spill holds the newest once the array is full).
    #[inline]
    fn pop(&mut self) -> Option<T> {
        if let Some(item) = self.spill.pop() {
            return Some(item);
        }
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        Some(self.inline[self.len])
    }
}

#[cfg(test)]
pub(crate) mod tests;
