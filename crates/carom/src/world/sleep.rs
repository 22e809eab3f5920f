//! The sleep stage: islands whose bodies have all rested long enough leave the awake set
//! (bodies, colliders, contacts, joints), and wake as a whole when something touches or moves
//! them.

use crate::constants::TIME_TO_SLEEP;
use crate::dynamics::body::BodyKind;
use crate::math::Real;
use crate::solver_set::SolverSet;
use crate::world::World;

impl World {
    /// The sleep stage: advances the awake dynamic bodies' sleep timers, puts every island
    /// whose bodies have all rested long enough to sleep (if it is known to be whole), and
    /// splits the sleepiest island that may have come apart, so its resting parts can sleep
    /// at the next step. Returns how many sleep timers were advanced and how many islands were
    /// split.
    #[allow(
        clippy::expect_used,
        reason = "the sleep pass visits only awake dynamic bodies, and every dynamic body has an island"
    )]
    pub(crate) fn update_sleep(&mut self, dt: Real) -> (usize, usize) {
        let step = self.state.step_count + 1;
        let awake = self.state.body_sets.awake();
        let mut checked = 0;
        // The sleepiest body whose island may have come apart: (sleep time, island).
        let mut split: Option<(Real, u32)> = None;
        for index in awake.clone() {
            let body = &mut self.state.bodies.as_mut_slice()[index];
            if body.kind() != BodyKind::Dynamic {
                continue;
            }
            body.update_sleep_time(dt);
            checked += 1;
            let (time, id) = (body.sleep_time(), body.island().expect("dynamic bodies"));
            let island = self.state.islands.get_mut(id);
            if island.rest_step != step {
                (island.rest_step, island.rest) = (step, time);
            } else {
                island.rest = island.rest.min(time);
            }
            // Ties go to the larger island id, as in Box2D, so the choice is deterministic.
            if time >= TIME_TO_SLEEP
                && island.removed > 0
                && split.is_none_or(|(t, i)| time > t || (time == t && id > i))
            {
                split = Some((time, id));
            }
        }
        // Islands at rest fall asleep, unless they may have come apart (then they wait to be
        // split). Found by their bodies, in storage order; each is put to sleep once.
        let mut sleepy = std::mem::take(&mut self.island_scratch.sleepy);
        sleepy.clear();
        for index in awake {
            let body = &self.state.bodies.as_slice()[index];
            let Some(id) = body.island().filter(|_| body.kind() == BodyKind::Dynamic) else {
                continue;
            };
            let island = self.state.islands.get_mut(id);
            let whole = island.removed == 0 || island.len == 1;
            if island.rest_step == step && island.rest >= TIME_TO_SLEEP && whole {
                // Marked so it is listed once.
                island.rest_step = 0;
                sleepy.push(id);
            }
        }
        for &id in &sleepy {
            self.sleep_island(id);
        }
        self.island_scratch.sleepy = sleepy;
        if let Some((_, id)) = split {
            self.split_island(id);
        }
        (checked, usize::from(split.is_some()))
    }

    /// Puts every body of island `id` to sleep: they, their colliders, contacts and joints
    /// leave the awake set.
    pub(crate) fn sleep_island(&mut self, id: u32) {
        let mut next = self.state.islands.get(id).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.state.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            body.fall_asleep();
            self.move_body(index, SolverSet::Asleep);
        }
    }

    /// Wakes every body of island `id`: they, their colliders, contacts and joints go back to
    /// the awake set. An island already awake is left alone.
    pub(crate) fn wake_island(&mut self, id: u32) {
        let mut next = self.state.islands.get(id).head;
        while let Some(handle) = next {
            let index = self.handle_index(handle);
            let body = &mut self.state.bodies.as_mut_slice()[index];
            next = body.island_neighbours().1;
            if !body.is_sleeping() && self.state.body_sets.set_of(index) == SolverSet::Awake {
                continue;
            }
            body.wake_up();
            self.move_body(index, SolverSet::Awake);
        }
    }
}
