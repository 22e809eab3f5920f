//! What each kind of joint holds, and the settings the kinds share: springs, motors, limits.

use crate::constants::{MAX_ANGULAR_SPEED, MAX_JOINT_LENGTH, MAX_SPEED, MAX_SPRING};
use crate::dynamics::body::check_position;
use crate::error::{
    CaromError, check_finite, check_finite_not_negative, check_finite_vec, check_within,
};
use crate::math::consts::{PI, TAU};
use crate::math::{Real, Vec2, vec2};

/// A soft spring: its natural frequency and damping ratio. Frequency 0 is no spring at all
/// (the joint is free along what the spring would hold).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Spring {
    /// Hz, from 0 to 1e6.
    pub hertz: Real,
    /// 1 is critically damped; below it the spring overshoots. From 0 to 1e6.
    pub damping_ratio: Real,
}

impl Spring {
    /// A spring of `hertz` and `damping_ratio`.
    pub fn new(hertz: Real, damping_ratio: Real) -> Self {
        Spring {
            hertz,
            damping_ratio,
        }
    }
}

/// A motor: drives the joint's free motion at a speed, with at most so much force or torque.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Motor {
    /// rad/s for a turning motor, m/s for a sliding one.
    pub speed: Real,
    /// N·m for a turning motor, N for a sliding one; not negative.
    pub max_force: Real,
}

/// A range the joint's free motion stays within: angles (rad) or distances (m).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Limits {
    /// The least value, not above `upper`.
    pub lower: Real,
    /// The greatest value.
    pub upper: Real,
}

/// Holds two anchors at a distance: a rod, a spring, or a rope.
///
/// Without a spring the distance is held rigidly at `length`. With one, the spring pulls
/// toward `length` with a force within `spring_force`, a motor drives the length's rate,
/// and `limits`, if any, stop it rigidly outside `[lower, upper]`; a spring of 0 Hz with
/// limits `[0, L]` is a rope of length `L`. In that order, as Box2D 3.2 solves them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct DistanceJoint {
    /// The rest length, m (positive).
    pub length: Real,
    /// Soft instead of rigid.
    pub spring: Option<Spring>,
    /// The least and most force the spring applies, N: negative pulls the anchors together,
    /// positive pushes them apart. `lower` 0 makes a spring that only pushes, `upper` 0 one
    /// that only pulls. Default unbounded.
    #[cfg_attr(feature = "serde", serde(default))]
    pub spring_force: Option<Limits>,
    /// Drives the length's rate of change (m/s, positive lengthening) with at most
    /// `max_force` N (with a spring).
    #[cfg_attr(feature = "serde", serde(default))]
    pub motor: Option<Motor>,
    /// Lengths the anchors stay between (with a spring).
    pub limits: Option<Limits>,
}

/// A hinge: the anchors coincide and the bodies turn freely about them, within limits,
/// driven by a motor or pulled toward an angle by a spring.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct RevoluteJoint {
    /// The angles of B relative to A (less the reference angle) it stays between, rad.
    pub limits: Option<Limits>,
    /// Turns B relative to A.
    pub motor: Option<Motor>,
    /// Pulls the angle toward `target_angle`.
    pub spring: Option<Spring>,
    /// The angle the spring pulls to, rad.
    pub target_angle: Real,
}

/// A slider: B moves along an axis fixed in A, without turning relative to it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct PrismaticJoint {
    /// The direction of travel (in the world when the joint is defined from world points,
    /// in A's frame once made); a unit vector.
    pub axis: Vec2,
    /// The translations along the axis it stays between, m.
    pub limits: Option<Limits>,
    /// Drives the translation.
    pub motor: Option<Motor>,
    /// Pulls the translation toward `target_translation`.
    pub spring: Option<Spring>,
    /// The translation the spring pulls to, m.
    pub target_translation: Real,
}

impl Default for PrismaticJoint {
    fn default() -> Self {
        PrismaticJoint {
            axis: vec2(1.0, 0.0),
            limits: None,
            motor: None,
            spring: None,
            target_translation: 0.0,
        }
    }
}

