//! Splitting an island that may have come apart, as Box2D's `b2SplitIsland` does: its bodies
//! are joined by union-find over the touching contacts and joints between them. An island
//! still whole is left as it is; otherwise each group of joined bodies becomes an island, in
//! the order of its first body in the old island's list.

use crate::constants::SPLIT_SCAN_SHARE;
use crate::dynamics::body::BodyHandle;
use crate::world::World;
use crate::world::islands::IslandScratch;

/// No island given to a group yet.
const NO_GROUP: u32 = u32::MAX;

impl World {
    /// Splits island `id` into the groups of its bodies that touching contacts and joints
    /// still join; the first group keeps the id. A large island's contacts are found by
    /// reading every awake touching contact, a small one's through its bodies' lists: both
    /// find the same groups.
    pub(super) fn split_island(&mut self, id: u32) {
        let len = self.state.islands.get(id).len as usize;
        let scan = len * SPLIT_SCAN_SHARE >= self.state.body_sets.awake().len();
        self.split_island_by(id, scan);
    }

    /// [`Self::split_island`], finding the island's contacts by a scan of every awake one
    /// (`scan`) or through its bodies' lists.
    fn split_island_by(&mut self, id: u32, scan: bool) {
        let mut s = std::mem::take(&mut self.island_scratch);
        self.list_members(id, &mut s);
        let n = s.members.len();
        s.parents.clear();
        s.parents.extend(0..n as u32);
        if scan {
            for [a, b] in self.state.contacts.awake_touching_bodies() {
                if let (Some(a), Some(b)) = (member(&s, a), member(&s, b)) {
                    union(&mut s.parents, a, b);
                }
            }
        } else {
            for i in 0..n {
                let mut partners = std::mem::take(&mut s.partners);
                self.state
                    .contacts
                    .touching_partners(s.members[i], &mut partners);
                for &partner in &partners {
                    if let Some(j) = member(&s, partner) {
                        union(&mut s.parents, i as u32, j);
                    }
                }
                s.partners = partners;
            }
        }
        for i in 0..n {
            let mut joined = std::mem::take(&mut s.joined);
            self.joint_partners(s.members[i], &mut joined);
            for &partner in &joined {
                if let Some(j) = member(&s, partner) {
                    union(&mut s.parents, i as u32, j);
                }
            }
            s.joined = joined;
        }
        let mut roots = 0;
        for i in 0..n {
            let root = find(&mut s.parents, i as u32);
            s.parents[i] = root;
            roots += usize::from(root == i as u32);
        }
        if roots > 1 {
            self.regroup(id, &mut s);
        } else {
            self.state.islands.get_mut(id).removed = 0;
        }
        self.island_scratch = s;
    }

    /// Lists island `id`'s bodies in `s.members`, in its list's order, and notes where each is.
    fn list_members(&self, id: u32, s: &mut IslandScratch) {
        s.members.clear();
        let mut next = self.state.islands.get(id).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            next = self.state.bodies.as_slice()[index].island_neighbours().1;
            let slot = handle.index() as usize;
            if s.local.len() <= slot {
                s.local.resize(slot + 1, u32::MAX);
            }
            s.local[slot] = s.members.len() as u32;
            s.members.push(handle);
        }
    }

    /// Rebuilds island `id` from the groups `s.parents` names (each member's root): the
    /// first member's group keeps the id, each other group takes a new island as its first
    /// member is met, and every group lists its bodies in their old order.
    fn regroup(&mut self, id: u32, s: &mut IslandScratch) {
        {
            let island = self.state.islands.get_mut(id);
            (island.head, island.tail, island.len, island.removed) = (None, None, 0, 0);
        }
        s.groups.clear();
        s.groups.resize(s.members.len(), NO_GROUP);
        for (i, &handle) in s.members.iter().enumerate() {
            let root = s.parents[i] as usize;
            if s.groups[root] == NO_GROUP {
                s.groups[root] = if i == 0 {
                    id
                } else {
                    self.state.islands.create()
                };
            }
            let index = self.handle_index(handle);
            self.append_to_island(index, s.groups[root]);
        }
    }
}

/// Where `body` is among the members listed in `s`, if it is one of them.
fn member(s: &IslandScratch, body: BodyHandle) -> Option<u32> {
    let place = *s.local.get(body.index() as usize)?;
    (s.members.get(place as usize) == Some(&body)).then_some(place)
}

