//! Sensors: colliders that notice what overlaps them and never collide.
//!
//! A sensor ([`crate::ColliderDef::sensor`]) is kept out of the broadphase, so it never pairs
//! with anything: no contact, no narrowphase, no push, and queries, ray casts and continuous
//! collision do not see it. Instead, after each step, every sensor asks the broadphase which
//! colliders' boxes meet its own and keeps those it overlaps exactly (their shapes touch or
//! overlap), sorted by handle; comparing the list with the last step's gives the begin and end
//! events, sensor by sensor, each sensor's in handle order, so they come out the same from run
//! to run and on any number of threads. A world without sensors does none of this.
//!
//! Box2D's rules: a sensor sees the colliders of other bodies it could collide with, so a
//! sensor on a static or kinematic body sees dynamic bodies only, and one on a dynamic body
//! sees every kind; sensors do not see other sensors; the sensor's and the visitor's
//! collision filters must allow each other. A visitor that falls asleep inside stays where it
//! is, so it stays seen (no end). Removing a visitor ends its overlaps at the next step (the
//! sensor no longer finds it); removing a sensor ends all of its overlaps, reported after the
//! next step as removals' contact ends are.

use crate::clone_in_place::clone_in_place;
use crate::collision::broadphase::{BroadPhase, kinds_can_collide};
use crate::constants::SENSORS_PER_TASK;
use crate::dynamics::body::{Body, BodyHandle};
use crate::dynamics::collider::{Collider, ColliderHandle};
#[cfg(feature = "serde")]
use crate::error::CaromError;
use crate::geometry::query::distance::separation;
use crate::handle_map::HandleMap;
use crate::heap_bytes::{HeapBytes, array, nothing};
use crate::parallel::map_mut_into;

/// A collider overlapping a sensor: which sensor, which visitor, and their bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SensorOverlap {
    /// The sensor collider.
    pub sensor: ColliderHandle,
    /// The sensor's body.
    pub sensor_body: BodyHandle,
    /// The collider overlapping it.
    pub visitor: ColliderHandle,
    /// The visitor's body.
    pub visitor_body: BodyHandle,
}

/// A change in what overlaps a sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SensorEvent {
    /// A collider began to overlap a sensor.
    Begin(SensorOverlap),
    /// A collider stopped overlapping a sensor (or it, the sensor, or a body of theirs was
    /// removed).
    End(SensorOverlap),
}

impl SensorEvent {
    /// The sensor and visitor the event is about.
    pub fn overlap(&self) -> SensorOverlap {
        match *self {
            SensorEvent::Begin(overlap) | SensorEvent::End(overlap) => overlap,
        }
    }
}

/// One sensor and what overlaps it.
#[derive(Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Sensor {
    collider: ColliderHandle,
    /// What overlaps it now, sorted by visitor handle.
    overlaps: Vec<SensorOverlap>,
    /// What overlapped it a step ago (kept to reuse the memory).
    #[cfg_attr(feature = "serde", serde(skip))]
    previous: Vec<SensorOverlap>,
}

/// The sensors of a world, in the order they were added, and their events.
#[derive(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Sensors {
    sensors: Vec<Sensor>,
    /// Whether each sensor's overlaps changed in the last update (kept to reuse the memory).
    #[cfg_attr(feature = "serde", serde(skip))]
    changed: Vec<bool>,
    events: Vec<SensorEvent>,
    /// Events raised between steps (removing a sensor), reported after the next step.
    pending: Vec<SensorEvent>,
}

clone_in_place!(Sensor { collider, overlaps } keep { previous });
clone_in_place!(Sensors { sensors } roomy { events, pending } keep { changed });

impl HeapBytes for Sensor {
    fn heap_bytes(&self) -> usize {
        let Sensor {
            collider,
            overlaps,
            previous: _,
        } = self;
        nothing(collider) + array(overlaps)
    }
}

impl HeapBytes for Sensors {
    fn heap_bytes(&self) -> usize {
        let Sensors {
            sensors,
            changed: _,
            events,
            pending,
        } = self;
        sensors.heap_bytes() + array(events) + array(pending)
    }
}

impl Sensors {
    /// Starts watching a sensor collider; it sees nothing until the next step.
    pub(crate) fn add(&mut self, collider: ColliderHandle) {
        self.sensors.push(Sensor {
            collider,
            overlaps: Vec::new(),
            previous: Vec::new(),
        });
    }

    /// Stops watching a sensor collider that is being removed: each of its overlaps ends,
    /// reported after the next step.
    pub(crate) fn remove(&mut self, collider: ColliderHandle) {
        if let Some(at) = self.sensors.iter().position(|s| s.collider == collider) {
            let sensor = self.sensors.remove(at);
            let ends = sensor.overlaps.into_iter().map(SensorEvent::End);
            self.pending.extend(ends);
        }
    }

