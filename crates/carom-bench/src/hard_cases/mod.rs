//! The hard cases of `tests/stability.rs`, run in carom and in Box2D and measured the same way.
//!
//! Each case builds its carom world with the builders of [`crate::cases::worlds`] (the
//! geometry the stability suite uses) and soft step at its defaults (4 substeps, 30 Hz contacts,
//! damping ratio 10, push speed 3 m/s, which are Box2D's); Box2D runs the copy
//! [`Box2dWorld::from_carom`] makes of it. Every measure is written once, against
//! [`CaseWorld`], which both engines implement, so a figure means the same in both columns.
//! Demo scenes (`demos/*.ron`) are loaded with `carom_scene::load` and stepped at 1/60 s; none
//! of the scenes used has events, and scene events would not be replayed in Box2D anyway.

use std::time::{Duration, Instant};

use crate::cases::skinny_box;
use crate::cases::{wall_shot, worlds};
use carom::{BodyHandle, BodyKind, Effect, Real, SolverKind, SolverParams, World, vec2};

use crate::box2d_world::Box2dWorld;

#[cfg(feature = "sweep")]
pub mod table;

/// Time step of every case, s.
pub const DT: Real = 1.0 / 60.0;

/// Steps of the full soak: one simulated hour.
const SOAK_STEPS: usize = 216_000;

/// Steps of the soak with `--quick`: one simulated minute.
const QUICK_SOAK_STEPS: usize = 3_600;

/// Steps of each wall shot: half a second, long after the bullet has met its wall.
const WALL_SHOT_STEPS: usize = 30;

/// Random worlds measured (each 2000 steps).
const RANDOM_WORLDS: usize = 4;

type Res<T> = Result<T, String>;

/// What the hard cases read from and do to an engine's world. Bodies are numbered in carom's
/// dense order (`World::bodies()`), which [`Box2dWorld`] keeps.
pub trait CaseWorld {
    /// Advances the world by `dt` seconds.
    ///
    /// # Errors
    /// The engine refused the step.
    fn advance(&mut self, dt: Real) -> Res<()>;
    /// Number of bodies, static ones included.
    fn body_total(&self) -> usize;
    /// Whether body `i` is dynamic.
    fn is_dynamic(&self, i: usize) -> bool;
    /// Position (centre of mass) of body `i`.
    ///
    /// # Errors
    /// The engine no longer holds the body.
    fn body_position(&mut self, i: usize) -> Res<[f32; 2]>;
    /// Angle of body `i`, rad.
    ///
    /// # Errors
    /// The engine no longer holds the body.
    fn body_angle(&mut self, i: usize) -> Res<f32>;
    /// Linear and angular velocity of body `i`.
    ///
    /// # Errors
    /// The engine no longer holds the body.
    fn body_velocity(&mut self, i: usize) -> Res<([f32; 2], f32)>;
    /// Tight bounding box `(min, max)` of body `i`'s shape.
    ///
    /// # Errors
    /// The engine no longer holds the body.
    fn body_aabb(&mut self, i: usize) -> Res<([f32; 2], [f32; 2])>;
    /// Whether body `i` is asleep.
    ///
    /// # Errors
    /// The engine no longer holds the body.
    fn is_asleep(&mut self, i: usize) -> Res<bool>;
    /// Kinetic energy of the awake moving bodies, J.
    ///
    /// # Errors
    /// The engine no longer holds a body.
    fn total_kinetic_energy(&mut self) -> Res<f64>;
    /// The deepest overlap among the contacts the last step built, m.
    ///
    /// # Errors
    /// The engine no longer holds a body.
    fn deepest_penetration(&mut self) -> Res<f64>;
    /// Puts body `i` at `position` and `angle` with the velocities given.
    ///
    /// # Errors
    /// A non-finite value, or the engine no longer holds the body.
    fn relaunch(
        &mut self,
        i: usize,
        position: [f32; 2],
        angle: f32,
        linear: [f32; 2],
        angular: f32,
    ) -> Res<()>;
}

fn nth(world: &World, i: usize) -> Res<&carom::Body> {
    world.bodies().nth(i).ok_or_else(|| format!("no body {i}"))
}

impl CaseWorld for World {
    fn advance(&mut self, dt: Real) -> Res<()> {
        self.step(dt).map_err(|e| e.to_string())
    }

    fn body_total(&self) -> usize {
        self.body_count()
    }

    fn is_dynamic(&self, i: usize) -> bool {
        self.bodies().nth(i).is_some_and(|b| b.is_dynamic())
    }

    fn body_position(&mut self, i: usize) -> Res<[f32; 2]> {
        let p = nth(self, i)?.position();
        Ok([p.x, p.y])
    }

    fn body_angle(&mut self, i: usize) -> Res<f32> {
        Ok(nth(self, i)?.angle())
    }

    fn body_velocity(&mut self, i: usize) -> Res<([f32; 2], f32)> {
        let b = nth(self, i)?;
        let v = b.linear_velocity();
        Ok(([v.x, v.y], b.angular_velocity()))
    }

    fn body_aabb(&mut self, i: usize) -> Res<([f32; 2], [f32; 2])> {
        let a = nth(self, i)?.aabb();
        Ok(([a.min.x, a.min.y], [a.max.x, a.max.y]))
    }

    fn is_asleep(&mut self, i: usize) -> Res<bool> {
        Ok(nth(self, i)?.is_sleeping())
    }

