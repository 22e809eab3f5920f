//! Degenerate and random input: constructors answer with a value or an error, never a panic,
//! and what they accept is a well-formed shape.

use carom::{
    BodyDef, CaromError, ColliderDef, Polygon, Real, Shape, Vec2, World, WorldShape, vec2,
};
use carom_bench::cases::Rng;
use carom_tests::first_non_finite_body;

/// A polygon carom accepted must be convex, counter-clockwise, centred, with unit outward
/// normals.
fn assert_well_formed(polygon: &Polygon) {
    let (vertices, normals) = (polygon.vertices(), polygon.normals());
    let n = vertices.len();
    assert!(n >= 3);
    for i in 0..n {
        let (a, b, c) = (vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]);
        assert!(
            carom::testing::cross(b - a, c - b) > 0.0,
            "not strictly convex at {i}"
        );
        assert!((normals[i].norm() - 1.0).abs() < 1e-5);
        assert!(normals[i].dot(&(b - a)).abs() < 1e-4 * (b - a).norm());
        // The centroid (origin) is behind every edge.
        assert!(normals[i].dot(&a) > 0.0);
    }
    let centroid = carom::testing::polygon_centroid(vertices).unwrap();
    assert!(centroid.norm() < 1e-4 * polygon.radius().max(1.0));
}

#[test]
fn hull_of_random_clouds_contains_every_point() {
    let mut rng = Rng::new(42);
    for round in 0..500 {
        let count = 3 + rng.below(40);
        let scale = [0.01, 1.0, 100.0][round % 3];
        let cloud: Vec<Vec2> = (0..count)
            .map(|_| vec2(rng.range(-scale, scale), rng.range(-scale, scale)))
            .collect();
        match Polygon::hull(&cloud) {
            Ok(hull) => {
                assert_well_formed(&hull);
                for p in &cloud {
                    let local = p - hull.source_centroid();
                    let outside = hull
                        .vertices()
                        .iter()
                        .zip(hull.normals())
                        .map(|(v, n)| n.dot(&(local - v)))
                        .fold(Real::MIN, Real::max);
                    assert!(
                        outside <= 1e-4 * scale,
                        "round {round}: point {p:?} outside by {outside}"
                    );
                }
            }
            Err(e) => assert!(count < 3 || matches!(e, CaromError::ZeroArea), "{e}"),
        }
    }
}

#[test]
fn random_outlines_are_accepted_only_when_convex() {
    let mut rng = Rng::new(7);
    let (mut accepted, mut rejected) = (0, 0);
    for _ in 0..2000 {
        let count = 3 + rng.below(6);
        let points: Vec<Vec2> = (0..count)
            .map(|_| vec2(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
            .collect();
        match Polygon::new(&points) {
            Ok(polygon) => {
                assert_well_formed(&polygon);
                accepted += 1;
            }
            Err(e) => {
                assert!(!e.to_string().is_empty());
                rejected += 1;
            }
        }
    }
    // Random outlines are mostly not convex, but triangles always are.
    assert!(accepted > 200 && rejected > 200, "{accepted} / {rejected}");
}

#[test]
fn points_on_a_circle_in_any_order_of_winding() {
    for n in [3, 4, 7, 16, 64] {
        let ring: Vec<Vec2> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU as Real * i as Real / n as Real;
                vec2(5.0 + 2.0 * a.cos(), -3.0 + 2.0 * a.sin())
            })
            .collect();
        let ccw = Polygon::new(&ring).unwrap();
        let reversed: Vec<Vec2> = ring.iter().rev().copied().collect();
        let cw = Polygon::new(&reversed).unwrap();
        assert_well_formed(&ccw);
        assert_well_formed(&cw);
        assert_eq!(ccw.len(), n);
        assert!((ccw.source_centroid() - vec2(5.0, -3.0)).norm() < 1e-4);
        assert!((cw.source_centroid() - ccw.source_centroid()).norm() < 1e-5);
    }
}

#[test]
fn degenerate_input_is_an_error_with_a_message() {
    let cases: Vec<(Vec<Vec2>, &str)> = vec![
        (vec![], "at least 3"),
        (vec![vec2(0.0, 0.0), vec2(1.0, 0.0)], "at least 3"),
        (
            vec![vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(Real::INFINITY, 1.0)],
            "finite",
        ),
        (
            vec![vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 0.0)],
            "coincide",
        ),
        (
            vec![
                vec2(0.0, 0.0),
                vec2(1.0, 1.0),
                vec2(2.0, 2.0),
                vec2(3.0, 3.0),
            ],
            "zero area",
        ),
        (
            vec![
                vec2(0.0, 0.0),
                vec2(2.0, 0.0),
                vec2(1.0, 1.0),
                vec2(2.0, 2.0),
                vec2(0.0, 2.0),
            ],
            "vertex 2",
        ),
        // A bow tie: its two halves cancel, so its signed area is zero.
        (
            vec![
                vec2(0.0, 0.0),
                vec2(1.0, 1.0),
                vec2(1.0, 0.0),
                vec2(0.0, 1.0),
            ],
            "zero area",
        ),
    ];
    for (points, expected) in cases {
        let message = Polygon::new(&points).unwrap_err().to_string();
        assert!(
            message.contains(expected),
            "{message:?} should mention {expected:?}"
        );
    }
    assert!(
        Shape::circle(0.0)
            .validate()
            .unwrap_err()
            .to_string()
            .contains("positive")
    );
    assert!(
        Shape::circle(Real::NAN)
            .validate()
            .unwrap_err()
            .to_string()
            .contains("finite")
    );
}

