//! Surfaces against their analytic answers: a ball slowed by rolling resistance stops where
//! its energy runs out and rests on a slope only as steep as the resistance allows, a box on
//! a belt is carried up to the belt's speed, the world's mixers decide friction and bounce
//! from material ids, and each link of a chain has its own surface. Every figure is checked
//! with both solvers that have friction.

use carom::{
    BodyDef, BodyHandle, CaromError, ChainDef, Real, Shape, SolverKind, SolverParams, Surface,
    World, WorldSettings, vec2,
};

const DT: Real = 1.0 / 60.0;
const G: Real = 10.0;
const SOLVERS: [SolverKind; 2] = [SolverKind::SoftStep, SolverKind::SequentialImpulse];

/// A world with gravity `G` tilted by `tilt` radians (a slope of that angle, seen from the
/// slope: down-slope is +x) and a level floor whose top is at y = 0.
fn world_on_slope(kind: SolverKind, tilt: Real, floor: Surface) -> World {
    let mut world = World::with_settings(WorldSettings {
        solver: SolverParams::for_kind(kind),
        gravity: vec2(G * tilt.sin(), -G * tilt.cos()),
        ..WorldSettings::default()
    })
    .unwrap();
    world
        .add_body(
            BodyDef::static_body(Shape::rect(100.0, 0.5))
                .position(vec2(0.0, -0.5))
                .surface(floor),
        )
        .unwrap();
    world
}

/// A ball of radius 0.5 resting on the floor at x = 0, rolling at `speed` (no slip).
fn add_ball(world: &mut World, speed: Real, surface: Surface) -> BodyHandle {
    let radius = 0.5;
    world
        .add_body(
            BodyDef::dynamic(Shape::circle(radius))
                .position(vec2(0.0, radius))
                .linear_velocity(vec2(speed, 0.0))
                .angular_velocity(-speed / radius)
                .surface(surface),
        )
        .unwrap()
}

fn rolling(resistance: Real) -> Surface {
    Surface {
        rolling_resistance: resistance,
        ..Surface::default()
    }
}

#[test]
fn rolling_resistance_stops_a_ball_where_its_energy_runs_out() {
    // A disc's kinetic energy is (3/4) m v²; the resisting torque c R m g turns it into work
    // over a distance d = (3/4) v² / (c g).
    let (speed, c) = (3.0, 0.2);
    let expected = 0.75 * speed * speed / (c * G);
    for kind in SOLVERS {
        let mut world = world_on_slope(kind, 0.0, Surface::default());
        let ball = add_ball(&mut world, speed, rolling(c));
        let mut steps = 0;
        while world.body(ball).unwrap().linear_velocity().x > 1e-3 && steps < 600 {
            world.step(DT).unwrap();
            steps += 1;
        }
        let travelled = world.body(ball).unwrap().position().x;
        let error = (travelled - expected).abs() / expected;
        assert!(
            error < 0.02,
            "{kind:?}: stopped after {travelled} m, energy says {expected} m"
        );
        // And it stays stopped.
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        assert!((world.body(ball).unwrap().position().x - travelled).abs() < 1e-3);
    }
}

#[test]
fn rolling_resistance_holds_a_ball_on_a_slope_up_to_its_angle() {
    let c: Real = 0.2;
    for kind in SOLVERS {
        // Gentler than atan(c): it stays.
        let gentle = (0.75 * c).atan();
        let mut world = world_on_slope(kind, gentle, Surface::default());
        let ball = add_ball(&mut world, 0.0, rolling(c));
        for _ in 0..120 {
            world.step(DT).unwrap();
        }
        let crept = world.body(ball).unwrap().position().x;
        assert!(
            crept.abs() < 1e-3,
            "{kind:?}: crept {crept} m down the slope"
        );

        // Steeper: it rolls down at a = (2/3) g (sin θ - c cos θ).
        let steep = (1.5 * c).atan();
        let mut world = world_on_slope(kind, steep, Surface::default());
        let ball = add_ball(&mut world, 0.0, rolling(c));
        let seconds = 2.0;
        for _ in 0..(seconds / DT).round() as usize {
            world.step(DT).unwrap();
        }
        let a = 2.0 / 3.0 * G * (steep.sin() - c * steep.cos());
        let expected = 0.5 * a * seconds * seconds;
        let rolled = world.body(ball).unwrap().position().x;
        let error = (rolled - expected).abs() / expected;
        assert!(
            error < 0.02,
            "{kind:?}: rolled {rolled} m in {seconds} s, expected {expected} m"
        );
    }
}