    fn total_kinetic_energy(&mut self) -> Res<f64> {
        Ok(f64::from(self.stats().kinetic_energy))
    }

    fn deepest_penetration(&mut self) -> Res<f64> {
        Ok(f64::from(self.stats().max_penetration))
    }

    fn relaunch(
        &mut self,
        i: usize,
        position: [f32; 2],
        angle: f32,
        linear: [f32; 2],
        angular: f32,
    ) -> Res<()> {
        let handle = nth(self, i)?.handle();
        let mut body = self.body_mut(handle).ok_or("body vanished")?;
        let e = |e: carom::CaromError| e.to_string();
        body.set_position(vec2(position[0], position[1]))
            .map_err(e)?;
        body.set_angle(angle).map_err(e)?;
        body.set_linear_velocity(vec2(linear[0], linear[1]))
            .map_err(e)?;
        body.set_angular_velocity(angular).map_err(e)
    }
}

impl CaseWorld for Box2dWorld {
    fn advance(&mut self, dt: Real) -> Res<()> {
        self.step(dt)
    }

    fn body_total(&self) -> usize {
        self.body_count()
    }

    fn is_dynamic(&self, i: usize) -> bool {
        self.kind(i) == BodyKind::Dynamic
    }

    fn body_position(&mut self, i: usize) -> Res<[f32; 2]> {
        self.position(i)
    }

    fn body_angle(&mut self, i: usize) -> Res<f32> {
        self.angle(i)
    }

    fn body_velocity(&mut self, i: usize) -> Res<([f32; 2], f32)> {
        Ok((self.linear_velocity(i)?, self.angular_velocity(i)?))
    }

    fn body_aabb(&mut self, i: usize) -> Res<([f32; 2], [f32; 2])> {
        self.aabb(i)
    }

    fn is_asleep(&mut self, i: usize) -> Res<bool> {
        Ok(!self.is_awake(i)?)
    }

    fn total_kinetic_energy(&mut self) -> Res<f64> {
        self.kinetic_energy()
    }

    fn deepest_penetration(&mut self) -> Res<f64> {
        Ok(f64::from(self.max_penetration()?))
    }

    fn relaunch(
        &mut self,
        i: usize,
        position: [f32; 2],
        angle: f32,
        linear: [f32; 2],
        angular: f32,
    ) -> Res<()> {
        self.set_pose(i, position, angle)?;
        self.set_velocity(i, linear, angular)
    }
}

/// The engines a case runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// carom, soft step at its defaults.
    Carom,
    /// Box2D v3, through [`Box2dWorld::from_carom`].
    Box2d,
}

/// A figure's bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bar {
    /// Recorded only.
    None,
    /// Met when the figure is below the limit.
    Below(f64),
    /// Met when the figure is at most the limit.
    AtMost(f64),
}

impl Bar {
    /// Whether `value` meets the bar (NaN never does).
    pub fn met(self, value: f64) -> bool {
        match self {
            Bar::None => true,
            Bar::Below(limit) => value < limit,
            Bar::AtMost(limit) => value <= limit,
        }
    }

    fn label(self) -> String {
        // An f32 slop widened to f64 prints its rounding; show the limit as written.
        let round = |x: f64| (x * 1e6).round() / 1e6;
        match self {
            Bar::None => "-".into(),
            Bar::Below(limit) => format!("< {}", round(limit)),
            Bar::AtMost(limit) => format!("≤ {}", round(limit)),
        }
    }
}

/// One measure of one case in one engine.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// What is measured, with its unit.
    pub measure: String,
    /// Its bar.
    pub bar: Bar,
    /// The value (infinite for "never").
    pub value: f64,
}

/// What one case measured in one engine.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outcome {
    /// The figures, in table order.
    pub figures: Vec<Figure>,
    /// True when a body's position or velocity stopped being finite.
    pub nan: bool,
    /// Wall time of the case.
    pub time: Duration,
}

impl Outcome {
    fn figure(&mut self, measure: &str, value: f64) {
        self.bar(measure, Bar::None, value);
    }

    fn bar(&mut self, measure: &str, bar: Bar, value: f64) {
        self.figures.push(Figure {
            measure: measure.into(),
            bar,
            value,
        });
    }

    /// Notes any body whose position or velocity is no longer finite.
    fn check_finite(&mut self, w: &mut dyn CaseWorld) -> Res<()> {
        for i in 0..w.body_total() {
            let p = w.body_position(i)?;
            let (v, omega) = w.body_velocity(i)?;
            let finite = p.iter().chain(&v).all(|x| x.is_finite()) && omega.is_finite();
            self.nan |= !finite;
        }
        Ok(())
    }
}

/// Options of a run of the hard cases.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Options {
    /// Soak one simulated minute instead of an hour.
    pub quick: bool,
    /// carom's solver (soft step, Box2D's, by default); Box2D is always itself.
    pub solver: SolverKind,
    /// carom's joint cases with `SolverParams::direct_joints` on (Box2D has no such option:
    /// its side is as it always is).
    pub direct_joints: bool,
    /// carom with `SolverParams::shock_propagation` on, in every case.
    pub shock_propagation: bool,
}

/// A hard case: its name (for `--case`), its title in the table, and how to run it.
pub struct Case {
    /// Short name, as `tests/stability.rs` writes its table (`target/stability/NAME.md`).
    pub name: &'static str,
    /// Title in the table.
    pub title: &'static str,
    run: fn(Side, Options, &mut Outcome) -> Res<()>,
}

