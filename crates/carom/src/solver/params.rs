//! The solvers' settings: which solver runs ([`SolverKind`]), its parameters
//! ([`SolverParams`], Box2D v3's defaults) and a soft constraint's coefficients ([`Softness`]).

use crate::constants::{MAX_SPEED, MAX_SPRING};
use crate::error::{CaromError, check_positive_up_to, check_within};
use crate::math::Real;

/// Which contact solver runs. Scene files and the command line name it in snake case
/// ([`SolverKind::id`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum SolverKind {
    /// Moves overlapping bodies apart along the contact normal in proportion to their inverse
    /// masses and removes their approaching velocity. No impulses: stacks sink and jitter,
    /// which is the point of showing it.
    PushOut,
    /// The tutorial's impulses: per point, `j = max((-vn + bias) / k, 0)` with Baumgarte bias
    /// `0.2 / dt · max(0, depth - 0.01)`, repeated for the iterations, nothing accumulated.
    TutorialImpulse,
    /// Sequential impulses (Catto 2006) as Box2D v2.4 runs them: accumulated, clamped normal and
    /// friction impulses, warm started from the last step, restitution; overlap beyond the slop
    /// removed by position passes after the bodies move, not by a velocity bias.
    SequentialImpulse,
    /// Box2D v3's soft step: substeps, soft contacts, relaxation, a restitution pass.
    #[default]
    SoftStep,
}

impl SolverKind {
    /// Every solver, from the simplest.
    pub const ALL: [SolverKind; 4] = [
        SolverKind::PushOut,
        SolverKind::TutorialImpulse,
        SolverKind::SequentialImpulse,
        SolverKind::SoftStep,
    ];

    /// A short name for menus and reports.
    pub fn name(self) -> &'static str {
        match self {
            SolverKind::PushOut => "push-out",
            SolverKind::TutorialImpulse => "tutorial impulse",
            SolverKind::SequentialImpulse => "sequential impulse",
            SolverKind::SoftStep => "soft step",
        }
    }

    /// Its name in scene files and on the command line: `push_out`, `tutorial_impulse`,
    /// `sequential_impulse`, `soft_step`.
    pub fn id(self) -> &'static str {
        match self {
            SolverKind::PushOut => "push_out",
            SolverKind::TutorialImpulse => "tutorial_impulse",
            SolverKind::SequentialImpulse => "sequential_impulse",
            SolverKind::SoftStep => "soft_step",
        }
    }

    /// The solver with this [`SolverKind::id`], if there is one.
    pub fn from_id(id: &str) -> Option<SolverKind> {
        SolverKind::ALL.into_iter().find(|kind| kind.id() == id)
    }

    /// True for the solvers that divide the step into substeps.
    pub fn has_substeps(self) -> bool {
        self == SolverKind::SoftStep
    }
}

/// Solver settings. The defaults are Box2D v3's.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct SolverParams {
    /// The impulse solver used while [`SolverParams::impulse_resolution`] is on.
    pub kind: SolverKind,
    /// The tutorial's "impulse resolution" checkbox: off runs [`SolverKind::PushOut`] whatever
    /// `kind` says. Default on.
    pub impulse_resolution: bool,
    /// Velocity iterations: per step for the classic solvers, per substep (solve and relax
    /// each) for soft step. Default `None`: the count suited to `kind`, 1 for soft step and 8
    /// for the classic solvers ([`SolverParams::effective_iterations`]).
    pub iterations: Option<u32>,
    /// Substeps per step (soft step only). Default 4.
    pub substeps: u32,
    /// Start each step from last step's impulses (sequential impulse and soft step). Default on.
    pub warm_starting: bool,
    /// Soft step: solve the contacts colour by colour (no two of a colour share a moving
    /// body), eight at a time in SIMD lanes where the CPU has AVX, else four, as Box2D v3
    /// does. A contact keeps its colour while it touches, and contacts with static bodies take
    /// the last colours, so they are solved last in each pass. Several times faster than one
    /// by one. Off solves one by one, oldest contact first. Default on.
    pub graph_coloring: bool,
    /// Soft step: solve friction in the biased pass too, not only in the relaxation, as Box2D
    /// v3.1 does. Friction then converges twice as often, so large pyramids spread and sink
    /// less and resting piles jitter less; Box2D 3.2 and Rapier solve it in the relaxation
    /// only, saying friction that reacts to push-out velocity pumps lean into tall stacks.
    /// Default on.
    pub friction_in_bias_pass: bool,
    /// Soft step: contact stiffness in Hz, capped at a quarter of the substep rate. Default 30,
    /// as in Box2D. Soft contacts give a little under load, more the taller the stack (the
    /// stacks of `docs/hard-cases.md` measure it); stiffer contacts give less.
    pub contact_hertz: Real,
    /// Soft step: contact damping ratio. Default 10 (heavily over-damped: no bounce from bias).
    pub damping_ratio: Real,
    /// Soft step: contacts against static bodies are this much stiffer. Default 2.
    pub static_stiffness: Real,
    /// Soft step: how stiffly a joint's drift is pushed back in the biased pass, Hz, at most
    /// a quarter of the substep rate. Default 60, as Box2D. A soft joint gives under load,
    /// most where a heavy body hangs from light ones (a chain of light links holding a heavy
    /// load: `docs/hard-cases.md` measures its stretch, and `docs/accuracy.md` what stiffer
    /// joints and more substeps buy, at what cost).
    pub joint_hertz: Real,
    /// Soft step: the joints' damping ratio. Default 2, as Box2D.
    pub joint_damping_ratio: Real,
    /// Soft step: solve the points of hinged bodies (revolute joints) exactly, a whole tree
    /// of them at once, with the hinge limits that hold, in each pass, where Gauss-Seidel
    /// moves a light body's share of the momentum at a time and lets a heavy load stretch a
    /// light chain or a falling ragdoll part. Continuous collision then puts a hinged group
    /// back together when it puts back one of its bodies. A joint that closes a loop is
    /// still solved iteratively, as are motors, springs and other joints. Costs some dozens
    /// of flops a hinge per pass, whole trees shared among threads. Default off.
    pub direct_joints: bool,
    /// Soft step: after each pass over the contacts, solve once more, from the ground up,
    /// each contact where a body rests on one lower in the pile (its normal within 60° of
    /// straight up), with the lower body immovable (shock propagation). A heavy body resting
    /// on light ones then stops on them as on the ground, held by the friction its weight
    /// gives, where Gauss-Seidel lets it push them into the ground; tall stacks and pyramids
    /// barely compress. The lower body does not feel that pass, so the ground under a light
    /// body reports less than the load it bears (the contacts that hold the heavy body up
    /// report all of it). Without gravity it does nothing. Costs one more pass over those
    /// contacts, on one thread. Default off.
    pub shock_propagation: bool,
    /// Soft step: the fastest overlap is pushed apart, m/s. Default 3.
    pub max_push_speed: Real,
    /// Sequential and tutorial impulse: fraction of the overlap beyond the slop removed per
    /// position pass (sequential impulse) or per step by a velocity bias (tutorial impulse), in
    /// `[0, 1]` (0 turns it off). Default 0.2.
    pub baumgarte: Real,
    /// Approach speeds below this do not bounce, m/s. Default 1.
    pub restitution_threshold: Real,
    /// Guard rail: no body moves faster, m/s, at most [`crate::MAX_SPEED`]. Default 400.
    pub max_linear_speed: Real,
    /// Guard rail: no body turns more per step, however many substeps, rad, at most π.
    /// Default π / 4 (Box2D's).
    pub max_rotation: Real,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            kind: SolverKind::SoftStep,
            impulse_resolution: true,
            iterations: None,
            substeps: 4,
            warm_starting: true,
            graph_coloring: true,
            friction_in_bias_pass: true,
            contact_hertz: 30.0,
            damping_ratio: 10.0,
            static_stiffness: 2.0,
            joint_hertz: 60.0,
            joint_damping_ratio: 2.0,
            direct_joints: false,
            shock_propagation: false,
            max_push_speed: 3.0,
            baumgarte: 0.2,
            restitution_threshold: 1.0,
            max_linear_speed: 400.0,
            max_rotation: 0.25 * crate::math::consts::PI,
        }
    }
}

