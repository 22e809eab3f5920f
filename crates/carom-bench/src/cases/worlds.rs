//! The worlds of the hard cases in `tests/stability.rs`, built once so the stability suite and
//! `carom-bench hard-cases` (which runs them in carom and in Box2D) share the same geometry.
//!
//! Every builder takes the solver to use, as the suite runs each case with every solver; the
//! effects are the case's own. Unless a builder says otherwise, gravity is `(0, -10)`.

use carom::{BodyDef, BodyHandle, Effect, Real, Shape, SolverParams, Vec2, World, vec2};
use carom_scene::SceneWorld;
use std::path::PathBuf;

/// Height of the boxes of the tiny pyramid, m.
pub const TINY_BOX_SIZE: Real = 0.05;

/// Boxes in the base of the tiny pyramid.
pub const TINY_PYRAMID_BASE: usize = 30;

/// Boxes in the column of Box2D's vertical stack with bullets.
pub const BULLET_STACK_BOXES: usize = 12;

/// The workspace root, where `demos/` is.
pub fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A demo scene with `params`' solver, keeping the scene's own substeps and contact stiffness.
///
/// # Panics
/// A scene that does not load or a solver the world refuses.
pub fn scene(name: &str, params: SolverParams) -> SceneWorld {
    let mut scene = carom_scene::load(&workspace().join(format!("demos/{name}.ron")))
        .unwrap_or_else(|e| panic!("{e}"));
    let own = *scene.world.solver();
    scene
        .world
        .update_settings(|s| {
            s.solver = SolverParams {
                substeps: own.substeps,
                contact_hertz: own.contact_hertz,
                joint_hertz: own.joint_hertz,
                ..params
            }
        })
        .unwrap();
    scene
}

/// A world with gravity (0, -10), `params`' solver and the effects given.
///
/// # Panics
/// A solver the world refuses.
pub fn world(params: SolverParams, effects: &[Effect]) -> World {
    let mut world = World::new();
    world
        .update_settings(|s| {
            s.solver = params;
            s.effects = carom::Effects::of(effects);
        })
        .unwrap();
    world
}

/// The effects of the cases where bodies rest under gravity.
const RESTING: [Effect; 3] = [Effect::Gravity, Effect::Friction, Effect::Continuous];

/// A static box `2 half_width` wide and `2 half_height` deep with its top at y = 0.
fn add_ground(world: &mut World, half_width: Real, half_height: Real) {
    world
        .add_body(
            BodyDef::static_body(Shape::rect(half_width, half_height))
                .position(vec2(0.0, -half_height)),
        )
        .unwrap();
}

/// Box2D's vertical stack: a column of `count` 1 m boxes, friction 0.3, rows shifted
/// alternately by ±0.01 m, on a ground with a wall beside it.
///
/// # Panics
/// A solver the world refuses.
pub fn vertical_stack(
    params: SolverParams,
    count: usize,
    sleeping: bool,
) -> (World, Vec<BodyHandle>) {
    let mut effects = RESTING.to_vec();
    if sleeping {
        effects.push(Effect::Sleeping);
    }
    let mut world = world(params, &effects);
    // The segment (-30, 0)-(30, 0) as a thin box with its top at y = 0, and the wall at x = 10.
    add_ground(&mut world, 30.0, 0.05);
    world
        .add_body(BodyDef::static_body(Shape::rect(0.05, 10.0)).position(vec2(10.0, 10.0)))
        .unwrap();
    let boxes = (0..count)
        .map(|i| {
            let shift = if i % 2 == 0 { -0.01 } else { 0.01 };
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(0.5, 0.5))
                        .position(vec2(shift, 0.5 + i as Real))
                        .friction(0.3),
                )
                .unwrap()
        })
        .collect();
    (world, boxes)
}

/// The 30-box column: [`vertical_stack`] of 30, taller than any the suite holds to a bar.
pub fn column_of_30(params: SolverParams, sleeping: bool) -> (World, Vec<BodyHandle>) {
    vertical_stack(params, 30, sleeping)
}

