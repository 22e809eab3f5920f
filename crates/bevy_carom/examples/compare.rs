//! The same scenes through `bevy_carom`, `bevy_rapier2d` and `avian2d`, each in a headless
//! Bevy app (`MinimalPlugins`, `TransformPlugin`, the physics plugin) on a 60 Hz fixed
//! timestep, one fixed step per update, and through plain carom without Bevy: milliseconds
//! per fixed step, and what `bevy_carom` costs over plain carom.
//!
//! Every engine runs on one thread, with its own default solver settings and sleeping off
//! (as in Box2D's benchmarks). The tumbler's drum is a kinematic body turning at 25°/s in all
//! of them (Box2D's recipe drives it with a motor).
//!
//! `cargo run --release -p bevy_carom --example compare --features compare -- [--csv] [--rounds 3] [--steps 200] [--scene pyramid|large_pyramid|tumbler] [--engine NAME]`
//!
//! With `--csv`, standard output holds only the table, as CSV (a header, then a row per
//! scene), for `carom-bench measure` to record and docs/bevy.md to draw; everything else
//! goes to standard error.

use std::time::Instant;

use avian2d::prelude as avian;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_carom::carom;
use bevy_carom::prelude as bc;
use bevy_rapier2d::prelude as rapier;

const DT: f32 = 1.0 / 60.0;

/// A collider of the neutral scene description: a box of half-extents `half`.
#[derive(Clone, Copy)]
struct Part {
    half: Vec2,
    offset: Vec2,
    density: f32,
    friction: f32,
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Static,
    Kinematic,
    Dynamic,
}

#[derive(Clone)]
struct Spec {
    kind: Kind,
    position: Vec2,
    angular_velocity: f32,
    parts: Vec<Part>,
}

fn boxed(half: Vec2, offset: Vec2, density: f32) -> Part {
    Part {
        half,
        offset,
        density,
        friction: 0.6,
    }
}

/// Box2D's pyramid recipes: one-metre boxes touching, `base` in the bottom row.
fn pyramid(base: u32) -> Vec<Spec> {
    let ground = Spec {
        kind: Kind::Static,
        position: Vec2::new(0.0, -1.0),
        angular_velocity: 0.0,
        parts: vec![boxed(Vec2::new(base as f32 + 20.0, 1.0), Vec2::ZERO, 1.0)],
    };
    let mut specs = vec![ground];
    for row in 0..base {
        for i in 0..base - row {
            specs.push(Spec {
                kind: Kind::Dynamic,
                position: Vec2::new(i as f32 - (base - 1 - row) as f32 * 0.5, 0.5 + row as f32),
                angular_velocity: 0.0,
                parts: vec![boxed(Vec2::splat(0.5), Vec2::ZERO, 1.0)],
            });
        }
    }
    specs
}

/// Box2D's tumbler: a 20 m drum of four 1 m walls around (0, 10) and 2025 boxes of 0.25 m.
fn tumbler() -> Vec<Spec> {
    let wall = |half: Vec2, offset: Vec2| boxed(half, offset, 50.0);
    let drum = Spec {
        kind: Kind::Kinematic,
        position: Vec2::new(0.0, 10.0),
        angular_velocity: 25f32.to_radians(),
        parts: vec![
            wall(Vec2::new(0.5, 10.0), Vec2::new(10.0, 0.0)),
            wall(Vec2::new(0.5, 10.0), Vec2::new(-10.0, 0.0)),
            wall(Vec2::new(10.0, 0.5), Vec2::new(0.0, 10.0)),
            wall(Vec2::new(10.0, 0.5), Vec2::new(0.0, -10.0)),
        ],
    };
    let mut specs = vec![drum];
    for i in 0..45 {
        for j in 0..45 {
            specs.push(Spec {
                kind: Kind::Dynamic,
                position: Vec2::new(-9.0 + 0.4 * i as f32, 1.0 + 0.4 * j as f32),
                angular_velocity: 0.0,
                parts: vec![boxed(Vec2::splat(0.125), Vec2::ZERO, 1.0)],
            });
        }
    }
    specs
}

fn carom_v(v: Vec2) -> carom::Vec2 {
    carom::vec2(v.x, v.y)
}

