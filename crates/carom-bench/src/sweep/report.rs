//! The sweep written down: a CSV of every point and a markdown report with one table per scene.

use super::{Engine, Point, Setting, front};
use carom::Real;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fmt::Write as _;
use web_time::{SystemTime, UNIX_EPOCH};

/// The CSV header, in the order [`csv()`] writes the columns.
pub const CSV_HEADER: &str = "engine,scene,error_kind,solver,iterations,substeps,ms_per_step,\
                              error,error_unit,max_penetration_m,joint_hertz,contact_hertz,\
                              stabilization,joints,direct_joints,shock_propagation";

/// One line of the CSV, column for column as [`CSV_HEADER`] names them. Numbers are written
/// as the report prints them (a microsecond, three significant digits), so a sweep read back
/// and written again gives the same text.
#[derive(Debug, Serialize, Deserialize)]
struct Row {
    /// Absent in files written before peers ran: every point is then carom's.
    #[serde(default)]
    engine: Option<String>,
    scene: String,
    error_kind: String,
    solver: String,
    iterations: u32,
    substeps: u32,
    #[serde(serialize_with = "micro")]
    ms_per_step: f64,
    #[serde(serialize_with = "three_digits")]
    error: f64,
    #[serde(default)]
    error_unit: Option<String>,
    #[serde(default, serialize_with = "micro_or_empty")]
    max_penetration_m: Option<f64>,
    #[serde(default, serialize_with = "shortest_or_empty")]
    joint_hertz: Option<Real>,
    #[serde(default, serialize_with = "shortest_or_empty")]
    contact_hertz: Option<Real>,
    #[serde(default)]
    stabilization: Option<u32>,
    /// Absent in files written before it was a column: then inferred (see [`parse_csv`]).
    #[serde(default)]
    joints: Option<bool>,
    /// Absent in files written before it was a column: then off.
    #[serde(default)]
    direct_joints: Option<bool>,
    /// Absent in files written before it was a column: then off.
    #[serde(default)]
    shock_propagation: Option<bool>,
}

fn micro<S: serde::Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(&format!("{value:.6}"))
}

fn three_digits<S: serde::Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(&format_error(*value))
}

fn micro_or_empty<S: serde::Serializer>(
    value: &Option<f64>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    match value {
        Some(value) => micro(value, serializer),
        None => serializer.serialize_none(),
    }
}

/// `120`, not `120.0`: the shortest text that reads back as the same number.
fn shortest_or_empty<S: serde::Serializer>(
    value: &Option<Real>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    match value {
        Some(value) => serializer.serialize_str(&value.to_string()),
        None => serializer.serialize_none(),
    }
}

/// Every point as one CSV line. NaN worlds have the error `inf`; `joint_hertz` is empty for
/// the solver's default (60 Hz, capped at a quarter of the substep rate), `contact_hertz`
/// where the scene's own contact stiffness ran, `stabilization` for all but Rapier, and
/// `max_penetration_m` for the peers, whose overlap is not measured; `joints` says whether
/// the scene has joints, `direct_joints` whether soft step solved them directly, and
/// `shock_propagation` whether it held bodies on those under them as on the ground.
pub fn csv(points: &[Point]) -> String {
    // The header is written even for no points, so the columns are always named.
    let mut writer = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let mut write = || -> csv::Result<()> {
        writer.write_record(CSV_HEADER.split(','))?;
        for p in points {
            writer.serialize(Row {
                engine: Some(p.setting.engine.name().to_string()),
                scene: p.scene.clone(),
                error_kind: format!("{:?}", p.error_kind),
                solver: p.setting.solver.name().to_string(),
                iterations: p.setting.iterations,
                substeps: p.setting.substeps,
                ms_per_step: p.ms_per_step,
                error: p.error,
                error_unit: Some(p.error_kind.unit().to_string()),
                max_penetration_m: p.max_penetration.is_finite().then_some(p.max_penetration),
                joint_hertz: p.setting.joint_hertz,
                contact_hertz: p.setting.contact_hertz,
                stabilization: p.setting.stabilization,
                joints: Some(p.joints),
                direct_joints: Some(p.setting.direct_joints),
                shock_propagation: Some(p.setting.shock_propagation),
            })?;
        }
        Ok(())
    };
    write().expect("writing to memory does not fail");
    let bytes = writer
        .into_inner()
        .expect("flushing to memory does not fail");
    String::from_utf8(bytes).expect("every field is text")
}

/// Where and when the sweep ran.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// The processor's model name.
    pub cpu: String,
    /// Logical cores available.
    pub cores: usize,
    /// The date, YYYY-MM-DD (UTC).
    pub date: String,
}

impl Machine {
    /// This machine, today.
    pub fn here() -> Self {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines()
                    .find(|line| line.starts_with("model name"))
                    .and_then(|line| line.split(':').nth(1))
                    .map(|name| name.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let days = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_secs() / 86_400) as i64;
        Machine {
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            date: civil_date(days),
        }
    }
}

