//! Area, centroid and rotational inertia of shapes of uniform density.
//!
//! Polygons are split into triangles: the area by the shoelace formula, the centroid as the
//! area-weighted mean of the triangles' barycentres, and the polar moment from the per-triangle
//! formula `I = ρ · cross(p, q) / 12 · (p·p + p·q + q·q)` for the triangle (origin, p, q).
//! Every triangle area is *signed*, so the sum is right wherever the origin lies, inside the
//! polygon or not. The sums run in `f64`: they are done once per shape and the extra digits
//! keep the centroid exact enough to recentre large coordinates.

use crate::error::CaromError;
use crate::math::{Real, Vec2, atan2_f64, sin_cos_f64};
use std::f64::consts::PI;

/// Mass, centre of mass and rotational inertia of a shape.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassProperties {
    /// Mass in kilograms (density times area).
    pub mass: Real,
    /// Centre of mass in the shape's local frame.
    pub center: Vec2,
    /// Rotational inertia about the centre of mass, in kg·m².
    pub inertia: Real,
}

impl MassProperties {
    /// `1 / mass`, or 0 for a massless (static) description.
    #[inline]
    pub fn inv_mass(&self) -> Real {
        if self.mass > 0.0 {
            1.0 / self.mass
        } else {
            0.0
        }
    }

    /// `1 / inertia`, or 0 when there is no rotational inertia.
    #[inline]
    pub fn inv_inertia(&self) -> Real {
        if self.inertia > 0.0 {
            1.0 / self.inertia
        } else {
            0.0
        }
    }

    /// Inertia about another point, by the parallel-axis theorem: `I + m d²`.
    #[inline]
    pub fn inertia_about(&self, point: Vec2) -> Real {
        self.inertia + self.mass * (self.center - point).norm_squared()
    }
}

/// Area, centroid and second moment of a polygon outline, in `f64`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Moments {
    /// Signed area: positive for counter-clockwise outlines.
    pub area: f64,
    /// Area-weighted centroid.
    pub centroid: [f64; 2],
    /// Polar second moment of area about the origin (inertia at unit density).
    pub second_moment: f64,
}

/// The moments of a closed outline given by its vertices in order.
///
/// Returns `None` when the area is zero (the centroid is then undefined).
pub(crate) fn moments(points: &[Vec2]) -> Option<Moments> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let p = |i: usize| [points[i].x as f64, points[i].y as f64];
    // Centroid triangles are fanned from the first vertex: with large coordinates this keeps
    // the cross products small and the sum accurate.
    let origin = p(0);
    let mut area = 0.0;
    let mut cx = 0.0;
    let mut cy = 0.0;
    for i in 1..n - 1 {
        let (a, b) = (p(i), p(i + 1));
        let (ex, ey) = (a[0] - origin[0], a[1] - origin[1]);
        let (fx, fy) = (b[0] - origin[0], b[1] - origin[1]);
        let triangle_area = 0.5 * (ex * fy - ey * fx);
        area += triangle_area;
        cx += triangle_area * (ex + fx) / 3.0;
        cy += triangle_area * (ey + fy) / 3.0;
    }
    if area == 0.0 || !area.is_finite() {
        return None;
    }
    let centroid = [origin[0] + cx / area, origin[1] + cy / area];

    let mut second_moment = 0.0;
    for i in 0..n {
        let (a, b) = (p(i), p((i + 1) % n));
        let cross = a[0] * b[1] - a[1] * b[0];
        let dots =
            a[0] * a[0] + a[1] * a[1] + a[0] * b[0] + a[1] * b[1] + b[0] * b[0] + b[1] * b[1];
        second_moment += cross * dots / 12.0;
    }
    Some(Moments {
        area,
        centroid,
        second_moment,
    })
}

/// Signed area of a polygon outline (shoelace formula): positive when counter-clockwise.
pub fn polygon_area(points: &[Vec2]) -> Real {
    moments(points).map_or(0.0, |m| m.area as Real)
}

/// Centroid of a polygon outline, or `None` when it has no area.
pub fn polygon_centroid(points: &[Vec2]) -> Option<Vec2> {
    moments(points).map(|m| Vec2::new(m.centroid[0] as Real, m.centroid[1] as Real))
}

/// Rotational inertia of a polygon of uniform `density` about the origin of its coordinates.
///
/// The outline may be given in either winding; the result is the physical (positive) inertia.
#[cfg(any(test, feature = "testing"))]
pub fn polygon_inertia_about_origin(points: &[Vec2], density: Real) -> Real {
    moments(points).map_or(0.0, |m| {
        // Reversing the winding flips the sign of every term, so the sign of the area fixes it.
        (density as f64 * m.second_moment * m.area.signum()) as Real
    })
}

/// Checks that a density is usable for a body with mass.
pub(crate) fn check_density(density: Real) -> Result<Real, CaromError> {
    if !density.is_finite() {
        return Err(CaromError::non_finite("density", density));
    }
    if density <= 0.0 {
        return Err(CaromError::InvalidDensity { density });
    }
    Ok(density)
}

