//! Scaling past the threads measured, on paper. Each stage's serial share comes from its time
//! on one thread and on several (Amdahl's law solved for the share), and the shares project the
//! step's time on more threads than the machine has.
//!
//! This is a projection, not a measurement. A share found this way holds everything that kept
//! the stage from running `n` times faster: the part that runs on one thread, and the
//! overheads of sharing (waking workers, waiting at barriers, memory traffic), taken as if they
//! did not shrink either. It stops being true where the memory bus saturates first, or where a
//! stage's share changes with the thread count (a scheduler that steals work better on more
//! threads, a serial part that grows with them).

/// The thread counts the projection is made for.
pub const PROJECTED_THREADS: [usize; 3] = [4, 8, 16];

/// A step's stages as the projection takes them, in order: broadphase, narrowphase, solve,
/// continuous, sleep, and what the step spent outside them.
pub const STAGES: [&str; 6] = [
    "broadphase",
    "narrowphase",
    "solve",
    "continuous",
    "sleep",
    "other",
];

/// The share of a stage's one-thread time `t1` that did not speed up on `threads` threads,
/// where it took `tn`: Amdahl's law, `tn = t1 (s + (1 - s) / threads)`, solved for `s`. Held
/// within 0..=1: a stage that took longer on more threads counts as wholly serial, one that ran
/// more than `threads` times faster as wholly parallel. `None` for a stage too short to tell
/// (under a microsecond on one thread) or on one thread.
pub fn serial_share(t1: f64, tn: f64, threads: usize) -> Option<f64> {
    if threads < 2 || t1.is_nan() || t1 < 1e-3 || !tn.is_finite() {
        return None;
    }
    let n = threads as f64;
    let share = (tn / t1 - 1.0 / n) / (1.0 - 1.0 / n);
    Some(share.clamp(0.0, 1.0))
}

/// The time, ms, of stages that took `t1` each on one thread with these serial shares (a stage
/// without one counted as serial), on `threads` threads.
pub fn projected_ms(stages: &[(f64, Option<f64>)], threads: usize) -> f64 {
    let n = threads.max(1) as f64;
    stages
        .iter()
        .map(|&(t1, share)| {
            let s = share.unwrap_or(1.0);
            t1 * (s + (1.0 - s) / n)
        })
        .sum()
}

/// The share of the whole step that is serial, from its stages' times on one thread and their
/// shares: the shares weighted by time.
pub fn step_share(stages: &[(f64, Option<f64>)]) -> f64 {
    let total: f64 = stages.iter().map(|s| s.0).sum();
    if total <= 0.0 {
        return 0.0;
    }
    stages
        .iter()
        .map(|&(t1, share)| t1 * share.unwrap_or(1.0))
        .sum::<f64>()
        / total
}

/// Each of the six [`STAGES`]' one-thread time and serial share, from the stages' times on one
/// thread (`one`) and on `threads` (`many`), each `[step, broadphase, narrowphase, solve,
/// continuous, sleep]` (what the step spent outside the five is the sixth stage).
pub fn stage_shares(one: [f64; 6], many: [f64; 6], threads: usize) -> [(f64, Option<f64>); 6] {
    let split = |ms: [f64; 6]| -> [f64; 6] {
        let [step, broad, narrow, solve, continuous, sleep] = ms;
        let other = (step - broad - narrow - solve - continuous - sleep).max(0.0);
        [broad, narrow, solve, continuous, sleep, other]
    };
    let (one, many) = (split(one), split(many));
    std::array::from_fn(|k| (one[k], serial_share(one[k], many[k], threads)))
}

/// One engine's stages on a scene, on one thread and on `threads`, for [`markdown`].
#[derive(Debug, Clone)]
pub struct Measured {
    /// The scene's name.
    pub scene: String,
    /// The engine's name.
    pub engine: String,
    /// The thread count of `many`.
    pub threads: usize,
    /// `[step, broadphase, narrowphase, solve, continuous, sleep]`, ms per step, one thread.
    pub one: [f64; 6],
    /// The same on `threads`.
    pub many: [f64; 6],
}

