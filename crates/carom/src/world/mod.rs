//! The world: bodies and their colliders, global settings, the step, and queries.

pub(crate) mod body_mut;
pub(crate) mod effects;
pub(crate) mod explosion;
pub(crate) mod islands;
pub(crate) mod joints;
pub(crate) mod queries;
#[cfg(feature = "serde")]
mod saved;
pub(crate) mod settings;
pub(crate) mod solver_sets;

use crate::collision::broadphase::BroadPhase;
use crate::collision::contact::{Contact, ContactEvent, ContactSet, ManifoldOptions};
use crate::collision::continuous::{self, Pose};
use crate::collision::hits::{HitEvent, find_hits};
use crate::collision::pre_solve::{PreSolveContact, PreSolveHook};
use crate::collision::sensor::{SensorEvent, SensorOverlap, Sensors};
use crate::constants::{
    CONTACTS_PER_TASK, ITEMS_PER_TASK, LINEAR_SLOP, RECYCLE_DISTANCE, RECYCLE_DISTANCE_CLASSIC,
};
use crate::dynamics::body::{Body, BodyDef, BodyHandle, BodyKind};
use crate::dynamics::collider::{
    Collider, ColliderDef, ColliderHandle, colliders_aabb, place_colliders,
};
use crate::dynamics::drag::DragModel;
use crate::dynamics::island::Islands;
use crate::error::{CaromError, check_finite_not_negative, check_finite_vec};
use crate::geometry::aabb::Aabb;
use crate::geometry::shape::WorldShape;
use crate::handle_map::HandleMap;
use crate::joint::store::JointStore;
use crate::math::{Real, Vec2};
use crate::parallel::{for_each_mut, map_zip_into};
use crate::solver::{self, Environment, SolverKind, SolverParams};
use crate::stats::{Instant, StepStats};
use crate::world::body_mut::BodyMut;
use crate::world::effects::{Effect, Effects};
use crate::world::islands::IslandScratch;
use crate::world::settings::WorldSettings;
use crate::world::solver_sets::{SetBounds, SolverSet};

/// Where a ray, or a shape cast along a translation, meets a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CastHit {
    /// The body hit.
    pub body: BodyHandle,
    /// Its collider that was met.
    pub collider: ColliderHandle,
    /// Where they meet, in world coordinates: a ray's entry point, or the point a cast shape
    /// touches, on the collider's surface.
    pub point: Vec2,
    /// The collider's outward unit normal there.
    pub normal: Vec2,
    /// How far along the ray or translation, in `[0, 1]`: the cast shape moved by this
    /// fraction of its translation just touches the collider (0 when it already overlaps it).
    pub fraction: Real,
}

/// A physics world: create bodies in it, step it, query it.
///
/// With the `serde` feature a world saves and restores whole, in any serde format: a restored
/// world steps on exactly as the saved one would have (the same state, bit for bit). The
/// pre-solve hook is code and is not saved; set it again after restoring. Reading checks that
/// the saved world holds together and answers [`CaromError::BadSave`] when it does not.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(into = "saved::SavedWorld", try_from = "saved::SavedWorld")
)]
pub struct World {
    /// Stored in solver sets: static, awake, asleep (see [`solver_sets`]).
    bodies: HandleMap<BodyHandle, Body>,
    /// Stored in the same sets as their bodies.
    colliders: HandleMap<ColliderHandle, Collider>,
    joints: JointStore,
    /// The dynamic bodies' islands.
    islands: Islands,
    island_scratch: IslandScratch,
    body_sets: SetBounds,
    collider_sets: SetBounds,
    broadphase: BroadPhase,
    contacts: ContactSet,
    settings: WorldSettings,
    time: f64,
    step_count: u64,
    stats: StepStats,
    /// The solver's memory, reused from step to step.
    solver_workspace: solver::Workspace,
    /// The other stages' memory, reused from step to step.
    scratch: StepScratch,
    /// How many colliders ask for hit events: with none, a step looks for none.
    hit_event_colliders: usize,
    /// The hits of the last step.
    hit_events: Vec<HitEvent>,
    /// The sensor colliders, which the broadphase does not hold, and what overlaps them.
    sensors: Sensors,
    /// The user's say over the contacts of colliders that opt in.
    pre_solve: Option<PreSolveHook>,
}

/// What the stages of a step work in besides the solver, kept so a step in steady state
/// allocates nothing.
#[derive(Debug, Clone, Default)]
struct StepScratch {
    /// New pairs from the broadphase.
    pairs: Vec<(ColliderHandle, ColliderHandle)>,
    /// Awake bodies' poses at the start of the step (for continuous collision).
    starts: Vec<Pose>,
    /// The shape a sweep places along its path (its memory reused from step to step).
    swept: Option<WorldShape>,
    /// Sleeping islands a moving body touched.
    wake: Vec<u32>,
    /// The joints solved this step.
    awake_joints: Vec<solver::AwakeJoint>,
    /// Per awake collider, its predicted box if it left its fat box (or its body changed
    /// kind), to re-fit in the broadphase.
    refits: Vec<Option<(Aabb, BodyKind)>>,
}

fn check_settings(settings: &WorldSettings) -> Result<(), CaromError> {
    check_finite_vec("gravity", settings.gravity)?;
    settings.solver.validate()?;
    check_finite_not_negative("speculative distance", settings.speculative_distance)?;
    check_finite_not_negative("AABB margin", settings.aabb_margin)?;
    check_finite_not_negative("hit event threshold", settings.hit_event_threshold)?;
    Ok(())
}

/// How much the broadphase enlarges the box of a collider of a body of this kind.
pub(crate) fn margin_for(settings: &WorldSettings, kind: BodyKind) -> Real {
    match kind {
        BodyKind::Static => settings.speculative_distance,
        BodyKind::Kinematic | BodyKind::Dynamic => {
            settings.aabb_margin.max(settings.speculative_distance)
        }
    }
}

