//! `carom-bench`: times carom, Box2D v3 and Rapier on the same scenes, in turn, in one process:
//! carom and Box2D on one thread and on two, Rapier on one; counts heap allocations per step and
//! memory per body in all three (Box2D's routed through Rust's allocator to be counted).
//! `carom-bench hard-cases` runs the hard cases of `tests/stability.rs` in carom and in Box2D.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use carom_bench::hard_cases;
use carom_bench::scaling;
use carom_bench::sweep::cli::resolve;
use carom_bench::{Box2dWorld, RapierWorld, RunResult, run_box2d, run_carom, run_rapier};
use clap::{Parser, Subcommand};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};
use std::alloc::System;

/// Every allocation is counted, to report allocations per step and memory per body.
#[global_allocator]
static ALLOCATOR: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// Time step of every run, s (Box2D's benchmark).
const DT: f32 = 1.0 / 60.0;

/// Box2D's benchmark scenes and step counts, run when no scene is named.
const DEFAULT_SCENES: [(&str, u32); 8] = [
    ("demos/joint_grid.ron", 500),
    ("demos/large_pyramid.ron", 500),
    ("demos/many_pyramids.ron", 200),
    ("demos/tumbler.ron", 750),
    ("demos/smash.ron", 300),
    ("demos/compounds.ron", 500),
    ("demos/ragdoll_rain.ron", 1000),
    ("demos/spinner.ron", 500),
];

/// Steps for a scene not in [`DEFAULT_SCENES`] when `--steps` is not given.
const FALLBACK_STEPS: u32 = 500;

/// Times carom, Box2D and Rapier on the same scenes: dt 1/60, first step untimed, minimum over
/// runs.
#[derive(Parser, Debug)]
#[command(name = "carom-bench", args_conflicts_with_subcommands = true)]
struct Args {
    #[command(subcommand)]
    command: Option<Command>,
    /// Scene files (default: Box2D's recipes with its step counts: demos/joint_grid.ron, 500
    /// steps; demos/large_pyramid.ron, 500; demos/many_pyramids.ron, 200; demos/tumbler.ron,
    /// 750; demos/smash.ron, 300; demos/compounds.ron, 500; demos/ragdoll_rain.ron, 1000;
    /// demos/spinner.ron, 500).
    scenes: Vec<PathBuf>,
    /// Steps per run, overriding each scene's default.
    #[arg(long)]
    steps: Option<u32>,
    /// Runs per engine, each from a fresh copy of the scene; the fastest is kept.
    #[arg(long, default_value_t = 3)]
    runs: u32,
    /// Also write the table as CSV to this file.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Also write carom's and Box2D's stage profiles and the work behind them as CSV to this
    /// file.
    #[arg(long)]
    stages_csv: Option<PathBuf>,
    /// Threads for the multi-threaded runs of carom and Box2D.
    #[arg(long, default_value_t = 2)]
    threads: usize,
    #[command(flatten)]
    carom: CaromOptions,
}

/// carom's options that the timing runs and profiles can turn on (the scene's own are kept).
/// The timing run and `profile` take them each, not as flags global to every command: the
/// accuracy sweep has options of these names with values of its own (`--direct-joints
/// off,on`), which a global flag's default would take the place of.
#[derive(Debug, Clone, Copy, clap::Args)]
struct CaromOptions {
    /// Step carom with shock propagation (heavy bodies held by the light ones under them);
    /// the peers step as they always do.
    #[arg(long)]
    shock_propagation: bool,
    /// Step carom with direct joints (each tree of hinges solved at once); the peers step as
    /// they always do.
    #[arg(long)]
    direct_joints: bool,
    /// Step carom without contacts that look a step ahead (`WorldSettings::look_ahead` off):
    /// continuous collision as Box2D's, fast bodies swept against static ones only; the peers
    /// step as they always do.
    #[arg(long)]
    no_look_ahead: bool,
}

impl CaromOptions {
    /// `world`'s settings with these options turned on.
    fn apply(self, world: &mut carom::World) -> Result<(), String> {
        world
            .update_settings(|s| {
                s.solver.shock_propagation |= self.shock_propagation;
                s.solver.direct_joints |= self.direct_joints;
                s.look_ahead &= !self.no_look_ahead;
            })
            .map_err(|e| e.to_string())
    }
}

