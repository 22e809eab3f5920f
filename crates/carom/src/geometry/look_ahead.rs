//! Look-ahead pairs: which pairs of fast bodies need a contact now.
//!
//! With continuous collision on, a moving body's broadphase box covers where its velocity
//! takes it in a step, so that a pair meets in the contacts before it can meet in space. The
//! box is swept by the body's own velocity, but what matters is how fast the two close: in a
//! crowd that moves together every box reaches a body or two ahead, though the bodies keep
//! their distances. So a pair with a body that outruns its fat box's margin (a runner) is
//! made, and kept, only while the two, moving at their velocities relative to each other, can
//! come within the margin in a step. Making and keeping read the same motions, kept in the
//! broadphase from the end of the last step, so a pair made is never dropped in the same step.

use crate::geometry::aabb::Aabb;
use crate::math::{Real, Vec2};

/// Where a collider can go in the next step, as the look-ahead test reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Motion {
    /// Its tight box, grown by the look-ahead margin (or, for a collider that is not a
    /// runner, its fat box, which holds every point it can reach in a step).
    pub aabb: Aabb,
    /// How far its body's velocity takes it in a step, m.
    pub shift: Vec2,
    /// How far its body's turn can carry its farthest point in a step, m.
    pub turn: Real,
}

impl Motion {
    /// A collider that stays within `aabb`.
    pub(crate) fn still(aabb: Aabb) -> Self {
        Motion {
            aabb,
            shift: Vec2::zeros(),
            turn: 0.0,
        }
    }

    /// True when every figure of it is finite (a saved world's is checked).
    #[cfg(feature = "serde")]
    pub(crate) fn is_finite(&self) -> bool {
        [self.aabb.min, self.aabb.max, self.shift]
            .iter()
            .all(|v| v.x.is_finite() && v.y.is_finite())
            && self.turn.is_finite()
    }

    /// True when the two can meet in the step: this one's box, swept by the pair's relative
    /// shift and grown by both turns, overlaps the other's.
    pub(crate) fn meets(&self, other: &Motion) -> bool {
        let shift = self.shift - other.shift;
        let moved = Aabb::new(self.aabb.min + shift, self.aabb.max + shift);
        self.aabb
            .union(&moved)
            .fattened(self.turn + other.turn)
            .overlaps(&other.aabb)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    fn unit_at(x: Real) -> Aabb {
        Aabb::new(vec2(x, 0.0), vec2(x + 1.0, 1.0))
    }

    #[test]
    fn bodies_moving_together_do_not_meet() {
        let a = Motion {
            aabb: unit_at(0.0),
            shift: vec2(5.0, 0.0),
            turn: 0.0,
        };
        let b = Motion {
            aabb: unit_at(2.0),
            ..a
        };
        assert!(!a.meets(&b) && !b.meets(&a));
    }

    #[test]
    fn a_closing_pair_meets_from_either_side() {
        let a = Motion {
            aabb: unit_at(0.0),
            shift: vec2(1.5, 0.0),
            turn: 0.0,
        };
        let b = Motion::still(unit_at(2.0));
        assert!(a.meets(&b) && b.meets(&a));
        // Moving apart, they do not.
        let away = Motion {
            shift: vec2(-1.5, 0.0),
            ..a
        };
        assert!(!away.meets(&b) && !b.meets(&away));
    }

    #[test]
    fn a_turn_reaches_across_the_gap() {
        let a = Motion {
            aabb: unit_at(0.0),
            shift: vec2(0.0, 0.0),
            turn: 0.6,
        };
        let b = Motion::still(unit_at(1.5));
        assert!(a.meets(&b) && b.meets(&a));
        let slow = Motion { turn: 0.4, ..a };
        assert!(!slow.meets(&b));
    }
}