/// A 20 m box (density 1) dropped from 1 m onto two small bodies 10 m apart, on a 100 m ground
/// with its top at y = 0.
///
/// # Panics
/// A solver the world refuses.
pub fn big_box_on(params: SolverParams, small: Shape) -> World {
    let mut world = world(params, &RESTING);
    add_ground(&mut world, 50.0, 0.5);
    for x in [-5.0, 5.0] {
        world
            .add_body(BodyDef::dynamic(small.clone()).position(vec2(x, 0.5)))
            .unwrap();
    }
    world
        .add_body(BodyDef::dynamic(Shape::rect(10.0, 10.0)).position(vec2(0.0, 12.0)))
        .unwrap();
    world
}

/// The small triangle [`big_box_on`] stands on in its second variant: 1 m wide and high.
///
/// # Panics
/// Never: the triangle is valid.
pub fn small_triangle() -> Shape {
    Shape::polygon(&[vec2(-0.5, -0.5), vec2(0.5, -0.5), vec2(0.0, 0.5)]).unwrap()
}

/// A pyramid of 1 m boxes, `base` in the bottom row, on a wide static floor.
///
/// # Panics
/// A solver the world refuses.
pub fn pyramid_world(params: SolverParams, base: usize) -> World {
    let mut world = world(params, &RESTING);
    add_ground(&mut world, 40.0, 1.0);
    add_pyramid(&mut world, base, 1.0);
    world
}

/// A pyramid of square boxes `size` across (friction 0.6), `base` in the bottom row, standing
/// on y = 0 and centred on x = 0, boxes touching.
///
/// # Panics
/// A non-positive `size`.
pub fn add_pyramid(world: &mut World, base: usize, size: Real) {
    for row in 0..base {
        for column in 0..base - row {
            let x = (column as Real - (base - row - 1) as Real * 0.5) * size;
            let y = (row as Real + 0.5) * size;
            world
                .add_body(
                    BodyDef::dynamic(Shape::rect(size * 0.5, size * 0.5))
                        .position(vec2(x, y))
                        .friction(0.6),
                )
                .unwrap();
        }
    }
}

/// The tiny pyramid: [`TINY_PYRAMID_BASE`] boxes of [`TINY_BOX_SIZE`] in the base on a 10 m
/// ground with its top at y = 0.
///
/// # Panics
/// A solver the world refuses.
pub fn tiny_pyramid(params: SolverParams) -> World {
    let mut world = world(params, &RESTING);
    add_ground(&mut world, 5.0, 0.5);
    add_pyramid(&mut world, TINY_PYRAMID_BASE, TINY_BOX_SIZE);
    world
}

/// Ten 0.5 m circles spawned at one point, with friction only (no gravity).
///
/// # Panics
/// A solver the world refuses.
pub fn coincident_circles(params: SolverParams) -> (World, Vec<BodyHandle>) {
    let mut world = world(params, &[Effect::Friction]);
    let circles = (0..10)
        .map(|_| {
            world
                .add_body(BodyDef::dynamic(Shape::circle(0.5)))
                .unwrap()
        })
        .collect();
    (world, circles)
}

/// Box2D's Skinny Box course with its plank, still to be placed and launched.
///
/// # Panics
/// A solver the world refuses.
pub fn skinny_plank(params: SolverParams) -> (World, BodyHandle) {
    let mut world = world(params, &RESTING);
    super::skinny_box::add_course(&mut world);
    let plank = world.add_body(super::skinny_box::plank()).unwrap();
    (world, plank)
}

/// Box2D's vertical stack with bullets, one shot: a fresh stack of [`BULLET_STACK_BOXES`] before
/// its wall and a 0.25 m circle (density 4) at 300 m/s, the `shot`-th of ten heights.
///
/// # Panics
/// A solver the world refuses.
pub fn bullet_shot(params: SolverParams, shot: usize) -> (World, BodyHandle) {
    let (mut world, _) = vertical_stack(params, BULLET_STACK_BOXES, false);
    let height = 0.5 + shot as Real * 1.15;
    let bullet = world
        .add_body(
            BodyDef::dynamic(Shape::circle(0.25))
                .position(vec2(-26.7, height))
                .linear_velocity(vec2(300.0, 0.0))
                .density(4.0)
                .bullet(true),
        )
        .unwrap();
    (world, bullet)
}

