//! Sleeping: islands of bodies at rest stop costing anything until something disturbs them.
//!
//! A body's sleep timer runs while its fastest point moves slower than [`SLEEP_THRESHOLD`].
//! Islands are the groups of awake dynamic bodies joined by touching contacts (static and
//! kinematic bodies do not join islands, or one floor would tie a whole world together). An
//! island whose every body has rested for [`TIME_TO_SLEEP`] falls asleep as one: its bodies
//! are skipped by integration, the solver, the narrowphase and the broadphase. It wakes as one
//! when a moving body touches it, or when the user moves or pushes one of its bodies.

use crate::constants::{SLEEP_THRESHOLD, TIME_TO_SLEEP};
use crate::dynamics::body::{Body, BodyKind};
use crate::math::Real;

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        // Path halving keeps the trees flat.
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

/// The memory island finding works in, kept from step to step so it allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct Islands {
    /// Union-find links between bodies (dense indices).
    parent: Vec<u32>,
    /// Per island root, the shortest time any of its bodies has rested.
    island_rest: Vec<Real>,
    /// Per island root, the sleep group it falls asleep as (0: not yet numbered).
    group_of_root: Vec<u32>,
}

/// Advances sleep timers and puts resting islands to sleep. `touching` lists the dense indices
/// of every touching contact's bodies; `next_group` numbers the islands that fall asleep.
/// Returns how many sleep timers were advanced.
pub(crate) fn update_sleep(
    bodies: &mut [Body],
    touching: &[(usize, usize)],
    dt: Real,
    next_group: &mut u32,
    islands: &mut Islands,
) -> usize {
    let Islands {
        parent,
        island_rest,
        group_of_root,
    } = islands;
    let awake_dynamic = |b: &Body| b.kind() == BodyKind::Dynamic && !b.is_sleeping();
    let mut checked = 0;
    for body in bodies.iter_mut().filter(|b| awake_dynamic(b)) {
        body.update_sleep_time(SLEEP_THRESHOLD, dt);
        checked += 1;
    }
    parent.clear();
    parent.extend(0..bodies.len() as u32);
    for &(a, b) in touching {
        if awake_dynamic(&bodies[a]) && awake_dynamic(&bodies[b]) {
            let (ra, rb) = (find(parent, a as u32), find(parent, b as u32));
            if ra != rb {
                parent[ra.max(rb) as usize] = ra.min(rb);
            }
        }
    }
    // The island rests as long as its most restless body.
    island_rest.clear();
    island_rest.resize(bodies.len(), Real::INFINITY);
    for (i, body) in bodies.iter().enumerate() {
        if awake_dynamic(body) {
            let root = find(parent, i as u32) as usize;
            island_rest[root] = island_rest[root].min(body.sleep_time());
        }
    }
    group_of_root.clear();
    group_of_root.resize(bodies.len(), 0);
    for (i, body) in bodies.iter_mut().enumerate() {
        if !awake_dynamic(body) {
            continue;
        }
        let root = find(parent, i as u32) as usize;
        if island_rest[root] >= TIME_TO_SLEEP {
            if group_of_root[root] == 0 {
                *next_group += 1;
                group_of_root[root] = *next_group;
            }
            body.fall_asleep(group_of_root[root]);
        }
    }
    checked
}

/// Wakes every sleeping body of the given islands.
pub(crate) fn wake_groups(bodies: &mut [Body], groups: &[u32]) {
    if groups.is_empty() {
        return;
    }
    for body in bodies.iter_mut().filter(|b| b.is_sleeping()) {
        if groups.contains(&body.sleep_group()) {
            body.wake_up();
        }
    }
}