/// Where, when and how a measurement ran. It heads the CSV the measurement writes, as
/// `# key: value` lines, so a report drawn from the CSV later names them.
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// The machine and the date.
    pub machine: Machine,
    /// The command that measured, as typed.
    pub command: String,
    /// Runs per point.
    pub runs: usize,
}

impl Provenance {
    /// The CSV's first lines.
    pub fn header(&self) -> String {
        format!(
            "# measured: {}\n# machine: {}\n# cores: {}\n# command: {}\n# runs: {}\n",
            self.machine.date, self.machine.cpu, self.machine.cores, self.command, self.runs
        )
    }

    /// Reads the lines [`Provenance::header`] wrote at the top of `text`; `None` when any is
    /// missing.
    pub fn parse(text: &str) -> Option<Provenance> {
        let value = |key: &str| {
            text.lines()
                .take_while(|line| line.starts_with('#'))
                .find_map(|line| line.strip_prefix(&format!("# {key}: ")))
                .map(str::to_string)
        };
        Some(Provenance {
            machine: Machine {
                cpu: value("machine")?,
                cores: value("cores")?.parse().ok()?,
                date: value("measured")?,
            },
            command: value("command")?,
            runs: value("runs")?.parse().ok()?,
        })
    }
}

/// Days since 1970-01-01 as YYYY-MM-DD (Howard Hinnant's civil-from-days).
fn civil_date(days: i64) -> String {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let day_of_era = z - era * 146_097;
    let year_of_era =
        (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_index = (5 * day_of_year + 2) / 153;
    let day = day_of_year - (153 * month_index + 2) / 5 + 1;
    let month = if month_index < 10 {
        month_index + 3
    } else {
        month_index - 9
    };
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}")
}

/// The markdown report: the machine, then per scene which engine is best within each time
/// budget (when peers ran) and a table per engine: carom's with a row per solver (and
/// substep count) and a column per iteration count, Box2D's with a row per contact
/// stiffness, Rapier's with a row per stabilization count, and their substeps in columns;
/// each cell "ms/step · error".
pub fn markdown(points: &[Point], provenance: &Provenance) -> String {
    let (machine, command, runs) = (&provenance.machine, &provenance.command, provenance.runs);
    let mut out = String::new();
    let _ = writeln!(out, "# What accuracy costs in time\n");
    let _ = writeln!(
        out,
        "Measured {} on {} ({} cores) with `{command}`: every cell is the median ms/step {} \
         and the error against the scene's exact answer. Release build, sleeping off (every \
         step is solved), scenes this size run on one thread. `inf` means the world went \
         NaN.\n",
        machine.date,
        machine.cpu,
        machine.cores,
        of_runs(runs)
    );
    let mut engines: Vec<Engine> = points.iter().map(|p| p.setting.engine).collect();
    engines.sort_unstable();
    engines.dedup();
    if engines.len() > 1 {
        let _ = writeln!(out, "{PEERS_NOTE}\n");
    }
    let _ = writeln!(out, "![error against time](accuracy.png)\n");
    for (scene, of_scene) in fronts(points) {
        let kind = of_scene[0].error_kind;
        let _ = writeln!(
            out,
            "## {scene}\n\nError: {} ({}). Each cell: ms/step · error.\n",
            kind.description(),
            kind.unit()
        );
        if engines.len() > 1 {
            budgets(&mut out, &of_scene, &engines);
        }
        if of_scene[0].joints && engines.contains(&Engine::Carom) {
            let _ = writeln!(out, "{JOINTS_NOTE}\n");
        }
        for &engine in &engines {
            let of_engine: Vec<&Point> = of_scene
                .iter()
                .copied()
                .filter(|p| p.setting.engine == engine)
                .collect();
            if of_engine.is_empty() {
                continue;
            }
            if engines.len() > 1 {
                let _ = writeln!(out, "### {}\n", engine.name());
            }
            match engine {
                Engine::Carom => table(&mut out, &of_engine, "solver", series_name, |p| {
                    (p.setting.iterations, format!("{} it", p.setting.iterations))
                }),
                Engine::Box2d => table(
                    &mut out,
                    &of_engine,
                    "contacts",
                    |p| match p.setting.contact_hertz {
                        Some(hertz) => format!("{hertz} Hz"),
                        None => "the scene's".into(),
                    },
                    |p| (p.setting.substeps, format!("{} sub", p.setting.substeps)),
                ),
                Engine::Rapier => table(
                    &mut out,
                    &of_engine,
                    "stabilization",
                    |p| format!("{} it", p.setting.stabilization.unwrap_or(1)),
                    |p| (p.setting.substeps, format!("{} sub", p.setting.substeps)),
                ),
            }
        }
    }
    out
}