/// Other jobs than timing.
#[derive(Subcommand, Debug)]
enum Command {
    /// Times taking a snapshot of a scene and restoring it beside one step (on one thread and
    /// on `--threads`), and counts a snapshot's bytes: by default on demos/large_pyramid.ron
    /// and demos/mixed_1000.ron.
    Snapshots {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// Steps before the timed rounds.
        #[arg(long, default_value_t = 100)]
        warm_up: u32,
        /// Timed rounds of snapshot, step and restore; medians are reported.
        #[arg(long, default_value_t = 60)]
        rounds: u32,
        /// Also write the table as CSV to this file (docs/bench/snapshots.csv is the one the
        /// docs draw from).
        #[arg(long)]
        csv: Option<PathBuf>,
    },
    /// Plays a scene for a long run with the demo's timeline (a keyframe every 20 steps in
    /// 192 MB, older ones thinned past it), and reports the memory its keyframes take as the
    /// run grows and the time to go back to steps across it: by default ten minutes of
    /// demos/mixed_1000.ron.
    Timeline {
        /// The scene file.
        #[arg(default_value = "demos/mixed_1000.ron")]
        scene: PathBuf,
        /// Steps to play (36,000 is ten minutes at 60 Hz).
        #[arg(long, default_value_t = 36_000)]
        steps: u64,
    },
    /// Steps one engine's copy of a scene alone and prints its ms per step and stage profile:
    /// the run to hand a profiler (`perf record`, `valgrind --tool=callgrind`), with nothing
    /// of the other engines in it. carom fires the scene's events; the peers follow its spawn
    /// schedule, as in the timing runs.
    Profile {
        /// The scene file.
        scene: PathBuf,
        /// The engine to step: carom, box2d or rapier.
        #[arg(long, default_value = "carom", value_parser = ["carom", "box2d", "rapier"])]
        engine: String,
        /// Steps, the first untimed (default: the scene's own count in the timing runs).
        #[arg(long)]
        steps: Option<u32>,
        /// Threads (carom) or workers (Box2D); Rapier always steps on one.
        #[arg(long, default_value_t = 1)]
        threads: usize,
        #[command(flatten)]
        carom: CaromOptions,
    },
    /// Times rows of Box2D's base-10 pyramids at about 1k, 5k, 20k and 100k boxes in every
    /// engine (one thread and `--threads`), and writes scaling.csv, scaling.md and a log-log
    /// chart of ms per step against bodies, scaling.png, to `--out`.
    Scaling {
        /// Folder for the CSV, table and chart.
        #[arg(long, default_value = "target/bench")]
        out: PathBuf,
        /// Steps per run (the first untimed).
        #[arg(long, default_value_t = 100)]
        steps: u32,
        /// Runs per engine and size; the fastest is kept.
        #[arg(long, default_value_t = 1)]
        runs: u32,
        /// Only sizes up to this many bodies.
        #[arg(long)]
        max_bodies: Option<usize>,
    },
    /// Measures what accuracy costs in time: every solver setting of carom, Box2D and Rapier
    /// on the scenes whose exact answer is known, each point's ms per step and error. Writes
    /// accuracy.csv, README.md (the tables) and accuracy.png (each engine's front) to --out
    /// (default docs/accuracy).
    Sweep(carom_bench::sweep::cli::SweepArgs),
    /// Draws the figures of README.md and docs/ again from the measurements committed in
    /// docs/ (docs/accuracy/accuracy.csv, docs/hard-cases/hard-cases.csv,
    /// docs/bench/peers.csv, docs/bench/stages.csv, docs/bench/snapshots.csv,
    /// docs/effects/effect-cost.csv, and the tables `carom-bench measure` wrote): every part
    /// marked `<!-- figures: NAME -->`, the accuracy report and its chart.
    Docs {
        /// Write nothing; fail when a doc differs from what would be drawn.
        #[arg(long)]
        check: bool,
    },
    /// Times carom with contacts that look a step ahead (its default) and without (Box2D's
    /// promise), beside Box2D, on one thread, with the deepest overlap each lets a step start
    /// from; writes the table to `--out` for docs/bench to draw (by default Box2D's eight
    /// recipes, each for its step count).
    LookAhead {
        /// The CSV file to write.
        #[arg(long, default_value = "docs/bench/look-ahead.csv")]
        out: PathBuf,
        /// Scene files (default: the eight recipes).
        scenes: Vec<PathBuf>,
        /// Runs of each; the fastest is kept.
        #[arg(long, default_value_t = 3)]
        runs: u32,
    },
    /// Runs a measuring program that prints a table as CSV on its standard output (a header
    /// line, then the rows), and writes the table to FILE under lines naming the machine, the
    /// date and this command, for a doc to draw with `<!-- figures: table FILE -->`. FILE is
    /// left as it was when the program fails or prints no table.
    Measure {
        /// The CSV file to write.
        file: PathBuf,
        /// Runs behind each figure, as the program's own options set them (recorded).
        #[arg(long, default_value_t = 1)]
        runs: usize,
        /// The program and its arguments, after `--`.
        #[arg(last = true, required = true)]
        command: Vec<String>,
    },
    /// Runs every hard case of tests/stability.rs in each of carom's solvers, in soft step with
    /// each of its options, and in Box2D v3 with the same geometry and settings, and prints the
    /// table: case, measure, bar, a column each (a figure that misses its bar is bold). The
    /// whole run writes hard-cases.csv to --out, which the docs' tables are drawn from.
    HardCases {
        /// Only the cases whose name contains this (repeatable), e.g. `vertical_stack`; the
        /// table is then printed, not written.
        #[arg(long)]
        case: Vec<String>,
        /// Folder for hard-cases.csv (with --check: where the committed table is read from).
        #[arg(long, default_value = "docs/hard-cases")]
        out: PathBuf,
        /// Soak one simulated minute instead of an hour; the table is then printed, not
        /// written.
        #[arg(long)]
        quick: bool,
        /// Write nothing; compare every figure with --out's hard-cases.csv, failing where
        /// they differ (with --quick, the soak is not compared).
        #[arg(long)]
        check: bool,
        /// Cases run at once (default: every core).
        #[arg(long)]
        jobs: Option<usize>,
    },
}

/// One table row.
struct Row {
    scene: String,
    bodies: usize,
    /// carom on one thread.
    carom: RunResult,
    /// carom on `--threads` threads.
    carom_threads: RunResult,
    rapier: RunResult,
    /// Box2D v3 on one worker.
    box2d: RunResult,
    /// Box2D v3 on `--threads` workers (its own scheduler).
    box2d_threads: RunResult,
    /// Heap bytes live after a run, per body (Box2D's own count of its bytes).
    carom_bytes_per_body: f64,
    rapier_bytes_per_body: f64,
    box2d_bytes_per_body: f64,
    /// What the peers' copies leave out or approximate, each line naming its engine.
    notes: Vec<String>,
}

impl Row {
    /// ms/step of carom on one thread, on several, of Rapier and of Box2D.
    fn ms_per_step(&self) -> (f64, f64, f64, f64) {
        (
            self.carom.ms_per_step(),
            self.carom_threads.ms_per_step(),
            self.rapier.ms_per_step(),
            self.box2d.ms_per_step(),
        )
    }

    /// Box2D's speed-up on several workers.
    fn box2d_speedup(&self) -> f64 {
        self.box2d.ms_per_step() / self.box2d_threads.ms_per_step()
    }
}

/// Live heap bytes that `build` leaves, per body, with what it built kept alive for `use_it`.
fn bytes_per_body<T>(
    bodies: usize,
    build: impl FnOnce() -> Result<T, String>,
    use_it: impl FnOnce(&mut T) -> Result<(), String>,
) -> Result<(f64, T), String> {
    let region = Region::new(&INSTRUMENTED_SYSTEM);
    let mut built = build()?;
    use_it(&mut built)?;
    let change = region.change();
    let live = change.bytes_allocated as f64 - change.bytes_deallocated as f64
        + change.bytes_reallocated as f64;
    Ok((live / bodies.max(1) as f64, built))
}

