//! World settings and the engine's tuning constants, each named once.

use crate::drag::DragModel;
use crate::effects::Effects;
use crate::math::{Real, Vec2};
use crate::solver::SolverParams;

/// Penetration the solver tolerates, and the scale of "touching", in metres (Box2D's 0.5 cm).
pub const LINEAR_SLOP: Real = 0.005;

/// Shapes closer than this get speculative contact points, in metres (4 × slop, as Box2D).
pub const SPECULATIVE_DISTANCE: Real = 4.0 * LINEAR_SLOP;

/// How much moving bodies' bounding boxes are enlarged in the broadphase, in metres, so a
/// body can move a little without its tree entry changing.
pub const AABB_MARGIN: Real = 0.05;

/// World-wide settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// Gravitational acceleration, m/s². Default `(0, -10)`, as in Box2D.
    pub gravity: Vec2,
    /// The law that applies each body's drag coefficients. Default exponential damping.
    pub drag: DragModel,
    /// Shapes closer than this get contact points with positive separation, so the solver
    /// can stop fast bodies before they overlap. Default [`SPECULATIVE_DISTANCE`].
    pub speculative_distance: Real,
    /// Broadphase enlargement of moving bodies' boxes. Default [`AABB_MARGIN`]; static
    /// bodies use the speculative distance, which keeps every speculative pair visible.
    pub aabb_margin: Real,
    /// Which contact solver runs, and how hard it works. Default: soft step, 4 substeps.
    pub solver: SolverParams,
    /// The effects simulated; what is not named costs nothing. Default: all of them.
    pub effects: Effects,
    /// Carry a pair's manifold along with its bodies while they barely move relative to each
    /// other ([`crate::recycle`]), instead of rebuilding it every step. Default on.
    pub contact_recycling: bool,
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
            contact_recycling: true,
        }
    }
}
