//! A definition for each kind of joint ([`RevoluteJointDef`], [`DistanceJointDef`], ...), as
//! Box2D's `b2RevoluteJointDef` and Rapier's joint builders: only the settings of its kind,
//! so that a setting the kind lacks does not compile. Each turns into a [`JointDef`], which
//! [`crate::World::add_joint`] takes.

use super::kinds::{
    DistanceJoint, Limits, Motor, MotorJoint, MouseJoint, MoverJoint, PogoJoint, PrismaticJoint,
    RevoluteJoint, Spring, WeldJoint, WheelJoint,
};
use super::{JointDef, JointKind};
use crate::dynamics::body::BodyHandle;
use crate::math::{Real, Vec2};

/// Defines a kind's definition: the joint's common part (a [`JointDef`] whose kind is filled
/// in on conversion) and the kind's settings, the setters every kind shares, and the
/// conversion.
macro_rules! kind_def {
    ($(#[$doc:meta])* $name:ident, $variant:ident, $settings:ty) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name {
            /// Bodies, anchors and the settings every joint has; its kind is `joint`.
            common: JointDef,
            /// The kind's settings.
            joint: $settings,
        }

        impl $name {
            /// The definition of `joint` between `a` and `b` at world points `anchor_a` and
            /// `anchor_b`.
            fn of(a: BodyHandle, b: BodyHandle, anchor_a: Vec2, anchor_b: Vec2, joint: $settings) -> Self {
                let common = JointDef::new(a, b, anchor_a, anchor_b, JointKind::$variant(joint));
                $name { common, joint }
            }

            /// The kind's settings so far.
            pub fn settings(&self) -> &$settings {
                &self.joint
            }

            /// Anchors in each body's own frame, with B's angle relative to A's at the joint's
            /// zero (an axis is then in A's frame); see [`JointDef::local_anchors`].
            pub fn local_anchors(mut self, a: Vec2, b: Vec2, reference_angle: Real) -> Self {
                self.common = self.common.local_anchors(a, b, reference_angle);
                self
            }

            /// Lets the two bodies collide with each other (or not).
            pub fn collide_connected(mut self, collide: bool) -> Self {
                self.common = self.common.collide_connected(collide);
                self
            }

            /// Breaks the joint when it applies more than `force` newtons.
            pub fn break_force(mut self, force: Real) -> Self {
                self.common = self.common.break_force(force);
                self
            }

            /// Breaks the joint when it applies more than `torque` newton-metres.
            pub fn break_torque(mut self, torque: Real) -> Self {
                self.common = self.common.break_torque(torque);
                self
            }
        }

        impl From<$name> for JointDef {
            fn from(def: $name) -> JointDef {
                JointDef {
                    kind: JointKind::$variant(def.joint),
                    ..def.common
                }
            }
        }
    };
}

kind_def!(
    /// A rod, spring or rope between two anchors ([`DistanceJoint`]).
    DistanceJointDef,
    Distance,
    DistanceJoint
);

impl DistanceJointDef {
    /// A rigid rod between world points `anchor_a` on `a` and `anchor_b` on `b`, as long as
    /// they are apart now.
    pub fn new(a: BodyHandle, b: BodyHandle, anchor_a: Vec2, anchor_b: Vec2) -> Self {
        let joint = DistanceJoint {
            length: (anchor_b - anchor_a).norm(),
            spring: None,
            spring_force: None,
            motor: None,
            limits: None,
        };
        Self::of(a, b, anchor_a, anchor_b, joint)
    }

    /// The rest length, m.
    pub fn length(mut self, length: Real) -> Self {
        self.joint.length = length;
        self
    }

    /// Soft: a spring of `hertz` and `damping_ratio` toward the rest length.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.spring = Some(Spring::new(hertz, damping_ratio));
        self
    }

    /// The least and most force the spring applies, N (negative pulls).
    pub fn spring_force(mut self, lower: Real, upper: Real) -> Self {
        self.joint.spring_force = Some(Limits { lower, upper });
        self
    }

    /// Drives the length's rate (m/s) with at most `max_force` N (with a spring).
    pub fn motor(mut self, speed: Real, max_force: Real) -> Self {
        self.joint.motor = Some(Motor { speed, max_force });
        self
    }

    /// Lengths the anchors stay between, m (with a spring).
    pub fn limits(mut self, lower: Real, upper: Real) -> Self {
        self.joint.limits = Some(Limits { lower, upper });
        self
    }
}

kind_def!(
    /// A hinge ([`RevoluteJoint`]).
    RevoluteJointDef,
    Revolute,
    RevoluteJoint
);

