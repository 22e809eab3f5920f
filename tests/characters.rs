//! The kinematic character: slopes held and slid down, steps climbed and refused, the ground
//! followed downhill, platforms ridden, bodies pushed with a bounded force, and what it
//! touches reported. Each is driven as a game drives it: a walk velocity, gravity added to
//! the character's own vertical velocity, the move, the velocity clipped by what it touched,
//! then the world's step. And the dynamic character: a body walked by a mover joint on a
//! pogo leg, within their forces.

use carom::{
    BodyDef, BodyKind, Character, CharacterDef, CharacterMove, JointDef, QueryFilter, Real, Shape,
    Vec2, World, vec2,
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
    add_floor(&mut world);
    world
}

/// A static floor 100 m wide, its top at y = 0.
fn add_floor(world: &mut World) -> carom::BodyHandle {
    world
        .add_body(BodyDef::static_body(Shape::rect(50.0, 0.5)).position(vec2(0.0, -0.5)))
        .unwrap()
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

#[test]
fn a_conveyor_belt_carries_it_at_the_belt_s_speed() {
    // A static belt moving its top at 2 m/s to the right (clockwise round the box).
    let mut world = World::new();
    world
        .add_body(
            BodyDef::static_body(Shape::rect(20.0, 0.5))
                .position(vec2(0.0, -0.5))
                .surface(carom::Surface {
                    tangent_speed: 2.0,
                    ..carom::Surface::default()
                }),
        )
        .unwrap();
    let mut player = Player::standing_at(0.0, 0.0);
    player.step(&mut world, 0.0);
    let start = player.position().x;
    for _ in 0..60 {
        player.step(&mut world, 0.0);
    }
    let carried = player.position().x - start;
    assert!(
        (carried - 2.0).abs() < 0.02 * 2.0,
        "carried {carried} m in 1 s"
    );
    // Walking against it at its speed, it stays put.
    let before = player.position().x;
    for _ in 0..60 {
        player.step(&mut world, -2.0);
    }
    let moved = player.position().x - before;
    assert!(
        moved.abs() < 0.01,
        "moved {moved} m walking against the belt"
    );
}

// The dynamic character: a body that never turns, walked by a mover joint and held up by a
// pogo leg re-made each step on what a ray from its foot hits, as Box2D's dynamic mover is.

/// How long the leg is, and how far below the foot the ray looks for ground.
const LEG: Real = 0.9;
/// Half the walker's box, m (1 m²: 1 kg at density 1).
const WALKER_HALF: Real = 0.5;

/// A walker: its body, its mover, and its leg if it stands on something.
struct Walker {
    body: carom::BodyHandle,
    mover: carom::JointHandle,
    leg: Option<carom::JointHandle>,
    weight: Real,
}

impl Walker {
    /// A 1 kg box that never turns, its foot (the middle of its bottom) `height` above
    /// `x`, walked by a mover of at most 70 N along x against `reference`.
    fn new(world: &mut World, reference: carom::BodyHandle, x: Real, height: Real) -> Self {
        let body = world
            .add_body(
                BodyDef::dynamic(Shape::rect(WALKER_HALF, WALKER_HALF))
                    .position(vec2(x, height + WALKER_HALF))
                    .friction(0.0)
                    .fixed_rotation(true),
            )
            .unwrap();
        let mover = world
            .add_joint(JointDef::mover(
                reference,
                body,
                Vec2::zeros(),
                vec2(70.0, 0.0),
            ))
            .unwrap();
        let weight = world.body(body).unwrap().mass() * 10.0;
        Walker {
            body,
            mover,
            leg: None,
            weight,
        }
    }

    fn foot(&self, world: &World) -> Vec2 {
        world.body(self.body).unwrap().position() - vec2(0.0, WALKER_HALF)
    }

    /// Walks at `speed` for one step: the leg re-made on what is under the foot, carrying
    /// on from the last one, then the world's step.
    fn step(&mut self, world: &mut World, speed: Real) {
        let mut mover = *world.joint(self.mover).unwrap().kind();
        if let carom::JointKind::Mover(m) = &mut mover {
            m.velocity = vec2(speed, 0.0);
        }
        world
            .joint_mut(self.mover)
            .unwrap()
            .set_kind(mover)
            .unwrap();
        let previous = self.leg.take().map(|leg| {
            let joint = world.joint(leg).unwrap().clone();
            world.remove_joint(leg).unwrap();
            joint
        });
        let foot = self.foot(world);
        let ray = carom::Ray::new(foot, vec2(0.0, -2.0 * LEG));
        if let Some(hit) = world.cast_ray(&ray, QueryFilter::ALL.excluding(self.body)) {
            let mut leg = JointDef::pogo(
                hit.body,
                self.body,
                hit.point,
                foot,
                hit.normal,
                LEG,
                (100.0 * self.weight, 100.0 * self.weight),
            );
            if let Some(previous) = &previous {
                leg = leg.continue_from(previous);
            }
            self.leg = Some(world.add_joint(leg).unwrap());
        }
        world.step(DT).unwrap();
    }
}

fn world_with_gravity(solver: carom::SolverKind) -> World {
    World::with_settings(carom::WorldSettings {
        gravity: vec2(0.0, GRAVITY),
        solver: carom::SolverParams::for_kind(solver),
        ..carom::WorldSettings::default()
    })
    .unwrap()
}

#[test]
fn a_dynamic_walker_stands_on_its_leg_and_walks_at_its_speed() {
    for solver in [
        carom::SolverKind::SoftStep,
        carom::SolverKind::SequentialImpulse,
    ] {
        let mut world = world_with_gravity(solver);
        let ground = add_floor(&mut world);
        // Dropped from 0.3 m above its leg's length.
        let mut walker = Walker::new(&mut world, ground, 0.0, LEG + 0.3);
        for _ in 0..120 {
            walker.step(&mut world, 0.0);
        }
        let foot = walker.foot(&world);
        assert!(
            (foot.y - LEG).abs() < 0.01,
            "{solver:?}: the foot stands {} m up, the leg is {LEG}",
            foot.y
        );
        let leg = world.joint(walker.leg.unwrap()).unwrap();
        let push = leg.reaction_force().y;
        assert!(
            (push - walker.weight).abs() < 0.02 * walker.weight,
            "{solver:?}: the leg pushes {push} N, the walker weighs {}",
            walker.weight
        );
        // 3 m/s, reached at 70 N at most: 1 kg takes 3/70 s. After 2 s it walks at 3 m/s,
        // still on its leg, still upright.
        for _ in 0..120 {
            walker.step(&mut world, 3.0);
        }
        let body = world.body(walker.body).unwrap();
        let v = body.linear_velocity();
        assert!((v.x - 3.0).abs() < 1e-3, "{solver:?}: walks at {v}");
        assert!(
            (walker.foot(&world).y - LEG).abs() < 0.01,
            "{solver:?}: walking, the foot is {} m up",
            walker.foot(&world).y
        );
        assert_eq!(body.angle(), 0.0, "{solver:?}: a fixed rotation turned");
        assert_eq!(body.angular_velocity(), 0.0);
    }
}

#[test]
fn a_mover_drives_each_axis_within_its_force_and_leaves_the_other_free() {
    for solver in [
        carom::SolverKind::SoftStep,
        carom::SolverKind::SequentialImpulse,
    ] {
        let mut world = world_with_gravity(solver);
        let reference = world
            .add_body(BodyDef::static_body(Shape::rect(0.1, 0.1)).position(vec2(0.0, 50.0)))
            .unwrap();
        // 2 kg, driven to 3 m/s along x with at most 4 N: 2 m/s² until 1.5 s. Nothing on y:
        // it falls freely.
        let body = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 1.0)).position(vec2(0.0, 0.0)))
            .unwrap();
        let mover = world
            .add_joint(JointDef::mover(
                reference,
                body,
                vec2(3.0, 0.0),
                vec2(4.0, 0.0),
            ))
            .unwrap();
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let v = world.body(body).unwrap().linear_velocity();
        assert!((v.x - 2.0).abs() < 0.02 * 2.0, "{solver:?}: {v} after 1 s");
        assert!((v.y - GRAVITY).abs() < 1e-3, "{solver:?}: falls at {v}");
        let force = world.joint(mover).unwrap().reaction_force();
        assert!((force.x - 4.0).abs() < 1e-3, "{solver:?}: {force}");
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let v = world.body(body).unwrap().linear_velocity();
        assert!((v.x - 3.0).abs() < 1e-3, "{solver:?}: {v} after 2 s");
        // Held on y too, with at most 30 N against 20 N of weight: it rises at 5 m/s².
        world
            .joint_mut(mover)
            .unwrap()
            .set_kind(carom::JointKind::Mover(carom::MoverJoint {
                velocity: vec2(3.0, 10.0),
                max_force: vec2(4.0, 30.0),
            }))
            .unwrap();
        let before = world.body(body).unwrap().linear_velocity().y;
        for _ in 0..30 {
            world.step(DT).unwrap();
        }
        let after = world.body(body).unwrap().linear_velocity().y;
        assert!(
            ((after - before) / 0.5 - 5.0).abs() < 0.02 * 5.0,
            "{solver:?}: {before} to {after} m/s in 0.5 s"
        );
    }
}

