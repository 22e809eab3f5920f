//! The world: bodies and their colliders, global settings, the step, and queries.

pub(crate) mod body_mut;
mod capacity;
pub(crate) mod collider_mut;
pub(crate) mod effects;
pub(crate) mod explosion;
mod island_split;
pub(crate) mod islands;
pub(crate) mod joint_mut;
pub(crate) mod joints;
pub(crate) mod queries;
#[cfg(feature = "serde")]
mod saved;
pub(crate) mod settings;
mod sleep;
pub(crate) mod snapshot;
pub(crate) mod solver_sets;
mod state;
mod step;

use state::WorldState;
use step::StepScratch;

use crate::collision::broadphase::BroadPhase;
use crate::collision::contact::{Contact, ContactEvent};
use crate::collision::hits::HitEvent;
use crate::collision::pre_solve::{PreSolveContact, PreSolveHook};
use crate::collision::sensor::{SensorEvent, SensorOverlap};
use crate::constants::MAX_SHAPE_EXTENT;
use crate::dynamics::body::{Body, BodyHandle, BodyKind};
use crate::dynamics::body_def::BodyDef;
use crate::dynamics::collider::{Collider, ColliderDef, ColliderHandle, place_colliders};
use crate::dynamics::surface::{MaterialMixer, Mixers};
use crate::error::{CaromError, check_finite_not_negative, check_finite_vec, check_within};
use crate::math::{Real, Vec2};
use crate::solver::{self, SolverParams};
use crate::stats::StepStats;
use crate::world::body_mut::BodyMut;
use crate::world::collider_mut::ColliderMut;
use crate::world::effects::{Effect, Effects};
use crate::world::islands::IslandScratch;
use crate::world::settings::WorldSettings;

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
    /// Everything that outlives a step: what a snapshot copies and a saved world holds.
    state: WorldState,
    island_scratch: IslandScratch,
    stats: StepStats,
    /// The solver's memory, reused from step to step.
    solver_workspace: solver::Workspace,
    /// The other stages' memory, reused from step to step.
    scratch: StepScratch,
    /// The user's say over the contacts of colliders that opt in.
    pre_solve: Option<PreSolveHook>,
    /// The most the world has held at once, or made room for ([`World::high_water`]).
    high_water: crate::Capacity,
}

