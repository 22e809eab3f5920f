//! A joint lent out to be changed, so that its bodies wake to feel the change.

use crate::error::CaromError;
use crate::joint::{Joint, JointHandle, JointKind};
use crate::math::Vec2;
use crate::world::World;
use std::ops::Deref;

/// A joint borrowed from its world to be changed ([`crate::World::joint_mut`]). It reads as a
/// [`Joint`] and has the joint's setters; each change wakes the joint's bodies.
#[derive(Debug)]
pub struct JointMut<'w> {
    world: &'w mut World,
    handle: JointHandle,
}

impl<'w> JointMut<'w> {
    pub(crate) fn new(world: &'w mut World, handle: JointHandle) -> Self {
        JointMut { world, handle }
    }

    /// Replaces the joint's settings (a motor's speed, a spring's stiffness, limits) with
    /// `kind`, which must be of the same kind and is checked first; an axis is in body A's
    /// frame and is normalised.
    ///
    /// # Errors
    /// A kind of another kind, or a bad value in it; the joint is then left as it was.
    #[allow(
        clippy::expect_used,
        reason = "the joint was checked live when it was lent, and the loan holds the world"
    )]
    pub fn set_kind(&mut self, kind: JointKind) -> Result<(), CaromError> {
        let joint = self
            .world
            .state
            .joints
            .get_mut(self.handle)
            .expect("lent live");
        joint.set_kind(kind)?;
        self.world.wake_joint_bodies(self.handle);
        Ok(())
    }

    /// Moves a mouse joint's target, the point its body is pulled towards.
    ///
    /// # Errors
    /// A joint that is not a mouse joint, or a target that is not finite or lies beyond
    /// [`crate::MAX_POSITION`].
    pub fn set_mouse_target(&mut self, target: Vec2) -> Result<(), CaromError> {
        let JointKind::Mouse(mut mouse) = *self.kind() else {
            return Err(CaromError::JointKindChange {
                from: self.kind().name(),
                to: "mouse",
            });
        };
        mouse.target = target;
        self.set_kind(JointKind::Mouse(mouse))
    }
}

impl Deref for JointMut<'_> {
    type Target = Joint;

    #[allow(
        clippy::expect_used,
        reason = "the joint was checked live when it was lent, and the loan holds the world"
    )]
    fn deref(&self) -> &Joint {
        self.world.state.joints.get(self.handle).expect("lent live")
    }
}
