//! World settings: what a world is created with and can change between steps (the tuning
//! constants behind their defaults are in `constants`).

use crate::constants::{AABB_MARGIN, HIT_EVENT_THRESHOLD, SPECULATIVE_DISTANCE};
use crate::dynamics::drag::DragModel;
use crate::math::{Real, Vec2};
use crate::solver::SolverParams;
use crate::world::effects::Effects;

/// World-wide settings.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct WorldSettings {
    /// Gravitational acceleration, m/s², within [`crate::MAX_ACCELERATION`] on each axis.
    /// Default `(0, -10)`, as in Box2D.
    pub gravity: Vec2,
    /// The law that applies each body's drag coefficients. Default exponential damping.
    pub drag: DragModel,
    /// Shapes closer than this get contact points with positive separation, so the solver
    /// can stop fast bodies before they overlap; 0 to [`crate::MAX_SHAPE_EXTENT`]. Default
    /// [`SPECULATIVE_DISTANCE`].
    pub speculative_distance: Real,
    /// Broadphase enlargement of moving bodies' boxes, 0 to [`crate::MAX_SHAPE_EXTENT`].
    /// Default 5 cm; static
    /// bodies use the speculative distance, which keeps every speculative pair visible.
    pub aabb_margin: Real,
    /// Which contact solver runs, and how hard it works. Default: soft step, 4 substeps.
    pub solver: SolverParams,
    /// The effects simulated; what is not named costs nothing. Default: all of them.
    pub effects: Effects,
    /// With continuous collision on, contacts look a step ahead: a pair's contact is made, and
    /// its face points kept, as soon as the two can close within a step at their present
    /// speeds, so an impact at any speed is stopped at the surface. Off, a contact is made
    /// when the bodies' fat boxes meet and keeps points within the speculative distance
    /// only, as Box2D's do: a body that closes faster than that in a step sinks into what it
    /// hits for a step before it is pushed back out, and the step costs less where many
    /// bodies move fast. Continuous collision's sweeps keep fast bodies from passing through
    /// static ones (bullets through any body) either way. Default on.
    pub look_ahead: bool,
    /// Keep a pair's manifold while its bodies barely move relative to each other, updating
    /// only each point's separation, instead of rebuilding it every step (as Box2D does):
    /// under soft step while they move less than Box2D's 10 × slop (5 cm), under the classic
    /// solvers 2 × slop, and never more than a tenth of the smaller body's inradius. Default
    /// on.
    pub contact_recycling: bool,
    /// A contact of a collider that asks for hit events ([`crate::ColliderDef::hit_events`])
    /// reports a hit when a point that pushed during a step was approaching faster than this
    /// as the step began, m/s. Default 1 (Box2D's `hitEventThreshold`).
    pub hit_event_threshold: Real,
}

impl Default for WorldSettings {
    fn default() -> Self {
        WorldSettings {
            gravity: Vec2::new(0.0, -10.0),
            drag: DragModel::default(),
            speculative_distance: SPECULATIVE_DISTANCE,
            aabb_margin: AABB_MARGIN,
            solver: SolverParams::default(),
            effects: Effects::ALL,
            look_ahead: true,
            contact_recycling: true,
            hit_event_threshold: HIT_EVENT_THRESHOLD,
        }
    }
}
