//! The figures the docs print, drawn from the files the measuring commands write, so that no
//! figure is typed by hand and none goes stale unseen.
//!
//! A doc marks each generated part with a pair of lines:
//!
//! ```text
//! <!-- figures: hard-cases/contacts -->
//! ...drawn here...
//! <!-- end figures -->
//! ```
//!
//! A part named `table FILE` draws FILE, a table that `carom-bench measure` wrote from another
//! program's output (see [`crate::measured`]), as it stands.
//!
//! `carom-bench docs` draws every marked part of `README.md` and `docs/**/*.md` again from
//! the measurements committed beside them ([`SOURCES`]), and the accuracy report
//! (`docs/accuracy/README.md`) whole; `carom-bench docs --check` (and the `docs` test) fails
//! when one of them differs from what it would draw. Whether the measurements themselves
//! still hold is the business of `carom-bench sweep --check` and
//! `carom-bench hard-cases --check`, which measure again.

use crate::hard_cases::table::{self, Column};
use crate::measured;
use crate::projection;
use crate::sweep::{self, Engine, Point, front, report};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The accuracy sweep's points, written by `carom-bench sweep`.
pub const ACCURACY_CSV: &str = "docs/accuracy/accuracy.csv";
/// The report `carom-bench sweep` writes beside them.
pub const ACCURACY_REPORT: &str = "docs/accuracy/README.md";
/// The hard cases' figures, written by `carom-bench hard-cases`.
pub const HARD_CASES_CSV: &str = "docs/hard-cases/hard-cases.csv";
/// carom, Box2D and Rapier timed on Box2D's recipes, written by `carom-bench --csv`.
pub const SPEED_CSV: &str = "docs/bench/peers.csv";
/// Instructions per step of a resting pyramid with each set of effects, counted by
/// `scripts/effect_cost.sh` and written by `carom-bench measure`.
pub const EFFECTS_CSV: &str = "docs/effects/effect-cost.csv";
/// What a snapshot and a restore cost beside a step, written by `carom-bench snapshots --csv`.
pub const SNAPSHOTS_CSV: &str = "docs/bench/snapshots.csv";
/// carom's and Box2D's stages on Box2D's recipes, written by `carom-bench --stages-csv` in the
/// run that writes [`SPEED_CSV`].
pub const STAGES_CSV: &str = "docs/bench/stages.csv";
/// Every file figures are drawn from.
pub const SOURCES: [&str; 6] = [
    ACCURACY_CSV,
    HARD_CASES_CSV,
    SPEED_CSV,
    EFFECTS_CSV,
    SNAPSHOTS_CSV,
    STAGES_CSV,
];

const BEGIN: &str = "<!-- figures: ";
const END: &str = "<!-- end figures -->";

/// The committed measurements, read once.
pub struct Sources {
    /// The repository, which `table FILE` parts name their files from.
    root: PathBuf,
    accuracy: Vec<Point>,
    accuracy_provenance: report::Provenance,
    hard_cases: Vec<table::Row>,
    hard_cases_provenance: report::Provenance,
    speed: Vec<SpeedRow>,
    speed_provenance: report::Provenance,
    effects: Vec<EffectCost>,
    effects_provenance: report::Provenance,
    snapshots: Vec<SnapshotRow>,
    snapshots_provenance: report::Provenance,
    stages: Vec<StageRow>,
    stages_provenance: report::Provenance,
}

/// One row of [`STAGES_CSV`]: a recipe in one engine on a number of threads, its stages' ms per
/// step and the work behind them (NaN where the engine does not count it), in the file's column
/// order.
struct StageRow {
    scene: String,
    engine: String,
    threads: usize,
    /// step, broadphase, narrowphase, solve, continuous, sleep.
    ms: [f64; 6],
    /// contacts, awake contacts, recycled, touching, created, destroyed, proxies moved, pair
    /// candidates, island splits.
    work: [f64; 9],
}

/// Reads [`STAGES_CSV`]'s rows.
fn parse_stages(text: &str) -> Result<Vec<StageRow>, String> {
    const HEADER: &str = "scene,engine,threads,step_ms,broadphase_ms,narrowphase_ms,solve_ms,\
                          continuous_ms,sleep_ms,contacts,awake_contacts,recycled,touching,\
                          created,destroyed,proxies_moved,pair_candidates,island_splits";
    data_lines(text, HEADER)?
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            if fields.len() != 18 {
                return Err(format!("`{line}` has not 18 fields"));
            }
            let threads = fields[2]
                .parse::<usize>()
                .map_err(|e| format!("`{line}`: {e}"))?;
            let numbers = fields[3..]
                .iter()
                .map(|f| f.parse::<f64>().map_err(|e| format!("`{line}`: {e}")))
                .collect::<Result<Vec<f64>, String>>()?;
            Ok(StageRow {
                scene: fields[0].to_string(),
                engine: fields[1].to_string(),
                threads,
                ms: std::array::from_fn(|k| numbers[k]),
                work: std::array::from_fn(|k| numbers[6 + k]),
            })
        })
        .collect()
}