/// The points grouped by what a front is drawn over, in the order they first come: one
/// group per scene, or per scene and error where a scene's measure gives more than one (a
/// pile of ragdolls: its hinges' gap and their turn past their limits). Each group's label is
/// the scene's name, with the error's name where the scene has several.
pub fn fronts(points: &[Point]) -> Vec<(String, Vec<&Point>)> {
    let mut groups: Vec<(&str, super::ErrorKind, Vec<&Point>)> = Vec::new();
    for p in points {
        match groups
            .iter_mut()
            .find(|(scene, kind, _)| *scene == p.scene && *kind == p.error_kind)
        {
            Some((_, _, members)) => members.push(p),
            None => groups.push((&p.scene, p.error_kind, vec![p])),
        }
    }
    let kinds_of = |scene: &str| groups.iter().filter(|g| g.0 == scene).count();
    groups
        .iter()
        .map(|(scene, kind, members)| {
            let label = if kinds_of(scene) > 1 {
                format!("{scene}, {}", kind.name())
            } else {
                scene.to_string()
            };
            (label, members.clone())
        })
        .collect()
}

/// The time budgets the report compares engines at, ms per step.
pub const BUDGETS: [f64; 3] = [0.1, 1.0, 10.0];

/// Per budget: the engine with the smallest error within it, its setting, and how many times
/// smaller that error is than the next engine's best within the same budget.
fn budgets(out: &mut String, points: &[&Point], engines: &[Engine]) {
    let _ = writeln!(
        out,
        "| within | best | its error | next best | its error | times smaller |\n\
         |---|---|---|---|---|---|"
    );
    for budget in BUDGETS {
        let mut best: Vec<&Point> = engines
            .iter()
            .filter_map(|&engine| front::best_within(points, engine, budget))
            .collect();
        best.sort_by(|a, b| a.error.total_cmp(&b.error));
        let describe = |p: Option<&&Point>| match p {
            Some(p) => (setting_name(&p.setting), format_error(p.error)),
            None => ("none within it".into(), String::new()),
        };
        let (first, first_error) = describe(best.first());
        let (second, second_error) = describe(best.get(1));
        let ratio = match (best.first(), best.get(1)) {
            (Some(a), Some(b)) if a.error == b.error => "equal".into(),
            (Some(a), Some(b)) if a.error > 0.0 => format!("{:.1}", b.error / a.error),
            (Some(_), Some(_)) => "exact, the other not".into(),
            _ => String::new(),
        };
        let _ = writeln!(
            out,
            "| {budget} ms | {first} | {first_error} | {second} | {second_error} | {ratio} |"
        );
    }
    out.push('\n');
}

/// A table of `points`: a row per `row` label (in sweep order), a column per `column` key
/// (sorted, labelled), each cell "ms/step · error".
fn table(
    out: &mut String,
    points: &[&Point],
    row_title: &str,
    row: impl Fn(&Point) -> String,
    column: impl Fn(&Point) -> (u32, String),
) {
    let mut columns: Vec<(u32, String)> = points.iter().map(|p| column(p)).collect();
    columns.sort_unstable();
    columns.dedup();
    let mut rows: Vec<String> = Vec::new();
    for p in points {
        let label = row(p);
        if !rows.contains(&label) {
            rows.push(label);
        }
    }
    let _ = write!(out, "| {row_title} |");
    for (_, label) in &columns {
        let _ = write!(out, " {label} |");
    }
    let _ = write!(out, "\n|---|");
    for _ in &columns {
        let _ = write!(out, "---|");
    }
    out.push('\n');
    for label in rows {
        let _ = write!(out, "| {label} |");
        for (key, _) in &columns {
            match points
                .iter()
                .find(|p| row(p) == label && column(p).0 == *key)
            {
                Some(p) => {
                    let _ = write!(out, " {:.3} · {} |", p.ms_per_step, format_error(p.error));
                }
                None => out.push_str(" |"),
            }
        }
        out.push('\n');
    }
    out.push('\n');
}

/// What a report with peers says first: what each engine ran, and what has no counterpart.
pub const PEERS_NOTE: &str = "Box2D v3 (3.2.0) and Rapier 0.36 run the same scenes, rebuilt \
    from carom's world by `carom-bench` with matched parameters, each over its own settings: \
    Box2D over its substeps and contact stiffness (it has no iteration count), Rapier over \
    its solver iterations (its substeps) and stabilization iterations. carom's push-out, \
    tutorial impulse and sequential impulse have no counterpart in either, so only carom has \
    those rows. Joints run at 60 Hz in carom and Box2D, capped at a quarter of the substep \
    rate; Rapier's joints keep their own stiffness. The peers' overlap is not measured.";

