//! Which colliders may collide: Box2D's rule of categories, masks and groups.

/// A collider's collision filter. Two colliders collide when each one's category is in the
/// other's mask, unless they share a group: a positive group always collides within
/// itself, a negative one never does (the limbs of one ragdoll). Group 0 is no group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct CollisionFilter {
    /// What this collider is: usually one bit.
    pub category: u64,
    /// The categories it collides with.
    pub mask: u64,
    /// Its group: colliders of one positive group always collide, of one negative group
    /// never; 0 for none.
    pub group: i32,
}

impl CollisionFilter {
    /// Collides with everything: category 1, every bit of the mask, no group.
    pub const DEFAULT: CollisionFilter = CollisionFilter {
        category: 1,
        mask: u64::MAX,
        group: 0,
    };

    /// Whether colliders with these filters collide.
    #[inline]
    pub fn collides_with(&self, other: &CollisionFilter) -> bool {
        if self.group == other.group && self.group != 0 {
            return self.group > 0;
        }
        self.mask & other.category != 0 && other.mask & self.category != 0
    }
}

impl Default for CollisionFilter {
    fn default() -> Self {
        CollisionFilter::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_override_categories_and_masks() {
        let a = CollisionFilter {
            category: 2,
            mask: !2,
            group: 0,
        };
        assert!(!a.collides_with(&a), "a mask without its own category");
        assert!(a.collides_with(&CollisionFilter::DEFAULT));
        let limb = CollisionFilter {
            group: -3,
            ..CollisionFilter::DEFAULT
        };
        assert!(
            !limb.collides_with(&limb),
            "one negative group never collides"
        );
        assert!(limb.collides_with(&CollisionFilter::DEFAULT));
        let team = CollisionFilter { group: 4, ..a };
        assert!(
            team.collides_with(&team),
            "one positive group always collides"
        );
        let foot = CollisionFilter {
            category: 2,
            mask: 1,
            group: -3,
        };
        assert!(!foot.collides_with(&CollisionFilter {
            category: 2,
            ..CollisionFilter::DEFAULT
        }));
    }
}