#[test]
fn a_belt_carries_a_box_up_to_its_speed() {
    let speed = 2.0;
    for kind in SOLVERS {
        let belt = Surface {
            tangent_speed: speed,
            ..Surface::default()
        };
        let mut world = world_on_slope(kind, 0.0, belt);
        let crate_body = world
            .add_body(BodyDef::dynamic(Shape::rect(0.25, 0.25)).position(vec2(0.0, 0.25)))
            .unwrap();
        // Friction accelerates it at μ g (μ = 0.6 for both) until it moves with the belt.
        let mut history = Vec::new();
        for _ in 0..90 {
            world.step(DT).unwrap();
            history.push(world.body(crate_body).unwrap().linear_velocity().x);
        }
        let early = history[11]; // after 0.2 s
        let expected_early = 0.6 * G * 0.2;
        assert!(
            (early - expected_early).abs() / expected_early < 0.02,
            "{kind:?}: {early} m/s after 0.2 s, μ g t = {expected_early}"
        );
        let last = *history.last().unwrap();
        assert!(
            (last - speed).abs() / speed < 0.02,
            "{kind:?}: {last} m/s on a {speed} m/s belt"
        );
        assert!(
            history.iter().all(|&v| v <= speed * 1.02),
            "{kind:?}: overshot"
        );
    }
}

const ICE: u64 = 7;
const RUBBER: u64 = 9;

fn ice_mixer(fa: Real, a: u64, fb: Real, b: u64) -> Real {
    if a == ICE || b == ICE {
        0.05
    } else {
        (fa * fb).sqrt()
    }
}

fn rubber_mixer(ra: Real, a: u64, rb: Real, b: u64) -> Real {
    if a == RUBBER && b == RUBBER {
        0.8
    } else {
        ra.max(rb)
    }
}

#[test]
fn the_worlds_mixers_decide_friction_and_bounce_from_material_ids() {
    for kind in SOLVERS {
        let ice = Surface {
            material: ICE,
            ..Surface::default()
        };
        let mut world = world_on_slope(kind, 0.0, ice);
        world.set_friction_mixer(Some(ice_mixer));
        let sliding = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.25, 0.25))
                    .position(vec2(0.0, 0.25))
                    .linear_velocity(vec2(2.0, 0.0)),
            )
            .unwrap();
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        // Slowed at 0.05 g for a second, not the default 0.6 g.
        let v = world.body(sliding).unwrap().linear_velocity().x;
        let expected = 2.0 - 0.05 * G;
        assert!((v - expected).abs() / expected < 0.02, "{kind:?}: {v} m/s");
        let contact = world
            .contacts()
            .find(|c| c.body_a() == sliding || c.body_b() == sliding)
            .unwrap();
        assert_eq!(contact.friction(), 0.05);
        // Taken away, the default mix comes back at once: it stops within the next second.
        world.set_friction_mixer(None);
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        assert!(world.body(sliding).unwrap().linear_velocity().x.abs() < 1e-3);

        // Two rubber surfaces bounce with 0.8, though neither has any restitution alone:
        // exactly as two surfaces of restitution 0.8 do, and unlike two of none.
        let rubber = Surface {
            material: RUBBER,
            ..Surface::default()
        };
        let bouncy = Surface {
            restitution: 0.8,
            ..Surface::default()
        };
        let peak = |floor: Surface, ball: Surface, mixer: Option<carom::MaterialMixer>| {
            let mut world = world_on_slope(kind, 0.0, floor);
            world.set_restitution_mixer(mixer);
            let ball = world
                .add_body(
                    BodyDef::dynamic(Shape::circle(0.25))
                        .position(vec2(0.0, 2.25))
                        .surface(ball),
                )
                .unwrap();
            let (mut peak, mut bounced): (Real, bool) = (0.0, false);
            for _ in 0..120 {
                world.step(DT).unwrap();
                let body = world.body(ball).unwrap();
                bounced |= body.linear_velocity().y > 0.0;
                if bounced {
                    peak = peak.max(body.position().y - 0.25);
                }
            }
            peak
        };
        let mixed = peak(rubber, rubber, Some(rubber_mixer));
        assert_eq!(mixed, peak(bouncy, bouncy, None), "{kind:?}");
        assert!(mixed > 1.0, "{kind:?}: bounced to {mixed} m");
        assert!(peak(rubber, rubber, None) < 0.05, "{kind:?}");
    }
}

