//! The hard cases as the docs print them: every case in every column that applies (carom's
//! four solvers, soft step with each of its options, Box2D), run side by side, written to a
//! CSV, read back, drawn as markdown tables and checked against what the code gives now.

use super::{Case, Engine, Options, Outcome, cases};
use carom::SolverKind;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// One column of the hard-case tables: an engine and the settings it runs with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Column {
    /// carom's soft step at its defaults (Box2D's settings).
    SoftStep,
    /// Soft step with shock propagation.
    ShockPropagation,
    /// Soft step with direct joints.
    DirectJoints,
    /// Soft step with shock propagation and direct joints.
    BothOptions,
    /// carom's sequential impulse at its defaults (8 iterations).
    SequentialImpulse,
    /// The tutorial's impulse solver.
    TutorialImpulse,
    /// The tutorial's push-out.
    PushOut,
    /// Box2D v3 at its defaults.
    Box2d,
}

impl Column {
    /// Every column, in table order.
    pub const ALL: [Column; 8] = [
        Column::SoftStep,
        Column::ShockPropagation,
        Column::DirectJoints,
        Column::BothOptions,
        Column::Box2d,
        Column::SequentialImpulse,
        Column::TutorialImpulse,
        Column::PushOut,
    ];

    /// Its heading.
    pub fn name(self) -> &'static str {
        match self {
            Column::SoftStep => "soft step",
            Column::ShockPropagation => "soft step, shock propagation",
            Column::DirectJoints => "soft step, direct joints",
            Column::BothOptions => "soft step, both options",
            Column::SequentialImpulse => "sequential impulse",
            Column::TutorialImpulse => "tutorial impulse",
            Column::PushOut => "push-out",
            Column::Box2d => "Box2D v3",
        }
    }

    /// Its name in the CSV.
    pub fn id(self) -> &'static str {
        match self {
            Column::SoftStep => "soft_step",
            Column::ShockPropagation => "shock_propagation",
            Column::DirectJoints => "direct_joints",
            Column::BothOptions => "both_options",
            Column::SequentialImpulse => "sequential_impulse",
            Column::TutorialImpulse => "tutorial_impulse",
            Column::PushOut => "push_out",
            Column::Box2d => "box2d",
        }
    }

    fn from_id(id: &str) -> Option<Column> {
        Column::ALL.into_iter().find(|c| c.id() == id)
    }

    /// The engine and options the column runs a case with. Push-out and tutorial impulse
    /// soak one simulated minute, as the stability suite soaks them: they do not stay at rest
    /// for an hour.
    pub fn side(self, quick: bool) -> (Engine, Options) {
        let carom = |solver| Options {
            quick,
            solver,
            ..Options::default()
        };
        match self {
            Column::SoftStep => (Engine::Carom, carom(SolverKind::SoftStep)),
            Column::ShockPropagation => (
                Engine::Carom,
                Options {
                    shock_propagation: true,
                    ..carom(SolverKind::SoftStep)
                },
            ),
            Column::DirectJoints => (
                Engine::Carom,
                Options {
                    direct_joints: true,
                    ..carom(SolverKind::SoftStep)
                },
            ),
            Column::BothOptions => (
                Engine::Carom,
                Options {
                    direct_joints: true,
                    shock_propagation: true,
                    ..carom(SolverKind::SoftStep)
                },
            ),
            Column::SequentialImpulse => (Engine::Carom, carom(SolverKind::SequentialImpulse)),
            Column::TutorialImpulse => (
                Engine::Carom,
                Options {
                    quick: true,
                    ..carom(SolverKind::TutorialImpulse)
                },
            ),
            Column::PushOut => (
                Engine::Carom,
                Options {
                    quick: true,
                    ..carom(SolverKind::PushOut)
                },
            ),
            Column::Box2d => (Engine::Box2d, carom(SolverKind::SoftStep)),
        }
    }

    /// Whether the column runs `case`: on joints, the options that act on joints and the
    /// solvers that solve them; elsewhere, every solver and shock propagation (direct joints
    /// have nothing to act on).
    pub fn runs(self, case: &Case) -> bool {
        if case.has_joints() {
            !matches!(
                self,
                Column::ShockPropagation | Column::TutorialImpulse | Column::PushOut
            )
        } else {
            !matches!(self, Column::DirectJoints | Column::BothOptions)
        }
    }
}

/// One figure of one case in one column: a line of the CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// The case's name (`--case`).
    pub case: String,
    /// The column's id.
    pub column: String,
    /// What is measured, with its unit.
    pub measure: String,
    /// The bar, as the table prints it (`-` for none).
    pub bar: String,
    /// The figure as the table prints it, bold when it misses its bar; `error: ...` when the
    /// engine failed the case.
    pub cell: String,
}

