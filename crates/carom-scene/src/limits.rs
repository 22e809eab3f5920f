//! How much a scene file may ask to be made. A few bytes of a generator (a pyramid of four
//! billion, a repeat of repeats) can ask for more bodies than any machine holds, so what each
//! generator makes is counted from its numbers before anything is made, and a scene that asks
//! for more than its limits is refused.

use crate::scene::Generator;

/// The most bodies and joints building a scene may make: its own, its generators' and each
/// spawn event's copies. A scene asking for more is refused with an error before anything is
/// made. The defaults, half a million of each, are more than twenty times the largest demo
/// (22,000 bodies); raise them for a larger scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The most bodies a scene makes when built, and that one spawn adds.
    pub bodies: u64,
    /// The most joints a scene makes when built, and that one spawn adds.
    pub joints: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            bodies: 500_000,
            joints: 500_000,
        }
    }
}

impl Limits {
    /// What in `counts` is more than these limits allow (`None` when nothing is).
    pub(crate) fn exceeded(&self, counts: Counts) -> Option<String> {
        let over = |what: &str, asked: u64, limit: u64| {
            format!(
                "{asked} {what}, more than the limit of {limit} (carom_scene::Limits \
                 raises it)"
            )
        };
        if counts.bodies > self.bodies {
            Some(over("bodies", counts.bodies, self.bodies))
        } else if counts.joints > self.joints {
            Some(over("joints", counts.joints, self.joints))
        } else {
            None
        }
    }
}

/// How many bodies and joints something makes; sums and products saturate, so a count past
/// `u64` is `u64::MAX`, still more than any limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Counts {
    pub bodies: u64,
    pub joints: u64,
}

impl Counts {
    fn bodies(bodies: u64) -> Self {
        Counts { bodies, joints: 0 }
    }

    /// This and `other` together.
    pub fn plus(self, other: Counts) -> Counts {
        Counts {
            bodies: self.bodies.saturating_add(other.bodies),
            joints: self.joints.saturating_add(other.joints),
        }
    }

    /// `copies` of this.
    pub fn times(self, copies: u64) -> Counts {
        Counts {
            bodies: self.bodies.saturating_mul(copies),
            joints: self.joints.saturating_mul(copies),
        }
    }
}

/// What `generator` makes, counted from its numbers without making it (at most that: a
/// chain that joins fewer ends, or a generator that turns out invalid, makes fewer).
pub(crate) fn counts(generator: &Generator) -> Counts {
    let n = u64::from;
    match generator {
        Generator::Stack { count, .. } | Generator::Rain { count, .. } => Counts::bodies(n(*count)),
        Generator::Pyramid { count, rows, .. } => {
            // Rows of count, count - 1, ... boxes: r · count - r (r - 1) / 2, r <= count.
            let (c, r) = (n(*count), n(rows.unwrap_or(*count).min(*count)));
            let triangle = r.saturating_mul(r.saturating_sub(1)) / 2;
            Counts::bodies(r.saturating_mul(c).saturating_sub(triangle))
        }
        Generator::Grid {
            columns,
            rows,
            count,
            ..
        } => Counts::bodies(count.map_or(n(*columns).saturating_mul(n(*rows)), n)),
        Generator::JointGrid { columns, rows, .. } => {
            let (c, r) = (n(*columns), n(*rows));
            let down = c.saturating_mul(r.saturating_sub(1));
            let across = r.saturating_mul(c.saturating_sub(1));
            Counts {
                bodies: c.saturating_mul(r),
                joints: down.saturating_add(across),
            }
        }
        Generator::Repeat {
            columns, rows, of, ..
        } => counts(of).times(n(*columns).saturating_mul(n(*rows))),
        Generator::Chain { count, .. } => Counts {
            bodies: n(*count),
            joints: n(*count).saturating_add(1),
        },
        Generator::Group { bodies, joints, .. } => Counts {
            bodies: bodies.len() as u64,
            joints: joints.len() as u64,
        },
        Generator::Room { .. } => Counts::bodies(4),
    }
}
