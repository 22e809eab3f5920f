//! Sleeping: islands of bodies at rest stop costing anything until something disturbs them.
//!
//! A body's sleep timer runs while its fastest point moves slower than [`SLEEP_THRESHOLD`].
//! Islands are the groups of awake dynamic bodies joined by touching contacts (static and
//! kinematic bodies do not join islands, or one floor would tie a whole world together). An
//! island whose every body has rested for [`TIME_TO_SLEEP`] falls asleep as one: the world
//! moves its bodies, colliders and contacts out of the awake set (see
//! `world::solver_sets`), so no stage of a step visits them. It wakes as one when a moving
//! body touches it, or when the user moves or pushes one of its bodies.

use crate::constants::{SLEEP_THRESHOLD, TIME_TO_SLEEP};
use crate::dynamics::body::{Body, BodyHandle, BodyKind};
use crate::math::Real;

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        // Path halving keeps the trees flat.
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

/// Island finding's memory, kept from step to step so it allocates nothing, and what it found.
#[derive(Debug, Clone, Default)]
pub(crate) struct Islands {
    /// Union-find links between bodies (indices in the awake set).
    parent: Vec<u32>,
    /// Per island root, the shortest time any of its bodies has rested.
    island_rest: Vec<Real>,
    /// Per island root, its number among the islands falling asleep (0: not falling asleep).
    number_of_root: Vec<u32>,
    /// The bodies falling asleep (indices in the awake set), with their island's number,
    /// before grouping.
    sleepers: Vec<(u32, u32)>,
    /// The bodies falling asleep this step, island after island.
    pub falling: Vec<BodyHandle>,
    /// Where each island of `falling` ends.
    pub falling_ends: Vec<usize>,
}

/// Advances the sleep timers of the awake set's bodies and finds the islands that fall asleep
/// (into `islands.falling`). `touching` lists the bodies (indices in `awake`) of every
/// touching contact between two awake bodies. Returns how many sleep timers were advanced.
pub(crate) fn update_sleep(
    awake: &mut [Body],
    touching: &[(usize, usize)],
    dt: Real,
    islands: &mut Islands,
) -> usize {
    let Islands {
        parent,
        island_rest,
        number_of_root,
        sleepers,
        falling,
        falling_ends,
    } = islands;
    falling.clear();
    falling_ends.clear();
    // Room for every awake body up front, so a step that puts islands to sleep allocates
    // nothing once the awake set has been this large.
    falling.reserve(awake.len());
    falling_ends.reserve(awake.len());
    sleepers.clear();
    sleepers.reserve(awake.len());
    let dynamic = |b: &Body| b.kind() == BodyKind::Dynamic;
    let mut checked = 0;
    for body in awake.iter_mut().filter(|b| dynamic(b)) {
        body.update_sleep_time(SLEEP_THRESHOLD, dt);
        checked += 1;
    }
    parent.clear();
    parent.extend(0..awake.len() as u32);
    for &(a, b) in touching {
        if dynamic(&awake[a]) && dynamic(&awake[b]) {
            let (ra, rb) = (find(parent, a as u32), find(parent, b as u32));
            if ra != rb {
                parent[ra.max(rb) as usize] = ra.min(rb);
            }
        }
    }
    // The island rests as long as its most restless body.
    island_rest.clear();
    island_rest.resize(awake.len(), Real::INFINITY);
    for (i, body) in awake.iter().enumerate() {
        if dynamic(body) {
            let root = find(parent, i as u32) as usize;
            island_rest[root] = island_rest[root].min(body.sleep_time());
        }
    }
    number_of_root.clear();
    number_of_root.resize(awake.len(), 0);
    let mut islands_falling = 0;
    for (i, body) in awake.iter().enumerate() {
        if !dynamic(body) {
            continue;
        }
        let root = find(parent, i as u32) as usize;
        if island_rest[root] >= TIME_TO_SLEEP {
            if number_of_root[root] == 0 {
                islands_falling += 1;
                number_of_root[root] = islands_falling;
            }
            sleepers.push((number_of_root[root], i as u32));
        }
    }
    // Island by island, each in storage order (an unstable sort allocates nothing).
    sleepers.sort_unstable();
    for (k, &(island, body)) in sleepers.iter().enumerate() {
        falling.push(awake[body as usize].handle());
        if sleepers.get(k + 1).is_none_or(|&(next, _)| next != island) {
            falling_ends.push(falling.len());
        }
    }
    checked
}