/// The data lines of a measurement's CSV `text`: past its `#` lines, after a header that
/// must be `header`; an error when the header differs or no line follows it.
fn data_lines<'a>(
    text: &'a str,
    header: &str,
) -> Result<impl Iterator<Item = &'a str> + 'a, String> {
    let mut lines = text
        .lines()
        .filter(|line| !line.starts_with('#'))
        .peekable();
    if lines.next() != Some(header) {
        return Err(format!("its header is not `{header}`"));
    }
    if lines.peek().is_none() {
        return Err("no rows".into());
    }
    Ok(lines)
}

/// One row of [`SNAPSHOTS_CSV`]: a scene on some threads, the medians of its rounds, ms, and
/// the bytes a snapshot takes.
struct SnapshotRow {
    scene: String,
    bodies: usize,
    threads: usize,
    step: f64,
    snapshot: f64,
    restore: f64,
    bytes: u64,
}

impl SnapshotRow {
    /// Snapshot plus restore over one step.
    fn ratio(&self) -> f64 {
        (self.snapshot + self.restore) / self.step
    }
}

/// Reads [`SNAPSHOTS_CSV`]'s rows, its columns in the order `carom-bench snapshots` writes them.
fn parse_snapshots(text: &str) -> Result<Vec<SnapshotRow>, String> {
    const HEADER: &str = "scene,bodies,threads,step_ms,snapshot_ms,restore_ms,bytes";
    data_lines(text, HEADER)?
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let [scene, bodies, threads, step, snapshot, restore, bytes] = fields[..] else {
                return Err(format!("`{line}` has not seven fields"));
            };
            let bad = |e: &dyn std::fmt::Display| format!("`{line}`: {e}");
            let ms = |field: &str| field.parse::<f64>().map_err(|e| bad(&e));
            Ok(SnapshotRow {
                scene: scene.to_string(),
                bodies: bodies.parse().map_err(|e| bad(&e))?,
                threads: threads.parse().map_err(|e| bad(&e))?,
                step: ms(step)?,
                snapshot: ms(snapshot)?,
                restore: ms(restore)?,
                bytes: bytes.parse().map_err(|e| bad(&e))?,
            })
        })
        .collect()
}

/// One row of [`EFFECTS_CSV`]: the effects switched from all six (`-sleeping,-drag`), and
/// the instructions a step costs with them.
struct EffectCost {
    effects: String,
    instructions: u64,
}

/// Reads [`EFFECTS_CSV`]'s rows (the effects may hold commas: the count is the last field).
fn parse_effects(text: &str) -> Result<Vec<EffectCost>, String> {
    data_lines(text, "effects,instructions_per_step")?
        .map(|line| {
            let (effects, count) = line
                .rsplit_once(',')
                .ok_or_else(|| format!("`{line}` has no count"))?;
            Ok(EffectCost {
                effects: effects.trim_matches('"').to_string(),
                instructions: count
                    .parse()
                    .map_err(|e| format!("`{line}`: the count: {e}"))?,
            })
        })
        .collect()
}

/// One recipe of [`SPEED_CSV`]: ms per step of each engine, and on `--threads` threads.
struct SpeedRow {
    scene: String,
    bodies: usize,
    carom: f64,
    box2d: f64,
    rapier: f64,
    carom_threads: f64,
    box2d_threads: f64,
    /// How far the top body fell, m: carom's, Box2D's, Rapier's (NaN: no body to follow).
    drops: [f64; 3],
    /// Whether a body went non-finite: carom, Box2D, Rapier.
    nan: [bool; 3],
    /// Heap allocations per step: carom's, Box2D's, Rapier's.
    allocations: [f64; 3],
    /// Heap bytes per body: carom's, Box2D's, Rapier's.
    bytes_per_body: [f64; 3],
}

