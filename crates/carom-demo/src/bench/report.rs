//! The sweep written down: a CSV of every point and a markdown report with one table per scene.

use super::{Engine, Point, Setting, front};
use std::fmt::Write as _;
use std::time::{SystemTime, UNIX_EPOCH};

/// The CSV header, in the order [`csv`] writes the columns.
pub const CSV_HEADER: &str = "engine,scene,error_kind,solver,iterations,substeps,ms_per_step,\
                              error,error_unit,max_penetration_m,joint_hertz,contact_hertz,\
                              stabilization";

/// Every point as one CSV line. NaN worlds have the error `inf`; `joint_hertz` is empty for
/// the solver's default (60 Hz, capped at a quarter of the substep rate), `contact_hertz`
/// where the scene's own contact stiffness ran, `stabilization` for all but Rapier, and
/// `max_penetration_m` for the peers, whose overlap is not measured.
pub fn csv(points: &[Point]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    let or_empty = |value: Option<String>| value.unwrap_or_default();
    for p in points {
        let _ = writeln!(
            out,
            "{},{},{:?},{},{},{},{:.6},{},{},{},{},{},{}",
            p.setting.engine.name(),
            p.scene,
            p.error_kind,
            p.setting.solver.name(),
            p.setting.iterations,
            p.setting.substeps,
            p.ms_per_step,
            format_error(p.error),
            p.error_kind.unit(),
            or_empty(
                p.max_penetration
                    .is_finite()
                    .then(|| format!("{:.6}", p.max_penetration))
            ),
            or_empty(p.setting.joint_hertz.map(|h| h.to_string())),
            or_empty(p.setting.contact_hertz.map(|h| h.to_string())),
            or_empty(p.setting.stabilization.map(|k| k.to_string())),
        );
    }
    out
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
pub fn markdown(points: &[Point], machine: &Machine, command: &str, runs: usize) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# What accuracy costs in time\n");
    let _ = writeln!(
        out,
        "Measured {} on {} ({} cores) with `{command}`: every cell is the median ms/step over \
         {runs} runs and the error against the scene's exact answer. Release build, sleeping \
         off (every step is solved), scenes this size run on one thread. `inf` means the world \
         went NaN.\n",
        machine.date, machine.cpu, machine.cores
    );
    let mut engines: Vec<Engine> = points.iter().map(|p| p.setting.engine).collect();
    engines.sort_unstable();
    engines.dedup();
    if engines.len() > 1 {
        let _ = writeln!(out, "{PEERS_NOTE}\n");
    }
    let _ = writeln!(out, "![error against time](accuracy.png)\n");
    let mut scenes: Vec<&str> = points.iter().map(|p| p.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let of_scene: Vec<&Point> = points.iter().filter(|p| p.scene == scene).collect();
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
    unless a row names another.";

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
/// joints" (a joint stiffness other than the default), or just the solver's name: carom's
/// series, its iterations along each.
pub fn series_name(point: &Point) -> String {
    let solver = point.setting.solver;
    let mut name = solver.name().to_string();
    if solver.has_substeps() {
        let _ = write!(name, ", {}", substeps(point.setting.substeps));
    }
    if let Some(hertz) = point.setting.contact_hertz {
        let _ = write!(name, ", {hertz} Hz contacts");
    }
    if let Some(hertz) = point.setting.joint_hertz {
        let _ = write!(name, ", {hertz} Hz joints");
    }
    name
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
            if let Some(hertz) = setting.contact_hertz {
                let _ = write!(name, ", {hertz} Hz contacts");
            }
            if let Some(hertz) = setting.joint_hertz {
                let _ = write!(name, ", {hertz} Hz joints");
            }
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

#[cfg(test)]
mod tests {
    use super::*;

    use crate::bench::ErrorKind;
    use carom::SolverKind;

    fn point(substeps: u32, joint_hertz: Option<f32>) -> Point {
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
        let points = [point(4, None), point(8, None), point(8, Some(120.0))];
        let machine = Machine {
            cpu: "cpu".into(),
            cores: 1,
            date: "2026-11-24".into(),
        };
        let report = markdown(&points, &machine, "carom bench", 1);
        assert!(report.contains(JOINTS_NOTE), "{report}");
        assert!(report.contains("worst stretch"), "{report}");
        assert!(
            report.contains("| soft step, 8 substeps, 120 Hz joints |"),
            "{report}"
        );
        assert_eq!(series_name(&points[1]), "soft step, 8 substeps");
        let csv = csv(&points);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], CSV_HEADER);
        assert!(CSV_HEADER.ends_with("max_penetration_m,joint_hertz,contact_hertz,stabilization"));
        assert!(lines[2].ends_with(",%,0.000000,,,"), "{}", lines[2]);
        assert!(lines[3].ends_with(",%,0.000000,120,,"), "{}", lines[3]);
        assert!(lines[3].starts_with("carom,chain,"), "{}", lines[3]);
    }

    #[test]
    fn civil_dates_are_right() {
        assert_eq!(civil_date(0), "1970-01-01");
        assert_eq!(civil_date(11_016), "2000-02-29");
        assert_eq!(civil_date(20_780), "2026-11-23");
    }
}