fn default_steps(path: &Path) -> u32 {
    DEFAULT_SCENES
        .iter()
        .find(|(p, _)| path.ends_with(p) || Path::new(p).file_name() == path.file_name())
        .map_or(FALLBACK_STEPS, |(_, s)| *s)
}

/// Keeps the faster run's time and stage profile; accuracy figures are those of the first
/// run.
fn keep_min(best: Option<RunResult>, run: RunResult) -> RunResult {
    match best {
        Some(b) if b.total_ms <= run.total_ms => b,
        Some(b) => RunResult {
            total_ms: run.total_ms,
            stages: run.stages,
            ..b
        },
        None => run,
    }
}

fn bench_scene(
    path: &Path,
    (steps, runs): (u32, u32),
    options: CaromOptions,
    one: &rayon::ThreadPool,
    many: &rayon::ThreadPool,
) -> Result<Row, String> {
    let path = &resolve(path);
    let load = || {
        let mut scene = carom_scene::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
        options.apply(&mut scene.world)?;
        Ok(scene)
    };
    let mut name = path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into(),
    );
    let named = [
        (options.shock_propagation, "shock propagation"),
        (options.direct_joints, "direct joints"),
        (options.no_look_ahead, "no look-ahead"),
    ];
    let on: Vec<&str> = named
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, n)| *n)
        .collect();
    if !on.is_empty() {
        name += &format!(" (carom: {})", on.join(", "));
    }
    bench_world(&name, load, steps, runs, one, many)
}

/// Times the scene `load` builds (afresh for every run) in every engine, each stepped by
/// [`DT`]: carom fires the scene's events as the demo does, and the peers make and remove the
/// bodies of its spawn events before the same steps (the scene's schedule of them, written
/// out before timing); its other events are not replayed in the peers, and noted.
fn bench_world(
    name: &str,
    load: impl Fn() -> Result<carom_scene::SceneWorld, String>,
    steps: u32,
    runs: u32,
    one: &rayon::ThreadPool,
    many: &rayon::ThreadPool,
) -> Result<Row, String> {
    let load = || {
        let mut scene = load()?;
        scene.time_step = DT;
        Ok::<_, String>(scene)
    };
    let schedule = load()?.spawn_schedule(u64::from(steps))?;
    let replayed = (!schedule.changes.is_empty()).then_some(&schedule);
    let path = Path::new(name);
    let (mut carom_best, mut threads_best, mut rapier_best) = (None, None, None);
    let (mut box2d_best, mut box2d_threads_best) = (None, None);
    let (mut bodies, mut carom_bytes, mut rapier_bytes, mut box2d_bytes) = (0, 0.0, 0.0, 0.0);
    let mut notes = Vec::new();
    for event in &schedule.other_events {
        for peer in ["Box2D", "Rapier"] {
            notes.push(format!(
                "{peer}: a {event} event: not replayed (only spawns are; carom fires it)"
            ));
        }
    }
    for run in 1..=runs {
        // carom on one thread; its memory is what the world holds after the run.
        let mut result = None;
        let (bytes, scene) = bytes_per_body(1, load, |scene| {
            result = Some(one.install(|| run_carom(scene, steps))?);
            Ok(())
        })?;
        bodies = scene.world.body_count();
        carom_bytes = bytes / bodies.max(1) as f64;
        let c = result.ok_or("no carom run")?;
        eprintln!(
            "{} run {run}: carom {:.3} ms/step",
            path.display(),
            c.ms_per_step()
        );
        carom_best = Some(keep_min(carom_best, c));
        drop(scene);

        let mut scene = load()?;
        let t = many.install(|| run_carom(&mut scene, steps))?;
        eprintln!(
            "{} run {run}: carom on {} threads {:.3} ms/step",
            path.display(),
            many.current_num_threads(),
            t.ms_per_step()
        );
        threads_best = Some(keep_min(threads_best, t));
        drop(scene);

        let scene = load()?;
        let mut result = None;
        let (bytes, rapier) = bytes_per_body(
            bodies,
            || RapierWorld::from_carom(&scene.world, DT),
            |rapier| {
                result = Some(run_rapier(rapier, steps, replayed)?);
                Ok(())
            },
        )?;
        rapier_bytes = bytes;
        if run == 1 {
            notes.extend(
                rapier
                    .notes()
                    .lines()
                    .into_iter()
                    .map(|l| format!("Rapier: {l}")),
            );
        }
        drop(rapier);
        drop(scene);
        let r = result.ok_or("no Rapier run")?;
        eprintln!(
            "{} run {run}: Rapier {:.3} ms/step",
            path.display(),
            r.ms_per_step()
        );
        rapier_best = Some(keep_min(rapier_best, r));

        let mut time_box2d = |workers: usize| -> Result<RunResult, String> {
            let scene = load()?;
            let mut box2d = Box2dWorld::with_workers(&scene.world, workers as u32)?;
            drop(scene);
            let b = run_box2d(&mut box2d, DT, steps, replayed)?;
            if workers == 1 {
                let bytes = box2d.counters()?.byte_count as f64;
                box2d_bytes = bytes / box2d.native_body_count()?.max(1) as f64;
            }
            // After the run: the spawned copies' joints are noted as they are made.
            if run == 1 && workers == 1 {
                notes.extend(
                    box2d
                        .notes()
                        .lines()
                        .into_iter()
                        .map(|l| format!("Box2D: {l}")),
                );
            }
            let on = match workers {
                1 => String::new(),
                n => format!(" on {n} threads"),
            };
            eprintln!(
                "{} run {run}: Box2D{on} {:.3} ms/step",
                path.display(),
                b.ms_per_step()
            );
            Ok(b)
        };
        box2d_best = Some(keep_min(box2d_best, time_box2d(1)?));
        let b = time_box2d(many.current_num_threads())?;
        box2d_threads_best = Some(keep_min(box2d_threads_best, b));
    }
    Ok(Row {
        scene: name.to_string(),
        bodies,
        carom: carom_best.ok_or("no runs")?,
        carom_threads: threads_best.ok_or("no runs")?,
        rapier: rapier_best.ok_or("no runs")?,
        box2d: box2d_best.ok_or("no runs")?,
        box2d_threads: box2d_threads_best.ok_or("no runs")?,
        carom_bytes_per_body: carom_bytes,
        rapier_bytes_per_body: rapier_bytes,
        box2d_bytes_per_body: box2d_bytes,
        notes,
    })
}