/// Reads [`SPEED_CSV`]'s rows by their column names.
fn parse_speed(text: &str) -> Result<Vec<SpeedRow>, String> {
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().ok_or("no header")?.split(',').collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| format!("no `{name}` column"))
    };
    let [
        scene,
        bodies,
        carom,
        box2d,
        rapier,
        carom_threads,
        box2d_threads,
    ] = [
        "scene",
        "bodies",
        "carom_ms_per_step",
        "box2d_ms_per_step",
        "rapier_ms_per_step",
        "carom_threads_ms_per_step",
        "box2d_threads_ms_per_step",
    ]
    .map(column);
    let (scene, bodies) = (scene?, bodies?);
    let numbers = [carom?, box2d?, rapier?, carom_threads?, box2d_threads?];
    let [carom_drop, box2d_drop, rapier_drop] =
        ["carom_top_drop_m", "box2d_top_drop_m", "rapier_top_drop_m"].map(column);
    let drops = [carom_drop?, box2d_drop?, rapier_drop?];
    let [carom_nan, box2d_nan, rapier_nan] = ["carom_nan", "box2d_nan", "rapier_nan"].map(column);
    let nans = [carom_nan?, box2d_nan?, rapier_nan?];
    let [
        carom_allocations,
        box2d_allocations,
        rapier_allocations,
        carom_bytes,
        box2d_bytes,
        rapier_bytes,
    ] = [
        "carom_allocations_per_step",
        "box2d_allocations_per_step",
        "rapier_allocations_per_step",
        "carom_bytes_per_body",
        "box2d_bytes_per_body",
        "rapier_bytes_per_body",
    ]
    .map(column);
    let memory = [
        carom_allocations?,
        box2d_allocations?,
        rapier_allocations?,
        carom_bytes?,
        box2d_bytes?,
        rapier_bytes?,
    ];
    lines
        .enumerate()
        .map(|(i, line)| {
            let fields: Vec<&str> = line.split(',').collect();
            let field = |k: usize| {
                fields
                    .get(k)
                    .copied()
                    .ok_or_else(|| format!("line {}: too few fields", i + 2))
            };
            let number = |k: usize| {
                field(k)?
                    .parse::<f64>()
                    .map_err(|e| format!("line {}: {e}", i + 2))
            };
            Ok(SpeedRow {
                scene: field(scene)?.to_string(),
                bodies: field(bodies)?
                    .parse()
                    .map_err(|e| format!("line {}: {e}", i + 2))?,
                carom: number(numbers[0])?,
                box2d: number(numbers[1])?,
                rapier: number(numbers[2])?,
                carom_threads: number(numbers[3])?,
                box2d_threads: number(numbers[4])?,
                drops: [number(drops[0])?, number(drops[1])?, number(drops[2])?],
                nan: [
                    field(nans[0])? == "true",
                    field(nans[1])? == "true",
                    field(nans[2])? == "true",
                ],
                allocations: [number(memory[0])?, number(memory[1])?, number(memory[2])?],
                bytes_per_body: [number(memory[3])?, number(memory[4])?, number(memory[5])?],
            })
        })
        .collect()
}