#[test]
fn bodies_with_bad_values_are_refused_at_the_door() {
    let mut world = World::new();
    let square = || Shape::rect(0.5, 0.5);
    let bad = [
        BodyDef::dynamic(Shape::circle(-1.0)),
        BodyDef::static_body(Shape::rect(0.0, 1.0)),
        BodyDef::kinematic(Shape::rect(1.0, Real::INFINITY)),
        BodyDef::dynamic(square()).density(0.0),
        BodyDef::dynamic(square()).density(-2.0),
        BodyDef::dynamic(square()).density(Real::NAN),
        BodyDef::dynamic(square()).position(vec2(Real::NAN, 0.0)),
        BodyDef::dynamic(square()).angle(Real::INFINITY),
        BodyDef::dynamic(square()).linear_velocity(vec2(0.0, Real::NEG_INFINITY)),
        BodyDef::dynamic(square()).friction(-1.0),
        BodyDef::dynamic(square()).restitution(Real::NAN),
        BodyDef::dynamic(square()).damping(-0.5, 0.0),
        BodyDef::static_body(square()).density(Real::NAN),
    ];
    for def in bad {
        assert!(world.add_body(def).is_err());
    }
    assert_eq!(world.body_count(), 0);
    // A static body needs no positive density: it has no mass.
    let floor = world
        .add_body(BodyDef::static_body(square()).density(0.0))
        .unwrap();
    // Nor can a body take a bad collider later, or lose its last one.
    let bad_collider = ColliderDef::new(Shape::circle(Real::NAN));
    assert!(world.add_collider(floor, bad_collider).is_err());
    let only = world.body(floor).unwrap().colliders()[0];
    assert!(world.collider_mut(only).unwrap().set_density(-1.0).is_err());
    assert!(matches!(
        world.remove_collider(only),
        Err(CaromError::NoCollider)
    ));
    assert_eq!(world.body(floor).unwrap().colliders(), &[only]);
    assert_eq!(world.collider(only).unwrap().shape(), &square());
    assert!(
        world
            .update_settings(|s| s.gravity = vec2(0.0, Real::NAN))
            .is_err()
    );
    assert_eq!(world.gravity(), vec2(0.0, -10.0));
}

/// A density so small that a dynamic body's mass or rotational inertia is beyond what the
/// solver can invert and multiply (mass under 1e-20 kg, inertia under 1e-28 kg·m²) is refused
/// with an error that names it, when the body is made and when a collider's density is
/// changed (which then keeps its old density); the smallest accepted steps finite.
#[test]
fn a_density_too_small_for_the_solver_is_refused() {
    let mut world = World::new();
    // A unit square's mass is its density; a 0.2 mm one's inertia is its mass times 6.7e-9,
    // under the least inertia while its mass is just above the least mass.
    let refused = [
        (Shape::rect(0.5, 0.5), 0.5e-20, "mass"),
        (Shape::rect(0.5, 0.5), 0.5 / Real::MAX, "mass"),
        (Shape::rect(1.0e-4, 1.0e-4), 3.0e-13, "inertia"),
    ];
    for (shape, density, what) in refused {
        let error = world
            .add_body(BodyDef::dynamic(shape).density(density))
            .unwrap_err();
        assert!(matches!(
            error,
            CaromError::OutOfRange {
                name: "density",
                ..
            }
        ));
        assert!(error.to_string().contains(what), "{error}");
    }
    assert_eq!(world.body_count(), 0);
    let body = world
        .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 2.0)))
        .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
        .unwrap();
    let collider = world.body(body).unwrap().colliders()[0];
    assert!(
        world
            .collider_mut(collider)
            .unwrap()
            .set_density(0.5e-20)
            .is_err()
    );
    assert_eq!(world.collider(collider).unwrap().density(), 1.0);
    assert_eq!(world.body(body).unwrap().mass(), 1.0);
    // The least mass is taken, and the body falls onto the ground and rests there, finite.
    world
        .collider_mut(collider)
        .unwrap()
        .set_density(1.0e-20)
        .unwrap();
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    let b = world.body(body).unwrap();
    assert!(
        b.position().iter().all(|x| x.is_finite()),
        "{:?}",
        b.position()
    );
    assert!((b.position().y - 1.0).abs() < 0.05, "{:?}", b.position());
    assert!(b.linear_velocity().iter().all(|x| x.is_finite()));
}

/// A kinematic capsule told to move at an absurd speed is refused; at the fastest speed a body
/// takes, over the longest steps, it is carried so far out that rounding joins its two ends:
/// it stays a finite shape (its normals its own, turned) and the world holds together as it
/// steps on.
#[test]
fn a_capsule_flung_past_where_rounding_keeps_its_length_stays_finite() {
    let mut world = World::new();
    let capsule = world
        .add_body(BodyDef::kinematic(Shape::capsule(
            vec2(-0.1, 0.0),
            vec2(0.1, 0.0),
            0.05,
        )))
        .unwrap();
    world
        .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
        .unwrap();
    let mut flung = world.body_mut(capsule).unwrap();
    assert!(flung.set_linear_velocity(vec2(-1.0e17, 1.0e14)).is_err());
    flung.set_linear_velocity(vec2(-1.0e6, 1.0e3)).unwrap();
    for _ in 0..3 {
        world.step(10.0).unwrap();
        world.check_invariants();
    }
    let body = world.body(capsule).unwrap();
    assert!(body.position().x < -2.9e7, "{:?}", body.position());
    let collider = world.collider(body.colliders()[0]).unwrap();
    let WorldShape::Polygon {
        vertices, normals, ..
    } = collider.world_shape()
    else {
        panic!("a capsule is placed as a rounded two-point polygon");
    };
    assert_eq!(vertices[0], vertices[1], "rounding joined the ends");
    assert!(
        normals
            .iter()
            .all(|n| n.x.is_finite() && n.y.is_finite() && (n.norm() - 1.0).abs() < 1e-5),
        "{normals:?}"
    );
}

