//! Pareto fronts: the settings no other setting beats in both time and error, and which
//! engine is best within a time budget.

use super::{Engine, Point};

/// The points of `points` on their Pareto front, fastest first: each is more accurate than
/// every faster point (a point with a non-finite error, a world gone NaN, is on no front).
pub fn pareto_front<'a>(points: &[&'a Point]) -> Vec<&'a Point> {
    let mut sorted: Vec<&Point> = points
        .iter()
        .copied()
        .filter(|p| p.error.is_finite() && p.ms_per_step.is_finite())
        .collect();
    sorted.sort_by(|a, b| {
        a.ms_per_step
            .total_cmp(&b.ms_per_step)
            .then(a.error.total_cmp(&b.error))
    });
    let mut front: Vec<&Point> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|best| p.error < best.error) {
            front.push(p);
        }
    }
    front
}

/// The smallest error `engine` reaches within `budget` ms per step on these points, and the
/// point that reaches it.
pub fn best_within<'a>(points: &[&'a Point], engine: Engine, budget: f64) -> Option<&'a Point> {
    points
        .iter()
        .copied()
        .filter(|p| p.setting.engine == engine && p.ms_per_step <= budget && p.error.is_finite())
        .min_by(|a, b| a.error.total_cmp(&b.error))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::{ErrorKind, Setting};
    use carom::SolverKind;

    fn point(engine: Engine, ms: f64, error: f64) -> Point {
        Point {
            scene: "s".into(),
            error_kind: ErrorKind::Rest,
            setting: Setting {
                engine,
                ..Setting::carom(SolverKind::SoftStep, 1, 4)
            },
            ms_per_step: ms,
            error,
            max_penetration: 0.0,
            joints: false,
        }
    }

    #[test]
    fn the_front_keeps_only_what_nothing_beats_in_both() {
        let points = [
            point(Engine::Carom, 1.0, 0.5),
            point(Engine::Carom, 2.0, 0.6), // slower and worse than the first
            point(Engine::Carom, 3.0, 0.1),
            point(Engine::Carom, 0.5, 0.9),
            point(Engine::Carom, 4.0, f64::INFINITY), // went NaN
            point(Engine::Carom, 5.0, 0.1),           // as good as a faster one
        ];
        let refs: Vec<&Point> = points.iter().collect();
        let front: Vec<(f64, f64)> = pareto_front(&refs)
            .iter()
            .map(|p| (p.ms_per_step, p.error))
            .collect();
        assert_eq!(front, [(0.5, 0.9), (1.0, 0.5), (3.0, 0.1)]);
    }

    #[test]
    fn the_best_within_a_budget_is_per_engine() {
        let points = [
            point(Engine::Carom, 0.05, 0.5),
            point(Engine::Carom, 0.8, 0.2),
            point(Engine::Box2d, 0.09, 0.3),
            point(Engine::Box2d, 5.0, 0.01),
        ];
        let refs: Vec<&Point> = points.iter().collect();
        let error = |engine, budget| best_within(&refs, engine, budget).map(|p| p.error);
        assert_eq!(error(Engine::Carom, 0.1), Some(0.5));
        assert_eq!(error(Engine::Box2d, 0.1), Some(0.3));
        assert_eq!(error(Engine::Carom, 1.0), Some(0.2));
        assert_eq!(error(Engine::Box2d, 10.0), Some(0.01));
        assert_eq!(error(Engine::Rapier, 10.0), None);
    }
}
