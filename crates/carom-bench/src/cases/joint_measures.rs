//! What the joint scenes are measured by: how far joints come apart, how far past their
//! limits they turn, how much a chain stretches, a pendulum's period and energy.

use carom::{Joint, JointKind, Real, World};

/// The distance between a joint's two anchors, m: zero for a hinge held together.
pub fn separation(world: &World, joint: &Joint) -> Real {
    let [a, b] = joint
        .bodies()
        .map(|h| world.body(h).expect("joints join live bodies"));
    let [pa, pb] = joint.world_anchors(a, b);
    (pb - pa).norm()
}

/// The largest anchor separation of the world's hinges, m.
pub fn worst_hinge_separation(world: &World) -> Real {
    world
        .joints()
        .filter(|j| matches!(j.kind(), JointKind::Revolute(_)))
        .map(|j| separation(world, j))
        .fold(0.0, Real::max)
}

/// How far past its limits a hinge has turned, rad (0 within them).
pub fn limit_violation(world: &World, joint: &Joint) -> Real {
    let JointKind::Revolute(hinge) = joint.kind() else {
        return 0.0;
    };
    let Some(limits) = hinge.limits else {
        return 0.0;
    };
    let [a, b] = joint
        .bodies()
        .map(|h| world.body(h).expect("joints join live bodies"));
    let angle = joint.angle(a, b);
    (limits.lower - angle).max(angle - limits.upper).max(0.0)
}

/// The largest limit violation of the world's hinges, rad.
pub fn worst_limit_violation(world: &World) -> Real {
    world
        .joints()
        .map(|j| limit_violation(world, j))
        .fold(0.0, Real::max)
}

/// The sum of the hinges' anchor separations, m: how much longer a chain of them is than its
/// links laid end to end.
pub fn total_hinge_separation(world: &World) -> Real {
    world
        .joints()
        .filter(|j| matches!(j.kind(), JointKind::Revolute(_)))
        .map(|j| separation(world, j))
        .sum()
}

/// The mean period of a signal's upward zero crossings, linearly interpolated, from samples
/// `(t, x)`; `None` with fewer than three crossings. The stability suite measures in carom's
/// `Real`, the accuracy sweep in double precision.
pub fn period<T: Sample>(samples: &[(T, T)]) -> Option<T> {
    let mut crossings = Vec::new();
    for pair in samples.windows(2) {
        let ((t0, x0), (t1, x1)) = (pair[0], pair[1]);
        if x0 < T::ZERO && x1 >= T::ZERO {
            crossings.push(t0 + (t1 - t0) * (-x0 / (x1 - x0)));
        }
    }
    (crossings.len() >= 3).then(|| {
        (crossings[crossings.len() - 1] - crossings[0]) / T::from_count(crossings.len() - 1)
    })
}

/// A number [`period`] measures in: `f32` or `f64`.
pub trait Sample:
    Copy
    + PartialOrd
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::Neg<Output = Self>
{
    /// Zero.
    const ZERO: Self;
    /// A count as this type.
    fn from_count(count: usize) -> Self;
}

impl Sample for f32 {
    const ZERO: Self = 0.0;
    fn from_count(count: usize) -> Self {
        count as f32
    }
}

impl Sample for f64 {
    const ZERO: Self = 0.0;
    fn from_count(count: usize) -> Self {
        count as f64
    }
}
