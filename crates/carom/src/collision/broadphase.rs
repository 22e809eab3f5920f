//! The broadphase: which pairs of colliders are close enough to need a closer look.
//!
//! A dynamic AABB tree (as in Box2D) holds one enlarged ("fat") box per collider. A collider
//! that moves within its fat box costs nothing; one that leaves it in a step gets its new fat
//! box in place and is queued, and at the next pair update only queued colliders look for
//! pairs, so the cost per step follows motion, not the collider count: each queries the trees,
//! or when many moved, the moving tree is walked against itself once for the pairs with a
//! queued leaf. The part of the moving tree those colliders loosened is then built again,
//! once. Static bodies' colliders live in a tree of their own that is never queried by static
//! colliders, so static-static pairs are never even looked at; two colliders of one body never
//! pair.

use crate::capacity::room;
use crate::clone_in_place::clone_in_place;
use crate::constants::{MOVES_PER_TASK, WALK_MOVED_FRACTION, WALK_PIECES};
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::dynamics::collider::ColliderHandle;
use crate::dynamics::filter::CollisionFilter;
#[cfg(feature = "serde")]
use crate::error::CaromError;
use crate::geometry::aabb::Aabb;
use crate::geometry::dynamic_tree::{DynamicTree, Walk};
use crate::geometry::look_ahead::Motion;
use crate::heap_bytes::{HeapBytes, array};
use crate::math::{Real, Vec2};
use crate::parallel::worth_sharing;
use crate::prefetch::prefetch;
use rayon::prelude::*;
use std::collections::TryReserveError;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// True when a pair of bodies of these kinds can ever produce a contact response: at least
/// one of them must be dynamic.
#[inline]
pub(crate) fn kinds_can_collide(a: BodyKind, b: BodyKind) -> bool {
    a == BodyKind::Dynamic || b == BodyKind::Dynamic
}

const STATIC_TREE: usize = 0;
const MOVING_TREE: usize = 1;

/// New pairs each thread's list of the pair update has room for from the start.
const PAIRS_PER_LIST: usize = 64;

#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Proxy {
    handle: ColliderHandle,
    /// The slot of the collider's body.
    body: u32,
    kind: BodyKind,
    node: u32,
    /// Its fat box, as its tree holds it: the narrowphase reads it for every contact, and
    /// here it costs one memory access instead of two.
    fat: Aabb,
    /// What its collider collides with: pairs it forbids are never reported.
    filter: CollisionFilter,
    /// Where it can go next step, if its body moves farther in a step than its fat box's
    /// margin (a runner): its box, swept along its path, overlaps colliders it cannot reach,
    /// so its pairs are made and kept only while the two can close within a step
    /// ([`crate::geometry::look_ahead`]), and it looks for new pairs every step.
    #[cfg_attr(feature = "serde", serde(default))]
    runner: Option<Motion>,
}

impl Proxy {
    fn tree(&self) -> usize {
        tree_for(self.kind)
    }

    /// Its motion, or for a collider that is not a runner, its fat box held still (every
    /// point it can reach in a step lies in it).
    fn motion(&self) -> Motion {
        self.runner.unwrap_or(Motion::still(self.fat))
    }

    /// True when a pair with `other` may have a contact: for a pair with a runner, only
    /// while the two can meet in a step.
    fn may_meet(&self, other: &Proxy) -> bool {
        (self.runner.is_none() && other.runner.is_none()) || self.motion().meets(&other.motion())
    }
}

fn tree_for(kind: BodyKind) -> usize {
    if kind == BodyKind::Static {
        STATIC_TREE
    } else {
        MOVING_TREE
    }
}

/// The new pairs a pair update finds, one list per thread that finds them (gathered and
/// sorted after, so which thread found a pair changes nothing). Each list keeps room for the
/// most pairs a step has found, so a step allocates only when it finds more than any before
/// (a list per piece of the walk would grow whenever a piece met more than it had), or for as
/// many as were reserved.
#[derive(Debug, Default)]
struct FoundPairs {
    lists: Vec<Mutex<Vec<(u32, u32)>>>,
    /// The pairs each list has room for at least (a few, or as many as were reserved).
    room: usize,
}

impl FoundPairs {
    /// Empties the lists, one for each of `threads`, each with room for a few pairs or for
    /// as many as were reserved.
    fn start(&mut self, threads: usize) {
        if self.lists.len() < threads {
            self.lists.resize_with(threads, Mutex::default);
        }
        for list in &mut self.lists {
            let list = list.get_mut().unwrap_or_else(PoisonError::into_inner);
            list.clear();
            list.reserve(self.room.max(PAIRS_PER_LIST));
        }
    }

