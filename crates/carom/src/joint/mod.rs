//! Joints: constraints between two bodies (a hinge, a slider, a rope, a weld, ...).
//!
//! A joint holds a point fixed in each body (its anchors) in some relation: together, at a
//! distance, along an axis. Define one with [`JointDef`]'s constructors, from points in the
//! world where the bodies are now, or with its kind's own definition ([`RevoluteJointDef`],
//! [`DistanceJointDef`], ...: only the settings of that kind), and add it with
//! [`crate::World::add_joint`]. Each step the
//! solver holds the joint together with the contacts, in the same substeps (softly in the
//! biased pass, rigidly in the relaxation, as Box2D v3 does); two bodies joined share an
//! island, so they sleep and wake together. A joint reports the force and torque it applied in
//! the last step, and one given a break force or torque comes apart when it exceeds it
//! ([`JointEvent::Broken`]).
//!
//! A door on a hinge that swings at most 45° either way, with a little friction:
//!
//! ```
//! use carom::{BodyDef, JointDef, Shape, World, vec2};
//!
//! let mut world = World::new();
//! let hook = world.add_body(BodyDef::static_body(Shape::rect(0.2, 0.2)))?;
//! let door = world.add_body(BodyDef::dynamic(Shape::rect(1.0, 0.1)).position(vec2(1.0, 0.0)))?;
//! let hinge = world.add_joint(
//!     JointDef::revolute(hook, door, vec2(0.0, 0.0)).limits(-0.785, 0.785).motor_drive(0.0, 0.5),
//! )?;
//! for _ in 0..120 {
//!     world.step(1.0 / 60.0)?;
//! }
//! // It hangs on its lower limit, its hinge pushing up on it.
//! let angle = world.body(door).unwrap().angle();
//! assert!((angle + 0.785).abs() < 0.02, "{angle}");
//! assert!(world.joint(hinge).unwrap().reaction_force().y > 0.0);
//! # Ok::<(), carom::CaromError>(())
//! ```

pub(crate) mod defs;
pub(crate) mod kinds;
pub(crate) mod store;

pub use defs::{
    DistanceJointDef, MotorJointDef, MouseJointDef, MoverJointDef, PogoJointDef, PrismaticJointDef,
    RevoluteJointDef, WeldJointDef, WheelJointDef,
};

pub use kinds::{
    DistanceJoint, JointKind, Limits, Motor, MotorJoint, MouseJoint, MoverJoint, PogoJoint,
    PrismaticJoint, RevoluteJoint, Spring, WeldJoint, WheelJoint,
};

use crate::dynamics::body::{Body, BodyHandle};
#[cfg(feature = "serde")]
use crate::error::check_finite;
use crate::error::{CaromError, check_finite_vec};
use crate::geometry::checks::check_extent;
use crate::handle_map::generational_handle;
use crate::heap_bytes::OwnsNothing;
use crate::math::{Real, Vec2, angle_of, rotation};

generational_handle!(
    /// A stable reference to a joint in a [`crate::World`].
    JointHandle,
    "joint"
);

/// Where a joint's anchors are given.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Anchors {
    /// Points in the world, where the bodies are when the joint is added: the joint holds
    /// them as they are then (its reference angle is their angle then; an axis is a world
    /// direction then).
    World {
        /// On body A.
        a: Vec2,
        /// On body B.
        b: Vec2,
    },
    /// Points in each body's own frame, with the angle of B relative to A that the joint
    /// treats as zero (an axis is in A's frame).
    Local {
        /// In A's frame.
        a: Vec2,
        /// In B's frame.
        b: Vec2,
        /// B's angle less A's at the joint's zero, rad.
        reference_angle: Real,
    },
}