impl Case {
    /// Runs the case in `engine`.
    ///
    /// # Errors
    /// A world the engine could not build or step; the figures so far are lost.
    pub fn run(&self, engine: Engine, options: Options) -> Res<Outcome> {
        let mut outcome = Outcome::default();
        let started = Instant::now();
        (self.run)(Side { engine, options }, options, &mut outcome)?;
        outcome.time = started.elapsed();
        Ok(outcome)
    }

    /// Whether the case is one of joints, which `Options::direct_joints` changes.
    pub fn has_joints(&self) -> bool {
        JOINT_CASES.contains(&self.name)
    }

    /// The title, saying when `options` shortened the case.
    pub fn title(&self, options: Options) -> String {
        let title = if options.quick && self.name == "soak_one_hour" {
            "one minute of a base-10 pyramid (soak shortened by --quick)".into()
        } else if options.direct_joints && JOINT_CASES.contains(&self.name) {
            format!("{}, carom with direct joints", self.title)
        } else {
            self.title.into()
        };
        if options.shock_propagation {
            format!("{title}, carom with shock propagation")
        } else {
            title
        }
    }
}

impl std::fmt::Debug for Case {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Case").field("name", &self.name).finish()
    }
}

/// Every hard case, in the order of `tests/stability.rs` (the 30-box column after the 20).
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "vertical_stack_12",
            title: "vertical stack of 12",
            run: |e, _, o| stack_stands(e, 12, o),
        },
        Case {
            name: "vertical_stack_20",
            title: "vertical stack of 20",
            run: |e, _, o| stack_stands(e, 20, o),
        },
        Case {
            name: "vertical_stack_30",
            title: "vertical stack of 30",
            run: |e, _, o| stack_stands(e, 30, o),
        },
        Case {
            name: "vertical_stack_12_sleeps",
            title: "stack of 12 asleep within 5 s",
            run: |e, _, o| stack_sleeps(e, 12, o),
        },
        Case {
            name: "vertical_stack_20_sleeps",
            title: "stack of 20 asleep within 5 s",
            run: |e, _, o| stack_sleeps(e, 20, o),
        },
        Case {
            name: "pyramid_20",
            title: "pyramid of 20 (demos/pyramid.ron, sleeping off)",
            run: |e, _, o| pyramid_20(e, o),
        },
        Case {
            name: "high_mass_ratio_pyramids",
            title: "heavy tops on pyramids (demos/high_mass_ratio.ron, sleeping off)",
            run: |e, _, o| heavy_tops(e, o),
        },
        Case {
            name: "high_mass_ratio_boxes",
            title: "20 m box on two 1 m boxes",
            run: |e, _, o| {
                let world = worlds::big_box_on(e.params(), carom::Shape::rect(0.5, 0.5));
                on(e, world, |w| settles(w, 4.0, 2.0, o))
            },
        },
        Case {
            name: "high_mass_ratio_triangles",
            title: "20 m box on two triangles",
            run: |e, _, o| {
                let world = worlds::big_box_on(e.params(), worlds::small_triangle());
                on(e, world, |w| settles(w, 4.0, 2.0, o))
            },
        },
        Case {
            name: "overlap_recovery",
            title: "overlap recovery (demos/overlap_recovery.ron)",
            run: |e, _, o| overlap_recovery(e, o),
        },
        Case {
            name: "tiny_pyramid",
            title: "tiny pyramid, 5 cm boxes, 30 in the base",
            run: |e, _, o| tiny_pyramid(e, o),
        },
        Case {
            name: "card_house",
            title: "card house (demos/card_house.ron, 8 substeps)",
            run: |e, _, o| card_house(e, o),
        },
        Case {
            name: "confined",
            title: "confined, 625 circles (demos/confined.ron)",
            run: |e, _, o| confined(e, o),
        },
        Case {
            name: "coincident_centres",
            title: "ten circles at one point",
            run: |e, _, o| coincident(e, o),
        },
        Case {
            name: "skinny_box",
            title: "skinny plank, 500 launches",
            run: |e, _, o| skinny(e, o),
        },
        Case {
            name: "bullets",
            title: "bullets at 300 m/s into 12 boxes and a wall",
            run: |e, _, o| bullets(e, o),
        },
        Case {
            name: "wall_shots",
            title: "bullets at 300 to 1000 m/s into free 5 cm walls",
            run: |e, _, o| wall_shots(e, o),
        },
        Case {
            name: "soak_one_hour",
            title: "one hour of a base-10 pyramid",
            run: soak,
        },
        Case {
            name: "random_worlds",
            title: "random worlds, 4 seeds x 2000 steps",
            run: |e, _, o| random_worlds(e, o),
        },
        Case {
            name: "pendulum",
            title: "pendulum from 10°, 60 s (demos/pendulum.ron)",
            run: pendulum,
        },
        Case {
            name: "chain",
            title: "chain of 40 links holding 50 kg, 4 substeps and 60 Hz joints",
            run: chain,
        },
        Case {
            name: "bridge",
            title: "bridge of 160 planks with 30 boxes, 4 substeps and 60 Hz joints",
            run: bridge,
        },
        Case {
            name: "ragdolls",
            title: "20 ragdolls in a pile, 4 substeps and 60 Hz joints",
            run: ragdolls,
        },
    ]
}