    /// Makes room in every list, and in those made later, for `pairs` pairs.
    fn reserve(&mut self, pairs: usize) -> Result<(), TryReserveError> {
        self.room = self.room.max(pairs);
        for list in &mut self.lists {
            room(
                list.get_mut().unwrap_or_else(PoisonError::into_inner),
                pairs,
            )?;
        }
        Ok(())
    }

    /// The calling thread's list, held while a task of the update runs on it: no other thread
    /// takes it, so the lock is never waited on.
    fn mine(&self) -> MutexGuard<'_, Vec<(u32, u32)>> {
        let thread = rayon::current_thread_index().unwrap_or(0) % self.lists.len().max(1);
        self.lists[thread]
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Every list's pairs into `pairs` (cleared first), unsorted; each list then keeps room
    /// for all of them, as many as next step's threads could find between them.
    fn gather(&mut self, pairs: &mut Vec<(u32, u32)>) {
        pairs.clear();
        for list in &mut self.lists {
            pairs.extend_from_slice(list.get_mut().unwrap_or_else(PoisonError::into_inner));
        }
        for list in &mut self.lists {
            let list = list.get_mut().unwrap_or_else(PoisonError::into_inner);
            list.clear();
            list.reserve(pairs.len());
        }
    }
}

/// The broadphase of a world: one proxy per collider, keyed by the collider's handle.
#[derive(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BroadPhase {
    trees: [DynamicTree; 2],
    /// Indexed by collider slot index.
    proxies: Vec<Option<Proxy>>,
    /// Slots whose fat box changed since the last pair update.
    move_buffer: Vec<u32>,
    /// Per slot, whether it is in `move_buffer`: the pair queries ask it of every candidate,
    /// so it lives apart from the proxies, one byte a slot.
    moved: Vec<bool>,
    /// New pairs of slots found by the last pair update (kept to reuse the memory).
    #[cfg_attr(feature = "serde", serde(skip))]
    found: FoundPairs,
    /// All of them, sorted (kept to reuse the memory).
    #[cfg_attr(feature = "serde", serde(skip))]
    candidates: Vec<(u32, u32)>,
    /// The pieces the pair walk was cut into (kept to reuse the memory).
    #[cfg_attr(feature = "serde", serde(skip))]
    pieces: Vec<Walk>,
}

clone_in_place!(BroadPhase { trees, proxies, moved } roomy { move_buffer } keep { found, candidates, pieces });

impl HeapBytes for BroadPhase {
    fn heap_bytes(&self) -> usize {
        let BroadPhase {
            trees,
            proxies,
            move_buffer,
            moved,
            found: _,
            candidates: _,
            pieces: _,
        } = self;
        trees.heap_bytes() + array(proxies) + array(move_buffer) + array(moved)
    }
}

impl BroadPhase {
    /// Makes room for `colliders` colliders' proxies and moves, and for `contacts` pairs
    /// found in a step.
    pub(crate) fn reserve(
        &mut self,
        colliders: usize,
        contacts: usize,
    ) -> Result<(), TryReserveError> {
        room(&mut self.proxies, colliders)?;
        room(&mut self.move_buffer, colliders)?;
        room(&mut self.moved, colliders)?;
        room(&mut self.candidates, contacts)?;
        self.found.reserve(contacts)?;
        for tree in &mut self.trees {
            tree.reserve(colliders)?;
        }
        Ok(())
    }

    /// An empty broadphase.
    #[cfg(any(test, feature = "testing"))]
    pub fn new() -> Self {
        Self::default()
    }

    fn slot(handle: ColliderHandle) -> usize {
        handle.index() as usize
    }

    fn proxy(&self, handle: ColliderHandle) -> Option<&Proxy> {
        proxy_of(&self.proxies, handle)
    }

    /// [`BroadPhase::proxy`], to change.
    fn proxy_mut(&mut self, handle: ColliderHandle) -> Option<&mut Proxy> {
        self.proxies
            .get_mut(Self::slot(handle))
            .and_then(Option::as_mut)
            .filter(|p| p.handle == handle)
    }

    /// Adds a proxy for a collider of `body`, a body of `kind`, with a fat box `margin` wider
    /// than `aabb`.
    pub fn insert(
        &mut self,
        handle: ColliderHandle,
        body: BodyHandle,
        kind: BodyKind,
        aabb: Aabb,
        margin: Real,
    ) {
        let slot = Self::slot(handle);
        if self.proxies.len() <= slot {
            self.proxies.resize(slot + 1, None);
            self.moved.resize(slot + 1, false);
        }
        debug_assert!(self.proxies[slot].is_none(), "slot already has a proxy");
        let fat = aabb.fattened(margin);
        let node = self.trees[tree_for(kind)].create_proxy(fat, slot as u32);
        self.proxies[slot] = Some(Proxy {
            handle,
            body: body.index(),
            kind,
            node,
            fat,
            filter: CollisionFilter::DEFAULT,
            runner: None,
        });
        self.enqueue(slot);
    }