#[test]
fn a_pogo_leg_pushes_and_pulls_no_harder_than_its_bounds() {
    let mut world = world_with_gravity(carom::SolverKind::SoftStep);
    let ground = add_floor(&mut world);
    // A leg too weak to hold the walker: half its weight. It sinks to the ground, the leg
    // pushing its most the whole way.
    let body = world
        .add_body(
            BodyDef::dynamic(Shape::rect(WALKER_HALF, WALKER_HALF))
                .position(vec2(0.0, LEG + WALKER_HALF))
                .fixed_rotation(true),
        )
        .unwrap();
    let weight = world.body(body).unwrap().mass() * 10.0;
    let leg = world
        .add_joint(JointDef::pogo(
            ground,
            body,
            vec2(0.0, 0.0),
            vec2(0.0, LEG),
            vec2(0.0, 1.0),
            LEG,
            (0.5 * weight, 0.0),
        ))
        .unwrap();
    let mut most: Real = 0.0;
    for _ in 0..30 {
        world.step(DT).unwrap();
        most = most.max(world.joint(leg).unwrap().reaction_force().y);
    }
    // Falling at g/2 for 0.5 s: 0.625 m down.
    let drop = LEG + WALKER_HALF - world.body(body).unwrap().position().y;
    assert!(
        (drop - 0.625).abs() < 0.02 * 0.625,
        "sank {drop} m in 0.5 s, expected 0.625"
    );
    assert!(most <= 0.5 * weight * 1.0001, "pushed {most} N");
    // With no pull, a walker thrown up leaves its leg behind: it rises as if the leg were
    // not there.
    world.remove_joint(leg).unwrap();
    world
        .body_mut(body)
        .unwrap()
        .set_position(vec2(0.0, LEG + WALKER_HALF))
        .unwrap();
    world
        .body_mut(body)
        .unwrap()
        .set_linear_velocity(vec2(0.0, 5.0))
        .unwrap();
    world
        .add_joint(JointDef::pogo(
            ground,
            body,
            vec2(0.0, 0.0),
            vec2(0.0, LEG),
            vec2(0.0, 1.0),
            LEG,
            (100.0 * weight, 0.0),
        ))
        .unwrap();
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let v = world.body(body).unwrap().linear_velocity().y;
    assert!((v - 0.0).abs() < 1e-3, "{v} m/s after 0.5 s up at 5 m/s");
}

