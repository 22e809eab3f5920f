//! What accuracy costs, live: step times and error measures over the last seconds.

use carom::{Real, World};
use std::collections::VecDeque;

/// One step's cost and error.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepSample {
    /// Simulated time at the end of the step, s.
    pub time: f64,
    /// Wall time of the whole step, ms.
    pub step_ms: f64,
    /// Broadphase, narrowphase, solver, continuous and sleep, ms.
    pub stage_ms: [f64; 5],
    /// Deepest overlap after the step, m.
    pub max_penetration: Real,
    /// Mean speed of the bodies that should be at rest (slower than [`REST_SPEED`]), m/s.
    pub rest_drift: f32,
    /// Kinetic plus gravitational potential energy minus its value at the start, J.
    pub energy_change: f32,
}

/// Bodies slower than this count as resting for the drift measure, m/s.
pub const REST_SPEED: Real = 0.1;

/// The names of [`StepSample::stage_ms`], in order.
pub const STAGES: [&str; 5] = ["broadphase", "narrowphase", "solve", "continuous", "sleep"];

/// The last [`Metrics::CAPACITY`] steps.
#[derive(Debug, Clone, Default)]
pub struct Metrics {
    samples: VecDeque<StepSample>,
    start_energy: Option<f64>,
}

impl Metrics {
    /// Steps kept: ten seconds at 60 Hz.
    pub const CAPACITY: usize = 600;
    /// Steps the medians are taken over.
    pub const WINDOW: usize = 60;

    /// Forgets everything (a new scene, a reset).
    pub fn clear(&mut self) {
        self.samples.clear();
        self.start_energy = None;
    }

    /// Records the step just taken, which took `step_ms` of wall time.
    pub fn record(&mut self, world: &World, step_ms: f64) {
        let times = &world.stats().times;
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let energy = mechanical_energy(world);
        let start = *self.start_energy.get_or_insert(energy);
        let (mut resting, mut resting_speed) = (0usize, 0.0f64);
        for body in world.bodies().filter(|b| b.is_dynamic()) {
            let speed = body.linear_velocity().norm();
            if speed < REST_SPEED {
                resting += 1;
                resting_speed += speed as f64;
            }
        }
        if self.samples.len() == Self::CAPACITY {
            self.samples.pop_front();
        }
        self.samples.push_back(StepSample {
            time: world.time(),
            step_ms,
            stage_ms: [
                ms(times.broadphase),
                ms(times.narrowphase),
                ms(times.solve),
                ms(times.continuous),
                ms(times.sleep),
            ],
            max_penetration: world.stats().max_penetration,
            rest_drift: if resting > 0 {
                (resting_speed / resting as f64) as f32
            } else {
                0.0
            },
            energy_change: (energy - start) as f32,
        });
    }

    /// Every sample kept, oldest first.
    pub fn samples(&self) -> &VecDeque<StepSample> {
        &self.samples
    }

    /// The newest sample.
    pub fn latest(&self) -> Option<&StepSample> {
        self.samples.back()
    }

    /// Median over the last [`Metrics::WINDOW`] steps of what `value` picks.
    pub fn median(&self, value: impl Fn(&StepSample) -> f64) -> f64 {
        let mut recent: Vec<f64> = self
            .samples
            .iter()
            .rev()
            .take(Self::WINDOW)
            .map(value)
            .collect();
        if recent.is_empty() {
            return 0.0;
        }
        recent.sort_by(f64::total_cmp);
        recent[recent.len() / 2]
    }

    /// Mean over the last [`Metrics::WINDOW`] steps of what `value` picks.
    pub fn mean(&self, value: impl Fn(&StepSample) -> f64) -> f64 {
        let recent = self.samples.iter().rev().take(Self::WINDOW);
        let count = recent.len();
        if count == 0 {
            return 0.0;
        }
        recent.map(value).sum::<f64>() / count as f64
    }

    /// The typical step cost: the median, or in a browser the mean. A browser's clock ticks
    /// in steps of 0.1 ms, blurred by noise so pages cannot time other sites; the median of
    /// a fast scene's steps is then 0, the mean still close to the truth.
    pub fn typical(&self, value: impl Fn(&StepSample) -> f64) -> f64 {
        if cfg!(target_arch = "wasm32") {
            self.mean(value)
        } else {
            self.median(value)
        }
    }

    /// What [`Metrics::typical`] takes, for labels.
    pub const TYPICAL: &str = if cfg!(target_arch = "wasm32") {
        "mean"
    } else {
        "median"
    };
}

/// Kinetic energy plus gravity's potential energy (zero at height zero), J.
fn mechanical_energy(world: &World) -> f64 {
    let gravity = if world.effects().contains(carom::Effect::Gravity) {
        world.gravity()
    } else {
        carom::Vec2::zeros()
    };
    world
        .bodies()
        .filter(|b| b.is_dynamic())
        .map(|b| {
            let potential = -(b.mass() * b.gravity_scale() * gravity.dot(&b.position()));
            (b.kinetic_energy() + potential) as f64
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom::{BodyDef, Shape, vec2};

    #[test]
    fn free_fall_keeps_its_energy_and_a_resting_box_does_not_drift() {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 20.0)))
            .unwrap();
        let mut metrics = Metrics::default();
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
            metrics.record(&world, 1.0);
        }
        // Half a second of free fall: semi-implicit Euler gains a sliver of energy, no more.
        let falling = metrics.latest().unwrap();
        assert!(falling.energy_change.abs() < 0.5, "{falling:?}");
        for _ in 0..300 {
            world.step(1.0 / 60.0).unwrap();
            metrics.record(&world, 2.0);
        }
        let resting = metrics.latest().unwrap();
        // The landing took energy away; the box now rests without creeping.
        assert!(resting.energy_change < -100.0, "{resting:?}");
        assert!(resting.rest_drift < 1e-3, "{resting:?}");
        assert_eq!(metrics.median(|s| s.step_ms), 2.0);
        assert_eq!(metrics.samples().len(), 330);
    }
}