    /// Sets what a collider collides with (every proxy starts colliding with everything);
    /// it looks for pairs again at the next update.
    pub fn set_filter(&mut self, handle: ColliderHandle, filter: CollisionFilter) {
        let slot = Self::slot(handle);
        if let Some(Some(proxy)) = self.proxies.get_mut(slot) {
            proxy.filter = filter;
            self.enqueue(slot);
        }
    }

    /// Removes a collider's proxy.
    pub fn remove(&mut self, handle: ColliderHandle) {
        if let Some(proxy) = self.proxy(handle).copied() {
            self.trees[proxy.tree()].destroy_proxy(proxy.node);
            self.proxies[Self::slot(handle)] = None;
            // A queued slot is skipped at the next pair update (or, if another collider takes
            // the slot first, queries for that one).
        }
    }

    /// Whether [`BroadPhase::update`] would change anything for this collider: its tight box
    /// left its fat box, or its body changed kind. Reads only, so it may run on many threads.
    pub fn needs_update(&self, handle: ColliderHandle, kind: BodyKind, aabb: &Aabb) -> bool {
        self.proxy(handle)
            .is_some_and(|proxy| kind != proxy.kind || !proxy.fat.contains(aabb))
    }

    /// Follows a collider whose body was moved or changed kind by hand. Its fat box is replaced
    /// only when the tight box has left it, and then re-inserted where it now belongs (Box2D's
    /// `b2BroadPhase_MoveProxy`: a teleport may go anywhere); then the body is queued to look
    /// for new pairs.
    pub fn update(&mut self, handle: ColliderHandle, kind: BodyKind, aabb: Aabb, margin: Real) {
        self.refit(handle, kind, aabb, margin, false);
    }

    /// Follows a collider its body carried in a step: as [`BroadPhase::update`], but a new fat
    /// box in the moving tree is set in place, growing its ancestors
    /// ([`DynamicTree::enlarge_proxy`]), for [`BroadPhase::rebuild_moving_tree`] to build
    /// again once after the next pair update: many small moves cost a walk up each, not a
    /// search and rotations each.
    pub fn enlarge(&mut self, handle: ColliderHandle, kind: BodyKind, aabb: Aabb, margin: Real) {
        self.refit(handle, kind, aabb, margin, true);
    }

    /// [`BroadPhase::update`], or with `in_place` [`BroadPhase::enlarge`]. The static tree is
    /// never rebuilt in a step, so a static collider is always re-inserted.
    fn refit(
        &mut self,
        handle: ColliderHandle,
        kind: BodyKind,
        aabb: Aabb,
        margin: Real,
        in_place: bool,
    ) {
        let Some(proxy) = self.proxy(handle).copied() else {
            return;
        };
        if tree_for(kind) != proxy.tree() {
            let body = BodyHandle::from_raw_parts(proxy.body, 0);
            self.remove(handle);
            self.insert(handle, body, kind, aabb, margin);
            self.set_filter(handle, proxy.filter);
            return;
        }
        let left_fat_box = !proxy.fat.contains(&aabb);
        let fat = if left_fat_box {
            let fat = aabb.fattened(margin);
            let tree = &mut self.trees[proxy.tree()];
            if in_place && proxy.tree() == MOVING_TREE {
                tree.enlarge_proxy(proxy.node, fat);
            } else {
                tree.move_proxy(proxy.node, fat);
            }
            fat
        } else {
            proxy.fat
        };
        let slot = Self::slot(handle);
        if let Some(p) = self.proxies[slot].as_mut() {
            (p.kind, p.fat) = (kind, fat);
        }
        // A new kind can pair with bodies the old one ignored (kinematic turned dynamic).
        if left_fat_box || kind != proxy.kind {
            self.enqueue(slot);
        }
    }

    /// Builds again the part of the moving tree that [`BroadPhase::enlarge`] loosened (see
    /// [`DynamicTree::rebuild`]), so queries stay as fast as in a tree built by insertion.
    /// Nothing to do when nothing was enlarged; the static tree never is. A step does this
    /// through `BroadPhase::take_moving_tree`.
    #[cfg(any(test, feature = "testing"))]
    pub fn rebuild_moving_tree(&mut self) {
        self.trees[MOVING_TREE].rebuild(false);
    }