fn carom_settings() -> carom::WorldSettings {
    let mut settings = carom::WorldSettings::default();
    settings.effects = settings.effects.without(carom::Effect::Sleeping);
    settings
}

/// Plain carom, without Bevy.
fn plain_carom(specs: &[Spec]) -> carom::World {
    let mut world = carom::World::with_settings(carom_settings()).expect("valid settings");
    for spec in specs {
        let kind = match spec.kind {
            Kind::Static => carom::BodyKind::Static,
            Kind::Kinematic => carom::BodyKind::Kinematic,
            Kind::Dynamic => carom::BodyKind::Dynamic,
        };
        let mut def = carom::BodyDef::new(kind, carom::Shape::circle(1.0));
        def.colliders = spec.parts.iter().map(carom_collider).collect();
        def.position = carom_v(spec.position);
        def.angular_velocity = spec.angular_velocity;
        world.add_body(def).expect("valid body");
    }
    world
}

fn carom_collider(part: &Part) -> carom::ColliderDef {
    let shape = carom::Shape::rect(part.half.x, part.half.y);
    let mut def = carom::ColliderDef::new(shape)
        .density(part.density)
        .friction(part.friction);
    def.offset = carom_v(part.offset);
    def
}

/// A headless app stepping once per update on the fixed timestep.
fn headless() -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(Time::<Fixed>::from_seconds(DT as f64))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    app
}

fn ready(mut app: App) -> App {
    app.finish();
    app.cleanup();
    app
}

fn bevy_carom_app(specs: &[Spec]) -> App {
    let mut app = headless();
    app.insert_resource(bc::CaromWorld::new(carom_settings()).expect("valid settings"))
        .add_plugins(bc::CaromPlugin);
    for spec in specs {
        let kind = match spec.kind {
            Kind::Static => bc::RigidBody::Static,
            Kind::Kinematic => bc::RigidBody::Kinematic,
            Kind::Dynamic => bc::RigidBody::Dynamic,
        };
        let collider = |part: &Part| {
            let shape = bc::Collider::rectangle(2.0 * part.half.x, 2.0 * part.half.y);
            let material = bc::ColliderMaterial {
                density: part.density,
                friction: part.friction,
                ..default()
            };
            (shape, material)
        };
        let mut body = app.world_mut().spawn((
            kind,
            Transform::from_translation(spec.position.extend(0.0)),
            bc::Velocity {
                linear: Vec2::ZERO,
                angular: spec.angular_velocity,
            },
        ));
        if let [part] = spec.parts.as_slice()
            && part.offset == Vec2::ZERO
        {
            body.insert(collider(part));
        } else {
            body.with_children(|children| {
                for part in &spec.parts {
                    children.spawn((
                        collider(part),
                        Transform::from_translation(part.offset.extend(0.0)),
                    ));
                }
            });
        }
    }
    ready(app)
}

fn rapier_app(specs: &[Spec]) -> App {
    let mut app = headless();
    app.insert_resource(rapier::TimestepMode::Fixed {
        dt: DT,
        substeps: 1,
    })
    .add_plugins(rapier::RapierPhysicsPlugin::<rapier::NoUserData>::default().in_fixed_schedule());
    for spec in specs {
        let kind = match spec.kind {
            Kind::Static => rapier::RigidBody::Fixed,
            Kind::Kinematic => rapier::RigidBody::KinematicVelocityBased,
            Kind::Dynamic => rapier::RigidBody::Dynamic,
        };
        let shape = |part: &Part| rapier::Collider::cuboid(part.half.x, part.half.y);
        let part = spec.parts[0];
        let collider = if spec.parts.len() == 1 && part.offset == Vec2::ZERO {
            shape(&part)
        } else {
            rapier::Collider::compound(
                spec.parts
                    .iter()
                    .map(|p| (p.offset, 0.0, shape(p)))
                    .collect(),
            )
        };
        app.world_mut().spawn((
            kind,
            collider,
            rapier::ColliderMassProperties::Density(part.density),
            rapier::Friction::coefficient(part.friction),
            rapier::Velocity::angular(spec.angular_velocity),
            rapier::Sleeping::disabled(),
            Transform::from_translation(spec.position.extend(0.0)),
        ));
    }
    ready(app)
}

