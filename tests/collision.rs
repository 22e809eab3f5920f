//! Collision detection against the tutorial's worked example, brute-force references, and
//! degenerate input.

use carom::query::collide;
use carom::query::separation;
use carom::testing::PairSide;
use carom::{BodyDef, Polygon, Real, Shape, Vec2, World, WorldSettings, WorldShape, vec2};
use carom_bench::cases::Rng;
use proptest::prelude::*;

/// A polygon in world coordinates exactly where its points say (not recentred).
fn polygon_at_its_points(points: &[(Real, Real)]) -> WorldShape {
    let points: Vec<Vec2> = points.iter().map(|&(x, y)| vec2(x, y)).collect();
    let polygon = Polygon::new(&points).unwrap();
    let at = polygon.source_centroid();
    WorldShape::at(&Shape::Polygon(polygon), at, 0.0)
}

fn close(a: Vec2, b: Vec2, tolerance: Real) -> bool {
    (a - b).norm() <= tolerance
}

/// The tutorial's worked example, derived by hand.
///
/// A is the rectangle (-1,0) (3,0) (3,-2) (-1,-2), B the quadrilateral (3.5,-1.666) (4.5,0)
/// (1.5,2) (1.5,-0.333); both are given clockwise and carom turns them counter-clockwise.
///
/// SAT over A's normals (B's deepest vertex behind each face):
///   bottom (0,-1): -4.0; right (1,0): 3 - 4.5 = -1.5; top (0,1): -1.666 - 0 = -1.666;
///   left (-1,0): -5.5. Best: the right face, -1.5.
/// Over B's normals, the edge e = (1.5,-0.333) -> (3.5,-1.666) = (2, -1.333) has
///   |e| = sqrt(4 + 1.776889) = 2.4035164 and outward normal (-1.333, -2) / |e|
///   = (-0.5546110, -0.8321160). A's deepest vertex behind it is (3, 0):
///   ((3 - 1.5)(-1.333) + (0 + 0.333)(-2)) / |e| = -2.6655 / 2.4035164 = -1.1090003.
///   The other faces of B give -4.7157, -4.7150 and -1.5, so this one is the best: -1.109.
/// B's face beats A's (-1.109 > -1.5): it is the reference edge, and the MTV is
///   1.1090003 along (0.5546110, 0.8321160) (from A to B), i.e. (0.6150641, 0.9228171).
/// Incident edge: A's face most anti-parallel to the reference normal is the top edge
///   (0,1)·n = -0.832, running (3,0) -> (-1,0).
/// Clipping it to the strip over the reference edge, with t = e / |e| = (0.832116, -0.554611):
///   (3, 0) lies at t·((3,0) - (1.5,-0.333)) = 1.0634 in [0, 2.4035]: kept, depth 1.1090003.
///   (-1, 0) lies at -2.2648 < 0: clipped at the side plane through (1.5, -0.333), where
///   2 (x - 1.5) - 1.333 (0 + 0.333) = 0, so x = 1.5 + 0.443889 / 2 = 1.7219445;
///   its separation is ((0.2219445)(-1.333) + (0.333)(-2)) / |e| = -0.96185 / 2.4035164
///   = -0.4001854.
/// Each manifold point sits halfway between these incident points and the reference face.
#[test]
fn tutorial_worked_example() {
    let a = polygon_at_its_points(&[(-1.0, 0.0), (3.0, 0.0), (3.0, -2.0), (-1.0, -2.0)]);
    let b = polygon_at_its_points(&[(3.5, -1.666), (4.5, 0.0), (1.5, 2.0), (1.5, -0.333)]);
    let length = (4.0_f64 + 1.333 * 1.333).sqrt();
    let normal = vec2((1.333 / length) as Real, (2.0 / length) as Real);
    let depth = (2.6655 / length) as Real;

    let s = separation(&a, &b);
    assert!(close(s.normal, normal, 1e-6), "{:?}", s.normal);
    assert!((s.separation + depth).abs() < 1e-5, "{}", s.separation);
    assert!(close(s.mtv(), vec2(0.615_064_1, 0.922_817_1), 1e-5));

    let m = collide(&a, &b, 0.0);
    assert!(close(m.normal, normal, 1e-6));
    let reference = m.reference_edge.unwrap();
    assert_eq!(reference.side, PairSide::B);
    let (start, end) = reference.ends(&b).unwrap();
    assert!(close(start, vec2(1.5, -0.333), 1e-5));
    assert!(close(end, vec2(3.5, -1.666), 1e-5));
    let incident = m.incident_edge.unwrap();
    assert_eq!(incident.side, PairSide::A);
    let (start, end) = incident.ends(&a).unwrap();
    assert!(close(start, vec2(3.0, 0.0), 1e-5));
    assert!(close(end, vec2(-1.0, 0.0), 1e-5));

    let expected = [
        (vec2(1.721_944_5, 0.0), -0.400_185_4),
        (vec2(3.0, 0.0), -depth),
    ];
    assert_eq!(m.points().len(), 2);
    for (point, (incident_point, separation)) in m.points().iter().zip(expected) {
        assert!(
            (point.separation - separation).abs() < 1e-5,
            "{}",
            point.separation
        );
        // Halfway to the reference face: back along the A-to-B normal by half the depth.
        let midway = incident_point + normal * (0.5 * separation);
        assert!(
            close(point.point, midway, 1e-5),
            "{:?} vs {midway:?}",
            point.point
        );
    }
}

// ---------------------------------------------------------------- brute-force references

