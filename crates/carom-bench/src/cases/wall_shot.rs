//! Bullets into free bodies: a small circle fired at 300 to 1000 m/s at a thin dynamic wall,
//! light or heavy, still or moving, floating free or standing on the ground. The bullet must
//! stop at the wall's face and push it as momentum says: nothing else touches the pair in
//! flight, so with no restitution they end moving together at the velocity their momentum
//! gives.

use carom::{BodyDef, BodyHandle, Effect, Real, Shape, SolverParams, Vec2, World, vec2};

/// The bullet's radius, m.
pub const BULLET_RADIUS: Real = 0.05;
/// The bullet's density, kg/m².
pub const BULLET_DENSITY: Real = 8.0;
/// Half the wall's thickness, m: 5 cm thick.
pub const WALL_HALF_THICKNESS: Real = 0.025;
/// Half the wall's height, m.
pub const WALL_HALF_HEIGHT: Real = 1.0;
/// The worlds' speed cap, m/s: above every shot's speed.
pub const MAX_SPEED: Real = 2000.0;
/// How far before the wall's face the bullet starts, m.
const START_DISTANCE: Real = 10.0;

/// One shot: the bullet's speed and the wall it is fired at.
#[derive(Debug, Clone, Copy)]
pub struct WallShot {
    /// What the shot is, for tables.
    pub name: &'static str,
    /// The bullet's speed, along +x, m/s.
    pub speed: Real,
    /// The wall's density, kg/m²: 0.2 makes it a third of the bullet's mass, 1000 some 1600 times.
    pub wall_density: Real,
    /// The wall's velocity at the start, m/s.
    pub wall_velocity: [Real; 2],
    /// The wall stands on a static ground under gravity (and friction), rather than floating free.
    pub standing: bool,
}

/// The shots of the case.
pub const SHOTS: [WallShot; 10] = [
    shot("300 m/s, light, still", 300.0, 0.2, [0.0, 0.0]),
    shot("300 m/s, heavy, still", 300.0, 1000.0, [0.0, 0.0]),
    shot("1000 m/s, light, still", 1000.0, 0.2, [0.0, 0.0]),
    shot("1000 m/s, heavy, still", 1000.0, 1000.0, [0.0, 0.0]),
    shot(
        "1000 m/s, heavy, coming at 30 m/s",
        1000.0,
        1000.0,
        [-30.0, 0.0],
    ),
    shot(
        "1000 m/s, light, coming at 100 m/s",
        1000.0,
        0.2,
        [-100.0, 0.0],
    ),
    shot(
        "300 m/s, heavy, coming at 100 m/s",
        300.0,
        1000.0,
        [-100.0, 0.0],
    ),
    shot("600 m/s, light, going at 30 m/s", 600.0, 0.2, [30.0, 0.0]),
    shot(
        "600 m/s, heavy, sliding at 20 m/s",
        600.0,
        1000.0,
        [0.0, 20.0],
    ),
    WallShot {
        name: "1000 m/s, heavy, standing on the ground",
        speed: 1000.0,
        wall_density: 1000.0,
        wall_velocity: [0.0, 0.0],
        standing: true,
    },
];

const fn shot(
    name: &'static str,
    speed: Real,
    wall_density: Real,
    wall_velocity: [Real; 2],
) -> WallShot {
    WallShot {
        name,
        speed,
        wall_density,
        wall_velocity,
        standing: false,
    }
}

/// A shot's world, its bullet and its wall, and the masses of the two.
pub struct WallShotWorld {
    /// The world: no gravity unless the wall stands on the ground.
    pub world: World,
    /// The bullet, a bullet body with continuous collision on.
    pub bullet: BodyHandle,
    /// The wall.
    pub wall: BodyHandle,
    /// The bullet's mass, kg.
    pub bullet_mass: Real,
    /// The wall's mass, kg.
    pub wall_mass: Real,
}

impl WallShot {
    /// The shot's world. The bullet is aimed so that it meets the wall's centre height when it
    /// reaches the face (a sliding wall has moved on by then), so the push is straight.
    ///
    /// # Panics
    /// A solver the world refuses.
    pub fn world(&self, params: SolverParams) -> WallShotWorld {
        let wall_velocity = Vec2::from(self.wall_velocity);
        let effects: &[Effect] = if self.standing {
            &[Effect::Gravity, Effect::Friction, Effect::Continuous]
        } else {
            &[Effect::Friction, Effect::Continuous]
        };
        // The default speed cap (400 m/s, Box2D's) would slow the fastest bullets.
        let params = SolverParams {
            max_linear_speed: MAX_SPEED,
            ..params
        };
        let mut world = super::worlds::world(params, effects);
        let wall_center = if self.standing {
            world
                .add_body(BodyDef::static_body(Shape::rect(20.0, 0.5)).position(vec2(0.0, -0.5)))
                .unwrap();
            vec2(0.0, WALL_HALF_HEIGHT)
        } else {
            vec2(0.0, 0.0)
        };
        let wall = world
            .add_body(
                BodyDef::dynamic(Shape::rect(WALL_HALF_THICKNESS, WALL_HALF_HEIGHT))
                    .position(wall_center)
                    .linear_velocity(wall_velocity)
                    .density(self.wall_density),
            )
            .unwrap();
        // The closing speed brings the bullet to the face after `flight` seconds.
        let closing = self.speed - wall_velocity.x;
        let flight = START_DISTANCE / closing;
        let start = vec2(
            -WALL_HALF_THICKNESS - BULLET_RADIUS - START_DISTANCE + wall_velocity.x * flight,
            wall_center.y + wall_velocity.y * flight,
        );
        let bullet = world
            .add_body(
                BodyDef::dynamic(Shape::circle(BULLET_RADIUS))
                    .position(start)
                    .linear_velocity(vec2(self.speed, 0.0))
                    .density(BULLET_DENSITY)
                    .bullet(true),
            )
            .unwrap();
        let mass = |body| world.body(body).unwrap().mass();
        let (bullet_mass, wall_mass) = (mass(bullet), mass(wall));
        WallShotWorld {
            world,
            bullet,
            wall,
            bullet_mass,
            wall_mass,
        }
    }

    /// The velocity along x the bullet and the free wall share once the bullet has stopped
    /// against it: their momentum along x over their mass. (Friction on the face acts along y;
    /// a standing wall also has the ground's friction, so this holds only for free walls.)
    pub fn shared_velocity(&self, bullet_mass: Real, wall_mass: Real) -> f64 {
        let (mb, mw) = (f64::from(bullet_mass), f64::from(wall_mass));
        (mb * f64::from(self.speed) + mw * f64::from(self.wall_velocity[0])) / (mb + mw)
    }
}

/// How deep the bullet at `bullet` is into the wall at `wall` turned by `wall_angle`, along
/// the wall's normal, m: zero while it is clear of the face, and more than the wall's
/// thickness once it has passed through.
pub fn depth(bullet: Vec2, wall: Vec2, wall_angle: Real) -> f64 {
    let (sin, cos) = wall_angle.sin_cos();
    let d = bullet - wall;
    // The bullet's centre in the wall's frame.
    let (x, y) = (cos * d.x + sin * d.y, -sin * d.x + cos * d.y);
    if y.abs() > WALL_HALF_HEIGHT + BULLET_RADIUS {
        return 0.0;
    }
    f64::from(BULLET_RADIUS + WALL_HALF_THICKNESS + x).max(0.0)
}