/// Soft step at its defaults: the carom column, and (through the mapping) Box2D's settings.
fn soft_step() -> SolverParams {
    SolverParams::for_kind(SolverKind::SoftStep)
}

/// One side of a comparison: the engine, and the options carom runs with.
#[derive(Debug, Clone, Copy)]
struct Side {
    engine: Engine,
    options: Options,
}

impl Side {
    /// The solver a case's world is built with: carom's with the options' solver and
    /// settings at their defaults, or soft step at its defaults, which the Box2D copy maps
    /// to Box2D's settings.
    fn params(self) -> SolverParams {
        match self.engine {
            Engine::Carom => SolverParams {
                direct_joints: self.options.direct_joints,
                shock_propagation: self.options.shock_propagation,
                ..SolverParams::for_kind(self.options.solver)
            },
            Engine::Box2d => soft_step(),
        }
    }
}

/// Runs `f` on `world` (built with [`Side::params`]) in `side`'s engine: carom's world, or its
/// Box2D copy.
fn on<T>(side: Side, mut world: World, f: impl FnOnce(&mut dyn CaseWorld) -> Res<T>) -> Res<T> {
    match side.engine {
        Engine::Carom => f(&mut world),
        Engine::Box2d => {
            let mut copy = Box2dWorld::from_carom(&world)?;
            drop(world);
            f(&mut copy)
        }
    }
}

/// The dense index of `handle` in `world` (the same in its Box2D copy).
fn index(world: &World, handle: BodyHandle) -> Res<usize> {
    world
        .bodies()
        .position(|b| b.handle() == handle)
        .ok_or_else(|| "handle not in world".to_string())
}

fn steps(w: &mut dyn CaseWorld, n: usize) -> Res<()> {
    for _ in 0..n {
        w.advance(DT)?;
    }
    Ok(())
}

/// The highest dynamic body.
fn highest(w: &mut dyn CaseWorld) -> Res<usize> {
    let mut best: Option<(usize, f32)> = None;
    for i in 0..w.body_total() {
        if w.is_dynamic(i) {
            let y = w.body_position(i)?[1];
            if best.is_none_or(|(_, b)| y > b) {
                best = Some((i, y));
            }
        }
    }
    best.map(|(i, _)| i).ok_or_else(|| "no dynamic body".into())
}

fn distance(a: [f32; 2], b: [f32; 2]) -> f64 {
    f64::from((a[0] - b[0]).hypot(a[1] - b[1]))
}

fn max_speed(w: &mut dyn CaseWorld) -> Res<f64> {
    let mut fastest: f64 = 0.0;
    for i in 0..w.body_total() {
        if w.is_dynamic(i) {
            let (v, _) = w.body_velocity(i)?;
            fastest = fastest.max(f64::from(v[0].hypot(v[1])));
        }
    }
    Ok(fastest)
}

/// Deepest any dynamic body reaches below the ground's top (y = 0), m.
fn below_ground(w: &mut dyn CaseWorld) -> Res<f64> {
    let mut deepest: f64 = 0.0;
    for i in 0..w.body_total() {
        if w.is_dynamic(i) {
            deepest = deepest.max(-f64::from(w.body_aabb(i)?.0[1]));
        }
    }
    Ok(deepest)
}

fn stack_stands(engine: Side, count: usize, o: &mut Outcome) -> Res<()> {
    let (world, boxes) = worlds::vertical_stack(engine.params(), count, false);
    let top = index(&world, *boxes.last().ok_or("no boxes")?)?;
    on(engine, world, |w| {
        let start = w.body_position(top)?;
        // Drift is what the top box creeps once the column has settled on its soft contacts
        // (the first second); the settling itself is the column's compression.
        steps(w, 60)?;
        let settled = w.body_position(top)?;
        o.figure("compression m", f64::from(start[1] - settled[1]));
        steps(w, 1140)?;
        o.bar(
            "top drift m",
            Bar::Below(0.05),
            distance(w.body_position(top)?, settled),
        );
        o.check_finite(w)
    })
}

fn stack_sleeps(engine: Side, count: usize, o: &mut Outcome) -> Res<()> {
    let (world, boxes) = worlds::vertical_stack(engine.params(), count, true);
    let boxes = boxes
        .iter()
        .map(|b| index(&world, *b))
        .collect::<Res<Vec<_>>>()?;
    on(engine, world, |w| {
        let mut asleep_at = f64::INFINITY;
        'steps: for step in 0..600 {
            w.advance(DT)?;
            for &b in &boxes {
                if !w.is_asleep(b)? {
                    continue 'steps;
                }
            }
            asleep_at = (step + 1) as f64 * f64::from(DT);
            break;
        }
        o.bar("asleep after s", Bar::Below(5.0), asleep_at);
        o.check_finite(w)
    })
}

fn pyramid_20(engine: Side, o: &mut Outcome) -> Res<()> {
    let mut scene = worlds::scene("pyramid", engine.params());
    scene
        .world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .expect("switching an effect keeps the settings valid");
    let slop = f64::from(carom::LINEAR_SLOP);
    on(engine, scene.world, |w| {
        let top = highest(w)?;
        let start = w.body_position(top)?;
        let mut deepest: f64 = 0.0;
        for step in 0..1200 {
            w.advance(DT)?;
            // Past the first second, once the boxes have found their contacts.
            if step >= 60 {
                deepest = deepest.max(w.deepest_penetration()?);
            }
        }
        o.bar(
            "top drift m",
            Bar::Below(0.05),
            distance(w.body_position(top)?, start),
        );
        o.bar("max penetration m", Bar::Below(2.0 * slop), deepest);
        o.check_finite(w)
    })
}