impl World {
    /// An empty world with default settings (gravity `(0, -10)`).
    pub fn new() -> Self {
        World::default()
    }

    /// An empty world with the given settings.
    pub fn with_settings(settings: WorldSettings) -> Result<Self, CaromError> {
        check_settings(&settings)?;
        Ok(World {
            settings,
            ..World::default()
        })
    }

    /// The settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Replaces the settings (checked first). Turning sleeping off wakes every body.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<(), CaromError> {
        check_settings(&settings)?;
        self.settings = settings;
        self.set_effects(settings.effects);
        Ok(())
    }

    /// The effects simulated.
    pub fn effects(&self) -> Effects {
        self.settings.effects
    }

    /// Chooses the effects simulated; the rest are not computed at all. Turning sleeping off
    /// wakes every body.
    pub fn set_effects(&mut self, effects: Effects) {
        self.settings.effects = effects;
        if !effects.contains(Effect::Sleeping) {
            self.wake_all();
        }
    }

    /// Switches one effect on or off.
    pub fn set_effect(&mut self, effect: Effect, on: bool) {
        let mut effects = self.settings.effects;
        effects.set(effect, on);
        self.set_effects(effects);
    }

    /// Wakes every sleeping body.
    pub fn wake_all(&mut self) {
        self.wake_all_islands();
    }

    /// What the last step did and what each stage cost.
    pub fn stats(&self) -> &StepStats {
        &self.stats
    }

    /// Gravity, m/s².
    pub fn gravity(&self) -> Vec2 {
        self.settings.gravity
    }

    /// Sets gravity (finite).
    pub fn set_gravity(&mut self, gravity: Vec2) -> Result<(), CaromError> {
        self.settings.gravity = check_finite_vec("gravity", gravity)?;
        Ok(())
    }

    /// Chooses the drag law.
    pub fn set_drag_model(&mut self, model: DragModel) {
        self.settings.drag = model;
    }

    /// Adds a body with its colliders; the definition is checked first, and nothing is added
    /// if any of it is wrong.
    ///
    /// # Errors
    /// No collider, a bad shape, non-finite placement or velocity, a dynamic body without mass
    /// (no collider with a positive density), or a negative density, friction, restitution or
    /// drag coefficient.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyHandle, CaromError> {
        let handle = self.bodies.next_handle();
        let mut body = Body::new(handle, &def)?;
        let starts_awake = def.awake;
        let transform = body.transform();
        let index = self.bodies.len();
        let parts: Vec<Collider> = def
            .colliders
            .into_iter()
            .map(|collider| Collider::new(handle, index, collider, &transform))
            .collect();
        body.rebuild_mass(parts.iter())?;
        let handle = self.bodies.insert(body);
        for collider in parts {
            let collider = self.colliders.insert(collider);
            self.note_added(collider);
            self.bodies
                .get_mut(handle)
                .expect("just inserted")
                .attach(collider);
        }
        // Stored last, in the sleeping set; then moved into its own.
        let index = self.settle_body(index);
        if self.bodies.as_slice()[index].is_dynamic() {
            let island = self.create_island_for(index);
            if !starts_awake {
                self.sleep_island(island);
            }
        }
        self.place_colliders_of(handle);
        let body = self.bodies.get(handle).expect("just inserted");
        let margin = margin_for(&self.settings, body.kind());
        for &collider in body.colliders() {
            let attached = self.colliders.get(collider).expect("attached");
            if attached.is_sensor() {
                continue;
            }
            self.broadphase
                .insert(collider, handle, body.kind(), attached.aabb(), margin);
            self.broadphase.set_filter(collider, attached.filter());
        }
        Ok(handle)
    }

    /// Removes a body with its colliders and joints and returns it. Its contacts end
    /// (reported after the next step), and the sleeping bodies it touched or was joined to
    /// wake.
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<Body, CaromError> {
        self.bodies.checked_index(handle)?;
        self.remove_joints_of(handle);
        self.wake_touching(handle);
        let index = self.bodies.checked_index(handle).expect("checked");
        let index = self.prepare_removal(index);
        let body = self.bodies.remove(handle).expect("checked");
        self.contacts.remove_body(handle);
        self.apply_touch_changes();
        for &collider in body.colliders() {
            if let Some(removed) = self.colliders.remove(collider) {
                self.note_removed(collider, &removed);
            }
            self.broadphase.remove(collider);
        }
        // The last body moved into the hole: its colliders follow it.
        if let Some(moved) = self.bodies.as_slice().get(index) {
            for &collider in moved.colliders() {
                if let Some(c) = self.colliders.get_mut(collider) {
                    c.set_body_index(index);
                }
            }
        }
        Ok(body)
    }

    /// Attaches another collider to a body; its mass, centre of mass and inertia follow.
    ///
    /// # Errors
    /// A stale body handle, a bad definition, or a dynamic body left without mass.
    pub fn add_collider(
        &mut self,
        body: BodyHandle,
        def: ColliderDef,
    ) -> Result<ColliderHandle, CaromError> {
        let index = self.bodies.checked_index(body)?;
        def.validate()?;
        let owner = &self.bodies.as_slice()[index];
        let collider = Collider::new(body, index, def, &owner.transform());
        let mut updated = owner.clone();
        let existing: Vec<&Collider> = owner
            .colliders()
            .iter()
            .filter_map(|&c| self.colliders.get(c))
            .collect();
        updated.rebuild_mass(existing.into_iter().chain(std::iter::once(&collider)))?;
        let handle = self.colliders.insert(collider);
        self.note_added(handle);
        updated.attach(handle);
        updated.wake_up();
        let kind = updated.kind();
        self.bodies.as_mut_slice()[index] = updated;
        self.wake_body(index);
        let index = self.bodies.checked_index(body).expect("live");
        self.settle_body(index);
        self.place_colliders_of(body);
        let attached = self.colliders.get(handle).expect("just inserted");
        if !attached.is_sensor() {
            let (aabb, filter) = (attached.aabb(), attached.filter());
            self.broadphase
                .insert(handle, body, kind, aabb, margin_for(&self.settings, kind));
            self.broadphase.set_filter(handle, filter);
        }
        Ok(handle)
    }

    /// Detaches a collider from its body and returns it; the body's mass follows. Its contacts
    /// end (reported after the next step).
    ///
    /// # Errors
    /// A stale handle, the body's last collider (remove the body instead), or a dynamic body
    /// left without mass.
    pub fn remove_collider(&mut self, handle: ColliderHandle) -> Result<Collider, CaromError> {
        let collider = self.colliders.get(handle).ok_or(CaromError::StaleHandle {
            what: "collider",
            index: handle.index(),
            generation: handle.generation(),
        })?;
        let body = collider.body();
        let owner = self.bodies.get(body).expect("a collider's body is live");
        if owner.colliders().len() == 1 {
            return Err(CaromError::NoCollider);
        }
        let mut updated = owner.clone();
        updated.detach(handle);
        let remaining: Vec<&Collider> = updated
            .colliders()
            .iter()
            .filter_map(|&c| self.colliders.get(c))
            .collect();
        updated.rebuild_mass(remaining.into_iter())?;
        updated.wake_up();
        *self.bodies.get_mut(body).expect("live") = updated;
        let index = self.bodies.checked_index(body).expect("live");
        self.wake_body(index);
        self.wake_touching(body);
        self.contacts.remove_collider(body, handle);
        self.apply_touch_changes();
        self.broadphase.remove(handle);
        self.prepare_collider_removal(handle);
        let removed = self.colliders.remove(handle).expect("checked");
        self.note_removed(handle, &removed);
        self.place_colliders_of(body);
        Ok(removed)
    }

    /// Changes what a collider collides with: its contacts the new filter forbids end (reported
    /// after the next step), and it is looked at again for pairs the filter now allows.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_filter(
        &mut self,
        handle: ColliderHandle,
        filter: crate::CollisionFilter,
    ) -> Result<(), CaromError> {
        let index = self.colliders.checked_index(handle)?;
        let collider = &mut self.colliders.as_mut_slice()[index];
        collider.set_filter(filter);
        let body = collider.body();
        let colliders = &self.colliders;
        self.contacts.remove_where(body, |c| {
            let (Some(a), Some(b)) = (colliders.get(c.collider_a()), colliders.get(c.collider_b()))
            else {
                return false;
            };
            !a.filter().collides_with(&b.filter())
        });
        let index = self.bodies.checked_index(body).expect("live");
        self.wake_body(index);
        self.apply_touch_changes();
        self.broadphase.set_filter(handle, filter);
        Ok(())
    }

    /// Changes a collider's density; its body's mass, centre of mass and inertia follow.
    ///
    /// # Errors
    /// A stale handle, a density that is negative or not finite, or a dynamic body left
    /// without mass; the density is then left as it was.
    pub fn set_collider_density(
        &mut self,
        handle: ColliderHandle,
        density: Real,
    ) -> Result<(), CaromError> {
        crate::dynamics::collider::check_non_negative("density", density)?;
        let index = self.colliders.checked_index(handle)?;
        let collider = &mut self.colliders.as_mut_slice()[index];
        let previous = collider.density();
        collider.set_density(density);
        let body = collider.body();
        if let Err(e) = self.rebuild_mass_of(body) {
            self.colliders
                .get_mut(handle)
                .expect("live")
                .set_density(previous);
            return Err(e);
        }
        let index = self.bodies.checked_index(body).expect("live");
        self.wake_body(index);
        Ok(())
    }

    /// Changes how a body moves: its mass is rebuilt, a static body stops, and its colliders
    /// move to the broadphase tree of the new kind.
    ///
    /// # Errors
    /// A stale handle, or a dynamic body without mass; the kind is then left as it was.
    pub fn set_body_kind(&mut self, handle: BodyHandle, kind: BodyKind) -> Result<(), CaromError> {
        let index = self.bodies.checked_index(handle)?;
        let previous = self.bodies.as_slice()[index].clone();
        self.bodies.as_mut_slice()[index].set_kind_unchecked(kind);
        if let Err(e) = self.rebuild_mass_of(handle) {
            self.bodies.as_mut_slice()[index] = previous;
            return Err(e);
        }
        // Its island wakes, and the body goes to its new kind's set and island.
        self.wake_body(index);
        let index = self.bodies.checked_index(handle).expect("live");
        let (was, is) = (previous.is_dynamic(), kind == BodyKind::Dynamic);
        if was && !is {
            self.leave_island(index);
        }
        let index = self.settle_body(index);
        self.repaint_contacts(handle);
        if is && !was {
            self.join_touching_islands(index);
        }
        self.place_colliders_of(handle);
        let body = self.bodies.get(handle).expect("live");
        let margin = margin_for(&self.settings, kind);
        for &collider in body.colliders() {
            let aabb = self.colliders.get(collider).expect("attached").aabb();
            self.broadphase.update(collider, kind, aabb, margin);
        }
        Ok(())
    }

    /// Notes a collider just added to the world among those asking for the optional events
    /// and the sensors, so a step does their work only when some ask.
    fn note_added(&mut self, handle: ColliderHandle) {
        let Some(collider) = self.colliders.get(handle) else {
            return;
        };
        self.hit_event_colliders += usize::from(collider.hit_events());
        if collider.is_sensor() {
            self.sensors.add(handle);
        }
    }

    /// Forgets a collider just removed from the world (as `removed`): a sensor's overlaps end.
    fn note_removed(&mut self, handle: ColliderHandle, removed: &Collider) {
        self.hit_event_colliders -= usize::from(removed.hit_events());
        if removed.is_sensor() {
            self.sensors.remove(handle);
        }
    }

    /// Rebuilds a body's mass from its colliders.
    fn rebuild_mass_of(&mut self, handle: BodyHandle) -> Result<(), CaromError> {
        let index = self.bodies.checked_index(handle)?;
        let colliders = &self.colliders;
        let body = &mut self.bodies.as_mut_slice()[index];
        let attached: Vec<ColliderHandle> = body.colliders().to_vec();
        body.rebuild_mass(attached.iter().filter_map(|&c| colliders.get(c)))
    }

    /// Places a body's colliders where the body is, and its box around them.
    fn place_colliders_of(&mut self, handle: BodyHandle) {
        let Some(body) = self.bodies.get_mut(handle) else {
            return;
        };
        body.set_aabb(place_colliders(body, &mut self.colliders));
    }

    /// The body behind a handle, unless it was removed.
    pub fn body(&self, handle: BodyHandle) -> Option<&Body> {
        self.bodies.get(handle)
    }

    /// The body behind a handle, to change, unless it was removed. When the borrow ends, its
    /// colliders follow wherever it was moved, so the next step and queries see it there.
    pub fn body_mut(&mut self, handle: BodyHandle) -> Option<BodyMut<'_>> {
        let index = self.bodies.dense_index(handle)?;
        Some(BodyMut::new(self, index))
    }

    /// The collider behind a handle, unless it was removed.
    pub fn collider(&self, handle: ColliderHandle) -> Option<&Collider> {
        self.colliders.get(handle)
    }

    /// The collider behind a handle, to change its friction or restitution (its density
    /// through [`World::set_collider_density`], as the body's mass depends on it).
    pub fn collider_mut(&mut self, handle: ColliderHandle) -> Option<&mut Collider> {
        self.colliders.get_mut(handle)
    }

    /// Every collider, in handle order: the order they were added, a removed collider's
    /// place taken by a later one. The order does not change as bodies sleep and wake.
    pub fn colliders(&self) -> impl ExactSizeIterator<Item = &Collider> {
        self.colliders.iter_by_handle()
    }

    /// True when the handle refers to a body of this world.
    pub fn contains(&self, handle: BodyHandle) -> bool {
        self.bodies.contains(handle)
    }

    /// Every body, in handle order: the order they were added, a removed body's place taken
    /// by a later one. The order does not change as bodies sleep and wake (it is also draw
    /// order: later is on top).
    pub fn bodies(&self) -> impl ExactSizeIterator<Item = &Body> {
        self.bodies.iter_by_handle()
    }

    /// How many bodies there are.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Every contact: pairs of colliders whose enlarged boxes overlap, touching or not.
    pub fn contacts(&self) -> impl ExactSizeIterator<Item = &Contact> {
        self.contacts.iter()
    }

    /// Contacts began and ended during the last step (and by removals before it).
    pub fn contact_events(&self) -> &[ContactEvent] {
        self.contacts.events()
    }

    /// What began and stopped overlapping each sensor during the last step (and the ends of
    /// sensors removed before it), sensor by sensor in the order they were added, each
    /// sensor's in visitor handle order.
    pub fn sensor_events(&self) -> &[SensorEvent] {
        self.sensors.events()
    }

    /// What overlaps a sensor as of the last step, in visitor handle order.
    ///
    /// # Errors
    /// A stale handle, or a collider that is not a sensor.
    pub fn sensor_overlaps(&self, sensor: ColliderHandle) -> Result<&[SensorOverlap], CaromError> {
        self.colliders.checked_index(sensor)?;
        self.sensors.overlaps(sensor).ok_or(CaromError::NotASensor {
            index: sensor.index(),
            generation: sensor.generation(),
        })
    }

    /// Sets the pre-solve hook, replacing any: each step, right after the narrowphase, it is
    /// shown every contact with points (speculative ones included) of a collider that opted in
    /// ([`ColliderDef::pre_solve`]), and returning false disables that contact for the step
    /// (no impulse, nothing warm started from it, no touching). It runs on the narrowphase's
    /// threads, in no set order: keep it a pure function of what it is shown (and of state
    /// changed only between steps) and the world stays deterministic. A clone of the world
    /// shares the hook. See [`PreSolveContact`].
    ///
    /// ```
    /// use carom::{BodyDef, Shape, World, vec2};
    ///
    /// let mut world = World::new();
    /// // A floor that only holds what comes down on its top (its normal points up to B).
    /// world.add_body(BodyDef::static_body(Shape::rect(5.0, 0.1)).pre_solve(true))?;
    /// world.set_pre_solve(|contact| contact.manifold.normal.y > 0.7);
    /// let ball = world.add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(0.0, 2.0)))?;
    /// for _ in 0..120 {
    ///     world.step(1.0 / 60.0)?;
    /// }
    /// assert!((world.body(ball).unwrap().position().y - 0.35).abs() < 0.01);
    /// # Ok::<(), carom::CaromError>(())
    /// ```
    pub fn set_pre_solve(
        &mut self,
        hook: impl Fn(&PreSolveContact) -> bool + Send + Sync + 'static,
    ) {
        self.pre_solve = Some(PreSolveHook::new(hook));
    }

    /// Removes the pre-solve hook: every contact is solved again.
    pub fn clear_pre_solve(&mut self) {
        self.pre_solve = None;
    }

    /// The hard hits of the last step on colliders that ask for them
    /// ([`ColliderDef::hit_events`]), in contact storage order (the same from run to run).
    pub fn hit_events(&self) -> &[HitEvent] {
        &self.hit_events
    }

    /// The broadphase, for inspection (fat boxes, tree shape) by carom's own tests.
    #[cfg(any(test, feature = "testing"))]
    pub fn broadphase(&self) -> &BroadPhase {
        &self.broadphase
    }

    /// Simulated time so far, in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// How many steps were taken.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    /// The solver settings.
    pub fn solver(&self) -> &SolverParams {
        &self.settings.solver
    }

    /// Replaces the solver settings (checked first); takes effect at the next step.
    pub fn set_solver(&mut self, params: SolverParams) -> Result<(), CaromError> {
        params.validate()?;
        self.settings.solver = params;
        Ok(())
    }

    /// Advances the world by `dt` seconds.
    ///
    /// The stages, in order, each over the awake set only: find new pairs in the broadphase;
    /// build contact manifolds in the narrowphase (waking the sleeping islands a moving body
    /// touched, joining the islands of contacts that started touching); solve (integrate
    /// forces into velocities, resolve contacts and then joints colour by colour, integrate
    /// positions, in substeps for soft step); report the hard hits, if some collider asks;
    /// remove the joints pulled past their break thresholds; continuous collision for fast bodies; place the moved colliders and refresh
    /// the broadphase from them; put resting islands to sleep; find what overlaps each sensor.
    ///
    /// # Errors
    /// A time step that is not finite and positive; the world is left untouched.
    pub fn step(&mut self, dt: Real) -> Result<(), CaromError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(CaromError::OutOfRange {
                name: "time step",
                expected: "finite and positive",
                value: dt,
            });
        }
        let started = Instant::now();
        let mut stats = StepStats::default();
        let times = &mut stats.times;
        self.contacts.begin_step();
        self.sensors.begin_step();
        self.hit_events.clear();

        let mut scratch = std::mem::take(&mut self.scratch);

        timed(&mut times.broadphase, || {
            self.find_pairs(&mut scratch.pairs)
        });
        let effects = self.settings.effects;
        let continuous = effects.contains(Effect::Continuous);
        // With continuous collision, contacts look a step ahead: a face point's margin reaches
        // as far as the pair can close in a step, and moving bodies' boxes cover where they
        // are going, so an impact at any speed has its contact before it happens.
        let prediction = if continuous { dt } else { 0.0 };
        stats.max_penetration = timed(&mut times.narrowphase, || {
            self.build_manifolds(prediction, &mut scratch.wake)
        });
        if continuous {
            self.poses(&mut scratch.starts);
        }
        self.awake_joints(&mut scratch.awake_joints);
        let solved = timed(&mut times.solve, || {
            let report = self.solve(dt, &scratch.awake_joints);
            self.place_moved_colliders();
            report
        });
        (stats.contact_points, stats.work) = (solved.points, solved.work);
        if self.hit_event_colliders > 0 {
            let (contacts, body_indices) = self.contacts.awake_and_bodies();
            let threshold = self.settings.hit_event_threshold;
            let bodies = self.bodies.as_slice();
            find_hits(
                contacts,
                body_indices,
                bodies,
                threshold,
                &mut self.hit_events,
            );
        }
        stats.joints = solved.joints;
        self.break_joints(&scratch.awake_joints);
        (times.prepare, times.store) = (solved.prepare, solved.store);
        if continuous {
            (stats.continuous_impacts, stats.work.sweeps) = timed(&mut times.continuous, || {
                continuous::solve_continuous(
                    &mut self.bodies,
                    self.body_sets.awake(),
                    &mut self.colliders,
                    &scratch.starts,
                    &mut scratch.swept,
                    &self.broadphase,
                    LINEAR_SLOP,
                    self.pre_solve.is_some(),
                )
            });
        }
        timed(&mut times.broadphase, || {
            self.refresh_broadphase(prediction, &mut scratch.refits)
        });
        if effects.contains(Effect::Sleeping) {
            stats.work.sleep_checks = timed(&mut times.sleep, || self.update_sleep(dt));
        }
        self.sensors
            .update(&self.bodies, &self.colliders, &self.broadphase);

        self.scratch = scratch;
        self.record(stats, started);
        self.time += dt as f64;
        self.step_count += 1;
        Ok(())
    }

    /// Rebuilds the manifolds of every pair where something moves, and wakes the sleeping
    /// islands a moving body touched so they join this step; returns the deepest overlap.
    fn build_manifolds(&mut self, prediction: Real, wake: &mut Vec<u32>) -> Real {
        wake.clear();
        let deepest = self.contacts.update(
            &self.bodies,
            &self.colliders,
            &self.broadphase,
            ManifoldOptions {
                margin: self.settings.speculative_distance,
                prediction,
                recycling: self.settings.contact_recycling.then(|| {
                    if self.settings.solver.effective_kind() == SolverKind::SoftStep {
                        RECYCLE_DISTANCE
                    } else {
                        RECYCLE_DISTANCE_CLASSIC
                    }
                }),
                pre_solve: self.pre_solve.as_ref(),
            },
            wake,
        );
        wake.sort_unstable();
        wake.dedup();
        for &island in wake.iter() {
            self.wake_island(island);
        }
        if !wake.is_empty() {
            let bodies = &self.bodies;
            self.contacts.find_body_indices(|body| {
                bodies
                    .dense_index(body)
                    .expect("contacts only join live bodies")
            });
        }
        // Islands join as their contacts start touching (after the waking, so a sleeping
        // island that is touched joins awake).
        self.apply_touch_changes();
        deepest
    }

    /// Completes a step's statistics with counts taken after it, and keeps them.
    fn record(&mut self, mut stats: StepStats, started: Instant) {
        stats.bodies = self.bodies.len();
        stats.contacts = self.contacts.len();
        stats.touching_contacts = self.contacts.touching_count();
        stats.sleeping_bodies = self.bodies.len() - self.body_sets.asleep_start();
        stats.kinetic_energy = self.awake_bodies().iter().map(Body::kinetic_energy).sum();
        stats.times.total = started.elapsed();
        self.stats = stats;
    }

    /// The awake set of bodies: what a step moves.
    fn awake_bodies(&self) -> &[Body] {
        &self.bodies.as_slice()[self.body_sets.awake()]
    }

    /// Every awake body's pose, in storage order, into `poses`.
    fn poses(&self, poses: &mut Vec<Pose>) {
        poses.clear();
        poses.extend(self.awake_bodies().iter().map(Pose::of));
    }

    /// Runs the configured solver over every moving body and touching contact; returns how
    /// many contact points it solved and the work its effects did.
    fn solve(&mut self, dt: Real, awake_joints: &[solver::AwakeJoint]) -> solver::StepReport {
        let effects = self.settings.effects;
        let environment = Environment {
            gravity: effects
                .contains(Effect::Gravity)
                .then_some(self.settings.gravity),
            drag: effects.contains(Effect::Drag).then_some(self.settings.drag),
            friction: effects.contains(Effect::Friction),
            restitution: effects.contains(Effect::Restitution),
        };
        let (contacts, body_indices, colors) = self.contacts.awake_mut_and_colors();
        let set = solver::AwakeSet {
            bodies: self.bodies.as_mut_slice(),
            awake: self.body_sets.awake(),
            contacts,
            body_indices,
            colors: &colors,
            joints: self.joints.as_mut_slice(),
            awake_joints,
        };
        solver::step(
            &self.settings.solver,
            environment,
            set,
            dt,
            &mut self.solver_workspace,
        )
    }

    /// Creates contacts for pairs of colliders whose enlarged boxes began to overlap.
    fn find_pairs(&mut self, pairs: &mut Vec<(ColliderHandle, ColliderHandle)>) {
        let contacts = &self.contacts;
        self.broadphase
            .update_pairs_into(|a, b| contacts.contains(a, b), pairs);
        for &(a, b) in pairs.iter() {
            let (Some(collider_a), Some(collider_b)) =
                (self.colliders.get(a), self.colliders.get(b))
            else {
                continue;
            };
            // Collision filters were applied by the broadphase; joints are a world matter.
            if self.joints.filters(collider_a.body(), collider_b.body()) {
                continue;
            }
            let sets = self.body_sets;
            let awake = [collider_a, collider_b]
                .iter()
                .any(|c| sets.set_of(c.body_index()) == SolverSet::Awake);
            self.contacts.add((a, collider_a), (b, collider_b), awake);
        }
    }

    /// Places the colliders of the awake set, which moved this step, and their bodies' boxes.
    fn place_moved_colliders(&mut self) {
        let bodies = self.bodies.as_slice();
        for_each_mut(
            &mut self.colliders.as_mut_slice()[self.collider_sets.awake()],
            CONTACTS_PER_TASK,
            |collider| collider.place(&bodies[collider.body_index()].transform()),
        );
        let colliders = &self.colliders;
        for_each_mut(
            &mut self.bodies.as_mut_slice()[self.body_sets.awake()],
            ITEMS_PER_TASK,
            |body| body.set_aabb(colliders_aabb(body, colliders)),
        );
    }

    /// Re-fits the broadphase entries of colliders that moved this step, each box covering
    /// where its collider can get to in `prediction` seconds at its body's present velocity:
    /// which ones left their fat boxes is found on all threads (into `refits`), then only
    /// those are re-fitted, in collider order.
    fn refresh_broadphase(&mut self, prediction: Real, refits: &mut Vec<Option<(Aabb, BodyKind)>>) {
        let bodies = self.bodies.as_slice();
        let awake = self.collider_sets.awake();
        let handles = &self.colliders.handles()[awake.clone()];
        let broadphase = &self.broadphase;
        map_zip_into(
            handles,
            &self.colliders.as_slice()[awake],
            refits,
            CONTACTS_PER_TASK,
            |&handle, collider| {
                let body = &bodies[collider.body_index()];
                if body.kind() == BodyKind::Static {
                    return None;
                }
                let aabb = predicted_aabb(body, collider.aabb(), prediction);
                broadphase
                    .needs_update(handle, body.kind(), &aabb)
                    .then_some((aabb, body.kind()))
            },
        );
        for (&handle, refit) in handles.iter().zip(refits.iter()) {
            if let &Some((aabb, kind)) = refit {
                let margin = margin_for(&self.settings, kind);
                self.broadphase.update(handle, kind, aabb, margin);
            }
        }
    }

    /// A fingerprint of the simulation state: FNV-1a over every body's position, rotation and
    /// velocities, bit for bit, in handle order. Equal runs give equal hashes.
    pub fn state_hash(&self) -> u64 {
        let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
        let mut mix = |value: Real| {
            for byte in value.to_bits().to_le_bytes() {
                hash = (hash ^ byte as u64).wrapping_mul(0x0000_0100_0000_01b3);
            }
        };
        for body in self.bodies() {
            let (p, q, v) = (body.position(), body.rotation(), body.linear_velocity());
            for value in [p.x, p.y, q.re, q.im, v.x, v.y, body.angular_velocity()] {
                mix(value);
            }
        }
        hash
    }

    /// The body under a world point, for grabbing with the mouse.
    ///
    /// Dynamic bodies win over kinematic ones and those over static ones; among equals the one
    /// latest in handle order (drawn on top) wins.
    pub fn body_at(&self, point: Vec2) -> Option<BodyHandle> {
        let rank = |kind: BodyKind| match kind {
            BodyKind::Static => 0,
            BodyKind::Kinematic => 1,
            BodyKind::Dynamic => 2,
        };
        self.bodies_at(point)
            .into_iter()
            .filter_map(|h| Some((self.bodies.get(h)?.kind(), h)))
            .max_by_key(|&(kind, h)| (rank(kind), h.index()))
            .map(|(_, h)| h)
    }

    /// Every body with a collider containing the point, in handle order.
    pub fn bodies_at(&self, point: Vec2) -> Vec<BodyHandle> {
        let probe = Aabb::new(point, point);
        let mut found = Vec::new();
        self.broadphase.query(&probe, |handle| {
            let Some(collider) = self.colliders.get(handle) else {
                return;
            };
            let Some(body) = self.bodies.get(collider.body()) else {
                return;
            };
            if collider.contains(point, body.local_point(point)) {
                found.push(collider.body());
            }
        });
        found.sort_unstable_by_key(|h| h.index());
        found.dedup();
        found
    }
}