/// Mass properties of a circle centred on its local origin: `m = ρπr²`, `I = m r² / 2`.
pub(crate) fn circle_mass(radius: Real, density: Real) -> MassProperties {
    let r = radius as f64;
    let mass = density as f64 * PI * r * r;
    MassProperties {
        mass: mass as Real,
        center: Vec2::zeros(),
        inertia: (0.5 * mass * r * r) as Real,
    }
}

/// Mass properties of a polygon outline (any winding) at uniform density.
///
/// The inertia is about the centroid. Returns `None` for an outline with zero area.
pub fn polygon_mass(points: &[Vec2], density: Real) -> Option<MassProperties> {
    let m = moments(points)?;
    let area = m.area.abs();
    let rho = density as f64;
    let [cx, cy] = m.centroid;
    // Parallel-axis theorem, from the origin to the centroid: I_c = I_o - A d².
    let about_origin = m.second_moment * m.area.signum();
    let about_centroid = (about_origin - area * (cx * cx + cy * cy)).max(0.0);
    Some(MassProperties {
        mass: (rho * area) as Real,
        center: Vec2::new(cx as Real, cy as Real),
        inertia: (rho * about_centroid) as Real,
    })
}

/// Mass properties of a convex core grown by `radius` at uniform density: a rounded polygon
/// (a counter-clockwise core of three or more vertices) or a capsule (a core of two).
///
/// Exact: the shape is the core, a rectangle `radius` deep on the outside of each edge, and a
/// circular sector at each vertex between its edges' normals (the sectors make one whole
/// circle). The inertia is about the centroid, which [`MassProperties::center`] gives.
pub(crate) fn rounded_mass(core: &[Vec2], radius: Real, density: Real) -> MassProperties {
    let r = radius as f64;
    let n = core.len();
    let point = |v: Vec2| [v.x as f64, v.y as f64];
    let mut area = 0.0;
    let mut first = [0.0f64; 2];
    let mut second = 0.0;
    let mut add = |a: f64, centroid: [f64; 2], own_second: f64| {
        area += a;
        first[0] += a * centroid[0];
        first[1] += a * centroid[1];
        second += own_second + a * (centroid[0] * centroid[0] + centroid[1] * centroid[1]);
    };
    if n >= 3
        && let Some(m) = moments(core)
    {
        let a = m.area.abs();
        let [cx, cy] = m.centroid;
        // `moments` gives the second moment about the origin; split it at the centroid.
        let own = m.second_moment * m.area.signum() - a * (cx * cx + cy * cy);
        add(a, m.centroid, own);
    }
    // Each edge's outward normal; a two-vertex core has one edge each way.
    let normal = |i: usize| {
        let [x0, y0] = point(core[i]);
        let [x1, y1] = point(core[(i + 1) % n]);
        let (ex, ey) = (x1 - x0, y1 - y0);
        let length = (ex * ex + ey * ey).sqrt();
        ([ey / length, -ex / length], length)
    };
    for i in 0..n {
        let ([nx, ny], length) = normal(i);
        let [x0, y0] = point(core[i]);
        let [x1, y1] = point(core[(i + 1) % n]);
        let a = length * r;
        let centroid = [
            0.5 * (x0 + x1) + 0.5 * r * nx,
            0.5 * (y0 + y1) + 0.5 * r * ny,
        ];
        add(a, centroid, a * (length * length + r * r) / 12.0);
    }
    for (i, &vertex) in core.iter().enumerate() {
        let ([px, py], _) = normal((i + n - 1) % n);
        let ([qx, qy], _) = normal(i);
        // The sector's angle, from the previous edge's normal round to the next one's; the
        // turn is counter-clockwise, so the cross product is never negative (a two-vertex
        // core turns half round, where it is zero).
        let angle = atan2_f64((px * qy - py * qx).abs(), px * qx + py * qy);
        let a = 0.5 * angle * r * r;
        // Its centroid lies on the bisector, 2 r sin(α) / (3 α) from the vertex, α = angle / 2.
        let half = 0.5 * angle;
        let (sin, cos) = sin_cos_f64(half);
        let bisector = [px * cos - py * sin, px * sin + py * cos];
        let reach = 2.0 * r * sin / (3.0 * half);
        let [vx, vy] = point(vertex);
        let centroid = [vx + reach * bisector[0], vy + reach * bisector[1]];
        // About the vertex the sector's polar moment is a r² / 2; moved to its own centroid.
        let own = a * (0.5 * r * r - reach * reach);
        add(a, centroid, own);
    }
    let rho = density as f64;
    let center = [first[0] / area, first[1] / area];
    let about_center = (second - area * (center[0] * center[0] + center[1] * center[1])).max(0.0);
    MassProperties {
        mass: (rho * area) as Real,
        center: Vec2::new(center[0] as Real, center[1] as Real),
        inertia: (rho * about_center) as Real,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    fn pts(coords: &[(Real, Real)]) -> Vec<Vec2> {
        coords.iter().map(|&(x, y)| vec2(x, y)).collect()
    }

    #[test]
    fn unit_square_about_its_centre() {
        let square = pts(&[(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]);
        let mass = polygon_mass(&square, 2.0).unwrap();
        assert_eq!(mass.mass, 2.0);
        assert_eq!(mass.center, vec2(0.0, 0.0));
        // Box: m (w² + h²) / 12.
        assert!((mass.inertia - 2.0 * 2.0 / 12.0).abs() < 1e-7);
    }

    #[test]
    fn winding_does_not_change_the_physics() {
        let ccw = pts(&[(1.0, 1.0), (4.0, 1.0), (2.0, 5.0)]);
        let cw: Vec<Vec2> = ccw.iter().rev().copied().collect();
        assert_eq!(polygon_area(&ccw), -polygon_area(&cw));
        let (a, b) = (
            polygon_mass(&ccw, 1.0).unwrap(),
            polygon_mass(&cw, 1.0).unwrap(),
        );
        assert!((a.inertia - b.inertia).abs() < 1e-5);
        assert!((a.center - b.center).norm() < 1e-6);
        assert_eq!(
            polygon_inertia_about_origin(&ccw, 1.0),
            polygon_inertia_about_origin(&cw, 1.0)
        );
    }

    #[test]
    fn circle_inertia_is_half_m_r_squared() {
        let mass = circle_mass(2.0, 0.5);
        let expected_mass = 0.5 * crate::math::consts::PI * 4.0;
        assert!((mass.mass - expected_mass).abs() < 1e-5);
        assert!((mass.inertia - 0.5 * expected_mass * 4.0).abs() < 1e-4);
    }

    #[test]
    fn density_must_be_positive_and_finite() {
        assert!(check_density(1.0).is_ok());
        assert_eq!(
            check_density(0.0),
            Err(CaromError::InvalidDensity { density: 0.0 })
        );
        assert!(check_density(-3.0).is_err());
        assert!(matches!(
            check_density(Real::NAN),
            Err(CaromError::NonFinite { .. })
        ));
        assert!(check_density(Real::INFINITY).is_err());
    }

    /// Area, centroid and polar moment about the centroid of whatever `inside` holds within
    /// `extent` of the origin, by the midpoint rule on a fine grid.
    fn integrate(extent: f64, inside: impl Fn(Vec2) -> bool) -> (f64, [f64; 2], f64) {
        let cells = 1200;
        let h = 2.0 * extent / cells as f64;
        let (mut area, mut mx, mut my, mut second) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..cells {
            for j in 0..cells {
                let (x, y) = (
                    -extent + (i as f64 + 0.5) * h,
                    -extent + (j as f64 + 0.5) * h,
                );
                if inside(vec2(x as Real, y as Real)) {
                    area += h * h;
                    mx += h * h * x;
                    my += h * h * y;
                    second += h * h * (x * x + y * y);
                }
            }
        }
        let (cx, cy) = (mx / area, my / area);
        (area, [cx, cy], second - area * (cx * cx + cy * cy))
    }

    #[test]
    fn rounded_shapes_match_numeric_integration() {
        use crate::geometry::shape::Shape;
        let shapes = [
            Shape::capsule(vec2(-0.7, 0.2), vec2(0.5, -0.4), 0.3),
            Shape::rounded_rect(0.6, 0.3, 0.2),
            Shape::Polygon(
                crate::geometry::polygon::Polygon::new(&pts(&[
                    (-0.5, -0.4),
                    (0.7, -0.2),
                    (0.1, 0.6),
                ]))
                .unwrap()
                .rounded(0.15),
            ),
        ];
        for shape in &shapes {
            let mass = shape.mass_properties(2.0).unwrap();
            let (area, [cx, cy], inertia) = integrate(1.5, |p| shape.contains_local(p));
            let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 2e-3 * scale;
            assert!(
                close(mass.mass as f64, 2.0 * area, 2.0 * area),
                "{shape:?}: mass {} against {}",
                mass.mass,
                2.0 * area
            );
            assert!(
                close(mass.center.x as f64, cx, 1.0) && close(mass.center.y as f64, cy, 1.0),
                "{shape:?}: centre {:?} against ({cx}, {cy})",
                mass.center
            );
            assert!(
                close(mass.inertia as f64, 2.0 * inertia, 2.0 * inertia),
                "{shape:?}: inertia {} against {}",
                mass.inertia,
                2.0 * inertia
            );
        }
        // A capsule: Box2D's closed form, m = ρ (2 r L + π r²).
        let capsule = Shape::capsule(vec2(-1.0, 0.0), vec2(1.0, 0.0), 0.5)
            .mass_properties(1.0)
            .unwrap();
        let expected = 2.0 * 0.5 * 2.0 + crate::math::consts::PI * 0.25;
        assert!((capsule.mass - expected).abs() < 1e-5);
        assert!(capsule.center.norm() < 1e-6);
    }

    #[test]
    fn degenerate_outlines_have_no_mass() {
        let line = pts(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)]);
        assert!(polygon_mass(&line, 1.0).is_none());
        assert!(polygon_centroid(&line).is_none());
        assert_eq!(polygon_area(&line), 0.0);
    }
}