impl Sources {
    /// Reads [`SOURCES`] under the repository's `root`.
    pub fn read(root: &Path) -> Result<Sources, String> {
        let read = |name: &str| {
            let path = root.join(name);
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))
        };
        let provenance = |name: &str, text: &str| {
            report::Provenance::parse(text)
                .ok_or_else(|| format!("{name}: no `# measured: ...` lines at its top"))
        };
        let accuracy_text = read(ACCURACY_CSV)?;
        let hard_text = read(HARD_CASES_CSV)?;
        let speed_text = read(SPEED_CSV)?;
        let effects_text = read(EFFECTS_CSV)?;
        let snapshots_text = read(SNAPSHOTS_CSV)?;
        let stages_text = read(STAGES_CSV)?;
        Ok(Sources {
            root: root.to_path_buf(),
            accuracy: report::parse_csv(&accuracy_text)
                .map_err(|e| format!("{ACCURACY_CSV}: {e}"))?,
            accuracy_provenance: provenance(ACCURACY_CSV, &accuracy_text)?,
            hard_cases: table::parse_csv(&hard_text)
                .map_err(|e| format!("{HARD_CASES_CSV}: {e}"))?,
            hard_cases_provenance: provenance(HARD_CASES_CSV, &hard_text)?,
            speed: parse_speed(&speed_text).map_err(|e| format!("{SPEED_CSV}: {e}"))?,
            speed_provenance: provenance(SPEED_CSV, &speed_text)?,
            effects: parse_effects(&effects_text).map_err(|e| format!("{EFFECTS_CSV}: {e}"))?,
            effects_provenance: provenance(EFFECTS_CSV, &effects_text)?,
            snapshots: parse_snapshots(&snapshots_text)
                .map_err(|e| format!("{SNAPSHOTS_CSV}: {e}"))?,
            snapshots_provenance: provenance(SNAPSHOTS_CSV, &snapshots_text)?,
            stages: parse_stages(&stages_text).map_err(|e| format!("{STAGES_CSV}: {e}"))?,
            stages_provenance: provenance(STAGES_CSV, &stages_text)?,
        })
    }

    /// The part named `name`, drawn.
    pub fn draw(&self, name: &str) -> Result<String, String> {
        if let Some(file) = name.strip_prefix("table ") {
            return self.measured_table(file.trim());
        }
        match name {
            "accuracy/fronts" => Ok(self.accuracy_fronts()),
            "accuracy/summary" => Ok(self.accuracy_summary()),
            "hard-cases/contacts" => Ok(self.hard_case_table(
                false,
                &[
                    Column::SoftStep,
                    Column::Box2d,
                    Column::SequentialImpulse,
                    Column::TutorialImpulse,
                    Column::PushOut,
                ],
            )),
            "hard-cases/shock-propagation" => Ok(self.hard_case_table(
                false,
                &[Column::SoftStep, Column::ShockPropagation, Column::Box2d],
            )),
            "hard-cases/joints" => Ok(self.hard_case_table(
                true,
                &[
                    Column::SoftStep,
                    Column::DirectJoints,
                    Column::BothOptions,
                    Column::Box2d,
                    Column::SequentialImpulse,
                ],
            )),
            "hard-cases/summary" => Ok(self.hard_case_summary()),
            "accuracy/options" => Ok(self.option_costs()),
            "speed/recipes" => Ok(self.speed_recipes()),
            "speed/summary" => Ok(self.speed_summary()),
            "effects/cost" => Ok(self.effect_costs()),
            "bench/snapshots" => Ok(self.snapshot_costs()),
            "speed/drops" => Ok(self.speed_drops()),
            "speed/memory" => Ok(self.speed_memory()),
            "speed/stages" => Ok(self.speed_stages()),
            "speed/work" => Ok(self.speed_work()),
            "speed/projection" => Ok(self.speed_projection()),
            _ => Err(format!(
                "no figures named `{name}`: the names are {} and `table FILE`",
                NAMES.join(", ")
            )),
        }
    }

    /// The table `carom-bench measure` wrote to `file` (from the repository's root).
    fn measured_table(&self, file: &str) -> Result<String, String> {
        let path = self.root.join(file);
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let table = measured::parse(&text).map_err(|e| format!("{file}: {e}"))?;
        Ok(table.markdown())
    }

    /// The accuracy report, as `carom-bench sweep` wrote it from the same points.
    pub fn accuracy_report(&self) -> String {
        report::markdown(&self.accuracy, &self.accuracy_provenance)
    }

    /// "Measured DATE on CPU (N cores) by `COMMAND`."
    fn measured(provenance: &report::Provenance) -> String {
        format!(
            "Measured {} on {} ({} cores) by `{}`.",
            provenance.machine.date,
            provenance.machine.cpu,
            provenance.machine.cores,
            provenance.command
        )
    }

    /// Per scene and budget, each engine's smallest error within it and its setting.
    fn accuracy_fronts(&self) -> String {
        let mut out = Self::measured(&self.accuracy_provenance);
        out.push_str(
            " Each engine's smallest error within the time a step may take, and the setting \
             that gives it (a dash: no setting that fast).\n\n\
             | scene (error) | within | carom | Box2D | Rapier |\n|---|---|---|---|---|\n",
        );
        for (scene, points) in report::fronts(&self.accuracy) {
            let kind = points[0].error_kind;
            for (k, budget) in BUDGETS.into_iter().enumerate() {
                let label = if k == 0 {
                    format!("{scene} ({})", kind.unit())
                } else {
                    String::new()
                };
                let _ = write!(out, "| {label} | {budget} ms |");
                for engine in Engine::ALL {
                    match front::best_within(&points, engine, budget) {
                        Some(p) => {
                            let _ = write!(
                                out,
                                " {} ({}) |",
                                figure(p.error),
                                short_setting(&p.setting)
                            );
                        }
                        None => out.push_str(" - |"),
                    }
                }
                out.push('\n');
            }
        }
        out
    }

    /// What each of soft step's options costs and buys on each scene it is swept on, at
    /// Box2D's settings (4 substeps, 1 iteration, 30 Hz contacts, 60 Hz joints), beside
    /// Box2D's own step there.
    fn option_costs(&self) -> String {
        let mut out = format!(
            "{} Soft step at Box2D's settings (4 substeps, 1 iteration, 30 Hz contacts, 60 Hz \
             joints) with each option off and on, and Box2D at the same; ms per step on one \
             thread, the median {}, all from the same sweep.\n\n\
             | scene (error) | option | soft step | with the option | time, on / off | Box2D v3 \
             |\n|---|---|---|---|---|---|\n",
            Self::measured(&self.accuracy_provenance),
            crate::sweep::report::of_runs(self.accuracy_provenance.runs)
        );
        let base = |p: &&Point| {
            p.setting.engine == Engine::Carom
                && p.setting.solver == carom::SolverKind::SoftStep
                && p.setting.substeps == 4
                && p.setting.iterations == 1
                && p.setting.contact_hertz == Some(30.0)
                && p.setting.joint_hertz.is_none()
        };
        for (scene, points) in report::fronts(&self.accuracy) {
            let unit = points[0].error_kind.unit();
            let box2d = points.iter().find(|p| {
                p.setting.engine == Engine::Box2d
                    && p.setting.substeps == 4
                    && p.setting.contact_hertz == Some(30.0)
            });
            let plain = points
                .iter()
                .find(|p| base(p) && !p.setting.direct_joints && !p.setting.shock_propagation);
            // Each option alone: (direct joints, shock propagation).
            for (name, option) in [
                ("direct joints", (true, false)),
                ("shock propagation", (false, true)),
            ] {
                let on = |s: &sweep::Setting| (s.direct_joints, s.shock_propagation) == option;
                let (Some(plain), Some(with)) =
                    (plain, points.iter().find(|p| base(p) && on(&p.setting)))
                else {
                    continue;
                };
                let cell = |p: &Point| format!("{:.3} ms, {}", p.ms_per_step, figure(p.error));
                let _ = writeln!(
                    out,
                    "| {scene} ({unit}) | {name} | {} | {} | {:.2} | {} |",
                    cell(plain),
                    cell(with),
                    with.ms_per_step / plain.ms_per_step,
                    box2d.map_or_else(|| "-".into(), |p| cell(p))
                );
            }
        }
        out
    }

    /// One sentence per budget: on how many scenes carom's best error within it is the
    /// smallest of the three engines'.
    fn accuracy_summary(&self) -> String {
        let scenes = report::fronts(&self.accuracy);
        let mut out = format!("{}:", self.accuracy_provenance.machine.date);
        for (k, budget) in BUDGETS.into_iter().enumerate() {
            let (mut best, mut tied) = (0, 0);
            for (_, points) in &scenes {
                let error = |engine| front::best_within(points, engine, budget).map(|p| p.error);
                let carom = error(Engine::Carom).unwrap_or(f64::INFINITY);
                let peers = [error(Engine::Box2d), error(Engine::Rapier)]
                    .into_iter()
                    .flatten()
                    .fold(f64::INFINITY, f64::min);
                if carom < peers {
                    best += 1;
                } else if carom == peers && carom.is_finite() {
                    tied += 1;
                }
            }
            let _ = write!(
                out,
                "{} within {budget} ms a step, carom's most accurate setting beats Box2D's and \
                 Rapier's on {best} of {} fronts{}",
                if k == 0 { "" } else { ";" },
                scenes.len(),
                if tied > 0 {
                    format!(" and ties on {tied}")
                } else {
                    String::new()
                }
            );
        }
        out.push_str(".\n");
        out
    }

    /// The hard cases with joints (or without), in `columns`.
    fn hard_case_table(&self, joints: bool, columns: &[Column]) -> String {
        let names: Vec<&str> = crate::hard_cases::cases()
            .iter()
            .filter(|c| c.has_joints() == joints)
            .map(|c| c.name)
            .collect();
        format!(
            "{} A figure that misses its bar is bold.\n\n{}",
            Self::measured(&self.hard_cases_provenance),
            table::markdown(&self.hard_cases, &names, columns)
        )
    }

    /// Each recipe's ms per step in each engine, and their ratios.
    fn speed_recipes(&self) -> String {
        let mut out = format!(
            "{} ms per step, the best of {} runs; threads as the command sets them (2 by \
             default).\n\n| scene | carom | Box2D v3 | Rapier | carom / Box2D | carom / Rapier \
             | carom on threads / Box2D on threads | carom's speed-up on threads | Box2D's \
             |\n|---|---|---|---|---|---|---|---|---|\n",
            Self::measured(&self.speed_provenance),
            self.speed_provenance.runs
        );
        for r in &self.speed {
            let _ = writeln!(
                out,
                "| `{}` ({} bodies) | {:.3} | {:.3} | {:.3} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
                r.scene,
                r.bodies,
                r.carom,
                r.box2d,
                r.rapier,
                r.carom / r.box2d,
                r.carom / r.rapier,
                r.carom_threads / r.box2d_threads,
                r.carom / r.carom_threads,
                r.box2d / r.box2d_threads
            );
        }
        out
    }

    /// The ranges of carom's time over Box2D's and Rapier's, one thread and several.
    fn speed_summary(&self) -> String {
        let range = |ratio: &dyn Fn(&SpeedRow) -> f64| {
            let (low, high) = self
                .speed
                .iter()
                .map(ratio)
                .fold((f64::INFINITY, 0.0f64), |(l, h), x| (l.min(x), h.max(x)));
            format!("{low:.2} to {high:.2}")
        };
        format!(
            "{}: on {} of Box2D's benchmark recipes, carom's step takes {} times Box2D v3's \
             time and {} times Rapier's on one thread, and {} times Box2D's on two \
             ([docs/bench](docs/bench/README.md)).\n",
            self.speed_provenance.machine.date,
            self.speed.len(),
            range(&|r| r.carom / r.box2d),
            range(&|r| r.carom / r.rapier),
            range(&|r| r.carom_threads / r.box2d_threads),
        )
    }

    /// Instructions per step with each set of effects, against the first row (the baseline),
    /// and what the effects the page discusses cost.
    fn effect_costs(&self) -> String {
        let base = self.effects[0].instructions as f64;
        let ratio = |row: &EffectCost| row.instructions as f64 / base;
        let mut out = format!(
            "{} Instructions per step, counted by callgrind; the first row is the baseline.\n\n\
             | effects (from all six) | instructions/step | ratio |\n|---|---|---|\n",
            Self::measured(&self.effects_provenance)
        );
        for (index, row) in self.effects.iter().enumerate() {
            let label = if index == 0 {
                format!("`{}` (the baseline)", row.effects)
            } else if row.effects.split(',').count() == 6 {
                "none".to_string()
            } else {
                format!("`{}`", row.effects)
            };
            let _ = writeln!(
                out,
                "| {label} | {} | {:.3} |",
                row.instructions,
                ratio(row)
            );
        }
        // The share of the baseline an effect costs: what switching it off saves (sleeping's,
        // what switching it on saves).
        let share = |effects: &str| {
            self.effects
                .iter()
                .find(|row| row.effects == effects)
                .map_or("-".to_string(), |row| {
                    format!("{:.1} %", 100.0 * (1.0 - ratio(row)))
                })
        };
        let _ = writeln!(
            out,
            "\nHere continuous collision costs {} of the baseline's step and friction {}, \
             and sleeping removes {} of the work once the pyramid rests.",
            share("-sleeping,-continuous"),
            share("-sleeping,-friction"),
            share("+sleeping"),
        );
        out
    }

    /// How far each engine let the top body of each recipe fall over the run.
    fn speed_drops(&self) -> String {
        let mut out = format!(
            "{} How far the body highest at the start fell by the end, m (a dash: the scene \
             starts with no dynamic body to follow; NaN: a body went non-finite).\n\n\
             | scene | carom | Box2D v3 | Rapier |\n|---|---|---|---|\n",
            Self::measured(&self.speed_provenance)
        );
        for row in &self.speed {
            let cell = |k: usize| {
                if row.nan[k] {
                    "NaN".to_string()
                } else if row.drops[k].is_nan() {
                    "-".to_string()
                } else {
                    format!("{:.3}", row.drops[k])
                }
            };
            let _ = writeln!(
                out,
                "| `{}` | {} | {} | {} |",
                row.scene,
                cell(0),
                cell(1),
                cell(2)
            );
        }
        out
    }

    /// Heap allocations per step and bytes per body, carom's beside Box2D's and Rapier's.
    fn speed_memory(&self) -> String {
        let mut out = format!(
            "{} Heap allocations per timed step, one thread, counted by the bench's allocator \
             (Box2D's routed through it), and heap bytes per body after the run (Box2D's as it \
             counts them itself). None of the engines had room reserved ahead of time.\n\n\
             | scene | carom allocations/step | Box2D allocations/step | \
             Rapier allocations/step | carom bytes/body | Box2D bytes/body | \
             Rapier bytes/body |\n|---|---|---|---|---|---|---|\n",
            Self::measured(&self.speed_provenance)
        );
        for row in &self.speed {
            let _ = writeln!(
                out,
                "| `{}` | {:.2} | {:.2} | {:.1} | {:.0} | {:.0} | {:.0} |",
                row.scene,
                row.allocations[0],
                row.allocations[1],
                row.allocations[2],
                row.bytes_per_body[0],
                row.bytes_per_body[1],
                row.bytes_per_body[2]
            );
        }
        out
    }

    /// carom's stages beside Box2D's profile, one thread.
    fn speed_stages(&self) -> String {
        let mut out = format!(
            "{} ms per step on one thread, the fastest run's means.\n\n\
             | scene | engine | step | broadphase | narrowphase | solve | continuous | sleep | \
             other |\n|---|---|---|---|---|---|---|---|---|\n",
            Self::measured(&self.stages_provenance)
        );
        for row in self.stages.iter().filter(|r| r.threads == 1) {
            let [step, broad, narrow, solve, continuous, sleep] = row.ms;
            let other = step - broad - narrow - solve - continuous - sleep;
            let _ = writeln!(
                out,
                "| `{}` | {} | {step:.3} | {broad:.3} | {narrow:.3} | {solve:.3} | \
                 {continuous:.3} | {sleep:.3} | {other:.3} |",
                row.scene, row.engine
            );
        }
        out
    }

    /// Each stage's serial share, from its time on one thread and on several, and the step's
    /// time projected from them on more threads than were measured.
    fn speed_projection(&self) -> String {
        let rows: Vec<projection::Measured> = self
            .stages
            .iter()
            .filter(|one| one.threads == 1)
            .filter_map(|one| {
                let many = self.stages.iter().find(|r| {
                    r.threads > 1 && (&r.scene, &r.engine) == (&one.scene, &one.engine)
                })?;
                Some(projection::Measured {
                    scene: format!("`{}`", one.scene),
                    engine: one.engine.clone(),
                    threads: many.threads,
                    one: one.ms,
                    many: many.ms,
                })
            })
            .collect();
        format!(
            "{} A projection, not a measurement.\n\n{}",
            Self::measured(&self.stages_provenance),
            projection::markdown(&rows)
        )
    }

    /// The work behind the stages: contacts, recycling, pairs, island splits.
    fn speed_work(&self) -> String {
        let mut out = format!(
            "{} Means per step on one thread; a dash where the engine does not count it.\n\n\
             | scene | engine | contacts | awake contacts | recycled | touching | created | \
             destroyed | proxies moved | pair candidates | island splits |\n\
             |---|---|---|---|---|---|---|---|---|---|---|\n",
            Self::measured(&self.stages_provenance)
        );
        for row in self.stages.iter().filter(|r| r.threads == 1) {
            let _ = write!(out, "| `{}` | {} |", row.scene, row.engine);
            for (k, value) in row.work.iter().enumerate() {
                if value.is_nan() {
                    out.push_str(" - |");
                } else if k == row.work.len() - 1 {
                    let _ = write!(out, " {value:.3} |");
                } else {
                    let _ = write!(out, " {value:.0} |");
                }
            }
            out.push('\n');
        }
        out
    }

    /// What a snapshot and a restore cost beside a step, per scene and thread count, and the
    /// most they cost of a step.
    fn snapshot_costs(&self) -> String {
        let mut out = format!(
            "{} Each time is the median of the rounds, ms.\n\n\
             | scene | bodies | threads | step | snapshot | restore | (snapshot + restore) / step \
             | bytes | bytes per body |\n|---|---|---|---|---|---|---|---|---|\n",
            Self::measured(&self.snapshots_provenance)
        );
        for row in &self.snapshots {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.2} | {:.1} MB | {:.0} |",
                row.scene,
                row.bodies,
                row.threads,
                row.step,
                row.snapshot,
                row.restore,
                row.ratio(),
                row.bytes as f64 / 1e6,
                row.bytes as f64 / row.bodies.max(1) as f64
            );
        }
        let most = self
            .snapshots
            .iter()
            .map(SnapshotRow::ratio)
            .fold(0.0, f64::max);
        let _ = writeln!(
            out,
            "\nA snapshot plus a restore costs at most {most:.2} of a step here, on every scene \
             and thread count."
        );
        out
    }

    /// How many bars each column meets, over the cases it runs.
    fn hard_case_summary(&self) -> String {
        let met = |columns: &[Column]| {
            let mut counts = (0, 0);
            for row in self.hard_cases.iter().filter(|r| r.bar != "-") {
                if columns.iter().any(|c| c.id() == row.column) {
                    counts.1 += 1;
                    if !row.cell.starts_with("**") && !row.cell.starts_with("error") {
                        counts.0 += 1;
                    }
                }
            }
            counts
        };
        // Soft step's options: shock propagation on contacts, both options on joints.
        let soft = met(&[Column::SoftStep]);
        let options = met(&[Column::ShockPropagation, Column::BothOptions]);
        let box2d = met(&[Column::Box2d]);
        format!(
            "{}: of the hard cases' bars, soft step at its defaults meets {} of {}, with shock \
             propagation and direct joints on {} of {}, and Box2D v3 {} of {}.\n",
            self.hard_cases_provenance.machine.date,
            soft.0,
            soft.1,
            options.0,
            options.1,
            box2d.0,
            box2d.1
        )
    }
}

