//! Eight SIMD lanes on x86-64 CPUs with AVX, chosen at run time.
//!
//! [`Avx8`] wraps AVX's 256-bit vector. AVX instructions fault on a CPU without them, so the
//! solver makes `Avx8`s only after [`detected`] said yes (`bundles::WideContacts::new`),
//! and works on them inside `Lanes::run`, which checks again and runs the work compiled for
//! AVX. Each operation is the
//! same IEEE operation, lane by lane, as the four-lane `f32x4` path's (max and min handle NaN as
//! `wide` does), so both widths give the same bits.
#![allow(unsafe_code)]

use crate::solver::soft_step::lanes::{Kernel, Lanes};
use crate::solver::soft_step::shared_states::SharedStates;
use std::arch::x86_64::*;
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// True when this CPU has AVX (the answer is cached by the standard library).
pub(crate) fn detected() -> bool {
    std::arch::is_x86_feature_detected!("avx")
}

/// Runs `kernel` compiled for AVX, so the [`Avx8`] operations inlined into it become single
/// instructions.
///
/// # Panics
/// On a CPU without AVX (check [`detected`] first).
#[inline]
fn run<K: Kernel>(kernel: K) -> K::Output {
    assert!(detected(), "AVX lanes on a CPU without AVX");
    // SAFETY: the CPU has AVX (checked above).
    unsafe { with_avx(kernel) }
}

#[target_feature(enable = "avx")]
unsafe fn with_avx<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

/// Eight `f32` lanes in one AVX register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx8(__m256);

// Every block below runs an AVX instruction, which is sound because an `Avx8` exists only
// inside `run`, on a CPU with AVX.

impl Add for Avx8 {
    type Output = Avx8;
    #[inline(always)]
    fn add(self, other: Avx8) -> Avx8 {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_add_ps(self.0, other.0) })
    }
}

impl Sub for Avx8 {
    type Output = Avx8;
    #[inline(always)]
    fn sub(self, other: Avx8) -> Avx8 {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_sub_ps(self.0, other.0) })
    }
}

impl Mul for Avx8 {
    type Output = Avx8;
    #[inline(always)]
    fn mul(self, other: Avx8) -> Avx8 {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_mul_ps(self.0, other.0) })
    }
}

impl Neg for Avx8 {
    type Output = Avx8;
    /// Flips the sign bit, as `-x` does for a scalar (so `-0.0` from `0.0`).
    #[inline(always)]
    fn neg(self) -> Avx8 {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_xor_ps(self.0, _mm256_set1_ps(-0.0)) })
    }
}

impl AddAssign for Avx8 {
    #[inline(always)]
    fn add_assign(&mut self, other: Avx8) {
        *self = *self + other;
    }
}

impl SubAssign for Avx8 {
    #[inline(always)]
    fn sub_assign(&mut self, other: Avx8) {
        *self = *self - other;
    }
}

impl Lanes for Avx8 {
    const WIDTH: usize = 8;
    type Indices = [u32; 8];

    #[inline(always)]
    fn run<K: Kernel>(kernel: K) -> K::Output {
        run(kernel)
    }