/// Finite values too large (or too small) for f32 arithmetic to stay finite are refused like
/// non-numbers: time steps outside 1 µs to 10 s, positions beyond 1000 km, collider offsets
/// beyond 100 km. And a shape a world would refuse meets nothing in a query.
#[test]
fn values_beyond_what_f32_can_carry_are_refused() {
    let mut world = World::new();
    let square = || Shape::rect(0.5, 0.5);
    let body = world.add_body(BodyDef::dynamic(square())).unwrap();
    for dt in [0.0, 1e-9, Real::MIN_POSITIVE, 10.5, 3e38] {
        assert!(
            matches!(world.step(dt), Err(CaromError::OutOfRange { .. })),
            "a step of {dt} s"
        );
    }
    assert!(matches!(
        world.step(Real::NAN),
        Err(CaromError::NonFinite { .. })
    ));
    assert_eq!(world.step_count(), 0);
    for dt in [1e-6, 1.0 / 60.0, 10.0] {
        world.step(dt).unwrap();
    }
    let far = [vec2(2e6, 0.0), vec2(0.0, -1.5e6), vec2(3e38, 3e38)];
    for position in far {
        assert!(
            world
                .add_body(BodyDef::dynamic(square()).position(position))
                .is_err()
        );
        let before = world.body(body).unwrap().position();
        let mut handle = world.body_mut(body).unwrap();
        assert!(handle.set_position(position).is_err());
        assert!(handle.move_kinematic_to(position, 0.0, 1.0 / 60.0).is_err());
        assert_eq!(world.body(body).unwrap().position(), before);
    }
    world
        .add_body(BodyDef::dynamic(square()).position(vec2(-1e6, 1e6)))
        .unwrap();
    let offset = ColliderDef::new(Shape::circle(0.5)).offset(vec2(0.0, -1e9));
    assert!(world.add_collider(body, offset.clone()).is_err());
    assert!(
        world
            .add_body(BodyDef::dynamic(square()).collider(offset))
            .is_err()
    );
    // A capsule whose ends coincide (refused as a collider) has no normal to cast with.
    let point = Shape::capsule(Vec2::zeros(), Vec2::zeros(), 0.4);
    assert!(
        world
            .add_collider(body, ColliderDef::new(point.clone()))
            .is_err()
    );
    let at_body = world.body(body).unwrap().position();
    let shape = carom::WorldShape::at(&point, at_body + vec2(-3.0, 0.0), 0.0);
    let filter = carom::QueryFilter::default();
    assert!(world.cast_shape(&shape, vec2(6.0, 0.0), filter).is_none());
    assert!(world.query_shape(&shape, filter).is_empty());
    let sound = carom::WorldShape::at(&Shape::circle(0.4), at_body + vec2(-3.0, 0.0), 0.0);
    assert!(world.cast_shape(&sound, vec2(6.0, 0.0), filter).is_some());
}

#[test]
fn stepping_a_world_of_extreme_but_valid_bodies_stays_finite() {
    let mut world = World::new();
    let mut rng = Rng::new(3);
    for _ in 0..200 {
        let shape = if rng.below(2) == 0 {
            Shape::circle(rng.range(1e-3, 50.0))
        } else {
            Shape::regular(3 + rng.below(10), rng.range(1e-3, 50.0)).unwrap()
        };
        world
            .add_body(
                BodyDef::dynamic(shape)
                    .position(vec2(rng.range(-1e4, 1e4), rng.range(-1e4, 1e4)))
                    .linear_velocity(vec2(rng.range(-1e3, 1e3), rng.range(-1e3, 1e3)))
                    .angular_velocity(rng.range(-1e3, 1e3))
                    .density(rng.range(1e-3, 1e3))
                    .damping(rng.range(0.0, 1e3), rng.range(0.0, 1e3)),
            )
            .unwrap();
    }
    for _ in 0..600 {
        world.step(1.0 / 60.0).unwrap();
    }
    for body in world.bodies() {
        assert!(body.position().iter().all(|x| x.is_finite()));
        assert!(body.linear_velocity().iter().all(|x| x.is_finite()));
        assert!(body.angle().is_finite() && body.angular_velocity().is_finite());
        assert!(body.aabb().min.iter().all(|x| x.is_finite()));
    }
}

#[test]
fn shapes_beyond_100_km_or_with_hairline_edges_are_refused_or_repaired() {
    // Found by the narrowphase fuzz targets: a radius of 3e38 overflowed a sum of radii to -inf,
    // and coordinates of 1e19 left a zero normal.
    for error in [
        Shape::circle(3.4e38).validate().unwrap_err(),
        Shape::rect(2.0e5, 1.0).validate().unwrap_err(),
        Shape::regular(5, 1.0e6).unwrap_err(),
        Shape::hull(&[vec2(0.0, 0.0), vec2(1.6e19, 0.0), vec2(0.0, 1.0)]).unwrap_err(),
        Shape::polygon(&[vec2(0.0, 0.0), vec2(1.0e6, 0.0), vec2(0.0, 1.0)]).unwrap_err(),
    ] {
        assert!(error.to_string().contains("100 km"), "{error}");
    }
    // Two hull points 1e-13 m apart, far from the centroid, land on one another once the
    // polygon is recentred: the edge between them had a NaN normal. They are merged now.
    let hull = Shape::hull(&[
        vec2(-4.7e-38, 0.12182904),
        vec2(-7.534539e-14, -7.534539e-14),
        vec2(0.04630438, 0.061093558),
        vec2(1.6823371e-38, 0.0),
    ]);
    if let Ok(Shape::Polygon(polygon)) = hull {
        for normal in polygon.normals() {
            assert!((normal.norm() - 1.0).abs() < 1e-5, "{normal:?}");
        }
    }
}