/// The top drop, or a dash for a scene that starts with no dynamic body to follow.
fn drop_cell(r: &RunResult) -> String {
    if r.nan {
        format!("{:.3} (NaN!)", r.top_drop)
    } else if r.top_drop.is_nan() {
        "—".to_string()
    } else {
        format!("{:.3}", r.top_drop)
    }
}

fn markdown(rows: &[Row], threads: usize) -> String {
    let mut s = format!(
        "| scene | bodies | carom ms/step | Box2D ms/step | Rapier ms/step | carom / Box2D | \
         carom / Rapier | carom on {threads} threads ms/step | carom speed-up | \
         Box2D on {threads} threads ms/step | Box2D speed-up | \
         carom top drop m | Box2D top drop m | Rapier top drop m |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let (c, t, p, b) = r.ms_per_step();
        let _ = writeln!(
            s,
            "| {} | {} | {c:.3} | {b:.3} | {p:.3} | {:.2} | {:.2} | {t:.3} | {:.2} | {:.3} | {:.2} \
             | {} | {} | {} |",
            r.scene,
            r.bodies,
            c / b,
            c / p,
            c / t,
            r.box2d_threads.ms_per_step(),
            r.box2d_speedup(),
            drop_cell(&r.carom),
            drop_cell(&r.box2d),
            drop_cell(&r.rapier)
        );
    }
    let _ = write!(
        s,
        "\n| scene | carom allocations/step | on {threads} threads | Box2D allocations/step | \
         Rapier allocations/step | carom bytes/body | Box2D bytes/body | Rapier bytes/body |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.2} | {:.2} | {:.2} | {:.1} | {:.0} | {:.0} | {:.0} |",
            r.scene,
            r.carom.allocations_per_step(),
            r.carom_threads.allocations_per_step(),
            r.box2d.allocations_per_step(),
            r.rapier.allocations_per_step(),
            r.carom_bytes_per_body,
            r.box2d_bytes_per_body,
            r.rapier_bytes_per_body
        );
    }
    s.push_str(&stage_tables(rows));
    s.push('\n');
    s.push_str(&carom_bench::projection::markdown(&projection_rows(
        rows, threads,
    )));
    s
}

/// carom's and Box2D's stages on one thread and on several, for the projection.
fn projection_rows(rows: &[Row], threads: usize) -> Vec<carom_bench::projection::Measured> {
    let mut out = Vec::new();
    for r in rows {
        for (engine, one, many) in [
            ("carom", &r.carom, &r.carom_threads),
            ("Box2D", &r.box2d, &r.box2d_threads),
        ] {
            if let (Some(one), Some(many)) = (one.stages, many.stages) {
                out.push(carom_bench::projection::Measured {
                    scene: r.scene.clone(),
                    engine: engine.into(),
                    threads,
                    one: one.ms(),
                    many: many.ms(),
                });
            }
        }
    }
    out
}

/// Where each engine's step goes (one thread, the fastest run's means per step, ms; Box2D's
/// profile mapped onto carom's stages) and the work behind it.
fn stage_tables(rows: &[Row]) -> String {
    let engines = |r: &Row| [("carom", r.carom.stages), ("Box2D", r.box2d.stages)];
    let mut s = String::from(
        "\nms per step by stage, one thread (Box2D: broadphase = pairs + refit, narrowphase = \
         collide, continuous = bullets, sleep = sleep islands + split islands, solve = the rest \
         of its solve):\n\n\
         | scene | engine | step | broadphase | narrowphase | solve | continuous | sleep | other |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        for (engine, stages) in engines(r) {
            let Some(p) = stages else { continue };
            let other = p.step_ms
                - p.broadphase_ms
                - p.narrowphase_ms
                - p.solve_ms
                - p.continuous_ms
                - p.sleep_ms;
            let _ = writeln!(
                s,
                "| {} | {engine} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {other:.3} |",
                r.scene,
                p.step_ms,
                p.broadphase_ms,
                p.narrowphase_ms,
                p.solve_ms,
                p.continuous_ms,
                p.sleep_ms
            );
        }
    }
    s.push_str(
        "\nWork per step, one thread (means; – where the engine does not count it):\n\n\
         | scene | engine | contacts | awake contacts | recycled | touching | created | \
         destroyed | proxies moved | pair candidates | island splits |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let cell = |x: f64| {
        if x.is_nan() {
            "–".to_string()
        } else {
            format!("{x:.0}")
        }
    };
    for r in rows {
        for (engine, stages) in engines(r) {
            let Some(p) = stages else { continue };
            let _ = writeln!(
                s,
                "| {} | {engine} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r.scene,
                cell(p.contacts),
                cell(p.awake_contacts),
                cell(p.recycled),
                cell(p.touching),
                cell(p.created),
                cell(p.destroyed),
                cell(p.proxies_moved),
                cell(p.candidates),
                if p.island_splits.is_nan() {
                    "–".to_string()
                } else {
                    format!("{:.3}", p.island_splits)
                }
            );
        }
    }
    s
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "scene,bodies,carom_ms_per_step,rapier_ms_per_step,carom_rapier_ratio,\
         carom_threads_ms_per_step,thread_speedup,carom_top_drop_m,rapier_top_drop_m,carom_nan,\
         rapier_nan,carom_allocations_per_step,rapier_allocations_per_step,\
         carom_bytes_per_body,rapier_bytes_per_body,box2d_ms_per_step,carom_box2d_ratio,\
         box2d_top_drop_m,box2d_nan,box2d_threads_ms_per_step,box2d_thread_speedup,\
         box2d_allocations_per_step,box2d_bytes_per_body\n",
    );
    for r in rows {
        let (c, t, p, b) = r.ms_per_step();
        let _ = writeln!(
            s,
            "{},{},{c:.4},{p:.4},{:.4},{t:.4},{:.4},{:.4},{:.4},{},{},{:.2},{:.2},{:.0},{:.0},\
             {b:.4},{:.4},{:.4},{},{:.4},{:.4},{:.2},{:.0}",
            r.scene,
            r.bodies,
            c / p,
            c / t,
            r.carom.top_drop,
            r.rapier.top_drop,
            r.carom.nan,
            r.rapier.nan,
            r.carom.allocations_per_step(),
            r.rapier.allocations_per_step(),
            r.carom_bytes_per_body,
            r.rapier_bytes_per_body,
            c / b,
            r.box2d.top_drop,
            r.box2d.nan,
            r.box2d_threads.ms_per_step(),
            r.box2d_speedup(),
            r.box2d.allocations_per_step(),
            r.box2d_bytes_per_body
        );
    }
    s
}