/// Everything needed to create a joint: build one with a constructor ([`JointDef::revolute`],
/// [`JointDef::distance`], ...) and the chained setters, or from a kind's own definition
/// ([`RevoluteJointDef`], ...), whose setters are only its kind's; checked when added to a
/// world.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointDef {
    /// The first body.
    pub body_a: BodyHandle,
    /// The second body (for a mouse joint, the same as the first).
    pub body_b: BodyHandle,
    /// The anchors, in the world or in the bodies' frames.
    pub anchors: Anchors,
    /// Whether the two bodies still collide with each other. Default false.
    pub collide_connected: bool,
    /// The joint breaks when the force it applies exceeds this, N. Default infinite.
    pub break_force: Real,
    /// The joint breaks when the torque it applies exceeds this, N·m. Default infinite.
    pub break_torque: Real,
    /// What it does, with its settings.
    pub kind: JointKind,
    /// A setter used on a kind that has no such setting ("limits", "motor", "spring"),
    /// reported when the joint is added.
    misuse: Option<&'static str>,
    /// Impulses carried from an earlier joint ([`JointDef::continue_from`]).
    #[cfg_attr(feature = "serde", serde(skip))]
    carried: Option<JointImpulses>,
}

impl JointDef {
    /// A joint of `kind` between `a` and `b` at world points `anchor_a` and `anchor_b`.
    pub fn new(
        a: BodyHandle,
        b: BodyHandle,
        anchor_a: Vec2,
        anchor_b: Vec2,
        kind: JointKind,
    ) -> Self {
        JointDef {
            body_a: a,
            body_b: b,
            anchors: Anchors::World {
                a: anchor_a,
                b: anchor_b,
            },
            collide_connected: false,
            break_force: Real::INFINITY,
            break_torque: Real::INFINITY,
            kind,
            misuse: None,
            carried: None,
        }
    }

    /// A rigid rod between world points `anchor_a` on `a` and `anchor_b` on `b`, as long as
    /// they are apart now. Add [`JointDef::spring`] to make it soft, [`JointDef::limits`] to
    /// bound it.
    pub fn distance(a: BodyHandle, b: BodyHandle, anchor_a: Vec2, anchor_b: Vec2) -> Self {
        DistanceJointDef::new(a, b, anchor_a, anchor_b).into()
    }

    /// A rope between world points `anchor_a` on `a` and `anchor_b` on `b`: slack up to
    /// `length`, taut beyond.
    pub fn rope(
        a: BodyHandle,
        b: BodyHandle,
        anchor_a: Vec2,
        anchor_b: Vec2,
        length: Real,
    ) -> Self {
        DistanceJointDef::new(a, b, anchor_a, anchor_b)
            .length(length)
            .spring(0.0, 0.0)
            .limits(0.0, length)
            .into()
    }

    /// A hinge between `a` and `b` at world point `anchor`.
    pub fn revolute(a: BodyHandle, b: BodyHandle, anchor: Vec2) -> Self {
        RevoluteJointDef::new(a, b, anchor).into()
    }

    /// A slider: `b` moves along world direction `axis` through world point `anchor`.
    pub fn prismatic(a: BodyHandle, b: BodyHandle, anchor: Vec2, axis: Vec2) -> Self {
        PrismaticJointDef::new(a, b, anchor, axis).into()
    }

    /// Glues `a` and `b` together as they are, at world point `anchor` (where a soft weld
    /// bends).
    pub fn weld(a: BodyHandle, b: BodyHandle, anchor: Vec2) -> Self {
        WeldJointDef::new(a, b, anchor).into()
    }

    /// Wheel `b` on chassis `a`: `b`'s centre at world point `anchor` rides a suspension
    /// along world direction `axis` (4 Hz, damping ratio 0.7 until set).
    pub fn wheel(a: BodyHandle, b: BodyHandle, anchor: Vec2, axis: Vec2) -> Self {
        WheelJointDef::new(a, b, anchor, axis).into()
    }

    /// Holds `b` at its present pose relative to `a` through critically damped 4 Hz
    /// springs with at most `max_force` and `max_torque`, anchored at world point `anchor`
    /// (usually `b`'s centre). Move the target with the offsets, or drive velocities
    /// instead, through [`crate::JointMut::set_kind`] (see [`MotorJoint`]).
    pub fn motor(
        a: BodyHandle,
        b: BodyHandle,
        anchor: Vec2,
        max_force: Real,
        max_torque: Real,
    ) -> Self {
        MotorJointDef::new(a, b, anchor, max_force, max_torque).into()
    }