/// What a scene with joints says under its heading: why two solvers have no row, and what
/// joint stiffness soft step's rows ran.
pub const JOINTS_NOTE: &str = "The scene has joints: push-out and tutorial impulse leave \
    joints out, so they do not run on it. Soft step's joints are at 60 Hz (Box2D's default), \
    which the solver caps at a quarter of the substep rate (15 Hz at 1 substep, 30 Hz at 2), \
    unless a row names another. Rows named \"direct joints\" solve the hinges' points in one \
    exact solve over each joint tree per pass instead of one joint at a time.";

/// The points of one scene grouped into series: one per solver, and for solvers with substeps
/// one per substep count, in sweep order.
pub fn series_of<'a>(points: &[&'a Point]) -> Vec<(String, Vec<&'a Point>)> {
    let mut series: Vec<(String, Vec<&Point>)> = Vec::new();
    for &p in points {
        let name = series_name(p);
        match series.iter_mut().find(|(n, _)| *n == name) {
            Some((_, members)) => members.push(p),
            None => series.push((name, vec![p])),
        }
    }
    series
}

/// "soft step, 4 substeps, 30 Hz contacts", "soft step, 8 substeps, 30 Hz contacts, 120 Hz
/// joints" (a joint stiffness other than the default), "..., direct joints", "..., shock
/// propagation", or just the solver's name: carom's series, its iterations along each.
pub fn series_name(point: &Point) -> String {
    let solver = point.setting.solver;
    let mut name = solver.name().to_string();
    if solver.has_substeps() {
        let _ = write!(name, ", {}", substeps(point.setting.substeps));
    }
    name_stiffness_and_options(&mut name, &point.setting, false);
    name
}

/// Appends a setting's contact and joint stiffness where named ("30 Hz contacts", or
/// "30 Hz" where `short`), and its options.
pub(crate) fn name_stiffness_and_options(name: &mut String, setting: &Setting, short: bool) {
    if let Some(hertz) = setting.contact_hertz {
        let contacts = if short { "" } else { " contacts" };
        let _ = write!(name, ", {hertz} Hz{contacts}");
    }
    if let Some(hertz) = setting.joint_hertz {
        let _ = write!(name, ", {hertz} Hz joints");
    }
    if setting.direct_joints {
        name.push_str(", direct joints");
    }
    if setting.shock_propagation {
        name.push_str(", shock propagation");
    }
}

/// A setting in words: "soft step, 4 substeps, 2 iterations", "Box2D, 4 substeps, 30 Hz
/// contacts", "Rapier, 4 substeps, 2 stabilization iterations".
pub fn setting_name(setting: &Setting) -> String {
    let it = |n: u32| format!("{n} iteration{}", if n == 1 { "" } else { "s" });
    match setting.engine {
        Engine::Carom => {
            let mut name = setting.solver.name().to_string();
            if setting.solver.has_substeps() {
                let _ = write!(name, ", {}", substeps(setting.substeps));
            }
            let _ = write!(name, ", {}", it(setting.iterations));
            name_stiffness_and_options(&mut name, setting, false);
            name
        }
        Engine::Box2d => match setting.contact_hertz {
            Some(hertz) => format!("Box2D, {}, {hertz} Hz contacts", substeps(setting.substeps)),
            None => format!("Box2D, {}", substeps(setting.substeps)),
        },
        Engine::Rapier => {
            let k = setting.stabilization.unwrap_or(1);
            format!(
                "Rapier, {}, {k} stabilization iteration{}",
                substeps(setting.substeps),
                if k == 1 { "" } else { "s" }
            )
        }
    }
}

fn substeps(n: u32) -> String {
    format!("{n} substep{}", if n == 1 { "" } else { "s" })
}

/// Three significant digits, or `inf`.
fn format_error(error: f64) -> String {
    if error.is_finite() {
        format!("{error:.3e}")
    } else {
        "inf".into()
    }
}

/// Where `measured` disagrees with `committed` (a sweep read back from its CSV) in what the
/// physics decides: each measured point's error and overlap, as the CSV prints them, against
/// the committed point of the same scene and setting. Times are not compared: they are the
/// machine's. One line per difference, naming the scene and the setting; empty when they
/// agree. A measured point the committed sweep does not have is a difference too.
pub fn differences(measured: &[Point], committed: &[Point]) -> Vec<String> {
    let penetration = |p: &Point| {
        if p.max_penetration.is_finite() {
            format!("{:.6}", p.max_penetration)
        } else {
            "not measured".into()
        }
    };
    let mut lines = Vec::new();
    for point in measured {
        let name = format!(
            "{} ({}): {}",
            point.scene,
            point.error_kind.name(),
            setting_name(&point.setting)
        );
        let Some(old) = committed.iter().find(|c| {
            c.scene == point.scene && c.error_kind == point.error_kind && c.setting == point.setting
        }) else {
            lines.push(format!("{name}: not in the committed sweep"));
            continue;
        };
        let (error, old_error) = (format_error(point.error), format_error(old.error));
        if error != old_error {
            lines.push(format!(
                "{name}: error {error} {}, the committed sweep has {old_error}",
                point.error_kind.unit()
            ));
        }
        let (overlap, old_overlap) = (penetration(point), penetration(old));
        if overlap != old_overlap {
            lines.push(format!(
                "{name}: deepest overlap {overlap} m, the committed sweep has {old_overlap}"
            ));
        }
    }
    lines
}