impl RevoluteJointDef {
    /// A hinge between `a` and `b` at world point `anchor`.
    pub fn new(a: BodyHandle, b: BodyHandle, anchor: Vec2) -> Self {
        Self::of(a, b, anchor, anchor, RevoluteJoint::default())
    }

    /// The angles of B relative to A it stays between, rad, each within half a turn (±π).
    pub fn limits(mut self, lower: Real, upper: Real) -> Self {
        self.joint.limits = Some(Limits { lower, upper });
        self
    }

    /// Turns B relative to A at `speed` rad/s with at most `max_torque` N·m.
    pub fn motor(mut self, speed: Real, max_torque: Real) -> Self {
        self.joint.motor = Some(Motor {
            speed,
            max_force: max_torque,
        });
        self
    }

    /// A spring of `hertz` and `damping_ratio` pulling the angle toward the target angle.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.spring = Some(Spring::new(hertz, damping_ratio));
        self
    }

    /// The angle the spring pulls to, rad.
    pub fn target_angle(mut self, angle: Real) -> Self {
        self.joint.target_angle = angle;
        self
    }
}

kind_def!(
    /// A slider ([`PrismaticJoint`]).
    PrismaticJointDef,
    Prismatic,
    PrismaticJoint
);

impl PrismaticJointDef {
    /// A slider: `b` moves along world direction `axis` through world point `anchor`.
    pub fn new(a: BodyHandle, b: BodyHandle, anchor: Vec2, axis: Vec2) -> Self {
        let joint = PrismaticJoint {
            axis,
            ..PrismaticJoint::default()
        };
        Self::of(a, b, anchor, anchor, joint)
    }

    /// The translations along the axis it stays between, m.
    pub fn limits(mut self, lower: Real, upper: Real) -> Self {
        self.joint.limits = Some(Limits { lower, upper });
        self
    }

    /// Drives the translation at `speed` m/s with at most `max_force` N.
    pub fn motor(mut self, speed: Real, max_force: Real) -> Self {
        self.joint.motor = Some(Motor { speed, max_force });
        self
    }

    /// A spring of `hertz` and `damping_ratio` pulling toward the target translation.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.spring = Some(Spring::new(hertz, damping_ratio));
        self
    }

    /// The translation the spring pulls to, m.
    pub fn target_translation(mut self, translation: Real) -> Self {
        self.joint.target_translation = translation;
        self
    }
}

kind_def!(
    /// Two bodies glued together ([`WeldJoint`]).
    WeldJointDef,
    Weld,
    WeldJoint
);

impl WeldJointDef {
    /// Glues `a` and `b` together as they are, at world point `anchor` (where a soft weld
    /// bends).
    pub fn new(a: BodyHandle, b: BodyHandle, anchor: Vec2) -> Self {
        Self::of(a, b, anchor, anchor, WeldJoint::default())
    }

    /// Soft translation: a spring of `hertz` and `damping_ratio`.
    pub fn linear_spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.linear = Some(Spring::new(hertz, damping_ratio));
        self
    }

    /// Soft rotation: a spring of `hertz` and `damping_ratio`.
    pub fn angular_spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.angular = Some(Spring::new(hertz, damping_ratio));
        self
    }
}

kind_def!(
    /// A wheel on a suspension ([`WheelJoint`]).
    WheelJointDef,
    Wheel,
    WheelJoint
);

impl WheelJointDef {
    /// Wheel `b` on chassis `a`: `b`'s centre at world point `anchor` rides a suspension
    /// along world direction `axis` (4 Hz, damping ratio 0.7 until set).
    pub fn new(a: BodyHandle, b: BodyHandle, anchor: Vec2, axis: Vec2) -> Self {
        let joint = WheelJoint {
            axis,
            ..WheelJoint::default()
        };
        Self::of(a, b, anchor, anchor, joint)
    }

    /// The suspension: a spring of `hertz` and `damping_ratio` along the axis.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.spring = Some(Spring::new(hertz, damping_ratio));
        self
    }

    /// No suspension: the wheel is free along the axis, within the limits.
    pub fn no_spring(mut self) -> Self {
        self.joint.spring = None;
        self
    }

    /// The translations along the axis it stays between, m.
    pub fn limits(mut self, lower: Real, upper: Real) -> Self {
        self.joint.limits = Some(Limits { lower, upper });
        self
    }

    /// Turns the wheel at `speed` rad/s with at most `max_torque` N·m.
    pub fn motor(mut self, speed: Real, max_torque: Real) -> Self {
        self.joint.motor = Some(Motor {
            speed,
            max_force: max_torque,
        });
        self
    }
}

kind_def!(
    /// B driven relative to A by a velocity part and a spring part ([`MotorJoint`]).
    MotorJointDef,
    Motor,
    MotorJoint
);