    #[inline(always)]
    fn splat(x: f32) -> Self {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_set1_ps(x) })
    }

    #[allow(
        clippy::expect_used,
        reason = "bundles are eight lanes wide, and the slice is cut to eight"
    )]
    #[inline(always)]
    fn write_to(self, out: &mut [f32]) {
        let out: &mut [f32; 8] = (&mut out[..8]).try_into().expect("room for eight");
        // SAFETY: AVX (see above); room for eight floats.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) };
    }

    #[allow(
        clippy::expect_used,
        reason = "bundles are eight lanes wide, and the slice is cut to eight"
    )]
    #[inline(always)]
    fn from_slice(values: &[f32]) -> Self {
        let values: &[f32; 8] = values[..8].try_into().expect("eight values");
        // SAFETY: AVX (see above); eight floats to read.
        Avx8(unsafe { _mm256_loadu_ps(values.as_ptr()) })
    }

    #[inline(always)]
    fn lanes_mut(&mut self) -> &mut [f32] {
        // SAFETY: a `__m256` is eight `f32`s in memory, and `[f32; 8]` asks less alignment.
        unsafe { &mut *(&mut self.0 as *mut __m256).cast::<[f32; 8]>() }
    }

    #[inline(always)]
    fn max(self, other: Self) -> Self {
        // SAFETY: AVX (see above).
        self.or_self_for_nan(other, unsafe { _mm256_max_ps(self.0, other.0) })
    }

    #[inline(always)]
    fn min(self, other: Self) -> Self {
        // SAFETY: AVX (see above).
        self.or_self_for_nan(other, unsafe { _mm256_min_ps(self.0, other.0) })
    }

    #[inline(always)]
    fn gt(self, other: Self) -> Self {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn ne(self, other: Self) -> Self {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_cmp_ps::<_CMP_NEQ_UQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn select(self, if_set: Self, if_clear: Self) -> Self {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_blendv_ps(if_clear.0, if_set.0, self.0) })
    }

    #[inline(always)]
    fn and(self, other: Self) -> Self {
        // SAFETY: AVX (see above).
        Avx8(unsafe { _mm256_and_ps(self.0, other.0) })
    }

    #[inline(always)]
    fn bits(self) -> u32 {
        // SAFETY: AVX (see above).
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }

    #[inline(always)]
    fn gather(states: &SharedStates, indices: &[u32; 8]) -> [Self; 8] {
        // SAFETY: AVX (see above), and each row is eight floats.
        unsafe {
            let row = |lane: usize| _mm256_loadu_ps(states.read_lanes(indices[lane]).as_ptr());
            let [c0, c1, c2, c3, c4, c5, c6, c7] = transpose([
                row(0),
                row(1),
                row(2),
                row(3),
                row(4),
                row(5),
                row(6),
                row(7),
            ]);
            [
                Avx8(c0),
                Avx8(c1),
                Avx8(c2),
                Avx8(c3),
                Avx8(c4),
                Avx8(c5),
                Avx8(c6),
                Avx8(c7),
            ]
        }
    }

    #[inline(always)]
    fn scatter(states: &SharedStates, indices: &[u32; 8], lanes: u32, velocity: [Self; 3]) {
        let [v_x, v_y, w] = velocity.map(|v| v.0);
        // SAFETY: AVX (see above).
        let rows = unsafe {
            let zero = _mm256_setzero_ps();
            // [vx0 vy0 vx1 vy1 | vx4 vy4 vx5 vy5] and the odd pairs; w beside zeros.
            let (xy_low, xy_high) = (_mm256_unpacklo_ps(v_x, v_y), _mm256_unpackhi_ps(v_x, v_y));
            let (w_low, w_high) = (_mm256_unpacklo_ps(w, zero), _mm256_unpackhi_ps(w, zero));
            // Row k of body k in the low half and body k + 4 in the high half.
            let pairs = [
                _mm256_shuffle_ps::<0b01_00_01_00>(xy_low, w_low),
                _mm256_shuffle_ps::<0b11_10_11_10>(xy_low, w_low),
                _mm256_shuffle_ps::<0b01_00_01_00>(xy_high, w_high),
                _mm256_shuffle_ps::<0b11_10_11_10>(xy_high, w_high),
            ];
            let mut rows = [[0.0f32; 4]; 8];
            for (k, pair) in pairs.into_iter().enumerate() {
                _mm_storeu_ps(rows[k].as_mut_ptr(), _mm256_castps256_ps128(pair));
                _mm_storeu_ps(rows[k + 4].as_mut_ptr(), _mm256_extractf128_ps::<1>(pair));
            }
            rows
        };
        for (lane, (&index, row)) in indices.iter().zip(rows).enumerate() {
            if lanes & (1 << lane) != 0 {
                states.write_lane_velocity(index, row);
            }
        }
    }
}

impl Avx8 {
    /// `result` (of maxps or minps, which give `other` when either is NaN), with `self` in the
    /// lanes where `other` is NaN, as `f32::max` and `f32::min` give.
    #[inline(always)]
    fn or_self_for_nan(self, other: Self, result: __m256) -> Self {
        // SAFETY: AVX (see above).
        unsafe {
            let nan = _mm256_cmp_ps::<_CMP_UNORD_Q>(other.0, other.0);
            Avx8(_mm256_blendv_ps(result, self.0, nan))
        }
    }
}

/// Rows of eight floats into columns.
#[inline(always)]
unsafe fn transpose(rows: [__m256; 8]) -> [__m256; 8] {
    // SAFETY: AVX (see above).
    unsafe {
        let [r0, r1, r2, r3, r4, r5, r6, r7] = rows;
        let (a0, a1) = (_mm256_unpacklo_ps(r0, r1), _mm256_unpackhi_ps(r0, r1));
        let (a2, a3) = (_mm256_unpacklo_ps(r2, r3), _mm256_unpackhi_ps(r2, r3));
        let (a4, a5) = (_mm256_unpacklo_ps(r4, r5), _mm256_unpackhi_ps(r4, r5));
        let (a6, a7) = (_mm256_unpacklo_ps(r6, r7), _mm256_unpackhi_ps(r6, r7));
        const LOW: i32 = 0b01_00_01_00;
        const HIGH: i32 = 0b11_10_11_10;
        let b0 = _mm256_shuffle_ps::<LOW>(a0, a2);
        let b1 = _mm256_shuffle_ps::<HIGH>(a0, a2);
        let b2 = _mm256_shuffle_ps::<LOW>(a1, a3);
        let b3 = _mm256_shuffle_ps::<HIGH>(a1, a3);
        let b4 = _mm256_shuffle_ps::<LOW>(a4, a6);
        let b5 = _mm256_shuffle_ps::<HIGH>(a4, a6);
        let b6 = _mm256_shuffle_ps::<LOW>(a5, a7);
        let b7 = _mm256_shuffle_ps::<HIGH>(a5, a7);
        [
            _mm256_permute2f128_ps::<0x20>(b0, b4),
            _mm256_permute2f128_ps::<0x20>(b1, b5),
            _mm256_permute2f128_ps::<0x20>(b2, b6),
            _mm256_permute2f128_ps::<0x20>(b3, b7),
            _mm256_permute2f128_ps::<0x31>(b0, b4),
            _mm256_permute2f128_ps::<0x31>(b1, b5),
            _mm256_permute2f128_ps::<0x31>(b2, b6),
            _mm256_permute2f128_ps::<0x31>(b3, b7),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::soft_step::lanes::tests::{check_gather_and_scatter, check_operations};

    #[test]
    fn eight_lanes_gather_and_scatter() {
        if detected() {
            check_gather_and_scatter::<Avx8>();
        }
    }

    #[test]
    fn eight_lanes_operate_as_scalars() {
        if detected() {
            check_operations::<Avx8>();
        }
    }
}