/// Runs `seconds`, then `settle` more seconds in which nothing may move faster than 1 m/s;
/// no pair may overlap by half a metre (the supports are 1 m tall).
fn settles(w: &mut dyn CaseWorld, seconds: f64, settle: f64, o: &mut Outcome) -> Res<()> {
    let (mut sunk, mut overlap): (f64, f64) = (0.0, 0.0);
    let mut fastest: f64 = 0.0;
    let settling = (seconds / f64::from(DT)) as usize;
    for step in 0..settling + (settle / f64::from(DT)) as usize {
        w.advance(DT)?;
        sunk = sunk.max(below_ground(w)?);
        overlap = overlap.max(w.deepest_penetration()?);
        if step >= settling {
            fastest = fastest.max(max_speed(w)?);
        }
    }
    o.bar("ground penetration m", Bar::Below(0.1), sunk);
    o.bar("deepest overlap m", Bar::Below(0.5), overlap);
    o.bar("fastest once settled m/s", Bar::Below(1.0), fastest);
    o.check_finite(w)
}

fn heavy_tops(engine: Side, o: &mut Outcome) -> Res<()> {
    let mut scene = worlds::scene("high_mass_ratio", engine.params());
    scene
        .world
        .update_settings(|s| s.effects.set(Effect::Sleeping, false))
        .expect("switching an effect keeps the settings valid");
    on(engine, scene.world, |w| settles(w, 4.0, 2.0, o))
}

fn overlap_recovery(engine: Side, o: &mut Outcome) -> Res<()> {
    let scene = worlds::scene("overlap_recovery", engine.params());
    let cap = f64::from(scene.world.solver().max_push_speed);
    let slop = f64::from(carom::LINEAR_SLOP);
    on(engine, scene.world, |w| {
        let mut fastest: f64 = 0.0;
        for _ in 0..120 {
            w.advance(DT)?;
            fastest = fastest.max(max_speed(w)?);
        }
        o.bar(
            "penetration at 2 s m",
            Bar::Below(2.0 * slop),
            w.deepest_penetration()?,
        );
        o.bar("fastest / push cap", Bar::Below(1.1), fastest / cap);
        o.check_finite(w)
    })
}

fn tiny_pyramid(engine: Side, o: &mut Outcome) -> Res<()> {
    let size = f64::from(worlds::TINY_BOX_SIZE);
    on(engine, worlds::tiny_pyramid(engine.params()), |w| {
        let top = highest(w)?;
        let start = w.body_position(top)?;
        // Stands: once settled (the first second), the top box creeps less than a fifth of its
        // size in 10 s. The settling is the compression, in box sizes.
        steps(w, 60)?;
        let settled = w.body_position(top)?;
        o.figure(
            "compression / box size",
            f64::from(start[1] - settled[1]) / size,
        );
        steps(w, 600)?;
        o.bar(
            "top drift / box size",
            Bar::Below(0.2),
            distance(w.body_position(top)?, settled) / size,
        );
        o.check_finite(w)
    })
}

fn card_house(engine: Side, o: &mut Outcome) -> Res<()> {
    let scene = worlds::scene("card_house", engine.params());
    on(engine, scene.world, |w| {
        let mut cards = Vec::new();
        for i in 0..w.body_total() {
            if w.is_dynamic(i) {
                cards.push((i, w.body_position(i)?[1]));
            }
        }
        steps(w, 600)?;
        // Standing: no card has dropped (a falling card loses tens of centimetres).
        let mut dropped: f64 = 0.0;
        for (card, y) in cards {
            dropped = dropped.max(f64::from(y - w.body_position(card)?[1]));
        }
        o.bar("largest card drop m", Bar::Below(0.05), dropped);
        o.check_finite(w)
    })
}

fn confined(engine: Side, o: &mut Outcome) -> Res<()> {
    let scene = worlds::scene("confined", engine.params());
    on(engine, scene.world, |w| {
        // The circles start overlapped: the energy the push-apart gives them in the first
        // second is the start; after it, the energy may only fall.
        steps(w, 60)?;
        let start = w.total_kinetic_energy()?;
        let mut highest_energy = start;
        for _ in 0..540 {
            w.advance(DT)?;
            highest_energy = highest_energy.max(w.total_kinetic_energy()?);
        }
        let mut escaped = 0usize;
        for i in 0..w.body_total() {
            let p = w.body_position(i)?;
            if w.is_dynamic(i) && (p[0].abs() > 10.5 || p[1].abs() > 10.25) {
                escaped += 1;
            }
        }
        o.figure("energy at 1 s J", start);
        o.bar(
            "energy growth after 1 s J",
            Bar::Below(1e-3),
            highest_energy - start,
        );
        o.bar("escaped", Bar::Below(0.5), escaped as f64);
        o.check_finite(w)
    })
}