impl MotorJointDef {
    /// Holds `b` at its present pose relative to `a` through critically damped 4 Hz springs
    /// with at most `max_force` and `max_torque`, anchored at world point `anchor`.
    pub fn new(
        a: BodyHandle,
        b: BodyHandle,
        anchor: Vec2,
        max_force: Real,
        max_torque: Real,
    ) -> Self {
        let joint = MotorJoint {
            max_spring_force: max_force,
            max_spring_torque: max_torque,
            ..MotorJoint::default()
        };
        Self::of(a, b, anchor, anchor, joint)
    }

    /// Where the springs pull B: its anchor to `linear` from A's (in A's frame), m, and its
    /// angle to `angular` relative to A, rad.
    pub fn offsets(mut self, linear: Vec2, angular: Real) -> Self {
        self.joint.linear_offset = linear;
        self.joint.angular_offset = angular;
        self
    }

    /// The springs: the linear one's and the angular one's `hertz` and `damping_ratio`.
    pub fn springs(mut self, linear: Spring, angular: Spring) -> Self {
        self.joint.linear_spring = linear;
        self.joint.angular_spring = angular;
        self
    }

    /// The velocity part: B's anchor driven at `linear` m/s and B turned at `angular` rad/s
    /// relative to A, with at most `max_force` and `max_torque`.
    pub fn velocity(
        mut self,
        (linear, angular): (Vec2, Real),
        max_force: Real,
        max_torque: Real,
    ) -> Self {
        self.joint.linear_velocity = linear;
        self.joint.angular_velocity = angular;
        self.joint.max_velocity_force = max_force;
        self.joint.max_velocity_torque = max_torque;
        self
    }
}

kind_def!(
    /// A grab of a body toward a point in the world ([`MouseJoint`]).
    MouseJointDef,
    Mouse,
    MouseJoint
);

impl MouseJointDef {
    /// Grabs `body` at world point `point` and pulls that point toward `point` with at most
    /// `max_force`.
    pub fn new(body: BodyHandle, point: Vec2, max_force: Real) -> Self {
        let joint = MouseJoint {
            target: point,
            max_force,
            ..MouseJoint::default()
        };
        Self::of(body, body, point, point, joint)
    }

    /// The spring: `hertz` and `damping_ratio`.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.spring = Spring::new(hertz, damping_ratio);
        self
    }
}

kind_def!(
    /// A body's velocity driven relative to another's ([`MoverJoint`]).
    MoverJointDef,
    Mover,
    MoverJoint
);

impl MoverJointDef {
    /// Drives `body`'s velocity relative to `reference` toward `velocity` with at most
    /// `max_force` on each world axis; the two still collide.
    pub fn new(reference: BodyHandle, body: BodyHandle, velocity: Vec2, max_force: Vec2) -> Self {
        let joint = MoverJoint {
            velocity,
            max_force,
        };
        Self::of(reference, body, Vec2::zeros(), Vec2::zeros(), joint).collide_connected(true)
    }
}

kind_def!(
    /// A leg held above the ground ([`PogoJoint`]).
    PogoJointDef,
    Pogo,
    PogoJoint
);

impl PogoJointDef {
    /// A leg from world point `foot` on `body` down to world point `ground_point` on
    /// `ground`, whose surface there has normal `normal`, holding the foot `rest_length`
    /// above it (5 Hz, damping ratio 0.8 until set), pushing with at most
    /// `max_compression` and pulling with at most `max_tension`; the two still collide.
    pub fn new(
        (ground, ground_point): (BodyHandle, Vec2),
        (body, foot): (BodyHandle, Vec2),
        normal: Vec2,
        rest_length: Real,
        (max_compression, max_tension): (Real, Real),
    ) -> Self {
        let joint = PogoJoint {
            normal,
            rest_length,
            max_compression,
            max_tension,
            ..PogoJoint::default()
        };
        Self::of(ground, body, ground_point, foot, joint).collide_connected(true)
    }

    /// The leg's spring: `hertz` and `damping_ratio`.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        self.joint.spring = Spring::new(hertz, damping_ratio);
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;
    use crate::{BodyDef, Shape, World};