/// Reads back a CSV that [`csv()`] wrote: the points of a sweep, in file order.
///
/// Columns are found by their header names, so this header ([`CSV_HEADER`]) and older ones
/// are read: the one before peers ran (no `engine`, `contact_hertz` nor `stabilization`: every
/// point is carom's), the one before `joints`, and the ones before `direct_joints` and before
/// `shock_propagation` (every point then ran without). Empty `joint_hertz`, `contact_hertz` and
/// `stabilization` fields are `None`, an empty `max_penetration_m` is NaN (a peer's, not
/// measured), `inf` is a world gone NaN. Without a `joints` column, whether a scene has joints
/// is inferred as a sweep leaves it: when a point names a joint stiffness, or when carom ran on
/// it and only the solvers that solve joints did ([`super::solves_joints`]); that changes only
/// what the report says, not any number.
///
/// A line that does not fit is an error naming its line (the header is line 1), the column
/// and what is wrong with it.
pub fn parse_csv(text: &str) -> Result<Vec<Point>, String> {
    const REQUIRED: [&str; 7] = [
        "scene",
        "error_kind",
        "solver",
        "iterations",
        "substeps",
        "ms_per_step",
        "error",
    ];
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        // The provenance lines (`# measured: ...`).
        .comment(Some(b'#'))
        // Lines of the wrong length are read, to be named with what is wrong.
        .flexible(true)
        .from_reader(text.as_bytes());
    let headers = reader.headers().map_err(|e| e.to_string())?.clone();
    if headers.is_empty() {
        return Err("empty CSV: no header".into());
    }
    let columns: Vec<&str> = headers.iter().collect();
    let known: Vec<&str> = CSV_HEADER.split(',').collect();
    if let Some(unknown) = columns.iter().find(|c| !known.contains(c)) {
        return Err(format!(
            "line 1: unknown column `{unknown}` (expected the columns of `{CSV_HEADER}`)"
        ));
    }
    if let Some(missing) = REQUIRED.iter().find(|r| !columns.contains(r)) {
        return Err(format!(
            "line 1: no `{missing}` column in `{}`",
            columns.join(",")
        ));
    }
    let has = |name: &str| columns.contains(&name);
    let mut points = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| e.to_string())?;
        let number = record.position().map_or(0, |p| p.line());
        if record.len() != columns.len() {
            return Err(format!(
                "line {number}: {} fields, the header has {}: `{}`",
                record.len(),
                columns.len(),
                record.iter().collect::<Vec<_>>().join(",")
            ));
        }
        let bad = |name: &str, what: &str| {
            let field = columns
                .iter()
                .position(|c| *c == name)
                .map_or("", |i| &record[i]);
            format!("line {number}: column `{name}`: `{field}` {what}")
        };
        let row: Row = record.deserialize(Some(&headers)).map_err(|e| {
            let column = match e.kind() {
                csv::ErrorKind::Deserialize { err, .. } => {
                    err.field().and_then(|i| columns.get(i as usize).copied())
                }
                _ => None,
            };
            match column {
                Some(name) => bad(name, not_a(name)),
                None => format!("line {number}: {e}"),
            }
        })?;
        points.push(point_of(row, &has, &bad)?);
    }
    if !has("joints") {
        infer_joints(&mut points);
    }
    Ok(points)
}

/// What a field of `column` that does not parse is not.
fn not_a(column: &str) -> &'static str {
    match column {
        "iterations" | "substeps" | "stabilization" => "is not a count of 1 or more",
        "joint_hertz" | "contact_hertz" => "is not a stiffness in Hz",
        "joints" | "direct_joints" | "shock_propagation" => "is not true or false",
        _ => "is not a number",
    }
}

