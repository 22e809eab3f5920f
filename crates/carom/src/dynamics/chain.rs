//! Chains: terrain and walls as a run of one-sided segments that bodies slide along smoothly.
//!
//! A chain is a list of points, open or closed into a loop. Each pair of neighbours becomes
//! one collider, a [`ChainSegment`] that knows the points beyond its ends (its ghost
//! vertices), so a body crossing from one link to the next meets one smooth surface (see
//! `geometry::query::chain_segment`). Links collide on their right side, seen walking along the
//! points: a counter-clockwise loop is solid outside, a clockwise one inside, and ground whose
//! solid side is below runs from right to left. Chains have no area and so no mass: they are
//! for static (or kinematic) bodies, and they do not collide with other chains.

use crate::dynamics::collider::ColliderDef;
use crate::dynamics::filter::CollisionFilter;
use crate::dynamics::surface::Surface;
use crate::error::CaromError;
use crate::geometry::checks::check_apart;
use crate::geometry::checks::check_point;
use crate::geometry::shape::{ChainSegment, Shape};
use crate::math::{Real, Vec2};

/// A chain's points and the material of its links; build one with [`ChainDef::open`] or
/// [`ChainDef::closed`], then attach it with [`crate::BodyDef::static_chain`] or
/// [`ChainDef::colliders`].
#[derive(Debug, Clone, PartialEq)]
pub struct ChainDef {
    /// The points, in order.
    pub points: Vec<Vec2>,
    /// Whether the last point joins back to the first.
    pub closed: bool,
    /// For an open chain, the points before the first and after the last that its end links
    /// should meet smoothly (another chain's, say); `None` continues each end straight on.
    pub ghosts: Option<(Vec2, Vec2)>,
    /// The links' surfaces: one for every link, or one per link in order (the link from
    /// point `i` to point `i + 1` takes surface `i`).
    pub surfaces: Vec<Surface>,
    /// What the links collide with.
    pub filter: CollisionFilter,
}

impl ChainDef {
    /// An open chain through `points` (at least 2), with default material.
    pub fn open(points: impl Into<Vec<Vec2>>) -> Self {
        ChainDef {
            points: points.into(),
            closed: false,
            ghosts: None,
            surfaces: vec![Surface::default()],
            filter: CollisionFilter::DEFAULT,
        }
    }

    /// A loop through `points` (at least 3), the last joined back to the first.
    pub fn closed(points: impl Into<Vec<Vec2>>) -> Self {
        ChainDef {
            closed: true,
            ..ChainDef::open(points)
        }
    }

    /// Sets the ghost vertices of an open chain's ends; see [`ChainDef::ghosts`].
    pub fn ghosts(mut self, before: Vec2, after: Vec2) -> Self {
        self.ghosts = Some((before, after));
        self
    }

    /// Sets the friction coefficient of every link.
    pub fn friction(mut self, friction: Real) -> Self {
        for surface in &mut self.surfaces {
            surface.friction = friction;
        }
        self
    }

    /// Sets the restitution of every link.
    pub fn restitution(mut self, restitution: Real) -> Self {
        for surface in &mut self.surfaces {
            surface.restitution = restitution;
        }
        self
    }

    /// Sets one surface for every link.
    pub fn surface(mut self, surface: Surface) -> Self {
        self.surfaces = vec![surface];
        self
    }

    /// Sets each link's surface, in order: one per link.
    pub fn link_surfaces(mut self, surfaces: impl Into<Vec<Surface>>) -> Self {
        self.surfaces = surfaces.into();
        self
    }

    /// Sets what the links collide with.
    pub fn filter(mut self, filter: CollisionFilter) -> Self {
        self.filter = filter;
        self
    }