    /// Drives `body`'s velocity relative to `reference` (a static body for a velocity in
    /// the world) toward `velocity` with at most `max_force` on each world axis (x, y): a
    /// dynamic character's legs. It does not turn the body; the two still collide.
    pub fn mover(reference: BodyHandle, body: BodyHandle, velocity: Vec2, max_force: Vec2) -> Self {
        MoverJointDef::new(reference, body, velocity, max_force).into()
    }

    /// A leg from world point `foot` on `body` down to world point `ground_point` on
    /// `ground`, whose surface there has normal `normal`: it holds the foot `rest_length`
    /// above the ground through a 5 Hz spring of damping ratio 0.8 (change it with
    /// [`JointDef::spring`]), pushing with at most `max_compression` and pulling with at most
    /// `max_tension` (see [`PogoJoint`]). The two still collide.
    #[allow(
        clippy::too_many_arguments,
        reason = "a leg is where it stands and how it pushes; a builder would hide none"
    )]
    pub fn pogo(
        ground: BodyHandle,
        body: BodyHandle,
        ground_point: Vec2,
        foot: Vec2,
        normal: Vec2,
        rest_length: Real,
        forces: (Real, Real),
    ) -> Self {
        PogoJointDef::new(
            (ground, ground_point),
            (body, foot),
            normal,
            rest_length,
            forces,
        )
        .into()
    }

    /// Starts the joint where `previous` (of the same kind) left off: its impulses, and a
    /// pogo leg's spring's speed. For a joint that is removed and made again each step, as
    /// a leg is on whatever is under the foot, so it does not start cold every time.
    pub fn continue_from(mut self, previous: &Joint) -> Self {
        self.carried = Some(previous.impulses);
        if std::mem::discriminant(&previous.kind) != std::mem::discriminant(&self.kind) {
            self.misuse = Some("way to continue from a joint of another kind");
        }
        self
    }

    /// Grabs `body` at world point `point` and pulls that point toward `point` (move it with
    /// [`crate::JointMut::set_mouse_target`]) with at most `max_force`.
    pub fn mouse(body: BodyHandle, point: Vec2, max_force: Real) -> Self {
        MouseJointDef::new(body, point, max_force).into()
    }

    /// Only keeps `a` and `b` from colliding.
    pub fn filter(a: BodyHandle, b: BodyHandle) -> Self {
        JointDef::new(a, b, Vec2::zeros(), Vec2::zeros(), JointKind::Filter)
    }

    /// Anchors in each body's own frame, with B's angle relative to A's at the joint's zero
    /// (an axis is then in A's frame).
    pub fn local_anchors(mut self, a: Vec2, b: Vec2, reference_angle: Real) -> Self {
        self.anchors = Anchors::Local {
            a,
            b,
            reference_angle,
        };
        self
    }

    /// Lets the two bodies collide with each other (or not).
    pub fn collide_connected(mut self, collide: bool) -> Self {
        self.collide_connected = collide;
        self
    }

    /// Breaks the joint when it applies more than `force` newtons.
    pub fn break_force(mut self, force: Real) -> Self {
        self.break_force = force;
        self
    }

    /// Breaks the joint when it applies more than `torque` newton-metres.
    pub fn break_torque(mut self, torque: Real) -> Self {
        self.break_torque = torque;
        self
    }

    /// Limits: angles for a revolute joint, translations for a prismatic or wheel joint,
    /// lengths for a distance joint (which then also needs a spring to move between them).
    /// Ignored by the other kinds (reported when the joint is added).
    pub fn limits(mut self, lower: Real, upper: Real) -> Self {
        let limits = Some(Limits { lower, upper });
        match &mut self.kind {
            JointKind::Revolute(j) => j.limits = limits,
            JointKind::Prismatic(j) => j.limits = limits,
            JointKind::Wheel(j) => j.limits = limits,
            JointKind::Distance(j) => j.limits = limits,
            _ => self.misuse = Some("limits"),
        }
        self
    }

    /// A motor at `speed` with at most `max_force` (a torque for a revolute or wheel joint;
    /// for a distance joint, which needs a spring for it, the length's rate).
    pub fn motor_drive(mut self, speed: Real, max_force: Real) -> Self {
        let motor = Some(Motor { speed, max_force });
        match &mut self.kind {
            JointKind::Revolute(j) => j.motor = motor,
            JointKind::Prismatic(j) => j.motor = motor,
            JointKind::Wheel(j) => j.motor = motor,
            JointKind::Distance(j) => j.motor = motor,
            _ => self.misuse = Some("motor"),
        }
        self
    }

    /// Bounds a distance joint's spring force to `[lower, upper]` newtons (negative pulls);
    /// see [`DistanceJoint::spring_force`]. Ignored by the other kinds (reported when the
    /// joint is added).
    pub fn spring_force(mut self, lower: Real, upper: Real) -> Self {
        match &mut self.kind {
            JointKind::Distance(j) => j.spring_force = Some(Limits { lower, upper }),
            _ => self.misuse = Some("spring force"),
        }
        self
    }

    /// A spring of `hertz` and `damping_ratio`: the distance joint's, the revolute and
    /// prismatic joints' (toward their targets), the wheel's suspension, both of a weld's, the
    /// mouse joint's, or a pogo leg's.
    pub fn spring(mut self, hertz: Real, damping_ratio: Real) -> Self {
        let spring = Spring::new(hertz, damping_ratio);
        match &mut self.kind {
            JointKind::Distance(j) => j.spring = Some(spring),
            JointKind::Revolute(j) => j.spring = Some(spring),
            JointKind::Prismatic(j) => j.spring = Some(spring),
            JointKind::Wheel(j) => j.spring = Some(spring),
            JointKind::Weld(j) => (j.linear, j.angular) = (Some(spring), Some(spring)),
            JointKind::Mouse(j) => j.spring = spring,
            JointKind::Pogo(j) => j.spring = spring,
            _ => self.misuse = Some("spring"),
        }
        self
    }

    /// Checks the definition against the world's bodies (`None` for a stale handle), and
    /// makes the joint: anchors, reference angle and axis in the bodies' frames.
    pub(crate) fn build(
        &self,
        handle: JointHandle,
        a: Option<&Body>,
        b: Option<&Body>,
    ) -> Result<Joint, CaromError> {
        let stale = |h: BodyHandle| CaromError::StaleHandle {
            what: "body",
            index: h.index(),
            generation: h.generation(),
        };
        let a = a.ok_or_else(|| stale(self.body_a))?;
        let b = b.ok_or_else(|| stale(self.body_b))?;
        let mouse = matches!(self.kind, JointKind::Mouse(_));
        if mouse != (self.body_a == self.body_b) {
            return Err(CaromError::JointBodies {
                kind: self.kind.name(),
            });
        }
        if let Some(setting) = self.misuse {
            return Err(CaromError::JointSetting {
                kind: self.kind.name(),
                setting,
            });
        }
        for (name, value) in [
            ("joint break force", self.break_force),
            ("joint break torque", self.break_torque),
        ] {
            if value.is_nan() {
                return Err(CaromError::non_finite(name, value));
            }
            if value < 0.0 {
                return Err(CaromError::OutOfRange {
                    name,
                    expected: "not negative",
                    value,
                });
            }
        }
        self.kind.validate()?;
        let mut kind = self.kind;
        let (local_a, local_b, reference_angle) = match self.anchors {
            Anchors::World { a: pa, b: pb } => {
                check_finite_vec("joint anchor a", pa)?;
                check_finite_vec("joint anchor b", pb)?;
                if let Some(axis) = kind.axis_mut() {
                    *axis = a.rotation().inverse() * *axis;
                }
                (a.local_point(pa), b.local_point(pb), b.angle() - a.angle())
            }
            Anchors::Local {
                a: pa,
                b: pb,
                reference_angle,
            } => {
                check_finite_vec("joint anchor a", pa)?;
                check_finite_vec("joint anchor b", pb)?;
                if !reference_angle.is_finite() {
                    return Err(CaromError::non_finite(
                        "joint reference angle",
                        reference_angle,
                    ));
                }
                (pa, pb, reference_angle)
            }
        };
        if let Some(axis) = kind.axis_mut() {
            *axis = axis.normalize();
        }
        // Far from the origin, a mover's or filter's anchors (the origin) are far from
        // their bodies; they are not used, so not checked.
        if kind.has_anchors() {
            check_anchor(local_a)?;
            check_anchor(local_b)?;
        }
        Ok(Joint {
            handle,
            body_a: self.body_a,
            body_b: self.body_b,
            local_anchor_a: local_a,
            local_anchor_b: local_b,
            reference_angle,
            collide_connected: self.collide_connected,
            break_force: self.break_force,
            break_torque: self.break_torque,
            kind,
            force: Vec2::zeros(),
            torque: 0.0,
            impulses: self.carried.unwrap_or_default(),
        })
    }
}