/// Projection interval of a placed shape on a direction.
fn interval(shape: &WorldShape, d: [f64; 2]) -> (f64, f64) {
    match shape {
        WorldShape::Circle { center, radius } => {
            let c = center.x as f64 * d[0] + center.y as f64 * d[1];
            (c - *radius as f64, c + *radius as f64)
        }
        WorldShape::Polygon {
            vertices, radius, ..
        } => {
            let (lo, hi) =
                vertices
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                        let p = v.x as f64 * d[0] + v.y as f64 * d[1];
                        (lo.min(p), hi.max(p))
                    });
            (lo - *radius as f64, hi + *radius as f64)
        }
        WorldShape::ChainSegment { point1, point2, .. } => {
            let (p, q) = (
                point1.x as f64 * d[0] + point1.y as f64 * d[1],
                point2.x as f64 * d[0] + point2.y as f64 * d[1],
            );
            (p.min(q), p.max(q))
        }
    }
}

/// Directions worth testing: many evenly spaced ones, every edge normal, and the directions
/// between every pair of "corners" (vertices and circle centres).
fn axes(a: &WorldShape, b: &WorldShape) -> Vec<[f64; 2]> {
    let mut axes: Vec<[f64; 2]> = (0..7200)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / 7200.0;
            [t.cos(), t.sin()]
        })
        .collect();
    let corners = |s: &WorldShape| -> Vec<[f64; 2]> {
        match s {
            WorldShape::Circle { center, .. } => vec![[center.x as f64, center.y as f64]],
            WorldShape::Polygon { vertices, .. } => {
                vertices.iter().map(|v| [v.x as f64, v.y as f64]).collect()
            }
            WorldShape::ChainSegment { point1, point2, .. } => [point1, point2]
                .iter()
                .map(|v| [v.x as f64, v.y as f64])
                .collect(),
        }
    };
    for s in [a, b] {
        if let WorldShape::Polygon { vertices, .. } = s {
            for i in 0..vertices.len() {
                let (p, q) = (vertices[i], vertices[(i + 1) % vertices.len()]);
                let (ex, ey) = (q.x as f64 - p.x as f64, q.y as f64 - p.y as f64);
                let l = (ex * ex + ey * ey).sqrt();
                axes.push([ey / l, -ex / l]);
                axes.push([-ey / l, ex / l]);
            }
        }
    }
    for p in corners(a) {
        for q in corners(b) {
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let l = (dx * dx + dy * dy).sqrt();
            if l > 1e-12 {
                axes.push([dx / l, dy / l]);
            }
        }
    }
    axes
}