    fn two_bodies() -> (World, BodyHandle, BodyHandle) {
        let mut world = World::new();
        let a = world
            .add_body(BodyDef::static_body(Shape::rect(0.5, 0.5)))
            .expect("valid");
        let b = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(2.0, 0.0)))
            .expect("valid");
        (world, a, b)
    }

    #[test]
    fn each_kind_s_definition_is_the_joint_def_its_setters_name() {
        let (_, a, b) = two_bodies();
        let at = vec2(1.0, 0.0);
        let pairs: [(JointDef, JointDef); 9] = [
            (
                RevoluteJointDef::new(a, b, at)
                    .limits(-0.5, 0.5)
                    .motor(1.0, 2.0)
                    .spring(3.0, 0.5)
                    .target_angle(0.25)
                    .collide_connected(true)
                    .break_force(100.0)
                    .into(),
                JointDef::revolute(a, b, at)
                    .limits(-0.5, 0.5)
                    .motor_drive(1.0, 2.0)
                    .spring(3.0, 0.5)
                    .collide_connected(true)
                    .break_force(100.0),
            ),
            (
                DistanceJointDef::new(a, b, vec2(0.0, 0.0), vec2(2.0, 0.0))
                    .spring(2.0, 0.1)
                    .spring_force(-5.0, 5.0)
                    .motor(0.5, 9.0)
                    .limits(1.0, 3.0)
                    .into(),
                JointDef::distance(a, b, vec2(0.0, 0.0), vec2(2.0, 0.0))
                    .spring(2.0, 0.1)
                    .spring_force(-5.0, 5.0)
                    .motor_drive(0.5, 9.0)
                    .limits(1.0, 3.0),
            ),
            (
                PrismaticJointDef::new(a, b, at, vec2(1.0, 0.0))
                    .limits(-1.0, 1.0)
                    .motor(0.5, 10.0)
                    .spring(1.0, 1.0)
                    .into(),
                JointDef::prismatic(a, b, at, vec2(1.0, 0.0))
                    .limits(-1.0, 1.0)
                    .motor_drive(0.5, 10.0)
                    .spring(1.0, 1.0),
            ),
            (
                WeldJointDef::new(a, b, at)
                    .linear_spring(5.0, 0.7)
                    .angular_spring(5.0, 0.7)
                    .into(),
                JointDef::weld(a, b, at).spring(5.0, 0.7),
            ),
            (
                WheelJointDef::new(a, b, at, vec2(0.0, 1.0))
                    .spring(2.0, 0.5)
                    .limits(-0.2, 0.2)
                    .motor(4.0, 50.0)
                    .into(),
                JointDef::wheel(a, b, at, vec2(0.0, 1.0))
                    .spring(2.0, 0.5)
                    .limits(-0.2, 0.2)
                    .motor_drive(4.0, 50.0),
            ),
            (
                MotorJointDef::new(a, b, at, 10.0, 5.0).into(),
                JointDef::motor(a, b, at, 10.0, 5.0),
            ),
            (
                MouseJointDef::new(b, at, 50.0).spring(3.0, 0.9).into(),
                JointDef::mouse(b, at, 50.0).spring(3.0, 0.9),
            ),
            (
                MoverJointDef::new(a, b, vec2(1.0, 0.0), vec2(10.0, 0.0)).into(),
                JointDef::mover(a, b, vec2(1.0, 0.0), vec2(10.0, 0.0)),
            ),
            (
                PogoJointDef::new(
                    (a, vec2(2.0, -0.5)),
                    (b, vec2(2.0, 0.5)),
                    vec2(0.0, 1.0),
                    1.0,
                    (100.0, 0.0),
                )
                .spring(4.0, 0.5)
                .into(),
                JointDef::pogo(
                    a,
                    b,
                    vec2(2.0, -0.5),
                    vec2(2.0, 0.5),
                    vec2(0.0, 1.0),
                    1.0,
                    (100.0, 0.0),
                )
                .spring(4.0, 0.5),
            ),
        ];
        for (i, (typed, general)) in pairs.iter().enumerate() {
            // The revolute's target angle has no general setter: set it by hand to compare.
            let mut general = *general;
            if let JointKind::Revolute(hinge) = &mut general.kind {
                hinge.target_angle = 0.25;
            }
            assert_eq!(*typed, general, "pair {i}");
        }
    }

    #[test]
    fn a_kind_s_definition_adds_and_its_settings_read_back() {
        let (mut world, a, b) = two_bodies();
        let def = PrismaticJointDef::new(a, b, vec2(1.0, 0.0), vec2(1.0, 0.0)).limits(-0.5, 0.5);
        assert_eq!(
            def.settings().limits,
            Some(Limits {
                lower: -0.5,
                upper: 0.5
            })
        );
        let handle = world.add_joint(def).expect("a valid slider");
        let JointKind::Prismatic(slider) = world.joint(handle).expect("added").kind() else {
            panic!("a prismatic joint");
        };
        assert_eq!(slider.limits, def.settings().limits);
        // A bad value is still refused when added.
        let bad = RevoluteJointDef::new(a, b, vec2(1.0, 0.0)).limits(1.0, -1.0);
        assert!(world.add_joint(bad).is_err());
    }
}
