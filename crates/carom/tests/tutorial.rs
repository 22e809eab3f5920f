//! The seed tutorial's worked numbers and experiments, reproduced against the public API.

use carom::testing::{polygon_area, polygon_centroid, polygon_inertia_about_origin, polygon_mass};
use carom::{BodyDef, Polygon, QueryFilter, Ray, Real, Shape, Vec2, World, vec2};

fn pts(coords: &[(Real, Real)]) -> Vec<Vec2> {
    coords.iter().map(|&(x, y)| vec2(x, y)).collect()
}

const HOUSE: [(Real, Real); 5] = [(3.0, 1.0), (3.0, 3.0), (2.0, 4.0), (1.0, 3.0), (1.0, 1.0)];
const TRIANGLE: [(Real, Real); 3] = [(4.0, 1.0), (2.0, 4.0), (1.0, 1.0)];
const PENTAGON: [(Real, Real); 5] = [
    (2.0, -1.0),
    (2.2, 1.0),
    (1.5, 2.0),
    (-1.2, 1.0),
    (-1.0, -1.0),
];
// In f64: the tutorial computed in double precision, and 2.2 or 0.8 are not exact in f32.
const HEXAGON: [(f64, f64); 6] = [
    (3.0, 1.0),
    (3.0, 2.0),
    (2.2, 3.0),
    (1.5, 3.0),
    (0.8, 2.0),
    (1.0, 1.0),
];

#[test]
fn house_and_triangle_areas() {
    assert_eq!(polygon_area(&pts(&HOUSE)), 5.0);
    assert_eq!(polygon_area(&pts(&TRIANGLE)), 4.5);
    // The same through a body: mass = density * area.
    let mut world = World::new();
    let house = world
        .add_body(BodyDef::dynamic(Shape::polygon(&pts(&HOUSE)).unwrap()).density(2.0))
        .unwrap();
    assert_eq!(world.body(house).unwrap().mass(), 10.0);
}

#[test]
fn pentagon_centroid() {
    let centroid = polygon_centroid(&pts(&PENTAGON)).unwrap();
    // To the last bit of single precision; in double, to 1e-12 of the exact value.
    #[cfg(not(feature = "f64"))]
    assert_eq!(centroid, vec2(0.569_958_85, 0.296_296_3));
    #[cfg(feature = "f64")]
    assert!((centroid - vec2(0.569_958_847_736_625_5, 8.0 / 27.0)).norm() < 1e-12);
    // Building the polygon removes exactly that offset.
    let polygon = Polygon::new(&pts(&PENTAGON)).unwrap();
    assert_eq!(polygon.source_centroid(), centroid);
}

/// The tutorial's polygon inertia: triangles fanned from the origin, each weighted by its
/// *unsigned* area. Correct while the origin is inside the polygon; wrong once it is not.
fn tutorial_inertia_about_origin(points: &[(f64, f64)], density: f64) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (ax, ay) = points[i];
            let (bx, by) = points[(i + 1) % n];
            let cross = (ax * by - ay * bx).abs();
            density * cross / 12.0 * (ax * ax + ay * ay + ax * bx + ay * by + bx * bx + by * by)
        })
        .sum()
}

#[test]
fn hexagon_inertia_and_the_parallel_axis_theorem() {
    let shifted: Vec<(f64, f64)> = HEXAGON.iter().map(|&(x, y)| (x + 2.5, y + 2.5)).collect();
    // The tutorial's figure is reproduced by its own formula...
    let tutorial = tutorial_inertia_about_origin(&shifted, 1.0);
    assert!(
        (tutorial - 315.363_916_666_666_6).abs() < 1e-9,
        "{tutorial}"
    );

    // ...but the origin lies outside the shifted hexagon, so unsigned triangle areas count
    // the region between the origin and the near edges twice. Signed areas give the inertia.
    let shifted_points: Vec<Vec2> = shifted
        .iter()
        .map(|&(x, y)| vec2(x as Real, y as Real))
        .collect();
    let about_origin = polygon_inertia_about_origin(&shifted_points, 1.0);
    let exact = 139.505_75;
    assert!((about_origin - exact).abs() < 1e-4, "{about_origin}");

    // The parallel-axis theorem, from the centroid, decides between the two.
    let mass = polygon_mass(&shifted_points, 1.0).unwrap();
    let through_centroid = mass.inertia_about(Vec2::zeros());
    assert!((through_centroid - about_origin).abs() < 1e-4 * exact);
    assert!((through_centroid as f64 - tutorial).abs() > 100.0);

    // With the origin inside (the hexagon recentred on its centroid) the tutorial's formula
    // agrees with ours: both give the centroidal inertia.
    let (cx, cy) = (mass.center.x as f64 - 2.5, mass.center.y as f64 - 2.5);
    let centred: Vec<(f64, f64)> = HEXAGON.iter().map(|&(x, y)| (x - cx, y - cy)).collect();
    let tutorial_centred = tutorial_inertia_about_origin(&centred, 1.0);
    assert!(
        (tutorial_centred - mass.inertia as f64).abs() < 1e-4,
        "{tutorial_centred}"
    );

    // The recentred body's inertia is the centroidal one, at any density.
    let body_shape = Shape::polygon(&shifted_points).unwrap();
    let props = body_shape.mass_properties(3.0).unwrap();
    assert!((props.inertia - 3.0 * mass.inertia).abs() < 1e-4);
    assert!((props.mass - 3.0 * 3.55).abs() < 1e-5);
}