/// A collider's box, grown to cover where its body can take it in `time` at its present
/// velocity.
fn predicted_aabb(body: &Body, aabb: Aabb, time: Real) -> Aabb {
    if time == 0.0 {
        return aabb;
    }
    let shift = body.linear_velocity() * time;
    let moved = Aabb::new(aabb.min + shift, aabb.max + shift);
    let turn = body.angular_velocity().abs() * time * body.reach();
    aabb.union(&moved).fattened(turn)
}

/// Runs a stage and adds its wall time to `slot`.
fn timed<T>(slot: &mut std::time::Duration, stage: impl FnOnce() -> T) -> T {
    let clock = Instant::now();
    let result = stage();
    *slot += clock.elapsed();
    result
}

/// What the solver starts a step from: every body, the awake set's range, the awake contacts,
/// where their bodies are now, and their colours.
#[cfg(test)]
pub(crate) type SolverInputs<'a> = (
    &'a [Body],
    std::ops::Range<usize>,
    &'a [Contact],
    Vec<crate::collision::contact::BodyIndices>,
    crate::collision::contact_layout::ColorRanges,
);

/// What the solver starts a step from, for tests of the solver's parts.
#[cfg(test)]
impl World {
    /// The body itself, to put it in states tests need (asleep, say).
    pub(crate) fn body_raw_mut(&mut self, handle: BodyHandle) -> Option<&mut Body> {
        self.bodies.get_mut(handle)
    }