/// Glues two bodies together, rigidly or through linear and angular springs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct WeldJoint {
    /// Soft translation (rigid without).
    pub linear: Option<Spring>,
    /// Soft rotation (rigid without).
    pub angular: Option<Spring>,
}

/// A wheel on a suspension: B's anchor stays on an axis fixed in A, sprung along it, and B
/// turns freely, driven by a motor.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct WheelJoint {
    /// The suspension's direction (as [`PrismaticJoint::axis`]); a unit vector.
    pub axis: Vec2,
    /// The suspension (none leaves the wheel free along the axis, within the limits).
    pub spring: Option<Spring>,
    /// The translations along the axis it stays between, m.
    pub limits: Option<Limits>,
    /// Turns the wheel.
    pub motor: Option<Motor>,
}

impl Default for WheelJoint {
    fn default() -> Self {
        WheelJoint {
            axis: vec2(0.0, 1.0),
            spring: Some(Spring::new(4.0, 0.7)),
            limits: None,
            motor: None,
        }
    }
}

/// Drives B relative to A in two parts, each with its own force and torque caps, as Box2D
/// 3.2's motor joint does: a velocity part (B's anchor moves at `linear_velocity` relative
/// to A's, and B turns at `angular_velocity` relative to A) and a spring part (B's anchor
/// is pulled to `linear_offset` from A's anchor, and B's angle to `angular_offset`, both
/// relative to A). A part whose cap is 0 does nothing, so the default does nothing.
///
/// A top-down body with friction against the ground is the velocity part at rest with the
/// friction force as its cap; a body dragged toward a target is the spring part.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct MotorJoint {
    /// The velocity B's anchor is driven at relative to A's, in the world, m/s.
    pub linear_velocity: Vec2,
    /// The most force the velocity part applies, N (0: no linear velocity part).
    pub max_velocity_force: Real,
    /// The rate B is turned at relative to A, rad/s.
    pub angular_velocity: Real,
    /// The most torque the velocity part applies, N·m (0: no angular velocity part).
    pub max_velocity_torque: Real,
    /// Where the spring pulls B's anchor, relative to A's anchor in A's frame, m.
    pub linear_offset: Vec2,
    /// The angle the spring turns B to relative to A (less the reference angle), rad.
    pub angular_offset: Real,
    /// The spring pulling the anchor (0 Hz: none).
    pub linear_spring: Spring,
    /// The most force the linear spring applies, N.
    pub max_spring_force: Real,
    /// The spring turning B (0 Hz: none).
    pub angular_spring: Spring,
    /// The most torque the angular spring applies, N·m.
    pub max_spring_torque: Real,
}

impl Default for MotorJoint {
    fn default() -> Self {
        MotorJoint {
            linear_velocity: Vec2::zeros(),
            max_velocity_force: 0.0,
            angular_velocity: 0.0,
            max_velocity_torque: 0.0,
            linear_offset: Vec2::zeros(),
            angular_offset: 0.0,
            linear_spring: Spring::new(4.0, 1.0),
            max_spring_force: 0.0,
            angular_spring: Spring::new(4.0, 1.0),
            max_spring_torque: 0.0,
        }
    }
}

/// Drives B's velocity relative to A's with at most so much force on each world axis, and
/// leaves its rotation alone: how a dynamic character walks (Box2D's mover joint). An axis
/// whose force is 0 is free, so a walker driven along x still falls under gravity.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct MoverJoint {
    /// The velocity B is driven at relative to A, in the world, m/s.
    pub velocity: Vec2,
    /// The most force on each world axis (x, y), N, not negative.
    pub max_force: Vec2,
}

