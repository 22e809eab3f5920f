//! The kinematic character: slopes held and slid down, steps climbed and refused, the ground
//! followed downhill, platforms ridden, bodies pushed with a bounded force, and what it
//! touches reported. Each is driven as a game drives it: a walk velocity, gravity added to
//! the character's own vertical velocity, the move, the velocity clipped by what it touched,
//! then the world's step.

use carom::{
    BodyDef, BodyKind, Character, CharacterDef, CharacterMove, QueryFilter, Real, Shape, Vec2,
    World, vec2,
};

const DT: Real = 1.0 / 60.0;
const GRAVITY: Real = -10.0;
const HALF_HEIGHT: Real = 0.5;
const RADIUS: Real = 0.3;

/// A game's character: its vertical velocity carried from step to step.
struct Player {
    character: Character,
    velocity: Vec2,
}

impl Player {
    fn new(def: CharacterDef) -> Self {
        Player {
            character: Character::new(def).unwrap(),
            velocity: Vec2::zeros(),
        }
    }

    fn standing_at(x: Real, ground: Real) -> Self {
        Self::new(def_at(x, ground))
    }

    /// One step: walk at `walk` m/s (off the ground, only when walking), fall, move, clip,
    /// step the world.
    fn step(&mut self, world: &mut World, walk: Real) -> CharacterMove {
        if self.character.is_grounded() || walk != 0.0 {
            self.velocity.x = walk;
        }
        self.velocity.y += GRAVITY * DT;
        let moved = world
            .move_character(&mut self.character, self.velocity * DT, DT)
            .unwrap();
        self.velocity = self.character.clip_velocity(self.velocity);
        world.step(DT).unwrap();
        moved
    }

    fn position(&self) -> Vec2 {
        self.character.position()
    }

    /// How high the bottom of its capsule is.
    fn feet(&self) -> Real {
        self.position().y - HALF_HEIGHT - RADIUS
    }
}

/// A character whose feet rest on ground at height `ground`, at `x`.
fn def_at(x: Real, ground: Real) -> CharacterDef {
    CharacterDef::capsule(HALF_HEIGHT, RADIUS).position(vec2(x, ground + HALF_HEIGHT + RADIUS))
}

fn world_with_floor() -> World {
    let mut world = World::new();
    world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap();
    world
}

/// A static triangle with corners `points` (counter-clockwise), in world coordinates.
fn add_triangle(world: &mut World, points: [Vec2; 3]) {
    // Polygons are centred on their centroid when built: the body goes there.
    let centroid = (points[0] + points[1] + points[2]) / 3.0;
    let shape = Shape::polygon(&points).unwrap();
    world
        .add_body(BodyDef::static_body(shape).position(centroid))
        .unwrap();
}

/// A static ramp rising from x = 0 at `angle` radians for 10 m of run, on the floor.
fn add_ramp(world: &mut World, angle: Real) {
    let rise = 10.0 * angle.tan();
    add_triangle(world, [vec2(0.0, 0.0), vec2(10.0, 0.0), vec2(10.0, rise)]);
}

/// Height of the ramp's surface at `x`.
fn ramp_height(angle: Real, x: Real) -> Real {
    x.clamp(0.0, 10.0) * angle.tan()
}

#[test]
fn it_stands_still_on_a_slope_it_can_climb_and_walks_up_it() {
    let angle = 30.0_f32.to_radians();
    let mut world = world_with_floor();
    add_ramp(&mut world, angle);
    // Standing on the slope, a capsule's foot touches it where the slope is tangent to its
    // bottom circle: its centre is radius / cos above the slope under its middle.
    let x = 4.0;
    let rest = |x: Real| ramp_height(angle, x) + RADIUS / angle.cos() + HALF_HEIGHT;
    let mut player =
        Player::new(CharacterDef::capsule(HALF_HEIGHT, RADIUS).position(vec2(x, rest(x) + 0.01)));
    for _ in 0..120 {
        player.step(&mut world, 0.0);
    }
    let held = player.position();
    assert!(player.character.is_grounded());
    assert!(
        (held.x - x).abs() < 1e-3,
        "slid {} m down the slope",
        x - held.x
    );
    assert!(
        (held.y - rest(x)).abs() < 0.01,
        "{} above its rest",
        held.y - rest(x)
    );

    // Walking up it, it keeps its pace across and stays on the surface.
    let speed = 3.0;
    for _ in 0..60 {
        let moved = player.step(&mut world, speed);
        assert!(moved.grounded && !moved.sliding);
    }
    let walked = player.position();
    assert!((walked.x - (held.x + speed)).abs() < 0.02, "{walked:?}");
    assert!((walked.y - rest(walked.x)).abs() < 0.01, "{walked:?}");
}