/// A joint's accumulated impulses, kept from step to step to warm start the next. Each kind
/// uses the ones it needs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointImpulses {
    /// The point constraint's (revolute, weld, mouse, motor), or the prismatic and wheel
    /// joints' perpendicular one (x) and the prismatic's angular one (y).
    pub linear: Vec2,
    /// The weld's and the motor joint's angular constraint, the mouse joint's spin damping.
    pub angular: Real,
    /// Along the joint's free motion: the distance joint's rod or spring, a spring's.
    pub axial: Real,
    pub motor: Real,
    pub lower: Real,
    pub upper: Real,
    /// The motor joint's velocity part, the mover joint's drive.
    pub drive: Vec2,
    /// A pogo leg's spring's speed: motion carried from step to step, not an impulse.
    pub spring_velocity: Real,
}

/// A joint in a world.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Joint {
    handle: JointHandle,
    body_a: BodyHandle,
    body_b: BodyHandle,
    local_anchor_a: Vec2,
    local_anchor_b: Vec2,
    reference_angle: Real,
    collide_connected: bool,
    break_force: Real,
    break_torque: Real,
    kind: JointKind,
    force: Vec2,
    torque: Real,
    pub(crate) impulses: JointImpulses,
}

// Plain values: every field is `Copy` (one that is not fails to compile in the pattern below,
// which moves each out of a borrowed joint), so an array of joints is its capacity alone.
impl OwnsNothing for Joint {}
const _: fn(&Joint) -> Joint = |joint| Joint { ..*joint };

