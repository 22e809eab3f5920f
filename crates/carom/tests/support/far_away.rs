//! The same small worlds anywhere in the plane: a pyramid of boxes settling on its ground,
//! and a character walking over a floor, a ramp and a step. Run beside the origin and far
//! from it, they show what distance costs in precision.

use carom::{BodyDef, BodyKind, Character, CharacterDef, Real, Shape, Vec2, World, vec2};

/// The step, s.
pub const DT: Real = 1.0 / 60.0;

/// What a pyramid did, measured from where it stands.
pub struct PyramidRun {
    /// Every box's position at the end, less the pyramid's place.
    pub positions: Vec<Vec2>,
    /// How far the top box moved from where it started, m.
    pub top_drift: Real,
    /// The deepest overlap of any step, m.
    pub deepest: Real,
    /// The time the steps took, s.
    pub seconds: f64,
}

/// A pyramid of `count` one-metre boxes in its base, density 1 and friction 0.6 (Box2D's
/// benchmark's), its base's middle at `at` on a ground box 2 m thick, stepped `steps` times
/// with sleeping off.
pub fn pyramid(at: Vec2, count: usize, steps: usize) -> PyramidRun {
    let mut world = World::new();
    world
        .update_settings(|s| s.effects.set(carom::Effect::Sleeping, false))
        .unwrap();
    let width = count as Real + 10.0;
    world
        .add_body(BodyDef::static_body(Shape::rect(width, 1.0)).position(at + vec2(0.0, -1.0)))
        .unwrap();
    let mut top = None;
    for row in 0..count {
        for column in 0..count - row {
            let x = column as Real - (count - 1 - row) as Real * 0.5;
            let y = row as Real + 0.5;
            let body = world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(at + vec2(x, y))
                        .friction(0.6),
                )
                .unwrap();
            top = Some(body);
        }
    }
    let top = top.expect("a pyramid has a top");
    let start = world.body(top).unwrap().position();
    let mut deepest: Real = 0.0;
    let clock = std::time::Instant::now();
    for _ in 0..steps {
        world.step(DT).unwrap();
        deepest = deepest.max(world.stats().max_penetration);
    }
    let seconds = clock.elapsed().as_secs_f64();
    let positions = world
        .bodies()
        .filter(|b| b.kind() == BodyKind::Dynamic)
        .map(|b| b.position() - at)
        .collect();
    PyramidRun {
        positions,
        top_drift: (world.body(top).unwrap().position() - start).norm(),
        deepest,
        seconds,
    }
}

/// The path of a character, less `at`, walking right at 3 m/s for `steps` steps from `at`
/// over a floor, up a 20° ramp, along its top and down a 0.2 m step, under gravity of its
/// own (10 m/s²), as a game drives it.
pub fn walk(at: Vec2, steps: usize) -> Vec<Vec2> {
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(40.0, 0.5)).position(at + vec2(10.0, -0.5)))
        .unwrap();
    // A ramp rising 20° from x = 3 to x = 6, a plateau to x = 9, then a step down 0.2 m to
    // x = 13 and a drop to the floor. (A polygon is centred on its centroid: each body stands
    // there.)
    let rise = 3.0 * (20.0 as Real).to_radians().tan();
    let centroid = vec2(5.0, rise / 3.0);
    let ramp = [vec2(3.0, 0.0), vec2(6.0, 0.0), vec2(6.0, rise)].map(|p| p - centroid);
    let blocks = [
        (Shape::polygon(&ramp).unwrap(), centroid),
        (Shape::rect(1.5, 0.5 * rise), vec2(7.5, 0.5 * rise)),
        (
            Shape::rect(2.0, 0.5 * (rise - 0.2)),
            vec2(11.0, 0.5 * (rise - 0.2)),
        ),
    ];
    for (shape, place) in blocks {
        world
            .add_body(BodyDef::static_body(shape).position(at + place))
            .unwrap();
    }
    let mut hero =
        Character::new(CharacterDef::capsule(0.5, 0.3).position(at + vec2(0.0, 0.8))).unwrap();
    let mut velocity = Vec2::zeros();
    let mut path = Vec::with_capacity(steps);
    for _ in 0..steps {
        velocity.x = 3.0;
        velocity.y -= 10.0 * DT;
        world.move_character(&mut hero, velocity * DT, DT).unwrap();
        velocity = hero.clip_velocity(velocity);
        world.step(DT).unwrap();
        path.push(hero.position() - at);
    }
    path
}

/// The largest distance between matching points of two lists, m.
pub fn widest_gap(a: &[Vec2], b: &[Vec2]) -> Real {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, Real::max)
}
