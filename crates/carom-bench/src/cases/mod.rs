//! The worlds and measures the stability suite (`tests/stability.rs`) and `carom-bench` share:
//! the hard cases' worlds ([`worlds`]), what joint scenes are measured by
//! ([`joint_measures`]), a seeded random number generator, Box2D's Skinny Box course and a
//! compound body. They use only the core and the scene crate, so a suite that uses them builds
//! without the peers (`carom-bench` with default features off).

pub mod joint_measures;
pub mod wall_shot;
pub mod worlds;

use carom::{BodyDef, ColliderDef, Real, Shape, World, vec2};

/// A small deterministic random number generator (xorshift64*), so every suite sees the same
/// "random" worlds on every machine without pulling in a dependency.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed (any value; zero is remapped).
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// A uniform float in `[lo, hi)`.
    pub fn range(&mut self, lo: Real, hi: Real) -> Real {
        let unit = (self.next_u64() >> 40) as Real / (1u64 << 24) as Real;
        lo + (hi - lo) * unit
    }

    /// A uniform integer in `[0, n)`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// Box2D's Skinny Box course, shared by the continuous-collision and stability suites and the
/// hard cases: a 4 x 0.1 m plank dropped fast and spinning onto a thin floor beside a thin post.
pub mod skinny_box {
    use carom::{BodyDef, Real, Shape, Vec2, World, vec2};

    /// The post's centre line, x (m).
    pub const POST_X: Real = 1.0;
    /// The post's top, y (m).
    pub const POST_TOP: Real = 2.0;

    /// Adds the course: the "segment", a 0.02 m thick static floor with its top at y = 0, long
    /// enough that a plank thrown off the post at 50 m/s still lands on it within a second, and
    /// a 0.2 x 2 m post standing on it at x = 1.
    pub fn add_course(world: &mut World) {
        world
            .add_body(BodyDef::static_body(Shape::rect(200.0, 0.01)).position(vec2(0.0, -0.01)))
            .unwrap();
        world
            .add_body(
                BodyDef::static_body(Shape::rect(0.1, 1.0)).position(vec2(POST_X, 0.5 * POST_TOP)),
            )
            .unwrap();
    }

    /// The plank (friction 0.9), still to be placed and launched.
    pub fn plank() -> BodyDef {
        BodyDef::dynamic(Shape::rect(2.0, 0.05)).friction(0.9)
    }

    /// Whether the plank's centre, moving from `before` to `after` in one step, passed through
    /// the post: it may cross the post's centre line only above the top (going over the top
    /// corner and sliding down the far side is fine); lower, the centre was inside the post.
    pub fn through_post(before: Vec2, after: Vec2) -> bool {
        if (before.x < POST_X) == (after.x < POST_X) {
            return false;
        }
        let along = (POST_X - before.x) / (after.x - before.x);
        before.y + (after.y - before.y) * along < POST_TOP
    }
}

/// A world of one dynamic body of three colliders: Box2D's compound triangles (its compounds
/// benchmark), each placed at its centroid, and a box turned by 0.4 rad, denser and
/// slipperier than the body.
///
/// # Panics
/// Never: the shapes are valid.
pub fn compound_body() -> World {
    let triangle = |points: [(Real, Real); 3]| {
        let points = points.map(|(x, y)| vec2(x, y));
        let centroid = (points[0] + points[1] + points[2]) / 3.0;
        ColliderDef::new(Shape::polygon(&points).expect("a triangle")).offset(centroid)
    };
    let mut def = BodyDef::dynamic(Shape::circle(1.0))
        .position(vec2(3.0, 4.0))
        .angle(0.2)
        .friction(0.5);
    def.colliders = vec![
        triangle([(-1.0, 0.0), (0.5, 1.0), (0.0, 2.0)]),
        triangle([(1.0, 0.0), (-0.5, 1.0), (0.0, 2.0)]),
        ColliderDef::new(Shape::rect(0.5, 0.1))
            .offset(vec2(0.0, -0.5))
            .angle(0.4)
            .density(3.0)
            .friction(0.2),
    ];
    let mut world = World::new();
    world.add_body(def).expect("a valid body");
    world
}

#[cfg(test)]
mod tests {
    use super::Rng;

    #[test]
    fn rng_is_deterministic_and_in_range() {
        let (mut a, mut b) = (Rng::new(7), Rng::new(7));
        for _ in 0..1000 {
            let x = a.range(-2.0, 3.0);
            assert_eq!(x, b.range(-2.0, 3.0));
            assert!((-2.0..3.0).contains(&x));
            assert!(a.below(5) < 5);
            b.below(5);
        }
    }
}