/// The point a row holds, checked: `bad(column, what)` says what is wrong where.
/// `has(column)` says whether the file has the column.
fn point_of(
    row: Row,
    has: &dyn Fn(&str) -> bool,
    bad: &dyn Fn(&str, &str) -> String,
) -> Result<Point, String> {
    let engine = match &row.engine {
        None if !has("engine") => Engine::Carom,
        name => Engine::from_name(name.as_deref().unwrap_or(""))
            .ok_or_else(|| bad("engine", "is no engine (carom, Box2D or Rapier)"))?,
    };
    let error_kind = CSV_ERROR_KINDS
        .into_iter()
        .find(|kind| format!("{kind:?}") == row.error_kind)
        .ok_or_else(|| bad("error_kind", "is no error kind"))?;
    if has("error_unit") && row.error_unit.as_deref() != Some(error_kind.unit()) {
        return Err(bad(
            "error_unit",
            &format!("is not the unit of {error_kind:?} ({})", error_kind.unit()),
        ));
    }
    let solver = carom::SolverKind::ALL
        .into_iter()
        .find(|kind| kind.name() == row.solver)
        .ok_or_else(|| bad("solver", "is no solver"))?;
    if row.ms_per_step.is_nan() || row.ms_per_step < 0.0 {
        return Err(bad("ms_per_step", "is not a time"));
    }
    if row.error.is_nan() || row.error < 0.0 {
        return Err(bad("error", "is not an error (0 or more, or inf)"));
    }
    let count = |n: u32, name: &str| {
        if n > 0 {
            Ok(n)
        } else {
            Err(bad(name, not_a(name)))
        }
    };
    let hertz = |hertz: Option<Real>, name: &str| match hertz {
        Some(h) if !(h.is_finite() && h > 0.0) => Err(bad(name, not_a(name))),
        other => Ok(other),
    };
    Ok(Point {
        scene: row.scene,
        error_kind,
        setting: Setting {
            engine,
            solver,
            iterations: count(row.iterations, "iterations")?,
            substeps: count(row.substeps, "substeps")?,
            joint_hertz: hertz(row.joint_hertz, "joint_hertz")?,
            contact_hertz: hertz(row.contact_hertz, "contact_hertz")?,
            stabilization: row
                .stabilization
                .map(|k| count(k, "stabilization"))
                .transpose()?,
            direct_joints: match row.direct_joints {
                None if !has("direct_joints") => false,
                None => return Err(bad("direct_joints", not_a("direct_joints"))),
                Some(direct) => direct,
            },
            shock_propagation: match row.shock_propagation {
                None if !has("shock_propagation") => false,
                None => return Err(bad("shock_propagation", not_a("shock_propagation"))),
                Some(shock) => shock,
            },
        },
        ms_per_step: row.ms_per_step,
        error: row.error,
        max_penetration: row.max_penetration_m.unwrap_or(f64::NAN),
        joints: match row.joints {
            // Inferred for the whole file afterwards.
            None if !has("joints") => false,
            None => return Err(bad("joints", not_a("joints"))),
            Some(joints) => joints,
        },
    })
}

/// Which scenes have joints, for a file without the `joints` column, as the sweep's choice of
/// solvers shows it: a point names a joint stiffness, or carom ran only solvers that solve
/// joints on the scene.
fn infer_joints(points: &mut [Point]) {
    // Per scene: a joint stiffness named, carom ran, carom ran a solver without joints.
    let mut seen: HashMap<String, (bool, bool, bool)> = HashMap::new();
    for p in points.iter() {
        let entry = seen.entry(p.scene.clone()).or_default();
        entry.0 |= p.setting.joint_hertz.is_some();
        if p.setting.engine == Engine::Carom {
            entry.1 = true;
            entry.2 |= !super::solves_joints(p.setting.solver);
        }
    }
    for p in points.iter_mut() {
        let (stiffness, carom, without_joints) = seen[&p.scene];
        p.joints = stiffness || (carom && !without_joints);
    }
}

/// Every [`super::ErrorKind`], as the CSV names them (their `Debug` names).
const CSV_ERROR_KINDS: [super::ErrorKind; 10] = [
    super::ErrorKind::Rest,
    super::ErrorKind::Conservation,
    super::ErrorKind::SlideAngle,
    super::ErrorKind::Period,
    super::ErrorKind::Stretch,
    super::ErrorKind::Gaps,
    super::ErrorKind::HingeGap,
    super::ErrorKind::PastLimit,
    super::ErrorKind::Sink,
    super::ErrorKind::Overlap,
];