#[test]
fn it_slides_down_a_slope_too_steep_and_cannot_walk_up_it() {
    let angle = 60.0_f32.to_radians();
    let mut world = world_with_floor();
    add_ramp(&mut world, angle);
    // On the steep slope: it slides down to the floor.
    let x = 3.0;
    let on_slope = ramp_height(angle, x) + RADIUS / angle.cos() + HALF_HEIGHT;
    let mut player =
        Player::new(CharacterDef::capsule(HALF_HEIGHT, RADIUS).position(vec2(x, on_slope + 0.01)));
    let first = player.step(&mut world, 0.0);
    assert!(!first.grounded);
    let mut slid = false;
    for _ in 0..180 {
        slid |= player.step(&mut world, 0.0).sliding;
    }
    assert!(slid, "it never said it slid");
    assert!(player.character.is_grounded());
    assert!(
        player.feet().abs() < 0.01,
        "its feet are at {}",
        player.feet()
    );
    assert!(player.position().x < 0.0, "{:?}", player.position());

    // Walking into it from the floor, it gets no higher than its foot's curve reaches.
    let mut player = Player::standing_at(-2.0, 0.0);
    let mut highest: Real = 0.0;
    for _ in 0..240 {
        player.step(&mut world, 3.0);
        highest = highest.max(player.feet());
    }
    assert!(highest < 0.02, "it climbed to {highest} m");
    assert!(player.position().x < 0.0);
}

/// A floor with a box step of `height` whose face is at x = 2.
fn world_with_step(height: Real) -> World {
    let mut world = world_with_floor();
    world
        .add_body(
            BodyDef::static_body(Shape::rect(5.0, 0.5 * height)).position(vec2(7.0, 0.5 * height)),
        )
        .unwrap();
    world
}

#[test]
fn it_climbs_a_step_up_to_its_step_height_and_no_higher() {
    for (height, climbs) in [
        (0.1, true),
        (0.25, true),
        (0.29, true),
        (0.35, false),
        (0.6, false),
    ] {
        let mut world = world_with_step(height);
        let mut player = Player::standing_at(0.0, 0.0);
        let mut stepped = false;
        for _ in 0..120 {
            stepped |= player.step(&mut world, 2.0).stepped;
        }
        if climbs {
            assert!(
                player.position().x > 3.5,
                "{height} m: stuck at {:?}",
                player.position()
            );
            assert!(
                (player.feet() - height).abs() < 0.01,
                "{height} m: its feet are at {}",
                player.feet()
            );
            assert!(player.character.is_grounded());
            // Low steps are climbed as a slope is, by the rounded foot; high ones by a step.
            assert!(
                stepped || height < 0.15,
                "{height} m: climbed without a step"
            );
        } else {
            assert!(!stepped, "{height} m: stepped");
            assert!(
                player.position().x < 2.0 - RADIUS + 0.01,
                "{height} m: {:?}",
                player.position()
            );
            assert!(
                player.feet().abs() < 0.01,
                "{height} m: its feet are at {}",
                player.feet()
            );
        }
    }
}

#[test]
fn it_follows_the_ground_down_a_slope_and_a_low_step() {
    let angle = 30.0_f32.to_radians();
    let top = ramp_height(angle, 10.0);
    for snap in [true, false] {
        let mut world = world_with_floor();
        // A ramp falling to the right from its top at x = 0, and a level shelf to its left.
        add_triangle(
            &mut world,
            [vec2(0.0, 0.0), vec2(10.0, 0.0), vec2(0.0, top)],
        );
        world
            .add_body(
                BodyDef::static_body(Shape::rect(2.0, 0.5 * top)).position(vec2(-2.0, 0.5 * top)),
            )
            .unwrap();
        let def = def_at(-1.0, top).snap_distance(if snap { 0.2 } else { 0.0 });
        let mut player = Player::new(def);
        player.step(&mut world, 0.0);
        let mut airborne = 0;
        let mut gap: Real = 0.0;
        for _ in 0..150 {
            let moved = player.step(&mut world, 5.0);
            let x = player.position().x;
            if (0.5..9.5).contains(&x) {
                airborne += usize::from(!moved.grounded);
                // Vertical gap between its foot circle and the slope.
                let surface = top - x * angle.tan();
                let centre = player.position().y - HALF_HEIGHT;
                gap = gap.max(centre - RADIUS / angle.cos() - surface);
            }
        }
        if snap {
            assert_eq!(airborne, 0, "it left the slope");
            assert!(gap < 0.01, "{gap} m above the slope");
        } else {
            assert!(
                airborne > 0 && gap > 0.02,
                "without the snap it kept to the slope"
            );
        }
    }
}

