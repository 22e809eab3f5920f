//! The camera: which part of the world a view shows, and how screen pixels map to metres.

use carom::{Real, Vec2, vec2};

/// A 2D camera: the world point at the centre of the view and the scale in pixels per metre.
/// One metre is `zoom` pixels both ways, so shapes keep their aspect ratio in any view. Screen
/// coordinates are pixels from the view's top-left corner, y down; world y is up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// The world point at the centre of the view, m.
    pub center: Vec2,
    /// Pixels per metre.
    pub zoom: f32,
}

impl Camera {
    /// Closest and farthest zoom allowed, pixels per metre.
    pub const ZOOM_RANGE: (f32, f32) = (0.5, 5000.0);

    /// Where a world point appears in a view of `viewport` pixels.
    pub fn world_to_screen(&self, world: Vec2, viewport: [u32; 2]) -> Vec2 {
        let offset = (world - self.center) * self.zoom as Real;
        vec2(
            viewport[0] as Real * 0.5 + offset.x,
            viewport[1] as Real * 0.5 - offset.y,
        )
    }

    /// The world point under a screen point of a view of `viewport` pixels.
    pub fn screen_to_world(&self, screen: Vec2, viewport: [u32; 2]) -> Vec2 {
        let offset = vec2(
            screen.x - viewport[0] as Real * 0.5,
            viewport[1] as Real * 0.5 - screen.y,
        );
        self.center + offset / self.zoom as Real
    }

    /// Drags the view by `delta` screen pixels: what was under the cursor stays under it.
    pub fn pan_by_pixels(&mut self, delta: Vec2) {
        self.center -= vec2(delta.x, -delta.y) / self.zoom as Real;
    }

    /// Zooms by `factor` (above 1 zooms in) keeping the world point under `screen` in place.
    pub fn zoom_about(&mut self, screen: Vec2, factor: f32, viewport: [u32; 2]) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        let anchor = self.screen_to_world(screen, viewport);
        let (low, high) = Camera::ZOOM_RANGE;
        self.zoom = (self.zoom * factor).clamp(low, high);
        // Move the centre so the anchor lands back under the cursor.
        let drift = self.screen_to_world(screen, viewport) - anchor;
        self.center -= drift;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const VIEW: [u32; 2] = [800, 600];

    fn camera() -> Camera {
        Camera {
            center: vec2(2.0, 5.0),
            zoom: 40.0,
        }
    }

    #[test]
    fn screen_and_world_round_trip_with_y_up() {
        let camera = camera();
        assert_eq!(
            camera.world_to_screen(vec2(2.0, 5.0), VIEW),
            vec2(400.0, 300.0)
        );
        // One metre up is 40 pixels toward the top of the screen.
        assert_eq!(
            camera.world_to_screen(vec2(2.0, 6.0), VIEW),
            vec2(400.0, 260.0)
        );
        for point in [vec2(-3.0, 1.5), vec2(10.0, -7.25), vec2(0.0, 0.0)] {
            let back = camera.screen_to_world(camera.world_to_screen(point, VIEW), VIEW);
            assert!((back - point).norm() < 1e-4, "{point:?} -> {back:?}");
        }
    }

    #[test]
    fn panning_keeps_the_grabbed_point_under_the_cursor() {
        let mut camera = camera();
        let grabbed = camera.screen_to_world(vec2(100.0, 100.0), VIEW);
        camera.pan_by_pixels(vec2(30.0, -50.0));
        let now = camera.screen_to_world(vec2(130.0, 50.0), VIEW);
        assert!((now - grabbed).norm() < 1e-4);
    }

    #[test]
    fn zooming_keeps_the_point_under_the_cursor_and_stays_in_range() {
        let mut camera = camera();
        let cursor = vec2(650.0, 120.0);
        let under = camera.screen_to_world(cursor, VIEW);
        camera.zoom_about(cursor, 1.5, VIEW);
        assert_eq!(camera.zoom, 60.0);
        assert!((camera.screen_to_world(cursor, VIEW) - under).norm() < 1e-4);
        camera.zoom_about(cursor, 1e9, VIEW);
        assert_eq!(camera.zoom, Camera::ZOOM_RANGE.1);
        camera.zoom_about(cursor, f32::NAN, VIEW);
        assert_eq!(camera.zoom, Camera::ZOOM_RANGE.1);
    }
}