    /// What the solver starts a step from.
    pub(crate) fn solver_inputs(&self) -> SolverInputs<'_> {
        let contacts = self.contacts.awake();
        let bodies = &self.bodies;
        let body_indices = contacts
            .iter()
            .map(|c| {
                crate::collision::contact::body_indices_of(c, |body| {
                    bodies.dense_index(body).unwrap()
                })
            })
            .collect();
        let awake = self.body_sets.awake();
        let colors = self.contacts.color_ranges();
        (
            self.bodies.as_slice(),
            awake,
            contacts,
            body_indices,
            colors,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    #[test]
    fn bad_time_steps_and_settings_are_refused() {
        let mut world = World::new();
        for dt in [0.0, -1.0, Real::NAN, Real::INFINITY] {
            assert!(world.step(dt).is_err());
        }
        assert_eq!(world.step_count(), 0);
        let bad = WorldSettings {
            speculative_distance: -1.0,
            ..WorldSettings::default()
        };
        assert!(World::with_settings(bad).is_err());
        assert!(world.set_settings(bad).is_err());
    }

    #[test]
    fn static_bodies_do_not_fall_and_kinematic_ones_keep_their_velocity() {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
            .unwrap();
        let platform = world
            .add_body(
                BodyDef::kinematic(Shape::rect(1.0, 0.1))
                    .linear_velocity(vec2(1.0, 0.0))
                    .angular_velocity(0.5),
            )
            .unwrap();
        for _ in 0..60 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert_eq!(world.body(ground).unwrap().position(), Vec2::zeros());
        let p = world.body(platform).unwrap();
        assert!((p.position() - vec2(1.0, 0.0)).norm() < 1e-4);
        assert_eq!(p.linear_velocity(), vec2(1.0, 0.0));
        assert!((p.angle() - 0.5).abs() < 1e-4);
        // Static and kinematic bodies never pair up.
        assert_eq!(world.contacts().len(), 0);
    }

    #[test]
    fn body_at_prefers_dynamic_and_topmost() {
        let mut world = World::new();
        let floor = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 5.0)))
            .unwrap();
        let low = world
            .add_body(BodyDef::dynamic(Shape::circle(1.0)))
            .unwrap();
        let high = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)))
            .unwrap();
        assert_eq!(world.body_at(vec2(0.0, 0.0)), Some(high));
        assert_eq!(world.body_at(vec2(0.8, 0.0)), Some(low));
        assert_eq!(world.body_at(vec2(3.0, 3.0)), Some(floor));
        assert_eq!(world.body_at(vec2(30.0, 3.0)), None);
        assert_eq!(world.bodies_at(vec2(0.0, 0.0)), vec![floor, low, high]);
    }

    #[test]
    fn queries_see_bodies_moved_since_the_last_step() {
        let mut world = World::new();
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)))
            .unwrap();
        world
            .body_mut(ball)
            .unwrap()
            .set_position(vec2(20.0, 0.0))
            .unwrap();
        assert_eq!(world.body_at(vec2(20.0, 0.2)), Some(ball));
        assert_eq!(world.body_at(vec2(0.0, 0.0)), None);
        let hit = world
            .cast_ray(&Ray::new(vec2(10.0, 0.0), vec2(20.0, 0.0)))
            .unwrap();
        assert_eq!(hit.body, ball);
        world.step(1.0 / 60.0).unwrap();
        assert!(world.body_at(vec2(20.0, 0.0)).is_some());
        assert!(
            world
                .broadphase()
                .fat_aabb(world.body(ball).unwrap().colliders()[0])
                .unwrap()
                .contains_point(vec2(20.0, 0.0))
        );
    }

    #[test]
    fn cast_ray_finds_the_closest_body() {
        let mut world = World::new();
        let near = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(2.0, 0.0)))
            .unwrap();
        let far = world
            .add_body(
                BodyDef::dynamic(Shape::circle(0.5))
                    .position(vec2(5.0, 0.0))
                    .angle(1.0),
            )
            .unwrap();
        let hit = world
            .cast_ray(&Ray::new(vec2(0.0, 0.0), vec2(10.0, 0.0)))
            .unwrap();
        assert_eq!(hit.body, near);
        assert!((hit.point - vec2(1.5, 0.0)).norm() < 1e-6);
        assert!((hit.normal - vec2(-1.0, 0.0)).norm() < 1e-6);
        assert!((hit.fraction - 0.15).abs() < 1e-6);
        world.remove_body(near).unwrap();
        let hit = world
            .cast_ray(&Ray::new(vec2(0.0, 0.0), vec2(10.0, 0.0)))
            .unwrap();
        assert_eq!(hit.body, far);
        assert!((hit.point - vec2(4.5, 0.0)).norm() < 1e-5);
        assert!(
            world
                .cast_ray(&Ray::new(vec2(0.0, 3.0), vec2(10.0, 0.0)))
                .is_none()
        );
        assert!(
            world
                .cast_ray(&Ray::new(vec2(Real::NAN, 0.0), vec2(1.0, 0.0)))
                .is_none()
        );
    }

    #[test]
    fn contacts_begin_and_end_with_events() {
        let mut world = World::with_settings(WorldSettings {
            gravity: Vec2::zeros(),
            ..WorldSettings::default()
        })
        .unwrap();
        let wall = world
            .add_body(BodyDef::static_body(Shape::rect(0.1, 2.0)))
            .unwrap();
        // Bounces off the wall: one begin, one end.
        let ball = world
            .add_body(
                BodyDef::dynamic(Shape::circle(0.25))
                    .position(vec2(-2.0, 0.0))
                    .linear_velocity(vec2(3.0, 0.0))
                    .restitution(1.0),
            )
            .unwrap();
        let (mut begins, mut ends, mut touching_steps) = (0, 0, 0);
        for _ in 0..120 {
            world.step(1.0 / 60.0).unwrap();
            for event in world.contact_events() {
                match *event {
                    ContactEvent::Begin(pair) => {
                        assert_eq!((pair.body_a, pair.body_b), (wall, ball));
                        begins += 1;
                    }
                    ContactEvent::End { .. } => ends += 1,
                }
            }
            touching_steps += world.contacts().filter(|c| c.is_touching()).count();
        }
        assert_eq!((begins, ends), (1, 1));
        // In and out of the 2 cm speculative margin at 3 m/s: a handful of steps.
        assert!((1..=4).contains(&touching_steps), "{touching_steps}");
        let v = world.body(ball).unwrap().linear_velocity();
        assert!((v.x + 3.0).abs() < 0.05, "bounced back at {v:?}");
        assert_eq!(world.contacts().len(), 0, "the pair is dropped once apart");
    }

    #[test]
    fn removing_bodies_drops_exactly_their_contacts() {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let mut bodies = Vec::new();
        for i in 0..120 {
            let (x, y) = ((i % 12) as Real * 0.9 - 5.0, (i / 12) as Real * 0.9 + 0.5);
            let shape = if i % 2 == 0 {
                Shape::circle(0.45)
            } else {
                Shape::rect(0.4, 0.4)
            };
            bodies.push(
                world
                    .add_body(BodyDef::dynamic(shape).position(vec2(x, y)))
                    .unwrap(),
            );
        }
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
        }
        let doomed: Vec<BodyHandle> = bodies.iter().copied().step_by(3).collect();
        let of_doomed = |c: &Contact| doomed.contains(&c.body_a()) || doomed.contains(&c.body_b());
        let kept = world.contacts().filter(|c| !of_doomed(c)).count();
        assert!(
            world.contacts().len() > kept + 40,
            "the doomed bodies have contacts"
        );
        for &handle in &doomed {
            world.remove_body(handle).unwrap();
        }
        assert_eq!(world.contacts().len(), kept);
        assert!(
            world
                .contacts()
                .all(|c| world.contains(c.body_a()) && world.contains(c.body_b()))
        );
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert!(
            world
                .contacts()
                .all(|c| world.contains(c.body_a()) && world.contains(c.body_b()))
        );
    }

    #[test]
    fn removing_a_touching_body_ends_its_contact_after_the_next_step() {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let crate_box = world
            .add_body(BodyDef::kinematic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5)))
            .unwrap();
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(3.0, 0.49)))
            .unwrap();
        world.step(1.0 / 60.0).unwrap();
        let began = world
            .contact_events()
            .iter()
            .find(|e| matches!(e, ContactEvent::Begin(p) if (p.body_a, p.body_b) == (ground, ball)))
            .copied()
            .expect("the ball touches the ground");
        world.remove_body(ball).unwrap();
        world.step(1.0 / 60.0).unwrap();
        assert_eq!(world.contact_events(), &[ContactEvent::End(began.pair())]);
        assert!(world.contains(crate_box));
        assert_eq!(world.contacts().len(), 0);
    }
}
