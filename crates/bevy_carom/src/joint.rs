//! Joints: an entity with a [`Joint`] links the bodies of two entities. Despawning it, or
//! either body, removes the joint.

use crate::convert::to_carom;
use bevy::ecs::component::Component;
use bevy::ecs::entity::Entity;
use bevy::math::Vec2;
use carom::{Anchors, BodyHandle, JointDef, JointHandle, JointKind, Real};

/// A joint between the bodies of two entities, of any of carom's kinds. The constructors
/// take anchors in world coordinates, where the bodies are when the joint is made.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// The first body's entity.
    pub body_a: Entity,
    /// The second body's entity.
    pub body_b: Entity,
    /// Where the joint holds each body.
    pub anchors: Anchors,
    /// What kind of joint, with its parameters (limits, motor, spring). Changing only this
    /// retunes the joint in place; changing the rest makes it anew.
    pub kind: JointKind,
    /// Whether the two bodies still collide with each other.
    pub collide_connected: bool,
    /// The force, N, beyond which the joint breaks ([`crate::JointBroken`]); infinite by
    /// default.
    pub break_force: f32,
    /// The torque, N·m, beyond which it breaks.
    pub break_torque: f32,
}

// The bodies of a definition made only to borrow carom's constructors; replaced by the
// entities' bodies when the joint is made.
fn unset() -> BodyHandle {
    BodyHandle::from_raw_parts(u32::MAX, 0)
}

impl Joint {
    fn from_def(a: Entity, b: Entity, def: JointDef) -> Self {
        Joint {
            body_a: a,
            body_b: b,
            anchors: def.anchors,
            kind: def.kind,
            collide_connected: def.collide_connected,
            break_force: def.break_force as f32,
            break_torque: def.break_torque as f32,
        }
    }

    /// A joint of `kind` holding `anchor_a` on the first body to `anchor_b` on the second.
    pub fn new(a: Entity, b: Entity, anchor_a: Vec2, anchor_b: Vec2, kind: JointKind) -> Self {
        let def = JointDef::new(
            unset(),
            unset(),
            to_carom(anchor_a),
            to_carom(anchor_b),
            kind,
        );
        Self::from_def(a, b, def)
    }

    /// Keeps `anchor_a` and `anchor_b` at their present distance: a rigid rod.
    pub fn distance(a: Entity, b: Entity, anchor_a: Vec2, anchor_b: Vec2) -> Self {
        let def = JointDef::distance(unset(), unset(), to_carom(anchor_a), to_carom(anchor_b));
        Self::from_def(a, b, def)
    }

    /// Keeps the anchors at most `length` apart: a rope.
    pub fn rope(a: Entity, b: Entity, anchor_a: Vec2, anchor_b: Vec2, length: f32) -> Self {
        let def = JointDef::rope(
            unset(),
            unset(),
            to_carom(anchor_a),
            to_carom(anchor_b),
            length as Real,
        );
        Self::from_def(a, b, def)
    }

    /// Pins the bodies together at `anchor`, free to turn: a hinge.
    pub fn revolute(a: Entity, b: Entity, anchor: Vec2) -> Self {
        Self::from_def(a, b, JointDef::revolute(unset(), unset(), to_carom(anchor)))
    }

    /// Lets the second body slide along `axis` through `anchor` without turning.
    pub fn prismatic(a: Entity, b: Entity, anchor: Vec2, axis: Vec2) -> Self {
        let def = JointDef::prismatic(unset(), unset(), to_carom(anchor), to_carom(axis));
        Self::from_def(a, b, def)
    }

    /// Glues the bodies together at `anchor`.
    pub fn weld(a: Entity, b: Entity, anchor: Vec2) -> Self {
        Self::from_def(a, b, JointDef::weld(unset(), unset(), to_carom(anchor)))
    }

    /// A wheel on a suspension along `axis`: the second body turns freely at `anchor`.
    pub fn wheel(a: Entity, b: Entity, anchor: Vec2, axis: Vec2) -> Self {
        let def = JointDef::wheel(unset(), unset(), to_carom(anchor), to_carom(axis));
        Self::from_def(a, b, def)
    }

    /// Drives the second body toward its pose relative to the first, with at most
    /// `max_force` and `max_torque`.
    pub fn motor(a: Entity, b: Entity, anchor: Vec2, max_force: f32, max_torque: f32) -> Self {
        let def = JointDef::motor(
            unset(),
            unset(),
            to_carom(anchor),
            max_force as Real,
            max_torque as Real,
        );
        Self::from_def(a, b, def)
    }

    /// Pulls the body of `b` toward `target` with a soft spring of at most `max_force`: how a
    /// mouse drags a body. Move the target by changing [`carom::MouseJoint::target`] in `kind`.
    pub fn mouse(a: Entity, b: Entity, target: Vec2, max_force: f32) -> Self {
        let kind = JointKind::Mouse(carom::MouseJoint {
            target: to_carom(target),
            max_force: max_force as Real,
            ..carom::MouseJoint::default()
        });
        Self::new(a, b, target, target, kind)
    }

    /// Lets the bodies collide with each other.
    pub fn with_collide_connected(mut self) -> Self {
        self.collide_connected = true;
        self
    }

    /// Breaks the joint beyond `force`, N, or `torque`, N·m.
    pub fn with_break_limits(mut self, force: f32, torque: f32) -> Self {
        self.break_force = force;
        self.break_torque = torque;
        self
    }

    /// carom's definition, between the bodies `a` and `b`.
    pub(crate) fn def(&self, a: BodyHandle, b: BodyHandle) -> JointDef {
        let mut def = JointDef::new(a, b, carom::Vec2::zeros(), carom::Vec2::zeros(), self.kind);
        def.anchors = self.anchors;
        def.collide_connected = self.collide_connected;
        def.break_force = self.break_force as Real;
        def.break_torque = self.break_torque as Real;
        def
    }
}

/// The carom joint an entity's [`Joint`] made; added by the plugin.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
#[component(immutable)]
pub struct CaromJoint(pub(crate) JointHandle);

impl CaromJoint {
    /// The joint's handle in the [`crate::CaromWorld`].
    pub fn handle(&self) -> JointHandle {
        self.0
    }
}

/// The joint as it was made, to tell a change of kind (retuned in place) from one of bodies
/// or anchors (made anew).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub(crate) struct JointMirror(pub Joint);