/// Random sequences of every public call on a world (bodies, colliders and joints added and
/// removed, every setter, steps with any time step, queries, explosions, saves read back), with
/// sensible, extreme and non-number values: nothing panics, every call succeeds or is refused,
/// bodies stay finite and the world holds together after each call (`carom_tests::world_ops`,
/// the world-operations fuzz target's own checks). `CAROM_OPS_CASES` sets how many sequences
/// and `CAROM_OPS_CASE` runs one alone, by the number a failure names; `CAROM_OPS_FILE` runs
/// the bytes of a file instead (an input the fuzz target found), or of every file in a folder
/// (a corpus), and prints how long the slowest took.
#[test]
fn random_sequences_of_public_calls_keep_the_world_whole() {
    if let Ok(path) = std::env::var("CAROM_OPS_FILE") {
        let path = std::path::PathBuf::from(path);
        let files: Vec<_> = match std::fs::read_dir(&path) {
            Ok(entries) => entries
                .map(|e| e.expect("a readable entry").path())
                .collect(),
            Err(_) => vec![path],
        };
        let mut slowest = (std::time::Duration::ZERO, None);
        for file in &files {
            let bytes = std::fs::read(file).expect("CAROM_OPS_FILE names readable files");
            let started = std::time::Instant::now();
            let tally = carom_tests::world_ops::run(&bytes);
            if started.elapsed() > slowest.0 {
                slowest = (started.elapsed(), Some((file, tally)));
            }
        }
        println!("{} sequences, the slowest {slowest:?}", files.len());
        return;
    }
    let cases: usize = std::env::var("CAROM_OPS_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(1000);
    let mut total = carom_tests::world_ops::Tally::default();
    // Every case runs, so one run names all the sequences that break a promise.
    let mut broken = Vec::new();
    for case in std::env::var("CAROM_OPS_CASE")
        .ok()
        .and_then(|c| c.parse().ok())
        .map_or(0..cases as u64, |c: u64| c..c + 1)
    {
        let mut rng = carom_bench::cases::Rng::new(0x9e37_79b9_7f4a_7c15 ^ case);
        let bytes: Vec<u8> = (0..1500).map(|_| rng.next_u64() as u8).collect();
        let Ok(tally) = std::panic::catch_unwind(|| carom_tests::world_ops::run(&bytes)) else {
            eprintln!("case {case} broke a promise (above)");
            broken.push(case);
            continue;
        };
        total.calls += tally.calls;
        total.refused += tally.refused;
        total.steps += tally.steps;
        total.restores += tally.restores;
    }
    println!("{total:?}");
    assert!(broken.is_empty(), "cases that broke a promise: {broken:?}");
    // The sequences reached every kind of outcome: calls refused and made, steps and restores.
    assert!(
        total.refused > 0 && total.refused < total.calls && total.steps > 0 && total.restores > 0,
        "{total:?}"
    );
}

/// The fuzz targets' kept seeds (`fuzz/seeds/`), each run as its target runs it: the
/// world-operation sequences libFuzzer found that reach the most code, and saved worlds.
#[test]
fn the_fuzz_seeds_keep_their_promises() {
    let seeds = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/seeds");
    let files = |target: &str| {
        let mut files: Vec<_> = std::fs::read_dir(seeds.join(target))
            .expect("the seeds are there")
            .map(|entry| entry.expect("a readable entry").path())
            .collect();
        files.sort();
        files
    };
    let sequences = files("world_ops");
    assert!(sequences.len() >= 50, "{} sequences", sequences.len());
    for file in &sequences {
        let bytes = std::fs::read(file).expect("a readable seed");
        std::panic::catch_unwind(|| carom_tests::world_ops::run(&bytes))
            .unwrap_or_else(|_| panic!("{} broke a promise (above)", file.display()));
    }
    // Scene files asking for more than a machine holds, or for values past the ends of a
    // range: refused, quickly, not built.
    let scenes = files("scene_file");
    assert!(scenes.len() >= 6, "{} scenes", scenes.len());
    for file in &scenes {
        let text = std::fs::read_to_string(file).expect("a readable seed");
        assert!(
            carom_scene::parse(&text, "seed.ron").is_ok(),
            "{} parses",
            file.display()
        );
        let built = std::panic::catch_unwind(|| carom_tests::untrusted_files::scene_file(&text))
            .unwrap_or_else(|_| panic!("{} broke a promise (above)", file.display()));
        // Those named for it hold what the world accepts, at the ends of its ranges.
        let name = file
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        let builds = name == "repeat_of_nothing.ron" || name.starts_with("accepted_");
        assert_eq!(built, builds, "{} built", file.display());
    }
    let saved = files("saved_world");
    assert!(!saved.is_empty());
    for file in &saved {
        let text = std::fs::read_to_string(file).expect("a readable seed");
        assert!(
            carom_tests::untrusted_files::saved_world(&text),
            "{} no longer reads as a saved world: save it again from its demo",
            file.display()
        );
    }
}

/// Values at the far ends of what each call takes: each is refused with an error, or taken
/// with the world stepping on finite; none panics.
#[test]
fn values_at_the_ends_of_each_range_are_refused_or_kept_finite() {
    use carom::{
        CollisionPlane, DistanceJointDef, MoverJointDef, RevoluteJointDef, SolverKind, Surface,
        solve_planes,
    };
    // A plane's push limit that is negative or not a number pushes nothing.
    for limit in [-1.0, Real::NAN] {
        let mut planes = [CollisionPlane::soft(vec2(0.0, 1.0), 0.5, limit)];
        let solved = solve_planes(vec2(1.0, -1.0), &mut planes);
        assert_eq!(solved.delta, vec2(1.0, -1.0), "push limit {limit}");
    }
    // A plane with no direction, or numbers that are not finite, pushes nothing.
    for (normal, offset) in [(Vec2::zeros(), 0.5), (vec2(0.0, 1.0), Real::NAN)] {
        let mut planes = [CollisionPlane::rigid(normal, offset)];
        let solved = solve_planes(vec2(1.0, -1.0), &mut planes);
        assert_eq!(
            solved.delta,
            vec2(1.0, -1.0),
            "normal {normal:?}, offset {offset}"
        );
    }
    // A shape beyond 100 km is named as the shape it is.
    for (shape, name) in [
        (
            Shape::capsule(vec2(2e5, 0.0), vec2(2e5 + 1.0, 0.0), 0.5),
            "capsule coordinate",
        ),
        (
            Shape::segment(vec2(0.0, 0.0), vec2(0.0, -2e5)),
            "segment coordinate",
        ),
    ] {
        let def = BodyDef::static_body(shape);
        let error = World::new().add_body(def).unwrap_err().to_string();
        assert!(error.contains(name), "{error}");
    }
    // A regular polygon of more sides than any number a shape needs.
    assert!(Shape::regular(usize::MAX, 1.0).is_err());
    assert!(Shape::regular(1 << 40, 1.0).is_err());
    // Surfaces whose coefficients overflow what the solver multiplies them by.
    for solver in [SolverKind::SoftStep, SolverKind::SequentialImpulse] {
        let mut world = World::new();
        world.update_settings(|s| s.solver.kind = solver).unwrap();
        let huge = Surface {
            friction: 3e38,
            rolling_resistance: 3e38,
            restitution: 3e38,
            tangent_speed: 3e38,
            ..Surface::default()
        };
        let floor = BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5));
        let ball = BodyDef::dynamic(Shape::circle(0.5)).position(vec2(0.0, 0.6));
        // The greatest of each is taken, and the world steps on finite.
        for def in [floor, ball] {
            let refused = world.add_body(def.clone().surface(huge)).unwrap_err();
            assert!(refused.to_string().contains("from 0 to 1000"), "{refused}");
            let body = world.add_body(def).unwrap();
            let collider = world.body(body).unwrap().colliders()[0];
            let mut collider = world.collider_mut(collider).unwrap();
            assert!(collider.set_tangent_speed(1.5e4).is_err());
            collider.set_tangent_speed(1e4).unwrap();
            collider.set_friction(1000.0).unwrap();
            collider.set_restitution(1000.0).unwrap();
            collider.set_rolling_resistance(1000.0).unwrap();
        }
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert_eq!(first_non_finite_body(&world), None, "{solver:?}");
    }
    // The greatest friction holds a box on a slope, and so does a mixer's answer past it
    // (held to the greatest, not lost to 0).
    for mixer in [None, Some((|_, _, _, _| 1e30) as carom::MaterialMixer)] {
        let mut world = World::new();
        if let Some(mixer) = mixer {
            world.set_friction_mixer(Some(mixer));
        }
        let grip = Surface {
            friction: 1000.0,
            ..Surface::default()
        };
        assert!(
            Surface {
                friction: 1000.1,
                ..grip
            }
            .validate()
            .is_err()
        );
        let slope = BodyDef::static_body(Shape::rect(20.0, 0.5)).angle(0.5);
        world.add_body(slope.surface(grip)).unwrap();
        let top = carom::rotation(0.5) * vec2(0.0, 1.0);
        let sliding = BodyDef::dynamic(Shape::rect(0.5, 0.5))
            .position(top)
            .angle(0.5)
            .surface(grip);
        let block = world.add_body(sliding).unwrap();
        for _ in 0..60 {
            world.step(1.0 / 60.0).unwrap();
        }
        let moved = (world.body(block).unwrap().position() - top).norm();
        assert!(moved < 0.05, "the box slid {moved} m");
    }
    // A density whose mass overflows.
    let mut world = World::new();
    let heavy = BodyDef::dynamic(Shape::rect(10.0, 10.0)).density(3e37);
    let refused = world.add_body(heavy).unwrap_err().to_string();
    assert!(refused.contains("at most 1e30 kg"), "{refused}");
    let wide = BodyDef::dynamic(Shape::rect(1e4, 1.0)).density(1e25);
    let refused = world.add_body(wide).unwrap_err().to_string();
    assert!(refused.contains("at most 1e36 kg·m²"), "{refused}");
    world
        .add_body(BodyDef::dynamic(Shape::rect(10.0, 10.0)).density(2e27))
        .unwrap();
    world.step(1.0 / 60.0).unwrap();
    assert_eq!(first_non_finite_body(&world), None);
    // Springs stiffer than anything a step resolves, and solver settings past all use.
    let mut world = World::new();
    let ground = world
        .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
        .unwrap();
    let bob = world
        .add_body(BodyDef::dynamic(Shape::circle(0.25)).position(vec2(0.0, 3.0)))
        .unwrap();
    let stiff = [
        DistanceJointDef::new(ground, bob, vec2(0.0, 0.5), vec2(0.0, 3.0))
            .spring(1e30, 1.0)
            .into(),
        RevoluteJointDef::new(ground, bob, vec2(0.0, 3.0))
            .spring(3e38, 3e38)
            .into(),
    ];
    for def in stiff {
        let def: carom::JointDef = def;
        let refused = world.add_joint(def).unwrap_err().to_string();
        assert!(refused.contains("from 0 to 1e6"), "{refused}");
    }
    let stiffest = RevoluteJointDef::new(ground, bob, vec2(0.0, 3.0)).spring(1e6, 1e6);
    world.add_joint(stiffest).unwrap();
    for _ in 0..10 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(first_non_finite_body(&world), None);
    for (name, change) in [
        (
            "damping ratio",
            (|s: &mut carom::WorldSettings| s.solver.damping_ratio = 3e38) as fn(&mut _),
        ),
        ("static stiffness", |s| s.solver.static_stiffness = 3e38),
        ("joint damping ratio", |s| {
            s.solver.joint_damping_ratio = 3e38
        }),
    ] {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
            .unwrap();
        world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 0.99)))
            .unwrap();
        let refused = world.update_settings(change).unwrap_err().to_string();
        assert!(
            refused.contains(name) && refused.contains("at most 1e6"),
            "{refused}"
        );
        for _ in 0..10 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert_eq!(first_non_finite_body(&world), None, "{name}");
    }
    // Gravity as strong as a world takes, with forces pulling against it; stronger is
    // refused.
    assert!(
        World::new()
            .update_settings(|s| s.gravity.y = -3e38)
            .is_err()
    );
    for gravity in [vec2(0.0, -1e6), vec2(1e6, 1e6)] {
        let mut world = World::new();
        world.update_settings(|s| s.gravity = gravity).unwrap();
        world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
            .unwrap();
        let body = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 2.0)))
            .unwrap();
        let mut pulled = world.body_mut(body).unwrap();
        let _ = pulled.apply_force_at_center(-gravity * 0.9);
        for _ in 0..10 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert_eq!(first_non_finite_body(&world), None, "gravity {gravity:?}");
    }
    // Two placed shapes that no constructor would make, against each other.
    let odd = [
        WorldShape::Circle {
            center: vec2(0.0, 0.0),
            radius: -1.0,
        },
        WorldShape::Circle {
            center: vec2(0.5, 0.0),
            radius: Real::NAN,
        },
        WorldShape::at(&Shape::rect(0.5, 0.5), vec2(0.2, 0.1), 0.3),
        WorldShape::at(
            &Shape::capsule(vec2(-1.0, 0.0), vec2(1.0, 0.0), 0.2),
            vec2(0.0, 0.1),
            0.0,
        ),
    ];
    for a in &odd {
        for b in &odd {
            let _ = carom::query::collide(a, b, 0.1);
            let _ = carom::query::separation(a, b);
        }
    }
    // An explosion whose push is refused at one body (too light for it) pushes none: the
    // heavy body pushed before it keeps its speed of before.
    let mut world = World::new();
    let heavy = BodyDef::dynamic(Shape::rect(0.05, 0.05))
        .density(1e6)
        .position(vec2(1.0, 0.0));
    let light = BodyDef::dynamic(Shape::circle(0.05))
        .density(1e-3)
        .position(vec2(-1.0, 0.0));
    let bodies = [
        world.add_body(heavy).unwrap(),
        world.add_body(light).unwrap(),
    ];
    let blast = carom::ExplosionDef::new(Vec2::zeros(), 5.0, 3e38);
    assert!(world.explode(&blast).is_err());
    for body in bodies {
        let body = world.body(body).unwrap();
        assert_eq!(body.linear_velocity(), Vec2::zeros());
        assert_eq!(body.angular_velocity(), 0.0);
    }
    let gentle = carom::ExplosionDef::new(Vec2::zeros(), 5.0, 1e-3);
    assert_eq!(world.explode(&gentle).unwrap(), 2);
    // A mover far from the origin (it has no anchors to be far from).
    let mut world = World::new();
    let far = vec2(5e5, 0.0);
    let reference = world
        .add_body(BodyDef::static_body(Shape::rect(1.0, 0.5)).position(far))
        .unwrap();
    let moved = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(far + vec2(0.0, 2.0)))
        .unwrap();
    let mover = MoverJointDef::new(reference, moved, vec2(1.0, 0.0), vec2(100.0, 0.0));
    world.add_joint(mover).unwrap();
    world
        .add_joint(carom::JointDef::filter(reference, moved))
        .unwrap();
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
    }
    let speed = world.body(moved).unwrap().linear_velocity().x;
    assert!(
        (speed - 1.0).abs() < 0.01,
        "the mover drove it at {speed} m/s"
    );
}

