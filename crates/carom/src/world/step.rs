//! One step of the world, stage by stage.

use super::{World, margin_for};
use crate::capacity::{Capacity, room};
use crate::collision::broadphase::BroadPhase;
use crate::collision::continuous::{self, ContinuousScratch};
use crate::collision::hits::find_hits;
use crate::collision::narrowphase::{LookAhead, ManifoldOptions, Narrowphase};
use crate::constants::{
    CONTACTS_PER_TASK, LINEAR_SLOP, RECYCLE_DISTANCE, RECYCLE_DISTANCE_CLASSIC,
    RUNNER_STOP_FRACTION, TIME_STEP_RANGE,
};
use crate::dynamics::body::{Body, BodyKind};
use crate::dynamics::collider::{Collider, ColliderHandle, place_awake_colliders};
use crate::error::{CaromError, check_within};
use crate::geometry::aabb::Aabb;
use crate::geometry::look_ahead::Motion;
use crate::math::{Real, Vec2};
use crate::parallel::{map_zip_into, worth_sharing};
use crate::solver::{self, Environment, SolverKind};
use crate::solver_set::SolverSet;
use crate::stats::{CollisionWork, Instant, StageTimes, StepStats};
use crate::world::effects::Effect;
use std::collections::TryReserveError;

/// What the stages of a step work in besides the solver, kept so a step in steady state
/// allocates nothing.
#[derive(Debug, Clone, Default)]
pub(super) struct StepScratch {
    /// New pairs from the broadphase.
    pairs: Vec<(ColliderHandle, ColliderHandle)>,
    /// Continuous collision's memory.
    continuous: ContinuousScratch,
    /// The narrowphase's memory.
    narrowphase: Narrowphase,
    /// Sleeping islands a moving body touched.
    wake: Vec<u32>,
    /// The joints solved this step.
    awake_joints: Vec<solver::AwakeJoint>,
    /// Per awake collider, what the broadphase must learn of it, if anything.
    refits: Vec<Option<Refit>>,
}

impl StepScratch {
    /// Makes room for a step of a world holding `capacity`.
    pub(super) fn reserve(&mut self, capacity: Capacity) -> Result<(), TryReserveError> {
        room(&mut self.pairs, capacity.contacts)?;
        self.continuous.reserve(capacity.bodies)?;
        self.narrowphase.reserve(capacity.contacts)?;
        room(&mut self.wake, capacity.bodies)?;
        room(&mut self.awake_joints, capacity.joints)?;
        room(&mut self.refits, capacity.colliders)
    }
}

