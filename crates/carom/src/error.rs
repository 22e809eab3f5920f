//! The one error type of the engine.

use crate::math::{Real, Vec2};

/// Everything that can go wrong when building shapes, bodies and worlds, or stepping them.
///
/// Each message says what was wrong and what would be accepted, so a user can fix the input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CaromError {
    /// A polygon needs at least three distinct, non-collinear points.
    #[error("a polygon needs at least 3 vertices, got {count}")]
    TooFewVertices {
        /// How many usable points were left.
        count: usize,
    },
    /// A value that must be finite was NaN or infinite.
    #[error("{what} must be finite, got {value}")]
    NonFinite {
        /// What the value was (for example "vertex 2 x" or "position").
        what: String,
        /// The offending value, as text so vectors and scalars both fit.
        value: String,
    },
    /// Two polygon vertices (closer than the weld tolerance) coincide.
    #[error("polygon vertices {first} and {second} coincide at ({x}, {y}); remove one of them")]
    DuplicateVertex {
        /// Index of the first vertex in the input.
        first: usize,
        /// Index of the second vertex in the input.
        second: usize,
        /// Where they coincide.
        x: Real,
        /// Where they coincide.
        y: Real,
    },
    /// The points enclose no area (all collinear, or degenerate).
    #[error("the polygon has zero area (its points are collinear or coincident)")]
    ZeroArea,
    /// A vertex turns the wrong way, so the polygon is not convex.
    #[error(
        "the polygon is not convex: vertex {index} at ({x}, {y}) is reflex; \
         use Polygon::hull to take the convex hull of the points"
    )]
    ReflexVertex {
        /// Index of the reflex vertex in the input.
        index: usize,
        /// Its position.
        x: Real,
        /// Its position.
        y: Real,
    },
    /// The outline winds around its interior more than once (a star or a figure eight).
    #[error(
        "the polygon's edges cross each other (its outline winds {turns} times); give the vertices in order around the outline"
    )]
    SelfIntersecting {
        /// How many times the outline turns around.
        turns: i32,
    },
    /// A circle radius was zero or negative.
    #[error("circle radius must be positive, got {radius}")]
    InvalidRadius {
        /// The rejected radius.
        radius: Real,
    },
    /// A density was zero or negative for a body that needs mass.
    #[error("density must be positive for a dynamic body, got {density}")]
    InvalidDensity {
        /// The rejected density.
        density: Real,
    },
    /// A chain was given a number of surfaces that is neither 1 nor one per link.
    #[error("a chain of {links} links takes 1 surface or {links}, got {count}")]
    ChainSurfaces {
        /// How many links the chain has.
        links: usize,
        /// How many surfaces it was given.
        count: usize,
    },
    /// A parameter was outside its allowed range.
    #[error("{name} must be {expected}, got {value}")]
    OutOfRange {
        /// The parameter's name.
        name: &'static str,
        /// What would be accepted.
        expected: &'static str,
        /// The rejected value.
        value: Real,
    },
    /// A handle refers to a body or collider that was removed (or never belonged to this
    /// world).
    #[error(
        "no {what} for handle {index}v{generation}: it was removed or belongs to another world"
    )]
    StaleHandle {
        /// What the handle was for: "body", "collider" or "joint".
        what: &'static str,
        /// The handle's slot index.
        index: u32,
        /// The handle's generation.
        generation: u32,
    },
    /// A joint joins two different bodies, except a mouse joint, which holds one.
    #[error("a {kind} joint needs two different bodies (a mouse joint names one body twice)")]
    JointBodies {
        /// The joint's kind.
        kind: &'static str,
    },
    /// A joint definition set something its kind does not have.
    #[error("a {kind} joint has no {setting}")]
    JointSetting {
        /// The joint's kind.
        kind: &'static str,
        /// The setting: "limits", "motor", "spring", ...
        setting: &'static str,
    },
    /// A joint's settings were replaced with another kind's.
    #[error("a {from} joint cannot become a {to} joint; remove it and add another")]
    JointKindChange {
        /// The joint's kind.
        from: &'static str,
        /// The kind asked for.
        to: &'static str,
    },
    /// A collider that is not a sensor was asked what overlaps it.
    #[error("collider {index}v{generation} is not a sensor; make it one with ColliderDef::sensor")]
    NotASensor {
        /// The collider handle's slot index.
        index: u32,
        /// The collider handle's generation.
        generation: u32,
    },
    /// A polygon written around its centroid (as a saved world writes it) must list its
    /// vertices counter-clockwise, convex to within rounding, or it would not be kept as
    /// written.
    #[error("a polygon given around its centroid must be counter-clockwise and convex")]
    SavedPolygon,
    /// A saved world does not hold together: it was written by another version of carom, or
    /// changed by hand.
    #[error("the saved world does not hold together: {reason}")]
    BadSave {
        /// What was found wrong first.
        reason: String,
    },
    /// A body needs a collider to have a shape and a mass.
    #[error("a body needs at least one collider (a shape)")]
    NoCollider,
    /// Two points that must be apart (a capsule's centres, a segment's ends, neighbouring
    /// points of a chain) coincide, or are closer than the linear slop (0.005 m).
    #[error("{what} coincide at ({x}, {y}): they must be at least 0.005 m apart")]
    CoincidentPoints {
        /// Which points, for example "capsule centres" or "chain points 3 and 4".
        what: String,
        /// Where they coincide.
        x: Real,
        /// Where they coincide.
        y: Real,
    },
    /// A chain has too few points to make a segment (or a loop).
    #[error("{kind} needs at least {needed} points, got {count}")]
    TooFewChainPoints {
        /// "an open chain" or "a closed chain".
        kind: &'static str,
        /// How many it needs.
        needed: usize,
        /// How many it got.
        count: usize,
    },
    /// The heap could not give the room a world was asked to reserve ([`crate::Capacity`]).
    #[error("the heap could not give room for {what}")]
    OutOfMemory {
        /// What the room was for: "bodies", "contacts", ...
        what: &'static str,
    },
}

