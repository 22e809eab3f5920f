//! A scene's joints, waiting for their bodies to exist: found by name or by their place in a
//! generator's batch, and turned into carom's joint definitions.

use crate::scene::{JointKindSpec, JointSpec, Pair, RevoluteSpec};
use carom::{
    BodyHandle, DistanceJoint, JointDef, JointKind, Limits, MotorJoint, MouseJoint, MoverJoint,
    PogoJoint, PrismaticJoint, Real, RevoluteJoint, Vec2, WeldJoint, WheelJoint, vec2,
};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A joint's body: one of its batch's (by index), or one the scene named.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) enum Target {
    Local(usize),
    Named(String),
}

/// A joint waiting for its bodies to exist.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct PendingJoint {
    pub bodies: [Target; 2],
    kind: JointKindSpec,
    anchor: Vec2,
    anchor_b: Option<Vec2>,
    collide_connected: bool,
    break_force: Option<Real>,
    break_torque: Option<Real>,
}

pub(crate) fn point((x, y): Pair) -> Vec2 {
    vec2(x, y)
}

impl PendingJoint {
    /// `spec`, its bodies found by name among the scene's, moved by `shift`.
    pub(crate) fn named(spec: &JointSpec, shift: Vec2) -> Self {
        Self::with_targets(
            spec,
            [
                Target::Named(spec.bodies.0.clone()),
                Target::Named(spec.bodies.1.clone()),
            ],
            shift,
        )
    }

    pub(crate) fn with_targets(spec: &JointSpec, bodies: [Target; 2], shift: Vec2) -> Self {
        PendingJoint {
            bodies,
            kind: spec.kind,
            anchor: point(spec.anchor) + shift,
            anchor_b: spec.anchor_b.map(|b| point(b) + shift),
            collide_connected: spec.collide_connected,
            break_force: spec.break_force,
            break_torque: spec.break_torque,
        }
    }

    /// A hinge with `joint`'s settings between batch bodies `a` and `b` at `at`.
    pub(crate) fn hinge(joint: &RevoluteSpec, a: usize, b: usize, at: Vec2) -> Self {
        PendingJoint {
            bodies: [Target::Local(a), Target::Local(b)],
            kind: JointKindSpec::Revolute {
                limits: joint.limits,
                motor: joint.motor,
                spring: joint.spring,
                target_angle: joint.target_angle,
            },
            anchor: at,
            anchor_b: None,
            collide_connected: false,
            break_force: None,
            break_torque: None,
        }
    }

    /// The same joint moved by `shift`, its batch bodies `offset` further on.
    pub fn shifted(&self, shift: Vec2, offset: usize) -> Self {
        let mut moved = self.clone();
        for target in &mut moved.bodies {
            if let Target::Local(index) = target {
                *index += offset;
            }
        }
        moved.anchor += shift;
        moved.anchor_b = moved.anchor_b.map(|b| b + shift);
        if let JointKindSpec::Mouse { target, .. } = &mut moved.kind {
            *target = (target.0 + shift.x, target.1 + shift.y);
        }
        moved
    }

    /// The joint's definition, its bodies found among the batch's `handles` or the scene's
    /// `names`.
    pub fn def(
        &self,
        handles: &[BodyHandle],
        names: &HashMap<String, BodyHandle>,
    ) -> Result<JointDef, String> {
        let find = |target: &Target| match target {
            Target::Local(index) => Ok(handles[*index]),
            Target::Named(name) => names
                .get(name)
                .copied()
                .ok_or_else(|| format!("no body is named {name:?}")),
        };
        let (a, b) = (find(&self.bodies[0])?, find(&self.bodies[1])?);
        let anchor_b = self.anchor_b.unwrap_or(self.anchor);
        let limits = |limits: Option<Pair>| limits.map(|(lower, upper)| Limits { lower, upper });
        let kind = match self.kind {
            JointKindSpec::Distance {
                length,
                spring,
                limits: range,
            } => JointKind::Distance(DistanceJoint {
                length: length.unwrap_or_else(|| (anchor_b - self.anchor).norm()),
                spring,
                spring_force: None,
                motor: None,
                limits: limits(range),
            }),
            JointKindSpec::Revolute {
                limits: range,
                motor,
                spring,
                target_angle,
            } => JointKind::Revolute(RevoluteJoint {
                limits: limits(range),
                motor,
                spring,
                target_angle,
            }),
            JointKindSpec::Prismatic {
                axis,
                limits: range,
                motor,
                spring,
                target_translation,
            } => JointKind::Prismatic(PrismaticJoint {
                axis: point(axis),
                limits: limits(range),
                motor,
                spring,
                target_translation,
            }),
            JointKindSpec::Weld { linear, angular } => {
                JointKind::Weld(WeldJoint { linear, angular })
            }
            JointKindSpec::Wheel {
                axis,
                spring,
                limits: range,
                motor,
            } => JointKind::Wheel(WheelJoint {
                axis: point(axis),
                spring,
                limits: limits(range),
                motor,
            }),
            JointKindSpec::Motor {
                linear_velocity,
                max_velocity_force,
                angular_velocity,
                max_velocity_torque,
                linear_offset,
                angular_offset,
                linear_spring,
                max_spring_force,
                angular_spring,
                max_spring_torque,
            } => JointKind::Motor(MotorJoint {
                linear_velocity: point(linear_velocity),
                max_velocity_force,
                angular_velocity,
                max_velocity_torque,
                linear_offset: point(linear_offset),
                angular_offset,
                linear_spring,
                max_spring_force,
                angular_spring,
                max_spring_torque,
            }),
            JointKindSpec::Mover {
                velocity,
                max_force,
            } => JointKind::Mover(MoverJoint {
                velocity: point(velocity),
                max_force: point(max_force),
            }),
            JointKindSpec::Pogo {
                normal,
                rest_length,
                spring,
                max_compression,
                max_tension,
            } => JointKind::Pogo(PogoJoint {
                normal: point(normal),
                rest_length,
                spring,
                max_compression,
                max_tension,
            }),
            JointKindSpec::Mouse {
                target,
                spring,
                max_force,
            } => JointKind::Mouse(MouseJoint {
                target: point(target),
                spring,
                max_force,
            }),
            JointKindSpec::Filter => JointKind::Filter,
        };
        let mut def = JointDef::new(a, b, self.anchor, anchor_b, kind)
            .collide_connected(self.collide_connected);
        if let Some(force) = self.break_force {
            def = def.break_force(force);
        }
        if let Some(torque) = self.break_torque {
            def = def.break_torque(torque);
        }
        Ok(def)
    }
}
