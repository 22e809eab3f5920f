//! The world's side of joints: adding and removing them (with what that means for islands,
//! sleep and collisions between the joined bodies), finding the ones a step solves, and
//! breaking the ones pulled too hard.

use crate::constants::ITEMS_PER_TASK;
use crate::dynamics::body::BodyHandle;
use crate::error::CaromError;
use crate::joint::{Joint, JointDef, JointEvent, JointHandle};
use crate::parallel::{any, map_indexed_into};
use crate::solver::AwakeJoint;
use crate::world::World;
use crate::world::joint_mut::JointMut;

fn stale(handle: JointHandle) -> CaromError {
    CaromError::StaleHandle {
        what: "joint",
        index: handle.index(),
        generation: handle.generation(),
    }
}

impl World {
    /// Adds a joint, from a [`JointDef`] or a kind's own definition ([`crate::RevoluteJointDef`],
    /// ...); the definition is checked first (both bodies live and different except
    /// for a mouse joint, every setting finite and in range, only settings its kind has), and
    /// nothing is added if any of it is wrong. Both bodies wake. Unless the joint lets them
    /// collide, contacts between the two bodies end.
    #[allow(
        clippy::expect_used,
        reason = "both bodies were checked above, and a stale one refused with an error"
    )]
    pub fn add_joint(&mut self, def: impl Into<JointDef>) -> Result<JointHandle, CaromError> {
        let def: JointDef = def.into();
        let handle = self.state.joints.next_handle();
        let joint = def.build(
            handle,
            self.state.bodies.get(def.body_a),
            self.state.bodies.get(def.body_b),
        )?;
        let [a, b] = joint.bodies();
        let filters = !joint.collide_connected() && a != b;
        let set = self.joint_set_for(&joint);
        // Waking its bodies moves it on to the awake set if it has a dynamic body.
        let handle = self.state.joints.insert(joint, set);
        for body in [a, b] {
            let index = self.state.bodies.checked_index(body).expect("checked");
            self.wake_body(index);
        }
        self.link_islands(a, b);
        if filters {
            self.state.contacts.remove_between(a, b);
            self.apply_touch_changes();
        }
        Ok(handle)
    }

    /// Removes a joint and returns it. Its bodies wake; if it kept them from colliding, they
    /// may collide from the next step.
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint, CaromError> {
        let joint = self
            .state
            .joints
            .remove(handle)
            .ok_or_else(|| stale(handle))?;
        self.detach_joint(&joint);
        Ok(joint)
    }

    /// What removing `joint` means for its bodies: they wake, their island may have come
    /// apart, and if they did not collide they are looked at again for new pairs.
    fn detach_joint(&mut self, joint: &Joint) {
        let [a, b] = joint.bodies();
        for body in [a, b] {
            if let Some(index) = self.state.bodies.dense_index(body) {
                self.wake_body(index);
            }
        }
        if a != b {
            self.unlink_contact(a, b);
        }
        if !joint.collide_connected() && a != b {
            for body in [a, b] {
                let Some(body) = self.state.bodies.get(body) else {
                    continue;
                };
                for &collider in body.colliders() {
                    self.state.broadphase.requeue(collider);
                }
            }
        }
    }

    /// Removes every joint of a body (which is being removed).
    #[allow(
        clippy::expect_used,
        reason = "a body's joint list holds only live joints: removing a joint unlists it"
    )]
    pub(crate) fn remove_joints_of(&mut self, body: BodyHandle) {
        while let Some(&handle) = self.state.joints.of_body(body).first() {
            let joint = self
                .state
                .joints
                .remove(handle)
                .expect("listed joints live");
            self.detach_joint(&joint);
        }
    }

    /// The joint behind a handle, unless it was removed.
    pub fn joint(&self, handle: JointHandle) -> Option<&Joint> {
        self.state.joints.get(handle)
    }

    /// Every joint, in handle order.
    pub fn joints(&self) -> impl ExactSizeIterator<Item = &Joint> {
        self.state.joints.iter_by_handle()
    }

    /// How many joints there are.
    pub fn joint_count(&self) -> usize {
        self.state.joints.len()
    }

    /// The joints of a body.
    pub fn joints_of(&self, body: BodyHandle) -> &[JointHandle] {
        self.state.joints.of_body(body)
    }

    /// The joint behind a handle, to change, unless it was removed.
    pub fn joint_mut(&mut self, handle: JointHandle) -> Option<JointMut<'_>> {
        self.state.joints.get(handle)?;
        Some(JointMut::new(self, handle))
    }

    /// Wakes a joint's bodies, so they feel a change to it.
    pub(crate) fn wake_joint_bodies(&mut self, handle: JointHandle) {
        let Some(joint) = self.state.joints.get(handle) else {
            return;
        };
        for body in joint.bodies() {
            if let Some(index) = self.state.bodies.dense_index(body) {
                self.state.bodies.as_mut_slice()[index].wake_up();
                self.wake_body(index);
            }
        }
    }

    /// Joints broken in the last step.
    pub fn joint_events(&self) -> &[JointEvent] {
        &self.state.joints.events
    }

    /// The joints a step solves, into `awake`: the awake set of joints (those with an awake
    /// dynamic body), in storage order, with where their bodies are.
    #[allow(
        clippy::expect_used,
        reason = "a live joint's bodies are live: removing a body removes its joints"
    )]
    pub(crate) fn awake_joints(&self, awake: &mut Vec<AwakeJoint>) {
        let range = self.state.joints.awake();
        let joints = &self.state.joints.as_slice()[range.clone()];
        let bodies = &self.state.bodies;
        map_indexed_into(joints, awake, ITEMS_PER_TASK, |i, joint| AwakeJoint {
            index: (range.start + i) as u32,
            bodies: joint
                .bodies()
                .map(|body| bodies.dense_index(body).expect("joints join live bodies") as u32),
        });
    }

    /// Removes the joints the last step pulled past their break force or torque, reporting
    /// each; says whether any broke.
    #[allow(
        clippy::expect_used,
        reason = "the joints just solved are live: nothing removes a joint between the solve and here"
    )]
    pub(crate) fn break_joints(&mut self, solved: &[AwakeJoint]) -> bool {
        self.state.joints.events.clear();
        let joints = self.state.joints.as_slice();
        // Looked for on all threads; the few broken are then listed in order.
        if !any(solved, ITEMS_PER_TASK, |j| {
            joints[j.index as usize].is_broken()
        }) {
            return false;
        }
        let broken: Vec<JointHandle> = solved
            .iter()
            .map(|j| &joints[j.index as usize])
            .filter(|joint| joint.is_broken())
            .map(Joint::handle)
            .collect();
        for &handle in &broken {
            let joint = self
                .state
                .joints
                .remove(handle)
                .expect("solved joints live");
            self.detach_joint(&joint);
            self.state.joints.events.push(JointEvent::Broken {
                joint: handle,
                bodies: joint.bodies(),
                force: joint.reaction_force(),
                torque: joint.reaction_torque(),
            });
        }
        !broken.is_empty()
    }

    /// The bodies joined to `body`, into `out` (for islands).
    pub(crate) fn joint_partners(&self, body: BodyHandle, out: &mut Vec<BodyHandle>) {
        self.state.joints.partners(body, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body::BodyKind;
    use crate::dynamics::body_def::BodyDef;
    use crate::geometry::shape::Shape;
    use crate::math::{Real, vec2};

    const DT: Real = 1.0 / 60.0;

    /// A ground and `count` pairs of boxes resting on it, far apart, each pair hinged
    /// together and one of its boxes hinged to the ground: one island and two joints a pair.
    /// Returns the world and each pair's first box.
    fn hinged_pairs(count: usize) -> (World, Vec<BodyHandle>) {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(200.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let mut firsts = Vec::new();
        for i in 0..count {
            let x = i as Real * 5.0 - 100.0;
            let a = world
                .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x, 0.5)))
                .unwrap();
            let b = world
                .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(x + 1.0, 0.5)))
                .unwrap();
            world
                .add_joint(JointDef::revolute(a, b, vec2(x + 0.5, 0.5)))
                .unwrap();
            world
                .add_joint(JointDef::revolute(ground, a, vec2(x, 0.0)))
                .unwrap();
            firsts.push(a);
        }
        (world, firsts)
    }

    /// How many joints are stored in each set: static, awake, asleep.
    fn joints_by_set(world: &World) -> [usize; 3] {
        let mut counts = [0; 3];
        for i in 0..world.state.joints.len() {
            counts[world.state.joints.set_of(i) as usize] += 1;
        }
        counts
    }

    /// Many sleeping jointed islands and one awake: the step looks at the awake island's
    /// joints alone, and sleeping and waking move only an island's own joints.
    #[test]
    fn only_the_awake_islands_joints_are_visited() {
        let (mut world, firsts) = hinged_pairs(40);
        for _ in 0..120 {
            world.step(DT).unwrap();
        }
        world.check_sets();
        assert_eq!(world.stats().sleeping_bodies, 80, "every pair sleeps");
        assert_eq!(joints_by_set(&world), [0, 0, 80]);
        assert_eq!(world.stats().joints, 0);
        world
            .body_mut(firsts[17])
            .unwrap()
            .apply_impulse_at_center(vec2(0.0, 1.0))
            .unwrap();
        world.check_sets();
        assert_eq!(joints_by_set(&world), [0, 2, 78]);
        let mut awake = Vec::new();
        world.awake_joints(&mut awake);
        let woken: Vec<JointHandle> = world.joints_of(firsts[17]).to_vec();
        let mut solved: Vec<JointHandle> = awake
            .iter()
            .map(|j| world.state.joints.as_slice()[j.index as usize].handle())
            .collect();
        solved.sort();
        let mut expected = woken.clone();
        expected.sort();
        assert_eq!(solved, expected, "the woken pair's joints, and only those");
        world.step(DT).unwrap();
        world.check_sets();
        assert_eq!(world.stats().joints, 2);
        for _ in 0..120 {
            world.step(DT).unwrap();
        }
        world.check_sets();
        assert_eq!(joints_by_set(&world), [0, 0, 80], "asleep again");
    }

    /// While no island sleeps, joints are solved in the order they were added, removals
    /// moving the last one into the hole, whatever joints with no dynamic body come between:
    /// the order before joints were kept in sets, so no result changed for worlds that do not
    /// sleep.
    #[test]
    fn awake_joints_keep_the_order_they_were_added_in() {
        let (mut world, firsts) = hinged_pairs(6);
        let ground = world.bodies().next().unwrap().handle();
        let post = world
            .add_body(BodyDef::static_body(Shape::rect(0.5, 0.5)).position(vec2(0.0, 3.0)))
            .unwrap();
        let never_solved = world
            .add_joint(JointDef::weld(ground, post, vec2(0.0, 2.5)))
            .unwrap();
        world
            .add_joint(JointDef::distance(
                firsts[0],
                firsts[1],
                vec2(-100.0, 0.5),
                vec2(-95.0, 0.5),
            ))
            .unwrap();
        let added: Vec<JointHandle> = world
            .joints()
            .map(Joint::handle)
            .filter(|&h| h != never_solved)
            .collect();
        let order = |world: &World| -> Vec<JointHandle> {
            let mut awake = Vec::new();
            world.awake_joints(&mut awake);
            awake
                .iter()
                .map(|j| world.state.joints.as_slice()[j.index as usize].handle())
                .collect()
        };
        assert_eq!(order(&world), added);
        world.remove_joint(added[3]).unwrap();
        let mut expected = added.clone();
        expected.swap_remove(3);
        assert_eq!(order(&world), expected);
        world.check_sets();
    }

    /// A joint sleeps with its dynamic body's island even when its other body is kinematic
    /// (so it is not solved while its island sleeps), and a joint with no dynamic body is
    /// never solved; changing kinds moves the joints to their new sets.
    #[test]
    fn joints_follow_their_bodies_kinds_and_sleep() {
        let mut world = World::new();
        let ground = world
            .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let crane = world
            .add_body(BodyDef::kinematic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 5.0)))
            .unwrap();
        let load = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 3.0)))
            .unwrap();
        let rope = world
            .add_joint(JointDef::distance(
                crane,
                load,
                vec2(0.0, 4.5),
                vec2(0.0, 3.5),
            ))
            .unwrap();
        let anchor = world
            .add_joint(JointDef::weld(ground, crane, vec2(0.0, 5.0)))
            .unwrap();
        world.check_sets();
        assert_eq!(
            joints_by_set(&world),
            [1, 1, 0],
            "the weld has no dynamic body"
        );
        world.step(DT).unwrap();
        assert_eq!(world.stats().joints, 1, "only the rope is solved");
        for _ in 0..120 {
            world.step(DT).unwrap();
            world.check_sets();
        }
        assert!(world.body(load).unwrap().is_sleeping());
        assert_eq!(joints_by_set(&world), [1, 0, 1]);
        assert_eq!(
            world.stats().joints,
            0,
            "the sleeping load's rope is not solved"
        );
        // The crane turned dynamic joins the load's island, which wakes; the weld now holds
        // a dynamic body.
        world.set_body_kind(crane, BodyKind::Dynamic).unwrap();
        world.check_sets();
        assert!(!world.body(load).unwrap().is_sleeping());
        assert_eq!(joints_by_set(&world), [0, 2, 0]);
        world.set_body_kind(load, BodyKind::Static).unwrap();
        world.check_sets();
        world.set_body_kind(crane, BodyKind::Kinematic).unwrap();
        world.check_sets();
        assert_eq!(joints_by_set(&world), [2, 0, 0]);
        world.set_body_kind(load, BodyKind::Dynamic).unwrap();
        world.check_sets();
        assert_eq!(joints_by_set(&world), [1, 1, 0]);
        world.remove_body(crane).unwrap();
        world.check_sets();
        assert!(world.joint(rope).is_none() && world.joint(anchor).is_none());
        assert_eq!(world.state.joints.len(), 0);
    }

    /// Joints added, removed, broken and carried along by every edit a user can make, among
    /// islands that fall asleep and wake: after every edit and every step, each joint is in the
    /// set its bodies call for.
    #[test]
    fn random_edits_keep_every_joint_in_its_set() {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(30.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let mut seed: u32 = 99;
        let mut below = move |n: usize| {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as usize % n
        };
        let mut bodies: Vec<BodyHandle> = Vec::new();
        let (mut most_asleep, mut broken) = (0, 0);
        for round in 0..500 {
            let edit = below(12);
            let pick = |below: &mut dyn FnMut(usize) -> usize| {
                (!bodies.is_empty()).then(|| bodies[below(bodies.len())])
            };
            let (a, b) = (pick(&mut below), pick(&mut below));
            match (edit, a, b) {
                (0..=2, ..) | (_, None, _) => {
                    let x = below(40) as Real - 20.0;
                    let y = 0.5 + below(4) as Real;
                    let def = match below(8) {
                        0 => BodyDef::static_body(Shape::rect(0.5, 0.5)),
                        1 => BodyDef::kinematic(Shape::rect(0.5, 0.5)),
                        _ => BodyDef::dynamic(Shape::rect(0.5, 0.5)),
                    };
                    bodies.push(world.add_body(def.position(vec2(x, y))).unwrap());
                }
                (3..=5, Some(a), Some(b)) if a != b => {
                    let (pa, pb) = (
                        world.body(a).unwrap().position(),
                        world.body(b).unwrap().position(),
                    );
                    let def = match below(3) {
                        0 => JointDef::distance(a, b, pa, pb),
                        1 => JointDef::revolute(a, b, (pa + pb) * 0.5).break_force(50.0),
                        _ => JointDef::filter(a, b),
                    };
                    world.add_joint(def).unwrap();
                }
                (6, Some(a), _) => {
                    if let Some(&joint) = world.joints_of(a).first() {
                        world.remove_joint(joint).unwrap();
                    }
                }
                (7, Some(a), _) if round % 5 == 0 => {
                    world.remove_body(a).unwrap();
                    bodies.retain(|&h| h != a);
                }
                (8, Some(a), _) => {
                    let kinds = [BodyKind::Static, BodyKind::Kinematic, BodyKind::Dynamic];
                    world.set_body_kind(a, kinds[below(3)]).unwrap();
                }
                (9, Some(a), _) => {
                    let point = world.body(a).unwrap().position();
                    if world.body(a).unwrap().is_dynamic() {
                        world.add_joint(JointDef::mouse(a, point, 100.0)).unwrap();
                    }
                }
                (10, ..) if round % 40 == 0 => world.wake_all(),
                _ => {
                    for _ in 0..30 {
                        world.step(DT).unwrap();
                        world.check_sets();
                        broken += world.joint_events().len();
                        most_asleep = most_asleep.max(joints_by_set(&world)[2]);
                    }
                }
            }
            world.check_sets();
        }
        assert!(
            most_asleep > 5,
            "joints fell asleep ({most_asleep} at most)"
        );
        assert!(broken > 0, "some joints broke");
    }
}
