//! SIMD lanes for soft step's contact solve: what the solver needs of a vector of floats, and
//! how bodies are gathered into lanes and scattered back.
//!
//! Two widths: four lanes everywhere, through `wide`'s `f32x4` (SSE2 on x86-64, Neon, WASM's
//! SIMD, or plain arrays), and eight where the CPU has AVX (`avx`, chosen at run time,
//! as Box2D's AVX2 build solves eight contacts at a time). Every operation is the same IEEE
//! operation in every lane at either width (no fused multiply-add), so both widths give the
//! same bits, and the scalar solver too where [`Lane`] is as wide as `Real`.
//!
//! A lane is single precision in every build ([`Lane`]): what the contact solve works on is
//! relative to its two bodies (their velocities, their motion since the step began, the
//! anchors from their centres, the separation at the step's start), which single precision
//! holds as well 100 km from the origin as beside it. The double-precision build keeps
//! positions, geometry and everything solved one at a time in double, and solves its
//! contacts eight at a time where AVX does, as Box2D keeps its solver in `float`.

use crate::solver::soft_step::shared_states::SharedStates;

#[cfg(target_arch = "x86_64")]
pub(crate) mod avx;
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};
use wide::f32x4;

/// What one lane holds: `f32` in every build (see above).
pub(crate) type Lane = f32;

/// Four lanes, on every CPU.
pub(crate) type Four = f32x4;

/// A vector of [`Lanes::WIDTH`] floats.
pub(crate) trait Lanes:
    Copy
    + Debug
    + Send
    + Sync
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + 'static
{
    /// Lanes per vector.
    const WIDTH: usize;
    /// One `u32` per lane.
    type Indices: Copy + Debug + Default + Send + Sync + AsRef<[u32]> + AsMut<[u32]>;

    /// Runs `kernel` in code compiled for these lanes' instructions (AVX for eight lanes), so
    /// the operations inlined into it are single instructions. Every loop over bundles runs
    /// inside one.
    fn run<K: Kernel>(kernel: K) -> K::Output;
    /// Every lane `x`.
    fn splat(x: Lane) -> Self;
    /// The lanes into `out`.
    fn write_to(self, out: &mut [Lane]);
    /// The lanes as floats in memory, to set one at a time.
    fn lanes_mut(&mut self) -> &mut [Lane];
    /// The lanes from the first [`Lanes::WIDTH`] values.
    fn from_slice(values: &[Lane]) -> Self;
    /// Lane `lane`.
    #[cfg(test)]
    fn lane(self, lane: usize) -> Lane {
        let mut values = [0.0; 8];
        self.write_to(&mut values);
        values[lane]
    }
    /// Per lane, the larger (a NaN in `other` gives `self`; of +0 and -0, `other`), as x86's
    /// `maxps` on every CPU.
    fn max(self, other: Self) -> Self;
    /// Per lane, the smaller (a NaN in `other` gives `self`; of +0 and -0, `other`), as x86's
    /// `minps` on every CPU.
    fn min(self, other: Self) -> Self;
    /// Per lane: `self > other`, as a mask.
    fn gt(self, other: Self) -> Self;
    /// Per lane: `self != other`, as a mask.
    fn ne(self, other: Self) -> Self;
    /// Per lane: where `self` (a mask) is set, `if_set`, else `if_clear`.
    fn select(self, if_set: Self, if_clear: Self) -> Self;
    /// Per lane: where both masks are set.
    fn and(self, other: Self) -> Self;
    /// One bit per lane of a mask, lane 0 the lowest.
    fn bits(self) -> u32;

    /// The states of bodies `indices`, transposed: `[v.x, v.y, w, held, dp.x, dp.y, cos, sin]`
    /// (`held`'s bits, unused), each a vector of one value of every body.
    fn gather(states: &SharedStates, indices: &Self::Indices) -> [Self; 8];

    /// Writes the velocities `(v.x, v.y, w)` of the lanes whose bit is set in `lanes` back to
    /// their bodies' states (no two set lanes may name the same state), leaving the rest of
    /// each state as it was.
    fn scatter(states: &SharedStates, indices: &Self::Indices, lanes: u32, velocity: [Self; 3]);
}

/// Work on lanes, run by [`Lanes::run`]. Implement `run` with `#[inline(always)]`: it must be
/// inlined into the code compiled for the lanes (a closure's body, which cannot be marked so,
/// may be left out of line and compiled without them).
pub(crate) trait Kernel {
    /// What the work gives back.
    type Output;
    /// Does the work.
    fn run(self) -> Self::Output;
}

