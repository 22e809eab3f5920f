//! The sweep written down: a CSV of every point and a markdown report with one table per scene.

use super::Point;
use std::fmt::Write as _;
use std::time::{SystemTime, UNIX_EPOCH};

/// The CSV header, in the order [`csv`] writes the columns.
pub const CSV_HEADER: &str = "scene,error_kind,solver,iterations,substeps,ms_per_step,error,\
                              error_unit,max_penetration_m,joint_hertz";

/// Every point as one CSV line (NaN worlds have the error `inf`; `joint_hertz` is empty for
/// the solver's default, 60 Hz capped at a quarter of the substep rate).
pub fn csv(points: &[Point]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for p in points {
        let _ = writeln!(
            out,
            "{},{:?},{},{},{},{:.6},{},{},{:.6},{}",
            p.scene,
            p.error_kind,
            p.setting.solver.name(),
            p.setting.iterations,
            p.setting.substeps,
            p.ms_per_step,
            format_error(p.error),
            p.error_kind.unit(),
            p.max_penetration,
            p.setting
                .joint_hertz
                .map_or(String::new(), |hertz| hertz.to_string())
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

/// The markdown report: the machine, then per scene a table with a row per solver (and
/// substep count) and a column per iteration count, each cell "ms/step · error".
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
        if of_scene[0].joints {
            let _ = writeln!(out, "{JOINTS_NOTE}\n");
        }
        let mut iterations: Vec<u32> = of_scene.iter().map(|p| p.setting.iterations).collect();
        iterations.sort_unstable();
        iterations.dedup();
        let _ = write!(out, "| solver |");
        for i in &iterations {
            let _ = write!(out, " {i} it |");
        }
        let _ = write!(out, "\n|---|");
        for _ in &iterations {
            let _ = write!(out, "---|");
        }
        out.push('\n');
        for series in series_of(&of_scene) {
            let _ = write!(out, "| {} |", series.0);
            for i in &iterations {
                match series.1.iter().find(|p| p.setting.iterations == *i) {
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
    out
}

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

/// "soft step, 4 substeps", "soft step, 8 substeps, 120 Hz joints" (a joint stiffness
/// other than the default), or just the solver's name.
pub fn series_name(point: &Point) -> String {
    let solver = point.setting.solver;
    let mut name = solver.name().to_string();
    if solver.has_substeps() {
        let substeps = point.setting.substeps;
        let plural = if substeps == 1 { "" } else { "s" };
        let _ = write!(name, ", {substeps} substep{plural}");
    }
    if let Some(hertz) = point.setting.joint_hertz {
        let _ = write!(name, ", {hertz} Hz joints");
    }
    name
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

    use crate::bench::{ErrorKind, Setting};
    use carom::SolverKind;

    fn point(substeps: u32, joint_hertz: Option<f32>) -> Point {
        Point {
            scene: "chain".into(),
            error_kind: ErrorKind::Stretch,
            setting: Setting {
                solver: SolverKind::SoftStep,
                iterations: 1,
                substeps,
                joint_hertz,
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
        assert!(CSV_HEADER.ends_with("max_penetration_m,joint_hertz"));
        assert!(lines[2].ends_with(",%,0.000000,"), "{}", lines[2]);
        assert!(lines[3].ends_with(",%,0.000000,120"), "{}", lines[3]);
    }

    #[test]
    fn civil_dates_are_right() {
        assert_eq!(civil_date(0), "1970-01-01");
        assert_eq!(civil_date(11_016), "2000-02-29");
        assert_eq!(civil_date(20_780), "2026-11-23");
    }
}
