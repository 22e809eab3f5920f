//! Room made ahead of time: how many bodies, colliders, contacts and joints a world holds
//! memory for, so that a step need not take memory from the heap as the world fills (Box2D's
//! `b2Capacity`), and the most a world has held so far, to reserve for the next run.

use crate::capacity::{Capacity, room};
use crate::error::CaromError;
use crate::world::World;

impl World {
    /// Makes room for `capacity` in every store and every buffer a step works in, so that
    /// after its first step (which makes the working memory of the threads it runs on) the
    /// world steps without taking anything from the heap while it holds no more than that.
    /// Not covered: the sensors' lists of what overlaps them. Room already made is kept; the
    /// world is otherwise unchanged (the same bits follow).
    ///
    /// # Errors
    /// [`CaromError::OutOfMemory`] when the heap cannot give the room asked for (what was made
    /// before it ran out is kept).
    pub fn reserve(&mut self, capacity: Capacity) -> Result<(), CaromError> {
        let Capacity {
            bodies,
            colliders,
            contacts,
            joints,
        } = capacity;
        let out_of_memory = |what: &'static str| move |_| CaromError::OutOfMemory { what };
        let state = &mut self.state;
        state
            .bodies
            .reserve(bodies)
            .map_err(out_of_memory("bodies"))?;
        state
            .colliders
            .reserve(colliders)
            .map_err(out_of_memory("colliders"))?;
        state
            .joints
            .reserve(joints)
            .map_err(out_of_memory("joints"))?;
        state
            .islands
            .reserve(bodies)
            .map_err(out_of_memory("islands"))?;
        state
            .broadphase
            .reserve(colliders, contacts)
            .map_err(out_of_memory("the broadphase"))?;
        state
            .contacts
            .reserve(contacts, bodies)
            .map_err(out_of_memory("contacts"))?;
        room(&mut state.hit_events, contacts).map_err(out_of_memory("hit events"))?;
        self.island_scratch
            .reserve(bodies)
            .map_err(out_of_memory("islands"))?;
        self.scratch
            .reserve(capacity)
            .map_err(out_of_memory("a step's buffers"))?;
        self.solver_workspace
            .reserve(bodies, contacts, joints)
            .map_err(out_of_memory("the solver's buffers"))?;
        self.high_water = self.high_water.max(capacity);
        Ok(())
    }

    /// The most bodies, colliders, contacts and joints this world has held at once (or made
    /// room for with [`World::reserve`]): what to reserve for a run like the ones it has
    /// made. Contacts are counted at their peak within a step, after the broadphase made the
    /// new ones and before the narrowphase ended the old.
    pub fn high_water(&self) -> Capacity {
        self.high_water.max(self.holds())
    }

    /// What the world holds now.
    pub(crate) fn holds(&self) -> Capacity {
        Capacity {
            bodies: self.state.bodies.len(),
            colliders: self.state.colliders.len(),
            contacts: self.state.contacts.len(),
            joints: self.state.joints.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body_def::BodyDef;
    use crate::geometry::shape::Shape;
    use crate::math::{Real, vec2};

    /// A floor with a column of `count` boxes resting on it.
    fn column(count: usize) -> World {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(10.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        for i in 0..count {
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.5 + i as Real)),
                )
                .unwrap();
        }
        world
    }

    #[test]
    fn room_the_heap_cannot_give_is_refused_with_an_error() {
        let mut world = column(3);
        let all = usize::MAX;
        for capacity in [
            Capacity {
                bodies: all,
                ..Capacity::default()
            },
            Capacity {
                colliders: all,
                ..Capacity::default()
            },
            Capacity {
                contacts: all,
                ..Capacity::default()
            },
            Capacity {
                joints: all,
                ..Capacity::default()
            },
        ] {
            assert!(
                matches!(world.reserve(capacity), Err(CaromError::OutOfMemory { .. })),
                "{capacity:?}"
            );
        }
        // The world goes on as before.
        world.step(1.0 / 60.0).unwrap();
        assert_eq!(world.body_count(), 4);
    }

    #[test]
    fn the_high_water_keeps_the_most_the_world_held() {
        let mut world = column(6);
        assert_eq!(world.high_water().bodies, 7);
        assert_eq!(world.high_water().colliders, 7);
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
        }
        // Six resting contacts: each box on the one below, the lowest on the floor.
        let held = world.stats().contacts;
        assert!(held >= 6, "{held} contacts");
        assert_eq!(world.high_water().contacts, held);
        // Taking the top half away leaves fewer of everything; the high water stays.
        let top: Vec<_> = world.bodies().skip(4).map(|b| b.handle()).collect();
        for body in top {
            world.remove_body(body).unwrap();
        }
        world.step(1.0 / 60.0).unwrap();
        assert!(world.stats().contacts < held);
        assert_eq!(
            world.high_water(),
            Capacity {
                bodies: 7,
                colliders: 7,
                contacts: held,
                joints: 0
            }
        );
        // Room reserved counts as held.
        let reserved = Capacity {
            bodies: 100,
            colliders: 120,
            contacts: 400,
            joints: 30,
        };
        world.reserve(reserved).unwrap();
        assert_eq!(world.high_water(), reserved);
    }

    #[test]
    fn room_reserved_changes_no_bit_of_the_run() {
        let (mut plain, mut reserved) = (column(12), column(12));
        reserved
            .reserve(Capacity {
                bodies: 5000,
                colliders: 6000,
                contacts: 20000,
                joints: 100,
            })
            .unwrap();
        for _ in 0..120 {
            plain.step(1.0 / 60.0).unwrap();
            reserved.step(1.0 / 60.0).unwrap();
        }
        assert_eq!(plain.state_hash(), reserved.state_hash());
    }
}