/// What drawing from the whole of `f32` found: speeds, gravity, joint lengths and angles, a
/// mouse joint's target and a character's place past what the solver's products carry are
/// refused; a joint's 2×2 solve whose determinant overflows or underflows is solved scaled; a
/// plane or a mover from numbers past any world's is passed over. Each check fails without
/// its bound or its fix.
#[test]
fn values_past_the_solvers_products_are_refused_and_extreme_masses_stay_finite() {
    use carom::{
        Capsule, Character, CharacterDef, CollisionPlane, JointDef, QueryFilter, SolverKind,
        WorldSettings, solve_planes,
    };
    let mut world = World::new();
    let ball = BodyDef::dynamic(Shape::circle(0.5));
    // Speeds near f32's largest overflowed a step's motion (a body's last motion, |Δp|).
    for def in [
        ball.clone().linear_velocity(vec2(3e38, 0.0)),
        ball.clone().linear_velocity(vec2(0.0, -1.1e6)),
        ball.clone().angular_velocity(-1.1e6),
        ball.clone().gravity_scale(1e4),
    ] {
        assert!(world.add_body(def).is_err());
    }
    let body = world
        .add_body(
            ball.clone()
                .linear_velocity(vec2(1e6, -1e6))
                .angular_velocity(1e6),
        )
        .unwrap();
    {
        let mut body = world.body_mut(body).unwrap();
        assert!(body.set_linear_velocity(vec2(1.7e38, 0.0)).is_err());
        assert!(body.set_angular_velocity(1e38).is_err());
        assert!(body.set_gravity_scale(-1e38).is_err());
        // An impulse may not take a body past those speeds either: in the double build one
        // of 1e228 N·s was taken, and the step's contact impulses went infinite.
        let before = (body.linear_velocity(), body.angular_velocity());
        assert!(body.apply_impulse_at_center(vec2(1e30, 0.0)).is_err());
        assert!(body.apply_impulse(vec2(0.0, 1e6), vec2(1e20, 0.0)).is_err());
        assert!(body.apply_angular_impulse(-1e30).is_err());
        // Nor act at a point farther out than a body may be placed.
        for point in [vec2(2e6, 0.0), vec2(0.0, -1e30)] {
            for (expected, result) in [
                (
                    "impulse application point",
                    body.apply_impulse(vec2(0.0, 1.0), point),
                ),
                (
                    "force application point",
                    body.apply_force(vec2(0.0, 1.0), point),
                ),
            ] {
                let error = result.unwrap_err();
                assert!(
                    matches!(error, CaromError::OutOfRange { name, .. } if name == expected),
                    "{error}"
                );
            }
        }
        assert_eq!((body.linear_velocity(), body.angular_velocity()), before);
        assert!(body.apply_angular_impulse(-1.0).is_ok());
    }
    // Gravity near f32's largest overflowed a heavy body's contact impulses; margins as large
    // made every box span the world.
    for settings in [
        WorldSettings {
            gravity: vec2(0.0, 1e38),
            ..WorldSettings::default()
        },
        WorldSettings {
            speculative_distance: 3e38,
            ..WorldSettings::default()
        },
        WorldSettings {
            aabb_margin: 1e6,
            ..WorldSettings::default()
        },
    ] {
        assert!(World::with_settings(settings).is_err());
    }
    assert!(
        world
            .update_settings(|s| s.solver.max_linear_speed = 3e38)
            .is_err()
    );
    assert!(
        world
            .update_settings(|s| s.solver.max_rotation = 4.0)
            .is_err()
    );
    // Joint lengths, angles and axes past the bounds: refused.
    let (a, b) = (
        world
            .add_body(ball.clone().position(vec2(-1.0, 5.0)))
            .unwrap(),
        world
            .add_body(ball.clone().position(vec2(1.0, 5.0)))
            .unwrap(),
    );
    for def in [
        JointDef::pogo(
            a,
            b,
            vec2(0.0, 0.0),
            vec2(1.0, 5.0),
            vec2(0.0, 1.0),
            1.7e38,
            (1.0, 1.0),
        ),
        JointDef::prismatic(a, b, vec2(0.0, 5.0), vec2(3e38, 3e38)),
        JointDef::wheel(a, b, vec2(0.0, 5.0), vec2(1e-30, 1e-30)),
        JointDef::revolute(a, b, vec2(0.0, 5.0)).limits(-1e38, 1.0),
        JointDef::revolute(a, b, vec2(0.0, 5.0)).motor_drive(3e38, 10.0),
        JointDef::distance(a, b, vec2(-1.0, 5.0), vec2(1.0, 5.0)).limits(0.0, 1e30),
        JointDef::mouse(a, vec2(2e6, 0.0), 100.0),
    ] {
        assert!(world.add_joint(def).is_err());
    }
    // A light body with a tiny inertia, hinged far from its centre to a heavy one: its
    // solve's determinant overflowed f32 and the pair went NaN. Two bodies heavier than a
    // mountain on a slider to a kinematic one: the determinant underflowed, and 1/det was
    // infinite.
    for solver in [SolverKind::SoftStep, SolverKind::SequentialImpulse] {
        let mut world = World::new();
        world.update_settings(|s| s.solver.kind = solver).unwrap();
        let light = world
            .add_body(BodyDef::dynamic(Shape::circle(0.01)).density(5e-14))
            .unwrap();
        let heavy = world
            .add_body(BodyDef::dynamic(Shape::rect(1.0, 1.0)).position(vec2(30.0, 0.0)))
            .unwrap();
        world
            .add_joint(JointDef::revolute(light, heavy, vec2(20.0, 20.0)))
            .unwrap();
        let mountain = world
            .add_body(
                BodyDef::dynamic(Shape::rect(1.0, 1.0))
                    .position(vec2(-30.0, 0.0))
                    .density(1e21),
            )
            .unwrap();
        let lift = world
            .add_body(BodyDef::kinematic(Shape::rect(1.0, 1.0)).position(vec2(-33.0, 0.0)))
            .unwrap();
        world
            .add_joint(
                JointDef::prismatic(lift, mountain, vec2(-31.5, 0.0), vec2(0.6, 0.8))
                    .motor_drive(10.0, 300.0),
            )
            .unwrap();
        for _ in 0..60 {
            world.step(1.0 / 60.0).unwrap();
            carom_tests::assert_bodies_finite(&world);
        }
    }
    // A plane whose offset lies past where anything can be, or whose normal is not a unit,
    // pushes nothing (an offset of 1.7e38 pushed the displacement to infinity).
    for plane in [
        CollisionPlane::rigid(vec2(0.6, 0.8), 1.7e38),
        CollisionPlane::rigid(vec2(3.6e10, 0.8), 0.5),
    ] {
        let solved = solve_planes(vec2(1.0, -1.0), &mut [plane]);
        assert_eq!(solved.delta, vec2(1.0, -1.0), "{plane:?}");
    }
    // A mover too large for any shape touches nothing (a radius of 1e38 made a NaN clamp
    // bound, which panicked), and one far past the world's reach does not move.
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)))
        .unwrap();
    let huge = Capsule::new(vec2(0.0, 0.0), vec2(1.0, 0.0), 1e38);
    assert!(
        world
            .collide_mover(&huge, QueryFilter::default())
            .is_empty()
    );
    let far = Capsule::new(vec2(3e38, 0.0), vec2(3e38, 1.0), 0.5);
    assert_eq!(
        world.cast_mover(&far, vec2(1.0, 0.0), QueryFilter::default()),
        0.0
    );
    // A character placed or moved past where a body may be: refused.
    let def = CharacterDef::capsule(0.5, 0.3);
    assert!(Character::new(def.clone().position(vec2(0.0, 2e6))).is_err());
    assert!(Character::new(def.clone().up(vec2(3e38, 3e38))).is_err());
    let mut character = Character::new(def.position(vec2(0.0, 2.0))).unwrap();
    assert!(character.set_position(vec2(-3e38, 0.0)).is_err());
    assert!(
        world
            .move_character(&mut character, vec2(1e38, 0.0), 1.0 / 60.0)
            .is_err()
    );
    assert!(character.position().iter().all(|x| x.is_finite()));
}

