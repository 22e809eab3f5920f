//! Which colliders a query sees.

use crate::dynamics::body::BodyHandle;
use crate::dynamics::filter::CollisionFilter;

/// Which colliders a query (a ray or shape cast, a box or shape overlap) sees. Every query
/// takes one; [`QueryFilter::ALL`] (the default) sees every collider.
///
/// A collider is seen when its category shares a bit with `mask`, when its own mask names
/// the query's `category` (a query in no category, 0, skips that test), and when it is not
/// on `exclude_body`. This is Box2D's rule for its query filters, with a query in no
/// category by default so that nothing is hidden unless asked; collision groups do not
/// apply to queries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct QueryFilter {
    /// The categories of colliders seen. Default every one.
    pub mask: u64,
    /// What the query is, for colliders that choose what finds them: when not 0, only
    /// colliders whose mask shares a bit with it are seen. Default 0.
    pub category: u64,
    /// A body whose colliders are not seen: the caster's own, say. Default none.
    pub exclude_body: Option<BodyHandle>,
}

impl QueryFilter {
    /// Sees every collider.
    pub const ALL: QueryFilter = QueryFilter {
        mask: u64::MAX,
        category: 0,
        exclude_body: None,
    };

    /// Sees only colliders whose category shares a bit with `mask`.
    pub fn mask(mask: u64) -> Self {
        QueryFilter {
            mask,
            ..QueryFilter::ALL
        }
    }

    /// Sees what a collider with `filter` would collide with, groups aside: colliders in its
    /// mask whose own mask names its category.
    pub fn like(filter: CollisionFilter) -> Self {
        QueryFilter {
            mask: filter.mask,
            category: filter.category,
            exclude_body: None,
        }
    }

    /// The same filter, not seeing `body`'s colliders.
    pub fn excluding(self, body: BodyHandle) -> Self {
        QueryFilter {
            exclude_body: Some(body),
            ..self
        }
    }

    /// Whether a collider with `filter`, on `body`, is seen.
    #[inline]
    pub fn sees(&self, filter: &CollisionFilter, body: BodyHandle) -> bool {
        filter.category & self.mask != 0
            && (self.category == 0 || filter.mask & self.category != 0)
            && self.exclude_body != Some(body)
    }
}

impl Default for QueryFilter {
    fn default() -> Self {
        QueryFilter::ALL
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_sees_every_collider_and_the_rest_sees_what_it_names() {
        let body = BodyHandle::from_raw_parts(3, 0);
        let other = BodyHandle::from_raw_parts(4, 0);
        let loner = CollisionFilter {
            category: 4,
            mask: 0,
            group: -1,
        };
        assert!(
            QueryFilter::ALL.sees(&loner, body),
            "a collider that collides with nothing"
        );
        assert!(QueryFilter::ALL.sees(&CollisionFilter::DEFAULT, body));
        assert!(!QueryFilter::mask(2).sees(&loner, body));
        assert!(QueryFilter::mask(4).sees(&loner, body));
        let named = QueryFilter::like(CollisionFilter::DEFAULT);
        assert!(
            !named.sees(&loner, body),
            "its mask does not name the query"
        );
        assert!(named.sees(&CollisionFilter::DEFAULT, body));
        let mine = QueryFilter::ALL.excluding(body);
        assert!(!mine.sees(&CollisionFilter::DEFAULT, body));
        assert!(mine.sees(&CollisionFilter::DEFAULT, other));
    }
}