fn coincident(engine: Side, o: &mut Outcome) -> Res<()> {
    let (world, circles) = worlds::coincident_circles(engine.params());
    let slop = f64::from(carom::LINEAR_SLOP);
    let circles = circles
        .iter()
        .map(|c| index(&world, *c))
        .collect::<Res<Vec<_>>>()?;
    on(engine, world, |w| {
        steps(w, 180)?;
        let mut closest = f64::INFINITY;
        for (k, &a) in circles.iter().enumerate() {
            for &b in &circles[k + 1..] {
                let gap = distance(w.body_position(a)?, w.body_position(b)?) - 1.0;
                closest = closest.min(gap);
            }
        }
        o.bar(
            "deepest overlap after 3 s m",
            Bar::Below(2.0 * slop),
            -closest,
        );
        o.check_finite(w)
    })
}

fn skinny(engine: Side, o: &mut Outcome) -> Res<()> {
    // Box2D's Skinny Box: a 4 x 0.1 m plank falling at 100 m/s, spinning at ±50 rad/s, onto a
    // thin floor beside a thin post, relaunched every 60 steps from a different angle and place.
    let (world, plank) = worlds::skinny_plank(engine.params());
    let plank = index(&world, plank)?;
    on(engine, world, |w| {
        let mut rng = crate::cases::Rng::new(500);
        let (mut under_floor, mut through_post) = (0usize, 0usize);
        let mut lowest: f64 = 0.0;
        for _ in 0..500 {
            let offset = rng.range(-2.0, 0.6);
            let angle = rng.range(-std::f32::consts::PI, std::f32::consts::PI);
            let spin = if rng.below(2) == 0 { 50.0 } else { -50.0 };
            w.relaunch(plank, [offset, 8.0], angle, [0.0, -100.0], spin)?;
            let mut before = vec2(offset, 8.0);
            let mut crossed = false;
            for _ in 0..60 {
                w.advance(DT)?;
                lowest = lowest.max(-f64::from(w.body_aabb(plank)?.0[1]));
                let p = w.body_position(plank)?;
                let after = vec2(p[0], p[1]);
                crossed |= skinny_box::through_post(before, after);
                before = after;
            }
            under_floor += usize::from(w.body_position(plank)?[1] < 0.0);
            through_post += usize::from(crossed);
        }
        o.figure("deepest below the floor m", lowest);
        o.bar(
            "launches ending under the floor",
            Bar::Below(0.5),
            under_floor as f64,
        );
        o.bar(
            "launches through the post",
            Bar::Below(0.5),
            through_post as f64,
        );
        o.check_finite(w)
    })
}

fn bullets(engine: Side, o: &mut Outcome) -> Res<()> {
    // Each of ten bullets into a fresh stack (a hit stack falls, and a bullet through the gap a
    // box left is no tunnel).
    let (mut tunnels, mut past_wall) = (0usize, 0usize);
    for shot in 0..10 {
        let (world, bullet) = worlds::bullet_shot(engine.params(), shot);
        let bullet = index(&world, bullet)?;
        on(engine, world, |w| {
            let mut checked_stack = false;
            for _ in 0..60 {
                w.advance(DT)?;
                let x = w.body_position(bullet)?[0];
                let (v, _) = w.body_velocity(bullet)?;
                let speed = v[0].hypot(v[1]);
                // Past the stack's far face (0.51 + r) still at nearly full speed: it went
                // through the boxes without hitting them.
                if !checked_stack && x > 0.76 {
                    checked_stack = true;
                    tunnels += usize::from(speed > 270.0);
                }
                past_wall += usize::from(x > 10.05);
            }
            o.check_finite(w)
        })?;
    }
    o.bar("bullets through the stack", Bar::Below(0.5), tunnels as f64);
    o.bar(
        "steps with a bullet past the wall",
        Bar::Below(0.5),
        past_wall as f64,
    );
    Ok(())
}

fn wall_shots(engine: Side, o: &mut Outcome) -> Res<()> {
    // Each shot's deepest point into the wall after any step, and for a free wall how far its
    // velocity ends from the one its momentum and the bullet's give, of the closing speed.
    let (mut deepest, mut through, mut worst_push): (f64, usize, f64) = (0.0, 0, 0.0);
    for shot in &wall_shot::SHOTS {
        let made = shot.world(engine.params());
        let (bullet, wall) = (
            index(&made.world, made.bullet)?,
            index(&made.world, made.wall)?,
        );
        let shared = shot.shared_velocity(made.bullet_mass, made.wall_mass);
        let closing = f64::from(shot.speed - shot.wall_velocity[0]);
        on(engine, made.world, |w| {
            let mut shot_deepest: f64 = 0.0;
            for _ in 0..WALL_SHOT_STEPS {
                w.advance(DT)?;
                let b = w.body_position(bullet)?;
                let p = w.body_position(wall)?;
                let depth =
                    wall_shot::depth(vec2(b[0], b[1]), vec2(p[0], p[1]), w.body_angle(wall)?);
                shot_deepest = shot_deepest.max(depth);
            }
            o.figure(&format!("{}: deepest cm", shot.name), 100.0 * shot_deepest);
            deepest = deepest.max(shot_deepest);
            through += usize::from(shot_deepest > 2.0 * f64::from(wall_shot::WALL_HALF_THICKNESS));
            if !shot.standing {
                let v = f64::from(w.body_velocity(wall)?.0[0]);
                let push = (v - shared).abs() / closing;
                o.figure(&format!("{}: push off %", shot.name), 100.0 * push);
                worst_push = worst_push.max(push);
            }
            o.check_finite(w)
        })?;
    }
    o.bar("deepest into a wall cm", Bar::Below(1.0), 100.0 * deepest);
    o.bar("shots through a wall", Bar::Below(0.5), through as f64);
    o.bar(
        "worst push off momentum's % of closing speed",
        Bar::Below(1.0),
        100.0 * worst_push,
    );
    Ok(())
}