#[test]
fn a_walker_falls_asleep_standing_and_goes_with_its_body() {
    let mut world = world_with_gravity(carom::SolverKind::SoftStep);
    let ground = add_floor(&mut world);
    let mut walker = Walker::new(&mut world, ground, 0.0, LEG);
    // Standing still on the same leg (not re-made), it rests and sleeps.
    walker.step(&mut world, 0.0);
    for _ in 0..240 {
        world.step(DT).unwrap();
    }
    assert!(world.body(walker.body).unwrap().is_sleeping());
    assert_eq!(world.joints_of(walker.body).len(), 2);
    world.remove_body(walker.body).unwrap();
    assert_eq!(world.joint_count(), 0);
    world.step(DT).unwrap();
}

#[test]
fn it_stays_on_the_floor_when_a_pile_falls_on_it() {
    // Dynamic bodies do not see the character: the pile falls through it onto the floor and
    // presses down on it from above, against the floor's push up. The floor holds.
    let mut world = world_with_floor();
    for x in [-1.5, 1.5] {
        world
            .add_body(BodyDef::static_body(Shape::rect(0.1, 10.0)).position(vec2(x, 10.0)))
            .unwrap();
    }
    for i in 0..40 {
        let at = vec2(-0.5 + 0.5 * (i % 3) as Real, 2.0 + 0.6 * i as Real);
        world
            .add_body(BodyDef::dynamic(Shape::rect(0.25, 0.25)).position(at))
            .unwrap();
    }
    let mut player = Player::standing_at(0.0, 0.0);
    let mut lowest: Real = 0.0;
    for _ in 0..1200 {
        player.step(&mut world, 0.0);
        lowest = lowest.min(player.feet());
    }
    // It rests the slop into the floor, as contacts do; a little more while the pile lands.
    assert!(lowest > -0.01, "its feet sank to {lowest} m");
    assert!(player.character.is_grounded());
}