/// Every part [`Sources::draw`] draws.
pub const NAMES: [&str; 16] = [
    "bench/snapshots",
    "speed/drops",
    "speed/memory",
    "speed/stages",
    "speed/work",
    "speed/projection",
    "effects/cost",
    "accuracy/fronts",
    "accuracy/options",
    "accuracy/summary",
    "hard-cases/contacts",
    "hard-cases/shock-propagation",
    "hard-cases/joints",
    "hard-cases/summary",
    "speed/recipes",
    "speed/summary",
];

/// The budgets the fronts are read at, ms per step.
const BUDGETS: [f64; 2] = [0.1, 1.0];

/// An error with three significant digits (in exponent form below a thousandth), `inf` for a
/// world gone NaN.
fn figure(error: f64) -> String {
    if !error.is_finite() {
        return "inf".into();
    }
    if error == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e4).contains(&error) {
        return format!("{error:.2e}");
    }
    let decimals = (2 - error.log10().floor() as i32).max(0) as usize;
    format!("{error:.decimals$}")
}

/// A setting in a few words: "4 sub, 2 it, 60 Hz", "SI 64 it", with its options.
fn short_setting(setting: &sweep::Setting) -> String {
    let mut name = match setting.engine {
        Engine::Carom if !setting.solver.has_substeps() => {
            format!("{} {} it", setting.solver.name(), setting.iterations)
        }
        Engine::Carom => format!("{} sub, {} it", setting.substeps, setting.iterations),
        Engine::Box2d => format!("{} sub", setting.substeps),
        Engine::Rapier => format!(
            "{} sub, {} stab",
            setting.substeps,
            setting.stabilization.unwrap_or(1)
        ),
    };
    report::name_stiffness_and_options(&mut name, setting, true);
    name
}