fn avian_app(specs: &[Spec]) -> App {
    let mut app = headless();
    app.add_plugins(avian::PhysicsPlugins::default());
    for spec in specs {
        let kind = match spec.kind {
            Kind::Static => avian::RigidBody::Static,
            Kind::Kinematic => avian::RigidBody::Kinematic,
            Kind::Dynamic => avian::RigidBody::Dynamic,
        };
        let shape = |part: &Part| avian::Collider::rectangle(2.0 * part.half.x, 2.0 * part.half.y);
        let part = spec.parts[0];
        let collider = if spec.parts.len() == 1 && part.offset == Vec2::ZERO {
            shape(&part)
        } else {
            avian::Collider::compound(
                spec.parts
                    .iter()
                    .map(|p| (p.offset, avian::Rotation::IDENTITY, shape(p)))
                    .collect(),
            )
        };
        app.world_mut().spawn((
            kind,
            collider,
            avian::ColliderDensity(part.density),
            avian::Friction::new(part.friction),
            avian::AngularVelocity(spec.angular_velocity),
            avian::SleepingDisabled,
            Transform::from_translation(spec.position.extend(0.0)),
        ));
    }
    ready(app)
}

/// The highest dynamic body's height after the run: a check that the scene did what it
/// should (the pyramid stands; the tumbler's boxes stay in the drum).
fn top(app: &mut App, dynamic: impl Fn(&World, Entity) -> bool) -> f32 {
    let world = app.world_mut();
    let entities: Vec<(Entity, f32)> = world
        .query::<(Entity, &Transform)>()
        .iter(world)
        .map(|(e, t)| (e, t.translation.y))
        .collect();
    entities
        .into_iter()
        .filter(|&(e, _)| dynamic(app.world(), e))
        .map(|(_, y)| y)
        .fold(f32::MIN, f32::max)
}

/// Milliseconds per step of `steps` steps after `warmup`.
fn time(mut step: impl FnMut(), warmup: u32, steps: u32) -> f64 {
    for _ in 0..warmup {
        step();
    }
    let start = Instant::now();
    for _ in 0..steps {
        step();
    }
    start.elapsed().as_secs_f64() * 1e3 / steps as f64
}

const ENGINES: [&str; 4] = ["carom", "bevy_carom", "bevy_rapier2d", "avian2d"];