impl CaromError {
    /// The error for a non-finite scalar called `what`.
    pub(crate) fn non_finite(what: impl Into<String>, value: Real) -> Self {
        CaromError::NonFinite {
            what: what.into(),
            value: value.to_string(),
        }
    }

    /// The error for a non-finite vector called `what`.
    pub(crate) fn non_finite_vec(what: impl Into<String>, value: Vec2) -> Self {
        CaromError::NonFinite {
            what: what.into(),
            value: format!("({}, {})", value.x, value.y),
        }
    }

    /// The error for a saved world that does not hold together, `reason` saying where.
    #[cfg(feature = "serde")]
    pub(crate) fn bad_save(reason: impl Into<String>) -> Self {
        CaromError::BadSave {
            reason: reason.into(),
        }
    }
}

/// Checks that a scalar is finite.
pub(crate) fn check_finite(what: &str, value: Real) -> Result<Real, CaromError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(CaromError::non_finite(what, value))
    }
}

/// Checks that a scalar is finite (else [`CaromError::NonFinite`]) and within `range` (else
/// [`CaromError::OutOfRange`], saying it must be `expected`).
pub(crate) fn check_within(
    name: &'static str,
    value: Real,
    range: std::ops::RangeInclusive<Real>,
    expected: &'static str,
) -> Result<Real, CaromError> {
    check_finite(name, value)?;
    if range.contains(&value) {
        Ok(value)
    } else {
        Err(CaromError::OutOfRange {
            name,
            expected,
            value,
        })
    }
}

/// Checks that a scalar is finite (else [`CaromError::NonFinite`]), positive and at most `max`
/// (else [`CaromError::OutOfRange`], saying it must be `expected`).
pub(crate) fn check_positive_up_to(
    name: &'static str,
    value: Real,
    max: Real,
    expected: &'static str,
) -> Result<Real, CaromError> {
    check_finite(name, value)?;
    if value > 0.0 && value <= max {
        Ok(value)
    } else {
        Err(CaromError::OutOfRange {
            name,
            expected,
            value,
        })
    }
}

/// Checks that a scalar is finite (else [`CaromError::NonFinite`]) and not negative (a
/// distance, a rate).
pub(crate) fn check_finite_not_negative(
    name: &'static str,
    value: Real,
) -> Result<Real, CaromError> {
    check_finite(name, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(CaromError::OutOfRange {
            name,
            expected: "finite and not negative",
            value,
        })
    }
}

/// Checks that both components of a vector are finite.
pub(crate) fn check_finite_vec(what: &str, value: Vec2) -> Result<Vec2, CaromError> {
    if crate::math::is_finite_vec(value) {
        Ok(value)
    } else {
        Err(CaromError::non_finite_vec(what, value))
    }
}