#[test]
fn it_rides_moving_and_turning_platforms() {
    // A platform gliding back and forth and up and down; then one turning slowly.
    for turning in [false, true] {
        let mut world = World::new();
        let platform = world
            .add_body(
                BodyDef::new(BodyKind::Kinematic, Shape::rect(3.0, 0.25))
                    .position(vec2(0.0, -0.25)),
            )
            .unwrap();
        let mut player = Player::standing_at(0.8, 0.0);
        player.step(&mut world, 0.0);
        // Where it stands, in the platform's frame: its middle on a gliding platform, its
        // foot's contact on a turning one (an upright character's middle does not turn).
        let standing = |world: &World, player: &Player| {
            let platform = world.body(platform).unwrap();
            let at = if turning {
                player.character.ground().unwrap().point
            } else {
                player.position()
            };
            platform.local_point(at)
        };
        let start = standing(&world, &player);
        let mut worst: Real = 0.0;
        for i in 0..300 {
            let t = i as Real * DT;
            let mut body = world.body_mut(platform).unwrap();
            if turning {
                body.set_angular_velocity(0.1).unwrap();
            } else {
                body.set_linear_velocity(vec2(3.0 * (2.0 * t).cos(), 1.5 * (3.0 * t).sin()))
                    .unwrap();
            }
            let moved = player.step(&mut world, 0.0);
            assert!(moved.grounded, "step {i}: off the platform");
            worst = worst.max((standing(&world, &player) - start).norm());
        }
        assert!(
            worst < 0.01,
            "turning {turning}: drifted {worst} m on the platform"
        );
    }
}

#[test]
fn it_pushes_bodies_with_a_bounded_force() {
    let force = 200.0;
    for (mass, speed) in [(2.0, 2.0), (400.0, 2.0)] {
        let mut world = world_with_floor();
        let size = 0.5;
        let crate_body = world
            .add_body(
                BodyDef::dynamic(Shape::rect(size, size))
                    .position(vec2(1.5, size))
                    .density(mass / (4.0 * size * size)),
            )
            .unwrap();
        for collider in world.body(crate_body).unwrap().colliders().to_vec() {
            world
                .collider_mut(collider)
                .unwrap()
                .set_friction(0.0)
                .unwrap();
        }
        let ground = world.bodies().next().unwrap().handle();
        for collider in world.body(ground).unwrap().colliders().to_vec() {
            world
                .collider_mut(collider)
                .unwrap()
                .set_friction(0.0)
                .unwrap();
        }
        let mut player = Player::new(def_at(0.0, 0.0).max_push_force(force));
        let seconds = 2.0;
        let mut fastest: Real = 0.0;
        for _ in 0..(seconds / DT) as usize {
            player.step(&mut world, speed);
            fastest = fastest.max(world.body(crate_body).unwrap().linear_velocity().x);
        }
        let pushed = world.body(crate_body).unwrap().linear_velocity().x;
        if mass < 10.0 {
            // Light: it goes at the character's pace, no faster.
            assert!(fastest < speed * 1.02, "{mass} kg pushed to {fastest} m/s");
            assert!(pushed > speed * 0.9, "{mass} kg only at {pushed} m/s");
        } else {
            // Heavy: the force bounds it. Pushing starts once the character reaches it.
            let bound = force / mass * seconds;
            assert!(
                fastest <= bound * 1.001,
                "{mass} kg at {fastest} m/s, over {bound}"
            );
            assert!(
                pushed > 0.5 * bound,
                "{mass} kg at {pushed} m/s, bound {bound}"
            );
        }
    }
}