/// Signed distance by the support-function definition: the largest gap between the shapes'
/// projections over all directions (the distance when apart, minus the depth when not).
fn brute_separation(a: &WorldShape, b: &WorldShape) -> f64 {
    axes(a, b)
        .into_iter()
        .map(|d| {
            let (_, a_hi) = interval(a, d);
            let (b_lo, _) = interval(b, d);
            b_lo - a_hi
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The distance from `p` to the segment `a`–`b`.
fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> Real {
    let e = b - a;
    let t = ((p - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
    (a + e * t - p).norm()
}

/// How far a point is outside a shape (negative inside), exactly for points inside.
fn depth_outside(shape: &WorldShape, p: Vec2) -> Real {
    match shape {
        WorldShape::Circle { center, radius } => (p - center).norm() - radius,
        WorldShape::Polygon {
            vertices,
            normals,
            radius,
        } => {
            let n = vertices.len();
            let inside_core = vertices
                .iter()
                .zip(normals)
                .map(|(v, n)| n.dot(&(p - v)))
                .fold(Real::NEG_INFINITY, Real::max);
            if n >= 3 && inside_core <= 0.0 {
                inside_core - radius
            } else {
                (0..n)
                    .map(|i| segment_distance(p, vertices[i], vertices[(i + 1) % n]))
                    .fold(Real::INFINITY, Real::min)
                    - radius
            }
        }
        WorldShape::ChainSegment { point1, point2, .. } => segment_distance(p, *point1, *point2),
    }
}

fn translated(shape: &WorldShape, by: Vec2) -> WorldShape {
    let mut moved = shape.clone();
    moved.translate(by);
    moved
}

// ---------------------------------------------------------------- property tests

/// Every shape with an inside: circles, polygons sharp and rounded, capsules.
fn shape_strategy() -> impl Strategy<Value = Shape> {
    let hull = prop::collection::vec((-1.5f32..1.5, -1.5f32..1.5), 3..10).prop_filter_map(
        "degenerate hull",
        |points| {
            let points: Vec<Vec2> = points.into_iter().map(|(x, y)| vec2(x, y)).collect();
            // Skip slivers: properties are about geometry, not float noise.
            Shape::hull(&points).ok().filter(|s| s.min_extent() > 0.05)
        },
    );
    prop_oneof![
        (0.05f32..1.5).prop_map(Shape::circle),
        hull.clone(),
        (hull, 0.02f32..0.5).prop_map(|(shape, radius)| match shape {
            Shape::Polygon(p) => Shape::Polygon(p.rounded(radius)),
            other => other,
        }),
        ((-1.0f32..1.0, -1.0f32..1.0), 0.1f32..1.5, 0.05f32..0.6).prop_map(
            |((x, y), length, radius)| {
                let half =
                    vec2(x, y).try_normalize(1e-3).unwrap_or(vec2(1.0, 0.0)) * (0.5 * length);
                Shape::capsule(-half, half, radius)
            }
        ),
    ]
}

fn placed_strategy() -> impl Strategy<Value = WorldShape> {
    (shape_strategy(), -1.5f32..1.5, -1.5f32..1.5, -3.2f32..3.2)
        .prop_map(|(shape, x, y, angle)| WorldShape::at(&shape, vec2(x, y), angle))
}

/// 400 cases from a fixed seed, so CI is deterministic; proptest's own `PROPTEST_CASES` and
/// `PROPTEST_RNG_SEED` variables widen or vary the search locally.
fn config() -> ProptestConfig {
    let from_env = ProptestConfig::default();
    ProptestConfig {
        cases: if std::env::var_os("PROPTEST_CASES").is_some() {
            from_env.cases
        } else {
            400
        },
        rng_seed: if std::env::var_os("PROPTEST_RNG_SEED").is_some() {
            from_env.rng_seed
        } else {
            proptest::test_runner::RngSeed::Fixed(0xca20)
        },
        max_global_rejects: 1 << 20,
        ..from_env
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn collide_is_symmetric(a in placed_strategy(), b in placed_strategy()) {
        let ab = separation(&a, &b);
        let ba = separation(&b, &a);
        prop_assert!((ab.separation - ba.separation).abs() < 1e-5);
        prop_assert!((ab.normal + ba.normal).norm() < 1e-5, "{:?} vs {:?}", ab, ba);

        let (mab, mba) = (collide(&a, &b, 0.02), collide(&b, &a, 0.02));
        prop_assert_eq!(mab.points().len(), mba.points().len());
        if !mab.is_empty() {
            prop_assert!((mab.normal + mba.normal).norm() < 1e-5);
            for p in mab.points() {
                prop_assert!(mba.points().iter().any(|q| (p.point - q.point).norm() < 1e-5
                    && (p.separation - q.separation).abs() < 1e-6));
            }
        }
    }

    #[test]
    fn separation_matches_brute_force(a in placed_strategy(), b in placed_strategy()) {
        let s = separation(&a, &b);
        let brute = brute_separation(&a, &b);
        prop_assert!((s.separation as f64 - brute).abs() < 2e-5, "{} vs {}", s.separation, brute);
        prop_assert!((s.normal.norm() - 1.0).abs() < 1e-5);
    }

    #[test]
    fn mtv_just_separates(a in placed_strategy(), b in shape_strategy(), offset in (-0.5f32..0.5, -0.5f32..0.5), angle in -3.2f32..3.2) {
        // B is placed near A's centre, so the pair overlaps nearly always.
        let center = match &a {
            WorldShape::Circle { center, .. } => *center,
            WorldShape::Polygon { vertices, .. } => vertices.iter().sum::<Vec2>() / vertices.len() as Real,
            WorldShape::ChainSegment { .. } => unreachable!("not generated"),
        };
        let b = WorldShape::at(&b, center + vec2(offset.0, offset.1), angle);
        let s = separation(&a, &b);
        prop_assume!(s.separation < -1e-3);
        let moved = translated(&b, s.mtv());
        let after = brute_separation(&a, &moved);
        prop_assert!(after.abs() < 1e-6, "left touching within 1e-6, got {}", after);
        // No shorter translation, in any direction, separates them.
        let shorter = -s.separation * 0.999;
        for i in 0..72 {
            let t = std::f32::consts::TAU * i as Real / 72.0;
            let try_b = translated(&b, vec2(t.cos(), t.sin()) * shorter);
            prop_assert!(brute_separation(&a, &try_b) < 0.0, "direction {} separated", t);
        }
    }

    #[test]
    fn manifold_points_lie_in_both_shapes(a in placed_strategy(), b in placed_strategy()) {
        let m = collide(&a, &b, 0.0);
        let brute = brute_separation(&a, &b);
        if brute < -1e-4 {
            prop_assert!(!m.is_empty(), "overlapping shapes need contact points");
        }
        for p in m.points() {
            // No point is deeper than the penetration depth.
            prop_assert!(p.separation as f64 >= brute - 2e-5, "{} deeper than {}", p.separation, brute);
            // Inside both, within the tolerance the clipper itself allows for rounding. Where
            // a capsule's core crosses the other shape, the clipped points lie on the other
            // shape's edge, which may be farther from the core than the capsule's radius (as
            // in Box2D's clipping): there, inside the other shape is what holds.
            let tolerance = carom::testing::SPURIOUS_TOLERANCE + 1e-5;
            let core_crossed = |s: &WorldShape| matches!(s,
                WorldShape::Polygon { vertices, radius, .. }
                    if vertices.len() == 2 && brute < -(*radius as f64));
            if core_crossed(&a) || core_crossed(&b) {
                let inside = [&a, &b].iter().filter(|s| depth_outside(s, p.point) <= tolerance).count();
                prop_assert!(inside >= 1, "{:?} outside both: {:?}", p, m);
                continue;
            }
            prop_assert!(depth_outside(&a, p.point) <= tolerance, "{:?} outside A by {}: {:?}", p, depth_outside(&a, p.point), m);
            prop_assert!(depth_outside(&b, p.point) <= tolerance, "{:?} outside B by {}: {:?}", p, depth_outside(&b, p.point), m);
        }
        if matches!(a, WorldShape::Circle { .. }) || matches!(b, WorldShape::Circle { .. }) {
            prop_assert!(m.points().len() <= 1);
        }
    }
}

#[test]
fn overlapping_triangle_faces_keep_two_points() {
    // Two equilateral triangles face to face, overlapping by 0.1 m and offset along the face.
    // Their corners are sharper than a right angle, so the side planes of the reference face
    // leave the incident edge's ends outside the reference triangle; the clipper must pull them
    // inside, not drop them: with one point the pair rotates into itself.
    let h = (3.0 as Real).sqrt() / 2.0;
    let a = polygon_at_its_points(&[(0.0, 0.0), (1.0, 0.0), (0.5, h)]);
    // Outward normal of A's face from (1, 0) to (0.5, h), and the face's direction.
    let normal = vec2(h, 0.5);
    let along = vec2(-0.5, h);
    let shift = -normal * 0.1 + along * 0.2;
    let b = polygon_at_its_points(&[
        (1.0 + shift.x, shift.y),
        (1.5 + shift.x, h + shift.y),
        (0.5 + shift.x, h + shift.y),
    ]);
    for (first, second) in [(&a, &b), (&b, &a)] {
        let manifold = collide(first, second, 0.02);
        assert_eq!(manifold.points().len(), 2, "{manifold:?}");
        for point in manifold.points() {
            assert!((point.separation + 0.1).abs() < 0.02, "{point:?}");
            assert!(
                depth_outside(&a, point.point) <= 1e-4,
                "{point:?} outside A"
            );
            assert!(
                depth_outside(&b, point.point) <= 1e-4,
                "{point:?} outside B"
            );
        }
        // Spread along the face, so the pair cannot pivot about a single point.
        let [p, q] = [manifold.points()[0].point, manifold.points()[1].point];
        assert!(
            (p - q).norm() > 0.5,
            "points {p:?} and {q:?} bunch together"
        );
    }
}

// ---------------------------------------------------------------- degenerate but valid input

fn assert_finite(a: &WorldShape, b: &WorldShape) -> carom::query::Separation {
    let s = separation(a, b);
    assert!(
        s.separation.is_finite() && s.normal.iter().all(|x| x.is_finite()),
        "{s:?}"
    );
    assert!((s.normal.norm() - 1.0).abs() < 1e-4);
    let m = collide(a, b, 0.02);
    assert!(m.normal.iter().all(|x| x.is_finite()));
    for p in m.points() {
        assert!(p.point.iter().all(|x| x.is_finite()) && p.separation.is_finite());
    }
    s
}

#[test]
fn tiny_and_huge_shapes() {
    let mm = Shape::rect(0.0005, 0.0005);
    let s = assert_finite(
        &WorldShape::at(&mm, vec2(0.0, 0.0), 0.0),
        &WorldShape::at(&mm, vec2(0.0008, 0.0), 0.0),
    );
    assert!((s.separation + 0.0002).abs() < 1e-7);
    let km = Shape::rect(5000.0, 5000.0);
    let s = assert_finite(
        &WorldShape::at(&km, vec2(0.0, 0.0), 0.0),
        &WorldShape::at(&km, vec2(0.0, 9999.0), 0.0),
    );
    assert!((s.separation + 1.0).abs() < 1e-2);
    let ball = Shape::circle(5000.0);
    assert_finite(
        &WorldShape::at(&km, vec2(0.0, 0.0), 0.0),
        &WorldShape::at(&ball, vec2(3.0, 9990.0), 0.0),
    );
    // A millimetre box on a kilometre floor.
    let s = assert_finite(
        &WorldShape::at(&km, vec2(0.0, -5000.0), 0.0),
        &WorldShape::at(&mm, vec2(1.0, 0.0004), 0.3),
    );
    assert!(s.separation < 0.0);
}

#[test]
fn slivers_one_to_a_thousand() {
    let sliver = Shape::rect(1.0, 0.001);
    let quarter = std::f32::consts::FRAC_PI_2;
    for angle in [0.0, 0.001, 0.7, quarter - 1e-4, quarter] {
        let s = assert_finite(
            &WorldShape::at(&sliver, vec2(0.0, 0.0), 0.0),
            &WorldShape::at(&sliver, vec2(0.3, 0.0005), angle),
        );
        assert!(s.separation <= 0.0);
        let m = collide(
            &WorldShape::at(&sliver, vec2(0.0, 0.0), 0.0),
            &WorldShape::at(&sliver, vec2(0.3, 0.0005), angle),
            0.0,
        );
        assert!(!m.is_empty());
    }
}

#[test]
fn identical_polygons_on_top_of_each_other() {
    for shape in [Shape::rect(0.5, 0.5), Shape::regular(7, 1.0).unwrap()] {
        let a = WorldShape::at(&shape, vec2(1.0, 2.0), 0.3);
        let s = assert_finite(&a, &a.clone());
        // The cheapest way out is the polygon's own narrowest width.
        let widths = match &a {
            WorldShape::Polygon {
                vertices, normals, ..
            } => normals
                .iter()
                .zip(vertices)
                .map(|(n, v)| {
                    vertices
                        .iter()
                        .map(|w| n.dot(&(v - w)))
                        .fold(0.0, Real::max)
                })
                .fold(Real::INFINITY, Real::min),
            _ => unreachable!(),
        };
        assert!(
            (s.separation + widths).abs() < 1e-4,
            "{} vs {widths}",
            s.separation
        );
        assert_eq!(collide(&a, &a.clone(), 0.0).points().len(), 2);
    }
}

#[test]
fn coincident_circle_centres() {
    let a = WorldShape::at(&Shape::circle(0.5), vec2(3.0, -1.0), 0.0);
    let b = WorldShape::at(&Shape::circle(0.25), vec2(3.0, -1.0), 2.0);
    let s = assert_finite(&a, &b);
    assert_eq!(s.separation, -0.75);
    assert_eq!(s.normal, carom::testing::COINCIDENT_NORMAL);
    let moved = translated(&b, s.mtv());
    assert!(separation(&a, &moved).separation.abs() < 1e-6);
}

#[test]
fn circle_centred_on_a_polygon_vertex_or_edge() {
    let square = WorldShape::at(&Shape::rect(1.0, 1.0), vec2(0.0, 0.0), 0.0);
    let ball = Shape::circle(0.3);
    // On a vertex: the way out is through either adjacent face, 0.3 deep.
    let s = assert_finite(&square, &WorldShape::at(&ball, vec2(1.0, 1.0), 0.0));
    assert!((s.separation + 0.3).abs() < 1e-6);
    assert!(s.normal == vec2(1.0, 0.0) || s.normal == vec2(0.0, 1.0));
    // On an edge.
    let s = assert_finite(&square, &WorldShape::at(&ball, vec2(0.2, 1.0), 0.0));
    assert_eq!(s.normal, vec2(0.0, 1.0));
    assert!((s.separation + 0.3).abs() < 1e-6);
    // At the centre.
    let s = assert_finite(&square, &WorldShape::at(&ball, vec2(0.0, 0.0), 0.0));
    assert!((s.separation + 1.3).abs() < 1e-6);
}

// ---------------------------------------------------------------- the pipeline in a world

#[test]
fn world_contacts_track_brute_force_pairs_as_thousands_of_bodies_move() {
    let mut world = World::with_settings(WorldSettings {
        gravity: Vec2::zeros(),
        ..WorldSettings::default()
    })
    .unwrap();
    let mut rng = Rng::new(11);
    for i in 0..2500 {
        let shape = if i % 3 == 0 {
            Shape::circle(rng.range(0.1, 0.6))
        } else {
            Shape::regular(3 + rng.below(5), rng.range(0.1, 0.7)).unwrap()
        };
        let position = vec2(rng.range(-60.0, 60.0), rng.range(-60.0, 60.0));
        let def = match i % 10 {
            0 => BodyDef::static_body(shape),
            1 => BodyDef::kinematic(shape).linear_velocity(vec2(rng.range(-3.0, 3.0), 0.0)),
            _ => BodyDef::dynamic(shape)
                .linear_velocity(vec2(rng.range(-20.0, 20.0), rng.range(-20.0, 20.0)))
                .angular_velocity(rng.range(-5.0, 5.0)),
        };
        world.add_body(def.position(position)).unwrap();
    }
    // Contacts are made at the start of a step from the fat boxes the last step left, so
    // after step k + 1 the world must hold exactly the brute-force pairs of step k's boxes
    // that the look-ahead test keeps.
    let mut expected_from_last_step: Option<Vec<_>> = None;
    let mut passed_over = 0;
    for step in 0..30 {
        world.step(1.0 / 60.0).unwrap();
        let mut held: Vec<_> = world
            .contacts()
            .map(|c| (c.collider_a(), c.collider_b()))
            .collect();
        held.sort_unstable_by_key(|(a, b)| (a.index(), b.index()));
        if let Some(expected) = expected_from_last_step.take() {
            assert_eq!(held, expected, "step {step}");
        }
        // One collider per body, so the reference needs no rule for colliders of one body.
        let entries: Vec<_> = world
            .bodies()
            .map(|b| {
                let collider = b.colliders()[0];
                let fat = world.broadphase().fat_aabb(collider).unwrap();
                assert!(fat.contains(&b.aabb()), "a fat box must cover its body");
                (collider, b.kind(), fat)
            })
            .collect();
        let overlapping = carom::testing::brute_force_pairs(&entries);
        assert_eq!(
            world.broadphase().overlapping_pairs(),
            overlapping,
            "step {step}"
        );
        assert!(overlapping.len() > 200, "the test world must have pairs");
        // Of those, a pair with a body faster than its fat box's margin is made only if the
        // two can meet in the next step at their relative velocity.
        let expected: Vec<_> = overlapping
            .iter()
            .copied()
            .filter(|&(a, b)| world.broadphase().may_keep(a, b))
            .collect();
        passed_over += overlapping.len() - expected.len();
        expected_from_last_step = Some(expected);
    }
    assert!(
        passed_over > 100,
        "the look-ahead test must leave pairs out: {passed_over}"
    );
}

#[test]
fn a_hairline_capsule_beside_a_large_circle_gets_finite_points() {
    // Found by the any_pair fuzz target: a capsule of subnormal radius, its core a two-vertex
    // polygon turned 48.5 rad, whose nearest point to a 48.6 m circle is its end: the line
    // from there along the normal runs beside its core's side, a rounding error outside it.
    let bits = f32::from_bits;
    let capsule = Shape::capsule(
        vec2(bits(0x42ffffff), bits(0x0042003f)),
        vec2(bits(0x42420000), bits(0x31fffe42)),
        bits(0x00ff3aff),
    );
    let a = WorldShape::at(
        &capsule,
        vec2(bits(0xff), bits(0x0042003f)),
        bits(0x42420000),
    );
    let b = WorldShape::at(&Shape::circle(bits(0x42424242)), vec2(0.0, 0.0), 0.0);
    for margin in [0.0, 0.02] {
        for m in [collide(&a, &b, margin), collide(&b, &a, margin)] {
            assert!(!m.points().is_empty(), "they overlap: {m:?}");
            assert!(m.normal.x.is_finite() && m.normal.y.is_finite(), "{m:?}");
            for p in m.points() {
                let finite = [p.point, p.anchor_a, p.anchor_b]
                    .iter()
                    .all(|v| v.x.is_finite() && v.y.is_finite());
                assert!(finite && p.separation.is_finite(), "{m:?}");
            }
        }
    }
}

#[test]
fn polygon_circle_survives_a_zero_length_edge_and_a_centre_on_a_vertex() {
    // Found by the polygon_circle fuzz target: a hairline polygon 1 km from the origin rounds
    // to world vertices that coincide, and a circle centred on one of them had a NaN normal.
    let vertices = [
        vec2(0.0, 0.0),
        vec2(1.0, 0.0),
        vec2(1.0, 0.0),
        vec2(0.0, 1.0),
    ];
    let normals = [
        vec2(0.0, -1.0),
        vec2(1.0, 0.0),
        vec2(
            std::f32::consts::FRAC_1_SQRT_2,
            std::f32::consts::FRAC_1_SQRT_2,
        ),
        vec2(-1.0, 0.0),
    ];
    // The last centre is outside by 1e-23 m: its squared distance to the vertex underflows
    // to zero.
    for center in [vec2(1.0, 0.0), vec2(2.0, -1.0), vec2(-1e-23, -1e-23)] {
        let pc = carom::testing::polygon_circle(&vertices, &normals, center, 1e-17);
        let s = pc.separation;
        assert!(s.separation.is_finite(), "{center:?}: {s:?}");
        assert!((s.normal.norm() - 1.0).abs() < 1e-5, "{center:?}: {s:?}");
    }
}

#[test]
fn a_circle_a_hair_from_a_segment_end_gets_a_unit_normal() {
    // Found by the any_pair fuzz target: a circle of radius 3e-23 m whose centre is 5e-23 m
    // from the end of a 1.5 km segment. The squared distance is subnormal, and the normal
    // made from it was 0.85 long.
    let segment = Shape::segment(
        vec2(-1571.649, 3.186_753_8e-23),
        vec2(3.186_753_8e-23, 3.186_753_8e-23),
    );
    let circle = Shape::circle(3.186_753_8e-23);
    let at = vec2(3.186_753_8e-23, 3.186_753_8e-23);
    let (a, b) = (
        WorldShape::at(&segment, at, 3.186_753_8e-23),
        WorldShape::at(&circle, at, 3.186_753_8e-23),
    );
    for s in [
        carom::query::separation(&a, &b),
        carom::query::separation(&b, &a),
    ] {
        assert!(s.separation.is_finite(), "{s:?}");
        assert!((s.normal.norm() - 1.0).abs() < 1e-5, "{s:?}");
    }
}

#[test]
fn a_segment_ending_on_a_chain_links_end_gets_a_finite_manifold() {
    // Found by the any_pair fuzz target: a 3 km segment whose end is 1e-38 m from the end of
    // a 94 km chain link. The normal made from that distance was infinite.
    let link = Shape::ChainSegment(carom::ChainSegment::new(
        vec2(7.70042e-15, 0.3852941),
        vec2(-94062.45, 5.310414e-12),
        vec2(6.6749636e-38, -0.00076571107),
        vec2(3252.358, 3156.3557),
    ));
    let segment = Shape::segment(vec2(3248.0598, 6.36165e-39), vec2(6.5184e-41, 0.0));
    let a = WorldShape::at(&link, vec2(1.1443805e-28, 7.69414e-15), 0.3852941);
    let b = WorldShape::at(&segment, vec2(0.0, 0.0), 0.0);
    for margin in [0.0, 0.02] {
        for manifold in [collide(&a, &b, margin), collide(&b, &a, margin)] {
            for point in manifold.points() {
                assert!(point.point.iter().all(|x| x.is_finite()), "{manifold:?}");
            }
            if !manifold.is_empty() {
                assert!((manifold.normal.norm() - 1.0).abs() < 1e-3, "{manifold:?}");
            }
        }
    }
}

#[test]
fn segments_shorter_than_the_linear_slop_are_refused() {
    // Found by the any_pair fuzz target: segments 30 um long, whose direction is rounding
    // noise, gave a NaN normal against each other. Box2D refuses them too.
    for (p, q) in [
        (vec2(1.5e-36, 0.0), vec2(0.0, -3.0517172e-5)),
        (
            vec2(2.7911188e-17, 1.3964586e-16),
            vec2(1.2095e-41, -2.1900623e-5),
        ),
        (vec2(0.0, 0.0), vec2(0.0049, 0.0)),
    ] {
        let error = Shape::segment(p, q).validate().expect_err("too short");
        assert!(error.to_string().contains("0.005 m apart"), "{error}");
        let capsule = Shape::capsule(p, q, 0.1).validate().expect_err("too short");
        assert!(capsule.to_string().contains("0.005 m apart"), "{capsule}");
    }
    Shape::segment(vec2(0.0, 0.0), vec2(0.0051, 0.0))
        .validate()
        .expect("a segment just longer than the slop");
}

/// Filters decide which colliders collide, as Box2D's rule: a shared negative group never, a
/// shared positive group always, otherwise each one's category in the other's mask. A filter
/// changed at run time ends the contacts it forbids and lets new ones begin.
#[test]
fn collision_filters_pick_the_pairs_that_collide() {
    use carom::{CollisionFilter, Effects};
    let limb = CollisionFilter {
        group: -1,
        ..CollisionFilter::DEFAULT
    };
    let grid = CollisionFilter {
        category: 2,
        mask: !2,
        group: 0,
    };
    for (a, b, collide) in [
        (limb, limb, false),
        (limb, CollisionFilter::DEFAULT, true),
        (grid, grid, false),
        (grid, CollisionFilter::DEFAULT, true),
        (
            CollisionFilter { group: 3, ..grid },
            CollisionFilter { group: 3, ..grid },
            true,
        ),
    ] {
        let mut world = World::new();
        world
            .update_settings(|s| s.effects = Effects::NONE)
            .unwrap();
        let first = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).filter(a))
            .unwrap();
        let second = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .position(vec2(0.5, 0.0))
                    .filter(b),
            )
            .unwrap();
        world.step(1.0 / 60.0).unwrap();
        assert_eq!(world.contacts().len() == 1, collide, "{a:?} and {b:?}");
        // Swap the second's filter for the first's: a limb with a limb never collides.
        let collider = world.body(second).unwrap().colliders()[0];
        world.collider_mut(collider).unwrap().set_filter(a);
        world.step(1.0 / 60.0).unwrap();
        let same = a.collides_with(&a);
        assert_eq!(world.contacts().len() == 1, same, "{a:?} twice");
        assert!(world.contains(first));
    }
}

/// A filter that only category-1 colliders collide with ("odd" ones), and one that collides
/// only with category-1 colliders.
const ODD: carom::CollisionFilter = carom::CollisionFilter {
    category: 2,
    mask: 1,
    group: 0,
};
const PLAIN: carom::CollisionFilter = carom::CollisionFilter {
    category: 1,
    mask: 1,
    group: 0,
};

/// The filters the query tests try: every collider, what a [`PLAIN`] collider collides with
/// (no odd ones), odd ones only, and every collider but the first body's.
fn query_filters(world: &World) -> [carom::QueryFilter; 4] {
    use carom::QueryFilter;
    let first = world.bodies().next().expect("a body").handle();
    [
        QueryFilter::ALL,
        QueryFilter::like(PLAIN),
        QueryFilter::mask(ODD.category),
        QueryFilter::ALL.excluding(first),
    ]
}

/// `count` circles and regular polygons scattered over 30 x 30 m at random angles, every
/// `odd_every`th [`ODD`], every `static_every`th static (0: none), stepped once so their
/// boxes are placed; nothing simulated.
fn scattered_world(rng: &mut Rng, count: usize, odd_every: usize, static_every: usize) -> World {
    use carom::{CollisionFilter, Effects};
    let mut world = World::new();
    world
        .update_settings(|s| s.effects = Effects::NONE)
        .unwrap();
    for i in 0..count {
        let shape = if i % 2 == 0 {
            Shape::circle(rng.range(0.1, 0.8))
        } else {
            Shape::regular(3 + rng.below(5), rng.range(0.2, 0.9)).unwrap()
        };
        let at = vec2(rng.range(-15.0, 15.0), rng.range(-15.0, 15.0));
        let filter = if i % odd_every == 0 {
            ODD
        } else {
            CollisionFilter::DEFAULT
        };
        let def = if static_every > 0 && i % static_every == 0 {
            BodyDef::static_body(shape)
        } else {
            BodyDef::dynamic(shape)
        };
        world
            .add_body(def.position(at).angle(rng.range(0.0, 6.0)).filter(filter))
            .unwrap();
    }
    world.step(1.0 / 60.0).unwrap();
    world
}

/// The world's box and shape queries find exactly what a search of every collider finds, in
/// random worlds, for random boxes and shapes, with and without a filter.
#[test]
fn box_and_shape_queries_agree_with_brute_force() {
    use carom::Aabb;
    let mut rng = Rng::new(0x9e7);
    for seed in 0..8 {
        let world = scattered_world(&mut rng, 120, 5, 3);
        let mut found_any = 0;
        for _ in 0..40 {
            let (x, y) = (rng.range(-16.0, 16.0), rng.range(-16.0, 16.0));
            let (w, h) = (rng.range(0.0, 6.0), rng.range(0.0, 6.0));
            let probe = Aabb::new(vec2(x, y), vec2(x + w, y + h));
            let shape = WorldShape::at(
                &Shape::regular(3 + rng.below(5), rng.range(0.3, 3.0)).unwrap(),
                vec2(x, y),
                rng.range(0.0, 6.0),
            );
            for filter in query_filters(&world) {
                let wanted = |c: &carom::Collider| filter.sees(&c.filter(), c.body());
                let mut boxes: Vec<_> = world
                    .colliders()
                    .filter(|c| wanted(c) && c.aabb().overlaps(&probe))
                    .map(|c| world.body(c.body()).unwrap().colliders()[0])
                    .collect();
                boxes.sort_unstable_by_key(|h| h.index());
                assert_eq!(world.query_aabb(&probe, filter), boxes, "seed {seed}");
                let mut shapes: Vec<_> = world
                    .colliders()
                    .filter(|c| wanted(c) && separation(&shape, c.world_shape()).separation <= 0.0)
                    .map(|c| world.body(c.body()).unwrap().colliders()[0])
                    .collect();
                shapes.sort_unstable_by_key(|h| h.index());
                assert_eq!(world.query_shape(&shape, filter), shapes, "seed {seed}");
                found_any += shapes.len();
            }
        }
        assert!(found_any > 20, "the queries hit something: {found_any}");
    }
}

/// Ray casts find every collider a ray enters, nearest first, and the closest of those
/// allowed by a filter, as casting against every collider does, in random worlds.
#[test]
fn ray_casts_agree_with_brute_force() {
    use carom::Ray;
    let mut rng = Rng::new(0x4a7);
    let mut hits_seen = 0;
    for seed in 0..6 {
        let world = scattered_world(&mut rng, 100, 4, 0);
        for _ in 0..60 {
            let origin = vec2(rng.range(-18.0, 18.0), rng.range(-18.0, 18.0));
            let ray = Ray::new(origin, vec2(rng.range(-30.0, 30.0), rng.range(-30.0, 30.0)));
            for filter in query_filters(&world) {
                // Every collider, cast in its body's frame (each body is one shape at its
                // origin).
                let mut expected: Vec<(f32, carom::BodyHandle)> = world
                    .colliders()
                    .filter(|c| filter.sees(&c.filter(), c.body()))
                    .filter_map(|c| {
                        let body = world.body(c.body()).unwrap();
                        let inverse = body.rotation().inverse();
                        let local =
                            Ray::new(body.local_point(ray.origin), inverse * ray.translation);
                        c.shape()
                            .ray_cast_local(&local)
                            .map(|h| (h.fraction, c.body()))
                    })
                    .collect();
                expected.sort_by(|a, b| a.0.total_cmp(&b.0));
                let all: Vec<(f32, carom::BodyHandle)> = world
                    .cast_ray_all(&ray, filter)
                    .iter()
                    .map(|h| (h.fraction, h.body))
                    .collect();
                assert_eq!(all, expected, "seed {seed}");
                let closest = world.cast_ray(&ray, filter).map(|h| (h.fraction, h.body));
                assert_eq!(closest, expected.first().copied(), "seed {seed}");
                hits_seen += all.len();
            }
        }
    }
    assert!(hits_seen > 50, "the rays hit something: {hits_seen}");
}

/// A random shape to cast: a circle, a regular polygon, a capsule or a rounded box, at `at`.
fn random_cast_shape(rng: &mut Rng, at: Vec2) -> WorldShape {
    let shape = match rng.below(4) {
        0 => Shape::circle(rng.range(0.1, 1.0)),
        1 => Shape::regular(3 + rng.below(5), rng.range(0.2, 1.2)).unwrap(),
        2 => Shape::capsule(vec2(-0.6, 0.0), vec2(0.6, 0.0), rng.range(0.05, 0.5)),
        _ => Shape::rounded_rect(rng.range(0.1, 0.8), rng.range(0.1, 0.8), 0.1),
    };
    WorldShape::at(&shape, at, rng.range(0.0, 6.0))
}

/// `shape` moved by `fraction` of `translation`.
fn moved(shape: &WorldShape, translation: Vec2, fraction: Real) -> WorldShape {
    let mut moved = shape.clone();
    moved.translate(translation * fraction);
    moved
}

/// Shape casts in random worlds agree with sweeping each collider in fine steps: every
/// collider the sweep reaches is hit, where the shape first touches it (not past it, not far
/// short of it), with the point on that collider's surface and its normal pushing back; the
/// closest hit is the first of them; the filter is obeyed.
#[test]
fn shape_casts_agree_with_brute_force() {
    use carom::SHAPE_CAST_TOLERANCE;
    const SAMPLES: usize = 3000;
    let mut rng = Rng::new(0x5ca7);
    let (mut hits_seen, mut overlaps_seen) = (0, 0);
    for seed in 0..5 {
        let world = scattered_world(&mut rng, 100, 4, 3);
        for _ in 0..30 {
            let at = vec2(rng.range(-18.0, 18.0), rng.range(-18.0, 18.0));
            let shape = random_cast_shape(&mut rng, at);
            let translation = vec2(rng.range(-20.0, 20.0), rng.range(-20.0, 20.0));
            let path = shape.aabb().union(&moved(&shape, translation, 1.0).aabb());
            for filter in query_filters(&world) {
                let hits = world.cast_shape_all(&shape, translation, filter);
                let closest = world.cast_shape(&shape, translation, filter);
                assert_eq!(closest, hits.first().copied(), "seed {seed}");
                assert!(hits.windows(2).all(|w| w[0].fraction <= w[1].fraction));
                for c in world.colliders() {
                    let allowed = filter.sees(&c.filter(), c.body());
                    let handle = world.body(c.body()).unwrap().colliders()[0];
                    let found = hits.iter().find(|h| h.collider == handle);
                    if !allowed || !c.aabb().overlaps(&path) {
                        assert!(
                            found.is_none(),
                            "seed {seed}: {found:?} was not to be found"
                        );
                        continue;
                    }
                    let gap = |f: Real| separation(&moved(&shape, translation, f), c.world_shape());
                    // The first sampled time the shape touches the collider.
                    let touch = (0..=SAMPLES)
                        .map(|k| k as Real / SAMPLES as Real)
                        .find(|&f| gap(f).separation <= 0.0);
                    let Some(hit) = found else {
                        assert!(touch.is_none(), "seed {seed}: missed a touch at {touch:?}");
                        continue;
                    };
                    // Touching at the hit, not past it (unless overlapping from the start).
                    let s = gap(hit.fraction).separation;
                    let deepest = if hit.fraction == 0.0 {
                        Real::MIN
                    } else {
                        -1e-3
                    };
                    assert!(
                        (deepest..=SHAPE_CAST_TOLERANCE + 1e-4).contains(&s),
                        "seed {seed}: at the hit, {}, the gap is {s}",
                        hit.fraction
                    );
                    if let Some(touch) = touch {
                        assert!(
                            hit.fraction <= touch + 1e-4,
                            "{} after {touch}",
                            hit.fraction
                        );
                    }
                    // The point is on the collider's surface, the normal a unit vector
                    // opposing the motion (a shape overlapping at the start has no motion
                    // to oppose).
                    let point = WorldShape::Circle {
                        center: hit.point,
                        radius: 0.0,
                    };
                    let off = separation(&point, c.world_shape()).separation;
                    assert!((hit.normal.norm() - 1.0).abs() < 1e-4);
                    if hit.fraction > 0.0 {
                        assert!(off.abs() < 2.0 * SHAPE_CAST_TOLERANCE, "point {off} off");
                        assert!(hit.normal.dot(&translation) <= 1e-3 * translation.norm());
                        hits_seen += 1;
                    } else {
                        overlaps_seen += 1;
                    }
                }
            }
        }
    }
    assert!(
        hits_seen > 100 && overlaps_seen > 5,
        "{hits_seen} hits, {overlaps_seen} overlaps"
    );
}

/// A chain's link is one-sided for shape casts as for bodies: a shape cast from in front hits
/// it, from behind passes through.
#[test]
fn shape_casts_pass_through_a_chain_from_behind() {
    use carom::{ChainDef, QueryFilter};
    let mut world = World::new();
    // Solid below, walking right to left.
    let chain = ChainDef::open([vec2(10.0, 0.0), vec2(0.0, 0.0), vec2(-10.0, 0.0)]);
    world
        .add_body(BodyDef::static_chain(&chain).unwrap())
        .unwrap();
    world.step(1.0 / 60.0).unwrap();
    let ball = |y| WorldShape::at(&Shape::circle(0.5), vec2(1.0, y), 0.0);
    let down = world
        .cast_shape(&ball(3.0), vec2(0.0, -6.0), QueryFilter::ALL)
        .expect("from above, it lands on the chain");
    assert!(
        (down.fraction - 2.5 / 6.0).abs() < 1e-3,
        "{}",
        down.fraction
    );
    assert!((down.normal - vec2(0.0, 1.0)).norm() < 1e-5);
    assert!(
        (down.point - vec2(1.0, 0.0)).norm() < 2e-3,
        "{:?}",
        down.point
    );
    let up = world.cast_shape(&ball(-3.0), vec2(0.0, 6.0), QueryFilter::ALL);
    assert_eq!(up, None, "from below it passes through");
}