impl World {
    /// Advances the world by `dt` seconds.
    ///
    /// The stages, in order (`docs/architecture.md` names the file of each): find new pairs in
    /// the broadphase; build contact manifolds in the narrowphase (waking the sleeping islands a
    /// moving body touched, joining the islands of contacts that started touching); solve
    /// (integrate forces into velocities, resolve contacts and then joints colour by colour,
    /// integrate positions, in substeps for soft step) and place the moved colliders; report
    /// the hard hits, if some collider asks; remove the joints pulled past their break
    /// thresholds; continuous collision for fast bodies; refresh the broadphase from the moved
    /// colliders; put resting islands to sleep; find what overlaps each sensor. The stages walk
    /// the awake set of bodies, colliders, contacts and joints; the sensors to update are found
    /// by a walk over all of them.
    ///
    /// # Errors
    /// A time step outside 1 µs to 10 s (`TIME_STEP_RANGE`), or not a number; the world is
    /// left untouched.
    pub fn step(&mut self, dt: Real) -> Result<(), CaromError> {
        check_within("time step", dt, TIME_STEP_RANGE, "from 1e-6 s to 10 s")?;
        let started = Instant::now();
        let mut stats = StepStats::default();
        let times = &mut stats.times;
        self.state.contacts.begin_step();
        self.state.sensors.begin_step();
        self.state.hit_events.clear();

        let mut scratch = std::mem::take(&mut self.scratch);

        (
            stats.collision.pair_candidates,
            stats.collision.contacts_created,
        ) = timed(&mut times.broadphase, || {
            self.find_pairs(&mut scratch.pairs)
        });
        // The contacts peak here, the new ones made and the old not yet ended.
        self.high_water = self.high_water.max(self.holds());
        let effects = self.state.settings.effects;
        let continuous = effects.contains(Effect::Continuous);
        // Looking ahead, a face point's margin reaches as far as the pair can close in a
        // step, and moving bodies' boxes cover where they are going, so an impact at any
        // speed has its contact before it happens.
        let prediction = LookAhead::new(continuous, self.state.settings.look_ahead, dt);
        let (deepest, solved) =
            self.collide_and_solve(prediction, dt, &mut scratch, &mut stats.collision, times);
        stats.max_penetration = deepest;
        timed(&mut times.solve, || {
            self.place_moved_colliders(prediction, &mut scratch.refits)
        });
        (stats.contact_points, stats.work) = (solved.points, solved.work);
        if self.state.hit_event_colliders > 0 {
            let (contacts, body_indices) = self.state.contacts.awake_and_bodies();
            let threshold = self.state.settings.hit_event_threshold;
            let bodies = self.state.bodies.as_slice();
            find_hits(
                contacts,
                body_indices,
                bodies,
                threshold,
                &mut self.state.hit_events,
            );
        }
        stats.joints = solved.joints;
        let joints_broke = self.break_joints(&scratch.awake_joints);
        (times.prepare, times.store) = (solved.prepare, solved.store);
        if continuous {
            // The solve's hinged groups are by its states, the awake bodies as it found them:
            // a broken joint may have woken more since.
            let groups = if joints_broke {
                None
            } else {
                self.solver_workspace.joint_groups()
            };
            (stats.continuous_impacts, stats.work.sweeps) = timed(&mut times.continuous, || {
                continuous::solve_continuous(
                    &mut self.state.bodies,
                    self.state.body_sets.awake(),
                    &mut self.state.colliders,
                    &mut scratch.continuous,
                    &self.state.broadphase,
                    &self.state.joints,
                    LINEAR_SLOP,
                    self.pre_solve.is_some(),
                    groups,
                )
            });
        }
        stats.collision.proxies_moved = timed(&mut times.broadphase, || {
            // A broken joint may have woken bodies into the awake set, which the refits found
            // at placement do not cover; otherwise only the bodies continuous collision put
            // back have moved since.
            if joints_broke {
                self.find_refits(prediction, &mut scratch.refits);
            } else if continuous {
                self.refind_refits(prediction, scratch.continuous.moved(), &mut scratch.refits);
            }
            self.refresh_broadphase(&scratch.refits)
        });
        if effects.contains(Effect::Sleeping) {
            (stats.work.sleep_checks, stats.collision.island_splits) =
                timed(&mut times.sleep, || self.update_sleep(dt));
        }
        self.state.sensors.update(
            &self.state.bodies,
            &self.state.colliders,
            &self.state.broadphase,
        );

        self.scratch = scratch;
        self.record(stats, started);
        self.state.time += dt as f64;
        self.state.step_count += 1;
        Ok(())
    }

    /// The narrowphase and the solve; returns the deepest overlap and the solve's report.
    /// Beside them, on another thread if one is free, the part of the broadphase's moving
    /// tree that the last step's motion loosened is built again (Box2D's tree task): neither
    /// reads the tree (the narrowphase reads only the fat boxes), and the pair queries that
    /// need it come next step. A small world (few awake bodies, so little to rebuild) does it
    /// on the calling thread: a fork from outside rayon's pool (a game's main thread) wakes a
    /// worker and waits for it, which costs more than the rebuild.
    fn collide_and_solve(
        &mut self,
        prediction: LookAhead,
        dt: Real,
        scratch: &mut StepScratch,
        collision: &mut CollisionWork,
        times: &mut StageTimes,
    ) -> (Real, solver::StepReport) {
        let mut moving_tree = self.state.broadphase.take_moving_tree();
        let shared = worth_sharing(self.state.body_sets.awake().len(), CONTACTS_PER_TASK);
        let mut stages = || {
            let deepest = timed(&mut times.narrowphase, || {
                self.build_manifolds(
                    prediction,
                    &mut scratch.narrowphase,
                    &mut scratch.wake,
                    collision,
                )
            });
            self.awake_joints(&mut scratch.awake_joints);
            let solved = timed(&mut times.solve, || self.solve(dt, &scratch.awake_joints));
            (deepest, solved)
        };
        let ((deepest, solved), ()) = if shared {
            rayon::join(stages, || moving_tree.rebuild(false))
        } else {
            // In sequence, the rebuild is broadphase work and timed as such.
            let solved = stages();
            timed(&mut times.broadphase, || moving_tree.rebuild(false));
            (solved, ())
        };
        self.state.broadphase.restore_moving_tree(moving_tree);
        (deepest, solved)
    }

