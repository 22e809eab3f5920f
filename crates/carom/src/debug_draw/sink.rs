//! Where drawing goes: the [`DebugDraw`] sink and [`DrawList`], a sink that records.

use super::Color;
use crate::math::{Real, Vec2};

/// A sink for drawing primitives. Widths and sizes are screen pixels; everything else is metres.
pub trait DebugDraw {
    /// A convex polygon, vertices counter-clockwise, filled and outlined (the outline as
    /// thick as the renderer draws every outline).
    fn polygon(&mut self, vertices: &[Vec2], fill: Color, outline: Color);
    /// A disc, filled and outlined.
    fn circle(&mut self, center: Vec2, radius: Real, fill: Color, outline: Color);
    /// A straight line `width` pixels thick.
    fn segment(&mut self, start: Vec2, end: Vec2, width: f32, color: Color);
    /// An arrow from `start` to the head at `end`, as thick as the renderer draws arrows.
    fn arrow(&mut self, start: Vec2, end: Vec2, color: Color);
    /// A dot `size` pixels across.
    fn point(&mut self, at: Vec2, size: f32, color: Color);
}

/// A filled, outlined convex polygon of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawPolygon {
    /// Index of its first vertex in [`DrawList::vertices`].
    pub first: u32,
    /// How many vertices, counter-clockwise.
    pub count: u32,
    /// Interior colour.
    pub fill: Color,
    /// Outline colour.
    pub outline: Color,
}

/// A filled, outlined disc of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawCircle {
    /// Centre, m.
    pub center: Vec2,
    /// Radius, m.
    pub radius: Real,
    /// Interior colour.
    pub fill: Color,
    /// Outline colour.
    pub outline: Color,
}

/// A thick line of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawSegment {
    /// Start, m.
    pub start: Vec2,
    /// End, m.
    pub end: Vec2,
    /// Thickness, pixels.
    pub width: f32,
    /// Colour.
    pub color: Color,
}

/// An arrow of a [`DrawList`], its head at `end`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawArrow {
    /// Tail, m.
    pub start: Vec2,
    /// Head, m.
    pub end: Vec2,
    /// Colour.
    pub color: Color,
}

/// A dot of a [`DrawList`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawPoint {
    /// Where, m.
    pub at: Vec2,
    /// Diameter, pixels.
    pub size: f32,
    /// Colour.
    pub color: Color,
}

/// Every primitive recorded, by type, in drawing order within each type. A renderer draws
/// polygons, then circles, then segments and arrows, then points, so overlays stay on top.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrawList {
    /// Polygon vertices, shared by [`DrawList::polygons`].
    pub vertices: Vec<Vec2>,
    /// Filled polygons.
    pub polygons: Vec<DrawPolygon>,
    /// Filled discs.
    pub circles: Vec<DrawCircle>,
    /// Lines.
    pub segments: Vec<DrawSegment>,
    /// Arrows.
    pub arrows: Vec<DrawArrow>,
    /// Dots.
    pub points: Vec<DrawPoint>,
}

impl DrawList {
    /// An empty list.
    pub fn new() -> Self {
        Self::default()
    }

    /// Empties the list, keeping its memory for the next frame.
    pub fn clear(&mut self) {
        self.vertices.clear();
        self.polygons.clear();
        self.circles.clear();
        self.segments.clear();
        self.arrows.clear();
        self.points.clear();
    }

    /// True when nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
            && self.circles.is_empty()
            && self.segments.is_empty()
            && self.arrows.is_empty()
            && self.points.is_empty()
    }

    /// The vertices of one recorded polygon.
    pub fn polygon_vertices(&self, polygon: &DrawPolygon) -> &[Vec2] {
        let first = polygon.first as usize;
        &self.vertices[first..first + polygon.count as usize]
    }
}

impl DebugDraw for DrawList {
    fn polygon(&mut self, vertices: &[Vec2], fill: Color, outline: Color) {
        self.polygons.push(DrawPolygon {
            first: self.vertices.len() as u32,
            count: vertices.len() as u32,
            fill,
            outline,
        });
        self.vertices.extend_from_slice(vertices);
    }

    fn circle(&mut self, center: Vec2, radius: Real, fill: Color, outline: Color) {
        self.circles.push(DrawCircle {
            center,
            radius,
            fill,
            outline,
        });
    }

    fn segment(&mut self, start: Vec2, end: Vec2, width: f32, color: Color) {
        self.segments.push(DrawSegment {
            start,
            end,
            width,
            color,
        });
    }

    fn arrow(&mut self, start: Vec2, end: Vec2, color: Color) {
        self.arrows.push(DrawArrow { start, end, color });
    }

    fn point(&mut self, at: Vec2, size: f32, color: Color) {
        self.points.push(DrawPoint { at, size, color });
    }
}