fn soak(engine: Side, options: Options, o: &mut Outcome) -> Res<()> {
    // A base-10 pyramid at rest, sleeping off so every step is really solved.
    let total = if options.quick {
        QUICK_SOAK_STEPS
    } else {
        SOAK_STEPS
    };
    on(engine, worlds::pyramid_world(engine.params(), 10), |w| {
        let top = highest(w)?;
        steps(w, 120)?;
        let settled = w.body_position(top)?;
        let mut energy: f64 = 0.0;
        for _ in 120..total {
            w.advance(DT)?;
            energy = energy.max(w.total_kinetic_energy()?);
        }
        // Rounded to the millisecond: the f32 step widened to f64 shows its rounding.
        let simulated = (total as f64 * f64::from(DT) * 1e3).round() / 1e3;
        o.figure("simulated s", simulated);
        o.bar("kinetic energy after settling J", Bar::Below(1e-4), energy);
        o.bar(
            "top drift m",
            Bar::Below(0.01),
            distance(w.body_position(top)?, settled),
        );
        o.check_finite(w)
    })
}

/// The seeds and body counts of the random worlds, fixed so both engines see the same ones.
pub fn random_seeds() -> Vec<(u64, usize)> {
    let mut rng = crate::cases::Rng::new(0x5eed);
    (0..RANDOM_WORLDS)
        .map(|_| (rng.next_u64().max(1), 5 + rng.below(35)))
        .collect()
}

fn random_worlds(engine: Side, o: &mut Outcome) -> Res<()> {
    let (mut escaped, mut worst) = (0usize, 0.0f64);
    let mut nan = false;
    for (seed, count) in random_seeds() {
        let world = worlds::random_world(engine.params(), seed, count);
        let work = worlds::gravity_work(&world);
        let (e, ratio, n) = on(engine, world, |w| {
            let mut first_second: f64 = 0.0;
            for _ in 0..60 {
                w.advance(DT)?;
                first_second = first_second.max(w.total_kinetic_energy()?);
            }
            let ceiling = first_second + work;
            let mut highest_energy: f64 = 0.0;
            for _ in 60..2000 {
                w.advance(DT)?;
                highest_energy = highest_energy.max(w.total_kinetic_energy()?);
            }
            let mut out = 0usize;
            for i in 0..w.body_total() {
                let p = w.body_position(i)?;
                if w.is_dynamic(i) && worlds::outside_the_box(vec2(p[0], p[1])) {
                    out += 1;
                }
            }
            let mut finite = Outcome::default();
            finite.check_finite(w)?;
            Ok((out, highest_energy / ceiling, finite.nan))
        })?;
        escaped += e;
        worst = worst.max(ratio);
        nan |= n;
    }
    o.nan |= nan;
    o.bar("bodies out of their box", Bar::Below(0.5), escaped as f64);
    o.bar("highest energy / ceiling", Bar::AtMost(1.0), worst);
    Ok(())
}

/// A figure as the table shows it: bold when it misses its bar.
fn cell(figure: &Figure, nan: bool) -> String {
    // Adding zero makes -0 plain 0.
    let value = figure.value + 0.0;
    let text = if value.is_infinite() {
        "never".to_string()
    } else if value == value.trunc() && value.abs() < 1e9 {
        // Counts (escapes, launches, steps) and exact zeros.
        format!("{value:.0}")
    } else if value.abs() < 1e-3 {
        format!("{value:.2e}")
    } else {
        format!("{value:.4}")
    };
    let text = if nan { format!("{text} (NaN)") } else { text };
    if figure.bar.met(value) && !nan {
        text
    } else {
        format!("**{text}**")
    }
}

// Joints. The joint scenes run at soft step's defaults, Box2D's (4 substeps, 60 Hz joints),
// whatever the scene asks, so both engines are measured at the same settings; the scenes' own
// stiffer settings are `tests/stability.rs`'s business.

/// A joint as the measures need it: its bodies (dense indices), its anchors in their frames,
/// and a hinge's reference angle and limits.
struct JointInfo {
    bodies: [usize; 2],
    anchors: [[f32; 2]; 2],
    reference_angle: f32,
    limits: Option<(f32, f32)>,
    hinge: bool,
}

/// A demo scene at soft step's defaults, and its joints.
/// The cases `Options::direct_joints` changes.
const JOINT_CASES: [&str; 4] = ["pendulum", "chain", "bridge", "ragdolls"];

fn joint_scene(name: &str, side: Side) -> Res<(carom_scene::SceneWorld, Vec<JointInfo>)> {
    let mut scene = worlds::scene(name, side.params());
    let params = side.params();
    scene
        .world
        .update_settings(|s| s.solver = params)
        .map_err(|e| e.to_string())?;
    let world = &scene.world;
    let mut joints = Vec::new();
    for joint in world.joints() {
        let [a, b] = joint.bodies();
        let [la, lb] = joint.local_anchors();
        let (hinge, limits) = match joint.kind() {
            carom::JointKind::Revolute(r) => (true, r.limits.map(|l| (l.lower, l.upper))),
            _ => (false, None),
        };
        joints.push(JointInfo {
            bodies: [index(world, a)?, index(world, b)?],
            anchors: [[la.x, la.y], [lb.x, lb.y]],
            reference_angle: joint.reference_angle(),
            limits,
            hinge,
        });
    }
    Ok((scene, joints))
}