    /// Rebuilds the manifolds of every pair where something moves, and wakes the sleeping
    /// islands a moving body touched so they join this step; returns the deepest overlap and
    /// counts what it did into `work`.
    #[allow(
        clippy::expect_used,
        reason = "a live contact's bodies are live: removing a body removes its contacts"
    )]
    fn build_manifolds(
        &mut self,
        prediction: LookAhead,
        narrowphase: &mut Narrowphase,
        wake: &mut Vec<u32>,
        work: &mut CollisionWork,
    ) -> Real {
        wake.clear();
        let (contacts, bodies, colliders) = (
            &mut self.state.contacts,
            &self.state.bodies,
            &self.state.colliders,
        );
        let options = ManifoldOptions {
            margin: self.state.settings.speculative_distance,
            prediction,
            recycling: self.state.settings.contact_recycling.then(|| {
                if self.state.settings.solver.effective_kind() == SolverKind::SoftStep {
                    RECYCLE_DISTANCE
                } else {
                    RECYCLE_DISTANCE_CLASSIC
                }
            }),
            pre_solve: self.pre_solve.as_ref(),
        };
        let fat_boxes = self.state.broadphase.fat_boxes();
        contacts.cover_bodies(bodies.slot_count());
        let deepest =
            narrowphase.update(contacts, bodies, colliders, fat_boxes, options, wake, work);
        wake.sort_unstable();
        wake.dedup();
        for &island in wake.iter() {
            self.wake_island(island);
        }
        // Islands join as their contacts start touching (after the waking, so a sleeping
        // island that is touched joins awake).
        self.apply_touch_changes();
        // No body changes set again before the solver: where each awake contact's bodies
        // are can be found once.
        let bodies = &self.state.bodies;
        self.state.contacts.find_body_indices(|body| {
            bodies
                .dense_index(body)
                .expect("contacts only join live bodies")
        });
        deepest
    }

    /// Completes a step's statistics with counts taken after it, and keeps them.
    fn record(&mut self, mut stats: StepStats, started: Instant) {
        stats.bodies = self.state.bodies.len();
        stats.contacts = self.state.contacts.len();
        stats.touching_contacts = self.state.contacts.touching_count();
        stats.sleeping_bodies = self.state.bodies.len() - self.state.body_sets.asleep_start();
        stats.kinetic_energy = self.awake_bodies().iter().map(Body::kinetic_energy).sum();
        stats.times.total = started.elapsed();
        self.stats = stats;
    }

    /// The awake set of bodies: what a step moves.
    fn awake_bodies(&self) -> &[Body] {
        &self.state.bodies.as_slice()[self.state.body_sets.awake()]
    }

    /// Runs the configured solver over every moving body and touching contact; returns how
    /// many contact points it solved and the work its effects did.
    fn solve(&mut self, dt: Real, awake_joints: &[solver::AwakeJoint]) -> solver::StepReport {
        let effects = self.state.settings.effects;
        let environment = Environment {
            gravity: effects
                .contains(Effect::Gravity)
                .then_some(self.state.settings.gravity),
            drag: effects
                .contains(Effect::Drag)
                .then_some(self.state.settings.drag),
            friction: effects.contains(Effect::Friction),
            restitution: effects.contains(Effect::Restitution),
        };
        let (contacts, body_indices, colors) = self.state.contacts.awake_mut_and_colors();
        let set = solver::AwakeSet {
            bodies: self.state.bodies.as_mut_slice(),
            awake: self.state.body_sets.awake(),
            contacts,
            body_indices,
            colors: &colors,
            joints: self.state.joints.as_mut_slice(),
            awake_joints,
        };
        solver::step(
            &self.state.settings.solver,
            environment,
            set,
            dt,
            &mut self.solver_workspace,
        )
    }

    /// Creates contacts for pairs of colliders whose enlarged boxes began to overlap; returns
    /// how many candidate pairs the broadphase met and how many contacts it created.
    fn find_pairs(&mut self, pairs: &mut Vec<(ColliderHandle, ColliderHandle)>) -> (usize, usize) {
        let contacts = &self.state.contacts;
        let candidates = self
            .state
            .broadphase
            .update_pairs_into(|a, b| contacts.contains(a, b), pairs);
        let mut created = 0;
        for &(a, b) in pairs.iter() {
            let (Some(collider_a), Some(collider_b)) =
                (self.state.colliders.get(a), self.state.colliders.get(b))
            else {
                continue;
            };
            // Collision filters were applied by the broadphase; joints are a world matter.
            if self
                .state
                .joints
                .filters(collider_a.body(), collider_b.body())
            {
                continue;
            }
            let sets = self.state.body_sets;
            let awake = [collider_a, collider_b]
                .iter()
                .any(|c| sets.set_of(c.body_index()) == SolverSet::Awake);
            self.state
                .contacts
                .add((a, collider_a), (b, collider_b), awake);
            created += 1;
        }
        (candidates, created)
    }

    /// Places the colliders of the awake set, which moved this step, and their bodies' boxes,
    /// and finds for each, while it is at hand, what the broadphase must learn of it
    /// (`refits`, see [`refit`]).
    fn place_moved_colliders(&mut self, prediction: LookAhead, refits: &mut Vec<Option<Refit>>) {
        let reach = margin_for(&self.state.settings, BodyKind::Dynamic);
        let broadphase = &self.state.broadphase;
        place_awake_colliders(
            &mut self.state.bodies,
            self.state.body_sets.awake(),
            &mut self.state.colliders,
            self.state.collider_sets.awake(),
            refits,
            |handle, collider, body| refit(handle, collider, body, prediction, reach, broadphase),
        );
    }

    /// Finds again what the broadphase must learn of every awake collider ([`refit`]).
    fn find_refits(&self, prediction: LookAhead, refits: &mut Vec<Option<Refit>>) {
        let bodies = self.state.bodies.as_slice();
        let awake = self.state.collider_sets.awake();
        let broadphase = &self.state.broadphase;
        let reach = margin_for(&self.state.settings, BodyKind::Dynamic);
        map_zip_into(
            &self.state.colliders.handles()[awake.clone()],
            &self.state.colliders.as_slice()[awake],
            refits,
            CONTACTS_PER_TASK,
            |&handle, collider| {
                let body = &bodies[collider.body_index()];
                refit(handle, collider, body, prediction, reach, broadphase)
            },
        );
    }

    /// Finds again what the broadphase must learn of the colliders of the bodies at storage
    /// indices `moved`, all awake.
    fn refind_refits(
        &self,
        prediction: LookAhead,
        moved: impl Iterator<Item = usize>,
        refits: &mut [Option<Refit>],
    ) {
        let bodies = self.state.bodies.as_slice();
        let colliders = self.state.colliders.as_slice();
        let first = self.state.collider_sets.awake().start;
        let reach = margin_for(&self.state.settings, BodyKind::Dynamic);
        for body in moved.map(|index| &bodies[index]) {
            for &handle in body.colliders() {
                let Some(index) = self.state.colliders.dense_index(handle) else {
                    continue;
                };
                let collider = &colliders[index];
                refits[index - first] = refit(
                    handle,
                    collider,
                    body,
                    prediction,
                    reach,
                    &self.state.broadphase,
                );
            }
        }
    }

    /// Re-fits the broadphase entries of the awake colliders that moved this step, as found
    /// into `refits` (see [`refit`]): in collider order, each that left its fat box is
    /// enlarged in place, and each runner is marked, for the next step's rebuild and pair
    /// update. Returns how many were enlarged.
    fn refresh_broadphase(&mut self, refits: &[Option<Refit>]) -> usize {
        let awake = self.state.collider_sets.awake();
        let handles = &self.state.colliders.handles()[awake];
        let mut moved = 0;
        for (&handle, refit) in handles.iter().zip(refits) {
            let Some(Refit {
                aabb,
                kind,
                leaves,
                runner,
            }) = *refit
            else {
                continue;
            };
            // A runner's box is swept over its next step and it looks for pairs every step, so
            // a margin would only widen its tree walks and the pairs they meet.
            let margin = if runner.is_some() {
                0.0
            } else {
                margin_for(&self.state.settings, kind)
            };
            if leaves {
                self.state.broadphase.enlarge(handle, kind, aabb, margin);
                moved += 1;
            }
            self.state
                .broadphase
                .set_runner(handle, runner, aabb.fattened(margin));
        }
        moved
    }
}