/// A leg: a spring that holds B's foot (its anchor) `rest_length` above a point on the
/// ground (A's anchor), pushing along the ground's normal with at most `max_compression`
/// and pulling with at most `max_tension` (Box2D's pogo joint). The spring sets the speed
/// of the foot, not a force, so it holds any mass at its rest length as long as the forces
/// suffice; the length is measured along B's own up (its frame's +y).
///
/// It does not look for the ground: re-make it on what a ray from the foot hits as the
/// character moves ([`crate::JointDef::continue_from`] keeps the leg's momentum).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct PogoJoint {
    /// The ground's normal (in the world when the joint is defined from world points, in A's
    /// frame once made); a unit vector.
    pub normal: Vec2,
    /// The length the leg holds, m, not negative.
    pub rest_length: Real,
    /// The leg's spring (0 Hz: the leg does nothing).
    pub spring: Spring,
    /// The most force pushing B away from the ground, N.
    pub max_compression: Real,
    /// The most force pulling B toward the ground, N (0 lets it jump off).
    pub max_tension: Real,
}

impl Default for PogoJoint {
    fn default() -> Self {
        PogoJoint {
            normal: vec2(0.0, 1.0),
            rest_length: 1.0,
            spring: Spring::new(5.0, 0.8),
            max_compression: 0.0,
            max_tension: 0.0,
        }
    }
}

/// Pulls a point of a body toward a target in the world through a soft spring with a force
/// cap: how a user grabs and throws. The body still collides on the way.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct MouseJoint {
    /// Where the point is pulled, in the world.
    pub target: Vec2,
    /// The spring (defaults: 5 Hz, damping ratio 0.7).
    pub spring: Spring,
    /// N, not negative.
    pub max_force: Real,
}

impl Default for MouseJoint {
    fn default() -> Self {
        MouseJoint {
            target: Vec2::zeros(),
            spring: Spring::new(5.0, 0.7),
            max_force: 1000.0,
        }
    }
}

/// What a joint does.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum JointKind {
    /// See [`DistanceJoint`].
    Distance(DistanceJoint),
    /// See [`RevoluteJoint`].
    Revolute(RevoluteJoint),
    /// See [`PrismaticJoint`].
    Prismatic(PrismaticJoint),
    /// See [`WeldJoint`].
    Weld(WeldJoint),
    /// See [`WheelJoint`].
    Wheel(WheelJoint),
    /// See [`MotorJoint`].
    Motor(MotorJoint),
    /// See [`MoverJoint`].
    Mover(MoverJoint),
    /// See [`PogoJoint`].
    Pogo(PogoJoint),
    /// See [`MouseJoint`]: one body (both handles name it).
    Mouse(MouseJoint),
    /// Only keeps the two bodies from colliding.
    Filter,
}