/// A closed 20 x 20 m box with `count` random circles and convex polygons (0.05 to 5 m across,
/// density 0.1 to 100) scattered over it, overlapping as they fall.
///
/// # Panics
/// A solver the world refuses.
pub fn random_world(params: SolverParams, seed: u64, count: usize) -> World {
    let mut rng = super::Rng::new(seed);
    let mut world = world(
        params,
        &[
            Effect::Gravity,
            Effect::Friction,
            Effect::Restitution,
            Effect::Continuous,
        ],
    );
    for (center, half) in [
        (vec2(0.0, -0.5), vec2(11.0, 0.5)),
        (vec2(0.0, 20.5), vec2(11.0, 0.5)),
        (vec2(-10.5, 10.0), vec2(0.5, 11.0)),
        (vec2(10.5, 10.0), vec2(0.5, 11.0)),
    ] {
        world
            .add_body(BodyDef::static_body(Shape::rect(half.x, half.y)).position(center))
            .unwrap();
    }
    for _ in 0..count {
        let size = rng.range(0.05, 5.0);
        let shape = if rng.below(3) == 0 {
            Shape::circle(0.5 * size)
        } else {
            let points: Vec<Vec2> = (0..3 + rng.below(6))
                .map(|_| vec2(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5)) * size)
                .collect();
            Shape::hull(&points).unwrap_or_else(|_| Shape::rect(0.5 * size, 0.25 * size))
        };
        let reach = 0.5 * size.min(9.0);
        world
            .add_body(
                BodyDef::dynamic(shape)
                    .position(vec2(
                        rng.range(-10.0 + reach, 10.0 - reach),
                        rng.range(reach, 20.0 - reach),
                    ))
                    .angle(rng.range(-carom::consts::PI, carom::consts::PI))
                    .density(rng.range(0.1, 100.0))
                    .restitution(rng.range(0.0, 0.5)),
            )
            .unwrap();
    }
    world
}

/// Whether a body of a [`random_world`] centred at `position` has gone through a wall: its
/// centre is past the middle of one (the walls are 1 m thick). A body only pressed into a wall
/// is not out: a sliver 6 mm thick lying 2 mm into the floor has its centre below the floor's
/// top, yet it is held, not gone.
pub fn outside_the_box(position: Vec2) -> bool {
    position.x.abs() > 10.5 || !(-0.5..20.5).contains(&position.y)
}

/// Mass times the box's height times g: the most work gravity can do on the bodies of a
/// [`random_world`].
pub fn gravity_work(world: &World) -> f64 {
    world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| b.mass() as f64 * 10.0 * 20.0)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom::SolverKind;

    #[test]
    fn builders_make_the_bodies_the_cases_count_on() {
        let params = SolverParams::for_kind(SolverKind::SoftStep);
        let (world, boxes) = vertical_stack(params, 12, true);
        assert_eq!((world.body_count(), boxes.len()), (14, 12));
        assert!(world.effects().contains(Effect::Sleeping));
        assert_eq!(column_of_30(params, false).1.len(), 30);
        assert_eq!(big_box_on(params, small_triangle()).body_count(), 4);
        assert_eq!(pyramid_world(params, 10).body_count(), 56);
        assert_eq!(tiny_pyramid(params).body_count(), 466);
        assert_eq!(coincident_circles(params).0.body_count(), 10);
        assert_eq!(skinny_plank(params).0.body_count(), 3);
        assert_eq!(bullet_shot(params, 3).0.body_count(), 15);
        assert_eq!(random_world(params, 7, 12).body_count(), 16);
        assert_eq!(scene("card_house", params).world.solver().substeps, 8);
    }
}