/// What `carom-bench hard-cases` was asked.
struct HardCaseArgs<'a> {
    filter: &'a [String],
    out: &'a Path,
    quick: bool,
    check: bool,
    jobs: Option<usize>,
}

/// `carom-bench hard-cases`: runs the cases `filter` names (all if empty) in every column and
/// prints the table; writes it for a whole run, or with `check` compares it with the
/// committed one.
fn hard_cases(args: HardCaseArgs) -> Result<(), String> {
    use hard_cases::table::{self, Column};
    let started = std::time::Instant::now();
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let rows = table::run(
        args.filter,
        &Column::ALL,
        args.quick,
        jobs,
        |done, total, what| {
            eprintln!("[{done}/{total}] {what}");
        },
    )?;
    let seconds = started.elapsed().as_secs_f64();
    let path = args.out.join("hard-cases.csv");
    if args.check {
        let committed = std::fs::read_to_string(&path)
            .map_err(|e| format!("{}: {e}", path.display()))
            .and_then(|text| {
                table::parse_csv(&text).map_err(|e| format!("{}: {e}", path.display()))
            })?;
        // The quick soak is a minute: its figures are not the hour's.
        let skip: &[&str] = if args.quick { &["soak_one_hour"] } else { &[] };
        let differences = table::differences(&rows, &committed, skip);
        for line in &differences {
            eprintln!("{line}");
        }
        if !differences.is_empty() {
            return Err(format!(
                "{} of {} figures differ from {}: run `carom-bench hard-cases` and commit what \
                 it writes",
                differences.len(),
                rows.len(),
                path.display()
            ));
        }
        eprintln!(
            "{} figures in {seconds:.0} s: every one as in {}{}",
            rows.len(),
            path.display(),
            if args.quick {
                " (the soak left out)"
            } else {
                ""
            }
        );
        return Ok(());
    }
    let mut names: Vec<&str> = Vec::new();
    for row in &rows {
        if !names.contains(&row.case.as_str()) {
            names.push(&row.case);
        }
    }
    print!("{}", table::markdown(&rows, &names, &Column::ALL));
    if args.filter.is_empty() && !args.quick {
        std::fs::create_dir_all(args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
        write_measured(&path, 1, &table::csv(&rows))?;
        eprintln!(
            "{} figures in {seconds:.0} s -> {}",
            rows.len(),
            path.display()
        );
    }
    Ok(())
}

/// This command as typed, the program named `carom-bench` wherever it was run from.
/// Writes `csv` to `path` under the `# measured/machine/cores/command/runs` lines that say
/// where, when and how it was measured (`runs` per point), as the docs' figures need.
fn write_measured(path: &Path, runs: usize, csv: &str) -> Result<(), String> {
    let provenance = carom_bench::sweep::report::Provenance {
        machine: carom_bench::sweep::report::Machine::here(),
        command: typed_command(),
        runs,
    };
    std::fs::write(path, provenance.header() + csv).map_err(|e| format!("{}: {e}", path.display()))
}

/// `carom-bench measure`: runs `command` (its standard error shown as it goes) and writes the
/// table it printed to `file` under the provenance lines.
fn measure(file: &Path, runs: usize, command: &[String]) -> Result<(), String> {
    let (program, arguments) = command.split_first().ok_or("no command to run")?;
    eprintln!("running: {}", command.join(" "));
    let output = std::process::Command::new(program)
        .args(arguments)
        .stderr(std::process::Stdio::inherit())
        .output()
        .map_err(|e| format!("{program}: {e}"))?;
    if !output.status.success() {
        return Err(format!("`{}` failed: {}", command.join(" "), output.status));
    }
    let csv = String::from_utf8(output.stdout)
        .map_err(|_| format!("`{}` printed what is not UTF-8", command.join(" ")))?;
    let provenance = carom_bench::sweep::report::Provenance {
        machine: carom_bench::sweep::report::Machine::here(),
        command: typed_command(),
        runs,
    };
    let text = carom_bench::measured::write(&provenance, &csv)
        .map_err(|e| format!("`{}` printed no table: {e}", command.join(" ")))?;
    if let Some(folder) = file.parent().filter(|f| !f.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    }
    std::fs::write(file, &text).map_err(|e| format!("{}: {e}", file.display()))?;
    print!("{text}");
    Ok(())
}

/// `carom-bench look-ahead`: each scene (the recipes when none is named) timed with and
/// without look-ahead and in Box2D, on one thread; the table is written to `out`.
fn look_ahead(
    out: &Path,
    scenes: &[PathBuf],
    runs: u32,
    one: &rayon::ThreadPool,
) -> Result<(), String> {
    let scenes: Vec<PathBuf> = if scenes.is_empty() {
        DEFAULT_SCENES
            .iter()
            .map(|(p, _)| PathBuf::from(p))
            .collect()
    } else {
        scenes.to_vec()
    };
    let mut rows = Vec::new();
    for scene in &scenes {
        let path = resolve(scene);
        let name = path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into(),
        );
        let load = || carom_scene::load(&path).map_err(|e| format!("{}: {e}", path.display()));
        let steps = default_steps(scene);
        rows.push(one.install(|| carom_bench::look_ahead::measure(&name, load, steps, runs, DT))?);
    }
    let provenance = carom_bench::sweep::report::Provenance {
        machine: carom_bench::sweep::report::Machine::here(),
        command: typed_command(),
        runs: runs as usize,
    };
    let text = carom_bench::measured::write(&provenance, &carom_bench::look_ahead::csv(&rows))?;
    if let Some(folder) = out.parent().filter(|f| !f.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    }
    std::fs::write(out, &text).map_err(|e| format!("{}: {e}", out.display()))?;
    print!("{text}");
    Ok(())
}