/// Exact classification of a grid point against the pentagon, in integer tenths:
/// inside or on the boundary iff the point is on the left of (or on) every CCW edge.
fn exactly_inside_pentagon(x_tenths: i64, y_tenths: i64) -> (bool, bool) {
    let v: Vec<(i64, i64)> = PENTAGON
        .iter()
        .map(|&(x, y)| ((x * 10.0).round() as i64, (y * 10.0).round() as i64))
        .collect();
    let mut inside = true;
    let mut on_boundary = false;
    for i in 0..v.len() {
        let (ax, ay) = v[i];
        let (bx, by) = v[(i + 1) % v.len()];
        let cross = (bx - ax) * (y_tenths - ay) - (by - ay) * (x_tenths - ax);
        inside &= cross >= 0;
        on_boundary |= cross == 0;
    }
    (inside, inside && on_boundary)
}

/// A world holding the tutorial's pentagon as a static body, placed where its points say.
fn pentagon_world() -> (World, carom::BodyHandle, Polygon) {
    let polygon = Polygon::new(&pts(&PENTAGON)).unwrap();
    let mut world = World::new();
    let pentagon = world
        .add_body(
            BodyDef::static_body(Shape::Polygon(polygon.clone()))
                .position(polygon.source_centroid()),
        )
        .unwrap();
    (world, pentagon, polygon)
}

#[test]
fn grid_experiment_matches_exact_half_planes() {
    let (world, pentagon, polygon) = pentagon_world();
    let (mut inside_count, mut boundary_count) = (0, 0);
    // (-2, 2.5) to (2.5, -2) in steps of 0.1, both ends included.
    for row in 0..=45 {
        for column in 0..=45 {
            let (x_tenths, y_tenths) = (-20 + column, 25 - row);
            let point = vec2(x_tenths as Real / 10.0, y_tenths as Real / 10.0);
            let (expected, on_boundary) = exactly_inside_pentagon(x_tenths, y_tenths);
            let local = point - polygon.source_centroid();
            assert_eq!(
                polygon.contains_local(local),
                expected,
                "polygon test at ({}, {})",
                point.x,
                point.y
            );
            let found = world.body_at(point) == Some(pentagon);
            assert_eq!(found, expected, "world query at ({}, {})", point.x, point.y);
            inside_count += expected as usize;
            boundary_count += on_boundary as usize;
        }
    }
    // The grid really does probe the edges and corners, where naive tests go wrong.
    assert!(boundary_count >= 10, "{boundary_count} boundary points");
    assert!(inside_count > 700 && inside_count < 1000, "{inside_count}");
}

#[test]
#[cfg_attr(
    feature = "f64",
    ignore = "a ray exactly along an edge grazes it: in double precision it rounds to a miss"
)]
fn rays_through_vertices_and_along_edges() {
    let (world, pentagon, polygon) = pentagon_world();
    let corners = pts(&PENTAGON);
    let n = corners.len();
    let normals: Vec<Vec2> = polygon.normals().to_vec();
    for k in 0..n {
        let corner = corners[k];
        let prev_normal = normals[(k + n - 1) % n];
        let next_normal = normals[k];

        // Straight at the corner from outside, along the bisector of its two normals.
        let outward = (prev_normal + next_normal).normalize();
        let hit = world
            .cast_ray(
                &Ray::between(corner + outward * 3.0, corner - outward * 3.0),
                QueryFilter::ALL,
            )
            .unwrap_or_else(|| panic!("ray at corner {k} missed"));
        assert_eq!(hit.body, pentagon);
        assert!(
            (hit.point - corner).norm() < 1e-5,
            "corner {k}: {:?}",
            hit.point
        );
        assert!((hit.fraction - 0.5).abs() < 1e-5);
        assert!(
            (hit.normal - prev_normal).norm() < 1e-5 || (hit.normal - next_normal).norm() < 1e-5
        );

        // Along edge k's line, forwards: enters at the edge's start through edge k - 1.
        let next_corner = corners[(k + 1) % n];
        let edge = next_corner - corner;
        let hit = world
            .cast_ray(&Ray::new(corner - edge, edge * 3.0), QueryFilter::ALL)
            .unwrap_or_else(|| panic!("ray along edge {k} missed"));
        assert!(
            (hit.point - corner).norm() < 1e-5,
            "edge {k}: {:?}",
            hit.point
        );
        assert!((hit.fraction - 1.0 / 3.0).abs() < 1e-5);
        assert!((hit.normal - prev_normal).norm() < 1e-5);

        // Backwards along the same line: enters at the edge's end through edge k + 1.
        let hit = world
            .cast_ray(&Ray::new(next_corner + edge, -edge * 3.0), QueryFilter::ALL)
            .unwrap_or_else(|| panic!("reverse ray along edge {k} missed"));
        assert!((hit.point - next_corner).norm() < 1e-5);
        assert!((hit.normal - normals[(k + 1) % n]).norm() < 1e-5);

        // Grazing the corner from the side: touches only that point.
        let tangent = vec2(-outward.y, outward.x);
        let hit = world
            .cast_ray(
                &Ray::between(corner - tangent * 2.0, corner + tangent * 2.0),
                QueryFilter::ALL,
            )
            .unwrap_or_else(|| panic!("grazing ray at corner {k} missed"));
        assert!(
            (hit.point - corner).norm() < 1e-4,
            "graze {k}: {:?}",
            hit.point
        );

        // Just outside the corner, the same ray misses.
        let off = outward * 1e-3;
        assert!(
            world
                .cast_ray(
                    &Ray::between(corner + off - tangent * 2.0, corner + off + tangent * 2.0),
                    QueryFilter::ALL
                )
                .is_none(),
            "ray beside corner {k} hit"
        );
    }
}