/// Two tables from `rows`: each stage's serial share, and the step's time on one thread and
/// `threads` (measured) beside its projection on [`PROJECTED_THREADS`].
pub fn markdown(rows: &[Measured]) -> String {
    use std::fmt::Write as _;
    let threads = rows.first().map_or(2, |r| r.threads);
    let mut out = format!(
        "Serial share of each stage: the part of its one-thread time that did not speed up on \
         {threads} threads (Amdahl's law; a dash where the stage takes under a microsecond), \
         and of the whole step, weighted by time.\n\n| scene | engine | {} | step |\n|---|---|{}---|\n",
        STAGES.join(" | "),
        "---|".repeat(STAGES.len())
    );
    let percent =
        |share: Option<f64>| share.map_or("–".to_string(), |s| format!("{:.0} %", 100.0 * s));
    for r in rows {
        let stages = stage_shares(r.one, r.many, r.threads);
        let _ = write!(out, "| {} | {} |", r.scene, r.engine);
        for (_, share) in stages {
            let _ = write!(out, " {} |", percent(share));
        }
        let _ = writeln!(out, " {} |", percent(Some(step_share(&stages))));
    }
    let _ = write!(
        out,
        "\nms per step: measured on 1 and {threads} threads; projected from the serial shares on \
         {}.\n\n| scene | engine | 1 thread | {threads} threads |{}\n|---|---|---|---|{}\n",
        PROJECTED_THREADS.map(|n| n.to_string()).join(", "),
        PROJECTED_THREADS
            .map(|n| format!(" {n} (projected) |"))
            .concat(),
        "---|".repeat(PROJECTED_THREADS.len())
    );
    for r in rows {
        let stages = stage_shares(r.one, r.many, r.threads);
        let _ = write!(
            out,
            "| {} | {} | {:.3} | {:.3} |",
            r.scene, r.engine, r.one[0], r.many[0]
        );
        for n in PROJECTED_THREADS {
            let _ = write!(out, " {:.3} |", projected_ms(&stages, n));
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn amdahl_solved_for_the_share_gives_it_back() {
        // A stage a quarter serial: 8 ms on one thread, 8 (0.25 + 0.75 / 2) = 5 ms on two.
        let share = serial_share(8.0, 5.0, 2).unwrap();
        assert!((share - 0.25).abs() < 1e-12, "{share}");
        // Projected on four threads: 8 (0.25 + 0.75 / 4) = 3.5 ms.
        let four = projected_ms(&[(8.0, Some(share))], 4);
        assert!((four - 3.5).abs() < 1e-12, "{four}");
    }

    #[test]
    fn shares_are_held_within_what_amdahl_allows() {
        // Slower on two threads: all serial. More than twice as fast: all parallel.
        assert_eq!(serial_share(4.0, 5.0, 2), Some(1.0));
        assert_eq!(serial_share(4.0, 1.5, 2), Some(0.0));
        // Too short to tell, or nothing to compare with.
        assert_eq!(serial_share(0.0, 0.0, 2), None);
        assert_eq!(serial_share(4.0, 2.0, 1), None);
        assert_eq!(serial_share(f64::NAN, 2.0, 2), None);
    }

    #[test]
    fn the_step_s_share_is_its_stages_weighted_by_time() {
        // 6 ms wholly parallel, 2 ms wholly serial, and a stage too short to tell (serial).
        let stages = [(6.0, Some(0.0)), (2.0, Some(1.0)), (0.0, None)];
        assert!((step_share(&stages) - 0.25).abs() < 1e-12);
        // On 16 threads: 6 / 16 + 2.
        assert!((projected_ms(&stages, 16) - (6.0 / 16.0 + 2.0)).abs() < 1e-12);
    }

    #[test]
    fn the_tables_hold_a_row_per_engine_and_the_projection() {
        let row = Measured {
            scene: "pile".into(),
            engine: "carom".into(),
            threads: 2,
            one: [8.0, 0.0, 0.0, 8.0, 0.0, 0.0],
            many: [5.0, 0.0, 0.0, 5.0, 0.0, 0.0],
        };
        let text = markdown(&[row]);
        // The solve is a quarter serial, and so is the step; on 4 threads, 3.5 ms.
        assert!(
            text.contains("| pile | carom | – | – | 25 % | – | – | – | 25 % |"),
            "{text}"
        );
        assert!(
            text.contains("| pile | carom | 8.000 | 5.000 | 3.500 |"),
            "{text}"
        );
    }

    #[test]
    fn what_the_step_spent_outside_the_stages_is_a_stage_of_its_own() {
        let one = [10.0, 2.0, 3.0, 4.0, 0.0, 0.0];
        let many = [6.0, 1.0, 1.5, 2.5, 0.0, 0.0];
        let shares = stage_shares(one, many, 2);
        assert_eq!(shares[5].0, 1.0);
        assert_eq!(shares[5].1, Some(1.0), "the 1 ms outside stayed 1 ms");
        assert_eq!(shares[0].1, Some(0.0));
        assert_eq!(shares[3].1, None, "no continuous stage");
    }
}