/// What `wide`'s four-lane vectors share as [`Lanes`]: all but how bodies are gathered
/// into lanes and scattered back.
macro_rules! four_wide_lanes {
    ($lanes:ident) => {
        const WIDTH: usize = 4;
        type Indices = [u32; 4];

        #[inline(always)]
        fn run<K: Kernel>(kernel: K) -> K::Output {
            kernel.run()
        }

        #[inline(always)]
        fn splat(x: Lane) -> Self {
            $lanes::splat(x)
        }

        #[inline(always)]
        fn write_to(self, out: &mut [Lane]) {
            out[..4].copy_from_slice(self.as_array());
        }

        #[inline(always)]
        fn lanes_mut(&mut self) -> &mut [Lane] {
            self.as_mut_array()
        }

        #[inline(always)]
        fn from_slice(values: &[Lane]) -> Self {
            $lanes::new([values[0], values[1], values[2], values[3]])
        }

        // Spelt out as x86's `maxps` and `minps` are (`self` where it wins or `other` is NaN,
        // else `other`), so a tie of +0 and -0 gives the same zero everywhere: WASM's `pmax`
        // and Neon's `fmaxnm`, which `wide` uses there, settle it otherwise.
        #[inline(always)]
        fn max(self, other: Self) -> Self {
            (self.simd_gt(other) | other.simd_ne(other)).bitselect(self, other)
        }

        #[inline(always)]
        fn min(self, other: Self) -> Self {
            (self.simd_lt(other) | other.simd_ne(other)).bitselect(self, other)
        }

        #[inline(always)]
        fn gt(self, other: Self) -> Self {
            self.simd_gt(other)
        }

        #[inline(always)]
        fn ne(self, other: Self) -> Self {
            self.simd_ne(other)
        }

        #[inline(always)]
        fn select(self, if_set: Self, if_clear: Self) -> Self {
            self.bitselect(if_set, if_clear)
        }

        #[inline(always)]
        fn and(self, other: Self) -> Self {
            self & other
        }

        #[inline(always)]
        fn bits(self) -> u32 {
            self.to_bitmask()
        }
    };
}

impl Lanes for f32x4 {
    four_wide_lanes!(f32x4);

    #[inline(always)]
    fn gather(states: &SharedStates, indices: &[u32; 4]) -> [Self; 8] {
        // Read one by one: an array `map` here stays a call in WebAssembly builds.
        let [i0, i1, i2, i3] = *indices;
        let (r0, r1, r2, r3) = (
            states.read_lanes(i0),
            states.read_lanes(i1),
            states.read_lanes(i2),
            states.read_lanes(i3),
        );
        let half = |row: &[f32; 8], from: usize| Self::from_slice(&row[from..]);
        let [v_x, v_y, w, held] =
            f32x4::transpose([half(&r0, 0), half(&r1, 0), half(&r2, 0), half(&r3, 0)]);
        let [dp_x, dp_y, cos, sin] =
            f32x4::transpose([half(&r0, 4), half(&r1, 4), half(&r2, 4), half(&r3, 4)]);
        [v_x, v_y, w, held, dp_x, dp_y, cos, sin]
    }