/// The docs figures are drawn into: `README.md` and every `.md` under `docs/` but the
/// accuracy report (drawn whole).
pub fn marked_files(root: &Path) -> Result<Vec<PathBuf>, String> {
    let mut files = vec![root.join("README.md")];
    let mut folders = vec![root.join("docs")];
    while let Some(folder) = folders.pop() {
        let entries =
            std::fs::read_dir(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
        for entry in entries {
            let path = entry.map_err(|e| e.to_string())?.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "md")
                && path != root.join(ACCURACY_REPORT)
            {
                files.push(path);
            }
        }
    }
    files.sort();
    Ok(files)
}

/// `text` with every marked part drawn again; an unknown name or a part never ended is an
/// error naming its line.
pub fn redraw(text: &str, sources: &Sources) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    let mut lines = text.split_inclusive('\n').enumerate();
    while let Some((number, line)) = lines.next() {
        out.push_str(line);
        let Some(name) = line
            .trim_end()
            .strip_prefix(BEGIN)
            .and_then(|rest| rest.strip_suffix("-->"))
            .map(str::trim)
        else {
            continue;
        };
        let drawn = sources
            .draw(name)
            .map_err(|e| format!("line {}: {e}", number + 1))?;
        // Skip the old part up to its end marker.
        let ended = lines.by_ref().any(|(_, line)| line.trim_end() == END);
        if !ended {
            return Err(format!(
                "line {}: `{name}` has no `{END}` after it",
                number + 1
            ));
        }
        out.push_str(&drawn);
        out.push_str(END);
        out.push('\n');
    }
    Ok(out)
}

/// Draws every marked part and the accuracy report from the committed measurements under
/// `root`. With `write`, rewrites the files that change; either way returns the files that
/// differed from what was drawn.
pub fn update(root: &Path, write: bool) -> Result<Vec<PathBuf>, String> {
    let sources = Sources::read(root)?;
    let mut drawn = Vec::new();
    for path in marked_files(root)? {
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let new = redraw(&text, &sources).map_err(|e| format!("{}: {e}", path.display()))?;
        drawn.push((path, text, new));
    }
    let report = root.join(ACCURACY_REPORT);
    let text =
        std::fs::read_to_string(&report).map_err(|e| format!("{}: {e}", report.display()))?;
    drawn.push((report, text, sources.accuracy_report()));
    let mut changed = Vec::new();
    for (path, old, new) in drawn {
        if old != new {
            if write {
                std::fs::write(&path, &new).map_err(|e| format!("{}: {e}", path.display()))?;
            }
            changed.push(path);
        }
    }
    Ok(changed)
}