/// This command as a shell would take it again: an argument holding anything but plain
/// characters is single-quoted.
fn typed_command() -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./=:,+-@%".contains(c);
    let command: Vec<String> = std::env::args()
        .enumerate()
        .map(|(i, a)| {
            if i == 0 {
                "carom-bench".into()
            } else if !a.is_empty() && a.chars().all(plain) {
                a
            } else {
                format!("'{}'", a.replace('\'', r"'\''"))
            }
        })
        .collect();
    command.join(" ")
}

/// Times the pyramid rows of [`scaling::SIZES`] in every engine and writes the CSV, table and
/// chart to `out`.
/// `carom-bench timeline`: the timeline's memory over a long run of `scene`, and the time to go
/// back to steps across it.
fn timeline_run(scene: &Path, steps: u64) -> Result<(), String> {
    // The file is read once: the recording keeps the text the world is built from.
    let name = scene.display().to_string();
    let text = std::fs::read_to_string(scene).map_err(|e| format!("{name}: {e}"))?;
    let recording = carom_scene::Recording::new(&name, &text);
    let mut world = recording.start().map_err(|e| e.to_string())?;
    let heap =
        |stats: stats_alloc::Stats| stats.bytes_allocated as f64 - stats.bytes_deallocated as f64;
    let region = Region::new(&INSTRUMENTED_SYSTEM);
    let mut timeline = carom_scene::Timeline::new(recording, &world);
    let started = std::time::Instant::now();
    let growth =
        carom_bench::timeline_cost::play(&mut world, &mut timeline, steps, (steps / 6).max(1))
            .map_err(|e| e.to_string())?;
    let played = started.elapsed();
    let live = heap(region.change());
    let mb = |bytes: f64| bytes / (1 << 20) as f64;
    println!(
        "{} played {steps} steps in {:.1} s ({} bodies at the end), a keyframe every {} steps \
         within {:.0} MB\n",
        scene.display(),
        played.as_secs_f64(),
        world.world.body_count(),
        carom_scene::KEYFRAME_EVERY,
        mb(carom_scene::KEYFRAME_BUDGET as f64)
    );
    println!("| steps | keyframes | timeline, MB |\n|---|---|---|");
    for g in &growth {
        println!(
            "| {} | {} | {:.1} |",
            g.steps,
            g.keyframes,
            mb(g.bytes as f64)
        );
    }
    println!(
        "\nheap the timeline and the world hold at the end, counted by the allocator: {:.1} MB\n",
        mb(live)
    );
    let kept: Vec<String> = timeline.keyframe_steps().map(|s| s.to_string()).collect();
    println!("keyframes at steps {}\n", kept.join(", "));
    let end = timeline.end();
    let targets: Vec<u64> = [0.01, 0.25, 0.5, 0.75, 0.9, 0.99]
        .iter()
        .map(|f| (end as f64 * f) as u64)
        .chain([end - 1])
        .collect();
    let seeks = carom_bench::timeline_cost::seeks(&mut world, &mut timeline, &targets)
        .map_err(|e| e.to_string())?;
    println!("| go to step | steps replayed from its keyframe | ms |\n|---|---|---|");
    for seek in &seeks {
        println!(
            "| {} | {} | {:.1} |",
            seek.to,
            seek.replayed,
            seek.time.as_secs_f64() * 1e3
        );
    }
    Ok(())
}