impl Joint {
    /// Its handle.
    pub fn handle(&self) -> JointHandle {
        self.handle
    }

    /// The two bodies (a mouse joint's are the same body).
    pub fn bodies(&self) -> [BodyHandle; 2] {
        [self.body_a, self.body_b]
    }

    /// The anchors in the bodies' own frames.
    pub fn local_anchors(&self) -> [Vec2; 2] {
        [self.local_anchor_a, self.local_anchor_b]
    }

    /// B's angle less A's at the joint's zero, rad.
    pub fn reference_angle(&self) -> Real {
        self.reference_angle
    }

    /// Whether the two bodies collide with each other.
    pub fn collide_connected(&self) -> bool {
        self.collide_connected
    }

    /// The force and the torque past which it breaks (infinite: never).
    pub fn break_thresholds(&self) -> (Real, Real) {
        (self.break_force, self.break_torque)
    }

    /// What it does; an axis is in A's frame.
    pub fn kind(&self) -> &JointKind {
        &self.kind
    }

    /// The force it applied to body B in the last step, N (A felt the opposite).
    pub fn reaction_force(&self) -> Vec2 {
        self.force
    }

    /// The torque it applied to body B in the last step about the anchor, N·m.
    pub fn reaction_torque(&self) -> Real {
        self.torque
    }

