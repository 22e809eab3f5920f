//! What each kind of joint holds, and the settings the kinds share: springs, motors, limits.

use crate::error::{CaromError, check_finite_not_negative};
use crate::math::{Real, Vec2, vec2};

/// A soft spring: its natural frequency and damping ratio. Frequency 0 is no spring at all
/// (the joint is free along what the spring would hold).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Spring {
    /// Hz, not negative.
    pub hertz: Real,
    /// 1 is critically damped; below it the spring overshoots. Not negative.
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

/// Drives B toward a pose relative to A with at most so much force and torque: a character
/// pushed around, a top-down body with friction against the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct MotorJoint {
    /// Where B's anchor should be relative to A's, in A's frame, m.
    pub linear_offset: Vec2,
    /// B's angle relative to A's (less the reference angle) it should have, rad.
    pub angular_offset: Real,
    /// N, not negative.
    pub max_force: Real,
    /// N·m, not negative.
    pub max_torque: Real,
    /// How much of the offset's error is closed per second, as a fraction of the step rate,
    /// in `[0, 1]`.
    pub correction_factor: Real,
}

impl Default for MotorJoint {
    fn default() -> Self {
        MotorJoint {
            linear_offset: Vec2::zeros(),
            angular_offset: 0.0,
            max_force: 1.0,
            max_torque: 1.0,
            correction_factor: 0.3,
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
            JointKind::Mouse(_) => "mouse",
            JointKind::Filter => "filter",
        }
    }

    /// Checks every setting, naming the first bad one.
    pub(crate) fn validate(&self) -> Result<(), CaromError> {
        match self {
            JointKind::Distance(j) => {
                positive("distance joint length", j.length)?;
                check_spring(j.spring.as_ref())?;
                check_motor(j.motor.as_ref())?;
                if let Some(range) = j.spring_force
                    && (range.lower.is_nan() || range.upper.is_nan() || range.lower > range.upper)
                {
                    return Err(CaromError::OutOfRange {
                        name: "distance joint spring force's lower bound",
                        expected: "a number not above the upper bound",
                        value: range.lower,
                    });
                }
                check_limits(j.limits.as_ref(), "distance joint limits")?;
                if let Some(limits) = j.limits {
                    not_negative("distance joint lower limit", limits.lower)?;
                }
                Ok(())
            }
            JointKind::Revolute(j) => {
                check_limits(j.limits.as_ref(), "revolute joint limits")?;
                check_motor(j.motor.as_ref())?;
                check_spring(j.spring.as_ref())?;
                finite("revolute joint target angle", j.target_angle)
            }
            JointKind::Prismatic(j) => {
                check_axis(j.axis)?;
                check_limits(j.limits.as_ref(), "prismatic joint limits")?;
                check_motor(j.motor.as_ref())?;
                check_spring(j.spring.as_ref())?;
                finite("prismatic joint target translation", j.target_translation)
            }
            JointKind::Weld(j) => {
                check_spring(j.linear.as_ref())?;
                check_spring(j.angular.as_ref())
            }
            JointKind::Wheel(j) => {
                check_axis(j.axis)?;
                check_spring(j.spring.as_ref())?;
                check_limits(j.limits.as_ref(), "wheel joint limits")?;
                check_motor(j.motor.as_ref())
            }
            JointKind::Motor(j) => {
                crate::error::check_finite_vec("motor joint linear offset", j.linear_offset)?;
                finite("motor joint angular offset", j.angular_offset)?;
                not_negative("motor joint max force", j.max_force)?;
                not_negative("motor joint max torque", j.max_torque)?;
                if !(0.0..=1.0).contains(&j.correction_factor) {
                    return Err(CaromError::OutOfRange {
                        name: "motor joint correction factor",
                        expected: "between 0 and 1",
                        value: j.correction_factor,
                    });
                }
                Ok(())
            }
            JointKind::Mouse(j) => {
                crate::error::check_finite_vec("mouse joint target", j.target)?;
                check_spring(Some(&j.spring))?;
                not_negative("mouse joint max force", j.max_force)
            }
            JointKind::Filter => Ok(()),
        }
    }

    /// The axis, for the kinds that have one.
    pub(crate) fn axis_mut(&mut self) -> Option<&mut Vec2> {
        match self {
            JointKind::Prismatic(j) => Some(&mut j.axis),
            JointKind::Wheel(j) => Some(&mut j.axis),
            _ => None,
        }
    }
}

fn finite(name: &'static str, value: Real) -> Result<(), CaromError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(CaromError::OutOfRange {
            name,
            expected: "finite",
            value,
        })
    }
}

fn not_negative(name: &'static str, value: Real) -> Result<(), CaromError> {
    // Infinite is allowed: an unbounded force or torque.
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
    if value.is_finite() && value > 0.0 {
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
    check_finite_not_negative("spring hertz", spring.hertz)?;
    check_finite_not_negative("spring damping ratio", spring.damping_ratio)?;
    Ok(())
}

fn check_motor(motor: Option<&Motor>) -> Result<(), CaromError> {
    let Some(motor) = motor else {
        return Ok(());
    };
    finite("motor speed", motor.speed)?;
    not_negative("motor max force", motor.max_force)
}

fn check_limits(limits: Option<&Limits>, name: &'static str) -> Result<(), CaromError> {
    let Some(limits) = limits else {
        return Ok(());
    };
    finite(name, limits.lower)?;
    finite(name, limits.upper)?;
    if limits.lower > limits.upper {
        return Err(CaromError::OutOfRange {
            name,
            expected: "ordered: the lower limit not above the upper",
            value: limits.lower,
        });
    }
    Ok(())
}

fn check_axis(axis: Vec2) -> Result<(), CaromError> {
    crate::error::check_finite_vec("joint axis", axis)?;
    let length = axis.norm();
    if length < 1.0e-6 {
        return Err(CaromError::OutOfRange {
            name: "joint axis length",
            expected: "not zero",
            value: length,
        });
    }
    Ok(())
}