/// Where a point's median ms/step comes from, for the reports: "of one run" or "over N runs
/// (the median of their medians)".
pub fn of_runs(runs: usize) -> String {
    match runs {
        1 => "of one run".to_string(),
        n => format!("over {n} runs (the median of their medians)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::sweep::ErrorKind;
    use carom::SolverKind;

    fn point(substeps: u32, joint_hertz: Option<Real>) -> Point {
        Point {
            scene: "chain".into(),
            error_kind: ErrorKind::Stretch,
            setting: Setting {
                joint_hertz,
                ..Setting::carom(SolverKind::SoftStep, 1, substeps)
            },
            ms_per_step: 0.02,
            error: 6.5,
            max_penetration: 0.0,
            joints: true,
        }
    }

    #[test]
    fn a_joint_scene_says_what_it_leaves_out_and_names_its_stiffer_joints() {
        let mut direct = point(4, None);
        direct.setting.direct_joints = true;
        let points = [
            point(4, None),
            point(8, None),
            point(8, Some(120.0)),
            direct,
        ];
        let provenance = Provenance {
            machine: Machine {
                cpu: "cpu".into(),
                cores: 1,
                date: "2026-11-24".into(),
            },
            command: "carom bench".into(),
            runs: 1,
        };
        assert_eq!(
            Provenance::parse(&provenance.header()).as_ref(),
            Some(&provenance)
        );
        let report = markdown(&points, &provenance);
        assert!(report.contains(JOINTS_NOTE), "{report}");
        assert!(report.contains("worst stretch"), "{report}");
        assert!(
            report.contains("| soft step, 8 substeps, 120 Hz joints |"),
            "{report}"
        );
        assert!(
            report.contains("| soft step, 4 substeps, direct joints |"),
            "{report}"
        );
        assert_eq!(series_name(&points[1]), "soft step, 8 substeps");
        assert_eq!(
            series_name(&points[3]),
            "soft step, 4 substeps, direct joints"
        );
        let csv = csv(&points);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], CSV_HEADER);
        assert!(CSV_HEADER.ends_with(
            "joint_hertz,contact_hertz,stabilization,joints,direct_joints,shock_propagation"
        ));
        assert!(
            lines[2].ends_with(",%,0.000000,,,,true,false,false"),
            "{}",
            lines[2]
        );
        assert!(
            lines[3].ends_with(",%,0.000000,120,,,true,false,false"),
            "{}",
            lines[3]
        );
        assert!(lines[3].starts_with("carom,chain,"), "{}", lines[3]);
        assert!(
            lines[4].ends_with(",%,0.000000,,,,true,true,false"),
            "{}",
            lines[4]
        );
        // Read back, the direct joints are the point's.
        let read = parse_csv(&csv).unwrap();
        assert_eq!(read[3].setting, points[3].setting);
        assert!(!read[0].setting.direct_joints);
    }

    #[test]
    fn shock_propagation_is_named_and_read_back() {
        let mut shock = point(4, None);
        shock.scene = "high_mass_ratio".into();
        shock.error_kind = ErrorKind::Rest;
        shock.joints = false;
        shock.setting.shock_propagation = true;
        assert_eq!(
            series_name(&shock),
            "soft step, 4 substeps, shock propagation"
        );
        assert_eq!(
            setting_name(&shock.setting),
            "soft step, 4 substeps, 1 iteration, shock propagation"
        );
        let csv = csv(std::slice::from_ref(&shock));
        assert!(csv.trim_end().ends_with(",false,false,true"), "{csv}");
        let read = parse_csv(&csv).unwrap();
        assert_eq!(read[0].setting, shock.setting);
        // A file from before the column read as off.
        let older: String = csv
            .lines()
            .map(|line| format!("{}\n", &line[..line.rfind(',').unwrap()]))
            .collect();
        assert!(!parse_csv(&older).unwrap()[0].setting.shock_propagation);
    }

    #[test]
    fn civil_dates_are_right() {
        assert_eq!(civil_date(0), "1970-01-01");
        assert_eq!(civil_date(11_016), "2000-02-29");
        assert_eq!(civil_date(20_780), "2026-11-23");
    }
}

#[cfg(test)]
mod parse_tests {
    use super::*;
    use crate::sweep::ErrorKind;
    use carom::SolverKind;

    fn point(scene: &str, kind: ErrorKind, setting: Setting, ms: f64, error: f64) -> Point {
        Point {
            scene: scene.into(),
            error_kind: kind,
            setting,
            ms_per_step: ms,
            error,
            max_penetration: if setting.engine == Engine::Carom {
                0.0125
            } else {
                f64::NAN
            },
            joints: scene == "chain",
        }
    }

    /// A sweep's worth of points: carom's solvers with and without substeps, a stiffer
    /// joint, a world gone NaN, and both peers.
    fn points() -> Vec<Point> {
        let carom = Setting::carom;
        vec![
            point(
                "stack",
                ErrorKind::Rest,
                carom(SolverKind::PushOut, 8, 1),
                0.0051,
                10.32,
            ),
            point(
                "stack",
                ErrorKind::Rest,
                carom(SolverKind::SoftStep, 2, 4),
                0.0212,
                f64::INFINITY,
            ),
            point(
                "stack",
                ErrorKind::Rest,
                Setting {
                    engine: Engine::Box2d,
                    contact_hertz: Some(30.0),
                    ..carom(SolverKind::SoftStep, 1, 4)
                },
                0.0187,
                1.25e-3,
            ),
            point(
                "stack",
                ErrorKind::Rest,
                Setting {
                    engine: Engine::Rapier,
                    stabilization: Some(2),
                    ..carom(SolverKind::SoftStep, 1, 8)
                },
                0.034,
                0.0,
            ),
            point(
                "chain",
                ErrorKind::Stretch,
                carom(SolverKind::SequentialImpulse, 16, 1),
                0.012,
                6.5,
            ),
            point(
                "chain",
                ErrorKind::Stretch,
                Setting {
                    joint_hertz: Some(120.0),
                    ..carom(SolverKind::SoftStep, 4, 8)
                },
                0.09,
                1.75,
            ),
        ]
    }