#[test]
fn it_reports_what_it_touches_and_stands_on() {
    let mut world = world_with_floor();
    let wall = world
        .add_body(BodyDef::static_body(Shape::rect(0.5, 3.0)).position(vec2(2.0, 3.0)))
        .unwrap();
    let mut player = Player::standing_at(0.0, 0.0);
    for _ in 0..90 {
        player.step(&mut world, 3.0);
    }
    let floor = world.bodies().next().unwrap().handle();
    assert_eq!(player.character.ground().map(|g| g.body), Some(floor));
    let touched: Vec<_> = player.character.touching().iter().map(|p| p.body).collect();
    assert!(
        touched.contains(&wall) && touched.contains(&floor),
        "{touched:?}"
    );
    // Against the wall, a slop into it, its walk clipped away.
    assert!((player.position().x - (1.5 - RADIUS + carom::LINEAR_SLOP)).abs() < 1e-3);
    assert_eq!(player.velocity.x, 0.0);
    // A filter that leaves the wall out lets it walk through.
    let mut ghost = Player::new(def_at(0.0, 0.0).filter(QueryFilter::ALL.excluding(wall)));
    for _ in 0..90 {
        ghost.step(&mut world, 3.0);
    }
    assert!(ghost.position().x > 4.0);
}

#[test]
fn bad_input_gets_an_error() {
    assert!(Character::new(CharacterDef::capsule(0.5, 0.004)).is_err());
    assert!(Character::new(CharacterDef::capsule(0.5, 0.3).max_slope(2.0)).is_err());
    assert!(Character::new(CharacterDef::capsule(0.5, 0.3).up(Vec2::zeros())).is_err());
    assert!(Character::new(CharacterDef::capsule(0.5, 0.3).step(-1.0, 0.1)).is_err());
    let mut world = world_with_floor();
    let mut character = Character::new(def_at(0.0, 0.0)).unwrap();
    assert!(
        world
            .move_character(&mut character, vec2(Real::NAN, 0.0), DT)
            .is_err()
    );
    assert!(
        world
            .move_character(&mut character, vec2(1.0, 0.0), 0.0)
            .is_err()
    );
    assert!(character.set_position(vec2(Real::INFINITY, 0.0)).is_err());
    assert_eq!(character.position(), vec2(0.0, HALF_HEIGHT + RADIUS));
}

#[test]
fn it_jumps_up_through_a_one_way_ledge_and_lands_on_it() {
    let mut world = world_with_floor();
    // A chain's link is solid on its right: going from x = 3 to x = -3 that is its top.
    let ledge = carom::ChainDef::open(vec![vec2(3.0, 1.5), vec2(-3.0, 1.5)]);
    world
        .add_body(BodyDef::static_chain(&ledge).unwrap())
        .unwrap();
    let mut player = Player::standing_at(0.0, 0.0);
    player.step(&mut world, 0.0);
    player.velocity.y = 7.0;
    let mut highest: Real = 0.0;
    for _ in 0..120 {
        player.step(&mut world, 0.0);
        highest = highest.max(player.feet());
    }
    // v² / 2g = 2.45 m up, past the ledge; then down onto it.
    assert!(highest > 2.0, "it rose to {highest} m");
    assert!(player.character.is_grounded());
    assert!(
        (player.feet() - 1.5).abs() < 0.01,
        "its feet are at {}",
        player.feet()
    );
}

#[test]
fn its_weight_tips_a_seesaw_it_stands_on() {
    let mut world = world_with_floor();
    let floor = world.bodies().next().unwrap().handle();
    let plank = world
        .add_body(
            BodyDef::dynamic(Shape::rect(3.0, 0.1))
                .position(vec2(0.0, 1.0))
                .density(10.0),
        )
        .unwrap();
    world
        .add_joint(carom::JointDef::revolute(floor, plank, vec2(0.0, 1.0)))
        .unwrap();
    let mut player = Player::new(def_at(2.0, 1.1).mass(80.0));
    for _ in 0..90 {
        player.step(&mut world, 0.0);
    }
    // 80 kg at 2 m against a 60 kg plank on its middle: it goes down on the character's side
    // until that end meets the floor, and the character rides it down.
    let angle = world.body(plank).unwrap().angle();
    assert!(angle < -0.3, "the plank turned to {angle} rad");
    assert!(player.character.is_grounded());
    assert!(player.feet() < 0.6, "its feet are at {}", player.feet());
    // Weighing nothing, it leaves the plank level.
    let mut world = world_with_floor();
    let plank = world
        .add_body(BodyDef::dynamic(Shape::rect(3.0, 0.1)).position(vec2(0.0, 1.0)))
        .unwrap();
    let floor = world.bodies().next().unwrap().handle();
    world
        .add_joint(carom::JointDef::revolute(floor, plank, vec2(0.0, 1.0)))
        .unwrap();
    let mut player = Player::new(def_at(2.0, 1.1).mass(0.0));
    for _ in 0..90 {
        player.step(&mut world, 0.0);
    }
    assert!(world.body(plank).unwrap().angle().abs() < 1e-3);
}
