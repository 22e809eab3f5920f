//! What contacts that look a step ahead cost, and what they buy: carom with
//! `WorldSettings::look_ahead` on (its default: a pair's contact is made as soon as the two can
//! close within a step, so an impact at any speed stops at the surface) and off (Box2D's
//! promise: points kept within the speculative distance only, a fast body sinking in for a
//! step), beside Box2D v3, all on one thread, with the deepest overlap each lets a step start
//! from. `carom-bench look-ahead` writes the table docs/bench draws.

use carom_scene::SceneWorld;

use crate::box2d_world::Box2dWorld;
use crate::compare::{Overlap, RunResult, box2d_deepest_overlap, run_box2d, run_carom};

/// One scene's figures, in the order carom with look-ahead, carom without, Box2D.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The scene's name.
    pub scene: String,
    /// ms per step, the best of the runs.
    pub ms: [f64; 3],
    /// Contacts held, the mean over the timed steps.
    pub contacts: [f64; 3],
    /// The deepest overlap the narrowphase found at the start of a timed step, m.
    pub deepest: [Overlap; 3],
    /// Some of Box2D's contacts could not be read back: its overlap is a lower bound.
    pub box2d_unread: bool,
}

/// Times `load`'s scene `runs` times in each of the three, in turn (carom on, carom off,
/// Box2D, then again), for `steps` steps of `dt`, the first untimed, on the calling thread's
/// pool (carom) and one worker (Box2D); then steps Box2D once more, untimed, for its deepest
/// overlap. The scene's spawns are replayed in Box2D as the speed comparison does.
///
/// # Errors
/// A scene that does not load or step, or that Box2D cannot build.
pub fn measure(
    scene: &str,
    load: impl Fn() -> Result<SceneWorld, String>,
    steps: u32,
    runs: u32,
    dt: f32,
) -> Result<Row, String> {
    let load = || {
        let mut scene = load()?;
        scene.time_step = dt;
        Ok::<_, String>(scene)
    };
    let carom = |look_ahead: bool| -> Result<RunResult, String> {
        let mut scene = load()?;
        scene
            .world
            .update_settings(|s| s.look_ahead = look_ahead)
            .map_err(|e| e.to_string())?;
        run_carom(&mut scene, steps)
    };
    let schedule = load()?.spawn_schedule(u64::from(steps))?;
    let replayed = (!schedule.changes.is_empty()).then_some(&schedule);
    let box2d = || -> Result<Box2dWorld, String> { Box2dWorld::with_workers(&load()?.world, 1) };
    let mut best: [Option<RunResult>; 3] = [None, None, None];
    for run in 1..=runs {
        let results = [
            carom(true)?,
            carom(false)?,
            run_box2d(&mut box2d()?, dt, steps, replayed)?,
        ];
        eprintln!(
            "{scene} run {run}: carom with look-ahead {:.3}, without {:.3}, Box2D {:.3} ms/step",
            results[0].ms_per_step(),
            results[1].ms_per_step(),
            results[2].ms_per_step()
        );
        for (kept, result) in best.iter_mut().zip(results) {
            if kept.as_ref().is_none_or(|k| result.total_ms < k.total_ms) {
                *kept = Some(result);
            }
        }
    }
    let [Some(on), Some(off), Some(peer)] = best else {
        return Err("no runs".into());
    };
    let contacts = |r: &RunResult| r.stages.as_ref().map_or(f64::NAN, |s| s.contacts);
    let (box2d_deepest, box2d_unread) = box2d_deepest_overlap(&mut box2d()?, dt, steps, replayed)?;
    Ok(Row {
        scene: scene.to_string(),
        ms: [on.ms_per_step(), off.ms_per_step(), peer.ms_per_step()],
        contacts: [contacts(&on), contacts(&off), contacts(&peer)],
        deepest: [on.deepest_overlap, off.deepest_overlap, box2d_deepest],
        box2d_unread,
    })
}

/// The rows as the CSV `carom-bench measure` takes: a header as the doc shows it, then a
/// line per scene (times in ms, ratios to Box2D's time, contacts, and the overlaps in mm, the
/// deepest of the run and the mean of each step's deepest; Box2D's as "at least" where some
/// of its contacts could not be read back).
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from(
        "scene,carom with look-ahead (ms),carom without (ms),Box2D (ms),with / Box2D,\
         without / Box2D,contacts with,contacts without,Box2D's contacts,\
         deepest overlap with (mm),without (mm),Box2D's (mm),\
         mean step's deepest with (mm),without (mm),Box2D's (mm)\n",
    );
    for r in rows {
        let mm = |m: f32, peer: bool| {
            let figure = format!("{:.1}", m * 1000.0);
            if peer && r.box2d_unread {
                format!("at least {figure}")
            } else {
                figure
            }
        };
        let [on, off, peer] = r.deepest;
        out.push_str(&format!(
            "`{}`,{:.3},{:.3},{:.3},{:.2},{:.2},{:.0},{:.0},{:.0},{},{},{},{},{},{}\n",
            r.scene,
            r.ms[0],
            r.ms[1],
            r.ms[2],
            r.ms[0] / r.ms[2],
            r.ms[1] / r.ms[2],
            r.contacts[0],
            r.contacts[1],
            r.contacts[2],
            mm(on.most, false),
            mm(off.most, false),
            mm(peer.most, true),
            mm(on.mean, false),
            mm(off.mean, false),
            mm(peer.mean, true),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_csv_has_a_line_per_scene_with_every_column() {
        let row = Row {
            scene: "spinner".into(),
            ms: [30.0, 24.0, 20.0],
            contacts: [25_000.0, 22_000.0, 21_000.0],
            deepest: [(0.012, 0.001), (0.25, 0.002), (0.3, 0.003)]
                .map(|(most, mean)| Overlap { most, mean }),
            box2d_unread: true,
        };
        let text = csv(&[row]);
        let (header, rows) = crate::measured::check(&text).unwrap();
        assert_eq!(rows.len(), 1);
        assert_eq!(rows[0].len(), header.len());
        assert_eq!(rows[0][4], "1.50");
        assert_eq!(rows[0][5], "1.20");
        assert_eq!(rows[0][10], "250.0");
        assert_eq!(rows[0][11], "at least 300.0");
        assert_eq!(rows[0][13], "2.0");
    }
}