    #[inline(always)]
    fn scatter(states: &SharedStates, indices: &[u32; 4], lanes: u32, velocity: [Self; 3]) {
        let [v_x, v_y, w] = velocity;
        let rows = f32x4::transpose([v_x, v_y, w, f32x4::ZERO]);
        for (lane, (&index, row)) in indices.iter().zip(rows).enumerate() {
            if lanes & (1 << lane) != 0 {
                states.write_lane_velocity(index, row.to_array());
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::math::{Real, Rot, Vec2};
    use crate::solver::body_state::BodyState;
    use crate::solver::body_state::Held;

    /// Whether a result solved in lanes agrees with the one solved one constraint at a time in
    /// [`Real`]: equal where a lane is as wide as `Real` (a zero's sign aside); where it is
    /// narrower (the double-precision build), the same to within single precision's rounding,
    /// accumulated over a few passes (a relative 1e-4, or 1e-4 absolute near zero).
    pub(crate) fn agrees(lanes: Real, one_at_a_time: Real) -> bool {
        if size_of::<Lane>() == size_of::<Real>() {
            lanes == one_at_a_time
        } else {
            (lanes - one_at_a_time).abs() <= 1e-4 * one_at_a_time.abs().max(1.0)
        }
    }

    /// Body `i`'s state holds `10 i + k` in float `k` (and `held` is `i % 2`).
    pub(crate) fn numbered_states(count: usize) -> Vec<BodyState> {
        (0..count)
            .map(|i| {
                let x = |k: usize| (10 * i + k) as Real;
                BodyState {
                    v: Vec2::new(x(0), x(1)),
                    w: x(2),
                    held: (i % 2) as Held,
                    dp: Vec2::new(x(4), x(5)),
                    dq: Rot::from_cos_sin_unchecked(x(6), x(7)),
                }
            })
            .collect()
    }

    /// Gathering transposes bodies into lanes; scattering writes only the chosen lanes'
    /// velocities.
    pub(crate) fn check_gather_and_scatter<L: Lanes>() {
        let mut states = numbered_states(12);
        let mut indices = L::Indices::default();
        for (lane, index) in indices.as_mut().iter_mut().enumerate() {
            *index = (11 - lane) as u32;
        }
        // SAFETY: one thread.
        #[allow(unsafe_code)]
        let shared = unsafe { SharedStates::new(&mut states) };
        let gathered = L::gather(&shared, &indices);
        for (k, vector) in gathered.iter().enumerate() {
            for (lane, &index) in indices.as_ref().iter().enumerate() {
                let expected = if k == 3 {
                    // `held`'s bits, read as a lane (what it reads as does not matter).
                    Real::from_bits((index % 2) as Held) as Lane
                } else {
                    ((10 * index) as Real + k as Real) as Lane
                };
                assert_eq!(vector.lane(lane), expected, "float {k} of lane {lane}");
            }
        }
        let velocity = [L::splat(-1.0), L::splat(-2.0), L::splat(-3.0)];
        L::scatter(&shared, &indices, 0b101, velocity);
        for (lane, &index) in indices.as_ref().iter().enumerate() {
            let state = &states[index as usize];
            let written = lane == 0 || lane == 2;
            let expected = if written {
                (Vec2::new(-1.0, -2.0), -3.0)
            } else {
                let x = (10 * index) as Real;
                (Vec2::new(x, x + 1.0), x + 2.0)
            };
            assert_eq!((state.v, state.w), expected, "lane {lane}");
            assert_eq!(state.held, (index % 2) as Held, "held untouched");
            assert_eq!(
                state.dp.x,
                (10 * index) as Real + 4.0,
                "positions untouched"
            );
        }
    }

    /// The operations behave as the scalar ones, NaN included.
    pub(crate) fn check_operations<L: Lanes>() {
        let values: Vec<Lane> = (0..L::WIDTH)
            .map(|i| [1.0, -2.0, Lane::NAN, 0.5][i % 4])
            .collect();
        let x = L::from_slice(&values);
        let one = L::splat(1.0);
        for (lane, &v) in values.iter().enumerate() {
            assert_eq!(x.max(one).lane(lane), v.max(1.0), "max, lane {lane}");
            assert_eq!(x.min(one).lane(lane), v.min(1.0), "min, lane {lane}");
            assert_eq!(
                one.max(x).lane(lane).to_bits(),
                (1.0 as Lane).max(v).to_bits()
            );
            let gt = x.gt(L::splat(0.0));
            assert_eq!(gt.bits() & (1 << lane) != 0, v > 0.0);
            assert_eq!(
                gt.select(one, L::splat(2.0)).lane(lane),
                if v > 0.0 { 1.0 } else { 2.0 }
            );
            assert_eq!(x.ne(x).bits() & (1 << lane) != 0, v.is_nan());
            let both = gt.and(x.ne(one));
            assert_eq!(both.bits() & (1 << lane) != 0, v > 0.0 && v != 1.0);
        }
        // A tie of zeros gives `other`, as x86's maxps and minps, on every CPU.
        let (zero, negative_zero) = (L::splat(0.0), L::splat(-0.0));
        let bits = |lanes: L| lanes.lane(0).to_bits();
        assert_eq!(bits(zero.max(negative_zero)), (-0.0 as Lane).to_bits());
        assert_eq!(bits(negative_zero.max(zero)), (0.0 as Lane).to_bits());
        assert_eq!(bits(zero.min(negative_zero)), (-0.0 as Lane).to_bits());
        assert_eq!(bits(negative_zero.min(zero)), (0.0 as Lane).to_bits());
        assert_eq!((x + one - one * one).lane(1), -2.0);
        assert_eq!((-L::splat(0.0)).lane(0).to_bits(), (-0.0 as Lane).to_bits());
        let mut y = x;
        y.lanes_mut()[L::WIDTH - 1] = 7.0;
        assert_eq!((y.lane(L::WIDTH - 1), y.lane(0)), (7.0, 1.0));
    }

    #[test]
    fn four_lanes_gather_and_scatter() {
        check_gather_and_scatter::<Four>();
    }

    #[test]
    fn four_lanes_operate_as_scalars() {
        check_operations::<Four>();
    }
}