/// docs/ranges.md gives every bound a value as the code has it, and no bound the code lacks.
#[test]
fn the_ranges_page_gives_every_bound_as_the_code_has_it() {
    use carom::{
        MAX_ACCELERATION, MAX_ANGULAR_SPEED, MAX_BODY_INERTIA, MAX_BODY_MASS, MAX_GRAVITY_SCALE,
        MAX_JOINT_LENGTH, MAX_POSITION, MAX_REGULAR_SIDES, MAX_SHAPE_EXTENT, MAX_SPEED, MAX_SPRING,
        MAX_SURFACE_COEFFICIENT, MAX_TANGENT_SPEED, MIN_BODY_INERTIA, MIN_BODY_MASS,
    };
    let bounds: [(&str, String); 16] = [
        (
            "TIME_STEP_RANGE",
            format!(
                "{:e} to {:e} s",
                carom::TIME_STEP_RANGE.start(),
                carom::TIME_STEP_RANGE.end()
            ),
        ),
        ("MAX_POSITION", format!("{MAX_POSITION:e} m")),
        ("MAX_SHAPE_EXTENT", format!("{MAX_SHAPE_EXTENT:e} m")),
        ("MAX_SPEED", format!("{MAX_SPEED:e} m/s")),
        ("MAX_ANGULAR_SPEED", format!("{MAX_ANGULAR_SPEED:e} rad/s")),
        ("MAX_ACCELERATION", format!("{MAX_ACCELERATION:e} m/s²")),
        ("MAX_GRAVITY_SCALE", format!("{MAX_GRAVITY_SCALE:e}")),
        ("MAX_JOINT_LENGTH", format!("{MAX_JOINT_LENGTH:e} m")),
        ("MIN_BODY_MASS", format!("{MIN_BODY_MASS:e} kg")),
        ("MAX_BODY_MASS", format!("{MAX_BODY_MASS:e} kg")),
        ("MIN_BODY_INERTIA", format!("{MIN_BODY_INERTIA:e} kg·m²")),
        ("MAX_BODY_INERTIA", format!("{MAX_BODY_INERTIA:e} kg·m²")),
        (
            "MAX_SURFACE_COEFFICIENT",
            format!("{MAX_SURFACE_COEFFICIENT:e}"),
        ),
        ("MAX_TANGENT_SPEED", format!("{MAX_TANGENT_SPEED:e} m/s")),
        ("MAX_SPRING", format!("{MAX_SPRING:e}")),
        ("MAX_REGULAR_SIDES", MAX_REGULAR_SIDES.to_string()),
    ];
    let path = carom_bench::cases::worlds::workspace().join("docs/ranges.md");
    let page = std::fs::read_to_string(&path).expect("docs/ranges.md");
    let table: Vec<(String, String)> = page
        .split("## The bounds")
        .nth(1)
        .expect("a section of bounds")
        .split("\n## ")
        .next()
        .unwrap_or_default()
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            Some((name.to_owned(), cells.get(2)?.to_string()))
        })
        .collect();
    let names: Vec<&str> = table.iter().map(|(name, _)| name.as_str()).collect();
    let known: Vec<&str> = bounds.iter().map(|(name, _)| *name).collect();
    assert_eq!(names, known, "the page's bounds, in order");
    for ((name, written), (_, value)) in table.iter().zip(&bounds) {
        assert_eq!(written, value, "{name}");
    }
}

