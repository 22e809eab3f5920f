//! The points of a polygon, placed or not: its vertices, its edges or their normals.

use crate::heap_bytes::HeapBytes;
use crate::math::Vec2;
use smallvec::SmallVec;
use std::fmt;
use std::ops::Deref;

/// How many points are held inline; a polygon with more keeps them on the heap. Box2D's
/// polygons have at most eight vertices, and so do nearly all that games use.
const INLINE_POINTS: usize = 8;

/// Points held inline with what owns them (up to eight), so that reading a polygon reads its
/// collider's memory and nothing beyond: the narrowphase reads two placed ones per contact, in
/// no order a cache can guess, and a snapshot copies them with the collider. Read as a slice;
/// made from any iterator of points.
#[derive(PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(transparent))]
pub struct Points(SmallVec<[Vec2; INLINE_POINTS]>);

// Cloned into the old points' storage (the derive's would make new storage for many).
impl Clone for Points {
    fn clone(&self) -> Self {
        Points(self.0.clone())
    }

    fn clone_from(&mut self, source: &Self) {
        self.0.clone_from(&source.0);
    }
}

// Nothing while the points fit inline; past that, the heap array they spilled into.
impl HeapBytes for Points {
    fn heap_bytes(&self) -> usize {
        let Points(points) = self;
        if points.spilled() {
            points.capacity() * size_of::<Vec2>()
        } else {
            0
        }
    }
}

impl Points {
    /// Becomes `points`, keeping its storage.
    pub(crate) fn set(&mut self, points: impl IntoIterator<Item = Vec2>) {
        self.0.clear();
        self.0.extend(points);
    }

    /// Becomes `from`'s points each mapped by `place`, in place when it holds as many (a
    /// moved shape's world points every step), else in fresh storage as [`Points::set`].
    #[inline]
    pub(crate) fn set_mapped(&mut self, from: &[Vec2], place: impl Fn(Vec2) -> Vec2) {
        if self.0.len() == from.len() {
            for (point, &p) in self.0.iter_mut().zip(from) {
                *point = place(p);
            }
        } else {
            self.set(from.iter().map(|&p| place(p)));
        }
    }

    /// The points, to change in place.
    pub(crate) fn as_mut_slice(&mut self) -> &mut [Vec2] {
        &mut self.0
    }
}

impl Deref for Points {
    type Target = [Vec2];

    #[inline]
    fn deref(&self) -> &[Vec2] {
        &self.0
    }
}

impl<'a> IntoIterator for &'a Points {
    type Item = &'a Vec2;
    type IntoIter = std::slice::Iter<'a, Vec2>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl FromIterator<Vec2> for Points {
    fn from_iter<I: IntoIterator<Item = Vec2>>(points: I) -> Self {
        Points(points.into_iter().collect())
    }
}

impl fmt::Debug for Points {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn holds_few_points_inline_and_many_on_the_heap() {
        let mut points = Points::default();
        points.set((0..3).map(|i| vec2(i as crate::math::Real, 0.0)));
        assert!(!points.0.spilled());
        assert_eq!(points[2], vec2(2.0, 0.0));
        points.set((0..12).map(|i| vec2(0.0, i as crate::math::Real)));
        assert!(points.0.spilled());
        assert_eq!((points.len(), points[11]), (12, vec2(0.0, 11.0)));
        points.set([vec2(1.0, 1.0)]);
        assert_eq!(&points[..], &[vec2(1.0, 1.0)]);
    }
}
