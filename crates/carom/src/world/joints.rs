//! The world's side of joints: adding and removing them (with what that means for islands,
//! sleep and collisions between the joined bodies), finding the ones a step solves, and
//! breaking the ones pulled too hard.

use crate::dynamics::body::BodyHandle;
use crate::error::CaromError;
use crate::joint::{Joint, JointDef, JointEvent, JointHandle, JointKind};
use crate::math::Vec2;
use crate::solver::AwakeJoint;
use crate::world::World;

fn stale(handle: JointHandle) -> CaromError {
    CaromError::StaleHandle {
        what: "joint",
        index: handle.index(),
        generation: handle.generation(),
    }
}

impl World {
    /// Adds a joint; the definition is checked first (both bodies live and different except
    /// for a mouse joint, every setting finite and in range, only settings its kind has), and
    /// nothing is added if any of it is wrong. Both bodies wake. Unless the joint lets them
    /// collide, contacts between the two bodies end.
    pub fn add_joint(&mut self, def: JointDef) -> Result<JointHandle, CaromError> {
        let handle = self.joints.next_handle();
        let joint = def.build(
            handle,
            self.bodies.get(def.body_a),
            self.bodies.get(def.body_b),
        )?;
        let [a, b] = joint.bodies();
        let filters = !joint.collide_connected() && a != b;
        let set = self.joint_set_for(&joint);
        // Waking its bodies moves it on to the awake set if it has a dynamic body.
        let handle = self.joints.insert(joint, set);
        for body in [a, b] {
            let index = self.bodies.checked_index(body).expect("checked");
            self.wake_body(index);
        }
        self.link_islands(a, b);
        if filters {
            self.contacts.remove_between(a, b);
            self.apply_touch_changes();
        }
        Ok(handle)
    }

    /// Removes a joint and returns it. Its bodies wake; if it kept them from colliding, they
    /// may collide from the next step.
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint, CaromError> {
        let joint = self.joints.remove(handle).ok_or_else(|| stale(handle))?;
        self.detach_joint(&joint);
        Ok(joint)
    }

    /// What removing `joint` means for its bodies: they wake, their island may have come
    /// apart, and if they did not collide they are looked at again for new pairs.
    fn detach_joint(&mut self, joint: &Joint) {
        let [a, b] = joint.bodies();
        for body in [a, b] {
            if let Some(index) = self.bodies.dense_index(body) {
                self.wake_body(index);
            }
        }
        if a != b {
            self.unlink_contact(a, b);
        }
        if !joint.collide_connected() && a != b {
            for body in [a, b] {
                let Some(body) = self.bodies.get(body) else {
                    continue;
                };
                for &collider in body.colliders() {
                    self.broadphase.requeue(collider);
                }
            }
        }
    }

    /// Removes every joint of a body (which is being removed).
    pub(crate) fn remove_joints_of(&mut self, body: BodyHandle) {
        while let Some(&handle) = self.joints.of_body(body).first() {
            let joint = self.joints.remove(handle).expect("listed joints live");
            self.detach_joint(&joint);
        }
    }

    /// The joint behind a handle, unless it was removed.
    pub fn joint(&self, handle: JointHandle) -> Option<&Joint> {
        self.joints.get(handle)
    }

    /// Every joint, in handle order.
    pub fn joints(&self) -> impl ExactSizeIterator<Item = &Joint> {
        self.joints.iter_by_handle()
    }

    /// How many joints there are.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The joints of a body.
    pub fn joints_of(&self, body: BodyHandle) -> &[JointHandle] {
        self.joints.of_body(body)
    }

    /// Replaces a joint's settings (a motor's speed, a spring's stiffness, limits) with a
    /// `kind` of the same kind, checked first; an axis is in body A's frame. Its bodies wake.
    pub fn set_joint_kind(
        &mut self,
        handle: JointHandle,
        kind: JointKind,
    ) -> Result<(), CaromError> {
        let joint = self.joints.get_mut(handle).ok_or_else(|| stale(handle))?;
        joint.set_kind(kind)?;
        self.wake_joint_bodies(handle);
        Ok(())
    }

    /// Moves a mouse joint's target; its body wakes.
    ///
    /// # Errors
    /// A stale handle, a joint that is not a mouse joint, or a target that is not finite.
    pub fn set_mouse_target(
        &mut self,
        handle: JointHandle,
        target: Vec2,
    ) -> Result<(), CaromError> {
        let joint = self.joints.get(handle).ok_or_else(|| stale(handle))?;
        let JointKind::Mouse(mut mouse) = *joint.kind() else {
            return Err(CaromError::JointKindChange {
                from: joint.kind().name(),
                to: "mouse",
            });
        };
        mouse.target = target;
        self.set_joint_kind(handle, JointKind::Mouse(mouse))
    }

    fn wake_joint_bodies(&mut self, handle: JointHandle) {
        let Some(joint) = self.joints.get(handle) else {
            return;
        };
        for body in joint.bodies() {
            if let Some(index) = self.bodies.dense_index(body) {
                self.bodies.as_mut_slice()[index].wake_up();
                self.wake_body(index);
            }
        }
    }

    /// Joints broken in the last step.
    pub fn joint_events(&self) -> &[JointEvent] {
        &self.joints.events
    }

    /// The joints a step solves, into `awake`: the awake set of joints (those with an awake
    /// dynamic body), in storage order, with where their bodies are.
    pub(crate) fn awake_joints(&self, awake: &mut Vec<AwakeJoint>) {
        awake.clear();
        let range = self.joints.awake();
        let joints = &self.joints.as_slice()[range.clone()];
        for (index, joint) in range.zip(joints) {
            let bodies = joint.bodies().map(|body| {
                self.bodies
                    .dense_index(body)
                    .expect("joints join live bodies") as u32
            });
            awake.push(AwakeJoint {
                index: index as u32,
                bodies,
            });
        }
    }

    /// Removes the joints the last step pulled past their break force or torque, reporting
    /// each.
    pub(crate) fn break_joints(&mut self, solved: &[AwakeJoint]) {
        self.joints.events.clear();
        let broken: Vec<JointHandle> = solved
            .iter()
            .map(|j| &self.joints.as_slice()[j.index as usize])
            .filter(|joint| joint.is_broken())
            .map(Joint::handle)
            .collect();
        for handle in broken {
            let joint = self.joints.remove(handle).expect("solved joints live");
            self.detach_joint(&joint);
            self.joints.events.push(JointEvent::Broken {
                joint: handle,
                bodies: joint.bodies(),
                force: joint.reaction_force(),
                torque: joint.reaction_torque(),
            });
        }
    }

    /// The bodies joined to `body`, into `out` (for islands).
    pub(crate) fn joint_partners(&self, body: BodyHandle, out: &mut Vec<BodyHandle>) {
        self.joints.partners(body, out);
    }
}