    /// The links, each with its ghost vertices.
    ///
    /// # Errors
    /// Too few points (2 for an open chain, 3 for a loop), a point that is not finite or is
    /// beyond 100 km, or two neighbouring points that coincide.
    pub fn segments(&self) -> Result<Vec<ChainSegment>, CaromError> {
        let points = &self.points;
        let n = points.len();
        let (kind, needed) = if self.closed {
            ("a closed chain", 3)
        } else {
            ("an open chain", 2)
        };
        if n < needed {
            return Err(CaromError::TooFewChainPoints {
                kind,
                needed,
                count: n,
            });
        }
        for (i, &p) in points.iter().enumerate() {
            check_point((&format!("chain point {i}"), "chain coordinate"), p)?;
        }
        let links = if self.closed { n } else { n - 1 };
        for i in 0..links {
            let j = (i + 1) % n;
            check_apart(&format!("chain points {i} and {j}"), points[i], points[j])?;
        }
        // The point before `i` and the point after `i`, going round a loop or past an open
        // chain's ends (given, or straight on).
        let (before, after) = match self.ghosts {
            Some((before, after)) if !self.closed => {
                check_point(("chain ghost before", "chain coordinate"), before)?;
                check_point(("chain ghost after", "chain coordinate"), after)?;
                check_apart("chain ghost before and point 0", before, points[0])?;
                check_apart(
                    &format!("chain point {} and ghost after", n - 1),
                    points[n - 1],
                    after,
                )?;
                (before, after)
            }
            _ => (
                points[0] * 2.0 - points[1],
                points[n - 1] * 2.0 - points[n - 2],
            ),
        };
        let at = |i: isize| -> Vec2 {
            if self.closed {
                points[i.rem_euclid(n as isize) as usize]
            } else if i < 0 {
                before
            } else if i as usize >= n {
                after
            } else {
                points[i as usize]
            }
        };
        Ok((0..links as isize)
            .map(|i| ChainSegment::new(at(i - 1), at(i), at(i + 1), at(i + 2)))
            .collect())
    }

    /// One massless collider per link, with its surface.
    ///
    /// # Errors
    /// As [`ChainDef::segments`], and [`CaromError::ChainSurfaces`] for a number of surfaces
    /// that is neither 1 nor the number of links.
    pub fn colliders(&self) -> Result<Vec<ColliderDef>, CaromError> {
        let links = self.segments()?;
        if self.surfaces.len() != 1 && self.surfaces.len() != links.len() {
            return Err(CaromError::ChainSurfaces {
                links: links.len(),
                count: self.surfaces.len(),
            });
        }
        Ok(links
            .into_iter()
            .zip(self.surfaces.iter().cycle())
            .map(|(link, surface)| {
                ColliderDef::new(Shape::ChainSegment(link))
                    .density(0.0)
                    .surface(*surface)
                    .filter(self.filter)
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn links_know_their_neighbours() {
        let points = [vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(2.0, 1.0)];
        let open = ChainDef::open(points).segments().unwrap();
        assert_eq!(open.len(), 2);
        // Straight on past the ends.
        assert_eq!(open[0].ghost1(), vec2(-1.0, 0.0));
        assert_eq!(open[0].ghost2(), vec2(2.0, 1.0));
        assert_eq!(open[1].ghost1(), vec2(0.0, 0.0));
        assert_eq!(open[1].ghost2(), vec2(3.0, 2.0));
        let given = ChainDef::open(points)
            .ghosts(vec2(-1.0, 1.0), vec2(3.0, 0.0))
            .segments()
            .unwrap();
        assert_eq!(given[0].ghost1(), vec2(-1.0, 1.0));
        assert_eq!(given[1].ghost2(), vec2(3.0, 0.0));
        let closed = ChainDef::closed(points).segments().unwrap();
        assert_eq!(closed.len(), 3);
        assert_eq!(closed[0].ghost1(), vec2(2.0, 1.0));
        assert_eq!(closed[2].point2(), vec2(0.0, 0.0));
        assert_eq!(closed[2].ghost2(), vec2(1.0, 0.0));
    }

    #[test]
    fn bad_chains_are_named_errors() {
        let one = ChainDef::open(vec![vec2(0.0, 0.0)]).segments();
        assert_eq!(
            one,
            Err(CaromError::TooFewChainPoints {
                kind: "an open chain",
                needed: 2,
                count: 1
            })
        );
        assert!(
            ChainDef::closed(vec![vec2(0.0, 0.0), vec2(1.0, 0.0)])
                .segments()
                .is_err()
        );
        let repeated =
            ChainDef::open(vec![vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 0.0)]).segments();
        assert!(
            repeated
                .unwrap_err()
                .to_string()
                .contains("chain points 1 and 2")
        );
        assert!(
            ChainDef::open(vec![vec2(0.0, 0.0), vec2(Real::NAN, 0.0)])
                .segments()
                .is_err()
        );
    }
}
