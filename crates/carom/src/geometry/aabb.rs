//! Axis-aligned bounding boxes.

use crate::math::{Real, Vec2};

/// An axis-aligned box from `min` to `max` (inclusive).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Aabb {
    /// The lower-left corner.
    pub min: Vec2,
    /// The upper-right corner.
    pub max: Vec2,
}

impl Aabb {
    /// A box from its corners; the caller guarantees `min <= max` component-wise.
    #[inline]
    pub fn new(min: Vec2, max: Vec2) -> Self {
        Aabb { min, max }
    }

    /// The smallest box holding every point, or `None` for no points.
    pub fn from_points(points: &[Vec2]) -> Option<Self> {
        let (first, rest) = points.split_first()?;
        let mut aabb = Aabb::new(*first, *first);
        for p in rest {
            aabb.min = aabb.min.inf(p);
            aabb.max = aabb.max.sup(p);
        }
        Some(aabb)
    }

    /// The centre of the box.
    #[inline]
    pub fn center(&self) -> Vec2 {
        (self.min + self.max) * 0.5
    }

    /// Half the box's size along each axis.
    #[inline]
    pub fn half_extents(&self) -> Vec2 {
        (self.max - self.min) * 0.5
    }

    /// The perimeter: the cost measure of a bounding-volume tree.
    #[inline]
    pub fn perimeter(&self) -> Real {
        let size = self.max - self.min;
        2.0 * (size.x + size.y)
    }

    /// The smallest box holding both boxes.
    #[inline]
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb::new(self.min.inf(&other.min), self.max.sup(&other.max))
    }

    /// The box grown by `margin` on every side.
    #[inline]
    pub fn fattened(&self, margin: Real) -> Aabb {
        let m = Vec2::new(margin, margin);
        Aabb::new(self.min - m, self.max + m)
    }

    /// True when the boxes share at least one point (touching counts).
    #[inline]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
    }

    /// True when `other` lies entirely inside this box.
    #[inline]
    pub fn contains(&self, other: &Aabb) -> bool {
        self.min.x <= other.min.x
            && self.min.y <= other.min.y
            && other.max.x <= self.max.x
            && other.max.y <= self.max.y
    }

    /// True when the point lies inside or on the box.
    #[inline]
    pub fn contains_point(&self, p: Vec2) -> bool {
        self.min.x <= p.x && p.x <= self.max.x && self.min.y <= p.y && p.y <= self.max.y
    }

    /// The range of fractions `t` in `[0, max_fraction]` for which `origin + t * translation`
    /// is inside the box, or `None` when the segment misses it (slab test).
    pub fn ray_interval(
        &self,
        origin: Vec2,
        translation: Vec2,
        max_fraction: Real,
    ) -> Option<(Real, Real)> {
        let mut lower: Real = 0.0;
        let mut upper = max_fraction;
        for axis in 0..2 {
            let (o, d) = (origin[axis], translation[axis]);
            if d == 0.0 {
                if o < self.min[axis] || o > self.max[axis] {
                    return None;
                }
            } else {
                let inv = 1.0 / d;
                let (mut t0, mut t1) = ((self.min[axis] - o) * inv, (self.max[axis] - o) * inv);
                if t0 > t1 {
                    std::mem::swap(&mut t0, &mut t1);
                }
                lower = lower.max(t0);
                upper = upper.min(t1);
                if lower > upper {
                    return None;
                }
            }
        }
        Some((lower, upper))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn union_overlap_and_containment() {
        let a = Aabb::new(vec2(0.0, 0.0), vec2(1.0, 1.0));
        let b = Aabb::new(vec2(1.0, 0.5), vec2(2.0, 2.0));
        let c = Aabb::new(vec2(1.5, 1.5), vec2(3.0, 3.0));
        assert!(a.overlaps(&b), "touching boxes overlap");
        assert!(!a.overlaps(&c));
        let u = a.union(&c);
        assert_eq!(u, Aabb::new(vec2(0.0, 0.0), vec2(3.0, 3.0)));
        assert!(u.contains(&b));
        assert!(!b.contains(&u));
        assert_eq!(a.perimeter(), 4.0);
        assert_eq!(a.fattened(0.5).perimeter(), 8.0);
    }

    #[test]
    fn ray_interval_clips_to_the_box() {
        let a = Aabb::new(vec2(1.0, -1.0), vec2(2.0, 1.0));
        let (t0, t1) = a.ray_interval(vec2(0.0, 0.0), vec2(4.0, 0.0), 1.0).unwrap();
        assert_eq!((t0, t1), (0.25, 0.5));
        assert!(
            a.ray_interval(vec2(0.0, 2.0), vec2(4.0, 0.0), 1.0)
                .is_none()
        );
        assert!(
            a.ray_interval(vec2(0.0, 0.0), vec2(0.5, 0.0), 1.0)
                .is_none()
        );
    }
}