impl SolverParams {
    /// The defaults, with `kind`'s solver.
    pub fn for_kind(kind: SolverKind) -> Self {
        SolverParams {
            kind,
            ..SolverParams::default()
        }
    }

    /// The velocity iterations that run: [`SolverParams::iterations`], or when it is `None`
    /// the count suited to `kind`: 1 per substep for soft step, 8 per step for the others.
    pub fn effective_iterations(&self) -> u32 {
        let suited = if self.kind == SolverKind::SoftStep {
            1
        } else {
            8
        };
        self.iterations.unwrap_or(suited)
    }

    /// The solver that actually runs, given the impulse-resolution toggle.
    pub fn effective_kind(&self) -> SolverKind {
        if self.impulse_resolution {
            self.kind
        } else {
            SolverKind::PushOut
        }
    }

    /// Checks every value, naming the first bad one.
    pub fn validate(&self) -> Result<(), CaromError> {
        let counts = [
            ("iterations", self.effective_iterations()),
            ("substeps", self.substeps),
        ];
        for (name, value) in counts {
            if !(1..=1024).contains(&value) {
                return Err(CaromError::OutOfRange {
                    name,
                    expected: "between 1 and 1024",
                    value: value as Real,
                });
            }
        }
        // Springs: positive, and no stiffer or more damped than a step can carry.
        let spring =
            |name, value| check_positive_up_to(name, value, MAX_SPRING, "positive, at most 1e6");
        spring("contact hertz", self.contact_hertz)?;
        spring("damping ratio", self.damping_ratio)?;
        spring("static stiffness", self.static_stiffness)?;
        spring("joint hertz", self.joint_hertz)?;
        spring("joint damping ratio", self.joint_damping_ratio)?;
        // Speeds: positive, and no faster than a body may be set moving.
        let speed =
            |name, value| check_positive_up_to(name, value, MAX_SPEED, "positive, at most 1e6 m/s");
        speed("max push speed", self.max_push_speed)?;
        check_within("baumgarte", self.baumgarte, 0.0..=1.0, "between 0 and 1")?;
        speed("restitution threshold", self.restitution_threshold)?;
        speed("max linear speed", self.max_linear_speed)?;
        // More than half a turn a step could not be told from a turn the other way.
        check_positive_up_to(
            "max rotation",
            self.max_rotation,
            crate::math::consts::PI,
            "positive, at most π (half a turn a step)",
        )
        .map(drop)
    }
}

/// A soft constraint's coefficients for one (sub)step (Box2D's `b2MakeSoft`): how much of
/// the position error becomes velocity bias, and how much the impulse is softened.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Softness {
    pub bias_rate: Real,
    pub mass_scale: Real,
    pub impulse_scale: Real,
}

impl Softness {
    /// A spring of `hertz` with `damping_ratio`, stepped at `h` seconds.
    pub(crate) fn new(hertz: Real, damping_ratio: Real, h: Real) -> Self {
        if hertz == 0.0 {
            return Softness {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            };
        }
        let omega = 2.0 * crate::math::consts::PI * hertz;
        let a1 = 2.0 * damping_ratio + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}