    #[test]
    fn what_csv_writes_parse_csv_reads_back() {
        let points = points();
        let text = csv(&points);
        let parsed = parse_csv(&text).unwrap();
        assert_eq!(parsed.len(), points.len());
        for (read, written) in parsed.iter().zip(&points) {
            assert_eq!(read.scene, written.scene);
            assert_eq!(read.error_kind, written.error_kind);
            assert_eq!(read.setting, written.setting);
            assert_eq!(read.joints, written.joints, "{}", read.scene);
            // Written to a microsecond and to three significant digits.
            assert!((read.ms_per_step - written.ms_per_step).abs() < 1e-6);
            let relative = (read.error - written.error).abs() / written.error.max(1e-300);
            assert!(
                read.error == written.error || relative < 1e-3,
                "{} for {}",
                read.error,
                written.error
            );
            assert_eq!(
                read.max_penetration.is_nan(),
                written.max_penetration.is_nan()
            );
        }
        assert_eq!(parsed[1].error, f64::INFINITY);
        // And once read, writing again gives the same text.
        assert_eq!(csv(&parsed), text);
    }

    #[test]
    fn the_header_before_peers_ran_reads_as_carom() {
        let old = "scene,error_kind,solver,iterations,substeps,ms_per_step,error,error_unit,\
                   max_penetration_m,joint_hertz\n\
                   vertical_stack,Rest,push-out,1,1,0.005158,1.032e1,m,0.959006,\n\
                   chain,Stretch,soft step,1,8,0.061234,9.123e-1,%,0.000000,120\n\
                   \n";
        let points = parse_csv(old).unwrap();
        assert_eq!(points.len(), 2);
        assert!(points.iter().all(|p| p.setting.engine == Engine::Carom));
        assert_eq!(points[0].setting, Setting::carom(SolverKind::PushOut, 1, 1));
        assert_eq!(points[0].error, 10.32);
        assert_eq!(points[0].max_penetration, 0.959006);
        assert!(!points[0].joints, "push-out ran on the stack: no joints");
        assert_eq!(points[1].setting.joint_hertz, Some(120.0));
        assert_eq!(points[1].setting.substeps, 8);
        assert!(points[1].joints);
    }

    #[test]
    fn the_checked_in_sweep_parses() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../docs/accuracy/accuracy.csv"
        );
        let text = std::fs::read_to_string(path).unwrap();
        let points = parse_csv(&text).unwrap();
        // It says where and how it was measured, then holds exactly what the writer writes.
        let provenance = Provenance::parse(&text).expect("the provenance lines");
        assert!(provenance.command.starts_with("carom-bench sweep"));
        assert_eq!(text, provenance.header() + &csv(&points));
        assert!(points.iter().any(|p| p.scene == "pendulum" && p.joints));
        assert!(points.iter().any(|p| p.scene == "pyramid" && !p.joints));
    }

    #[test]
    fn a_malformed_line_is_named_with_what_is_wrong() {
        let text = csv(&points());
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        let error_of = |lines: &[String]| parse_csv(&lines.join("\n")).unwrap_err();

        let mut short = lines.clone();
        short[3] = short[3].rsplit_once(',').unwrap().0.to_string();
        let message = error_of(&short);
        assert!(
            message.starts_with("line 4: 15 fields, the header has 16"),
            "{message}"
        );

        let mut solver = lines.clone();
        solver[1] = solver[1].replace("push-out", "push out");
        let message = error_of(&solver);
        assert_eq!(message, "line 2: column `solver`: `push out` is no solver");

        let mut iterations = lines.clone();
        iterations[1] = iterations[1].replace(",push-out,8,", ",push-out,eight,");
        let message = error_of(&iterations);
        assert!(
            message.starts_with("line 2: column `iterations`: `eight`"),
            "{message}"
        );

        let mut engine = lines.clone();
        engine[3] = engine[3].replacen("Box2D", "Bullet", 1);
        let message = error_of(&engine);
        assert!(
            message.starts_with("line 4: column `engine`: `Bullet`"),
            "{message}"
        );

        let mut unit = lines.clone();
        unit[1] = unit[1].replace(",m,", ",%,");
        let message = error_of(&unit);
        assert!(
            message.starts_with("line 2: column `error_unit`"),
            "{message}"
        );

        lines[0] = lines[0].replace("substeps", "sub_steps");
        let message = error_of(&lines);
        assert!(
            message.starts_with("line 1: unknown column `sub_steps`"),
            "{message}"
        );
        assert!(parse_csv("").unwrap_err().contains("no header"));
    }
}
