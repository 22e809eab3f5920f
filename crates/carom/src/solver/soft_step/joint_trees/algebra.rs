//! The small dense algebra of a joint tree's elimination: symmetric 3x3 effective inverse
//! masses over a body's `(vx, vy, w)`, a joint's rows at a body, and their regularised
//! inverses.

use crate::math::{Real, Vec2};

/// A symmetric 3x3 matrix over a body's `(vx, vy, w)`: `[xx, xy, xw, yy, yw, ww]`.
pub(super) type Sym3 = [Real; 6];

/// A 3-vector over a body's `(vx, vy, w)`, or over a joint's rows.
pub(super) type Vec3 = [Real; 3];

/// `W Gᵀ` for a joint's rows at a body with anchor `r` and effective inverse mass `W`, less
/// their sign: the rows are `[1, 0, -r.y]`, `[0, 1, r.x]` and `[0, 0, turn]` (the last only
/// when `N` is 3, else zero) over the body's `(vx, vy, w)`.
#[inline]
pub(super) fn columns<const N: usize>(w: &Sym3, r: Vec2, turn: Real) -> [Vec3; 3] {
    let [xx, xy, xw, yy, yw, ww] = *w;
    let turned = if N == 3 {
        [turn * xw, turn * yw, turn * ww]
    } else {
        [0.0; 3]
    };
    [
        [xx - r.y * xw, xy - r.y * yw, xw - r.y * ww],
        [xy + r.x * xw, yy + r.x * yw, yw + r.x * ww],
        turned,
    ]
}

/// `G c` for a joint's rows at a body (as [`columns`], less their sign): what vector `c`
/// over the body's `(vx, vy, w)` is on each row.
#[inline]
pub(super) fn on_rows<const N: usize>(r: Vec2, turn: Real, c: Vec3) -> Vec3 {
    [
        c[0] - r.y * c[2],
        c[1] + r.x * c[2],
        if N == 3 { turn * c[2] } else { 0.0 },
    ]
}

pub(super) fn dot(a: Vec3, b: Vec3) -> Real {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `m v` for the symmetric `m`, of which only the first `N` rows and columns are read (the
/// rest of the result is zero).
#[inline]
pub(super) fn sym_mul<const N: usize>(m: &Sym3, v: Vec3) -> Vec3 {
    let [xx, xy, xw, yy, yw, ww] = *m;
    if N == 3 {
        [
            xx * v[0] + xy * v[1] + xw * v[2],
            xy * v[0] + yy * v[1] + yw * v[2],
            xw * v[0] + yw * v[1] + ww * v[2],
        ]
    } else {
        [xx * v[0] + xy * v[1], xy * v[0] + yy * v[1], 0.0]
    }
}

/// Where entry `(i, j)` of a symmetric 3x3 matrix is kept in a [`Sym3`].
const SYM: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];

/// `w -= C D⁻¹ Cᵀ` for the 3xN `C` given by its columns and the symmetric `D⁻¹` (its first
/// `N` rows and columns).
pub(super) fn subtract_outer<const N: usize>(w: &mut Sym3, c: &[Vec3; N], inverse: &Sym3) {
    // Row i of C D⁻¹.
    let mut e = [[0.0; N]; 3];
    for (i, row) in e.iter_mut().enumerate() {
        for (l, entry) in row.iter_mut().enumerate() {
            for (k, column) in c.iter().enumerate() {
                *entry += column[i] * inverse[SYM[k][l]];
            }
        }
    }
    for i in 0..3 {
        for j in i..3 {
            let mut outer = 0.0;
            for (l, column) in c.iter().enumerate() {
                outer += e[i][l] * column[j];
            }
            w[SYM[i][j]] -= outer;
        }
    }
}

/// The inverse of the symmetric `[[d11, d12], [d12, d22]]`, regularised so that a joint
/// made redundant by others (two pins on one body) takes no impulse rather than an infinite
/// one.
pub(super) fn inverse22([d11, d12, d22]: [Real; 3]) -> [Real; 3] {
    let trace = d11 + d22;
    let det = d11 * d22 - d12 * d12;
    let (d11, d22, det) = if det > 1e-6 * trace * trace {
        (d11, d22, det)
    } else {
        let eps = 1e-3 * trace;
        let (d11, d22) = (d11 + eps, d22 + eps);
        (d11, d22, d11 * d22 - d12 * d12)
    };
    if det > 0.0 && det.is_finite() {
        [d22 / det, -d12 / det, d11 / det]
    } else {
        [0.0; 3]
    }
}

/// The inverse of the symmetric `d`, regularised as [`inverse22`] is (relative to each
/// diagonal entry, since the rows mix lengths and angles).
pub(super) fn inverse33(d: Sym3) -> Sym3 {
    let det =
        |[a, b, c, e, f, i]: Sym3| a * (e * i - f * f) - b * (b * i - f * c) + c * (b * f - e * c);
    let scale = d[0] * d[3] * d[5];
    let d = if det(d) > 1e-6 * scale {
        d
    } else {
        let grow = 1.0 + 1e-3;
        [d[0] * grow, d[1], d[2], d[3] * grow, d[4], d[5] * grow]
    };
    let det = det(d);
    if !(det > 0.0 && det.is_finite()) {
        return [0.0; 6];
    }
    let [a, b, c, e, f, i] = d;
    let inv = 1.0 / det;
    [
        (e * i - f * f) * inv,
        (c * f - b * i) * inv,
        (b * f - c * e) * inv,
        (a * i - c * c) * inv,
        (b * c - a * f) * inv,
        (a * e - b * b) * inv,
    ]
}