/// Every case and column asked for, each (case, column) on one of `jobs` threads, carom on
/// one thread; `progress(done, total, what)` is told as each ends, on the calling thread.
/// The rows come back in case order, then column order, then figure order.
pub fn run(
    filter: &[String],
    columns: &[Column],
    quick: bool,
    jobs: usize,
    mut progress: impl FnMut(usize, usize, &str),
) -> Result<Vec<Row>, String> {
    let all = cases();
    let chosen: Vec<&Case> = all
        .iter()
        .filter(|c| filter.is_empty() || filter.iter().any(|f| c.name.contains(f.as_str())))
        .collect();
    if chosen.is_empty() {
        let names: Vec<_> = all.iter().map(|c| c.name).collect();
        return Err(format!(
            "no case matches {filter:?}; the cases: {}",
            names.join(", ")
        ));
    }
    let cells: Vec<(&Case, Column)> = chosen
        .iter()
        .flat_map(|&case| {
            columns
                .iter()
                .filter(move |c| c.runs(case))
                .map(move |&c| (case, c))
        })
        .collect();
    let total = cells.len();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (send, receive) = std::sync::mpsc::channel();
    let mut outcomes: Vec<Option<Result<Outcome, String>>> = vec![None; total];
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, total.max(1)) {
            let (send, next, cells) = (send.clone(), &next, &cells);
            scope.spawn(move || {
                let Ok(one_thread) = rayon::ThreadPoolBuilder::new().num_threads(1).build() else {
                    return;
                };
                loop {
                    let taken = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&(case, column)) = cells.get(taken) else {
                        return;
                    };
                    let (engine, options) = column.side(quick);
                    let outcome = one_thread.install(|| case.run(engine, options));
                    if send.send((taken, outcome)).is_err() {
                        return;
                    }
                }
            });
        }
        drop(send);
        for (done, (cell, outcome)) in receive.iter().enumerate() {
            let (case, column) = cells[cell];
            progress(
                done + 1,
                total,
                &format!("{}: {}", case.name, column.name()),
            );
            outcomes[cell] = Some(outcome);
        }
    });
    let mut rows = Vec::new();
    for (&(case, column), outcome) in cells.iter().zip(outcomes) {
        let outcome =
            outcome.ok_or_else(|| format!("{}: {} did not run", case.name, column.id()))?;
        let row = |measure: &str, bar: &str, cell: String| Row {
            case: case.name.into(),
            column: column.id().into(),
            measure: measure.into(),
            bar: bar.into(),
            cell,
        };
        match outcome {
            Ok(outcome) => {
                for figure in &outcome.figures {
                    let cell = super::cell(figure, outcome.nan);
                    rows.push(row(&figure.measure, &figure.bar.label(), cell));
                }
            }
            Err(e) => rows.push(row("-", "-", format!("error: {e}"))),
        }
    }
    Ok(rows)
}

/// The rows as CSV.
pub fn csv(rows: &[Row]) -> String {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for row in rows {
        writer
            .serialize(row)
            .expect("writing to memory does not fail");
    }
    let bytes = writer
        .into_inner()
        .expect("flushing to memory does not fail");
    String::from_utf8(bytes).expect("every field is text")
}

/// Reads back what [`csv()`] wrote.
pub fn parse_csv(text: &str) -> Result<Vec<Row>, String> {
    let mut reader = csv::ReaderBuilder::new()
        // The provenance lines (`# measured: ...`).
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let mut rows = Vec::new();
    for record in reader.deserialize() {
        let row: Row = record.map_err(|e| e.to_string())?;
        if Column::from_id(&row.column).is_none() {
            return Err(format!("unknown column `{}`", row.column));
        }
        rows.push(row);
    }
    Ok(rows)
}

/// Where `measured` disagrees with `committed`: one line per figure that differs or is
/// missing, naming the case, the column and the measure. Cases in `skip` are left out.
pub fn differences(measured: &[Row], committed: &[Row], skip: &[&str]) -> Vec<String> {
    let mut lines = Vec::new();
    for row in measured.iter().filter(|r| !skip.contains(&r.case.as_str())) {
        let name = format!("{}, {}, {}", row.case, row.column, row.measure);
        match committed
            .iter()
            .find(|c| c.case == row.case && c.column == row.column && c.measure == row.measure)
        {
            None => lines.push(format!("{name}: not in the committed table")),
            Some(old) if old.cell != row.cell || old.bar != row.bar => lines.push(format!(
                "{name}: {} (bar {}), the committed table has {} (bar {})",
                row.cell, row.bar, old.cell, old.bar
            )),
            Some(_) => {}
        }
    }
    lines
}

/// A markdown table of `rows`: a line per case and measure, a column per `columns` (those
/// with no figure for a case print a dash). The case's title heads its first line.
pub fn markdown(rows: &[Row], case_names: &[&str], columns: &[Column]) -> String {
    let titles: Vec<(&str, &str)> = cases().iter().map(|c| (c.name, c.title)).collect();
    let mut out = String::from("| case | measure | bar |");
    for column in columns {
        let _ = write!(out, " {} |", column.name());
    }
    out.push_str("\n|---|---|---|");
    for _ in columns {
        out.push_str("---|");
    }
    out.push('\n');
    for &case in case_names {
        let title = titles
            .iter()
            .find(|(name, _)| *name == case)
            .map_or(case, |(_, title)| title);
        // The case's measures in the order its first column measured them.
        let mut measures: Vec<(&str, &str)> = Vec::new();
        for row in rows.iter().filter(|r| r.case == case) {
            if !measures.iter().any(|(m, _)| *m == row.measure) {
                measures.push((&row.measure, &row.bar));
            }
        }
        for (k, (measure, bar)) in measures.iter().enumerate() {
            let _ = write!(
                out,
                "| {} | {measure} | {bar} |",
                if k == 0 { title } else { "" }
            );
            for column in columns {
                let cell = rows
                    .iter()
                    .find(|r| r.case == case && r.column == column.id() && r.measure == *measure)
                    .map_or("-", |r| r.cell.as_str());
                let _ = write!(out, " {cell} |");
            }
            out.push('\n');
        }
    }
    out
}
