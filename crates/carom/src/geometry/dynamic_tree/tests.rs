//! The tree's tests: churn, casts, enlarging and rebuilding, and saved nodes.

use super::*;
use crate::math::vec2;

/// A tiny deterministic generator for the randomised tests (the broadphase's too).
pub(crate) struct Lcg(pub(crate) u64);
impl Lcg {
    pub(crate) fn next(&mut self) -> Real {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        (self.0 >> 40) as Real / (1u64 << 24) as Real
    }
    pub(crate) fn range(&mut self, lo: Real, hi: Real) -> Real {
        lo + (hi - lo) * self.next()
    }
}

/// A box of half sizes 0.05 to 1 centred anywhere within `extent` of the origin.
pub(crate) fn random_box(rng: &mut Lcg, extent: Real) -> Aabb {
    let c = vec2(rng.range(-extent, extent), rng.range(-extent, extent));
    let h = vec2(rng.range(0.05, 1.0), rng.range(0.05, 1.0));
    Aabb::new(c - h, c + h)
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
fn tree_box_cast_visits_every_box_on_the_sweep() {
    let mut rng = Lcg(5);
    let mut tree = DynamicTree::new();
    let boxes: Vec<Aabb> = (0..500).map(|_| random_box(&mut rng, 30.0)).collect();
    for (i, b) in boxes.iter().enumerate() {
        tree.create_proxy(*b, i as u32);
    }
    let translation = vec2(80.0, 7.0);
    let start = vec2(-40.0, -3.0);
    // A ray (a box of no size) and a box.
    for half in [vec2(0.0, 0.0), vec2(1.5, 0.5)] {
        let swept = Aabb::new(start - half, start + half);
        let mut visited = Vec::new();
        tree.box_cast(&swept, translation, 1.0, |p, max| {
            visited.push(tree.payload(p));
            max
        });
        visited.sort_unstable();
        // Every box the sweep meets at one of many sampled times is visited...
        let met = |b: &Aabb, t: Real| {
            let at = Aabb::new(swept.min + translation * t, swept.max + translation * t);
            at.overlaps(b)
        };
        for (i, b) in boxes.iter().enumerate() {
            if (0..=4000).any(|k| met(b, k as Real / 4000.0)) {
                assert!(visited.contains(&(i as u32)), "box {i} missed");
            }
        }
        // ...and only boxes near the swept path are.
        let path = swept.union(&Aabb::new(swept.min + translation, swept.max + translation));
        assert!(visited.iter().all(|&i| boxes[i as usize].overlaps(&path)));
        assert!(!visited.is_empty());
    }
}
/// The leaves of `live` whose boxes overlap `probe`, sorted, and what the tree finds.
fn found_and_expected(
    tree: &DynamicTree,
    live: &[(u32, Aabb)],
    probe: &Aabb,
) -> (Vec<u32>, Vec<u32>) {
    let mut found = Vec::new();
    tree.query(probe, |p| found.push(p));
    found.sort_unstable();
    let mut expected: Vec<u32> = live
        .iter()
        .filter(|(_, a)| a.overlaps(probe))
        .map(|(p, _)| *p)
        .collect();
    expected.sort_unstable();
    (found, expected)
}

fn marked_nodes(tree: &DynamicTree) -> usize {
    tree.nodes
        .iter()
        .filter(|n| n.height >= 0 && n.enlarged)
        .count()
}

/// Leaves drift and jump in place, a few are re-inserted, made and destroyed, and the
/// marked part is rebuilt every few rounds: the tree stays valid throughout, queries find
/// exactly the overlapping leaves before and after each rebuild, a rebuild leaves nothing
/// marked, and the height stays logarithmic.
#[test]
fn enlarging_and_rebuilding_keep_the_tree_valid_and_exact() {
    let mut rng = Lcg(21);
    let mut tree = DynamicTree::new();
    let mut live: Vec<(u32, Aabb)> = Vec::new();
    for i in 0..1500 {
        let aabb = random_box(&mut rng, 60.0);
        live.push((tree.create_proxy(aabb, i), aabb));
    }
    let mut rebuilds = 0;
    for round in 0..4000u32 {
        let choice = rng.next();
        let i = (rng.next() * live.len() as Real) as usize % live.len();
        if choice < 0.85 {
            // A drift, or now and then a long jump, as a fast body takes.
            let jump = if rng.next() < 0.05 { 30.0 } else { 0.5 };
            let d = vec2(rng.range(-jump, jump), rng.range(-jump, jump));
            let aabb = Aabb::new(live[i].1.min + d, live[i].1.max + d);
            tree.enlarge_proxy(live[i].0, aabb);
            live[i].1 = aabb;
        } else if choice < 0.9 {
            let aabb = random_box(&mut rng, 60.0);
            tree.move_proxy(live[i].0, aabb);
            live[i].1 = aabb;
        } else if choice < 0.95 {
            let aabb = random_box(&mut rng, 60.0);
            live.push((tree.create_proxy(aabb, round), aabb));
        } else {
            tree.destroy_proxy(live.swap_remove(i).0);
        }
        if round % 97 == 0 {
            tree.validate().unwrap();
            let probe = random_box(&mut rng, 60.0);
            let (found, expected) = found_and_expected(&tree, &live, &probe);
            assert_eq!(found, expected, "round {round}, before the rebuild");
        }
        if round % 50 == 49 {
            assert!(marked_nodes(&tree) > 0, "round {round}: moves mark nodes");
            tree.rebuild(false);
            rebuilds += 1;
            tree.validate().unwrap();
            assert_eq!(marked_nodes(&tree), 0, "round {round}");
            assert_eq!(tree.proxy_count(), live.len());
            for _ in 0..5 {
                let probe = random_box(&mut rng, 60.0);
                let (found, expected) = found_and_expected(&tree, &live, &probe);
                assert_eq!(found, expected, "round {round}, after the rebuild");
            }
            let bound = 2.0 * (live.len() as Real).log2() + 2.0;
            assert!((tree.height() as Real) <= bound, "height {}", tree.height());
        }
    }
    assert_eq!(rebuilds, 80);
    // Every leaf is still where it was put: each finds itself.
    for (proxy, aabb) in &live {
        assert_eq!(tree.fat_aabb(*proxy), *aabb);
        let (found, _) = found_and_expected(&tree, &live, aabb);
        assert!(found.contains(proxy));
    }
}

/// Enlarging marks the leaf's ancestors (all the way to the root, not the leaf), grows
/// them to hold the new box, and a rebuild clears every mark; with nothing marked a
/// rebuild changes nothing.
#[test]
fn a_rebuild_clears_the_marks_that_enlarging_sets() {
    let mut rng = Lcg(4);
    let mut tree = DynamicTree::new();
    let proxies: Vec<u32> = (0..200)
        .map(|i| tree.create_proxy(random_box(&mut rng, 20.0), i))
        .collect();
    assert_eq!(marked_nodes(&tree), 0);
    let before = tree.nodes.clone();
    tree.rebuild(false);
    assert_eq!(format!("{:?}", tree.nodes), format!("{before:?}"));

    let far = Aabb::new(vec2(100.0, 100.0), vec2(101.0, 101.0));
    tree.enlarge_proxy(proxies[7], far);
    tree.validate().unwrap();
    assert!(!tree.nodes[proxies[7] as usize].enlarged);
    let mut ancestor = tree.nodes[proxies[7] as usize].parent;
    let mut path = 0;
    while ancestor != NULL {
        let node = &tree.nodes[ancestor as usize];
        assert!(node.enlarged && node.aabb.contains(&far));
        ancestor = node.parent;
        path += 1;
    }
    assert_eq!(marked_nodes(&tree), path);
    tree.enlarge_proxy(proxies[50], random_box(&mut rng, 20.0));
    assert!(marked_nodes(&tree) > path);

    tree.rebuild(false);
    tree.validate().unwrap();
    assert_eq!(marked_nodes(&tree), 0);
    let mut found = Vec::new();
    tree.query(&far, |p| found.push(p));
    assert_eq!(found, vec![proxies[7]]);
}

/// A full rebuild of a tree built by insertion gives a valid, balanced tree over the same
/// leaves.
#[test]
fn a_full_rebuild_keeps_every_leaf() {
    let mut rng = Lcg(8);
    let mut tree = DynamicTree::new();
    let live: Vec<(u32, Aabb)> = (0..1000)
        .map(|i| {
            let aabb = random_box(&mut rng, 40.0);
            (tree.create_proxy(aabb, i), aabb)
        })
        .collect();
    let nodes = tree.nodes.len();
    tree.rebuild(true);
    tree.validate().unwrap();
    assert_eq!(tree.nodes.len(), nodes, "freed nodes are reused");
    assert!(tree.height() <= 2 * 10 + 2, "height {}", tree.height());
    for _ in 0..50 {
        let probe = random_box(&mut rng, 40.0);
        let (found, expected) = found_and_expected(&tree, &live, &probe);
        assert_eq!(found, expected);
    }
}

/// The median split halves a range about the middle of its centres on the longer axis,
/// and halves by count when every centre is the same.
#[test]
fn the_median_split_cuts_the_longer_axis() {
    let mut items: Vec<u32> = (0..6).collect();
    let xs = [5.0, 0.0, 9.0, 1.0, 10.0, 2.0];
    let mut centers: Vec<Vec2> = xs.iter().map(|&x| vec2(x, 0.5 * x / 10.0)).collect();
    let split = partition_mid(&mut items, &mut centers);
    assert_eq!(split, 3);
    assert!(centers[..split].iter().all(|c| c.x < 5.0));
    assert!(centers[split..].iter().all(|c| c.x >= 5.0));
    for (item, c) in items.iter().zip(&centers) {
        assert_eq!(c.x, xs[*item as usize], "items move with their centres");
    }
    let mut same = vec![vec2(1.0, 1.0); 5];
    assert_eq!(partition_mid(&mut [0, 1, 2, 3, 4], &mut same), 2);
}

/// A saved tree whose marks break the rule (a marked leaf, or a marked node under an
/// unmarked one) is refused.
#[test]
fn validate_checks_the_marks() {
    let mut rng = Lcg(2);
    let mut tree = DynamicTree::new();
    let proxies: Vec<u32> = (0..20)
        .map(|i| tree.create_proxy(random_box(&mut rng, 10.0), i))
        .collect();
    let mut marked_leaf = tree.clone();
    marked_leaf.nodes[proxies[3] as usize].enlarged = true;
    assert!(marked_leaf.validate().unwrap_err().contains("marked"));
    let mut orphan_mark = tree.clone();
    let parent = orphan_mark.nodes[proxies[3] as usize].parent;
    orphan_mark.nodes[parent as usize].enlarged = true;
    assert!(orphan_mark.validate().unwrap_err().contains("not marked"));
    tree.enlarge_proxy(proxies[3], random_box(&mut rng, 10.0));
    tree.validate().unwrap();
}

/// A saved node keeps a leaf's payload in a field of its own and no second child, and
/// reads back to the same node, free nodes included; a record with a second child but no
/// first is refused.
#[cfg(feature = "serde")]
#[test]
fn saved_nodes_keep_the_payload_apart() {
    let mut rng = Lcg(3);
    let mut tree = DynamicTree::new();
    let proxies: Vec<u32> = (0..20)
        .map(|i| tree.create_proxy(random_box(&mut rng, 10.0), 100 + i))
        .collect();
    tree.destroy_proxy(proxies[5]);
    for (id, node) in tree.nodes.iter().enumerate() {
        let record = NodeRecord::from(node.clone());
        if node.is_leaf() {
            assert_eq!(record.child2, NULL, "node {id}");
            assert_eq!(record.payload, node.child2, "node {id}");
        } else {
            assert_eq!(record.payload, NULL, "node {id}");
        }
        let back = TreeNode::try_from(record).unwrap();
        assert_eq!(
            (
                back.aabb,
                back.parent,
                back.child1,
                back.child2,
                back.height
            ),
            (
                node.aabb,
                node.parent,
                node.child1,
                node.child2,
                node.height
            ),
            "node {id}"
        );
    }
    assert_eq!(tree.payload(proxies[7]), 107);
    let mut bad = NodeRecord::from(tree.nodes[proxies[7] as usize].clone());
    bad.child2 = 0;
    assert!(TreeNode::try_from(bad).is_err());
}