/// A value that is not a number (or is infinite where a finite one is needed) is refused as
/// not finite, naming it, wherever it is handed in; a finite one outside its range is refused
/// as out of range. Which of the two a caller gets does not depend on which check holds it.
#[test]
fn not_a_number_is_refused_as_not_finite_everywhere() {
    use carom::{Character, CharacterDef, JointDef, WorldSettings};
    let nan = Real::NAN;
    let settings = |edit: &dyn Fn(&mut WorldSettings)| {
        let mut settings = WorldSettings::default();
        edit(&mut settings);
        World::with_settings(settings).map(drop)
    };
    let mut world = World::new();
    let a = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)))
        .unwrap();
    let b = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)).position(vec2(2.0, 0.0)))
        .unwrap();
    let kinematic = world
        .add_body(BodyDef::kinematic(Shape::circle(0.5)).position(vec2(5.0, 0.0)))
        .unwrap();
    let mut calls: Vec<(&str, Result<(), CaromError>)> = vec![
        ("step", world.clone().step(nan)),
        ("step (infinite)", world.clone().step(Real::INFINITY)),
        ("contact hertz", settings(&|s| s.solver.contact_hertz = nan)),
        ("baumgarte", settings(&|s| s.solver.baumgarte = nan)),
        ("max rotation", settings(&|s| s.solver.max_rotation = nan)),
        (
            "max linear speed",
            settings(&|s| s.solver.max_linear_speed = nan),
        ),
    ];
    let mut add = |name, def: BodyDef| (name, world.add_body(def).map(drop));
    calls.push(add("radius", BodyDef::dynamic(Shape::circle(nan))));
    calls.push(add("half height", BodyDef::dynamic(Shape::rect(1.0, nan))));
    calls.push(add(
        "friction",
        BodyDef::dynamic(Shape::circle(0.5)).friction(nan),
    ));
    calls.push(add(
        "sweep threshold",
        BodyDef::dynamic(Shape::circle(0.5)).sweep_threshold(nan),
    ));
    let mut join = |name, def: JointDef| (name, world.add_joint(def).map(drop));
    let revolute = || JointDef::revolute(a, b, vec2(1.0, 0.0));
    calls.push(join("joint limits", revolute().limits(nan, 0.5)));
    calls.push(join("joint break force", revolute().break_force(nan)));
    calls.push(join("motor max torque", revolute().motor_drive(1.0, nan)));
    calls.push(join("spring hertz", revolute().spring(nan, 0.5)));
    calls.push((
        "kinematic move's time step",
        world
            .body_mut(kinematic)
            .unwrap()
            .move_kinematic_to(vec2(5.0, 1.0), 0.0, nan),
    ));
    calls.push((
        "character max slope",
        Character::new(CharacterDef::capsule(0.5, 0.3).max_slope(nan)).map(drop),
    ));
    let mut character =
        Character::new(CharacterDef::capsule(0.5, 0.3).position(vec2(0.0, 5.0))).unwrap();
    calls.push((
        "character time step",
        world
            .move_character(&mut character, vec2(0.1, 0.0), nan)
            .map(drop),
    ));
    for (name, result) in calls {
        match result {
            Err(CaromError::NonFinite { .. }) => {}
            other => panic!("{name}: {other:?}, expected a NonFinite error"),
        }
    }
    // A finite value out of range is the other error.
    assert!(matches!(
        world.step(-1.0),
        Err(CaromError::OutOfRange {
            name: "time step",
            ..
        })
    ));
}