    /// The anchors in the world, where `a` and `b` (its bodies) are now.
    pub fn world_anchors(&self, a: &Body, b: &Body) -> [Vec2; 2] {
        [
            a.world_point(self.local_anchor_a),
            b.world_point(self.local_anchor_b),
        ]
    }

    /// The angle of B relative to A less the reference angle, rad, in `(-π, π]`.
    pub fn angle(&self, a: &Body, b: &Body) -> Real {
        let relative = a.rotation().inverse() * b.rotation() * rotation(-self.reference_angle);
        angle_of(&relative)
    }

    /// Replaces its settings with a checked `kind` of the same kind, axis in A's frame.
    pub(crate) fn set_kind(&mut self, kind: JointKind) -> Result<(), CaromError> {
        if std::mem::discriminant(&kind) != std::mem::discriminant(&self.kind) {
            return Err(CaromError::JointKindChange {
                from: self.kind.name(),
                to: kind.name(),
            });
        }
        kind.validate()?;
        let mut kind = kind;
        if let Some(axis) = kind.axis_mut() {
            *axis = axis.normalize();
        }
        self.kind = kind;
        Ok(())
    }

    /// Records what the last step applied.
    pub(crate) fn set_reaction(&mut self, force: Vec2, torque: Real) {
        (self.force, self.torque) = (force, torque);
    }

    /// Whether the last step's reaction exceeded a break threshold.
    pub(crate) fn is_broken(&self) -> bool {
        self.force.norm() > self.break_force || self.torque.abs() > self.break_torque
    }
}

/// Something that happened to a joint during a step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum JointEvent {
    /// The joint applied more than its break force or torque and was removed.
    Broken {
        /// The joint, no longer in the world.
        joint: JointHandle,
        /// Its bodies.
        bodies: [BodyHandle; 2],
        /// The force it applied in its last step, N.
        force: Vec2,
        /// The torque it applied in its last step, N·m.
        torque: Real,
    },
}

/// Checks an anchor in its body's frame: farther than a shape may reach, its lever arm would
/// overflow the solver's effective mass.
fn check_anchor(anchor: Vec2) -> Result<(), CaromError> {
    check_extent("joint anchor, from its body", anchor.x)?;
    check_extent("joint anchor, from its body", anchor.y)
}

#[cfg(feature = "serde")]
impl Joint {
    /// Checks a joint read from a saved world: its settings as adding it checks them, and
    /// finite anchors, impulses and reactions.
    pub(crate) fn check_saved(&self) -> Result<(), CaromError> {
        self.kind.validate()?;
        if self.kind.has_anchors() {
            check_anchor(self.local_anchor_a)?;
            check_anchor(self.local_anchor_b)?;
        }
        let i = &self.impulses;
        for (name, value) in [
            ("joint anchor", self.local_anchor_a),
            ("joint anchor", self.local_anchor_b),
            ("joint force", self.force),
            ("joint impulse", i.linear),
            ("joint impulse", i.drive),
        ] {
            check_finite_vec(name, value)?;
        }
        for (name, value) in [
            ("joint reference angle", self.reference_angle),
            ("joint torque", self.torque),
            ("joint impulse", i.angular),
            ("joint impulse", i.axial),
            ("joint impulse", i.motor),
            ("joint impulse", i.lower),
            ("joint impulse", i.upper),
            ("pogo joint spring velocity", i.spring_velocity),
        ] {
            check_finite(name, value)?;
        }
        for (name, value) in [
            ("break force", self.break_force),
            ("break torque", self.break_torque),
        ] {
            if value.is_nan() {
                return Err(CaromError::non_finite(name, value));
            }
            if value < 0.0 {
                return Err(CaromError::OutOfRange {
                    name,
                    expected: "zero or positive",
                    value,
                });
            }
        }
        Ok(())
    }
}