/// `carom-bench snapshots`: the table of what a snapshot and a restore cost beside a step.
fn snapshots_run(
    scenes: &[PathBuf],
    (warm_up, rounds): (u32, u32),
    csv: Option<&Path>,
    (one, many): (&rayon::ThreadPool, &rayon::ThreadPool),
) -> Result<(), String> {
    if rounds == 0 {
        return Err("--rounds must be at least 1".into());
    }
    let defaults = [
        PathBuf::from("demos/large_pyramid.ron"),
        PathBuf::from("demos/mixed_1000.ron"),
    ];
    let scenes = if scenes.is_empty() {
        &defaults[..]
    } else {
        scenes
    };
    let pools = if many.current_num_threads() > 1 {
        vec![one, many]
    } else {
        vec![one]
    };
    println!(
        "{warm_up} steps, then {rounds} rounds of snapshot, step, restore; medians, ms \
         (bytes: the heap a new snapshot takes)\n"
    );
    println!(
        "| scene | bodies | threads | step | snapshot | restore | (snapshot + restore) / step | \
         bytes | bytes per body |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut rows = String::from("scene,bodies,threads,step_ms,snapshot_ms,restore_ms,bytes\n");
    for path in scenes {
        for &pool in &pools {
            let mut scene = carom_scene::load(path).map_err(|e| e.to_string())?;
            let cost =
                pool.install(|| carom_bench::snapshot_cost::measure(&mut scene, warm_up, rounds))?;
            let region = Region::new(&INSTRUMENTED_SYSTEM);
            let snapshot = scene.world.snapshot();
            let bytes = region.change().bytes_allocated;
            drop(snapshot);
            let bodies = scene.world.body_count();
            let ms = |d: std::time::Duration| format!("{:.3}", d.as_secs_f64() * 1e3);
            println!(
                "| {} | {bodies} | {} | {} | {} | {} | {:.2} | {bytes} | {:.0} |",
                path.display(),
                pool.current_num_threads(),
                ms(cost.step.median),
                ms(cost.snapshot.median),
                ms(cost.restore.median),
                cost.ratio(),
                bytes as f64 / bodies.max(1) as f64,
            );
            let scene_name = path.file_stem().map_or_else(
                || path.display().to_string(),
                |s| s.to_string_lossy().into_owned(),
            );
            let _ = writeln!(
                rows,
                "{scene_name},{bodies},{},{},{},{},{bytes}",
                pool.current_num_threads(),
                ms(cost.step.median),
                ms(cost.snapshot.median),
                ms(cost.restore.median),
            );
        }
    }
    if let Some(path) = csv {
        write_measured(path, 1, &rows)?;
    }
    Ok(())
}

fn scaling_run(
    out: &Path,
    steps: u32,
    runs: u32,
    max_bodies: Option<usize>,
    (one, many): (&rayon::ThreadPool, &rayon::ThreadPool),
) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let threads = many.current_num_threads();
    let mut points = Vec::new();
    for (rows, columns) in scaling::SIZES {
        let text = scaling::pyramid_rows(rows, columns);
        let name = format!("pyramids_{rows}x{columns}");
        let load = || {
            let scene = carom_scene::parse(&text, &name).map_err(|e| e.to_string())?;
            carom_scene::build(&scene, &name).map_err(|e| e.to_string())
        };
        let bodies = load()?.world.body_count();
        if max_bodies.is_some_and(|max| bodies > max) {
            continue;
        }
        let row = bench_world(&name, load, steps, runs, one, many)?;
        let (c, t, p, b) = row.ms_per_step();
        for (engine, ms) in [
            ("carom, 1 thread".to_string(), c),
            (format!("carom, {threads} threads"), t),
            ("Box2D v3, 1 thread".to_string(), b),
            (
                format!("Box2D v3, {threads} threads"),
                row.box2d_threads.ms_per_step(),
            ),
            ("Rapier, 1 thread".to_string(), p),
        ] {
            points.push(scaling::Point {
                engine,
                bodies: row.bodies,
                ms_per_step: ms,
            });
        }
    }
    let table = scaling::markdown(&points);
    let write = |file: &str, text: &str| {
        let path = out.join(file);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    write("scaling.csv", &scaling::csv(&points))?;
    write("scaling.md", &table)?;
    scaling::write_chart(&points, &out.join("scaling.png"))?;
    println!(
        "dt 1/60, {steps} steps (the first untimed), best of {runs} run(s), ms per step\n\n{table}"
    );
    Ok(())
}

/// `carom-bench profile`: one engine's copy of `scene` stepped `steps` times on `threads`.
fn profile_run(
    scene: &Path,
    engine: &str,
    steps: u32,
    options: CaromOptions,
    threads: rayon::ThreadPool,
) -> Result<(), String> {
    if steps < 2 {
        return Err("profile needs --steps of at least 2 (the first is untimed)".into());
    }
    let path = resolve(scene);
    let load = || -> Result<carom_scene::SceneWorld, String> {
        let mut scene = carom_scene::load(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        scene.time_step = DT;
        if engine == "carom" {
            options.apply(&mut scene.world)?;
        }
        Ok(scene)
    };
    let schedule = load()?.spawn_schedule(u64::from(steps))?;
    let replayed = (!schedule.changes.is_empty()).then_some(&schedule);
    let workers = threads.current_num_threads();
    let result = match engine {
        "carom" => threads.install(|| run_carom(&mut load()?, steps))?,
        "box2d" => {
            let mut box2d = Box2dWorld::with_workers(&load()?.world, workers as u32)?;
            run_box2d(&mut box2d, DT, steps, replayed)?
        }
        _ => {
            let mut rapier = RapierWorld::from_carom(&load()?.world, DT)?;
            run_rapier(&mut rapier, steps, replayed)?
        }
    };
    let on = if engine == "rapier" { 1 } else { workers };
    println!(
        "{}: {engine} on {on} thread(s), {steps} steps (the first untimed): {:.3} ms/step",
        path.display(),
        result.ms_per_step()
    );
    if let Some(stages) = &result.stages {
        println!("{}", stages.describe());
    }
    Ok(())
}

fn main() -> Result<(), String> {
    // Before any Box2D world: its blocks are then counted as carom's and Rapier's are.
    carom_bench::box2d_heap::route_through_global_allocator();
    let args = Args::parse();
    if let Some(Command::HardCases {
        case,
        out,
        quick,
        check,
        jobs,
    }) = &args.command
    {
        return hard_cases(HardCaseArgs {
            filter: case,
            out,
            quick: *quick,
            check: *check,
            jobs: *jobs,
        });
    }
    if let Some(Command::Measure {
        file,
        runs,
        command,
    }) = &args.command
    {
        return measure(file, *runs, command);
    }
    if let Some(Command::Docs { check }) = &args.command {
        // The repository: here, or where this program was built from.
        let root = if Path::new("docs").is_dir() && Path::new("README.md").is_file() {
            PathBuf::from(".")
        } else {
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
        };
        let changed = carom_bench::docs::update(&root, !check)?;
        for path in &changed {
            eprintln!(
                "{} {}",
                if *check { "stale:" } else { "drawn again:" },
                path.display()
            );
        }
        if *check && !changed.is_empty() {
            return Err(format!(
                "{} docs differ from what their measurements draw: run `carom-bench docs`",
                changed.len()
            ));
        }
        if !*check {
            // The chart too, from the same points (it is a picture, so not checked).
            let csv = root.join(carom_bench::docs::ACCURACY_CSV);
            let text =
                std::fs::read_to_string(&csv).map_err(|e| format!("{}: {e}", csv.display()))?;
            let points = carom_bench::sweep::report::parse_csv(&text)?;
            carom_bench::sweep::chart::write_chart(&points, &csv.with_file_name("accuracy.png"))?;
        }
        return Ok(());
    }
    if let Some(Command::Sweep(sweep)) = &args.command {
        let base = carom_bench::sweep::SweepOptions::full();
        return sweep.run(base, Path::new("docs/accuracy"), &typed_command());
    }
    if args.runs == 0 {
        return Err("--runs must be at least 1".into());
    }
    let scenes: Vec<(PathBuf, u32)> = if args.scenes.is_empty() {
        DEFAULT_SCENES
            .iter()
            .map(|(p, s)| (PathBuf::from(p), args.steps.unwrap_or(*s)))
            .collect()
    } else {
        args.scenes
            .iter()
            .map(|p| (p.clone(), args.steps.unwrap_or_else(|| default_steps(p))))
            .collect()
    };
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| e.to_string())
    };
    let (one, many) = (pool(1)?, pool(args.threads.max(1))?);
    if let Some(Command::LookAhead { out, scenes, runs }) = &args.command {
        return look_ahead(out, scenes, *runs, &one);
    }
    if let Some(Command::Scaling {
        out,
        steps,
        runs,
        max_bodies,
    }) = &args.command
    {
        if *runs == 0 || *steps < 2 {
            return Err("scaling needs --runs of at least 1 and --steps of at least 2".into());
        }
        return scaling_run(out, *steps, *runs, *max_bodies, (&one, &many));
    }
    if let Some(Command::Snapshots {
        scenes,
        warm_up,
        rounds,
        csv,
    }) = &args.command
    {
        return snapshots_run(scenes, (*warm_up, *rounds), csv.as_deref(), (&one, &many));
    }
    if let Some(Command::Timeline { scene, steps }) = &args.command {
        return many.install(|| timeline_run(scene, *steps));
    }
    if let Some(Command::Profile {
        scene,
        engine,
        steps,
        threads,
        carom,
    }) = &args.command
    {
        let steps = steps.unwrap_or_else(|| default_steps(scene));
        return profile_run(scene, engine, steps, *carom, pool(*threads)?);
    }
    let mut rows = Vec::new();
    for (path, steps) in &scenes {
        let options = args.carom;
        rows.push(bench_scene(
            path,
            (*steps, args.runs),
            options,
            &one,
            &many,
        )?);
    }
    println!(
        "dt 1/60, steps {}, first step untimed, minimum of {} run(s)\n",
        scenes
            .iter()
            .map(|(p, s)| format!("{}: {s}", p.display()))
            .collect::<Vec<_>>()
            .join(", "),
        args.runs
    );
    print!("{}", markdown(&rows, args.threads));
    // What a peer could not express, so a figure is never read as the same scene when it
    // is not quite.
    let noted: Vec<_> = rows.iter().filter(|r| !r.notes.is_empty()).collect();
    if !noted.is_empty() {
        println!("\nNot translated or approximated in the peers' copies:\n");
        for row in noted {
            for note in &row.notes {
                println!("- {}: {note}", row.scene);
            }
        }
    }
    if let Some(path) = &args.csv {
        write_measured(path, args.runs as usize, &csv(&rows))?;
    }
    if let Some(path) = &args.stages_csv {
        write_measured(
            path,
            args.runs as usize,
            &stages_csv(&rows, args.threads.max(1)),
        )?;
    }
    Ok(())
}