/// The root of `i`'s group, halving the path to it on the way.
fn find(parents: &mut [u32], mut i: u32) -> u32 {
    while parents[i as usize] != i {
        let grandparent = parents[parents[i as usize] as usize];
        parents[i as usize] = grandparent;
        i = grandparent;
    }
    i
}

/// Joins the groups of `a` and `b`, the lower root becoming the other's parent.
fn union(parents: &mut [u32], a: u32, b: u32) {
    let (a, b) = (find(parents, a), find(parents, b));
    if a != b {
        parents[a.max(b) as usize] = a.min(b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body_def::BodyDef;
    use crate::geometry::shape::Shape;
    use crate::math::{Real, vec2};

    const DT: Real = 1.0 / 60.0;

    /// Two columns of boxes on a ground, bridged by a plank across their tops, after the
    /// pile has settled; then the plank is removed, so the one island has come apart into
    /// the two columns. Returns the world and the columns' boxes.
    fn bridged_columns() -> (World, Vec<BodyHandle>, Vec<BodyHandle>) {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let mut columns = [Vec::new(), Vec::new()];
        for (column, x) in columns.iter_mut().zip([-1.0, 1.0]) {
            for j in 0..5 {
                let y = 0.5 + j as Real;
                let body = BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, y));
                column.push(world.add_body(body).unwrap());
            }
        }
        let plank = BodyDef::dynamic(Shape::rect(2.0, 0.25)).position(vec2(0.0, 5.25));
        let plank = world.add_body(plank).unwrap();
        for _ in 0..30 {
            world.step(DT).unwrap();
        }
        world.remove_body(plank).unwrap();
        let [left, right] = columns;
        (world, left, right)
    }

    /// Each body's island after splitting the left column's island, by scan or by walk.
    fn split(scan: bool) -> (Vec<Option<u32>>, usize) {
        let (mut world, left, right) = bridged_columns();
        let id = world.state.bodies.get(left[0]).unwrap().island().unwrap();
        assert!(world.state.islands.get(id).removed > 0);
        world.split_island_by(id, scan);
        let islands = left
            .iter()
            .chain(&right)
            .map(|&b| world.state.bodies.get(b).unwrap().island())
            .collect();
        let len = world.state.islands.get(id).len;
        (islands, len as usize)
    }

    /// The plank's removal parts the columns: a split by either way of finding the contacts
    /// gives each column an island of its own, the same islands both ways.
    #[test]
    fn a_parted_island_splits_into_its_groups_whichever_way_its_contacts_are_found() {
        for scan in [false, true] {
            let (islands, len) = split(scan);
            let (left, right) = islands.split_at(5);
            assert!(left.iter().all(|&i| i == left[0]), "{islands:?}");
            assert!(right.iter().all(|&i| i == right[0]), "{islands:?}");
            assert_ne!(left[0], right[0]);
            assert_eq!(len, 5);
        }
        assert_eq!(split(false), split(true));
    }

    /// An island still whole keeps its list and id, and is known whole again.
    #[test]
    fn a_whole_island_is_left_as_it_is() {
        let (mut world, left, _) = bridged_columns();
        let id = world.state.bodies.get(left[0]).unwrap().island().unwrap();
        world.split_island_by(id, true);
        // Something between its bodies stopped touching, and it did not part them.
        world.state.islands.get_mut(id).removed = 1;
        let before: Vec<_> = {
            let mut s = IslandScratch::default();
            world.list_members(id, &mut s);
            s.members
        };
        world.split_island_by(id, false);
        let mut s = IslandScratch::default();
        world.list_members(id, &mut s);
        assert_eq!(s.members, before);
        assert_eq!(world.state.islands.get(id).removed, 0);
        assert_eq!(world.state.islands.get(id).len, 5);
    }

    /// Union-find keeps the lowest member as each group's root.
    #[test]
    fn union_makes_the_lowest_member_the_root() {
        let mut parents: Vec<u32> = (0..6).collect();
        union(&mut parents, 4, 2);
        union(&mut parents, 5, 4);
        union(&mut parents, 1, 3);
        let roots: Vec<u32> = (0..6).map(|i| find(&mut parents, i)).collect();
        assert_eq!(roots, [0, 1, 2, 1, 2, 2]);
    }
}