/// What the broadphase must learn of a collider (`handle`) of `body` that moved this step,
/// if anything: its box, grown to cover where it can get to in the time it looks ahead at its
/// body's present velocity, if that left its fat box, and whether it outruns its margin
/// (`reach`: a runner, whose pairs the look-ahead test judges). Reads only, so it may run on
/// all threads.
fn refit(
    handle: ColliderHandle,
    collider: &Collider,
    body: &Body,
    prediction: LookAhead,
    reach: Real,
    broadphase: &BroadPhase,
) -> Option<Refit> {
    if body.kind() == BodyKind::Static {
        return None;
    }
    let stride = Stride::of(body, prediction.for_body(body));
    let aabb = stride.map_or(collider.aabb(), |s| s.sweep(collider.aabb()));
    let leaves = broadphase.needs_update(handle, body.kind(), &aabb);
    // A runner runs on until it is well below the speed that made it one, so that a body
    // near that speed does not make and drop its pairs step after step.
    let was_runner = broadphase.is_runner(handle);
    let threshold = if was_runner {
        reach * RUNNER_STOP_FRACTION
    } else {
        reach
    };
    let runner = stride.filter(|s| s.reach() > threshold).map(|s| Motion {
        aabb: collider.aabb().fattened(reach),
        shift: s.shift,
        turn: s.turn,
    });
    (leaves || runner.is_some() || was_runner).then_some(Refit {
        aabb,
        kind: body.kind(),
        leaves,
        runner,
    })
}