    /// True when the collider's body outran its fat box's margin in the last step (see
    /// [`BroadPhase::set_runner`]).
    pub(crate) fn is_runner(&self, handle: ColliderHandle) -> bool {
        self.proxy(handle).is_some_and(|p| p.runner.is_some())
    }

    /// Marks whether the collider's body outruns its fat box's margin, with its motion if it
    /// does. A runner looks for new pairs every step, since the pairs its swept box overlaps
    /// are made only once the two can close within a step. One that stops running takes
    /// `fat` as its fat box (its box swept at its own, slower speed, grown by the margin:
    /// the old one reaches as far as it could go at a runner's speed) and looks once more,
    /// for the pairs it passed over.
    pub(crate) fn set_runner(&mut self, handle: ColliderHandle, runner: Option<Motion>, fat: Aabb) {
        let Some(proxy) = self.proxy_mut(handle) else {
            return;
        };
        let was = std::mem::replace(&mut proxy.runner, runner);
        if was.is_some() && runner.is_none() && proxy.tree() == MOVING_TREE {
            proxy.fat = fat;
            let node = proxy.node;
            self.trees[MOVING_TREE].enlarge_proxy(node, fat);
        }
        if runner.is_some() || was.is_some() {
            self.enqueue(Self::slot(handle));
        }
    }

    /// Forgets where the last step said the collider was going (its body was moved or pushed
    /// by hand): its pairs are judged by its fat box alone until the next step says again.
    pub(crate) fn forget_motion(&mut self, handle: ColliderHandle) {
        if self
            .proxy_mut(handle)
            .is_some_and(|proxy| proxy.runner.take().is_some())
        {
            self.enqueue(Self::slot(handle));
        }
    }

    /// Looks for new pairs of a collider at the next pair update, though it has not moved
    /// (two bodies that could not collide now can).
    pub fn requeue(&mut self, handle: ColliderHandle) {
        if self.proxy(handle).is_some() {
            self.enqueue(Self::slot(handle));
        }
    }

    fn enqueue(&mut self, slot: usize) {
        if self.proxies[slot].is_some() && !std::mem::replace(&mut self.moved[slot], true) {
            self.move_buffer.push(slot as u32);
        }
    }

    /// The fat box of a collider, if it has a proxy.
    #[cfg(any(test, feature = "testing"))]
    pub fn fat_aabb(&self, handle: ColliderHandle) -> Option<Aabb> {
        self.proxy(handle).map(|p| p.fat)
    }

    /// True when two colliders may keep a contact (`FatBoxes::may_keep`).
    #[cfg(any(test, feature = "testing"))]
    pub fn may_keep(&self, a: ColliderHandle, b: ColliderHandle) -> bool {
        let proxies = &self.proxies;
        FatBoxes { proxies }.may_keep(a, b)
    }