    /// What overlaps the sensor `collider` as of the last step, or `None` if it is not one.
    pub(crate) fn overlaps(&self, collider: ColliderHandle) -> Option<&[SensorOverlap]> {
        let sensor = self.sensors.iter().find(|s| s.collider == collider)?;
        Some(&sensor.overlaps)
    }

    /// Forgets last step's events; those raised since (by removals) become this step's.
    pub(crate) fn begin_step(&mut self) {
        self.events.clear();
        self.events.append(&mut self.pending);
    }

    /// The begin and end events of the last step, sensor by sensor.
    pub(crate) fn events(&self) -> &[SensorEvent] {
        &self.events
    }

    /// Finds what overlaps each sensor now (on all threads when there are many) and raises
    /// the events of what changed.
    pub(crate) fn update(
        &mut self,
        bodies: &HandleMap<BodyHandle, Body>,
        colliders: &HandleMap<ColliderHandle, Collider>,
        broadphase: &BroadPhase,
    ) {
        if self.sensors.is_empty() {
            return;
        }
        map_mut_into(
            &mut self.sensors,
            &mut self.changed,
            SENSORS_PER_TASK,
            |sensor| sensor.refresh(bodies, colliders, broadphase),
        );
        for (sensor, _) in self.sensors.iter().zip(&self.changed).filter(|(_, c)| **c) {
            diff(&sensor.previous, &sensor.overlaps, &mut self.events);
        }
    }
}

impl Sensor {
    /// Finds what overlaps the sensor now, keeping the last step's list; true if they differ.
    fn refresh(
        &mut self,
        bodies: &HandleMap<BodyHandle, Body>,
        colliders: &HandleMap<ColliderHandle, Collider>,
        broadphase: &BroadPhase,
    ) -> bool {
        std::mem::swap(&mut self.previous, &mut self.overlaps);
        self.overlaps.clear();
        let Some(sensor) = colliders.get(self.collider) else {
            return !self.previous.is_empty();
        };
        let all = bodies.as_slice();
        let sensor_body = &all[sensor.body_index()];
        let aabb = sensor.aabb();
        broadphase.query(&aabb, |handle| {
            let Some(visitor) = colliders.get(handle) else {
                return;
            };
            let visitor_body = &all[visitor.body_index()];
            let sees = visitor.body() != sensor.body()
                && kinds_can_collide(sensor_body.kind(), visitor_body.kind())
                && sensor.filter().collides_with(&visitor.filter())
                && visitor.aabb().overlaps(&aabb)
                && separation(sensor.world_shape(), visitor.world_shape()).separation <= 0.0;
            if sees {
                self.overlaps.push(SensorOverlap {
                    sensor: self.collider,
                    sensor_body: sensor.body(),
                    visitor: handle,
                    visitor_body: visitor.body(),
                });
            }
        });
        let key = |o: &SensorOverlap| (o.visitor.index(), o.visitor.generation());
        self.overlaps.sort_unstable_by_key(key);
        self.overlaps != self.previous
    }
}

/// The events that take a sensor from `before` to `after` (both sorted by visitor handle),
/// into `events`, in handle order.
fn diff(before: &[SensorOverlap], after: &[SensorOverlap], events: &mut Vec<SensorEvent>) {
    let key = |o: &SensorOverlap| (o.visitor.index(), o.visitor.generation());
    let (mut i, mut j) = (0, 0);
    loop {
        match (before.get(i), after.get(j)) {
            (None, None) => break,
            (Some(old), Some(new)) if key(old) == key(new) => {
                (i, j) = (i + 1, j + 1);
            }
            (Some(old), Some(new)) if key(old) < key(new) => {
                events.push(SensorEvent::End(*old));
                i += 1;
            }
            (Some(old), None) => {
                events.push(SensorEvent::End(*old));
                i += 1;
            }
            (_, Some(new)) => {
                events.push(SensorEvent::Begin(*new));
                j += 1;
            }
        }
    }
}

#[cfg(feature = "serde")]
impl Sensors {
    /// Checks sensors read from a saved world: each is a live sensor collider, listed once,
    /// and so is every sensor collider.
    pub(crate) fn check_saved(
        &self,
        colliders: &HandleMap<ColliderHandle, Collider>,
    ) -> Result<(), CaromError> {
        let mut listed: Vec<ColliderHandle> = self.sensors.iter().map(|s| s.collider).collect();
        listed.sort_unstable();
        let mut sensors: Vec<ColliderHandle> = colliders
            .handles()
            .iter()
            .copied()
            .filter(|&c| colliders.get(c).is_some_and(Collider::is_sensor))
            .collect();
        sensors.sort_unstable();
        if listed != sensors {
            return Err(CaromError::bad_save(
                "the sensors listed are not the sensor colliders",
            ));
        }
        Ok(())
    }
}