/// What the broadphase must learn of a collider that moved in a step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Refit {
    /// Its box, grown to cover where its body can take it next step.
    aabb: Aabb,
    /// Its body's kind.
    kind: BodyKind,
    /// `aabb` left its fat box (or its body changed kind).
    leaves: bool,
    /// Where it can go next step, if its body outruns the fat box's margin (see
    /// [`crate::geometry::look_ahead`]).
    runner: Option<Motion>,
}

/// How far a body's velocity takes it in a time.
#[derive(Debug, Clone, Copy)]
struct Stride {
    /// Its translation, m.
    shift: Vec2,
    /// How far its turn carries its farthest point, m.
    turn: Real,
}

impl Stride {
    /// `body`'s stride in `time` at its present velocity; none when there is no time to
    /// look ahead.
    fn of(body: &Body, time: Real) -> Option<Self> {
        (time != 0.0).then(|| Stride {
            shift: body.linear_velocity() * time,
            turn: body.angular_velocity().abs() * time * body.reach(),
        })
    }

    /// A box carried along the stride and grown by its turn: every point of it can reach.
    fn sweep(&self, aabb: Aabb) -> Aabb {
        let moved = Aabb::new(aabb.min + self.shift, aabb.max + self.shift);
        aabb.union(&moved).fattened(self.turn)
    }

    /// How far any point can move along it.
    fn reach(&self) -> Real {
        self.shift.norm() + self.turn
    }
}

/// Runs a stage and adds its wall time to `slot`.
fn timed<T>(slot: &mut std::time::Duration, stage: impl FnOnce() -> T) -> T {
    let clock = Instant::now();
    let result = stage();
    *slot += clock.elapsed();
    result
}