impl JointKind {
    /// Its name, for messages and menus: "distance", "revolute", ...
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Distance(_) => "distance",
            JointKind::Revolute(_) => "revolute",
            JointKind::Prismatic(_) => "prismatic",
            JointKind::Weld(_) => "weld",
            JointKind::Wheel(_) => "wheel",
            JointKind::Motor(_) => "motor",
            JointKind::Mover(_) => "mover",
            JointKind::Pogo(_) => "pogo",
            JointKind::Mouse(_) => "mouse",
            JointKind::Filter => "filter",
        }
    }

    /// Checks every setting, naming the first bad one.
    pub(crate) fn validate(&self) -> Result<(), CaromError> {
        match self {
            JointKind::Distance(j) => {
                positive("distance joint length", j.length)?;
                length("distance joint length", j.length)?;
                check_spring(j.spring.as_ref())?;
                check_motor(j.motor.as_ref(), speed)?;
                if let Some(range) = j.spring_force
                    && (range.lower.is_nan() || range.upper.is_nan() || range.lower > range.upper)
                {
                    return Err(CaromError::OutOfRange {
                        name: "distance joint spring force's lower bound",
                        expected: "a number not above the upper bound",
                        value: range.lower,
                    });
                }
                check_limits(j.limits.as_ref(), "distance joint limits", length)?;
                if let Some(limits) = j.limits {
                    not_negative("distance joint lower limit", limits.lower)?;
                }
                Ok(())
            }
            JointKind::Revolute(j) => {
                check_limits(j.limits.as_ref(), "revolute joint limits", half_turn)?;
                check_motor(j.motor.as_ref(), spin)?;
                check_spring(j.spring.as_ref())?;
                angle("revolute joint target angle", j.target_angle).map(drop)
            }
            JointKind::Prismatic(j) => {
                check_axis(j.axis)?;
                check_limits(j.limits.as_ref(), "prismatic joint limits", length)?;
                check_motor(j.motor.as_ref(), speed)?;
                check_spring(j.spring.as_ref())?;
                length("prismatic joint target translation", j.target_translation).map(drop)
            }
            JointKind::Weld(j) => {
                check_spring(j.linear.as_ref())?;
                check_spring(j.angular.as_ref())
            }
            JointKind::Wheel(j) => {
                check_axis(j.axis)?;
                check_spring(j.spring.as_ref())?;
                check_limits(j.limits.as_ref(), "wheel joint limits", length)?;
                check_motor(j.motor.as_ref(), spin)
            }
            JointKind::Motor(j) => {
                check_finite_vec("motor joint linear velocity", j.linear_velocity)?;
                speed("motor joint linear velocity", j.linear_velocity.x)?;
                speed("motor joint linear velocity", j.linear_velocity.y)?;
                spin("motor joint angular velocity", j.angular_velocity)?;
                check_finite_vec("motor joint linear offset", j.linear_offset)?;
                length("motor joint linear offset", j.linear_offset.x)?;
                length("motor joint linear offset", j.linear_offset.y)?;
                angle("motor joint angular offset", j.angular_offset)?;
                check_spring(Some(&j.linear_spring))?;
                check_spring(Some(&j.angular_spring))?;
                for (name, value) in [
                    ("motor joint max velocity force", j.max_velocity_force),
                    ("motor joint max velocity torque", j.max_velocity_torque),
                    ("motor joint max spring force", j.max_spring_force),
                    ("motor joint max spring torque", j.max_spring_torque),
                ] {
                    not_negative(name, value)?;
                }
                Ok(())
            }
            JointKind::Mover(j) => {
                check_finite_vec("mover joint velocity", j.velocity)?;
                speed("mover joint velocity", j.velocity.x)?;
                speed("mover joint velocity", j.velocity.y)?;
                not_negative("mover joint max force", j.max_force.x)?;
                not_negative("mover joint max force", j.max_force.y)
            }
            JointKind::Pogo(j) => {
                check_direction("pogo joint normal", j.normal)?;
                check_finite_not_negative("pogo joint rest length", j.rest_length)?;
                length("pogo joint rest length", j.rest_length)?;
                check_spring(Some(&j.spring))?;
                not_negative("pogo joint max compression", j.max_compression)?;
                not_negative("pogo joint max tension", j.max_tension)
            }
            JointKind::Mouse(j) => {
                check_position("mouse joint target", j.target)?;
                check_spring(Some(&j.spring))?;
                not_negative("mouse joint max force", j.max_force)
            }
            JointKind::Filter => Ok(()),
        }
    }

    /// Whether the kind acts at its anchors: a mover drives one body's velocity and a filter
    /// only keeps two bodies apart, so theirs (the world's origin) mean nothing.
    pub(crate) fn has_anchors(&self) -> bool {
        !matches!(self, JointKind::Mover(_) | JointKind::Filter)
    }

    /// The axis (a pogo joint's normal), for the kinds that have one.
    pub(crate) fn axis_mut(&mut self) -> Option<&mut Vec2> {
        match self {
            JointKind::Prismatic(j) => Some(&mut j.axis),
            JointKind::Wheel(j) => Some(&mut j.axis),
            JointKind::Pogo(j) => Some(&mut j.normal),
            _ => None,
        }
    }
}