fn check_settings(settings: &WorldSettings) -> Result<(), CaromError> {
    check_finite_vec("gravity", settings.gravity)?;
    for value in [settings.gravity.x, settings.gravity.y] {
        let bound = crate::constants::MAX_ACCELERATION;
        check_within(
            "gravity",
            value,
            -bound..=bound,
            "within 1e6 m/s² either way",
        )?;
    }
    settings.solver.validate()?;
    // Every collider's box grows by these, so they are held to a shape's size.
    let (margins, expected) = (0.0..=MAX_SHAPE_EXTENT, "from 0 to 1e5 m");
    check_within(
        "speculative distance",
        settings.speculative_distance,
        margins.clone(),
        expected,
    )?;
    check_within("AABB margin", settings.aabb_margin, margins, expected)?;
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
            state: WorldState {
                settings,
                ..WorldState::default()
            },
            ..World::default()
        })
    }

    /// The settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.state.settings
    }

    /// Changes the settings: `change` edits a copy, which is checked and then takes effect
    /// at the next step (turning sleeping off wakes every body at once). This is the one way
    /// to change gravity, the solver, the effects simulated or any other setting.
    ///
    /// # Errors
    /// A value out of range (the first one found is named); the settings are then left as
    /// they were.
    pub fn update_settings(
        &mut self,
        change: impl FnOnce(&mut WorldSettings),
    ) -> Result<(), CaromError> {
        let mut settings = self.state.settings;
        change(&mut settings);
        check_settings(&settings)?;
        self.state.settings = settings;
        if !settings.effects.contains(Effect::Sleeping) {
            self.wake_all();
        }
        Ok(())
    }

    /// The effects simulated.
    pub fn effects(&self) -> Effects {
        self.state.settings.effects
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
        self.state.settings.gravity
    }

    /// Adds a body with its colliders; the definition is checked first, and nothing is added
    /// if any of it is wrong.
    ///
    /// # Errors
    /// No collider, a bad shape, non-finite placement or velocity, a dynamic body without mass
    /// (no collider with a positive density), or a negative density, friction, restitution or
    /// drag coefficient.
    #[allow(
        clippy::expect_used,
        reason = "the body and its colliders were inserted just above"
    )]
    pub fn add_body(&mut self, mut def: BodyDef) -> Result<BodyHandle, CaromError> {
        // Colliders pushed onto `def.colliders` directly take the body's material too.
        let every = def.every_collider;
        for collider in &mut def.colliders {
            every.apply(collider);
        }
        let handle = self.state.bodies.next_handle();
        let mut body = Body::new(handle, &def)?;
        let starts_awake = def.awake;
        let transform = body.transform();
        let index = self.state.bodies.len();
        let parts: Vec<Collider> = def
            .colliders
            .into_iter()
            .map(|collider| Collider::new(handle, index, collider, &transform))
            .collect();
        body.rebuild_mass(parts.iter())?;
        let handle = self.state.bodies.insert(body);
        for collider in parts {
            let collider = self.state.colliders.insert(collider);
            self.note_added(collider);
            self.state
                .bodies
                .get_mut(handle)
                .expect("just inserted")
                .attach(collider);
        }
        // Stored last, in the sleeping set; then moved into its own.
        let index = self.settle_body(index);
        if self.state.bodies.as_slice()[index].is_dynamic() {
            let island = self.create_island_for(index);
            if !starts_awake {
                self.sleep_island(island);
            }
        }
        self.place_colliders_of(handle);
        let body = self.state.bodies.get(handle).expect("just inserted");
        let margin = margin_for(&self.state.settings, body.kind());
        for &collider in body.colliders() {
            let attached = self.state.colliders.get(collider).expect("attached");
            if attached.is_sensor() {
                continue;
            }
            self.state
                .broadphase
                .insert(collider, handle, body.kind(), attached.aabb(), margin);
            self.state
                .broadphase
                .set_filter(collider, attached.filter());
        }
        Ok(handle)
    }

    /// Removes a body with its colliders and joints and returns it. Its contacts end
    /// (reported after the next step), and the sleeping bodies it touched or was joined to
    /// wake.
    #[allow(
        clippy::expect_used,
        reason = "the handle was checked first, and a stale one refused with an error"
    )]
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<Body, CaromError> {
        self.state.bodies.checked_index(handle)?;
        self.remove_joints_of(handle);
        self.wake_touching(handle);
        let index = self.state.bodies.checked_index(handle).expect("checked");
        let index = self.prepare_removal(index);
        let body = self.state.bodies.remove(handle).expect("checked");
        self.state.contacts.remove_body(handle);
        self.apply_touch_changes();
        for &collider in body.colliders() {
            if let Some(removed) = self.state.colliders.remove(collider) {
                self.note_removed(collider, &removed);
            }
            self.state.broadphase.remove(collider);
        }
        // The last body moved into the hole: its colliders follow it.
        if let Some(moved) = self.state.bodies.as_slice().get(index) {
            for &collider in moved.colliders() {
                if let Some(c) = self.state.colliders.get_mut(collider) {
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
    #[allow(
        clippy::expect_used,
        reason = "the body was checked first, and the collider inserted just above"
    )]
    pub fn add_collider(
        &mut self,
        body: BodyHandle,
        def: ColliderDef,
    ) -> Result<ColliderHandle, CaromError> {
        let index = self.state.bodies.checked_index(body)?;
        def.validate()?;
        let owner = &self.state.bodies.as_slice()[index];
        let collider = Collider::new(body, index, def, &owner.transform());
        let mut updated = owner.clone();
        let existing: Vec<&Collider> = owner
            .colliders()
            .iter()
            .filter_map(|&c| self.state.colliders.get(c))
            .collect();
        updated.rebuild_mass(existing.into_iter().chain(std::iter::once(&collider)))?;
        let handle = self.state.colliders.insert(collider);
        self.note_added(handle);
        updated.attach(handle);
        updated.wake_up();
        let kind = updated.kind();
        self.state.bodies.as_mut_slice()[index] = updated;
        self.wake_body(index);
        let index = self.state.bodies.checked_index(body).expect("live");
        self.settle_body(index);
        self.place_colliders_of(body);
        let attached = self.state.colliders.get(handle).expect("just inserted");
        if !attached.is_sensor() {
            let (aabb, filter) = (attached.aabb(), attached.filter());
            self.state.broadphase.insert(
                handle,
                body,
                kind,
                aabb,
                margin_for(&self.state.settings, kind),
            );
            self.state.broadphase.set_filter(handle, filter);
        }
        Ok(handle)
    }

    /// Detaches a collider from its body and returns it; the body's mass follows. Its contacts
    /// end (reported after the next step).
    ///
    /// # Errors
    /// A stale handle, the body's last collider (remove the body instead), or a dynamic body
    /// left without mass.
    #[allow(
        clippy::expect_used,
        reason = "the collider was checked first, and a live collider's body is live"
    )]
    pub fn remove_collider(&mut self, handle: ColliderHandle) -> Result<Collider, CaromError> {
        let collider = self
            .state
            .colliders
            .get(handle)
            .ok_or(CaromError::StaleHandle {
                what: "collider",
                index: handle.index(),
                generation: handle.generation(),
            })?;
        let body = collider.body();
        let owner = self
            .state
            .bodies
            .get(body)
            .expect("a collider's body is live");
        if owner.colliders().len() == 1 {
            return Err(CaromError::NoCollider);
        }
        let mut updated = owner.clone();
        updated.detach(handle);
        let remaining: Vec<&Collider> = updated
            .colliders()
            .iter()
            .filter_map(|&c| self.state.colliders.get(c))
            .collect();
        updated.rebuild_mass(remaining.into_iter())?;
        updated.wake_up();
        *self.state.bodies.get_mut(body).expect("live") = updated;
        let index = self.state.bodies.checked_index(body).expect("live");
        self.wake_body(index);
        self.wake_touching(body);
        self.state.contacts.remove_collider(body, handle);
        self.apply_touch_changes();
        self.state.broadphase.remove(handle);
        self.prepare_collider_removal(handle);
        let removed = self.state.colliders.remove(handle).expect("checked");
        self.note_removed(handle, &removed);
        self.place_colliders_of(body);
        Ok(removed)
    }

    /// Changes how a body moves ([`BodyMut::set_kind`]).
    #[allow(
        clippy::expect_used,
        reason = "the body was checked first, and a body's colliders live while it does"
    )]
    pub(crate) fn set_body_kind(
        &mut self,
        handle: BodyHandle,
        kind: BodyKind,
    ) -> Result<(), CaromError> {
        let index = self.state.bodies.checked_index(handle)?;
        let previous = self.state.bodies.as_slice()[index].clone();
        self.state.bodies.as_mut_slice()[index].set_kind_unchecked(kind);
        if let Err(e) = self.rebuild_mass_of(handle) {
            self.state.bodies.as_mut_slice()[index] = previous;
            return Err(e);
        }
        // Its island wakes, and the body goes to its new kind's set and island.
        self.wake_body(index);
        let index = self.state.bodies.checked_index(handle).expect("live");
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
        let body = self.state.bodies.get(handle).expect("live");
        let margin = margin_for(&self.state.settings, kind);
        for &collider in body.colliders() {
            let aabb = self.state.colliders.get(collider).expect("attached").aabb();
            self.state.broadphase.update(collider, kind, aabb, margin);
        }
        Ok(())
    }

    /// Notes a collider just added to the world among those asking for the optional events
    /// and the sensors, so a step does their work only when some ask.
    fn note_added(&mut self, handle: ColliderHandle) {
        let Some(collider) = self.state.colliders.get(handle) else {
            return;
        };
        self.state.hit_event_colliders += usize::from(collider.hit_events());
        if collider.is_sensor() {
            self.state.sensors.add(handle);
        }
    }

    /// Forgets a collider just removed from the world (as `removed`): a sensor's overlaps end.
    fn note_removed(&mut self, handle: ColliderHandle, removed: &Collider) {
        self.state.hit_event_colliders -= usize::from(removed.hit_events());
        if removed.is_sensor() {
            self.state.sensors.remove(handle);
        }
    }

    /// Rebuilds a body's mass from its colliders.
    pub(crate) fn rebuild_mass_of(&mut self, handle: BodyHandle) -> Result<(), CaromError> {
        let index = self.state.bodies.checked_index(handle)?;
        let colliders = &self.state.colliders;
        let body = &mut self.state.bodies.as_mut_slice()[index];
        let attached: Vec<ColliderHandle> = body.colliders().to_vec();
        body.rebuild_mass(attached.iter().filter_map(|&c| colliders.get(c)))
    }

    /// Places a body's colliders where the body is, and its box around them.
    fn place_colliders_of(&mut self, handle: BodyHandle) {
        let Some(body) = self.state.bodies.get_mut(handle) else {
            return;
        };
        place_colliders(body, &mut self.state.colliders);
    }

    /// The body behind a handle, unless it was removed.
    pub fn body(&self, handle: BodyHandle) -> Option<&Body> {
        self.state.bodies.get(handle)
    }

    /// The body behind a handle, to change, unless it was removed. Each change that moves it
    /// places its colliders at once, so the next step and queries see it there.
    pub fn body_mut(&mut self, handle: BodyHandle) -> Option<BodyMut<'_>> {
        let index = self.state.bodies.dense_index(handle)?;
        Some(BodyMut::new(self, index))
    }

    /// The collider behind a handle, unless it was removed.
    pub fn collider(&self, handle: ColliderHandle) -> Option<&Collider> {
        self.state.colliders.get(handle)
    }

    /// The collider behind a handle, to change, unless it was removed. Each change that other
    /// state depends on (the body's mass, its contacts) updates that state at once.
    pub fn collider_mut(&mut self, handle: ColliderHandle) -> Option<ColliderMut<'_>> {
        self.state
            .colliders
            .contains(handle)
            .then(|| ColliderMut::new(self, handle))
    }

    /// Every collider, in handle order: the order they were added, a removed collider's
    /// place taken by a later one. The order does not change as bodies sleep and wake.
    pub fn colliders(&self) -> impl ExactSizeIterator<Item = &Collider> {
        self.state.colliders.iter_by_handle()
    }

    /// True when the handle refers to a body of this world.
    pub fn contains(&self, handle: BodyHandle) -> bool {
        self.state.bodies.contains(handle)
    }

    /// Every body, in handle order: the order they were added, a removed body's place taken
    /// by a later one. The order does not change as bodies sleep and wake (it is also draw
    /// order: later is on top).
    pub fn bodies(&self) -> impl ExactSizeIterator<Item = &Body> {
        self.state.bodies.iter_by_handle()
    }

    /// How many bodies there are.
    pub fn body_count(&self) -> usize {
        self.state.bodies.len()
    }

    /// Every contact: pairs of colliders whose enlarged boxes overlap, touching or not.
    pub fn contacts(&self) -> impl ExactSizeIterator<Item = &Contact> {
        self.state.contacts.iter()
    }

    /// Contacts began and ended during the last step (and by removals before it).
    pub fn contact_events(&self) -> &[ContactEvent] {
        self.state.contacts.events()
    }

    /// What began and stopped overlapping each sensor during the last step (and the ends of
    /// sensors removed before it), sensor by sensor in the order they were added, each
    /// sensor's in visitor handle order.
    pub fn sensor_events(&self) -> &[SensorEvent] {
        self.state.sensors.events()
    }

    /// What overlaps a sensor as of the last step, in visitor handle order.
    ///
    /// # Errors
    /// A stale handle, or a collider that is not a sensor.
    pub fn sensor_overlaps(&self, sensor: ColliderHandle) -> Result<&[SensorOverlap], CaromError> {
        self.state.colliders.checked_index(sensor)?;
        self.state
            .sensors
            .overlaps(sensor)
            .ok_or(CaromError::NotASensor {
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

    /// Mixes friction where two surfaces touch with `mixer` (given each surface's friction
    /// and [`crate::Surface::material`] id), or, with `None`, as the geometric mean. Every
    /// contact takes it at once. Not saved with the world: set it again after restoring one.
    ///
    /// ```
    /// use carom::{BodyDef, ColliderDef, Shape, Surface, World, vec2};
    ///
    /// const ICE: u64 = 1;
    /// let mut world = World::new();
    /// // Ice on anything is slippery, whatever the other surface's friction.
    /// world.set_friction_mixer(Some(|fa, a, fb, b| if a == ICE || b == ICE { 0.02 } else { (fa * fb).sqrt() }));
    /// let ice = Surface { material: ICE, ..Surface::default() };
    /// world.add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).surface(ice))?;
    /// let crate_ = world.add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 1.0)))?;
    /// world.body_mut(crate_).unwrap().set_linear_velocity(vec2(2.0, 0.0))?;
    /// for _ in 0..60 {
    ///     world.step(1.0 / 60.0)?;
    /// }
    /// // 0.02 × 10 m/s² slows it by 0.2 m/s in a second.
    /// assert!((world.body(crate_).unwrap().linear_velocity().x - 1.8).abs() < 0.02);
    /// # Ok::<(), carom::CaromError>(())
    /// ```
    pub fn set_friction_mixer(&mut self, mixer: Option<MaterialMixer>) {
        let mixers = Mixers {
            friction: mixer,
            ..self.state.contacts.mixers()
        };
        self.state
            .contacts
            .set_mixers(mixers, &self.state.colliders);
    }

    /// Mixes restitution where two surfaces touch with `mixer` (given each surface's
    /// restitution and material id), or, with `None`, as the larger. As
    /// [`World::set_friction_mixer`].
    pub fn set_restitution_mixer(&mut self, mixer: Option<MaterialMixer>) {
        let mixers = Mixers {
            restitution: mixer,
            ..self.state.contacts.mixers()
        };
        self.state
            .contacts
            .set_mixers(mixers, &self.state.colliders);
    }

    /// The hard hits of the last step on colliders that ask for them
    /// ([`ColliderDef::hit_events`]), in contact storage order (the same from run to run).
    pub fn hit_events(&self) -> &[HitEvent] {
        &self.state.hit_events
    }

    /// The broadphase, for inspection (fat boxes, tree shape) by carom's own tests.
    #[cfg(any(test, feature = "testing"))]
    pub fn broadphase(&self) -> &BroadPhase {
        &self.state.broadphase
    }

    /// The broadphase, for the queries outside this module (a character's).
    #[cfg(not(any(test, feature = "testing")))]
    pub(crate) fn broadphase(&self) -> &BroadPhase {
        &self.state.broadphase
    }

    /// Simulated time so far, in seconds.
    pub fn time(&self) -> f64 {
        self.state.time
    }

    /// How many steps were taken.
    pub fn step_count(&self) -> u64 {
        self.state.step_count
    }

    /// The solver settings.
    pub fn solver(&self) -> &SolverParams {
        &self.state.settings.solver
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
}

/// What the solver starts a step from: every body, the awake set's range, the awake contacts,
/// where their bodies are now, and their colours.
#[cfg(test)]
pub(crate) type SolverInputs<'a> = (
    &'a [Body],
    std::ops::Range<usize>,
    &'a [Contact],
    Vec<crate::collision::contact::BodyIndices>,
    crate::graph::layout::ColorRanges,
);

/// What the solver starts a step from, for tests of the solver's parts.
#[cfg(test)]
impl World {
    /// The body itself, to put it in states tests need (asleep, say).
    pub(crate) fn body_raw_mut(&mut self, handle: BodyHandle) -> Option<&mut Body> {
        self.state.bodies.get_mut(handle)
    }

    /// What the solver starts a step from.
    pub(crate) fn solver_inputs(&self) -> SolverInputs<'_> {
        let contacts = self.state.contacts.awake();
        let bodies = &self.state.bodies;
        let body_indices = contacts
            .iter()
            .map(|c| {
                crate::collision::contact::body_indices_of(c, |body| {
                    bodies.dense_index(body).unwrap()
                })
            })
            .collect();
        let awake = self.state.body_sets.awake();
        let colors = self.state.contacts.color_ranges();
        (
            self.state.bodies.as_slice(),
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
        assert!(world.update_settings(|s| *s = bad).is_err());
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