/// One run of one engine on one scene: ms per step and the top body's height.
fn run(engine: &str, specs: &[Spec], warmup: u32, steps: u32) -> (f64, f32) {
    match engine {
        "carom" => {
            let mut world = plain_carom(specs);
            let ms = time(|| world.step(DT).expect("steps"), warmup, steps);
            let top = world
                .bodies()
                .filter(|b| b.is_dynamic())
                .map(|b| b.position().y)
                .fold(f32::MIN, f32::max);
            (ms, top)
        }
        "bevy_carom" => {
            let mut app = bevy_carom_app(specs);
            let ms = time(|| app.update(), warmup, steps);
            (
                ms,
                top(&mut app, |w, e| {
                    w.get::<bc::RigidBody>(e) == Some(&bc::RigidBody::Dynamic)
                }),
            )
        }
        "bevy_rapier2d" => {
            let mut app = rapier_app(specs);
            let ms = time(|| app.update(), warmup, steps);
            (
                ms,
                top(&mut app, |w, e| {
                    w.get::<rapier::RigidBody>(e) == Some(&rapier::RigidBody::Dynamic)
                }),
            )
        }
        _ => {
            let mut app = avian_app(specs);
            let ms = time(|| app.update(), warmup, steps);
            (
                ms,
                top(&mut app, |w, e| {
                    w.get::<avian::RigidBody>(e) == Some(&avian::RigidBody::Dynamic)
                }),
            )
        }
    }
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// The decimals that show `ms` to three significant figures, so a cell's range reads at the
/// precision of its median.
fn decimals(ms: f64) -> usize {
    match ms {
        ms if ms < 1.0 => 3,
        ms if ms < 10.0 => 2,
        ms if ms < 100.0 => 1,
        _ => 0,
    }
}

/// One engine's cell of the CSV table: the median and (fastest-slowest) round, ms per step,
/// and for all but the first engine the median's ratio to the first's.
fn cell(times: &mut [f64], first: Option<f64>) -> String {
    let min = times.iter().copied().fold(f64::MAX, f64::min);
    let max = times.iter().copied().fold(0.0, f64::max);
    let m = median(times);
    let d = decimals(m);
    let text = format!("{m:.d$} ({min:.d$}-{max:.d$})");
    match first {
        // Quoted: the ratio follows a comma.
        Some(first) => format!("\"{text}, {:.2}x\"", m / first),
        None => text,
    }
}

/// The table's name for an engine: carom without Bevy is "plain carom".
fn column(engine: &str) -> &str {
    match engine {
        "carom" => "plain carom",
        other => other,
    }
}

fn main() {
    let mut rounds = 3;
    let mut steps = 200;
    let mut csv = false;
    let mut scenes = vec!["pyramid", "large_pyramid", "tumbler"];
    let mut engines = ENGINES.to_vec();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{arg} needs a value"));
        match arg.as_str() {
            "--csv" => csv = true,
            "--rounds" => rounds = value().parse().expect("--rounds N"),
            "--steps" => steps = value().parse().expect("--steps N"),
            "--scene" => scenes = vec![Box::leak(value().into_boxed_str())],
            "--engine" => {
                let name = value();
                engines =
                    vec![ENGINES.into_iter().find(|e| *e == name).unwrap_or_else(|| {
                        panic!("unknown engine {name}: {}", ENGINES.join(", "))
                    })];
            }
            _ => {
                panic!(
                    "unknown argument {arg}: --csv, --rounds N, --steps N, --scene NAME, \
                     --engine NAME"
                )
            }
        }
    }
    // The human report goes where the table does not: standard error when the CSV is asked.
    let say = |line: String| {
        if csv {
            eprintln!("{line}");
        } else {
            println!("{line}");
        }
    };
    // One thread for all: carom's rayon pool, and Bevy's task pools (its multi-threaded
    // executor is not built in here).
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global()
        .expect("the first pool");
    let warmup = 60;
    say(format!(
        "{rounds} rounds of {steps} steps after {warmup}, engines alternating; ms per fixed step, median (min-max)"
    ));
    let mut table = vec![format!(
        "scene,bodies,{},top body's height (m)",
        engines
            .iter()
            .map(|e| column(e))
            .collect::<Vec<_>>()
            .join(",")
    )];
    for scene in scenes {
        let specs = match scene {
            "pyramid" => pyramid(20),
            "large_pyramid" => pyramid(100),
            "tumbler" => tumbler(),
            other => panic!("unknown scene {other}: pyramid, large_pyramid, tumbler"),
        };
        let mut times = vec![Vec::new(); engines.len()];
        let mut tops = vec![0.0; engines.len()];
        for round in 0..rounds {
            for k in 0..engines.len() {
                // Each round starts with the next engine, so none always runs first.
                let e = (k + round) % engines.len();
                let (ms, top) = run(engines[e], &specs, warmup, steps);
                times[e].push(ms);
                tops[e] = top;
            }
        }
        say(format!("\n{scene} ({} bodies)", specs.len()));
        // The first engine's median: plain carom's, unless one engine was asked for.
        let plain = median(&mut times[0].clone());
        for (e, engine) in engines.iter().enumerate() {
            let min = times[e].iter().copied().fold(f64::MAX, f64::min);
            let max = times[e].iter().copied().fold(0.0, f64::max);
            let m = median(&mut times[e].clone());
            say(format!(
                "  {engine:14} {m:8.3} ({min:.3}-{max:.3})  {:5.2}x plain carom  top body at y = {:.2}",
                m / plain,
                tops[e]
            ));
        }
        let cells: Vec<String> = times
            .iter_mut()
            .enumerate()
            .map(|(e, times)| cell(times, (e > 0).then_some(plain)))
            .collect();
        let tops: Vec<String> = tops.iter().map(|top| format!("{top:.2}")).collect();
        table.push(format!(
            "`{scene}`,{},{},{}",
            specs.len(),
            cells.join(","),
            tops.join(" / ")
        ));
    }
    if csv {
        for line in table {
            println!("{line}");
        }
    }
}