fn not_negative(name: &'static str, value: Real) -> Result<(), CaromError> {
    // Infinite is allowed: an unbounded force or torque.
    if value.is_nan() {
        return Err(CaromError::non_finite(name, value));
    }
    if value >= 0.0 {
        Ok(())
    } else {
        Err(CaromError::OutOfRange {
            name,
            expected: "not negative",
            value,
        })
    }
}

fn positive(name: &'static str, value: Real) -> Result<(), CaromError> {
    check_finite(name, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(CaromError::OutOfRange {
            name,
            expected: "finite and positive",
            value,
        })
    }
}

fn check_spring(spring: Option<&Spring>) -> Result<(), CaromError> {
    let Some(spring) = spring else {
        return Ok(());
    };
    let (range, expected) = (0.0..=MAX_SPRING, "from 0 to 1e6");
    check_within("spring hertz", spring.hertz, range.clone(), expected)?;
    check_within(
        "spring damping ratio",
        spring.damping_ratio,
        range,
        expected,
    )?;
    Ok(())
}

/// A motor's speed is checked by `speed`, the linear or the angular bound as the joint moves.
fn check_motor(
    motor: Option<&Motor>,
    speed: fn(&'static str, Real) -> Result<Real, CaromError>,
) -> Result<(), CaromError> {
    let Some(motor) = motor else {
        return Ok(());
    };
    speed("motor speed", motor.speed)?;
    not_negative("motor max force", motor.max_force)
}

/// Limits, each within `bound` (a length's or an angle's), the lower not above the upper.
fn check_limits(
    limits: Option<&Limits>,
    name: &'static str,
    bound: fn(&'static str, Real) -> Result<Real, CaromError>,
) -> Result<(), CaromError> {
    let Some(limits) = limits else {
        return Ok(());
    };
    bound(name, limits.lower)?;
    bound(name, limits.upper)?;
    if limits.lower > limits.upper {
        return Err(CaromError::OutOfRange {
            name,
            expected: "ordered: the lower limit not above the upper",
            value: limits.lower,
        });
    }
    Ok(())
}

/// A length, translation or offset: within [`MAX_JOINT_LENGTH`] either way.
fn length(name: &'static str, value: Real) -> Result<Real, CaromError> {
    let bound = MAX_JOINT_LENGTH;
    check_within(name, value, -bound..=bound, "within 1e7 m either way")
}

/// An angle: within a turn either way.
fn angle(name: &'static str, value: Real) -> Result<Real, CaromError> {
    check_within(name, value, -TAU..=TAU, "within a turn (2π) either way")
}

/// A revolute joint's limit: within half a turn either way, since the angle it bounds is
/// measured in (-π, π] and a limit beyond would never act. The slack takes `f32`'s π in the
/// `f64` build.
fn half_turn(name: &'static str, value: Real) -> Result<Real, CaromError> {
    let bound = PI + 1.0e-6;
    check_within(
        name,
        value,
        -bound..=bound,
        "within half a turn (π) either way",
    )
}

/// A linear speed: within [`MAX_SPEED`] either way.
fn speed(name: &'static str, value: Real) -> Result<Real, CaromError> {
    check_within(
        name,
        value,
        -MAX_SPEED..=MAX_SPEED,
        "within 1e6 m/s either way",
    )
}

/// An angular speed: within [`MAX_ANGULAR_SPEED`] either way.
fn spin(name: &'static str, value: Real) -> Result<Real, CaromError> {
    let bound = MAX_ANGULAR_SPEED;
    check_within(name, value, -bound..=bound, "within 1e6 rad/s either way")
}

fn check_axis(axis: Vec2) -> Result<(), CaromError> {
    check_direction("joint axis", axis)
}

fn check_direction(name: &'static str, axis: Vec2) -> Result<(), CaromError> {
    check_finite_vec(name, axis)?;
    // Normalised later: too short, its direction is rounding; too long, its square overflows.
    let length = axis.norm();
    if !(1.0e-6..=1.0e18).contains(&length) {
        return Err(CaromError::OutOfRange {
            name,
            expected: "from 1e-6 to 1e18 long",
            value: length,
        });
    }
    Ok(())
}