    /// The fat boxes, which the narrowphase reads.
    pub(crate) fn fat_boxes(&self) -> FatBoxes<'_> {
        FatBoxes {
            proxies: &self.proxies,
        }
    }

    /// Takes the moving tree out, to rebuild ([`DynamicTree::rebuild`]) beside the stages
    /// that do not read it, leaving an empty one until [`BroadPhase::restore_moving_tree`]
    /// puts it back.
    pub(crate) fn take_moving_tree(&mut self) -> DynamicTree {
        std::mem::take(&mut self.trees[MOVING_TREE])
    }

    /// Puts back the tree [`BroadPhase::take_moving_tree`] took out.
    pub(crate) fn restore_moving_tree(&mut self, tree: DynamicTree) {
        debug_assert_eq!(
            self.trees[MOVING_TREE].proxy_count(),
            0,
            "nothing joins the moving tree while it is out"
        );
        self.trees[MOVING_TREE] = tree;
    }

    /// [`BroadPhase::update_pairs_into`] into a new vector, for tests.
    #[cfg(any(test, feature = "testing"))]
    pub fn update_pairs(
        &mut self,
        exists: impl Fn(u32, u32) -> bool + Sync,
    ) -> Vec<(ColliderHandle, ColliderHandle)> {
        let mut pairs = Vec::new();
        self.update_pairs_into(exists, &mut pairs);
        pairs
    }

    /// Pairs whose fat boxes began to overlap because one of them moved since the last call,
    /// each ordered `(lower slot, higher slot)`, sorted, without duplicates, and only where
    /// one body is dynamic, into `out` (cleared first), allocating nothing once the buffers
    /// have grown. Pairs for which `exists(lower slot, higher slot)` answers true are left
    /// out. Returns how many pairs of overlapping fat boxes it met.
    ///
    /// When many of the moving tree's leaves moved, they are marked and the tree is walked
    /// against itself and against the static tree for the overlapping pairs with a marked leaf
    /// (`DynamicTree::walk`), and only queued static colliders (a static body moved by hand)
    /// query the moving tree; when few moved, each queued collider queries the trees. Threads
    /// share the walk in pieces, and the queries in runs, when there is enough of either.
    pub fn update_pairs_into(
        &mut self,
        exists: impl Fn(u32, u32) -> bool + Sync,
        out: &mut Vec<(ColliderHandle, ColliderHandle)>,
    ) -> usize {
        out.clear();
        let moved = self.move_buffer.len();
        let walked =
            moved as Real >= WALK_MOVED_FRACTION * self.trees[MOVING_TREE].proxy_count() as Real;
        if walked {
            for &slot in &self.move_buffer {
                if let Some(proxy) = self.proxies[slot as usize]
                    && proxy.tree() == MOVING_TREE
                {
                    self.trees[MOVING_TREE].mark_moved(proxy.node);
                }
            }
        }
        let shared = worth_sharing(moved, MOVES_PER_TASK);
        let mut pieces = std::mem::take(&mut self.pieces);
        pieces.clear();
        let [static_tree, moving_tree] = &self.trees;
        if walked {
            let wanted = if shared { WALK_PIECES } else { 1 };
            moving_tree.split_walk(static_tree, wanted, &mut pieces);
        }
        let query_tasks = if shared && !walked {
            moved.div_ceil(MOVES_PER_TASK)
        } else {
            1
        };
        let per_task = moved.div_ceil(query_tasks).max(1);
        let mut found = std::mem::take(&mut self.found);
        found.start(if shared {
            rayon::current_num_threads()
        } else {
            1
        });
        let list = || found.mine();
        let walk = |piece: &Walk, found: &mut Vec<(u32, u32)>| {
            let other_tree = match piece {
                Walk::Against(..) => static_tree,
                _ => moving_tree,
            };
            let mut met = 0;
            moving_tree.walk(static_tree, *piece, |a, b| {
                met += 1;
                self.judge(
                    moving_tree.payload(a),
                    other_tree.payload(b),
                    &exists,
                    found,
                );
            });
            met
        };
        let query = |slots: &[u32], found: &mut Vec<(u32, u32)>| {
            slots
                .iter()
                .map(|&slot| self.query_pairs(slot, walked, &exists, found))
                .sum::<usize>()
        };
        let met: usize = if shared {
            let walk_met: usize = pieces
                .par_iter()
                .map(|piece| walk(piece, &mut list()))
                .sum();
            let query_met: usize = self
                .move_buffer
                .par_chunks(per_task)
                .map(|slots| query(slots, &mut list()))
                .sum();
            walk_met + query_met
        } else {
            let mut found = list();
            let walk_met: usize = pieces.iter().map(|piece| walk(piece, &mut found)).sum();
            walk_met + query(&self.move_buffer, &mut found)
        };
        for &slot in &self.move_buffer {
            if walked
                && let Some(proxy) = self.proxies[slot as usize]
                && proxy.tree() == MOVING_TREE
            {
                self.trees[MOVING_TREE].unmark_moved(proxy.node);
            }
            self.moved[slot as usize] = false;
        }
        self.move_buffer.clear();
        let pairs = &mut self.candidates;
        found.gather(pairs);
        self.found = found;
        self.pieces = pieces;
        pairs.sort_unstable();
        // The walk meets each pair once, and a query leaves out the pairs the walk or an
        // earlier query met.
        debug_assert!(pairs.windows(2).all(|w| w[0] != w[1]), "a pair met twice");
        out.extend(pairs.iter().filter_map(|&(a, b)| {
            Some((
                self.proxies[a as usize]?.handle,
                self.proxies[b as usize]?.handle,
            ))
        }));
        met
    }

    /// The pairs the queued proxy in `slot` makes with the proxies its fat box overlaps, into
    /// `found`, as [`BroadPhase::judge`] rules. None if the walk (`walked`) met them: a
    /// proxy of the moving tree, or a pair with another queued proxy. Where two queued proxies
    /// query, only the lower slot's query keeps their pair. Returns how many leaves the queries
    /// met.
    fn query_pairs(
        &self,
        slot: u32,
        walked: bool,
        exists: &impl Fn(u32, u32) -> bool,
        found: &mut Vec<(u32, u32)>,
    ) -> usize {
        let Some(proxy) = self.proxies[slot as usize] else {
            return 0;
        };
        if walked && proxy.tree() == MOVING_TREE {
            return 0;
        }
        // Only dynamic bodies need the static tree; everything needs the moving one.
        let trees: &[usize] = if proxy.kind == BodyKind::Dynamic {
            &[STATIC_TREE, MOVING_TREE]
        } else {
            &[MOVING_TREE]
        };
        let mut met = 0;
        for &tree in trees {
            self.trees[tree].query(&proxy.fat, |node| {
                let other = self.trees[tree].payload(node);
                if other == slot || (self.moved[other as usize] && (walked || other < slot)) {
                    return;
                }
                met += 1;
                self.judge(slot, other, exists, found);
            });
        }
        met
    }

    /// Adds to `found` the pair of the proxies in slots `a` and `b`, whose fat boxes overlap
    /// and at least one of which is queued, if it is new and may collide. The pair is judged
    /// from the side of the queued one (of two, the lower slot), as that side's query saw it.
    fn judge(
        &self,
        a: u32,
        b: u32,
        exists: &impl Fn(u32, u32) -> bool,
        found: &mut Vec<(u32, u32)>,
    ) {
        let (low, high) = (a.min(b), a.max(b));
        let (mover, other) = if self.moved[low as usize] {
            (low, high)
        } else {
            (high, low)
        };
        if exists(low, high) {
            return;
        }
        let (Some(proxy), Some(other)) =
            (self.proxies[mover as usize], self.proxies[other as usize])
        else {
            return;
        };
        if other.body != proxy.body
            && kinds_can_collide(proxy.kind, other.kind)
            && proxy.filter.collides_with(&other.filter)
            && proxy.may_meet(&other)
        {
            found.push((low, high));
        }
    }

    /// Every pair whose fat boxes overlap now, as [`BroadPhase::update_pairs`] orders them:
    /// the full answer the incremental one must agree with.
    #[allow(
        clippy::expect_used,
        reason = "every leaf of the trees was made for a proxy, and a proxy's leaf goes with it"
    )]
    #[cfg(any(test, feature = "testing"))]
    pub fn overlapping_pairs(&self) -> Vec<(ColliderHandle, ColliderHandle)> {
        let mut pairs = Vec::new();
        for proxy in self.proxies.iter().flatten() {
            if proxy.kind != BodyKind::Dynamic {
                continue;
            }
            let fat = proxy.fat;
            let slot = proxy.handle.index();
            for tree in &self.trees {
                tree.query(&fat, |node| {
                    let other_slot = tree.payload(node);
                    if other_slot == slot {
                        return;
                    }
                    let other =
                        self.proxies[other_slot as usize].expect("tree leaves have proxies");
                    if other.body == proxy.body {
                        return;
                    }
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

    /// Calls `visit(handle)` for every collider whose fat box overlaps `aabb`.
    pub fn query(&self, aabb: &Aabb, mut visit: impl FnMut(ColliderHandle)) {
        for tree in [STATIC_TREE, MOVING_TREE] {
            self.query_tree(tree, aabb, &mut visit);
        }
    }

    /// Calls `visit(handle)` for every static collider whose fat box overlaps `aabb`.
    pub fn query_static(&self, aabb: &Aabb, mut visit: impl FnMut(ColliderHandle)) {
        self.query_tree(STATIC_TREE, aabb, &mut visit);
    }

    /// [`BroadPhase::query`] in one tree.
    fn query_tree(&self, tree: usize, aabb: &Aabb, visit: &mut impl FnMut(ColliderHandle)) {
        let tree = &self.trees[tree];
        tree.query(aabb, |node| {
            if let Some(p) = self.proxies[tree.payload(node) as usize] {
                visit(p.handle);
            }
        });
    }

    /// Walks the colliders whose fat boxes the segment passes through, clipping the walk to the
    /// fraction `visit` returns (see `DynamicTree::ray_cast`).
    pub fn ray_cast(
        &self,
        origin: Vec2,
        translation: Vec2,
        visit: impl FnMut(ColliderHandle, Real) -> Real,
    ) {
        self.box_cast(&Aabb::new(origin, origin), translation, visit);
    }

    /// [`BroadPhase::ray_cast`] for a box swept along `translation` (see
    /// [`DynamicTree::box_cast`]).
    pub fn box_cast(
        &self,
        swept: &Aabb,
        translation: Vec2,
        mut visit: impl FnMut(ColliderHandle, Real) -> Real,
    ) {
        let mut max_fraction = 1.0;
        for tree in &self.trees {
            tree.box_cast(
                swept,
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
    #[cfg(any(test, feature = "testing"))]
    pub fn trees(&self) -> [&DynamicTree; 2] {
        [&self.trees[STATIC_TREE], &self.trees[MOVING_TREE]]
    }
}

/// The proxy of a live collider in `proxies` (indexed by slot): none for a slot now held by
/// another collider.
fn proxy_of(proxies: &[Option<Proxy>], handle: ColliderHandle) -> Option<&Proxy> {
    proxies
        .get(BroadPhase::slot(handle))
        .and_then(Option::as_ref)
        .filter(|p| p.handle == handle)
}

/// The fat boxes of a broadphase's colliders, read apart from its trees.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FatBoxes<'a> {
    proxies: &'a [Option<Proxy>],
}

impl FatBoxes<'_> {
    /// True when two colliders may have a contact: their fat boxes overlap and, for a pair
    /// with a runner, the two can meet in a step (the test that made the pair).
    pub(crate) fn may_keep(&self, a: ColliderHandle, b: ColliderHandle) -> bool {
        match (proxy_of(self.proxies, a), proxy_of(self.proxies, b)) {
            (Some(a), Some(b)) => a.fat.overlaps(&b.fat) && a.may_meet(b),
            _ => false,
        }
    }

    /// Asks for the proxies [`FatBoxes::may_keep`] reads to be fetched.
    pub(crate) fn prefetch(&self, a: ColliderHandle, b: ColliderHandle) {
        for collider in [a, b] {
            if let Some(proxy) = self.proxies.get(BroadPhase::slot(collider)) {
                prefetch(proxy);
            }
        }
    }
}

/// The O(n²) reference: every pair of `(handle, kind, fat box)` entries whose boxes overlap
/// and of which one is dynamic, ordered as the broadphase orders them.
#[cfg(any(test, feature = "testing"))]
pub fn brute_force_pairs(
    entries: &[(ColliderHandle, BodyKind, Aabb)],
) -> Vec<(ColliderHandle, ColliderHandle)> {
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

#[cfg(feature = "serde")]
impl BroadPhase {
    /// Checks a broadphase read from a saved world: sound trees, and one proxy for each
    /// collider that is not a sensor, in its slot, on its own leaf of the right tree.
    pub(crate) fn check_saved(
        &self,
        colliders: &crate::handle_map::HandleMap<
            ColliderHandle,
            crate::dynamics::collider::Collider,
        >,
        bodies: &crate::handle_map::HandleMap<BodyHandle, crate::dynamics::body::Body>,
    ) -> Result<(), CaromError> {
        let mut per_tree = [0; 2];
        for tree in &self.trees {
            tree.validate()
                .map_err(|e| CaromError::bad_save(format!("broadphase: {e}")))?;
        }
        for (slot, proxy) in self.proxies.iter().enumerate() {
            let Some(proxy) = proxy else { continue };
            let collider = colliders
                .get(proxy.handle)
                .filter(|c| Self::slot(proxy.handle) == slot && !c.is_sensor())
                .ok_or_else(|| {
                    CaromError::bad_save(format!("broadphase slot {slot} is not a live collider's"))
                })?;
            let body = &bodies.as_slice()[collider.body_index()];
            if proxy.body != collider.body().index() || proxy.kind != body.kind() {
                return Err(CaromError::bad_save(format!(
                    "broadphase slot {slot} has another body"
                )));
            }
            if self.trees[proxy.tree()].leaf_payload(proxy.node) != Some(slot as u32) {
                return Err(CaromError::bad_save(format!(
                    "broadphase slot {slot} is not on its leaf"
                )));
            }
            if proxy.runner.is_some_and(|m| !m.is_finite()) {
                return Err(CaromError::bad_save(format!(
                    "broadphase slot {slot} has a motion that is not finite"
                )));
            }
            per_tree[proxy.tree()] += 1;
        }
        for (tree, count) in self.trees.iter().zip(per_tree) {
            if tree.proxy_count() != count {
                return Err(CaromError::bad_save(
                    "a broadphase tree has leaves without proxies",
                ));
            }
        }
        let listed = colliders
            .handles()
            .iter()
            .filter(|&&c| self.proxy(c).is_some())
            .count();
        let wanted = colliders
            .as_slice()
            .iter()
            .filter(|c| !c.is_sensor())
            .count();
        if listed != wanted {
            return Err(CaromError::bad_save(
                "a collider is missing from the broadphase",
            ));
        }
        let mut listed = vec![false; self.proxies.len()];
        for &slot in &self.move_buffer {
            let fresh = listed
                .get_mut(slot as usize)
                .is_some_and(|seen| !std::mem::replace(seen, true));
            if !fresh {
                return Err(CaromError::bad_save(
                    "the broadphase's moved list is broken",
                ));
            }
        }
        if listed != self.moved {
            return Err(CaromError::bad_save(
                "the broadphase's moved list is broken",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::dynamic_tree::tests::{Lcg, random_box};
    use crate::math::vec2;

    /// Each collider of the tests has a body of its own, with the collider's index.
    fn body_of(collider: ColliderHandle) -> BodyHandle {
        BodyHandle::from_raw_parts(collider.index(), 0)
    }

    fn handle(index: u32) -> ColliderHandle {
        ColliderHandle::from_raw_parts(index, 0)
    }

    #[test]
    fn incremental_pairs_match_brute_force_as_bodies_move() {
        incremental_pairs_match_brute_force(1);
    }

    /// The pair walk's pieces and the moved colliders' queries, shared among threads, find
    /// the same pairs, in the same order.
    #[test]
    fn incremental_pairs_match_brute_force_with_queries_on_threads() {
        incremental_pairs_match_brute_force(3);
    }

    /// Moves 2000 colliders about for six rounds, checking each round's new pairs against a
    /// brute-force search, with the queries on `threads` threads.
    fn incremental_pairs_match_brute_force(threads: usize) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(check_incremental_pairs);
    }

    fn check_incremental_pairs() {
        let mut rng = Lcg(9);
        let mut broadphase = BroadPhase::new();
        let kinds = [
            BodyKind::Static,
            BodyKind::Kinematic,
            BodyKind::Dynamic,
            BodyKind::Dynamic,
        ];
        let mut bodies: Vec<(ColliderHandle, BodyKind, Aabb)> = (0..2000)
            .map(|i| {
                let kind = kinds[i % kinds.len()];
                (handle(i as u32), kind, random_box(&mut rng, 60.0))
            })
            .collect();
        let margin = 0.1;
        for (h, kind, aabb) in &bodies {
            broadphase.insert(*h, body_of(*h), *kind, *aabb, margin);
        }
        // The pairs a world would hold: created by `update_pairs`, dropped when fat boxes part.
        let mut held: Vec<(ColliderHandle, ColliderHandle)> = Vec::new();
        for round in 0..6 {
            // Queried while loosened by the last round's moves, then rebuilt, as in a step.
            let new = broadphase.update_pairs(|a, b| held.contains(&(handle(a), handle(b))));
            broadphase.rebuild_moving_tree();
            for tree in broadphase.trees() {
                tree.validate().unwrap();
            }
            let mut sorted_new = new.clone();
            sorted_new.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));
            assert_eq!(new, sorted_new, "pairs come out in a deterministic order");
            held.extend(new);
            held.retain(|&(a, b)| broadphase.may_keep(a, b));
            held.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));

            let fat: Vec<(ColliderHandle, BodyKind, Aabb)> = bodies
                .iter()
                .map(|(h, k, _)| (*h, *k, broadphase.fat_aabb(*h).unwrap()))
                .collect();
            let expected = brute_force_pairs(&fat);
            assert_eq!(held, expected, "round {round}");
            for proxy in broadphase.proxies.iter().flatten() {
                let in_tree = broadphase.trees[proxy.tree()].fat_aabb(proxy.node);
                assert_eq!(proxy.fat, in_tree, "a proxy's copy of its fat box");
            }
            assert_eq!(broadphase.overlapping_pairs(), expected, "round {round}");
            assert!(expected.len() > 100, "the test world must have pairs");
            assert!(held.iter().all(|(a, b)| a.index() < b.index()));

            // Move the non-static bodies: small drifts and a few long jumps, as steps carry
            // them (in place), and a few teleports (re-inserted). In every other round only
            // a few move (each then queries the trees; when most move, the tree is walked
            // against itself), and a few static bodies are moved by hand.
            let moving_share = if round % 2 == 0 { 1.0 } else { 0.05 };
            for (h, kind, aabb) in bodies.iter_mut() {
                if *kind == BodyKind::Static {
                    if rng.next() < 0.01 {
                        let d = vec2(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
                        *aabb = Aabb::new(aabb.min + d, aabb.max + d);
                        broadphase.update(*h, *kind, *aabb, margin);
                    }
                    continue;
                }
                if rng.next() >= moving_share {
                    continue;
                }
                let jump = if rng.next() < 0.05 { 20.0 } else { 0.3 };
                let d = vec2(rng.range(-jump, jump), rng.range(-jump, jump));
                *aabb = Aabb::new(aabb.min + d, aabb.max + d);
                if rng.next() < 0.02 {
                    broadphase.update(*h, *kind, *aabb, margin);
                } else {
                    broadphase.enlarge(*h, *kind, *aabb, margin);
                }
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
        broadphase.insert(handle(0), body_of(handle(0)), BodyKind::Static, unit, 0.0);
        broadphase.insert(handle(1), body_of(handle(1)), BodyKind::Static, unit, 0.0);
        broadphase.insert(
            handle(2),
            body_of(handle(2)),
            BodyKind::Kinematic,
            unit,
            0.0,
        );
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