#[test]
fn each_link_of_a_chain_has_its_own_surface() {
    for kind in SOLVERS {
        let mut world = World::with_settings(WorldSettings {
            solver: SolverParams::for_kind(kind),
            ..WorldSettings::default()
        })
        .unwrap();
        // Ground from right to left (solid below): the first link is ice, the second a belt
        // carrying what is on it to the left (along the chain's order: negative speed).
        let ice = Surface {
            friction: 0.0,
            ..Surface::default()
        };
        let belt = Surface {
            tangent_speed: -1.5,
            ..Surface::default()
        };
        let points = vec![vec2(10.0, 0.0), vec2(0.0, 0.0), vec2(-10.0, 0.0)];
        let ground = ChainDef::open(points.clone()).link_surfaces(vec![ice, belt]);
        world
            .add_body(BodyDef::static_chain(&ground).unwrap())
            .unwrap();
        let on_ice = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.25, 0.25))
                    .position(vec2(5.0, 0.25))
                    .linear_velocity(vec2(1.0, 0.0)),
            )
            .unwrap();
        let on_belt = world
            .add_body(BodyDef::dynamic(Shape::rect(0.25, 0.25)).position(vec2(-5.0, 0.25)))
            .unwrap();
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let slid = world.body(on_ice).unwrap().linear_velocity().x;
        assert!((slid - 1.0).abs() < 1e-3, "{kind:?}: on ice at {slid} m/s");
        let carried = world.body(on_belt).unwrap().linear_velocity().x;
        assert!(
            (carried + 1.5).abs() < 0.03,
            "{kind:?}: on the belt at {carried} m/s"
        );

        let wrong = ChainDef::open(points).link_surfaces(vec![ice, belt, ice]);
        assert_eq!(
            BodyDef::static_chain(&wrong).map(|_| ()),
            Err(CaromError::ChainSurfaces { links: 2, count: 3 })
        );
    }
}

#[test]
fn bad_surfaces_get_an_error() {
    let mut world = World::new();
    let bad = [
        Surface {
            rolling_resistance: -0.1,
            ..Surface::default()
        },
        Surface {
            tangent_speed: Real::NAN,
            ..Surface::default()
        },
        Surface {
            friction: Real::INFINITY,
            ..Surface::default()
        },
    ];
    for surface in bad {
        assert!(
            world
                .add_body(BodyDef::dynamic(Shape::circle(0.5)).surface(surface))
                .is_err(),
            "{surface:?}"
        );
    }
    let ball = world
        .add_body(BodyDef::dynamic(Shape::circle(0.5)))
        .unwrap();
    let collider = world.body(ball).unwrap().colliders()[0];
    let mut collider = world.collider_mut(collider).unwrap();
    assert!(collider.set_rolling_resistance(-1.0).is_err());
    assert!(collider.set_tangent_speed(Real::INFINITY).is_err());
    assert_eq!(collider.surface().rolling_resistance, 0.0);
    collider.set_tangent_speed(3.0).unwrap();
    assert_eq!(collider.surface().tangent_speed, 3.0);
}