/// [`stage_tables`] as CSV: a row per scene, engine (carom's, Box2D's) and thread count (one
/// and `threads`), the stages' ms per step and the work behind them; `NaN` where the engine
/// does not count it.
fn stages_csv(rows: &[Row], threads: usize) -> String {
    let mut s = String::from(
        "scene,engine,threads,step_ms,broadphase_ms,narrowphase_ms,solve_ms,continuous_ms,sleep_ms,\
         contacts,awake_contacts,recycled,touching,created,destroyed,proxies_moved,\
         pair_candidates,island_splits\n",
    );
    for r in rows {
        for (engine, threads, stages) in [
            ("carom", 1, r.carom.stages),
            ("carom", threads, r.carom_threads.stages),
            ("Box2D", 1, r.box2d.stages),
            ("Box2D", threads, r.box2d_threads.stages),
        ] {
            let Some(p) = stages else { continue };
            let _ = writeln!(
                s,
                "{},{engine},{threads},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.1},{:.1},{:.1},{:.1},{:.2},\
                 {:.2},{:.1},{:.1},{:.3}",
                r.scene,
                p.step_ms,
                p.broadphase_ms,
                p.narrowphase_ms,
                p.solve_ms,
                p.continuous_ms,
                p.sleep_ms,
                p.contacts,
                p.awake_contacts,
                p.recycled,
                p.touching,
                p.created,
                p.destroyed,
                p.proxies_moved,
                p.candidates,
                p.island_splits
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep's own options are its own: no other command's flag of the same name takes
    /// their place (a global one once did, with its default, so the whole sweep ran no
    /// direct joints and no shock propagation).
    #[test]
    fn the_sweep_keeps_its_options_and_the_timing_flags_stay_with_their_commands() {
        let args = Args::try_parse_from(["carom-bench", "sweep"]).expect("valid arguments");
        let Some(Command::Sweep(sweep)) = &args.command else {
            panic!("a sweep");
        };
        let options = sweep.options(carom_bench::sweep::SweepOptions::full());
        assert_eq!(options.direct_joints, vec![false, true]);
        assert_eq!(options.shock_propagation, vec![false, true]);
        let args = Args::try_parse_from(["carom-bench", "sweep", "--direct-joints", "on"])
            .expect("valid arguments");
        let Some(Command::Sweep(sweep)) = &args.command else {
            panic!("a sweep");
        };
        let options = sweep.options(carom_bench::sweep::SweepOptions::full());
        assert_eq!(options.direct_joints, vec![true]);
        let args = Args::try_parse_from([
            "carom-bench",
            "profile",
            "demos/tumbler.ron",
            "--no-look-ahead",
        ])
        .expect("valid arguments");
        let Some(Command::Profile { carom, .. }) = &args.command else {
            panic!("a profile");
        };
        assert!(carom.no_look_ahead && !carom.shock_propagation);
        let args =
            Args::try_parse_from(["carom-bench", "--shock-propagation"]).expect("valid arguments");
        assert!(args.carom.shock_propagation);
    }
}