/// Where body `i`'s point `local` (in its frame) is in the world.
fn world_point(w: &mut dyn CaseWorld, i: usize, local: [f32; 2]) -> Res<[f32; 2]> {
    let p = w.body_position(i)?;
    let (sin, cos) = w.body_angle(i)?.sin_cos();
    Ok([
        p[0] + cos * local[0] - sin * local[1],
        p[1] + sin * local[0] + cos * local[1],
    ])
}

/// The distance between a joint's two anchors, m.
fn joint_gap(w: &mut dyn CaseWorld, joint: &JointInfo) -> Res<f64> {
    let a = world_point(w, joint.bodies[0], joint.anchors[0])?;
    let b = world_point(w, joint.bodies[1], joint.anchors[1])?;
    Ok(distance(a, b))
}

/// How far past its limits a hinge has turned, rad.
fn limit_violation(w: &mut dyn CaseWorld, joint: &JointInfo) -> Res<f64> {
    let Some((lower, upper)) = joint.limits else {
        return Ok(0.0);
    };
    let relative = w.body_angle(joint.bodies[1])? - w.body_angle(joint.bodies[0])?;
    // The angle brought into [-π, π], as carom's `Joint::angle` measures it.
    let angle = carom::Rot::new(relative - joint.reference_angle).angle();
    Ok(f64::from((lower - angle).max(angle - upper).max(0.0)))
}

fn pendulum(engine: Side, _: Options, o: &mut Outcome) -> Res<()> {
    let (scene, joints) = joint_scene("pendulum", engine)?;
    let bob = index(&scene.world, scene.names["bob"])?;
    on(engine, scene.world, |w| {
        let mut crossings = Vec::new();
        let mut last = w.body_position(bob)?[0];
        for step in 1..=3600 {
            w.advance(DT)?;
            let x = w.body_position(bob)?[0];
            if last < 0.0 && x >= 0.0 {
                let t = (step as f64 - 1.0 + f64::from(-last / (x - last))) * f64::from(DT);
                crossings.push(t);
            }
            last = x;
        }
        let periods = crossings.len().saturating_sub(1).max(1) as f64;
        let period =
            (crossings.last().unwrap_or(&0.0) - crossings.first().unwrap_or(&0.0)) / periods;
        // A physical pendulum: the bob's own inertia included.
        let (length, radius, theta) = (1.0_f64, 0.05_f64, 10.0_f64.to_radians());
        let expected = 2.0
            * std::f64::consts::PI
            * ((1.0 + radius * radius / (2.0 * length * length)) * length / 10.0).sqrt()
            * (1.0 + theta * theta / 16.0);
        o.bar(
            "period error %",
            Bar::Below(0.5),
            100.0 * (period - expected).abs() / expected,
        );
        o.figure("hinge gap m", joint_gap(w, &joints[0])?);
        o.check_finite(w)
    })
}

fn chain(engine: Side, _: Options, o: &mut Outcome) -> Res<()> {
    let (scene, joints) = joint_scene("chain", engine)?;
    let ball = index(&scene.world, scene.names["ball"])?;
    let held = joints
        .iter()
        .position(|j| j.bodies[1] == ball)
        .ok_or("the ball hangs by a joint")?;
    let anchor = joints[held].anchors[1];
    on(engine, scene.world, |w| {
        let mut worst: f64 = 0.0;
        for _ in 0..600 {
            w.advance(DT)?;
            let at = world_point(w, ball, anchor)?;
            worst = worst.max(100.0 * (distance(at, [0.0, 0.0]) - 20.0) / 20.0);
        }
        o.bar("worst stretch %", Bar::Below(1.0), worst);
        let at = world_point(w, ball, anchor)?;
        o.figure(
            "stretch at 10 s %",
            100.0 * (distance(at, [0.0, 0.0]) - 20.0) / 20.0,
        );
        o.check_finite(w)
    })
}

fn bridge(engine: Side, _: Options, o: &mut Outcome) -> Res<()> {
    let (scene, joints) = joint_scene("bridge", engine)?;
    on(engine, scene.world, |w| {
        let mut worst: f64 = 0.0;
        for _ in 0..600 {
            w.advance(DT)?;
            let mut gaps = 0.0;
            for joint in &joints {
                gaps += joint_gap(w, joint)?;
            }
            worst = worst.max(100.0 * gaps / 160.0);
        }
        o.bar("worst stretch %", Bar::Below(2.0), worst);
        o.check_finite(w)
    })
}

fn ragdolls(engine: Side, _: Options, o: &mut Outcome) -> Res<()> {
    let (scene, joints) = joint_scene("ragdolls", engine)?;
    on(engine, scene.world, |w| {
        let (mut gap, mut past): (f64, f64) = (0.0, 0.0);
        for _ in 0..600 {
            w.advance(DT)?;
            for joint in joints.iter().filter(|j| j.hinge) {
                gap = gap.max(joint_gap(w, joint)?);
                past = past.max(limit_violation(w, joint)?.to_degrees());
            }
        }
        o.bar("worst hinge gap m", Bar::Below(0.02), gap);
        o.bar("worst past a limit deg", Bar::Below(5.0), past);
        o.check_finite(w)
    })
}
