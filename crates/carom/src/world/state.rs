//! What a world is between steps: every field that outlives a step, in one struct that the
//! world holds, a snapshot copies and a saved world writes, so that a field is added in one
//! place. What a step only works in (scratch memory, the solver's workspace, the last step's
//! figures) and the pre-solve hook, which is code, stay in [`World`](crate::World).

use crate::clone_in_place::copy_with_room;
use crate::collision::broadphase::BroadPhase;
use crate::collision::contact::ContactSet;
use crate::collision::hits::HitEvent;
use crate::collision::sensor::Sensors;
use crate::constants::COPY_ITEMS_PER_THREAD;
use crate::dynamics::body::{Body, BodyHandle};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::dynamics::island::Islands;
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, array, nothing};
use crate::joint::store::JointStore;
use crate::parallel::worth_sharing;
use crate::solver_set::SetBounds;
use crate::world::settings::WorldSettings;

/// Every part of a world that outlives a step.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub(crate) struct WorldState {
    pub settings: WorldSettings,
    pub time: f64,
    pub step_count: u64,
    /// Stored in solver sets: static, awake, asleep (see [`crate::solver_set`]).
    pub bodies: HandleMap<BodyHandle, Body>,
    /// Stored in the same sets as their bodies.
    pub colliders: HandleMap<ColliderHandle, Collider>,
    pub joints: JointStore,
    /// The dynamic bodies' islands.
    pub islands: Islands,
    pub body_sets: SetBounds,
    pub collider_sets: SetBounds,
    pub broadphase: BroadPhase,
    pub contacts: ContactSet,
    /// The sensor colliders, which the broadphase does not hold, and what overlaps them.
    pub sensors: Sensors,
    /// The hits of the last step.
    pub hit_events: Vec<HitEvent>,
    /// How many colliders ask for hit events: with none, a step looks for none. Not saved: a
    /// saved world counts its colliders again.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub hit_event_colliders: usize,
}

impl WorldState {
    /// Copies every part of `from` into this state, each into its old memory, so a state as
    /// large as `from` allocates nothing.
    pub(crate) fn copy_from(&mut self, from: &WorldState) {
        let WorldState {
            settings,
            time,
            step_count,
            bodies,
            colliders,
            joints,
            islands,
            body_sets,
            collider_sets,
            broadphase,
            contacts,
            sensors,
            hit_events,
            hit_event_colliders,
        } = self;
        settings.clone_from(&from.settings);
        *time = from.time;
        *step_count = from.step_count;
        *hit_event_colliders = from.hit_event_colliders;
        copy_with_room(hit_events, &from.hit_events);
        joints.clone_from(&from.joints);
        islands.clone_from(&from.islands);
        body_sets.clone_from(&from.body_sets);
        collider_sets.clone_from(&from.collider_sets);
        sensors.clone_from(&from.sensors);
        let mut copy_contacts = || contacts.clone_from(&from.contacts);
        let mut copy_bodies = || {
            bodies.clone_from(&from.bodies);
            colliders.clone_from(&from.colliders);
            broadphase.clone_from(&from.broadphase);
        };
        // The copy is bound by memory traffic, which a second core adds to.
        if worth_sharing(
            from.contacts.len() + from.bodies.len(),
            COPY_ITEMS_PER_THREAD,
        ) {
            rayon::join(copy_contacts, copy_bodies);
        } else {
            copy_contacts();
            copy_bodies();
        }
    }
}

impl HeapBytes for WorldState {
    fn heap_bytes(&self) -> usize {
        let WorldState {
            settings,
            time,
            step_count,
            bodies,
            colliders,
            joints,
            islands,
            body_sets,
            collider_sets,
            broadphase,
            contacts,
            sensors,
            hit_events,
            hit_event_colliders,
        } = self;
        nothing(settings)
            + nothing(time)
            + nothing(step_count)
            + bodies.heap_bytes()
            + colliders.heap_bytes()
            + joints.heap_bytes()
            + islands.heap_bytes()
            + nothing(body_sets)
            + nothing(collider_sets)
            + broadphase.heap_bytes()
            + contacts.heap_bytes()
            + sensors.heap_bytes()
            + array(hit_events)
            + nothing(hit_event_colliders)
    }
}
